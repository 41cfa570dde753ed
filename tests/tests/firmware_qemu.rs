//! The LED controller firmware under QEMU (`mps2-an386`, Cortex-M4F):
//!
//! - its host-side unit tests (controller, LED driver with embedded-hal-mock, light tables);
//! - the on-target self-test (semihosting exit code), with the flash and RAM budgets;
//! - end to end: the host's `specpoly led` code ↔ QEMU's UART on a pseudo-terminal ↔ firmware,
//!   whose every colour reply must agree with the host's independent f64 computation within
//!   the one tolerance table `specpoly::led::check::TOLERANCES` (which `led --check` uses too);
//! - the `fast-math` build (micromath): its colour error against the libm build, in ΔE00.
//!
//! Needs `qemu-system-arm` and the `thumbv7em-none-eabihf` target (`./test.sh` installs both);
//! without them these tests fail with a message saying so. They never skip.

use specpoly::led::lines::{refl, Preset};
use specpoly::led::{Link, Oracle};
use specpoly_core::{delta_e2000, Display, GamutMap, Illuminant, Lab, Observer, Transfer, Xyz};
use specpoly_protocol::{Command, Gamut, Reply};
use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};
use std::process::{Child, Command as Process, Stdio};
use std::sync::{Mutex, OnceLock};
use std::time::{Duration, Instant};

const TARGET: &str = "thumbv7em-none-eabihf";
const FLASH_BUDGET: u64 = 32 * 1024;
const RAM_BUDGET: u64 = 4 * 1024;

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

/// Runs an ELF that exits through semihosting; returns (exit code, stdout).
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
            let mut out = String::new();
            if let Some(mut s) = child.stdout.take() {
                let _ = s.read_to_string(&mut out);
            }
            return (status.code(), out);
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
fn firmware_unit_tests_pass_on_the_host() {
    require_tools();
    let host = Process::new("rustc")
        .arg("-vV")
        .output()
        .expect("rustc runs");
    let host = String::from_utf8_lossy(&host.stdout)
        .lines()
        .find_map(|l| l.strip_prefix("host: ").map(str::to_owned))
        .expect("rustc -vV names the host");
    let out = cargo()
        .args(["test", "--lib", "--target", &host])
        .output()
        .expect("cargo runs");
    assert!(
        out.status.success(),
        "firmware unit tests failed:\n{}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
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

    let (flash, ram) = budget(&dir.join("specpoly-firmware"));
    println!("flash {flash} B, static RAM {ram} B");
    assert!(
        flash <= FLASH_BUDGET,
        "flash {flash} B over {FLASH_BUDGET} B"
    );
    assert!(ram <= RAM_BUDGET, "static RAM {ram} B over {RAM_BUDGET} B");
}

fn field<T: std::str::FromStr>(out: &str, prefix: &str) -> T {
    out.lines()
        .find_map(|l| l.strip_prefix(prefix))
        .and_then(|v| v.trim().parse().ok())
        .unwrap_or_else(|| panic!("no `{prefix}` in:\n{out}"))
}

/// QEMU running the controller with its UART on a pseudo-terminal.
struct Emulator {
    child: Child,
    pty: String,
    log: std::sync::Arc<Mutex<String>>,
}

impl Emulator {
    fn start() -> Self {
        let elf = default_build().join("specpoly-firmware");
        let mut child = qemu(&elf, &["-serial", "pty"])
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .stdin(Stdio::null())
            .spawn()
            .expect("qemu-system-arm starts");
        let stdout = child.stdout.take().expect("piped stdout");
        let stderr = child.stderr.take().expect("piped stderr");
        let log = std::sync::Arc::new(Mutex::new(String::new()));
        let (tx, rx) = std::sync::mpsc::channel();
        for stream in [Box::new(stdout) as Box<dyn Read + Send>, Box::new(stderr)] {
            let log = log.clone();
            let tx = tx.clone();
            std::thread::spawn(move || {
                for line in BufReader::new(stream).lines().map_while(Result::ok) {
                    if let Some(i) = line.find("/dev/pts/") {
                        let pty: String = line[i..]
                            .chars()
                            .take_while(|c| !c.is_whitespace() && *c != ')')
                            .collect();
                        let _ = tx.send(pty);
                    }
                    let mut l = log.lock().unwrap_or_else(|e| e.into_inner());
                    l.push_str(&line);
                    l.push('\n');
                }
            });
        }
        let pty = match rx.recv_timeout(Duration::from_secs(20)) {
            Ok(p) => p,
            Err(_) => {
                let _ = child.kill();
                panic!("QEMU printed no pty path");
            }
        };
        Self { child, pty, log }
    }

    fn log(&self) -> String {
        self.log.lock().unwrap_or_else(|e| e.into_inner()).clone()
    }
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
            matches!(
                link.send(bad),
                Err(specpoly::led::LedError::Rejected { .. })
            ),
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

    // duties are also reported through semihosting, with the stack's high-water mark
    std::thread::sleep(Duration::from_millis(200));
    let log = emu.log();
    let duty_lines = log.lines().filter(|l| l.starts_with("duty ")).count();
    assert!(duty_lines >= 2 * lines.len(), "{log}");
    let stack: u64 = log
        .lines()
        .rev()
        .find_map(|l| l.split("stack=").nth(1))
        .and_then(|v| v.trim().parse().ok())
        .expect("a stack report");
    println!("firmware stack high-water mark: {stack} B");
    assert!(stack > 0 && stack < 16 * 1024, "stack {stack}");
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
    assert!(
        insns(&fast_out, "insns srgb encode ") < insns(&libm_out, "insns srgb encode "),
        "fast-math saves instructions"
    );
}

/// The controller's default LED: Rec. 709 primaries with a D65 white (the firmware's
/// `Controller::new`).
fn specpoly_firmware_default_display() -> Display {
    let _ = Illuminant::D65;
    Display::srgb()
}
