//! `specpoly led` against a fake controller on a pseudo-terminal: the happy path with
//! `--check`, and every way a device can fail — a malformed reply, another protocol version, a
//! silent device, a device that goes away, no such port — each a one-line error, exit code 1,
//! no panic. (The real firmware under QEMU: tests/tests/firmware_qemu.rs.)

use crate::common::cli;
use crate::common::pty;

use cli::output as specpoly;
use pty::{Answer, FakePort};
use serialport::TTYPort;
use specpoly_core::{Display, GamutMap, Observer, Transfer, Xyz};
use specpoly_led::{MixModel, Model};
use specpoly_protocol::{Command, CurveSummary, Reply, StateReport};
use std::process::Output;
use std::sync::atomic::AtomicBool;
use std::sync::Arc;

#[derive(Clone, Copy)]
enum Behaviour {
    /// Answers like the firmware (the host model, sRGB primaries, linear curves).
    Faithful,
    /// Answers like the firmware but with every duty off by 100 ticks.
    Wrong,
    /// Answers every line with garbage.
    Garbage,
    /// Speaks protocol 2.
    Version2,
    /// Never answers.
    Silent,
    /// Answers `hello`, then unplugs.
    Unplug,
}

fn fake(b: Behaviour) -> FakePort {
    pty::spawn(move |port, stop| serve(port, b, stop))
}

fn srgb_model() -> Model {
    let srgb = Display::srgb();
    let (xy, lum) = srgb.primaries();
    let t = [Transfer::Linear, Transfer::Linear, Transfer::Linear];
    Model {
        display: Display::from_primaries(xy, lum, Xyz::default(), t).unwrap(),
        map: GamutMap::Clip,
        observer: Observer::Cie1931,
        max: 1000,
    }
}

fn answer(b: Behaviour, model: &Model, mix: &mut MixModel, line: &str) -> String {
    let reply = match (b, Command::parse(line)) {
        (Behaviour::Garbage, _) => return "bonjour".into(),
        (Behaviour::Version2, _) => {
            return "ok hello specpoly-led protocol=2 max_line=1024 max=1000".into()
        }
        (_, Err(f)) => Reply::Error(f),
        (_, Ok(Command::Hello)) => Reply::hello(model.max),
        (_, Ok(Command::State)) => {
            let (xy, lum) = model.display.primaries();
            Reply::State(StateReport {
                protocol: 1,
                primaries: [0, 1, 2].map(|i| [xy[i][0], xy[i][1], lum[i]]),
                trc: [CurveSummary::Linear; 3],
                map: model.map,
                observer: model.observer,
                lut: 0,
                duty: [0; 3],
                max: model.max,
            })
        }
        (_, Ok(Command::Xyz(v))) => {
            let mut c = model.colour(v);
            if matches!(b, Behaviour::Wrong) {
                c.duty = c.duty.map(|d| d.saturating_add(100));
            }
            Reply::Colour(c)
        }
        (
            _,
            Ok(Command::Reflect {
                illuminant,
                product,
                hex,
                ..
            }),
        ) => {
            let mut c = model.colour(model.reflectance_xyz(illuminant, &product));
            c.hex = hex;
            Reply::Colour(c)
        }
        // the mixing commands: the host's simulated controller (the firmware's own calls)
        (_, Ok(c @ (Command::Channel(_) | Command::Mix(_) | Command::Fade(_)))) => {
            match mix.answer(&c) {
                Some(Reply::Mix(mut r)) if matches!(b, Behaviour::Wrong) => {
                    r.duty[0] = r.duty[0].saturating_add(100);
                    Reply::Mix(r)
                }
                Some(r) => r,
                None => Reply::Done("cal"),
            }
        }
        (_, Ok(_)) => Reply::Done("cal"),
    };
    let mut s = String::new();
    reply.write(&mut s).unwrap();
    s
}

fn serve(port: TTYPort, b: Behaviour, stop: Arc<AtomicBool>) {
    let model = srgb_model();
    let mut mix = MixModel::new(model.max);
    pty::serve_lines(port, stop, |line| match b {
        Behaviour::Silent => Answer::Nothing,
        // dropping the only master hangs the pty up
        Behaviour::Unplug if line == "hello" => {
            Answer::LineThenHangUp(answer(b, &model, &mut mix, line))
        }
        _ => Answer::Line(answer(b, &model, &mut mix, line)),
    })
}

/// `specpoly ARGS`, which must succeed.
fn succeeds(args: &[&str]) -> Output {
    let out = specpoly(args);
    assert!(out.status.success(), "{}", cli::text(&out.stderr));
    out
}

