//! `specpoly led --calibration CAL.toml` with a calibration whose model has channel
//! interaction (the Surface's fit of data/ti3): the CLI sends the drive-correction table
//! (`lut begin|row|end`, firmware/PROTOCOL.md) after `cal` and `trc`, to a fake controller on a
//! pseudo-terminal that takes the upload as the firmware does (rows in order, the checksum
//! over what arrived) and answers colours with the host model and the table it received.
//! The oracle for the colour: the full model at the reply's duties against the asked colour,
//! in `palette`'s CIEDE2000, within the table's bound. A controller that refuses the upload
//! (a row damaged on the way: `err lut-check`) makes `led` fail with one line.
//! (The real firmware under QEMU: tests/tests/firmware_qemu.rs.)

use crate::common::cli;
use crate::common::displays;
use crate::common::pty;

use cli::output as specpoly;
use displays::{de00, fitted};
use pty::{Answer, FakePort};
use serialport::TTYPort;
use specpoly_core::drive_table::checksum;
use specpoly_core::{Display, GamutMap, Observer, Transfer, Xyz};
use specpoly_led::table::{controller_display, TABLE_DE};
use specpoly_led::{DriveTable, Model};
use specpoly_protocol::{Command, CurveSummary, LutCommand, Reply, StateReport};
use std::sync::atomic::AtomicBool;
use std::sync::{Arc, Mutex};

/// What the fake controller holds: the primaries and curves sent, the table received.
#[derive(Default)]
struct Held {
    xy: [[f32; 2]; 3],
    lum: [f32; 3],
    trc: Option<[Transfer; 3]>,
    upload: Option<(usize, Vec<[i16; 3]>)>,
    table: Option<DriveTable>,
}

fn fake(damage: bool, held: Arc<Mutex<Held>>) -> FakePort {
    pty::spawn(move |port, stop| serve(port, stop, damage, held))
}

fn serve(port: TTYPort, stop: Arc<AtomicBool>, damage: bool, held: Arc<Mutex<Held>>) {
    pty::serve_lines(port, stop, |line| {
        let mut h = held.lock().unwrap();
        let reply = match Command::parse(line) {
            Err(f) => Reply::Error(f),
            Ok(Command::Hello) => Reply::hello(u16::MAX),
            Ok(Command::Calibrate { xy, luminance }) => {
                (h.xy, h.lum) = (xy, luminance);
                Reply::Done("cal")
            }
            Ok(Command::Transfer { channels, curve }) => {
                let mut t =
                    h.trc
                        .take()
                        .unwrap_or([Transfer::Linear, Transfer::Linear, Transfer::Linear]);
                for (i, c) in t.iter_mut().enumerate() {
                    if channels.includes(i) {
                        *c = curve.clone();
                    }
                }
                h.trc = Some(t);
                Reply::Done("trc")
            }
            Ok(Command::Lut(LutCommand::Begin(g))) => {
                h.upload = Some((g as usize, Vec::new()));
                h.table = None;
                Reply::Done("lut")
            }
            Ok(Command::Lut(LutCommand::Row { row, values })) => {
                let (_, nodes) = h.upload.as_mut().unwrap();
                assert_eq!(
                    row as usize * values.len() / 3,
                    nodes.len(),
                    "rows in order"
                );
                for v in values.chunks(3) {
                    nodes.push([v[0], v[1], v[2]]);
                }
                if damage && row == 5 {
                    nodes.last_mut().unwrap()[0] ^= 1;
                }
                Reply::Done("lut")
            }
            Ok(Command::Lut(LutCommand::End(check))) => {
                let (grid, nodes) = h.upload.take().unwrap();
                if checksum(grid, nodes.iter().copied()) == check {
                    h.table = Some(DriveTable { grid, nodes });
                    Reply::Done("lut")
                } else {
                    Reply::Error(specpoly_protocol::Fault::at(
                        specpoly_protocol::ErrorCode::LutCheck,
                        2,
                    ))
                }
            }
            Ok(Command::State) => Reply::State(StateReport {
                protocol: 1,
                primaries: [0, 1, 2].map(|i| [h.xy[i][0], h.xy[i][1], h.lum[i]]),
                trc: h.trc.as_ref().unwrap().each_ref().map(CurveSummary::of),
                map: GamutMap::Clip,
                observer: Observer::Cie1931,
                lut: h.table.as_ref().map_or(0, |t| t.grid as u8),
                duty: [0; 3],
                max: u16::MAX,
            }),
            Ok(Command::Xyz(v)) => {
                let model = Model {
                    display: Display::from_primaries(
                        h.xy,
                        h.lum,
                        Xyz::default(),
                        h.trc.clone().unwrap(),
                    )
                    .unwrap(),
                    map: GamutMap::Clip,
                    observer: Observer::Cie1931,
                    max: u16::MAX,
                };
                model.answer_with(v, h.table.as_ref())
            }
            Ok(_) => Reply::Done("map"),
        };
        let mut s = String::new();
        reply.write(&mut s).unwrap();
        Answer::Line(s)
    })
}

