//! `tests/c/specpoly_test.c` against the Rust API: compiled with the system `cc` and linked with
//! the host staticlib, its output must equal, byte for byte (floats as bit patterns), what the
//! core's own functions give for the same inputs ([`expected`]); compiled with
//! `arm-none-eabi-gcc` and linked with the `thumbv7em-none-eabihf` staticlib, run on QEMU
//! `mps2-an386` (Cortex-M4F, semihosting), and with `riscv64-unknown-elf-gcc -march=rv32imc`
//! and the `riscv32imc-unknown-none-elf` staticlib on QEMU `virt` (ESP32-C3's instruction
//! set), it must give the same within the core's f32 error
//! (4 ulp: `math::pow_unit`'s documented bound, the largest of the functions called) and ±1
//! on integer levels (a rounding boundary). Both fail, never skip, when a tool is missing
//! (`./test.sh` installs them).
//!
//! The error cases' statuses are written here by hand from the header's documentation.

use specpoly_core::blob::{self, Parts};
use specpoly_core::light::cct;
use specpoly_core::light::channels::{Channel, Curve, Goal, Mixer};
use specpoly_core::{
    DefaultSpectrum, Display, GamutMap, Illuminant, Moments, Observer, Tabulated, Transfer, Xyz,
};
use std::fmt::Write;
use std::path::{Path, PathBuf};
use std::process::Command;

const OK: i32 = 0;
const FADE_DONE: i32 = 1;
const NULL: i32 = -1;
const NOT_FINITE: i32 = -2;
const DOMAIN: i32 = -3;
const NO_CCT: i32 = -4;
const CHANNELS: i32 = -5;
const OUT_OF_GAMUT: i32 = -6;
const SINGULAR: i32 = -7;
const SIZE: i32 = -8;
const BLOB_VERSION: i32 = -9;
const BLOB_CHECKSUM: i32 = -10;
const BLOB_TRUNCATED: i32 = -11;

/// The display the C program reads from its calibration blob: one curve of each kind.
fn blob_parts() -> Parts {
    Parts {
        primaries: [[0.64, 0.33], [0.30, 0.60], [0.15, 0.06]],
        luminance: [21.26, 71.52, 7.22],
        black: Xyz::new(0.05, 0.05, 0.06),
        transfer: [
            Transfer::Srgb,
            Transfer::Gamma(2.2),
            Transfer::table(&[0.0, 0.1, 0.3, 0.6, 1.0]).unwrap(),
        ],
    }
}

/// `calibration_blob.h` for the C program: the blob of [`blob_parts`] as a C array.
fn blob_header(dir: &Path) {
    let mut buf = [0u8; blob::MAX_BYTES];
    let n = blob::write_parts(&blob_parts(), &mut buf).unwrap();
    let bytes: Vec<String> = buf[..n].iter().map(|b| format!("0x{b:02x}")).collect();
    let text = format!(
        "/* written by tests/c_program.rs (specpoly_core::blob::write_parts) */\n\
         static const uint8_t CALIBRATION_BLOB[{n}] = {{{}}};\n",
        bytes.join(", ")
    );
    std::fs::write(dir.join("calibration_blob.h"), text).unwrap();
}

/// The lines the C program prints, from the Rust API.
struct Lines(String);

impl Lines {
    fn line(&mut self, name: &str, status: i32, values: &str) {
        writeln!(self.0, "{name} {status}{values}").unwrap();
    }
}

fn f(v: f32) -> String {
    format!(" {:08x}", v.to_bits())
}

fn d(v: f64) -> String {
    format!(" {:016x}", v.to_bits())
}

fn ints(v: impl IntoIterator<Item = impl Into<i64>>) -> String {
    v.into_iter().map(|i| format!(" {}", i.into())).collect()
}

fn floats(v: &[f32]) -> String {
    v.iter().map(|v| f(*v)).collect()
}

