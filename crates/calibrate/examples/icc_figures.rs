//! The ICC export's figures on every shipped display (data/ti3), for docs/calibration.md:
//! the default model is fitted on each `.ti3`, written as a v2.4 profile (tables when the model
//! has channel interaction), and read back by Little CMS (`lcms2`) and ArgyllCMS (`xicclu`,
//! `profcheck -k`).
//!
//! Per display: the profile's white (`wtpt`) against the model's white `f(1, 1, 1)` (ΔE00,
//! CIELAB against D50); Little CMS's relative transform of the measured patches' device values
//! against the model's PCS prediction (mean/max ΔE00); `xicclu -ff -ia` (absolute) against the
//! model's prediction over its white's `Y` (mean/max ΔE00); `profcheck -k`'s mean/max against
//! the measurements next to the model's own; and the round trip device → `A2B0` → `B2A0` →
//! device through Little CMS and through `xicclu` (`-ff` then `-fb`, relative) on a 52³ grid of
//! 8-bit codes (max |Δ| in codes of 255, the share within 2 codes, the model's ΔE00 between the
//! colour and what comes back), and the model's own inverse (the core's) on the same codes; each
//! round trip also over only the codes the model's own inverse gives back within 2 codes (where
//! it does not, the model shows that code's colour at another code too).
//!
//! Run: `cargo run -p specpoly-calibrate --example icc_figures [GRID]`.

use lcms2::{Intent, PixelFormat, Profile, Tag, TagSignature, Transform};
use specpoly_calibrate::fit::{fit, FitOptions};
use specpoly_core::delta_e2000_xyz as delta_e00;
use specpoly_display::icc::{self, IccOptions};
use specpoly_formats::cgats::read_ti3;
use std::io::Write;
use std::path::Path;
use std::process::{Command, Stdio};

