//! The calibrated framebuffer demo (`firmware/src/bin/framebuffer.rs`) under QEMU
//! (`mps2-an386`, Cortex-M4F): a 240×240 RGB565 framebuffer filled from an sRGB gradient through
//! the `embedded-graphics` adapter. Checked against an f64 computation of the demo panel made
//! here (`specpoly_tests::pixel`, from the panel the firmware reports):
//!
//! - every sampled pixel's code is the floor or the ceiling of the reference level (the dither
//!   picks one of the two), within `LEVEL_SLACK`;
//! - every flat 8×8 block's mean light is within 0.5 ΔE00 of the reference;
//! - the whole frame's checksum equals the same transform run on the host (the Cortex-M4 build
//!   computes bit for bit what the host does); on target, the assembly kernel
//!   (`firmware/src/board/rgb565.rs`), the portable kernel and the adapter made that same frame,
//!   and the assembly and portable kernels agree on every pixel of a random frame too;
//! - the same panel in RGB888 through the RGB888 kernel (`firmware/src/board/rgb888.rs`, no
//!   dither): every sampled code within `LEVEL_SLACK` of the floor or ceiling of the reference
//!   level, the frame's checksum the host's, the assembly's XRGB8888 words and packed bytes the
//!   portable code's on the gradient and the random frame;
//! - the tables fit 8 KiB of flash; instruction counts per pixel are printed (docs/performance.md).
//!
//! Needs `qemu-system-arm` and the `thumbv7em-none-eabihf` target (`./test.sh` installs both).

use specpoly_core::delta_e2000_xyz as delta_e00;
use specpoly_core::pixel::{Dither, Options, PanelTransform, Source, White};
use specpoly_core::GamutMap;
use specpoly_tests::pixel::{gamma_panel, Panel};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const TARGET: &str = "thumbv7em-none-eabihf";
/// A pixel's code may be one level beyond floor/ceiling of the reference level when the
/// reference sits on a level boundary (the transform's bins are ½ bin off at most).
const LEVEL_SLACK: i64 = 1;
/// The figure for dithered blocks.
const BLOCK_LIMIT: f64 = 0.5;
const W: usize = 240;
const H: usize = 240;

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .unwrap()
        .to_path_buf()
}

fn build() -> PathBuf {
    let qemu = Command::new("qemu-system-arm").arg("--version").output();
    assert!(
        matches!(&qemu, Ok(o) if o.status.success()),
        "qemu-system-arm is not installed: run ./test.sh (or apt-get install qemu-system-arm)"
    );
    let mut c = Command::new(std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into()));
    c.current_dir(repo().join("firmware"));
    for v in [
        "RUSTFLAGS",
        "CARGO_ENCODED_RUSTFLAGS",
        "CARGO_BUILD_TARGET",
        "CARGO_TARGET_DIR",
        "CARGO_BUILD_RUSTFLAGS",
    ] {
        c.env_remove(v);
    }
    let dir = repo().join("firmware/target");
    c.args([
        "build",
        "--release",
        "--bin",
        "framebuffer",
        "--target",
        TARGET,
        "--target-dir",
    ])
    .arg(&dir);
    let out = c.output().expect("cargo runs");
    assert!(
        out.status.success(),
        "firmware build failed (is the {TARGET} target installed? ./test.sh adds it):\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    dir.join(TARGET).join("release/framebuffer")
}