/// The LED channels of the C program: red, green, blue (linear) and a white (gamma 2.2).
fn rgbw() -> Mixer<6> {
    let mut m = Mixer::new();
    let xyz = [
        [0.65, 0.30, 0.0],
        [0.25, 0.70, 0.10],
        [0.18, 0.08, 0.95],
        [0.95, 1.0, 0.85],
    ];
    for (i, c) in xyz.into_iter().enumerate() {
        let curve = if i == 3 {
            Curve::Gamma(2.2)
        } else {
            Curve::Linear
        };
        m.channels.set(i, Channel::new(c, 1.0, curve)).unwrap();
    }
    m
}

fn expected() -> String {
    let mut l = Lines(String::new());
    for (name, t, duv) in [
        ("cct_to_xy_2700", 2700.0, 0.0),
        ("cct_to_xy_6500_p01", 6500.0, 0.01),
        ("cct_to_xy_1000_m05", 1000.0, -0.05),
        ("cct_to_xy_25000_p05", 25000.0, 0.05),
    ] {
        let p = Goal::Cct {
            cct: t,
            duv,
            lum: 1.0,
        }
        .point()
        .unwrap();
        l.line(name, OK, &floats(&p.xy()));
    }
    for (name, s) in [
        ("cct_to_xy_nan", NOT_FINITE),
        ("cct_to_xy_inf_duv", NOT_FINITE),
        ("cct_to_xy_500", DOMAIN),
        ("cct_to_xy_duv_06", DOMAIN),
        // outside the chromaticity diagram: x + y > 1
        ("cct_to_xy_1000_p05", DOMAIN),
        ("cct_to_xy_null", NULL),
    ] {
        l.line(name, s, "");
    }
    for (name, x, y) in [
        ("xy_to_cct_d65", 0.3127, 0.3290),
        ("xy_to_cct_a", 0.44757, 0.40745),
    ] {
        let c = cct::cct_duv(cct::xy_to_uv([x, y])).unwrap();
        l.line(name, OK, &(d(c.cct) + &d(c.duv)));
    }
    for (name, s) in [
        ("xy_to_cct_far", NO_CCT),
        ("xy_to_cct_nan", NOT_FINITE),
        ("xy_to_cct_outside", DOMAIN),
        ("xy_to_cct_null", NULL),
    ] {
        l.line(name, s, "");
    }

    let mut m = rgbw();
    let mut solved = |m: &mut Mixer<6>, name: &str, goal: Goal| {
        let s = m.target(goal, 65535).unwrap();
        let p = s.point;
        let v = floats(&[p.uv[0], p.uv[1], p.lum])
            + &floats(&p.xy())
            + &floats(&s.light)
            + &ints(s.duty)
            + &ints([s.steps]);
        l.line(name, OK, &v);
    };
    let xy = Goal::Xy {
        xy: [0.3127, 0.329],
        lum: 0.5,
    };
    solved(&mut m, "mix_xy_d65", xy);
    let warm = Goal::Cct {
        cct: 2700.0,
        duv: 0.0,
        lum: 0.2,
    };
    solved(&mut m, "mix_cct_2700", warm);
    m.fade_ms = 250;
    let cool = Goal::Cct {
        cct: 6500.0,
        duv: 0.003,
        lum: 0.9,
    };
    solved(&mut m, "mix_cct_6500_fade", cool);
    while let Some((k, n, duty)) = m.step(65535) {
        let p = m.shown().unwrap();
        let v = ints([k, n]) + &floats(&[p.uv[0], p.uv[1], p.lum]) + &ints(duty);
        l.line("mix_step", OK, &v);
    }
    l.line("mix_step", FADE_DONE, "");
    for (name, s) in [
        ("mix_out_of_gamut", OUT_OF_GAMUT),
        ("mix_nan_lum", NOT_FINITE),
        ("mix_lum_above_1", DOMAIN),
        ("mix_cct_900", DOMAIN),
        ("mix_null_out", NULL),
        ("mix_null_mixer", NULL),
        ("mix_step_null", NULL),
        ("mix_7_channels", CHANNELS),
        ("mix_2_channels", CHANNELS),
        ("mix_nan_channel", NOT_FINITE),
        ("mix_negative_gamma", DOMAIN),
        ("mixer_init_null", NULL),
    ] {
        l.line(name, s, "");
    }

    let curves = [Transfer::Srgb, Transfer::Gamma(2.2), Transfer::Linear];
    let panel = Display::from_primaries(
        [[0.64, 0.33], [0.30, 0.60], [0.15, 0.06]],
        [21.26, 71.52, 7.22],
        Xyz::new(0.05, 0.05, 0.06),
        curves,
    )
    .unwrap();
    for (name, t, map) in [
        ("drive_white", [95.047, 100.0, 108.883], GamutMap::Clip),
        ("drive_grey", [20.0, 21.0, 23.0], GamutMap::Clip),
        ("drive_cyan_clip", [20.0, 40.0, 70.0], GamutMap::Clip),
        (
            "drive_cyan_desaturate",
            [20.0, 40.0, 70.0],
            GamutMap::Desaturate,
        ),
    ] {
        let r = panel.drive(Xyz::new(t[0], t[1], t[2]), map, 1023);
        let e = r.emitted;
        let v = floats(&r.linear)
            + &ints(r.level)
            + &floats(&[e.x, e.y, e.z])
            + &ints([r.out_of_gamut as i32]);
        l.line(name, OK, &v);
    }
    for (name, s) in [
        ("drive_nan", NOT_FINITE),
        ("drive_bad_map", DOMAIN),
        ("drive_null_display", NULL),
        ("drive_null_target", NULL),
        ("drive_singular", SINGULAR),
        ("drive_inf_display", NOT_FINITE),
    ] {
        l.line(name, s, "");
    }
    spectra(&mut l);
    display_model(&mut l);
    l.0.push_str("end\n");
    l.0
}

