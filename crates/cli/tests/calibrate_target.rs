//! Calibration to targets (`calibrate run --target`) on simulated displays, judged against the
//! simulation's own truth (the SPD-integrated primaries and transfer curve, without the
//! measurement noise the run saw): the grey axis through the LUT written to `CAL.cal` reaches
//! the target white within [`WHITE_DXY`] in xy and follows the target tone curve (computed
//! here from its definition) within [`TONE`] of the white's luminance. One run is through the
//! real binary; the others call the solve directly.

use crate::common::calibrate_run as common;

use specpoly_calibrate::fit::{fit, FitOptions};
use specpoly_calibrate::patches;
use specpoly_calibrate::sim::{SimHandle, SimModel};
use specpoly_display::target::MeterError;
use specpoly_display::target::{self, Meter, Target, Tone, White};
use specpoly_display::video_lut::VideoLut;
use specpoly_formats::measurement::Measurement;
use std::time::Duration;

/// The largest distance in xy of the calibrated white from the target's.
const WHITE_DXY: f64 = 0.002;
/// The largest error of a grey's luminance, as a fraction of the white's (black excluded).
const TONE: f64 = 0.01;

fn xy(v: [f64; 3]) -> [f64; 2] {
    let s = v[0] + v[1] + v[2];
    [v[0] / s, v[1] / s]
}

/// The target tone curve `f(v)` from its definition (IEC 61966-2-1, CIE 15 L*, ITU-R BT.1886).
fn tone(t: Tone, v: f64, white_y: f64, black_y: f64) -> f64 {
    match t {
        Tone::Gamma(g) => v.powf(g),
        Tone::Srgb if v <= 0.04045 => v / 12.92,
        Tone::Srgb => ((v + 0.055) / 1.055).powf(2.4),
        Tone::Lstar => {
            let l = 100.0 * v;
            if l > 8.0 {
                ((l + 16.0) / 116.0).powi(3)
            } else {
                l * 27.0 / 24389.0
            }
        }
        Tone::Bt1886 => {
            let (w, b) = (white_y.powf(1.0 / 2.4), black_y.powf(1.0 / 2.4));
            let l = (w - b).powf(2.4) * (v + b / (w - b)).max(0.0).powf(2.4);
            (l - black_y) / (white_y - black_y)
        }
    }
}

/// The truth of `spec` (without noise) through `lut`: white xy, its luminance, and the largest
/// tone error over every 8-bit grey.
fn judge(spec: &str, lut: &VideoLut, t: &Target) -> ([f64; 2], f64, f64) {
    let clean: Vec<&str> = spec
        .split(',')
        .filter(|o| !o.starts_with("noise") && !o.starts_with("seed"))
        .collect();
    let sim = SimModel::parse(&clean.join(",")).unwrap();
    let white = sim.xyz(lut.apply([1.0; 3]));
    let black = sim.xyz([0.0; 3]);
    let mut worst = 0.0f64;
    for k in 0..=255 {
        let v = k as f64 / 255.0;
        let y = sim.xyz(lut.apply([v; 3]))[1];
        let rel = (y - black[1]) / (white[1] - black[1]);
        worst = worst.max((rel - tone(t.tone, v, white[1], black[1])).abs());
    }
    (xy(white), white[1], worst)
}

/// Reads the simulated display through its handle.
struct SimMeter(SimHandle);

impl Meter for SimMeter {
    fn measure(&mut self, devices: &[[f64; 3]]) -> Result<Vec<[f64; 3]>, MeterError> {
        Ok(devices
            .iter()
            .map(|d| {
                self.0.set(*d);
                self.0.read()
            })
            .collect())
    }
}

/// Measures the standard patch set, fits, and calibrates to `t`.
fn solve(spec: &str, t: &Target) -> target::Outcome {
    let h = SimHandle::new(SimModel::parse(spec).unwrap());
    let set = patches::standard(9, 0).unwrap();
    let m: Vec<Measurement> = set
        .iter()
        .map(|p| {
            h.set(p.device);
            Measurement {
                device: p.device,
                xyz: h.read(),
            }
        })
        .collect();
    let model = fit(&m, &FitOptions::default()).unwrap();
    let mut meter = SimMeter(h);
    target::calibrate(
        &model,
        t,
        &mut meter,
        &target::Options::default(),
        &mut |_| Ok(()),
    )
    .unwrap()
}

fn check(spec: &str, t: Target, white_xy: [f64; 2]) -> target::Outcome {
    let o = solve(spec, &t);
    let (w, lum, tone_err) = judge(spec, &o.lut, &t);
    let dxy = ((w[0] - white_xy[0]).powi(2) + (w[1] - white_xy[1]).powi(2)).sqrt();
    let s = o.score();
    println!(
        "{spec} → {t}: white Δxy {dxy:.5}, {lum:.2} cd/m², tone error {:.3} %, {} iterations (kept {}), measured greys ΔE00 max {:.2}",
        tone_err * 100.0,
        o.scores.len(),
        s.iteration,
        s.grey_delta_e00_max
    );
    assert!(dxy <= WHITE_DXY, "{spec} {t}: white {w:?} vs {white_xy:?}");
    assert!(tone_err <= TONE, "{spec} {t}: tone error {tone_err}");
    if let Some(l) = t.luminance {
        assert!((lum / l - 1.0).abs() <= TONE, "{spec} {t}: {lum} cd/m²");
    }
    o
}

