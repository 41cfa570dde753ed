#!/usr/bin/env bash
# Runs every test of specpoly on a fresh machine: installs what is missing (the thumbv7em Rust
# target, QEMU for the firmware, Chromium for the web patch display, ArgyllCMS for the
# `--instrument argyll` tests, Xvfb for `dispwin`'s video-LUT load test), then formatting, lints,
# all tests (host, core, cross-crate, firmware under QEMU) and the microcontroller build of the
# core. Stops with a clear message if something cannot be installed; never skips a test.
set -euo pipefail
cd "$(dirname "$0")"
say() { printf '\n== %s (%d s)\n' "$*" "$SECONDS"; }
# every build here starts from a clean target dir: incremental state would only cost time
export CARGO_INCREMENTAL=0

say "checking tools"
missing=()
command -v qemu-system-arm >/dev/null 2>&1 || missing+=(qemu-system-arm)
command -v chromium >/dev/null 2>&1 || missing+=(chromium)
command -v spotread >/dev/null 2>&1 || missing+=(argyll)
command -v Xvfb >/dev/null 2>&1 || missing+=(xvfb)   # an X server for `dispwin`'s video LUT
[ -x /bin/kill ] || missing+=(procps)   # that test ends the X server's process group with kill
command -v cc >/dev/null 2>&1 || missing+=(gcc)   # compiles `calibrate export`'s C in a test
if ((${#missing[@]})); then
  if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
    echo "installing ${missing[*]} (apt)"
    apt-get update -o DPkg::Lock::Timeout=600 -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq -o DPkg::Lock::Timeout=600 \
      --no-install-recommends "${missing[@]}" >/dev/null
  else
    echo "test.sh: missing ${missing[*]}: install them (Debian: apt-get install ${missing[*]}) and run again" >&2
    exit 1
  fi
fi
for tool in qemu-system-arm chromium spotread dispread dispwin targen colprof profcheck iccdump applycal Xvfb cc; do
  command -v "$tool" >/dev/null 2>&1 || { echo "test.sh: $tool is still missing after install" >&2; exit 1; }
done
if ! rustup target list --installed | grep -qx thumbv7em-none-eabihf; then
  rustup target add thumbv7em-none-eabihf
fi
for c in rustfmt clippy; do
  rustup component list --installed | grep -q "^$c" || rustup component add "$c"
done

say "cargo fmt --check"
cargo fmt --all --check
(cd firmware && cargo fmt --check)

say "cargo clippy -D warnings"
cargo clippy --workspace --all-targets -- -D warnings
# the controller logic as the 32 KiB build compiles it (no settings, mixing, lut)
cargo clippy -p specpoly-device --no-default-features --all-targets -- -D warnings
(cd firmware && cargo clippy --release -- -D warnings)
# the STM32F4 board build (stm32f4xx-hal); firmware_qemu builds it and runs it on netduinoplus2
(cd firmware && cargo clippy --release --no-default-features --features stm32f4,full --bin stm32f4 \
  --target-dir target/stm32f4 -- -D warnings)
# the 32 KiB build (no settings store, no mixing); firmware_qemu builds it and runs it
(cd firmware && cargo clippy --profile small --no-default-features --features mps2 --bins \
  --target-dir target/small -- -D warnings)

say "specpoly-core, specpoly-graphics and specpoly-device for a microcontroller (thumbv7em-none-eabihf)"
cargo build -p specpoly-core -p specpoly-graphics -p specpoly-device --target thumbv7em-none-eabihf
cargo build -p specpoly-device --no-default-features --target thumbv7em-none-eabihf

say "tests (host, core, cross-crate, firmware under QEMU)"
cargo test --workspace --no-fail-fast
# the controller's unit tests as the 32 KiB build compiles it (no settings, mixing, lut)
cargo test -p specpoly-device --no-default-features --lib

say "all tests passed"