fn run(elf: &Path) -> String {
    let mut child = Command::new("qemu-system-arm")
        .args([
            "-machine",
            "mps2-an386",
            "-cpu",
            "cortex-m4",
            "-nographic",
            "-monitor",
            "none",
            "-semihosting-config",
            "enable=on,target=native",
            "-icount",
            "shift=0",
            "-kernel",
        ])
        .arg(elf)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .stdin(Stdio::null())
        .spawn()
        .expect("qemu-system-arm starts");
    let start = Instant::now();
    loop {
        if let Some(status) = child.try_wait().unwrap() {
            let out = child.wait_with_output().unwrap();
            let text = String::from_utf8_lossy(&out.stdout).to_string();
            assert_eq!(status.code(), Some(0), "framebuffer demo failed:\n{text}");
            return text;
        }
        if start.elapsed() > Duration::from_secs(120) {
            let _ = child.kill();
            panic!("the framebuffer demo did not exit within 120 s");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

fn numbers(line: &str) -> Vec<f64> {
    line.split_whitespace()
        .filter_map(|t| t.parse().ok())
        .collect()
}

/// The demo panel as the firmware describes it.
fn panel(out: &str) -> Panel {
    let line = out
        .lines()
        .find(|l| l.starts_with("panel "))
        .expect("a panel line");
    let v = numbers(line);
    // xy ×6, white ×2, Y, gamma ×3, bits ×3
    assert_eq!(v.len(), 15, "{line}");
    assert!(line.ends_with("bits 5 6 5 source srgb"), "{line}");
    gamma_panel(
        "demo-spi-lcd",
        [[v[0], v[1]], [v[2], v[3]], [v[4], v[5]]],
        [v[6], v[7]],
        v[8],
        [v[9], v[10], v[11]],
    )
}

fn split565(c: u16) -> [u16; 3] {
    [c >> 11, (c >> 5) & 63, c & 31]
}

/// The reference level (continuous, in level units) of light `l` on a channel of `bits`.
fn level_of(panel: &Panel, c: usize, bits: u8, l: f64) -> f64 {
    let max = (1u32 << bits) - 1;
    let light = |q: u32| panel.curves[c].decode(q as f64 / max as f64);
    if l <= light(0) {
        return 0.0;
    }
    for q in 0..max {
        let (a, b) = (light(q), light(q + 1));
        if l < b {
            return q as f64 + (l - a) / (b - a);
        }
    }
    max as f64
}

fn source(x: usize, y: usize) -> [u8; 3] {
    [
        (x * 255 / (W - 1)) as u8,
        (y * 255 / (H - 1)) as u8,
        ((x + y) * 255 / (W + H - 2)) as u8,
    ]
}

#[test]
fn calibrated_framebuffer_on_target_matches_the_f64_reference() {
    let out = run(&build());
    assert!(out.contains("framebuffer: pass"), "{out}");
    assert!(!out.contains("FAIL"), "{out}");
    let panel = panel(&out);
    let bits = Options::RGB565;
    let field = |prefix: &str| -> u64 {
        out.lines()
            .find_map(|l| l.strip_prefix(prefix))
            .and_then(|v| v.split_whitespace().next()?.parse().ok())
            .unwrap_or_else(|| panic!("no `{prefix}` in:\n{out}"))
    };
    let tables = field("tables ");
    assert!(tables <= 8 * 1024, "tables {tables} B");

    // sampled pixels: floor or ceiling of the reference level
    let (mut n, mut exact) = (0, 0);
    for line in out.lines().filter(|l| l.starts_with("px ")) {
        let v: Vec<u64> = line[3..].split(' ').map(|t| t.parse().unwrap()).collect();
        let rgb = [v[2] as u8, v[3] as u8, v[4] as u8];
        assert_eq!(rgb, source(v[0] as usize, v[1] as usize), "{line}");
        let light = panel.reference_light(Source::Srgb, White::Adapt, GamutMap::Clip, rgb);
        let code = split565(v[5] as u16);
        for c in 0..3 {
            let level = level_of(&panel, c, bits[c], light[c].clamp(0.0, 1.0));
            let (lo, hi) = (level.floor() as i64, level.ceil() as i64);
            let q = code[c] as i64;
            assert!(
                q >= lo - LEVEL_SLACK && q <= hi + LEVEL_SLACK,
                "{line}: channel {c} code {q}, reference level {level:.3}"
            );
            exact += usize::from(q == lo || q == hi);
            n += 1;
        }
    }
    assert!(n >= 3 * 200, "{n} samples");
    assert!(
        exact as f64 >= 0.99 * n as f64,
        "{exact} of {n} on floor/ceiling"
    );

    // flat 8×8 blocks: the mean light is the reference colour
    let white = panel.white();
    let mut blocks = 0;
    for line in out.lines().filter(|l| l.starts_with("block ")) {
        let t: Vec<&str> = line.split(' ').collect();
        let rgb = [1, 2, 3].map(|i| t[i].parse::<u8>().unwrap());
        let codes: Vec<u16> = t[4..]
            .iter()
            .map(|h| u16::from_str_radix(h, 16).unwrap())
            .collect();
        assert_eq!(codes.len(), 64, "{line}");
        let mut light = [0.0f64; 3];
        for code in &codes {
            let q = split565(*code);
            for c in 0..3 {
                light[c] += panel.level_light(c, bits[c], q[c] << 8) / 64.0;
            }
        }
        let want = panel.reference(Source::Srgb, White::Adapt, GamutMap::Clip, rgb);
        let de = delta_e00(panel.xyz(light), want, white);
        assert!(de <= BLOCK_LIMIT, "{line:.40}: ΔE00 {de}");
        blocks += 1;
    }
    assert_eq!(blocks, 8);

    // the whole frame, bit for bit as on the host
    let host = PanelTransform::new(
        &panel.display,
        Options {
            bits,
            ..Options::default()
        },
    )
    .unwrap();
    let mut h = 0x811c_9dc5u32;
    for y in 0..H {
        for x in 0..W {
            let c = host.apply(source(x, y), Dither::Ordered.threshold(x as u32, y as u32));
            let v = (c[0] as u16) << 11 | (c[1] as u16) << 5 | c[2] as u16;
            for b in v.to_le_bytes() {
                h = (h ^ b as u32).wrapping_mul(0x0100_0193);
            }
        }
    }
    let fw = out
        .lines()
        .find_map(|l| l.strip_prefix("checksum "))
        .expect("a checksum");
    assert_eq!(
        fw,
        format!("{h:08x}"),
        "firmware frame differs from the host's"
    );

    // the RGB888 kernel's frame (no dither): each sampled code is the reference level rounded
    // (within the slack), and the frame is the host's, bit for bit
    let bits888 = Options::RGB888;
    let (mut n, mut exact) = (0, 0);
    for line in out.lines().filter(|l| l.starts_with("px888 ")) {
        let v: Vec<u64> = line[6..].split(' ').map(|t| t.parse().unwrap()).collect();
        let rgb = [v[2] as u8, v[3] as u8, v[4] as u8];
        assert_eq!(rgb, source(v[0] as usize, v[1] as usize), "{line}");
        let light = panel.reference_light(Source::Srgb, White::Adapt, GamutMap::Clip, rgb);
        let code = [v[5] >> 16, (v[5] >> 8) & 255, v[5] & 255];
        for c in 0..3 {
            let level = level_of(&panel, c, bits888[c], light[c].clamp(0.0, 1.0));
            let (lo, hi) = (level.floor() as i64, level.ceil() as i64);
            let q = code[c] as i64;
            assert!(
                q >= lo - LEVEL_SLACK && q <= hi + LEVEL_SLACK,
                "{line}: channel {c} code {q}, reference level {level:.3}"
            );
            exact += usize::from(q == lo || q == hi);
            n += 1;
        }
    }
    assert!(n >= 3 * 200, "{n} RGB888 samples");
    assert!(
        exact as f64 >= 0.99 * n as f64,
        "RGB888: {exact} of {n} on floor/ceiling"
    );
    let host888 = PanelTransform::new(
        &panel.display,
        Options {
            bits: bits888,
            ..Options::default()
        },
    )
    .unwrap();
    let mut h = 0x811c_9dc5u32;
    for y in 0..H {
        for x in 0..W {
            let c = host888.apply(source(x, y), 128);
            let v = (c[0] as u32) << 16 | (c[1] as u32) << 8 | c[2] as u32;
            for b in v.to_le_bytes() {
                h = (h ^ b as u32).wrapping_mul(0x0100_0193);
            }
        }
    }
    let fw = out
        .lines()
        .find_map(|l| l.strip_prefix("checksum888 "))
        .expect("a checksum888");
    assert_eq!(
        fw,
        format!("{h:08x}"),
        "firmware RGB888 frame differs from the host's"
    );

    let per_px = |what: &str| field(&format!("insns {what} ")) as f64 / 100.0;
    for what in [
        "asm-equals-portable ",
        "asm-equals-portable-random ",
        "asm888-equals-portable ",
        "asm888-equals-portable-random ",
    ] {
        let same = out
            .lines()
            .find_map(|l| l.strip_prefix(what))
            .unwrap_or_else(|| panic!("no `{what}` line"));
        assert_eq!(same, format!("{} of {}", W * H, W * H), "{what}");
    }
    let (kernel, portable, levels) = (
        per_px("kernel"),
        per_px("kernel-portable"),
        per_px("levels"),
    );
    let (image, solid, plain) = (
        per_px("adapter-image"),
        per_px("adapter-solid"),
        per_px("unmanaged-image"),
    );
    let (xrgb, packed, portable888) = (
        per_px("kernel888-xrgb"),
        per_px("kernel888-packed"),
        per_px("kernel888-portable"),
    );
    println!(
        "instructions per pixel, RGB888: kernel {xrgb} (XRGB8888), {packed} (packed), portable \
         {portable888}"
    );
    println!(
        "instructions per pixel: kernel {kernel} (assembly; portable {portable}, levels only \
         {levels}), adapter image {image}, adapter solid fill {solid}, unmanaged image {plain}; \
         tables {tables} B"
    );
    assert!(solid < image, "a solid fill transforms its colour once");
    // the budget per pixel (docs/performance.md, "Calibrated framebuffer"): exact counts under
    // `-icount shift=0`
    assert!(
        kernel <= 40.0 && xrgb <= 40.0,
        "RGB565 {kernel}, RGB888 {xrgb} per pixel"
    );
}
