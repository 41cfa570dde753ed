//! The LED controller firmware under QEMU (`mps2-an386`, Cortex-M4F):
//!
//! - the controller's unit tests (`specpoly-device`) in the 32 KiB build's configuration;
//! - the on-target self-test (semihosting exit code), with the flash and RAM budgets;
//! - end to end: the host's `specpoly led` code ↔ QEMU's UART on a pseudo-terminal ↔ firmware,
//!   whose every colour reply must agree with the host's independent f64 computation within
//!   the one tolerance table `specpoly_led::check::TOLERANCES` (which `led --check` uses too);
//! - the `fast-math` build (micromath): its colour error against the libm build, in ΔE00;
//! - multi-channel mixing (`channel`, `xy`, `cct`, `fade`): the firmware against the host's
//!   simulated controller (equal replies) and the independent f64 check from the spectra.
//!
//! The firmware logs through defmt (semihosting under QEMU): QEMU's standard output carries
//! binary frames, decoded here with `defmt-decoder` and the ELF's `.defmt` table ([`log_of`]).
//!
//! Needs `qemu-system-arm` and the `thumbv7em-none-eabihf` target (`./test.sh` installs both);
//! without them these tests fail with a message saying so. They never skip.

use specpoly_core::light::channels::{Curve, Goal};
use specpoly_core::light::Source;
use specpoly_core::{delta_e2000, Display, GamutMap, Illuminant, Lab, Observer, Transfer, Xyz};
use specpoly_led::lines::{refl, refl_hex, Preset};
use specpoly_led::mix_check::{MixAgreement, MixOracle, Weight};
use specpoly_led::{Link, MixModel, Oracle};
use specpoly_protocol::{Command, Gamut, Reply};
use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};
use std::process::{Child, Command as Process, Stdio};
use std::sync::{Mutex, OnceLock};
use std::time::{Duration, Instant};

const TARGET: &str = "thumbv7em-none-eabihf";
/// The full build (features `settings`, `mixing` and `lut`, the default): the 32 KiB build below
/// plus settings in flash with `sequential-storage` (+12 952 B: the store, its records,
/// `save`/`load`) and mixing 3–6 LED channels on the device (+10 188 B; issue 15: solver,
/// locus table, four commands), +1.1 KiB for the mixer's settings record, with the protocol at
/// `"s"` (+0.7 KiB, the `refl` line −12 %): 56 700 B, and the drive-correction table (`lut`,
/// +3 844 B): 61 288 B measured, 62 520 B for the STM32F4 image (six channels)
/// (docs/performance.md, "Issue 13", "Flash, by build and by part"). The limit is 64 KiB, the
/// first four 16 KiB sectors of an STM32F4; real parts have 256–512 KiB.
const FLASH_BUDGET: u64 = 64 * 1024;
/// The 32 KiB build (`--no-default-features --features mps2 --profile small`): the colour
/// pipeline, `refl` (decimal and hex), `cal`, `trc` (curves and tables), `map`, `observer`,
/// `state`; no settings store, no mixing, no drive table. 32 448 B measured: 320 B free for a 32 KiB part
/// (docs/performance.md, "Issue 13").
const SMALL_FLASH_BUDGET: u64 = 32 * 1024;
const RAM_BUDGET: u64 = 4 * 1024;
/// Static RAM plus the deepest stack use (painted) over every command and a start-up that
/// loads saved settings (docs/performance.md, "## Firmware").
const TOTAL_RAM_BUDGET: u64 = 6 * 1024;

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("tests/ is inside the repository")
        .to_path_buf()
}

fn cargo() -> Process {
    let mut c = Process::new(std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into()));
    c.current_dir(repo().join("firmware"));
    // the firmware's own .cargo/config.toml decides target and link flags
    for v in [
        "RUSTFLAGS",
        "CARGO_ENCODED_RUSTFLAGS",
        "CARGO_BUILD_TARGET",
        "CARGO_TARGET_DIR",
        "CARGO_BUILD_RUSTFLAGS",
    ] {
        c.env_remove(v);
    }
    c
}

/// Fails (never skips) when QEMU or the Rust target is missing.
fn require_tools() {
    let qemu = Process::new("qemu-system-arm").arg("--version").output();
    assert!(
        matches!(&qemu, Ok(o) if o.status.success()),
        "qemu-system-arm is not installed: run ./test.sh (or apt-get install qemu-system-arm)"
    );
    let sysroot = Process::new("rustc")
        .args(["--print", "sysroot"])
        .output()
        .expect("rustc runs");
    let sysroot = String::from_utf8_lossy(&sysroot.stdout).trim().to_owned();
    assert!(
        Path::new(&sysroot)
            .join("lib/rustlib")
            .join(TARGET)
            .exists(),
        "the Rust target {TARGET} is not installed: run ./test.sh (or rustup target add {TARGET})"
    );
}

/// Builds the release firmware (both binaries) once, with `features`, into its own target
/// dir; returns that dir's release folder.
fn build(features: &str) -> PathBuf {
    static LOCK: Mutex<()> = Mutex::new(());
    let _guard = LOCK.lock().unwrap_or_else(|e| e.into_inner());
    require_tools();
    let dir = if features.is_empty() {
        repo().join("firmware/target")
    } else {
        repo().join("firmware/target").join(features)
    };
    let mut c = cargo();
    c.args([
        "build",
        "--release",
        "--bins",
        "--target",
        TARGET,
        "--target-dir",
    ])
    .arg(&dir);
    if !features.is_empty() {
        c.args(["--features", features]);
    }
    let out = c.output().expect("cargo runs");
    assert!(
        out.status.success(),
        "firmware build failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    dir.join(TARGET).join("release")
}

fn default_build() -> &'static PathBuf {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| build(""))
}

/// The 32 KiB build: no default features (no settings store, no mixing), board `mps2`, the
/// `small` profile (the protocol at `"z"` too), into its own target dir; its `small` folder.
fn small_build() -> &'static PathBuf {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        require_tools();
        let dir = repo().join("firmware/target/small");
        let out = cargo()
            .args(["build", "--profile", "small", "--bins", "--target", TARGET])
            .args([
                "--no-default-features",
                "--features",
                "mps2",
                "--target-dir",
            ])
            .arg(&dir)
            .output()
            .expect("cargo runs");
        assert!(
            out.status.success(),
            "small firmware build failed:\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
        dir.join(TARGET).join("small")
    })
}

fn qemu(elf: &Path, extra: &[&str]) -> Process {
    let mut c = Process::new("qemu-system-arm");
    c.args([
        "-machine",
        "mps2-an386",
        "-cpu",
        "cortex-m4",
        "-nographic",
        "-monitor",
        "none",
        "-semihosting-config",
        "enable=on,target=native",
    ])
    .args(extra)
    .arg("-kernel")
    .arg(elf);
    c
}

/// The defmt log of `elf` in `bytes` (QEMU's standard output), one line per frame: the message
/// of an `info` frame, `LEVEL: message` for the other levels. Fails on a malformed frame.
fn log_of(elf: &Path, bytes: &[u8]) -> String {
    decode_log(elf, bytes, false)
}

/// As [`log_of`], across a machine reset: a reset from QEMU's monitor may cut the frame being
/// written (a frame goes out in several semihosting writes), so a malformed frame is logged as
/// `(frame cut by a reset)` instead of failing; the decoder resumes at the next frame.
fn decode_log(elf: &Path, bytes: &[u8], across_reset: bool) -> String {
    let image = std::fs::read(elf).expect("read the ELF");
    let table = defmt_decoder::Table::parse(&image)
        .expect("the ELF's defmt table parses")
        .expect("the ELF has a defmt table");
    let mut decoder = table.new_stream_decoder();
    decoder.received(bytes);
    let mut out = String::new();
    loop {
        match decoder.decode() {
            Ok(frame) => {
                match frame.level().map(|l| l.as_str()) {
                    Some("info") | None => {}
                    Some(level) => {
                        out.push_str(level);
                        out.push_str(": ");
                    }
                }
                out.push_str(&frame.display_message().to_string());
                out.push('\n');
            }
            Err(defmt_decoder::DecodeError::UnexpectedEof) => break,
            Err(defmt_decoder::DecodeError::Malformed) if across_reset => {
                out.push_str("(frame cut by a reset)\n")
            }
            Err(defmt_decoder::DecodeError::Malformed) => {
                panic!("a malformed defmt frame after:\n{out}")
            }
        }
    }
    out
}