const SURFACE: &str = "microsoft-surface-pro-2017_825.ti3";

#[test]
fn led_sends_the_table_and_the_colour_is_the_full_models() {
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("surface.toml");
    let cal = fitted(SURFACE);
    cal.save(&path).unwrap();
    let model = cal.model();
    let matrix = controller_display(model.display()).unwrap();
    // a colour the full model shows, in the controller's relative XYZ
    let want = model.device_to_xyz([0.4, 0.55, 0.3]);
    let rel = want.scale(100.0 / matrix.white().y);
    let arg = |v: f32| format!("{v}");
    let held = Arc::new(Mutex::new(Held::default()));
    let f = fake(false, held.clone());
    let out = specpoly(&[
        "led",
        "--port",
        &f.path,
        "--calibration",
        path.to_str().unwrap(),
        "--check",
        "xyz",
        &arg(rel.x),
        &arg(rel.y),
        &arg(rel.z),
    ]);
    let stdout = cli::text(&out.stdout);
    assert!(out.status.success(), "{}", cli::text(&out.stderr));
    assert!(out.stderr.is_empty(), "{}", cli::text(&out.stderr));
    assert!(
        stdout.contains("check: the host agrees (full model at the duties"),
        "{stdout}"
    );
    let table = held.lock().unwrap().table.clone().expect("a table arrived");
    assert_eq!(table.grid, specpoly_led::table::DEFAULT_GRID);
    let reply = Reply::parse(stdout.lines().next().unwrap()).unwrap();
    let Reply::Colour(c) = reply else {
        panic!("{stdout}")
    };
    let shown = model.device_to_xyz(c.duty.map(|d| d as f32 / 65535.0));
    let de = de00(shown.into(), want.into(), model.white().into());
    assert!(de <= TABLE_DE, "ΔE00 {de}: {stdout}");
    // without the table the matrix model's duties miss by far more (1.2 mean on the Surface)
    let plain = matrix.drive(rel, GamutMap::Clip, u16::MAX);
    let plain_shown = model.device_to_xyz(plain.level.map(|d| d as f32 / 65535.0));
    let plain_de = de00(plain_shown.into(), want.into(), model.white().into());
    assert!(de < plain_de, "{de} vs {plain_de}");
}

#[test]
fn a_refused_upload_fails_with_one_line() {
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("surface.toml");
    fitted(SURFACE).save(&path).unwrap();
    let f = fake(true, Arc::new(Mutex::new(Held::default())));
    let out = specpoly(&[
        "led",
        "--port",
        &f.path,
        "--calibration",
        path.to_str().unwrap(),
        "xyz",
        "20",
        "20",
        "20",
    ]);
    let err = cli::text(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(err.contains("lut-check"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
}