const PATCHES: [&str; 3] = ["dark_skin", "blue_sky", "red"];

fn coefficients(s: &DefaultSpectrum) -> String {
    floats(s.coefficients().as_flattened())
}

fn spectra(l: &mut Lines) {
    let (nm, patches) = crate::spectra::samples();
    let mut r = Vec::new();
    for (_, v) in &patches {
        let s = DefaultSpectrum::fit(&Tabulated::new(&nm, v).unwrap()).unwrap();
        l.line("spectrum_fit", OK, &coefficients(&s));
        l.line("spectrum_mul", OK, &coefficients(&s.mul(&s)));
        r.push(s);
    }
    for light in [Illuminant::A, Illuminant::D65, Illuminant::FL11] {
        for o in Observer::ALL {
            let m = Moments::<8, 4>::new(o, &light.tabulated());
            for (i, s) in r.iter().enumerate() {
                for (sq, s) in [("r", *s), ("r2", s.mul(s))] {
                    let v = m.xyz(&s);
                    let name = format!("xyz:{}:{sq}:{}:{}", PATCHES[i], light.name(), o.name());
                    l.line(&name, OK, &floats(&v.to_array()));
                }
            }
        }
    }
    for nm in [380.0, 430.0, 555.5, 600.0, 780.0] {
        l.line("spectrum_eval", OK, &f(r[2].eval(nm)));
    }
    for (name, o, light) in [
        ("light_white_d65_1931", Observer::Cie1931, Illuminant::D65),
        ("light_white_fl11_1964", Observer::Cie1964, Illuminant::FL11),
        (
            "light_white_d65_2015_10",
            Observer::Cie2015_10,
            Illuminant::D65,
        ),
    ] {
        let w = Moments::<8, 4>::new(o, &light.tabulated()).white();
        l.line(name, OK, &floats(&w.to_array()));
    }
    for (name, s) in [
        ("spectrum_fit_0", SIZE),
        ("spectrum_fit_null", NULL),
        ("spectrum_fit_nan", NOT_FINITE),
        ("spectrum_fit_not_increasing", DOMAIN),
        ("spectrum_mul_null", NULL),
        ("spectrum_eval_379", DOMAIN),
        ("spectrum_xyz_observer_4", DOMAIN),
        ("spectrum_xyz_illuminant_7", DOMAIN),
        ("spectrum_xyz_nan", NOT_FINITE),
    ] {
        l.line(name, s, "");
    }
}

