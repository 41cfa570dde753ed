//! The web display in a real headless Chromium: the colour the page shows is read back from a
//! screenshot, the live page follows the patches, and a whole `calibrate run --display web`
//! completes with Chromium as the screen. Without Chromium these tests fail (never skip):
//! install it with `apt-get update && apt-get install -y chromium`.

#[path = "common/calibrate_run.rs"]
mod common;

use specpoly::calibrate::patch_display::web::WebDisplay;
use specpoly::calibrate::patch_display::PatchDisplay;
use specpoly::io::device_spec::DeviceSpec;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

fn quant(v: f64) -> u8 {
    (v * 255.0).round() as u8
}

/// Runs Chromium to completion (at most 60 s).
fn run_chromium(args: &[String]) -> std::process::ExitStatus {
    let mut c = Command::new(common::chromium())
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("start chromium");
    let deadline = Instant::now() + Duration::from_secs(60);
    loop {
        if let Some(s) = c.try_wait().unwrap() {
            return s;
        }
        if Instant::now() > deadline {
            let _ = c.kill();
            let _ = c.wait();
            panic!("chromium did not finish within 60 s");
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

struct Browser(Child);

impl Drop for Browser {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// A headless Chromium that keeps `url` open until dropped.
fn open_live(url: &str, profile: &std::path::Path) -> Browser {
    let mut args = common::chromium_args(profile);
    args.push("--remote-debugging-port=0".into());
    args.push(url.into());
    Browser(
        Command::new(common::chromium())
            .args(&args)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("start chromium"),
    )
}

#[test]
fn screenshot_shows_the_patch_colour() {
    let dir = tempfile::tempdir().unwrap();
    let d = WebDisplay::start(0).unwrap();
    for (i, rgb) in [[1.0, 0.5, 0.0], [0.2, 0.4, 0.6], [0.0, 0.0, 0.0]]
        .into_iter()
        .enumerate()
    {
        d.post(rgb);
        let shot = dir.path().join(format!("shot{i}.png"));
        let mut args = common::chromium_args(&dir.path().join(format!("profile{i}")));
        args.push(format!("--screenshot={}", shot.display()));
        args.push(d.url());
        let st = run_chromium(&args);
        assert!(st.success(), "chromium failed: {st}");
        let decoder = png::Decoder::new(std::fs::File::open(&shot).expect("a screenshot"));
        let mut reader = decoder.read_info().unwrap();
        let mut buf = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut buf).unwrap();
        let ch = info.color_type.samples();
        let (w, h) = (info.width as usize, info.height as usize);
        let at = |x: usize, y: usize| {
            let o = (y * w + x) * ch;
            [buf[o], buf[o + 1], buf[o + 2]]
        };
        let want = rgb.map(quant);
        assert_eq!(at(w / 2, h / 2), want, "centre pixel of patch {rgb:?}");
        assert_eq!(
            at(2, 2),
            want,
            "corner pixel of patch {rgb:?} (full window)"
        );
    }
}

#[test]
fn live_page_follows_the_patches() {
    let dir = tempfile::tempdir().unwrap();
    let mut d = WebDisplay::from_spec(&DeviceSpec::parse("web,wait=60,timeout=20")).unwrap();
    let _b = open_live(&d.url(), &dir.path().join("profile"));
    // each show() returns only once the page acknowledged the new colour
    for rgb in [
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.5, 0.5, 0.5],
    ] {
        let t = Instant::now();
        d.show(rgb).unwrap_or_else(|e| panic!("{e}"));
        assert!(t.elapsed() < Duration::from_secs(20));
    }
    assert!(d.requests() >= 5);
}

#[test]
fn calibrate_run_with_chromium_as_the_screen() {
    let dir = tempfile::tempdir().unwrap();
    let cal = dir.path().join("cal.toml");
    let mut run = common::start(&[
        "calibrate",
        "run",
        "--display",
        "web,wait=60,timeout=20",
        "--instrument",
        "sim:crt,noise=0.0005",
        "--ramp-steps",
        "4",
        "--verify",
        "3",
        "--settle",
        "0",
        "-o",
        cal.to_str().unwrap(),
    ]);
    let url = run.web_url();
    let _b = open_live(&url, &dir.path().join("profile"));
    let done = run.finish(Duration::from_secs(120));
    assert_eq!(done.code, Some(0), "{done:?}");
    assert!(cal.is_file(), "no calibration written: {done:?}");
    let ti3 = std::fs::read_to_string(dir.path().join("cal.ti3")).unwrap();
    assert!(ti3.starts_with("CTI3"), "{ti3}");
}
