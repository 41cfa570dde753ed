//! `calibrate run --display led:PORT`: the RGB-LED controller as the display, played by a fake
//! controller on a pseudo-terminal that answers with the host's own model of the firmware
//! (`specpoly_led::Model`, the specification the firmware is tested against). The duties it
//! is asked for must be the patches'.

use crate::common::calibrate_run as common;

use crate::common::pty;

use pty::{Answer, FakePort};
use specpoly_calibrate::patches;
use specpoly_core::{Display, GamutMap, Observer, Transfer, Xyz};
use specpoly_led::Model;
use specpoly_protocol::{Command, Reply};
use std::sync::{Arc, Mutex};
use std::time::Duration;

const MAX: u16 = 4095;

/// A fake controller; returns it and the duties it drove.
fn fake_controller() -> (FakePort, Arc<Mutex<Vec<[u16; 3]>>>) {
    let duties = Arc::new(Mutex::new(Vec::new()));
    let d = duties.clone();
    let port = pty::spawn(move |port, stop| {
        let mut xy = [[0.64f32, 0.33], [0.3, 0.6], [0.15, 0.06]];
        let mut lum = [0.2126f32, 0.7152, 0.0722];
        let mut trc = [Transfer::Srgb, Transfer::Srgb, Transfer::Srgb];
        let mut map = GamutMap::Clip;
        pty::serve_lines(port, stop, |text| {
            let reply = match Command::parse(text.trim()) {
                Ok(Command::Hello) => Reply::hello(MAX),
                Ok(Command::Calibrate { xy: x, luminance }) => {
                    xy = x;
                    lum = luminance;
                    Reply::Done("cal")
                }
                Ok(Command::Transfer { channels, curve }) => {
                    for (k, t) in trc.iter_mut().enumerate() {
                        if channels.includes(k) {
                            *t = curve.clone();
                        }
                    }
                    Reply::Done("trc")
                }
                Ok(Command::Map(m)) => {
                    map = m;
                    Reply::Done("map")
                }
                Ok(Command::Xyz(x)) => {
                    let display =
                        Display::from_primaries(xy, lum, Xyz::default(), trc.clone()).unwrap();
                    let model = Model {
                        display,
                        map,
                        observer: Observer::Cie1931,
                        max: MAX,
                    };
                    let c = model.colour(x);
                    d.lock().unwrap().push(c.duty);
                    Reply::Colour(c)
                }
                Ok(other) => panic!("unexpected command {other:?}"),
                Err(f) => Reply::Error(f),
            };
            let mut s = String::new();
            reply.write(&mut s).unwrap();
            Answer::Line(s)
        })
    });
    (port, duties)
}

#[test]
fn led_controller_as_the_display() {
    let (fake, duties) = fake_controller();
    let dir = tempfile::tempdir().unwrap();
    let cal = dir.path().join("led.toml");
    let display = format!("led:{}", fake.path);
    let done = common::calibrate(
        &display,
        "sim:crt,noise=0.001",
        &["--ramp-steps", "5", "--verify", "4", "--settle", "0"],
        cal.to_str().unwrap(),
        Duration::from_secs(60),
    );
    drop(fake);
    assert_eq!(done.code, Some(0), "{done:?}");
    assert!(done.stdout.contains("LED controller on"), "{done:?}");
    assert!(cal.is_file());
    let set = patches::standard(5, 4).unwrap();
    let got = duties.lock().unwrap().clone();
    assert_eq!(got.len(), set.len());
    for (d, p) in got.iter().zip(&set) {
        let want = p.device.map(|v| (v * MAX as f64).round() as i64);
        for k in 0..3 {
            assert!(
                (d[k] as i64 - want[k]).abs() <= 1,
                "{d:?} for {:?}",
                p.device
            );
        }
    }
}

#[test]
fn no_controller_on_the_port() {
    let dir = tempfile::tempdir().unwrap();
    let cal = dir.path().join("led.toml");
    let done = common::calibrate(
        "led:/dev/specpoly-no-such-port",
        "sim:crt",
        &[],
        cal.to_str().unwrap(),
        Duration::from_secs(30),
    );
    assert_eq!(done.code, Some(1), "{done:?}");
    assert!(done.stderr.contains("LED display"), "{done:?}");
    assert_eq!(done.stderr.trim().lines().count(), 1, "{done:?}");
}