/// The C program's `calibration_load` line: the fields of an `SpDisplay` read from a blob
/// (a curve's code in `gamma`: 0 sRGB, 1 linear, else the exponent; tables after it).
fn calibration_line(p: &Parts) -> String {
    let mut v = floats(p.primaries.as_flattened()) + &floats(&p.luminance);
    v += &floats(&p.black.to_array());
    let gamma = p.transfer.clone().map(|t| match t {
        Transfer::Srgb => 0.0,
        Transfer::Gamma(g) => g,
        _ => 1.0,
    });
    v += &floats(&gamma);
    for t in &p.transfer {
        match t {
            Transfer::Table(t) => v += &(ints([t.len() as i64]) + &floats(t)),
            _ => v += " 0",
        }
    }
    v
}

fn display_model(l: &mut Lines) {
    let p = blob_parts();
    l.line("calibration_load", OK, &calibration_line(&p));
    let d = p.clone().display().unwrap();
    for (name, rgb) in [
        ("forward_white", [1.0, 1.0, 1.0]),
        ("forward_black", [0.0, 0.0, 0.0]),
        ("forward_mid", [0.25, 0.5, 0.75]),
        ("forward_table_knee", [0.1, 0.9, 0.375]),
    ] {
        l.line(name, OK, &floats(&d.device_to_xyz(rgb).to_array()));
    }
    for (name, t, map) in [
        ("inverse_grey", [20.0, 21.0, 23.0], GamutMap::Clip),
        ("inverse_cyan_clip", [20.0, 40.0, 70.0], GamutMap::Clip),
        (
            "inverse_cyan_desaturate",
            [20.0, 40.0, 70.0],
            GamutMap::Desaturate,
        ),
    ] {
        let e = d.encode(Xyz::new(t[0], t[1], t[2]), map);
        let v = floats(&e.device) + &floats(&e.linear) + &ints([e.out_of_gamut as i32]);
        l.line(name, OK, &v);
    }
    let r = d.drive(Xyz::new(30.0, 35.0, 20.0), GamutMap::Clip, 1023);
    let e = r.emitted;
    let v = floats(&r.linear)
        + &ints(r.level)
        + &floats(&[e.x, e.y, e.z])
        + &ints([r.out_of_gamut as i32]);
    l.line("drive_loaded", OK, &v);
    for (name, s) in [
        ("forward_above_1", DOMAIN),
        ("forward_nan", NOT_FINITE),
        ("forward_null", NULL),
        ("inverse_bad_map", DOMAIN),
        ("forward_table_65", SIZE),
        ("forward_table_1", SIZE),
    ] {
        l.line(name, s, "");
    }
    l.line("calibration_longer_region", OK, &calibration_line(&p));
    for (name, s) in [
        ("calibration_cut", BLOB_TRUNCATED),
        ("calibration_header_only", BLOB_TRUNCATED),
        ("calibration_empty", BLOB_TRUNCATED),
        ("calibration_corrupted", BLOB_CHECKSUM),
        ("calibration_version_2", BLOB_VERSION),
        ("calibration_null", NULL),
        ("calibration_null_out", NULL),
    ] {
        l.line(name, s, "");
    }
}