/// Runs an ELF that exits through semihosting; returns (exit code, decoded defmt log).
fn run_to_exit(elf: &Path, extra: &[&str]) -> (Option<i32>, String) {
    let mut child = qemu(elf, extra)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .stdin(Stdio::null())
        .spawn()
        .expect("qemu-system-arm starts");
    let start = Instant::now();
    loop {
        if let Some(status) = child.try_wait().expect("wait for qemu") {
            let mut out = Vec::new();
            if let Some(mut s) = child.stdout.take() {
                let _ = s.read_to_end(&mut out);
            }
            return (status.code(), log_of(elf, &out));
        }
        if start.elapsed() > Duration::from_secs(120) {
            let _ = child.kill();
            panic!("{} did not exit within 120 s", elf.display());
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// Section sizes of an ELF32 file: (flash = text + rodata + data + vectors, static RAM =
/// data + bss + uninit).
fn budget(elf: &Path) -> (u64, u64) {
    let b = std::fs::read(elf).expect("read the ELF");
    let u16_at = |o: usize| u16::from_le_bytes([b[o], b[o + 1]]) as usize;
    let u32_at = |o: usize| u32::from_le_bytes([b[o], b[o + 1], b[o + 2], b[o + 3]]) as u64;
    assert_eq!(&b[..5], b"\x7fELF\x01", "an ELF32 file");
    let shoff = u32_at(0x20) as usize;
    let (shentsize, shnum, shstrndx) = (u16_at(0x2e), u16_at(0x30), u16_at(0x32));
    let strtab = u32_at(shoff + shstrndx * shentsize + 0x10) as usize;
    let (mut flash, mut ram) = (0, 0);
    for i in 0..shnum {
        let h = shoff + i * shentsize;
        let name_at = strtab + u32_at(h) as usize;
        let end = b[name_at..].iter().position(|c| *c == 0).unwrap_or(0);
        let name = String::from_utf8_lossy(&b[name_at..name_at + end]).to_string();
        let size = u32_at(h + 0x14);
        match name.as_str() {
            ".vector_table" | ".text" | ".rodata" => flash += size,
            ".data" => {
                flash += size;
                ram += size;
            }
            ".bss" | ".uninit" => ram += size,
            _ => {}
        }
    }
    (flash, ram)
}

#[test]
fn selftest_passes_on_target_within_the_budgets() {
    let dir = default_build();
    let (code, out) = run_to_exit(&dir.join("selftest"), &["-icount", "shift=0"]);
    assert_eq!(code, Some(0), "selftest failed under QEMU:\n{out}");
    assert!(out.contains("selftest: pass"), "{out}");
    assert!(!out.contains("FAIL"), "{out}");
    assert!(out.matches("check ").count() >= 6, "{out}");
    // the instruction counter is calibrated: delay(100000) is 2 × 100001 instructions
    let cal: u64 = field(&out, "insns calibration delay-100000 ");
    assert!((199_990..=200_100).contains(&cal), "calibration {cal}");

    // the instruction counts (docs/performance.md, "## Firmware"), for `--nocapture`
    for l in out.lines().filter(|l| l.starts_with("insns ")) {
        println!("{l}");
    }
    // the firmware's instruction budgets (docs/performance.md, "Issue 13"): exact counts under
    // `-icount shift=0`, the same on every run of the same build
    let line: u64 = field(&out, "insns default line-2-factors ");
    assert!(line <= 30_000, "decimal refl line {line} instructions");
    let colour: u64 = field(&out, "insns default colour ");
    assert!(colour <= 1_500, "colour step {colour} instructions");
    let (flash, ram) = budget(&dir.join("specpoly-firmware"));
    println!("flash {flash} B, static RAM {ram} B");
    assert!(
        flash <= FLASH_BUDGET,
        "flash {flash} B over {FLASH_BUDGET} B"
    );
    assert!(ram <= RAM_BUDGET, "static RAM {ram} B over {RAM_BUDGET} B");
}

/// The 32 KiB build ([`SMALL_FLASH_BUDGET`]): its self-test passes (every check; it has no
/// mixing to time), and over the UART its colour and `refl` replies (decimal, and hex answered
/// in hex) agree with the host's independent f64 check ([`Oracle`]); `save`/`load` answer
/// `err storage` and the mixing words `err unknown-command`.
#[test]
fn small_build_fits_32_kib_and_agrees_with_the_f64_check() {
    let dir = small_build();
    let (flash, ram) = budget(&dir.join("specpoly-firmware"));
    println!("32 KiB build: flash {flash} B, static RAM {ram} B");
    assert!(
        flash <= SMALL_FLASH_BUDGET,
        "flash {flash} B over {SMALL_FLASH_BUDGET} B"
    );
    assert!(ram <= RAM_BUDGET, "static RAM {ram} B over {RAM_BUDGET} B");
    let (code, out) = run_to_exit(&dir.join("selftest"), &["-icount", "shift=0"]);
    assert_eq!(code, Some(0), "small selftest failed under QEMU:\n{out}");
    assert!(
        out.contains("selftest: pass") && !out.contains("FAIL"),
        "{out}"
    );
    assert!(!out.contains("insns mix"), "{out}");
    for l in out.lines().filter(|l| l.starts_with("insns ")) {
        println!("small build: {l}");
    }

    let emu = Emulator::start_elf(dir.join("specpoly-firmware"), &[]);
    let mut link = Link::open(&emu.pty, Duration::from_secs(10)).expect("open the pty");
    let max = link.hello().expect("hello");
    let xy = [[0.68, 0.31], [0.2, 0.71], [0.14, 0.05]];
    let lum = [3.0, 8.0, 1.2];
    let srgb = [Transfer::Srgb, Transfer::Srgb, Transfer::Srgb];
    assert_eq!(
        link.send("cal 0.68 0.31 3 0.2 0.71 8 0.14 0.05 1.2")
            .unwrap(),
        Reply::Done("cal")
    );
    assert_eq!(link.send("trc rgb srgb").unwrap(), Reply::Done("trc"));
    let two = [
        "colorchecker#orange".to_owned(),
        "colorchecker#blue".to_owned(),
    ];
    let lines = [
        "xyz 20 20 20".to_owned(),
        "xyy 0.2 0.6 30".to_owned(),
        refl(Preset::Poly, Illuminant::D65, &two).unwrap(),
        refl_hex(Preset::Poly, Illuminant::D65, &two).unwrap(),
        refl_hex(Preset::Paper, Illuminant::FL11, &two).unwrap(),
    ];
    let oracle = Oracle::new(xy, lum, srgb, GamutMap::Clip, Observer::Cie1931, max);
    for line in &lines {
        let dev = colour(link.send(line).unwrap());
        let cmd = Command::parse(line).unwrap();
        if let Err(e) = oracle.verify(&cmd, &dev) {
            panic!("{line:.60}: {e}; device {dev:?}");
        }
        assert_eq!(
            dev.hex,
            matches!(cmd, Command::Reflect { hex: true, .. }),
            "{line:.60}"
        );
    }
    for (line, code) in [
        ("save", "err storage"),
        ("load", "err storage"),
        ("cct 4000 0 0.5", "err unknown-command"),
        ("channel clear", "err unknown-command"),
    ] {
        let text = link.exchange_unchecked(line).unwrap();
        assert!(text.starts_with(code), "{line} → {text}");
    }
    std::thread::sleep(Duration::from_millis(200));
    let log = emu.log();
    assert_eq!(log.lines().next(), Some("specpoly-led ready"), "{log}");
    assert_total_ram(&emu.elf, &log);
}

/// A panic reaches the host as a defmt `error` frame naming its location, and QEMU exits
/// with a failure code (`firmware/src/bin/panic.rs` panics on purpose).
#[test]
fn a_panic_is_logged_through_defmt_and_fails_the_run() {
    let dir = default_build();
    let (code, log) = run_to_exit(&dir.join("panic"), &[]);
    assert_eq!(code, Some(1), "{log}");
    let lines: Vec<&str> = log.lines().collect();
    assert_eq!(lines.first(), Some(&"about to panic"), "{log}");
    assert!(
        lines
            .iter()
            .any(|l| l.starts_with("error: firmware panic at src/bin/panic.rs:")),
        "{log}"
    );
}

fn field<T: std::str::FromStr>(out: &str, prefix: &str) -> T {
    out.lines()
        .find_map(|l| l.strip_prefix(prefix))
        .and_then(|v| v.trim().parse().ok())
        .unwrap_or_else(|| panic!("no `{prefix}` in:\n{out}"))
}

/// QEMU running the controller with its UART on a pseudo-terminal; its standard output (the
/// defmt frames) is collected as bytes, its standard error (QEMU's own messages, the pty path)
/// as text.
struct Emulator {
    child: Child,
    elf: PathBuf,
    pty: String,
    stdout: std::sync::Arc<Mutex<Vec<u8>>>,
}

impl Emulator {
    fn start() -> Self {
        Self::start_with(&[])
    }

    /// Starts QEMU with `extra` arguments.
    fn start_with(extra: &[&str]) -> Self {
        Self::start_elf(default_build().join("specpoly-firmware"), extra)
    }

    /// Starts QEMU with its monitor on a socket in `dir`, for [`Emulator::reset`].
    fn start_resettable(dir: &Path) -> Self {
        let sock = dir.join("monitor.sock");
        let chardev = format!("socket,id=mon,path={},server=on,wait=off", sock.display());
        Self::start_with(&["-chardev", &chardev, "-mon", "chardev=mon,mode=readline"])
    }

    /// A machine reset through the monitor of [`Emulator::start_resettable`] in `dir`
    /// (`system_reset`: the CPU restarts from the vector table, the RAM-backed settings flash
    /// kept); returns once the restarted firmware has loaded its saved settings.
    fn reset(&self, dir: &Path) {
        let mut monitor = std::os::unix::net::UnixStream::connect(dir.join("monitor.sock"))
            .expect("QEMU's monitor");
        std::io::Write::write_all(&mut monitor, b"system_reset\n").unwrap();
        wait_for_log_across_reset(self, "settings loaded from flash");
    }

    /// Starts QEMU on `elf` with `extra` arguments.
    fn start_elf(elf: PathBuf, extra: &[&str]) -> Self {
        let mut args = vec!["-serial", "pty"];
        args.extend_from_slice(extra);
        let mut child = qemu(&elf, &args)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .stdin(Stdio::null())
            .spawn()
            .expect("qemu-system-arm starts");
        let mut stdout = child.stdout.take().expect("piped stdout");
        let stderr = child.stderr.take().expect("piped stderr");
        let bytes = std::sync::Arc::new(Mutex::new(Vec::new()));
        let (tx, rx) = std::sync::mpsc::channel();
        // QEMU announces the pty ("char device redirected to /dev/pts/N (label serial0)") on
        // standard output, before the firmware's first frame: taken out of the defmt stream
        let sink = bytes.clone();
        let tx_out = tx.clone();
        std::thread::spawn(move || {
            let mut buf = [0u8; 4096];
            let mut announced = false;
            while let Ok(n) = stdout.read(&mut buf) {
                if n == 0 {
                    break;
                }
                let mut all = sink.lock().unwrap_or_else(|e| e.into_inner());
                all.extend_from_slice(&buf[..n]);
                if !announced {
                    if let Some((pty, end)) = pty_announcement(&all) {
                        all.drain(..end);
                        let _ = tx_out.send(pty);
                        announced = true;
                    }
                }
            }
        });
        std::thread::spawn(move || {
            for line in BufReader::new(stderr).lines().map_while(Result::ok) {
                if let Some((pty, _)) = pty_announcement(line.as_bytes()) {
                    let _ = tx.send(pty);
                }
            }
        });
        let pty = match rx.recv_timeout(Duration::from_secs(20)) {
            Ok(p) => p,
            Err(_) => {
                let _ = child.kill();
                panic!("QEMU printed no pty path");
            }
        };
        Self {
            child,
            elf,
            pty,
            stdout: bytes,
        }
    }

    /// The firmware's defmt log so far, decoded.
    fn log(&self) -> String {
        log_of(&self.elf, &self.bytes())
    }

    /// The log so far when the machine may have been reset mid-frame ([`decode_log`]).
    fn log_across_reset(&self) -> String {
        decode_log(&self.elf, &self.bytes(), true)
    }

    fn bytes(&self) -> Vec<u8> {
        self.stdout
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .clone()
    }
}

/// QEMU's pty announcement in `bytes`: the path and the end of its line (after the `\n`).
fn pty_announcement(bytes: &[u8]) -> Option<(String, usize)> {
    let key = b"/dev/pts/";
    let i = bytes.windows(key.len()).position(|w| w == key)?;
    let nl = i + bytes[i..].iter().position(|b| *b == b'\n')?;
    let pty: String = String::from_utf8_lossy(&bytes[i..nl])
        .chars()
        .take_while(|c| !c.is_whitespace() && *c != ')')
        .collect();
    Some((pty, nl + 1))
}

impl Drop for Emulator {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn colour(r: Reply) -> specpoly_protocol::ColourReport {
    match r {
        Reply::Colour(c) => c,
        other => panic!("expected a colour reply, got {other:?}"),
    }
}

#[test]
fn host_and_firmware_agree_over_the_emulated_uart() {
    let emu = Emulator::start();
    let mut link = Link::open(&emu.pty, Duration::from_secs(10)).expect("open the pty");
    let max = link.hello().expect("hello");
    assert_eq!(max, u16::MAX);

    // the settings sent, for the host's f64 reference
    let xy = [[0.70, 0.29], [0.17, 0.70], [0.135, 0.04]];
    let lum = [2.5, 7.25, 1.0];
    let gamma = [
        Transfer::Gamma(2.2),
        Transfer::Gamma(2.2),
        Transfer::Gamma(2.2),
    ];
    assert_eq!(
        link.send("cal 0.7 0.29 2.5 0.17 0.7 7.25 0.135 0.04 1")
            .unwrap(),
        Reply::Done("cal")
    );
    assert_eq!(link.send("trc rgb gamma 2.2").unwrap(), Reply::Done("trc"));

    let mut lines = vec![
        "xyz 20 20 20".to_owned(),
        "xyz 41.24 21.26 1.93".to_owned(),
        "xyy 0.3127 0.329 50".to_owned(),
        "xyy 0.2 0.6 30".to_owned(),
        "xyy 0.08 0.85 50".to_owned(),
        "xyz 0 0 0".to_owned(),
    ];
    let named = |n: &str| vec![n.to_owned()];
    lines.push(refl(Preset::Poly, Illuminant::D65, &named("colorchecker#red")).unwrap());
    lines.push(refl(Preset::Paper, Illuminant::FL11, &named("colorchecker#blue")).unwrap());
    lines.push(
        refl(
            Preset::Poly,
            Illuminant::A,
            &[
                "colorchecker#red".to_owned(),
                "colorchecker#yellow".to_owned(),
            ],
        )
        .unwrap(),
    );
    // the compact form (f32 bit patterns): the same check
    lines.push(
        refl_hex(
            Preset::Poly,
            Illuminant::D50,
            &[
                "colorchecker#orange".to_owned(),
                "colorchecker#blue".to_owned(),
            ],
        )
        .unwrap(),
    );
    lines.push(
        refl(
            Preset::Paper,
            Illuminant::FL2,
            &[
                "colorchecker#foliage".to_owned(),
                "colorchecker#foliage".to_owned(),
                "colorchecker#cyan".to_owned(),
            ],
        )
        .unwrap(),
    );

    let mut out_of_gamut = 0;
    for map in [GamutMap::Clip, GamutMap::Desaturate] {
        let oracle = Oracle::new(xy, lum, gamma.clone(), map, Observer::Cie1931, max);
        let m = if map == GamutMap::Clip {
            "clip"
        } else {
            "desaturate"
        };
        assert_eq!(link.send(&format!("map {m}")).unwrap(), Reply::Done("map"));
        for line in &lines {
            let dev = colour(link.send(line).unwrap());
            let cmd = Command::parse(line).unwrap();
            if let Err(e) = oracle.verify(&cmd, &dev) {
                panic!("{line:.60}: {e}; device {dev:?}");
            }
            // a hex `refl` line is answered in hex, every other line in decimal
            let hex = matches!(cmd, Command::Reflect { hex: true, .. });
            assert_eq!(dev.hex, hex, "{line:.60}");
            if dev.gamut != Gamut::In {
                out_of_gamut += 1;
                assert_eq!(dev.gamut, Gamut::Out(map));
            }
        }
    }
    assert!(
        out_of_gamut >= 2,
        "the saturated targets are reported out of gamut"
    );

    // bad and overlong lines get an error reply, and the controller carries on
    for bad in ["blink", "xyz 1 2", "refl paper D65 1 2 3"] {
        assert!(
            matches!(link.send(bad), Err(specpoly_led::Error::Rejected { .. })),
            "{bad:.20}"
        );
    }
    let long = format!("xyz 1 2 {}", "9".repeat(3000));
    assert_eq!(link.exchange_unchecked(&long).unwrap(), "err too-long");
    assert_eq!(link.exchange("xyz 1\u{7f} 2 3").unwrap(), "err bad-byte");
    // a measured curve (the deepest stack path), then the state
    assert_eq!(
        link.send("trc b table 0 0.02 0.1 0.3 0.6 1").unwrap(),
        Reply::Done("trc")
    );
    match link.send("state").unwrap() {
        Reply::State(s) => {
            assert_eq!(s.trc[2], specpoly_protocol::CurveSummary::Table(6));
            assert_eq!(s.map, GamutMap::Desaturate);
        }
        other => panic!("{other:?}"),
    }

    // the CLI itself, with its own --check, against the same device
    drop(link);
    use clap::Parser;
    let cli = specpoly::cli::Cli::try_parse_from([
        "specpoly",
        "led",
        "--port",
        &emu.pty,
        "--check",
        "--trc",
        "srgb",
        "--map",
        "clip",
        "refl",
        "--illuminant",
        "FL11",
        "colorchecker#red",
        "colorchecker#blue",
    ])
    .expect("the led command line parses");
    specpoly::cli::run(cli).expect("specpoly led --check agrees with the firmware");

    // a calibration file from `specpoly calibrate fit` (64-point measured curves)
    let dir = tempfile::tempdir().unwrap();
    let toml = dir.path().join("acer.toml");
    let ti3 = repo().join("data/ti3/acer-xb271hu-unit1_dispread_2068.ti3");
    let fit = specpoly::cli::Cli::try_parse_from::<[&std::ffi::OsStr; 7], _>([
        "specpoly".as_ref(),
        "calibrate".as_ref(),
        "fit".as_ref(),
        "--ti3".as_ref(),
        ti3.as_os_str(),
        "-o".as_ref(),
        toml.as_os_str(),
    ])
    .expect("the calibrate command line parses");
    specpoly::cli::run(fit).expect("calibrate fit");
    let cli = specpoly::cli::Cli::try_parse_from([
        "specpoly".as_ref(),
        "led".as_ref(),
        "--port".as_ref(),
        emu.pty.as_ref(),
        "--calibration".as_ref(),
        toml.as_os_str(),
        "--check".as_ref(),
        "refl".as_ref(),
        "colorchecker#red".as_ref(),
        "colorchecker#blue".as_ref(),
    ] as [&std::ffi::OsStr; 10])
    .expect("the led command line parses");
    specpoly::cli::run(cli).expect("specpoly led --calibration --check agrees with the firmware");

    // duties are also logged (defmt over semihosting), with the stack's high-water mark
    std::thread::sleep(Duration::from_millis(200));
    let log = emu.log();
    // a fresh start: nothing saved, then ready
    let start: Vec<&str> = log.lines().take(2).collect();
    assert_eq!(
        start,
        ["no saved settings: defaults used", "specpoly-led ready"],
        "{log}"
    );
    let duty_lines = log.lines().filter(|l| l.starts_with("duty ")).count();
    assert!(duty_lines >= 2 * lines.len(), "{log}");
    assert_total_ram(&emu.elf, &log);
}

/// The channel sets the mixing test uploads: the LED sets of `data/leds/` (one with measured
/// curves, two with efficacy weights) and a seeded random set of five Gaussian LEDs.
fn mix_sets() -> Vec<(&'static str, MixOracle)> {
    let leds = |file: &str, cols: &[&str]| -> Vec<Source> {
        cols.iter()
            .map(|c| {
                let p = repo().join("data/leds").join(format!("{file}#{c}"));
                let n =
                    specpoly_spectra::spectrum_names::light(p.to_str().unwrap()).expect("LED data");
                Source::new(&n.tabulated()).expect("a light")
            })
            .collect()
    };
    let linear = |n: usize| vec![Curve::Linear; n];
    let rgbwa = leds("rgbwa.csv", &["red", "green", "blue", "white", "amber"]);
    let mut six = rgbwa.clone();
    six.extend(leds("tunable_white.csv", &["warm"]));
    // five Gaussian LEDs, centres and widths from a seeded xorshift
    let mut seed = 0x9e37_79b9_7f4a_7c15u64;
    let mut unit = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let random: Vec<Source> = [450.0, 500.0, 540.0, 590.0, 630.0]
        .iter()
        .map(|c: &f64| {
            let (centre, width, peak) =
                (c + 20.0 * (unit() - 0.5), 8.0 + 20.0 * unit(), 0.5 + unit());
            Source::from_fn(|nm| peak * (-0.5 * ((nm - centre) / width).powi(2)).exp()).unwrap()
        })
        .collect();
    vec![
        (
            "rgb",
            MixOracle::new(
                leds("rgb.csv", &["red", "green", "blue"]),
                linear(3),
                Weight::Power,
            ),
        ),
        (
            "tunable_white",
            MixOracle::new(
                leds("tunable_white.csv", &["warm", "cool", "red"]),
                linear(3),
                Weight::Power,
            ),
        ),
        (
            "rgbwa",
            MixOracle::new(rgbwa.clone(), linear(5), Weight::Power),
        ),
        (
            "rgbwa, efficacy, gamma 2.2 and sRGB curves",
            MixOracle::new(
                rgbwa,
                vec![
                    Curve::Gamma(2.2),
                    Curve::Linear,
                    Curve::Srgb,
                    Curve::Gamma(2.2),
                    Curve::Linear,
                ],
                Weight::Efficacy,
            ),
        ),
        (
            "rgbwa + warm white, efficacy",
            MixOracle::new(six, linear(6), Weight::Efficacy),
        ),
        ("random", MixOracle::new(random, linear(5), Weight::Power)),
    ]
}

/// The mix targets: the Planckian locus at 2700–6500 K, off it, D65 and two other
/// chromaticities, at several luminances.
fn mix_goals() -> Vec<Goal> {
    let mut g = Vec::new();
    for cct in [2700.0, 3000.0, 4000.0, 5000.0, 6500.0] {
        for lum in [1.0, 0.8, 0.3] {
            g.push(Goal::Cct { cct, duv: 0.0, lum });
        }
    }
    g.push(Goal::Cct {
        cct: 4000.0,
        duv: -0.006,
        lum: 0.5,
    });
    g.push(Goal::Cct {
        cct: 2700.0,
        duv: -0.002,
        lum: 0.6,
    });
    g.push(Goal::Cct {
        cct: 10_000.0,
        duv: 0.01,
        lum: 0.4,
    });
    g.push(Goal::Xy {
        xy: [0.3127, 0.329],
        lum: 0.7,
    });
    g.push(Goal::Xy {
        xy: [0.45, 0.41],
        lum: 0.2,
    });
    g.push(Goal::Xy {
        xy: [0.25, 0.55],
        lum: 1.0,
    });
    g.push(Goal::Xy {
        xy: [0.08, 0.85],
        lum: 1.0,
    });
    g
}

/// One line to the device and the same command to the host's simulated controller: the replies
/// must be equal (the same core and protocol calls on both).
fn both<P: std::io::Read + std::io::Write>(
    link: &mut Link<P>,
    model: &mut MixModel,
    cmd: &Command,
) -> Reply {
    let line = specpoly_led::lines::line(cmd);
    let text = link.exchange(&line).expect("a reply");
    let dev = Reply::parse(&text).unwrap_or_else(|e| panic!("{line}: {text}: {e}"));
    let sim = model.answer(cmd).expect("a mixing command");
    assert_eq!(
        dev, sim,
        "{line}: the firmware and the host's simulated controller"
    );
    dev
}

/// `channel`, `xy`, `cct`, `fade` on the device: every reply equals the host's simulated
/// controller's and passes the independent f64 check from the channels' spectra
/// (`specpoly_led::mix_check`: Δu′v′ ≤ 0.0005 before quantisation, ≤ 0.0002 after 16-bit
/// quantisation, luminance, least weighted drive); out-of-gamut targets are refused where the
/// host's own mixer finds them out of gamut; a fade logs 10 ms steps that start near the old
/// target, approach the new one monotonically and end on its duties; the mixer's settings
/// survive `save`/`load`; RAM stays within the budget.
#[test]
fn mixing_on_the_device_agrees_with_the_host() {
    let emu = Emulator::start();
    let mut link = Link::open(&emu.pty, Duration::from_secs(10)).expect("open the pty");
    let max = link.hello().expect("hello");
    let mut model = MixModel::new(max);
    assert_eq!(link.exchange("xy 0.3 0.3").unwrap(), "err no-channels");
    assert_eq!(
        link.exchange("channel 1 1 1 1").unwrap(),
        "err out-of-range at=1"
    );
    let (mut worst, mut solved, mut refused) = (MixAgreement::default(), 0, 0);
    for (name, oracle) in mix_sets() {
        for cmd in oracle.commands() {
            assert!(matches!(both(&mut link, &mut model, &cmd), Reply::Done(_)));
        }
        for goal in mix_goals() {
            match both(&mut link, &mut model, &Command::Mix(goal)) {
                Reply::Mix(r) => {
                    let a = oracle
                        .verify(&goal, &r)
                        .unwrap_or_else(|e| panic!("{name} {goal:?}: {e}; device {r:?}"));
                    worst = worst.max(a);
                    solved += 1;
                }
                Reply::Error(f) => {
                    assert_eq!(f.code, specpoly_protocol::ErrorCode::OutOfGamut, "{name}");
                    assert!(
                        oracle.out_of_gamut(&goal),
                        "{name} {goal:?}: the host mixes it"
                    );
                    refused += 1;
                }
                other => panic!("{other:?}"),
            }
        }
    }
    println!(
        "mixing, {solved} targets solved, {refused} out of gamut: worst Δu′v′ target {:.2e}, \
         before quantisation {:.2e}, after {:.2e}; luminance {:.2e}; drive above optimum {:.2e}",
        worst.target, worst.chromaticity, worst.quantised, worst.luminance, worst.drive
    );
    assert!(
        solved >= 60 && refused >= 6,
        "{solved} solved, {refused} refused"
    );

    // a fade on rgbwa from 2700 K at 0.3 to 6500 K at 0.9 in 200 ms: 20 steps
    let sets = mix_sets();
    let oracle = &sets[2].1;
    for cmd in oracle.commands() {
        both(&mut link, &mut model, &cmd);
    }
    let from = Goal::Cct {
        cct: 2700.0,
        duv: 0.0,
        lum: 0.3,
    };
    let to = Goal::Cct {
        cct: 6500.0,
        duv: 0.0,
        lum: 0.9,
    };
    both(&mut link, &mut model, &Command::Fade(0));
    let start = match both(&mut link, &mut model, &Command::Mix(from)) {
        Reply::Mix(r) => r,
        other => panic!("{other:?}"),
    };
    assert_eq!(
        both(&mut link, &mut model, &Command::Fade(200)),
        Reply::Done("fade")
    );
    let end = match both(&mut link, &mut model, &Command::Mix(to)) {
        Reply::Mix(r) => r,
        other => panic!("{other:?}"),
    };
    assert_eq!(end.steps, 20);
    let mut sim = Vec::new();
    let channels = end.n as usize;
    while let Some((k, n, d)) = model.mixer.step(max) {
        sim.push((k, n, d[..channels].to_vec()));
    }
    let log = wait_for_log(&emu, "fade 20/20 ");
    let steps: Vec<(u16, u16, Vec<u16>)> = log
        .lines()
        .filter_map(|l| l.strip_prefix("fade "))
        .map(|l| {
            let (k, rest) = l.split_once('/').unwrap();
            let (n, rest) = rest.split_once(" duty [").unwrap();
            let duty = rest.split(']').next().unwrap();
            let duty = duty.split(", ").map(|d| d.parse().unwrap()).collect();
            (k.parse().unwrap(), n.parse().unwrap(), duty)
        })
        .collect();
    assert_eq!(steps, sim, "the device's fade steps are the host model's");
    assert_eq!(
        steps.last().unwrap().2,
        end.duty(),
        "the last step is the target"
    );
    let at = |d: &[u16]| oracle.emitted(d, max).unwrap();
    let (uv0, _) = at(start.duty());
    let (uv1, _) = at(end.duty());
    let total = (uv1[0] - uv0[0]).hypot(uv1[1] - uv0[1]);
    let (first, _) = at(&steps[0].2);
    assert!(
        (first[0] - uv0[0]).hypot(first[1] - uv0[1]) < 1.5 * total / 20.0,
        "the first step starts near the old target"
    );
    // closer to the new chromaticity and brighter (relative to the most light at each step's
    // chromaticity, the quantity interpolated) at every step
    let (mut last_dist, mut last_lum) = (f64::INFINITY, 0.0);
    for (k, _, d) in &steps {
        let (uv, y) = at(d);
        let dist = (uv[0] - uv1[0]).hypot(uv[1] - uv1[1]);
        let lum = y / oracle.most_light_at(uv).expect("in gamut");
        assert!(
            dist <= last_dist + 1e-6 && lum >= last_lum,
            "step {k}: not monotone"
        );
        (last_dist, last_lum) = (dist, lum);
    }
    assert!(
        last_dist < 1e-9 && (last_lum - 0.9).abs() < 1e-3,
        "{last_lum}"
    );

    // the mixer's settings survive save / load
    assert_eq!(link.send("save").unwrap(), Reply::Done("save"));
    assert_eq!(link.exchange("channel clear").unwrap(), "ok channel");
    assert_eq!(link.exchange("cct 4000").unwrap(), "err no-channels");
    assert_eq!(link.send("load").unwrap(), Reply::Done("load"));
    both(&mut link, &mut model, &Command::Fade(0));
    both(
        &mut link,
        &mut model,
        &Command::Mix(Goal::Cct {
            cct: 4000.0,
            duv: 0.0,
            lum: 0.5,
        }),
    );
    std::thread::sleep(Duration::from_millis(200));
    assert_total_ram(&emu.elf, &emu.log());
}

/// The instructions a mix solve and a fade step take on the Cortex-M4F (selftest under
/// `-icount shift=0`, 3–6 channels): a fade step must fit 10 ms of a 25 MHz core (100 solved
/// steps per second), i.e. 250 000 instructions (an M4's instructions take one cycle or more:
/// docs/performance.md states cycles are not measured).
#[test]
fn a_fade_step_fits_100_steps_per_second_at_25_mhz() {
    let dir = default_build();
    let (code, out) = run_to_exit(&dir.join("selftest"), &["-icount", "shift=0"]);
    assert_eq!(code, Some(0), "selftest failed under QEMU:\n{out}");
    assert!(out.contains("check mix-chromaticity ok"), "{out}");
    for n in 3..=6 {
        let solve: u64 = field(&out, &format!("insns mix {n} solve "));
        let step: u64 = field(&out, &format!("insns mix {n} step "));
        println!(
            "{n} channels: solve {solve} instructions, fade step {step} ({:.0} steps/s at 25 MHz)",
            25e6 / step as f64
        );
        assert!(
            step <= 250_000,
            "{n} channels: {step} instructions per step"
        );
    }
}

/// The deepest stack use the log reports (`stack=`, after each command) plus the ELF's static
/// RAM stays within [`TOTAL_RAM_BUDGET`].
fn assert_total_ram(elf: &Path, log: &str) {
    let stack: u64 = log
        .lines()
        .filter_map(|l| l.split("stack=").nth(1))
        .filter_map(|v| v.trim().parse().ok())
        .max()
        .expect("a stack report");
    let (_, ram) = budget(elf);
    println!("firmware RAM: static {ram} B + stack high-water mark {stack} B");
    assert!(
        stack > 0 && ram + stack <= TOTAL_RAM_BUDGET,
        "static {ram} B + stack {stack} B over {TOTAL_RAM_BUDGET} B"
    );
}

#[test]
fn micromath_colour_error_against_libm() {
    let libm_dir = default_build();
    let fast_dir = build("fast-math");
    let (c1, libm_out) = run_to_exit(&libm_dir.join("selftest"), &["-icount", "shift=0"]);
    let (c2, fast_out) = run_to_exit(&fast_dir.join("selftest"), &["-icount", "shift=0"]);
    assert_eq!((c1, c2), (Some(0), Some(0)), "{libm_out}\n{fast_out}");

    // the sRGB-curve LED the selftest uses: emitted colour of each build's duties, by libm
    let srgb = [Transfer::Srgb, Transfer::Srgb, Transfer::Srgb];
    let base = specpoly_firmware_default_display();
    let (xy, lum) = base.primaries();
    let led = Display::from_primaries(xy, lum, Xyz::default(), srgb).unwrap();
    let white = led.white();
    let duties = |out: &str| -> Vec<[f32; 3]> {
        out.lines()
            .filter_map(|l| l.strip_prefix("colour "))
            .map(|l| {
                let v: Vec<f32> = l
                    .split_whitespace()
                    .skip(2)
                    .map(|t| t.parse::<f32>().unwrap() / 65535.0)
                    .collect();
                [v[0], v[1], v[2]]
            })
            .collect()
    };
    let (a, b) = (duties(&libm_out), duties(&fast_out));
    assert_eq!(a.len(), 60);
    assert_eq!(a.len(), b.len());
    let mut worst = 0.0f64;
    let mut sum = 0.0f64;
    for (p, q) in a.iter().zip(&b) {
        let lp = Lab::from_xyz(led.device_to_xyz(*p), white);
        let lq = Lab::from_xyz(led.device_to_xyz(*q), white);
        let d = delta_e2000(lp, lq);
        worst = worst.max(d);
        sum += d;
    }
    let mean = sum / a.len() as f64;
    let insns = |out: &str, what: &str| -> u64 { field(out, what) };
    println!(
        "micromath vs libm over {} colours: mean ΔE00 {mean:.4}, max {worst:.4}; \
         sRGB encode {} → {} insns; default colour {} → {} insns; paper colour {} → {} insns",
        a.len(),
        insns(&libm_out, "insns srgb encode "),
        insns(&fast_out, "insns srgb encode "),
        insns(&libm_out, "insns default colour "),
        insns(&fast_out, "insns default colour "),
        insns(&libm_out, "insns paper colour "),
        insns(&fast_out, "insns paper colour "),
    );
    // micromath's powf is a coarse approximation: measured mean ≈ 1.9, max ≈ 3.8 ΔE00
    // (docs/performance.md); this bounds regressions and shows the builds do differ
    assert!(
        mean > 0.1 && mean < 3.0 && worst < 6.0,
        "mean {mean}, max ΔE00 {worst}"
    );
    // since issue 13 the default curves use the core's own `pow_unit` (≤ 4 ulp, ≈ 75
    // instructions), which is both more accurate and cheaper than micromath's `powf`: the
    // feature no longer buys speed (docs/performance.md, "Issue 13")
    assert!(
        insns(&libm_out, "insns srgb encode ") < insns(&fast_out, "insns srgb encode "),
        "the default build's sRGB encode is cheaper than fast-math's"
    );
}

/// The controller's default LED: Rec. 709 primaries with a D65 white (the firmware's
/// `Controller::new`).
fn specpoly_firmware_default_display() -> Display {
    let _ = Illuminant::D65;
    Display::srgb()
}

/// Waits (≤ 10 s) until the firmware's log holds `text`; returns the log.
fn wait_for_log(emu: &Emulator, text: &str) -> String {
    wait_for(emu, text, Emulator::log)
}

/// [`wait_for_log`] after a reset from QEMU's monitor.
fn wait_for_log_across_reset(emu: &Emulator, text: &str) -> String {
    wait_for(emu, text, Emulator::log_across_reset)
}

fn wait_for(emu: &Emulator, text: &str, log_of: fn(&Emulator) -> String) -> String {
    let start = Instant::now();
    loop {
        let log = log_of(emu);
        if log.contains(text) {
            return log;
        }
        assert!(
            start.elapsed() < Duration::from_secs(10),
            "no `{text}` in the firmware log:\n{log}"
        );
        std::thread::sleep(Duration::from_millis(50));
    }
}

fn state<P: std::io::Read + std::io::Write>(link: &mut Link<P>) -> specpoly_protocol::StateReport {
    match link.send("state").unwrap() {
        Reply::State(s) => s,
        other => panic!("expected a state reply, got {other:?}"),
    }
}

/// `save`, a machine reset through QEMU's monitor (`system_reset`: the CPU restarts from the
/// vector table, RAM-backed settings flash kept) and the settings are back; `load` restores them
/// after a change; flash holding garbage is ignored with a warning at start and defaults used.
#[test]
fn settings_survive_a_reset_and_damaged_flash_is_ignored() {
    let dir = tempfile::tempdir().unwrap();
    let emu = Emulator::start_resettable(dir.path());
    let mut link = Link::open(&emu.pty, Duration::from_secs(10)).expect("open the pty");
    link.hello().expect("hello");
    wait_for_log(&emu, "no saved settings: defaults used");
    let defaults = state(&mut link);
    assert_eq!(link.exchange("load").unwrap(), "err not-saved");

    for line in [
        "cal 0.7 0.29 2.5 0.17 0.7 7.25 0.135 0.04 1",
        "trc g gamma 2.2",
        "trc b table 0 0.02 0.1 0.3 0.6 1",
        "map desaturate",
    ] {
        assert!(matches!(link.send(line).unwrap(), Reply::Done(_)), "{line}");
    }
    let saved = state(&mut link);
    assert_eq!(link.send("save").unwrap(), Reply::Done("save"));

    emu.reset(dir.path());
    link.hello().expect("hello after the reset");
    let after = state(&mut link);
    assert_eq!(
        (after.primaries, after.trc, after.map),
        (saved.primaries, saved.trc, saved.map)
    );
    assert_ne!(after.primaries, defaults.primaries);

    assert_eq!(link.send("map clip").unwrap(), Reply::Done("map"));
    assert_eq!(link.send("load").unwrap(), Reply::Done("load"));
    assert_eq!(state(&mut link).map, GamutMap::Desaturate);
    // a start-up and a `load` of a record with a tabulated curve, within the RAM budget
    std::thread::sleep(Duration::from_millis(200));
    let log = emu.log_across_reset();
    assert!(log.matches("(frame cut by a reset)").count() <= 1, "{log}");
    assert_total_ram(&emu.elf, &log);
    drop(link);
    drop(emu);

    // the settings region preloaded with bytes that are no record
    let garbage = dir.path().join("garbage.bin");
    std::fs::write(&garbage, [0x5Au8; 256]).unwrap();
    let loader = format!(
        "loader,file={},addr=0x003FC000,force-raw=on",
        garbage.display()
    );
    let emu = Emulator::start_with(&["-device", &loader]);
    let mut link = Link::open(&emu.pty, Duration::from_secs(10)).expect("open the pty");
    link.hello().expect("hello");
    let log = wait_for_log(&emu, "specpoly-led ready");
    assert!(
        log.contains("warn: saved settings ignored (corrupted): defaults used"),
        "{log}"
    );
    assert_eq!(state(&mut link).primaries, defaults.primaries);
    assert_eq!(link.send("save").unwrap(), Reply::Done("save"));
    assert_eq!(link.send("load").unwrap(), Reply::Done("load"));
}

/// The STM32F4 board build (feature `stm32f4`, stm32f4xx-hal) on QEMU's `netduinoplus2`
/// (STM32F405): QEMU 7.2 models its USART2 and TIM2–5 (not RCC, GPIO or the flash interface).
/// The protocol runs end to end over USART2, and the six PWM channels are read back from the
/// timers' compare registers (TIM3 CCR1–4, TIM4 CCR1–2) through QEMU's monitor (`xp`), with the
/// full scale from ARR: the HAL's PWM channels behind `SetDutyCycle`, checked at the register
/// level. A colour lights CCR1–3 with the reply's duties; a six-channel mix (channels uploaded
/// with `channel`, a `cct` target) puts the duties of the host's own run of the same controller
/// (`specpoly-device`) in all six registers, and those duties are checked independently: within
/// the full scale, and the light they make through the channels' spectra (f64) on the target
/// chromaticity within the solver's tolerance plus the quantisation's, computed here. A fade
/// (TIM5 as the clock) changes the registers over time through the host model's steps and ends
/// on the target. `save` answers `err storage` there (no flash controller); the flash path is
/// tested on mps2-an386 and with the mock flash.
#[test]
fn board_build_drives_the_timer_registers_on_netduinoplus2() {
    let dir = {
        static LOCK: Mutex<()> = Mutex::new(());
        let _guard = LOCK.lock().unwrap_or_else(|e| e.into_inner());
        require_tools();
        let dir = repo().join("firmware/target/stm32f4");
        let out = cargo()
            .args([
                "build",
                "--release",
                "--no-default-features",
                "--features",
                "stm32f4,full",
                "--bin",
                "stm32f4",
                "--target",
                TARGET,
                "--target-dir",
            ])
            .arg(&dir)
            .output()
            .expect("cargo runs");
        assert!(
            out.status.success(),
            "board build failed:\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
        dir.join(TARGET).join("release")
    };
    let elf = dir.join("stm32f4");
    let (flash, _) = budget(&elf);
    println!("stm32f4 board image: flash {flash} B");
    assert!(
        flash <= FLASH_BUDGET,
        "flash {flash} B over {FLASH_BUDGET} B"
    );

    let tmp = tempfile::tempdir().unwrap();
    let (uart, mon) = (
        tmp.path().join("usart2.sock"),
        tmp.path().join("monitor.sock"),
    );
    let mut child = Process::new("qemu-system-arm")
        .args([
            "-machine",
            "netduinoplus2",
            "-nographic",
            "-serial",
            "null",
            "-serial",
        ])
        .arg(format!("unix:{},server=on,wait=off", uart.display()))
        .arg("-monitor")
        .arg(format!("unix:{},server=on,wait=off", mon.display()))
        .arg("-kernel")
        .arg(&elf)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .stdin(Stdio::null())
        .spawn()
        .expect("qemu-system-arm starts");
    let connect = |p: &Path| {
        let start = Instant::now();
        loop {
            match std::os::unix::net::UnixStream::connect(p) {
                Ok(s) => {
                    s.set_read_timeout(Some(Duration::from_millis(200)))
                        .unwrap();
                    return s;
                }
                Err(_) if start.elapsed() < Duration::from_secs(10) => {
                    std::thread::sleep(Duration::from_millis(50))
                }
                Err(e) => panic!("QEMU socket {}: {e}", p.display()),
            }
        }
    };
    let mut serial = connect(&uart);
    let mut monitor = connect(&mon);
    // one request; what arrived until a whole line follows `until` (or 10 s passed)
    let ask = |s: &mut std::os::unix::net::UnixStream, line: &str, until: &str| -> String {
        std::io::Write::write_all(s, line.as_bytes()).unwrap();
        let (mut got, start) = (Vec::new(), Instant::now());
        let mut buf = [0u8; 1024];
        let complete = |g: &[u8]| {
            let g = String::from_utf8_lossy(g);
            g.find(until).is_some_and(|i| g[i..].contains('\n'))
        };
        while !complete(&got) && start.elapsed() < Duration::from_secs(10) {
            if let Ok(n) = s.read(&mut buf) {
                got.extend_from_slice(&buf[..n]);
            }
        }
        String::from_utf8_lossy(&got).into_owned()
    };
    // QEMU's USART drops bytes that arrive before the firmware has enabled it: ask until heard
    let start = Instant::now();
    let hello = loop {
        let h = ask(&mut serial, "hello\n", "ok");
        if h.contains("ok hello") || start.elapsed() > Duration::from_secs(20) {
            break h;
        }
    };
    let reply = ask(&mut serial, "xyz 20 20 20\n", "ok");
    let state = ask(&mut serial, "state\n", "ok");
    let save = ask(&mut serial, "save\n", "err");
    // TIM3 at 0x4000_0400: ARR at +0x2C, CCR1–CCR3 at +0x34…+0x3C (RM0368 §13.4)
    let arr = ask(&mut monitor, "xp /1wx 0x4000042c\n", "000000004000042c:");
    let arr4 = ask(&mut monitor, "xp /1wx 0x4000082c\n", "000000004000082c:");
    let colour_ccr = registers(&mut |l, u| ask(&mut monitor, l, u));

    // six channels (rgbwa + warm white) mixed to a CCT target, then a fade to another: the
    // device's replies, the host's run of the same controller, and the registers
    let sets = mix_sets();
    let (_, mix_oracle) = sets
        .iter()
        .find(|(name, _)| *name == "rgbwa + warm white, efficacy")
        .expect("the six-channel set");
    let mut host = specpoly_device::Controller::new(max_of(&hello));
    let mut exchange = |line: &str| -> Reply {
        let text = ask(&mut serial, &format!("{line}\n"), "");
        let text = text
            .lines()
            .map(|l| l.trim_start_matches('\0').trim())
            .find(|l| l.starts_with("ok") || l.starts_with("err"))
            .unwrap_or_else(|| panic!("{line}: no reply in {text:?}"))
            .to_owned();
        let dev = Reply::parse(&text).unwrap_or_else(|e| panic!("{line}: {text}: {e}"));
        assert_eq!(
            dev,
            host.handle(Command::parse(line)),
            "{line}: the board and the host's controller"
        );
        dev
    };
    for cmd in mix_oracle.commands() {
        exchange(&specpoly_led::lines::line(&cmd));
    }
    exchange("fade 0");
    let from = Goal::Cct {
        cct: 2700.0,
        duv: 0.0,
        lum: 0.3,
    };
    let mixed = match exchange(&specpoly_led::lines::line(&Command::Mix(from))) {
        Reply::Mix(r) => r,
        other => panic!("{other:?}"),
    };
    // the board answers, then drives the channels: read until they settle (bounded)
    let mixed_duty: Vec<u32> = mixed.duty().iter().map(|d| u32::from(*d)).collect();
    let mut mix_ccr = registers(&mut |l, u| ask(&mut monitor, l, u));
    for _ in 0..100 {
        if mix_ccr == mixed_duty {
            break;
        }
        std::thread::sleep(Duration::from_millis(20));
        mix_ccr = registers(&mut |l, u| ask(&mut monitor, l, u));
    }
    // a long fade (QEMU's timers count faster than the board's), sampled while it runs
    let to = Goal::Cct {
        cct: 6500.0,
        duv: 0.0,
        lum: 0.9,
    };
    exchange(&format!("fade {FADE_MS}"));
    let end = match exchange(&specpoly_led::lines::line(&Command::Mix(to))) {
        Reply::Mix(r) => r,
        other => panic!("{other:?}"),
    };
    let mut samples = Vec::new();
    let start = Instant::now();
    loop {
        let r = registers(&mut |l, u| ask(&mut monitor, l, u));
        let done = r == end.duty().iter().map(|d| u32::from(*d)).collect::<Vec<_>>();
        samples.push(r);
        if done || start.elapsed() > Duration::from_secs(120) {
            break;
        }
    }
    let _ = child.kill();
    let _ = child.wait();

    let hello = hello
        .lines()
        .find(|l| l.contains("ok hello"))
        .unwrap_or_default();
    let Ok(Reply::Hello { max, .. }) = Reply::parse(hello.trim_start_matches('\0').trim()) else {
        panic!("hello: {hello:?}");
    };
    let dev = colour(Reply::parse(reply.trim()).unwrap_or_else(|_| panic!("{reply:?}")));
    assert_eq!(save.trim(), "err storage");
    let words = |out: &str, addr: &str| -> Vec<u32> {
        let line = out
            .lines()
            .find(|l| l.starts_with(addr))
            .unwrap_or_else(|| panic!("no {addr} in {out:?}"));
        line.split_whitespace()
            .skip(1)
            .map(|w| u32::from_str_radix(w.trim_start_matches("0x"), 16).unwrap())
            .collect()
    };
    assert_eq!(
        words(&arr, "000000004000042c:"),
        vec![max as u32 - 1],
        "ARR = max − 1"
    );
    assert_eq!(
        words(&arr4, "000000004000082c:"),
        vec![max as u32 - 1],
        "TIM4's ARR = max − 1 (one full scale)"
    );
    let mut rgb = dev.duty.map(u32::from).to_vec();
    rgb.extend([0; 3]);
    assert_eq!(
        colour_ccr, rgb,
        "TIM3 CCR1–3 hold the colour's duties, the other channels are off"
    );
    // the reply agrees with the host's independent f64 computation for the board's state
    let Ok(Reply::State(st)) = Reply::parse(state.trim()) else {
        panic!("state: {state:?}");
    };
    let oracle = Oracle::from_state(&st, None).expect("an oracle for the board's state");
    if let Err(e) = oracle.verify(&Command::Xyz(Xyz::new(20.0, 20.0, 20.0)), &dev) {
        panic!("board reply {dev:?}: {e}");
    }

    // the mix: the registers hold the reply's duties (equal to the host's controller's, above)
    assert_eq!(mixed.n, 6);
    assert_eq!(mix_ccr, mixed_duty, "TIM3 CCR1–4, TIM4 CCR1–2 hold the mix");
    check_mix_registers(mix_oracle, &from, &mix_ccr, max);
    // the fade: every sample is the start, a step of the host model's fade, or a step being
    // written (the channels are written in order: a prefix of the next step over the last one),
    // the samples change over time, and the last is the target
    let mut steps = vec![mixed_duty];
    while let Some((_, _, d)) = host.fade_step() {
        steps.push(d.iter().map(|v| u32::from(*v)).collect());
    }
    assert_eq!(steps.len() as u32, FADE_MS / 10 + 1, "one step per 10 ms");
    let end_duty: Vec<u32> = end.duty().iter().map(|d| u32::from(*d)).collect();
    assert_eq!(
        steps.last(),
        Some(&end_duty),
        "the host's fade ends on the target"
    );
    for s in &samples {
        let known = steps
            .windows(2)
            .any(|w| (0..=6).any(|p| s[..p] == w[1][..p] && s[p..] == w[0][p..]));
        assert!(known, "sample {s:?} is no step of the fade");
    }
    let distinct: std::collections::BTreeSet<&Vec<u32>> = samples.iter().collect();
    println!(
        "fade over {} steps: {} register samples, {} distinct",
        steps.len() - 1,
        samples.len(),
        distinct.len()
    );
    assert!(
        distinct.len() >= 3,
        "the registers change over the fade: {samples:?}"
    );
    assert_eq!(
        samples.last(),
        Some(&end_duty),
        "the fade ends on the target"
    );
    check_mix_registers(mix_oracle, &to, &end_duty, max);
}

/// The fade the netduinoplus2 test samples, ms: 500 steps.
const FADE_MS: u32 = 5_000;

/// TIM3 CCR1–4 and TIM4 CCR1–2 (TIM3 at `0x4000_0400`, TIM4 at `0x4000_0800`, CCR1 at +0x34:
/// RM0368 §13.4), read with the machine stopped, through `ask(line, until)` on QEMU's monitor.
fn registers(ask: &mut dyn FnMut(&str, &str) -> String) -> Vec<u32> {
    let out = ask(
        "stop\nxp /4wx 0x40000434\nxp /2wx 0x40000834\ncont\n",
        "0000000040000834:",
    );
    let mut r = monitor_words(&out, "0000000040000434:");
    r.extend(monitor_words(&out, "0000000040000834:"));
    r
}

/// The words QEMU's `xp` printed on the line starting with `addr`.
fn monitor_words(out: &str, addr: &str) -> Vec<u32> {
    let line = out
        .lines()
        .map(|l| l.trim_start_matches("(qemu) "))
        .find(|l| l.starts_with(addr))
        .unwrap_or_else(|| panic!("no {addr} in {out:?}"));
    line.split_whitespace()
        .skip(1)
        .map(|w| u32::from_str_radix(w.trim_start_matches("0x"), 16).unwrap())
        .collect()
}

/// The full scale in a `hello` reply.
fn max_of(hello: &str) -> u16 {
    let line = hello
        .lines()
        .map(|l| l.trim_start_matches('\0').trim())
        .find(|l| l.starts_with("ok hello"))
        .unwrap_or_else(|| panic!("hello: {hello:?}"));
    match Reply::parse(line) {
        Ok(Reply::Hello { max, .. }) => max,
        other => panic!("hello: {other:?}"),
    }
}

/// Mixed duties read from the registers, checked independently of the controller: each within
/// the full scale, and the light they make through the channels' spectra (f64) on `goal`'s
/// chromaticity within the solver's bound (Δu′v′ 0.0005 before quantisation) plus what the
/// quantisation can move it: half a duty step on each channel, measured here.
fn check_mix_registers(oracle: &MixOracle, goal: &Goal, duty: &[u32], max: u16) {
    assert!(
        duty.iter().all(|d| *d <= u32::from(max)),
        "{duty:?} over {max}"
    );
    let d: Vec<u16> = duty.iter().map(|v| *v as u16).collect();
    let (uv, _) = oracle.emitted(&d, max).expect("the light of the duties");
    let target = MixOracle::target_uv_prime(goal).expect("a target in its domain");
    let mut quantisation = 0.0;
    for i in 0..d.len() {
        let mut e = d.clone();
        e[i] = if e[i] < max { e[i] + 1 } else { e[i] - 1 };
        let (uv1, _) = oracle.emitted(&e, max).unwrap();
        quantisation += 0.5 * (uv1[0] - uv[0]).hypot(uv1[1] - uv[1]);
    }
    let off = (uv[0] - target[0]).hypot(uv[1] - target[1]);
    let bound = 0.0005 + quantisation;
    println!("mix {goal:?}: Δu′v′ {off:.2e} (bound {bound:.2e})");
    assert!(off <= bound, "{goal:?}: Δu′v′ {off:.3e} over {bound:.3e}");
}

/// The host's model of the controller ([`specpoly_led::Model::answer`], what the host's fake
/// controllers answer) and the firmware refuse the same colours with `err not-finite` and
/// otherwise report the same gamut and duties (within one tick), on the same seeded inputs:
/// targets from 1e-45 to 3.4e38, where the conversions overflow (issue 10).
#[test]
fn host_model_and_firmware_refuse_the_same_colours() {
    let emu = Emulator::start();
    let mut link = Link::open(&emu.pty, Duration::from_secs(10)).expect("open the pty");
    let max = link.hello().expect("hello");
    let cal = "cal 0.64 0.33 0.212639 0.3 0.6 0.71516865 0.15 0.06 0.072192304";
    assert_eq!(link.send(cal).unwrap(), Reply::Done("cal"));
    assert_eq!(link.send("trc rgb linear").unwrap(), Reply::Done("trc"));
    let Ok(Command::Calibrate { xy, luminance }) = Command::parse(cal) else {
        panic!("{cal}")
    };
    let model = specpoly_led::Model {
        display: Display::from_primaries(
            xy,
            luminance,
            Xyz::default(),
            [Transfer::Linear, Transfer::Linear, Transfer::Linear],
        )
        .unwrap(),
        map: GamutMap::Clip,
        observer: Observer::Cie1931,
        max,
    };
    let mut s: u64 = 0x2545_f491_4f6c_dd1d;
    let mut next = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        s
    };
    // log-uniform magnitudes 1e-45 … 3.4e38, either sign, or 0
    let wide = |n: u64| -> f32 {
        if n & 7 == 0 {
            return 0.0;
        }
        let e = -45.0 + 83.5 * ((n >> 11) as f64 / (1u64 << 53) as f64);
        let v = 10f64.powf(e).min(3.4e38) as f32;
        if n & 1 == 0 {
            v
        } else {
            -v
        }
    };
    let (mut refused, mut agreed) = (0, 0);
    for i in 0..400 {
        let line = if i == 0 {
            "xyy 0.5 1e-45 3.4e38".to_string()
        } else if i % 2 == 0 {
            format!(
                "xyz {:e} {:e} {:e}",
                wide(next()),
                wide(next()),
                wide(next())
            )
        } else {
            let (x, y) = (
                (next() % 1000) as f32 / 1000.0,
                (1 + next() % 1000) as f32 / 1000.0,
            );
            format!("xyy {x} {y} {:e}", wide(next()).abs())
        };
        // as the firmware's controller turns each command into a target
        let target = match Command::parse(&line) {
            Ok(Command::Xyz(t)) => t,
            Ok(Command::Xyy(v)) => v.to_xyz(),
            _ => continue, // out of the documented ranges: both sides answer the parser's error
        };
        let text = link.exchange_unchecked(&line).unwrap();
        let device = Reply::parse(&text).unwrap_or_else(|f| panic!("{line} → {text}: {f:?}"));
        match (device, model.answer(target)) {
            (Reply::Error(a), Reply::Error(b)) => {
                assert_eq!(a, b, "{line}");
                refused += 1;
            }
            (Reply::Colour(a), Reply::Colour(b)) => {
                assert_eq!(a.gamut, b.gamut, "{line}");
                for k in 0..3 {
                    assert!(a.duty[k].abs_diff(b.duty[k]) <= 1, "{line}: {a:?} vs {b:?}");
                }
                agreed += 1;
            }
            (a, b) => panic!("{line}: firmware {a:?}, host model {b:?}"),
        }
    }
    assert!(
        refused > 0 && agreed > 0,
        "refused {refused}, agreed {agreed}"
    );
}

/// The full display model on the controller (issue 12): the drive-correction table
/// (`specpoly_core::drive_table`, `lut` commands) for the Lenovo and the Surface fits of
/// data/ti3, uploaded as `led --calibration` sends it. Every colour reply equals the host
/// model's (`Model::answer_with`, the same core calls), and the full model at its duties shows
/// the asked colour within `TABLE_DE` ΔE00 (the table's interpolation error against the exact
/// inverse, measured in crates/cli/tests/led_table.rs); bad uploads are refused with one-line errors;
/// `save` and a reset keep the table; the lut path stays within the RAM budget.
#[test]
fn the_drive_table_shows_the_full_model_on_the_device() {
    use specpoly_calibrate::fit::{fit, FitOptions};
    use specpoly_led::lines::{calibration, calibration_table, line};
    use specpoly_led::table::{TABLE_DE, TABLE_MEAN_DE};
    use specpoly_led::Model;

    let dir = tempfile::tempdir().unwrap();
    let emu = Emulator::start_resettable(dir.path());
    let mut link = Link::open(&emu.pty, Duration::from_secs(10)).expect("open the pty");
    let max = link.hello().expect("hello");
    let mut last = None;
    for name in [
        "lenovo-thinkpad-x61_825.ti3",
        "microsoft-surface-pro-2017_825.ti3",
    ] {
        let text = std::fs::read_to_string(repo().join("data/ti3").join(name)).unwrap();
        let readings = specpoly_formats::cgats::read_ti3(&text, name)
            .unwrap()
            .measurements;
        let path = dir.path().join(format!("{name}.toml"));
        fit(&readings, &FitOptions::default())
            .unwrap()
            .save(&path)
            .unwrap();
        let spec = specpoly_display::spec::DisplaySpec::open_measured(&path).unwrap();
        let t = calibration_table(&spec).unwrap().expect("a lattice");
        let mut bytes = 0;
        for l in calibration(&spec)
            .unwrap()
            .into_iter()
            .chain(t.table.commands().iter().map(line))
        {
            bytes += l.len() + 1;
            assert!(matches!(link.send(&l), Ok(Reply::Done(_))), "{l}");
        }
        println!(
            "{name}: table {}³, {bytes} B sent: {:.2} s at 115 200 baud (8N1)",
            t.table.grid,
            bytes as f64 * 10.0 / 115_200.0
        );
        assert_eq!(state(&mut link).lut as usize, t.table.grid);
        let model = Model {
            display: t.matrix.clone(),
            map: GamutMap::Clip,
            observer: Observer::Cie1931,
            max,
        };
        let (mut sum, mut worst, mut n) = (0.0, 0.0f64, 0);
        let levels = [0.1f32, 0.3, 0.5, 0.7, 0.9];
        for r in levels {
            for g in levels {
                for b in levels {
                    // a colour the full model shows, as the controller's relative XYZ
                    let want = t.model.device_to_xyz([r, g, b]);
                    let rel = want.scale(100.0 / t.matrix.white().y);
                    let l = line(&Command::Xyz(rel));
                    let Ok(Command::Xyz(sent)) = Command::parse(&l) else {
                        panic!("{l}")
                    };
                    let reply = link.send(&l).unwrap();
                    assert_eq!(
                        reply,
                        model.answer_with(sent, Some(&t.table)),
                        "{name}: {l}"
                    );
                    let c = colour(reply);
                    if c.gamut != Gamut::In {
                        continue;
                    }
                    if let Some(de) = t.miss(sent, c.duty, c.max) {
                        assert!(de <= TABLE_DE, "{name}: {l}: ΔE00 {de}");
                        (sum, worst, n) = (sum + de, worst.max(de), n + 1);
                    }
                }
            }
        }
        let mean = sum / n as f64;
        println!("{name}: {n} colours, ΔE00 mean {mean:.3} max {worst:.3}");
        assert!(
            n >= 100 && mean <= TABLE_MEAN_DE,
            "{name}: {n} colours, mean {mean}"
        );
        last = Some((t, model));
    }
    let (t, _) = last.unwrap();

    // refused uploads: one-line errors, and the stored table is gone until a good one
    let err = |l: &str, link: &mut Link<_>| link.exchange(l).unwrap();
    assert_eq!(
        err("lut row 0 1 2 3 4 5 6", &mut link),
        "err lut-order at=2"
    );
    assert_eq!(err("lut begin 14", &mut link), "err out-of-range at=2");
    assert_eq!(state(&mut link).lut as usize, t.table.grid);
    let cmds: Vec<String> = t.table.commands().iter().map(line).collect();
    assert_eq!(link.exchange(&cmds[0]).unwrap(), "ok lut");
    assert_eq!(state(&mut link).lut, 0);
    assert_eq!(link.exchange(&cmds[2]).unwrap(), "err lut-order at=2");
    assert_eq!(link.exchange(&cmds[0]).unwrap(), "ok lut");
    for c in &cmds[1..cmds.len() - 1] {
        assert_eq!(link.exchange(c).unwrap(), "ok lut");
    }
    assert_eq!(
        link.exchange("lut end 00000000").unwrap(),
        "err lut-check at=2"
    );
    assert_eq!(state(&mut link).lut, 0);
    for c in &cmds {
        assert_eq!(link.exchange(c).unwrap(), "ok lut");
    }
    assert_eq!(state(&mut link).lut as usize, t.table.grid);

    // `save` and a reset: the calibration comes back and with it the table
    let probe = "xyz 30 25 20";
    let before = link.send(probe).unwrap();
    assert_eq!(link.send("save").unwrap(), Reply::Done("save"));
    emu.reset(dir.path());
    link.hello().expect("hello after the reset");
    assert_eq!(state(&mut link).lut as usize, t.table.grid);
    assert_eq!(link.send(probe).unwrap(), before);
    std::thread::sleep(Duration::from_millis(200));
    assert_total_ram(&emu.elf, &emu.log_across_reset());
}
