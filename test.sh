#!/usr/bin/env bash
# Runs every test of specpoly on a fresh machine: installs what is missing (the thumbv7em Rust
# target, QEMU for the firmware, arm-none-eabi-gcc and newlib, riscv64-unknown-elf-gcc, QEMU's
# RISC-V system and the riscv32imc Rust target for the C library's QEMU tests,
# Chromium for the web patch display, ArgyllCMS for the
# `--instrument argyll` tests, Xvfb for `dispwin`'s video-LUT load test, ffmpeg and
# OpenColorIO's tools for the 3D LUT tests, OpenEXR's and OpenImageIO's tools for the EXR
# tests, a Python virtual environment with maturin, NumPy, pytest and colour-science for the
# Python package's tests), then formatting, lints
# (clippy, inside the builds), the microcontroller builds and all tests (host, core, cross-crate,
# firmware under QEMU, the Python package's pytest). Stops with a clear message if something cannot be installed; never
# skips a test.
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
command -v g++ >/dev/null 2>&1 || missing+=(g++)   # compiles specpoly-c's C++ wrapper and examples
command -v exrheader >/dev/null 2>&1 || missing+=(openexr)   # reads our EXR attributes
command -v oiiotool >/dev/null 2>&1 || missing+=(openimageio-tools)   # so does OpenImageIO
command -v ffmpeg >/dev/null 2>&1 || missing+=(ffmpeg)   # applies `calibrate lut3d`'s LUTs in a test
command -v ocioconvert >/dev/null 2>&1 || missing+=(opencolorio-tools)   # OpenColorIO applies them too
# specpoly-c's C test program for the Cortex-M4F (QEMU): the cross compiler and its C library
command -v arm-none-eabi-gcc >/dev/null 2>&1 || missing+=(gcc-arm-none-eabi)
[ -f /usr/lib/arm-none-eabi/newlib/thumb/v7e-m+fp/hard/libc_nano.a ] || missing+=(libnewlib-arm-none-eabi)
# ... and for RV32IMC (ESP32-C3's instruction set) on QEMU `virt`
command -v riscv64-unknown-elf-gcc >/dev/null 2>&1 || missing+=(gcc-riscv64-unknown-elf)
command -v qemu-system-riscv32 >/dev/null 2>&1 || missing+=(qemu-system-misc)
# The installs run in the background while the host build below compiles (they need the
# network and the disk, the build the cores); each is waited for before the first step that
# needs it, and a failed install stops the run with its log.
logs=$(mktemp -d)
apt_pid=""
if ((${#missing[@]})); then
  if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
    echo "installing ${missing[*]} (apt, in the background)"
    (
      apt-get update -o DPkg::Lock::Timeout=600 -qq
      DEBIAN_FRONTEND=noninteractive apt-get install -y -qq -o DPkg::Lock::Timeout=600 \
        --no-install-recommends "${missing[@]}"
    ) >"$logs/apt.log" 2>&1 &
    apt_pid=$!
  else
    echo "test.sh: missing ${missing[*]}: install them (Debian: apt-get install ${missing[*]}) and run again" >&2
    exit 1
  fi
fi
targets=()
for target in thumbv7em-none-eabihf riscv32imc-unknown-none-elf; do
  rustup target list --installed | grep -qx "$target" || targets+=("$target")
done
targets_pid=""
if ((${#targets[@]})); then
  echo "installing the Rust targets ${targets[*]} (rustup, in the background)"
  rustup target add "${targets[@]}" >"$logs/rustup.log" 2>&1 &
  targets_pid=$!
fi
# Waits for a background install; on failure prints its log and stops.
await() {
  local pid=$1 what=$2 log=$3
  [ -n "$pid" ] || return 0
  if ! wait "$pid"; then
    echo "test.sh: $what failed:" >&2
    cat "$log" >&2
    exit 1
  fi
}
# The Python package's test environment (python/tests/requirements.txt: maturin, NumPy,
# pytest, colour-science, pinned), made in the background under target/ while cargo compiles.
py=$(command -v python3 || true)
[ -n "$py" ] || { echo "test.sh: python3 is missing (the Python package's tests need it)" >&2; exit 1; }
py=$("$py" -c 'import sys; print(sys.executable)')
venv="$PWD/target/python-venv"
mkdir -p target && rm -rf "$venv"
( "$py" -m venv "$venv" && "$venv/bin/pip" install -q --disable-pip-version-check \
    -r python/tests/requirements.txt ) >"$logs/venv.log" 2>&1 &
venv_pid=$!
# maturin builds pyo3 with these variables: set for every build here, the workspace build
# below compiles pyo3 as maturin wants it, and the wheel's build reuses that compilation
export PYO3_PYTHON="$py" PYTHON_SYS_EXECUTABLE="$py" PYO3_BUILD_EXTENSION_MODULE=1
PYO3_ENVIRONMENT_SIGNATURE=$("$py" -c 'import struct, sys; print("cpython-%d.%d-%dbit" % (sys.version_info[0], sys.version_info[1], 8 * struct.calcsize("P")))')
export PYO3_ENVIRONMENT_SIGNATURE
# the host build links with `cc`: without it, wait for the install now
if ! command -v cc >/dev/null 2>&1; then
  await "$apt_pid" "installing ${missing[*]}" "$logs/apt.log"
  apt_pid=""
fi
for c in rustfmt clippy; do
  rustup component list --installed | grep -q "^$c" || rustup component add "$c"
done

say "cargo fmt --check"
cargo fmt --all --check
(cd firmware && cargo fmt --check)

# Lints: clippy's driver compiles every workspace crate (and the firmware) in the builds below,
# with warnings as errors (see .ci/clippy-deny-warnings): one build both lints and tests.
export RUSTC_WORKSPACE_WRAPPER="$PWD/.ci/clippy-deny-warnings"

say "build and lint every target (clippy -D warnings)"
# Every build and test here uses the `dev` profile, tests included (`cargo test` alone would
# use `test`, which has the same settings but other artefact names for proc macros and build
# scripts): maturin builds the Python package with `dev`, and so reuses everything this build
# compiled except the package's own crate.
cargo test --profile dev --workspace --all-targets --no-run
# the controller logic as the 32 KiB build compiles it (no settings, mixing, lut)
cargo test --profile dev -p specpoly-device --no-default-features --all-targets --no-run

say "firmware builds and the microcontroller builds (linted as they build; the QEMU tests run these very binaries)"
await "$targets_pid" "installing the Rust targets ${targets[*]:-}" "$logs/rustup.log"
# The same commands and target dirs as tests/tests/firmware_qemu.rs, so its builds are no-ops.
# Each firmware build has a target dir of its own and ends in a one-thread link (LTO): the
# variants build side by side, and the microcontroller builds of the library crates beside them.
firmware() { local log=$1; shift; (cd firmware && cargo build "$@") >"$log" 2>&1; }
# the STM32F4 board build (stm32f4xx-hal), run on netduinoplus2
firmware "$logs/fw-stm32f4.log" --release --no-default-features --features stm32f4,full --bin stm32f4 \
  --target thumbv7em-none-eabihf --target-dir target/stm32f4 &
fw_stm32f4=$!
# the 32 KiB build (no settings store, no mixing)
firmware "$logs/fw-small.log" --profile small --bins --target thumbv7em-none-eabihf \
  --no-default-features --features mps2 --target-dir target/small &
fw_small=$!
# the micromath build, whose colour error a QEMU test measures against the libm build
firmware "$logs/fw-fast-math.log" --release --bins --target thumbv7em-none-eabihf \
  --target-dir target/fast-math --features fast-math &
fw_fast=$!
(cd firmware && cargo build --release --bins --target thumbv7em-none-eabihf --target-dir target)
# specpoly-core, specpoly-graphics and specpoly-device for a microcontroller (thumbv7em-none-eabihf)
cargo build -p specpoly-core -p specpoly-graphics -p specpoly-device --target thumbv7em-none-eabihf
cargo build -p specpoly-device --no-default-features --target thumbv7em-none-eabihf
# the C library's staticlibs as its QEMU tests link them (crates/capi/tests/c_program.rs)
cargo build -p specpoly-c --release --target thumbv7em-none-eabihf
cargo build -p specpoly-c --release --target riscv32imc-unknown-none-elf
await "$fw_stm32f4" "the STM32F4 firmware build" "$logs/fw-stm32f4.log"
await "$fw_small" "the 32 KiB firmware build" "$logs/fw-small.log"
await "$fw_fast" "the micromath firmware build" "$logs/fw-fast-math.log"

say "tests (host, core, cross-crate, firmware under QEMU)"
await "$apt_pid" "installing ${missing[*]:-}" "$logs/apt.log"
for tool in qemu-system-arm chromium spotread dispread dispwin targen colprof profcheck iccdump applycal Xvfb cc g++ \
  exrheader oiiotool ffmpeg ocioconvert arm-none-eabi-gcc riscv64-unknown-elf-gcc qemu-system-riscv32; do
  command -v "$tool" >/dev/null 2>&1 || { echo "test.sh: $tool is still missing after install" >&2; exit 1; }
done

# The Python package's wheel (maturin) builds while the tests run: only the package's own crate
# compiles (the workspace build above made everything else, with the same profile and features),
# and the tests often wait (on ArgyllCMS, QEMU, Chromium, serial timeouts). It starts once
# nextest's own build check has released the target directory's lock.
await "$venv_pid" "making the Python test environment" "$logs/venv.log"
rm -rf target/wheels
( sleep 20
  "$venv/bin/maturin" build --quiet --profile dev -m python/Cargo.toml -i "$py" -o target/wheels
) >"$logs/wheel.log" 2>&1 &
wheel_pid=$!

if cargo nextest --version >/dev/null 2>&1; then
  # all test binaries at once, longest tests first (.config/nextest.toml)
  cargo nextest run --cargo-profile dev --workspace --no-fail-fast
  cargo test --profile dev --workspace --doc
else
  echo "(cargo-nextest is not installed: cargo test runs the same tests, one binary at a time)"
  cargo test --profile dev --workspace --no-fail-fast
fi
# the controller's unit tests as the 32 KiB build compiles it (no settings, mixing, lut)
cargo test --profile dev -p specpoly-device --no-default-features --lib

say "Python package: its wheel (built during the tests), installed in a virtual environment, pytest"
await "$wheel_pid" "the Python package's wheel (maturin build)" "$logs/wheel.log"
"$venv/bin/pip" install -q --disable-pip-version-check --no-deps target/wheels/specpoly-*.whl
# against colour-science and the CLI this build made
SPECPOLY_CLI="$PWD/target/debug/specpoly" "$venv/bin/python" -m pytest -q -p no:cacheprovider python/tests

say "all tests passed"