/// The C program's XYZ lines against colour-science's (`tests/data/spectra_references.csv`):
/// within the fit's error, as
/// `spectra::fitted_spectra_give_colour_sciences_xyz_within_the_fits_error` bounds it (0.02
/// for a reflectance, 0.05 for its square).
fn check_references(got: &str, target: &str) {
    let mut n = 0;
    for r in include_str!("data/spectra_references.csv").lines().skip(1) {
        let f: Vec<&str> = r.split(',').collect();
        let name = format!("xyz:{}:{}:{}:{}", f[0], f[1], f[2], f[3]);
        let line = got
            .lines()
            .find(|l| l.split(' ').next() == Some(name.as_str()))
            .unwrap_or_else(|| panic!("{target}: no line {name}"));
        let v: Vec<f32> = line
            .split(' ')
            .skip(2)
            .map(|h| f32::from_bits(u32::from_str_radix(h, 16).unwrap()))
            .collect();
        let tol = if f[1] == "r" { 0.02 } else { 0.05 };
        for (g, w) in v.iter().zip(&f[4..7]) {
            let w: f32 = w.parse().unwrap();
            assert!(
                (g - w).abs() <= tol,
                "{target}: {name}: {g} vs colour-science {w}"
            );
        }
        n += 1;
    }
    assert_eq!(n, 72);
}

pub(crate) fn crate_dir() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The target directory this test was built in (`target/debug/deps/main-…` → `target`).
fn target_dir() -> PathBuf {
    let exe = std::env::current_exe().unwrap();
    exe.ancestors().nth(3).unwrap().to_path_buf()
}

/// Builds the staticlib with `args` (the same command a no-op when it is up to date).
fn staticlib(args: &[&str], lib: &[&str]) -> PathBuf {
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let target = target_dir();
    let status = Command::new(cargo)
        .current_dir(crate_dir())
        .args(["build", "-p", "specpoly-c", "--target-dir"])
        .arg(&target)
        .args(args)
        .status()
        .expect("cargo runs");
    assert!(
        status.success(),
        "cargo build -p specpoly-c {args:?} failed"
    );
    let mut p = target;
    p.extend(lib);
    p.push("libspecpoly_c.a");
    p
}