const D65: [f64; 2] = [0.3127, 0.3290];

#[test]
fn d65_gamma_on_the_crt() {
    check(
        "crt,noise=0.001,black=0.2,seed=3",
        target::parse("white=D65,gamma=2.2").unwrap(),
        D65,
    );
}

#[test]
fn d65_from_a_native_white_far_from_it() {
    // a bluish panel (x 0.28, y 0.29: about 10 000 K, Δxy 0.05 from D65)
    let spec = "crt,white_xy=0.28:0.29,gamma=2.4,black=0.3,noise=0.001,seed=5";
    let o = check(
        spec,
        target::parse("white=D65,gamma=srgb,luminance=60").unwrap(),
        D65,
    );
    assert!(o.notes.is_empty(), "{:?}", o.notes);
    // D65 at most: the display gives less than its native 100 cd/m² there; asking more says so
    let o = check(spec, target::parse("white=D65,gamma=2.2").unwrap(), D65);
    assert!(o.aim.white[1] < 100.0);
    let too_bright = solve(spec, &target::parse("white=D65,luminance=500").unwrap());
    assert_eq!(too_bright.notes.len(), 1, "{:?}", too_bright.notes);
}

#[test]
fn crosstalk_needs_the_measured_refinement() {
    // white ≠ R + G + B: the model's first LUT misses, the measured iterations correct it
    let spec = "crt,crosstalk=0.03,gamma=2.5,black=0.1,noise=0.0005,seed=9";
    for t in [
        "white=0.3457,0.3585,gamma=bt1886",
        "white=native,gamma=lstar",
    ] {
        let t = target::parse(t).unwrap();
        let want = match t.white {
            White::Xy(w) => w,
            White::Native => xy(SimModel::parse("crt,crosstalk=0.03").unwrap().xyz([1.0; 3])),
        };
        let o = check(spec, t, want);
        assert!(o.scores.len() >= 2, "{t}: {:?}", o.scores);
        assert!(
            o.score().badness() < o.scores[0].badness(),
            "{t}: {:?}",
            o.scores
        );
    }
}

#[test]
fn the_cli_writes_the_cal_the_ti3_and_the_calibration() {
    let dir = tempfile::tempdir().unwrap();
    let cal = dir.path().join("warm.toml");
    let spec = "sim:crt,white_xy=0.345:0.357,black=0.2,noise=0.001,seed=11";
    let t = "white=D65,gamma=2.2,luminance=70";
    let done = common::calibrate(
        spec,
        "sim",
        &["--target", t],
        cal.to_str().unwrap(),
        Duration::from_secs(120),
    );
    assert_eq!(done.code, Some(0), "{done:?}");
    println!("{}", done.stdout);
    let lut = VideoLut::load(&dir.path().join("warm.cal")).unwrap();
    assert_eq!(lut.len(), 256);
    let target = target::parse(t).unwrap();
    let (w, lum, tone_err) = judge(spec.trim_start_matches("sim:"), &lut, &target);
    let dxy = ((w[0] - D65[0]).powi(2) + (w[1] - D65[1]).powi(2)).sqrt();
    assert!(dxy <= WHITE_DXY, "{w:?}");
    assert!(tone_err <= TONE, "{tone_err}");
    assert!((lum / 70.0 - 1.0).abs() <= TONE, "{lum}");
    // the calibration holds the LUT and fits the readings taken through it
    let c = specpoly_display::calibration::load(&cal).unwrap();
    let held = c.video_lut().expect("the calibration holds the LUT");
    for ch in 0..3 {
        for k in 0..256 {
            assert!((held.tables()[ch][k] - lut.tables()[ch][k]).abs() < 1e-9);
        }
    }
    let white = c.predict([1.0; 3]);
    let cw = xy(white);
    assert!(
        ((cw[0] - D65[0]).powi(2) + (cw[1] - D65[1]).powi(2)).sqrt() <= WHITE_DXY,
        "{cw:?}"
    );
    // the readings through the LUT carry it as their CAL table, as `dispread -k` writes it
    let ti3 = specpoly_formats::cgats::read_ti3_file(&dir.path().join("warm.ti3")).unwrap();
    let back = VideoLut::from_rows(ti3.video_lut.as_ref().unwrap(), "warm.ti3").unwrap();
    for c in 0..3 {
        for k in 0..256 {
            assert!((back.tables()[c][k] - lut.tables()[c][k]).abs() < 1e-9);
        }
    }
    assert!(dir.path().join("warm.native.ti3").exists());
    // every file written is announced on stderr
    for f in ["warm.native.ti3", "warm.cal", "warm.ti3", "warm.toml"] {
        let p = dir.path().join(f);
        assert!(
            done.stderr
                .lines()
                .any(|l| l.starts_with(&format!("wrote {}", p.display()))),
            "{f}: {}",
            done.stderr
        );
    }
    // a bad target is a usage error
    let bad = common::calibrate(
        spec,
        "sim",
        &["--target", "gamma=12"],
        dir.path().join("x.toml").to_str().unwrap(),
        Duration::from_secs(30),
    );
    assert_eq!(bad.code, Some(2), "{bad:?}");
    assert!(bad.stderr.contains("gamma=12"), "{}", bad.stderr);
}