fn main() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/ti3");
    let mut names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|n| n.ends_with(".ti3"))
        .collect();
    names.sort();
    let tmp = tempfile::tempdir().unwrap();
    println!("| display | tables | white ΔE00 | lcms mean / max | xicclu mean / max | profcheck mean / max (model) | round trip max codes |");
    println!("|---|---|---|---|---|---|---|");
    for name in names {
        let text = std::fs::read_to_string(dir.join(&name)).unwrap();
        let t = read_ti3(&text, &name).unwrap();
        let meas = t.best_units().0;
        let cal = fit(&meas, &FitOptions::default()).unwrap();
        let opts = IccOptions::for_calibration(&cal);
        let t0 = std::time::Instant::now();
        let bytes = icc::build(&cal, &name, &opts).unwrap();
        let build_s = t0.elapsed().as_secs_f64();
        let path = tmp.path().join("p.icc");
        std::fs::write(&path, &bytes).unwrap();
        std::fs::write(tmp.path().join("m.ti3"), &text).unwrap();
        let p = Profile::new_icc(&bytes).unwrap();
        let w = icc::model_white(&cal);
        let wn = w.map(|v| v / w[1]);
        let Tag::CIEXYZ(wt) = p.read_tag(TagSignature::MediaWhitePointTag) else {
            panic!("no wtpt")
        };
        let white_de = delta_e00([wt.X, wt.Y, wt.Z], wn, icc::D50);
        // Little CMS, relative, on the measured patches
        let xyz = Profile::new_xyz();
        let fwd: Transform<[f64; 3], [f64; 3]> = Transform::new(
            &p,
            PixelFormat::RGB_DBL,
            &xyz,
            PixelFormat::XYZ_DBL,
            Intent::RelativeColorimetric,
        )
        .unwrap();
        let dev: Vec<[f64; 3]> = meas.iter().map(|m| m.device).collect();
        let mut out = vec![[0.0; 3]; dev.len()];
        fwd.transform_pixels(&dev, &mut out);
        let lcms: Vec<f64> = dev
            .iter()
            .zip(&out)
            .map(|(d, o)| delta_e00(*o, icc::predict_pcs(&cal, *d), icc::D50))
            .collect();
        // xicclu, absolute
        let mut child = Command::new("xicclu")
            .args(["-v0", "-ff", "-ia", "-px"])
            .arg(&path)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn()
            .unwrap();
        {
            let mut sin = child.stdin.take().unwrap();
            for d in &dev {
                writeln!(sin, "{} {} {}", d[0], d[1], d[2]).unwrap();
            }
        }
        let o = child.wait_with_output().unwrap();
        let argyll: Vec<[f64; 3]> = String::from_utf8_lossy(&o.stdout)
            .lines()
            .filter_map(|l| {
                let v: Vec<f64> = l
                    .split_whitespace()
                    .filter_map(|s| s.parse().ok())
                    .collect();
                (v.len() >= 3).then(|| [v[0], v[1], v[2]])
            })
            .collect();
        assert_eq!(
            argyll.len(),
            dev.len(),
            "{}",
            String::from_utf8_lossy(&o.stdout)
        );
        let xic: Vec<f64> = dev
            .iter()
            .zip(&argyll)
            .map(|(d, a)| delta_e00(*a, cal.predict(*d).map(|v| v / w[1]), icc::D50))
            .collect();
        // profcheck against the readings, and the model's own figures
        let o = Command::new("profcheck")
            .args(["-k", "m.ti3", "p.icc"])
            .current_dir(tmp.path())
            .output()
            .unwrap();
        let s = String::from_utf8_lossy(&o.stdout).to_string();
        let grab = |key: &str| -> f64 {
            s.split(key)
                .nth(1)
                .and_then(|r| r.split(|c: char| c == ',' || c.is_whitespace()).next())
                .and_then(|v| v.parse().ok())
                .unwrap_or(f64::NAN)
        };
        let (pc_mean, pc_max) = (grab("avg. = "), grab("max. = "));
        let mw = meas
            .iter()
            .find(|m| m.device.iter().all(|v| *v >= 1.0))
            .map(|m| m.xyz)
            .unwrap();
        let own: Vec<f64> = meas
            .iter()
            .map(|m| {
                delta_e00(
                    cal.predict(m.device).map(|v| v / w[1]),
                    m.xyz.map(|v| v / mw[1]),
                    icc::D50,
                )
            })
            .collect();
        // round trip through the tables (or the matrix/TRC)
        let back: Transform<[f64; 3], [f64; 3]> = Transform::new(
            &xyz,
            PixelFormat::XYZ_DBL,
            &p,
            PixelFormat::RGB_DBL,
            Intent::RelativeColorimetric,
        )
        .unwrap();
        let mut codes = Vec::new();
        for r in (0..=255).step_by(5) {
            for g in (0..=255).step_by(5) {
                for b in (0..=255).step_by(5) {
                    codes.push([r as f64 / 255.0, g as f64 / 255.0, b as f64 / 255.0]);
                }
            }
        }
        let mut pcs = vec![[0.0; 3]; codes.len()];
        fwd.transform_pixels(&codes, &mut pcs);
        let mut rgb = vec![[0.0; 3]; codes.len()];
        back.transform_pixels(&pcs, &mut rgb);
        // the same through ArgyllCMS: xicclu forward (A2B0), then backward (B2A0), relative
        let fwd_a = xicclu(&path, &["-ff", "-ir", "-px"], &codes);
        let rgb_a = xicclu(&path, &["-fb", "-ir", "-px"], &fwd_a);
        // the model's own inverse (the core's): where the model cannot tell codes apart
        let rgb_m: Vec<[f64; 3]> = codes.iter().map(|c| cal.inverse(cal.predict(*c))).collect();
        let off = |c: &[f64; 3], o: &[f64; 3]| {
            (0..3)
                .map(|k| (c[k] - o[k]).abs() * 255.0)
                .fold(0.0, f64::max)
        };
        // the codes the model itself gives back (its own inverse within 2 codes): where it
        // does not, the model shows the code's colour at another code too
        let told: Vec<bool> = codes
            .iter()
            .zip(&rgb_m)
            .map(|(c, m)| off(c, m) <= 2.0)
            .collect();
        let trip = |out: &[[f64; 3]]| {
            let mut worst = (0.0f64, [0.0; 3]);
            let (mut within, mut worst_de) = (0usize, 0.0f64);
            let (mut told_n, mut told_within, mut told_worst) = (0usize, 0usize, 0.0f64);
            for ((c, o), t) in codes.iter().zip(out).zip(&told) {
                if *t {
                    told_n += 1;
                    told_within += usize::from(off(c, o) <= 2.0);
                    told_worst = told_worst.max(off(c, o));
                }
                worst_de = worst_de.max(delta_e00(
                    icc::predict_pcs(&cal, *o),
                    icc::predict_pcs(&cal, *c),
                    icc::D50,
                ));
                let d = off(c, o);
                within += usize::from(d <= 2.0);
                if d > worst.0 {
                    worst = (d, *c);
                }
            }
            format!(
                "{:.1} at {:?}, {:.2} % ≤ 2, model ΔE00 {worst_de:.2}; of the {:.2} % the model gives back: {told_worst:.1}, {:.2} % ≤ 2",
                worst.0,
                worst.1.map(|v| (v * 255.0).round()),
                100.0 * within as f64 / codes.len() as f64,
                100.0 * told_n as f64 / codes.len() as f64,
                100.0 * told_within as f64 / told_n.max(1) as f64
            )
        };
        let (trip_l, trip_a, trip_m) = (trip(&rgb), trip(&rgb_a), trip(&rgb_m));
        let stat = |v: &[f64]| {
            (
                v.iter().sum::<f64>() / v.len() as f64,
                v.iter().fold(0.0f64, |a, b| a.max(*b)),
            )
        };
        let (lm, lx) = stat(&lcms);
        let (xm, xx) = stat(&xic);
        let (om, ox) = stat(&own);
        println!(
            "| {name} | {} | {white_de:.3} | {lm:.3} / {lx:.3} | {xm:.3} / {xx:.3} | {pc_mean:.3} / {pc_max:.3} ({om:.3} / {ox:.3}) | lcms {trip_l} | xicclu {trip_a} | model {trip_m} | build {build_s:.1} s, {} bytes",
            opts.tables,
            bytes.len()
        );
    }
}

/// `xicclu -v0 ARGS profile` on `input` (one triple per line): its output triples.
fn xicclu(profile: &Path, args: &[&str], input: &[[f64; 3]]) -> Vec<[f64; 3]> {
    let mut child = Command::new("xicclu")
        .arg("-v0")
        .args(args)
        .arg(profile)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    let mut sin = child.stdin.take().unwrap();
    let text: String = input
        .iter()
        .map(|d| format!("{} {} {}\n", d[0], d[1], d[2]))
        .collect();
    let writer = std::thread::spawn(move || sin.write_all(text.as_bytes()));
    let o = child.wait_with_output().unwrap();
    writer.join().unwrap().unwrap();
    let out: Vec<[f64; 3]> = String::from_utf8_lossy(&o.stdout)
        .lines()
        .filter_map(|l| {
            let v: Vec<f64> = l
                .split_whitespace()
                .filter_map(|s| s.parse().ok())
                .collect();
            (v.len() >= 3).then(|| [v[0], v[1], v[2]])
        })
        .collect();
    assert_eq!(out.len(), input.len(), "xicclu {args:?}");
    out
}