pub(crate) fn run(cmd: &mut Command, what: &str) -> Vec<u8> {
    let out = cmd.output().unwrap_or_else(|e| {
        panic!("{what}: {e} (./test.sh installs it; Debian: apt-get install gcc gcc-arm-none-eabi libnewlib-arm-none-eabi qemu-system-arm)")
    });
    assert!(
        out.status.success(),
        "{what} failed: {}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    out.stdout
}

pub(crate) fn out_dir(name: &str) -> PathBuf {
    let d = target_dir().join("capi-c").join(name);
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn the_c_program_on_the_host_gives_the_rust_apis_results_bit_for_bit() {
    let lib = staticlib(&[], &["debug"]);
    let dir = out_dir("host");
    blob_header(&dir);
    let exe = dir.join("specpoly_test");
    let c = crate_dir();
    run(
        Command::new("cc")
            .args(["-std=c11", "-Wall", "-Wextra", "-Werror", "-O1", "-I"])
            .arg(c.join("include"))
            .arg("-I")
            .arg(&dir)
            .arg(c.join("tests/c/specpoly_test.c"))
            .arg(&lib)
            .args(["-lm", "-lpthread", "-ldl", "-o"])
            .arg(&exe),
        "cc",
    );
    let got = String::from_utf8(run(&mut Command::new(&exe), "the C program")).unwrap();
    let want = expected();
    for (g, w) in got.lines().zip(want.lines()) {
        assert_eq!(g, w);
    }
    assert_eq!(got, want);
    check_references(&got, "host");
}

/// Whether two result lines agree: the same name, status and integers (±1 for levels), f32
/// bit patterns within 4 ulp, f64 ones within 1e-12 relative.
fn agree(got: &str, want: &str) -> bool {
    let (g, w): (Vec<_>, Vec<_>) = (got.split(' ').collect(), want.split(' ').collect());
    if g.len() != w.len() || g.iter().take(2).ne(w.iter().take(2)) {
        return false;
    }
    g.iter()
        .zip(&w)
        .skip(2)
        .all(|(g, w)| match (g.len(), w.len()) {
            (8, 8) if g.chars().all(|c| c.is_ascii_hexdigit()) && !g.starts_with('-') => {
                let a = f32::from_bits(u32::from_str_radix(g, 16).unwrap());
                let b = f32::from_bits(u32::from_str_radix(w, 16).unwrap());
                (a - b).abs() <= 4.0 * f32::EPSILON * b.abs().max(f32::MIN_POSITIVE)
            }
            (16, 16) => {
                let a = f64::from_bits(u64::from_str_radix(g, 16).unwrap());
                let b = f64::from_bits(u64::from_str_radix(w, 16).unwrap());
                (a - b).abs() <= 1e-12 * b.abs()
            }
            _ => match (g.parse::<i64>(), w.parse::<i64>()) {
                (Ok(a), Ok(b)) => (a - b).abs() <= 1,
                _ => g == w,
            },
        })
}

/// Builds the C program for `target` with `gcc` and `flags` (start-up and linker script from
/// `tests/c/<dir>/`), runs it under `qemu`, and compares its output with the Rust API's.
fn on_qemu(target: &str, gcc: &str, flags: &[&str], dir: &str, ld: &str, qemu: &[&str]) {
    let lib = staticlib(&["--release", "--target", target], &[target, "release"]);
    let out = out_dir(target);
    blob_header(&out);
    let elf = out.join("specpoly_test.elf");
    let c = crate_dir();
    let arch = c.join("tests/c").join(dir);
    run(
        Command::new(gcc)
            .args([
                "-std=c11",
                "-Wall",
                "-Wextra",
                "-Werror",
                "-O2",
                "-ffreestanding",
            ])
            .args(flags)
            .arg("-I")
            .arg(c.join("include"))
            .arg("-I")
            .arg(&out)
            .arg("-T")
            .arg(arch.join(ld))
            .arg(arch.join("startup.c"))
            .arg(c.join("tests/c/specpoly_test.c"))
            .arg(&lib)
            .arg("-lgcc")
            .arg("-o")
            .arg(&elf),
        gcc,
    );
    // semihosting's console is QEMU's standard error here (no serial port on stdio)
    let out = Command::new("timeout")
        .arg("20")
        .args(qemu)
        .args(["-nographic", "-monitor", "none", "-serial", "none"])
        .args(["-semihosting-config", "enable=on,target=native", "-kernel"])
        .arg(&elf)
        .output()
        .unwrap_or_else(|e| panic!("{}: {e} (./test.sh installs it)", qemu[0]));
    assert!(out.status.success(), "{}: {}", qemu[0], out.status);
    let got = String::from_utf8(out.stderr).unwrap();
    let want = expected();
    assert_eq!(got.lines().count(), want.lines().count(), "{got}");
    for (g, w) in got.lines().zip(want.lines()) {
        assert!(agree(g, w), "{target}: {g}\nRust: {w}");
    }
    check_references(&got, target);
}

#[test]
fn the_c_program_on_a_cortex_m4f_under_qemu_gives_the_rust_apis_results() {
    on_qemu(
        "thumbv7em-none-eabihf",
        "arm-none-eabi-gcc",
        &[
            "-mcpu=cortex-m4",
            "-mthumb",
            "-mfloat-abi=hard",
            "-mfpu=fpv4-sp-d16",
            "-nostartfiles",
            "-specs=nano.specs",
            "-Wl,-z,noexecstack",
        ],
        "arm",
        "mps2.ld",
        &[
            "qemu-system-arm",
            "-machine",
            "mps2-an386",
            "-cpu",
            "cortex-m4",
        ],
    );
}

/// ESP32-C3's instruction set (no FPU: the core's f32 and f64 in soft float).
#[test]
fn the_c_program_on_an_rv32imc_under_qemu_gives_the_rust_apis_results() {
    on_qemu(
        "riscv32imc-unknown-none-elf",
        "riscv64-unknown-elf-gcc",
        &[
            "-march=rv32imc",
            "-mabi=ilp32",
            "-nostdlib",
            "-Wl,--no-warn-rwx-segments",
        ],
        "riscv",
        "virt.ld",
        &["qemu-system-riscv32", "-machine", "virt", "-bios", "none"],
    );
}