/// Exit code 1, one line on stderr containing `needle`, no panic.
fn fails_cleanly(out: &Output, needle: &str) {
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "stderr: {err}");
    assert_eq!(err.trim_end().lines().count(), 1, "one line: {err}");
    assert!(err.starts_with("specpoly: error: "), "{err}");
    assert!(err.contains(needle), "`{needle}` in: {err}");
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn a_faithful_device_passes_the_check() {
    let f = fake(Behaviour::Faithful);
    let out = succeeds(&["led", "--port", &f.path, "--check", "xyz", "20", "21", "22"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    let first = stdout.lines().next().unwrap_or_default();
    let expected = srgb_model().colour(Xyz::new(20.0, 21.0, 22.0));
    assert_eq!(Reply::parse(first), Ok(Reply::Colour(expected)), "{stdout}");
    assert!(stdout.contains("check: the host agrees"), "{stdout}");

    succeeds(&[
        "led",
        "--port",
        &f.path,
        "--check",
        "refl",
        "--repr",
        "paper",
        "--illuminant",
        "FL11",
        "colorchecker#red",
        "colorchecker#green",
    ]);

    // the README's form: `--check` after the action
    let out = succeeds(&[
        "led",
        "--port",
        &f.path,
        "refl",
        "colorchecker#red",
        "colorchecker#blue",
        "--illuminant",
        "FL11",
        "--check",
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("check: the host agrees"), "{stdout}");

    // --json (the CLI convention): the reply's values as numbers, the check's verdict
    let out = succeeds(&[
        "led", "--port", &f.path, "xyz", "20", "21", "22", "--check", "--json",
    ]);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    assert_eq!(v["reply"], "colour");
    assert_eq!(v["check"]["agrees"], true);
    let duty: Vec<u64> = v["duty"]
        .as_array()
        .unwrap()
        .iter()
        .map(|d| d.as_u64().unwrap())
        .collect();
    assert_eq!(duty, expected.duty.map(u64::from).to_vec());
    assert_eq!(
        Reply::parse(v["line"].as_str().unwrap()),
        Ok(Reply::Colour(expected))
    );
}

#[test]
fn a_device_that_disagrees_fails_the_check() {
    let f = fake(Behaviour::Wrong);
    let out = specpoly(&["led", "--port", &f.path, "--check", "xyz", "20", "21", "22"]);
    fails_cleanly(&out, "disagrees with the host");
}

/// `--channel` uploads the channels' XYZ from their spectra, then `cct`/`xy` are mixed on the
/// device; `--check` recomputes the mix from the spectra (`specpoly_led::mix_check`).
#[test]
fn channels_are_uploaded_and_mixes_checked() {
    let leds = concat!(env!("CARGO_MANIFEST_DIR"), "/../../data/leds/rgbwa.csv");
    let mut args: Vec<String> = Vec::new();
    for c in ["red", "green", "blue", "white", "amber"] {
        args.push("--channel".into());
        args.push(format!("{c}={leds}#{c}"));
    }
    let run = |b: Behaviour, extra: &[&str]| {
        let f = fake(b);
        let mut all: Vec<&str> = vec!["led", "--port", &f.path];
        all.extend(args.iter().map(String::as_str));
        all.extend(extra);
        specpoly(&all)
    };
    for (extra, key) in [
        (
            &["--check", "cct", "3000", "--lum", "0.8"][..],
            "ok mix xy=",
        ),
        (
            &[
                "--optimize",
                "efficacy",
                "--fade",
                "500",
                "xy",
                "0.3127",
                "0.329",
                "--check",
            ],
            "steps=50",
        ),
        (&["cct", "4000", "--duv", "-0.006"], "ok mix"),
    ] {
        let out = run(Behaviour::Faithful, extra);
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert!(
            out.status.success(),
            "{extra:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(stdout.contains(key), "{extra:?}: {stdout}");
        if extra.contains(&"--check") {
            assert!(stdout.contains("check: the host agrees"), "{stdout}");
        }
    }
    let out = run(
        Behaviour::Wrong,
        &["--check", "cct", "3000", "--lum", "0.8"],
    );
    fails_cleanly(&out, "disagrees with the host");
    let out = run(Behaviour::Faithful, &["xy", "0.08", "0.85"]);
    fails_cleanly(&out, "out-of-gamut");
    // usage: too few channels, a CCT outside the locus table
    let f = fake(Behaviour::Faithful);
    for bad in [
        vec![
            "led",
            "--port",
            &f.path,
            "--channel",
            "r=x.csv",
            "cct",
            "3000",
        ],
        vec!["led", "--port", &f.path, "cct", "500"],
    ] {
        let out = specpoly(&bad);
        assert_eq!(
            out.status.code(),
            Some(2),
            "{bad:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

#[test]
fn a_malformed_reply_is_a_clear_error() {
    let f = fake(Behaviour::Garbage);
    let out = specpoly(&["led", "--port", &f.path, "state"]);
    fails_cleanly(&out, "unreadable reply to `hello`");
}

#[test]
fn another_protocol_version_is_refused() {
    let f = fake(Behaviour::Version2);
    let out = specpoly(&["led", "--port", &f.path, "state"]);
    fails_cleanly(&out, "protocol 2");
}

#[test]
fn a_silent_device_times_out() {
    let f = fake(Behaviour::Silent);
    let out = specpoly(&["led", "--port", &f.path, "--timeout-ms", "300", "hello"]);
    fails_cleanly(&out, "no reply to `hello` within 300 ms");
}

#[test]
fn a_device_that_goes_away_is_a_clear_error() {
    let f = fake(Behaviour::Unplug);
    let out = specpoly(&[
        "led",
        "--port",
        &f.path,
        "--timeout-ms",
        "2000",
        "xyz",
        "1",
        "2",
        "3",
    ]);
    fails_cleanly(&out, "the device closed the connection");
}

#[test]
fn no_such_port_and_bad_arguments() {
    let out = specpoly(&["led", "--port", "/dev/no-such-port", "state"]);
    fails_cleanly(&out, "/dev/no-such-port: cannot open the serial port");
    // usage errors come before the port is touched: exit code 2
    for args in [
        &[
            "led",
            "--port",
            "/dev/null",
            "--primaries",
            "1,2,3",
            "state",
        ][..],
        &["led", "--port", "/dev/null", "--trc", "cubic", "state"],
        &[
            "led",
            "--port",
            "/dev/null",
            "refl",
            "--illuminant",
            "D99",
            "colorchecker#red",
        ],
        &["led", "--port", "/dev/null", "xyy", "0.3", "0", "5"],
    ] {
        let out = specpoly(args);
        assert_eq!(
            out.status.code(),
            Some(2),
            "{args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}
