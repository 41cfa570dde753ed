//! Measuring a display (`specpoly calibrate run`): show patches, read them, save the readings
//! as CGATS .ti3 after every patch, fit Cowan's model and write the calibration.
//!
//! ```text
//! specpoly calibrate run --display D --instrument I -o CAL.toml [--ramp-steps N] [--verify N]
//!                        [--patches SET.ti1] [--resume | --force]
//! ```
//! writes `CAL.ti3` (all readings, committed after each patch — or each batch with
//! `--instrument argyll` — so an interrupted run keeps what it measured; see
//! [`crate::session`]) and `CAL.toml` (the fit of the non-verification patches).
//! An existing `CAL.ti3` is never overwritten: `--resume` measures only the patches it lacks,
//! `--force` keeps it as `CAL.ti3.1` (`.2`, …) and starts over.

use crate::error::{Error, Result};
use crate::fit::{self, FitOptions, MatrixFit};
use crate::instrument::{self, argyll, Instrument};
use crate::interrupt;
use crate::patch_display::{self, PatchDisplay};
use crate::patches::{self, Patch, PatchKind};
use crate::progress;
use crate::session::Session;
use specpoly_display::calibration::Calibration;
use specpoly_display::target::{Meter, MeterError};
use specpoly_display::video_lut::VideoLut;
use specpoly_formats::cgats::Ti3Info;
use specpoly_formats::measurement::Measurement;
use std::path::{Path, PathBuf};
use std::time::Duration;

/// Where the readings go: `CAL.toml` → `CAL.ti3`.
pub fn ti3_path(output: &Path) -> PathBuf {
    output.with_extension("ti3")
}

/// A failed run: the error and the readings taken before it.
#[derive(Debug)]
pub struct Interrupted {
    /// What went wrong, with the patch it happened at ([`Error::AtPatch`]).
    pub error: Box<Error>,
    /// Readings taken so far, in patch order.
    pub taken: Vec<Measurement>,
}

/// Shows each patch, waits `settle`, reads it, and calls `save` with all readings so far after
/// every patch. Stops at the first failure (of the display, the instrument or `save`).
pub fn measure_all(
    display: &mut dyn PatchDisplay,
    instrument: &mut dyn Instrument,
    patches: &[Patch],
    settle: Duration,
    mut save: impl FnMut(&[Measurement]) -> Result<()>,
) -> std::result::Result<Vec<Measurement>, Interrupted> {
    let bar = progress::bar(patches.len() as u64, "measuring", "patches");
    let mut taken: Vec<Measurement> = Vec::with_capacity(patches.len());
    for (i, p) in patches.iter().enumerate() {
        let at = |e: Error| Error::AtPatch {
            number: i + 1,
            total: patches.len(),
            kind: p.kind.name(),
            device: p.device,
            source: Box::new(e),
        };
        if interrupt::requested() {
            bar.abandon();
            return Err(Interrupted {
                error: Box::new(at(Error::Interrupted)),
                taken,
            });
        }
        let reading = display
            .show(p.device)
            .map_err(Error::from)
            .and_then(|()| {
                if !settle.is_zero() {
                    std::thread::sleep(settle);
                }
                Ok(instrument.measure()?)
            })
            .map_err(at);
        let xyz = match reading {
            Ok(x) => x,
            Err(error) => {
                bar.abandon();
                return Err(Interrupted {
                    error: Box::new(error),
                    taken,
                });
            }
        };
        taken.push(Measurement {
            device: p.device,
            xyz,
        });
        if let Err(e) = save(&taken) {
            bar.abandon();
            return Err(Interrupted {
                error: Box::new(e),
                taken,
            });
        }
        bar.inc(1);
    }
    bar.finish_and_clear();
    Ok(taken)
}

/// Opens the display and the instrument named on the command line.
pub fn open(
    display_spec: &str,
    instrument_spec: &str,
) -> Result<(Box<dyn PatchDisplay>, Box<dyn Instrument>)> {
    let d = patch_display::open(display_spec)?;
    instrument::open(instrument_spec, d)
}

/// The primaries as the raw readings give them: full channel minus black (what a fit must
/// come close to), `None` if a patch is missing.
pub fn raw_primaries(patches: &[Patch], m: &[Measurement]) -> Option<[[f64; 3]; 3]> {
    let find = |d: [f64; 3]| {
        patches
            .iter()
            .zip(m)
            .find(|(p, _)| p.device == d)
            .map(|(_, m)| m.xyz)
    };
    let black = find([0.0; 3])?;
    let mut out = [[0.0; 3]; 3];
    for (ch, o) in out.iter_mut().enumerate() {
        let mut d = [0.0; 3];
        d[ch] = 1.0;
        let f = find(d)?;
        *o = [0, 1, 2].map(|k| f[k] - black[k]);
    }
    Some(out)
}

/// The readings of the fit patches and of the verification patches of `set`, in order.
pub fn split(set: &[Patch], taken: &[Measurement]) -> (Vec<Measurement>, Vec<Measurement>) {
    let (fit, verify): (Vec<_>, Vec<_>) =
        set.iter().zip(taken).partition(|(p, _)| p.kind.for_fit());
    (
        fit.into_iter().map(|(_, m)| *m).collect(),
        verify.into_iter().map(|(_, m)| *m).collect(),
    )
}

/// Splits the readings `taken` of `set` ([`split`]), fits Cowan's model to the fit patches,
/// verifies it on the others, records where the readings came from (the file and its
/// SHA-256: fit and readings are one result) and writes the calibration to `out`: the
/// calibration and how many patches were fitted and verified.
pub fn fit_and_save(
    out: &Path,
    ti3: &Path,
    info: &Ti3Info,
    matrix: MatrixFit,
    set: &[Patch],
    taken: &[Measurement],
) -> Result<(Calibration, [usize; 2])> {
    let (fit_set, verify_set) = split(set, taken);
    let opts = FitOptions {
        matrix,
        ..FitOptions::default()
    };
    let mut cal = fit::fit_and_verify(&fit_set, &verify_set, &opts)?;
    {
        let (_, prov) = cal.report_mut();
        prov.source = ti3.display().to_string();
        prov.readings_sha256 = crate::session::sha256_file(ti3)?;
        prov.instrument = info.instrument.clone().unwrap_or_default();
        prov.measured = info.created.clone().unwrap_or_default();
        // repeated white and black readings that disagree, numbered as in the .ti3
        prov.notes
            .extend(crate::drift::check(taken).iter().map(|d| d.note()));
    }
    cal.save(out)?;
    Ok((cal, [fit_set.len(), verify_set.len()]))
}

/// The patch set of a run: `patches` (an ArgyllCMS `.ti1`), or the standard ramps and
/// verification patches.
pub fn patch_set(patches: Option<&Path>, ramp_steps: usize, verify: usize) -> Result<Vec<Patch>> {
    match patches {
        Some(p) => {
            let text = specpoly_formats::read::text(p)?;
            patches::from_devices(&specpoly_formats::ti1::read_ti1(
                &text,
                &p.display().to_string(),
            )?)
        }
        None => patches::standard(ramp_steps, verify),
    }
}

/// Where and how a run measures.
pub struct Devices<'a> {
    /// `--display`.
    pub display: &'a str,
    /// `--instrument`.
    pub instrument: &'a str,
    /// `--settle`, ms.
    pub settle: Option<u64>,
    /// The readings file.
    pub ti3: &'a Path,
}

/// The opened display and instrument of a run: a patch display read by an instrument, or
/// ArgyllCMS's `dispread` (which shows and reads its own patches). Optionally a video LUT is
/// applied to every patch before it is shown ([`Rig::set_lut`]), as a graphics card would.
pub enum Rig {
    /// `--display D --instrument I`.
    Patch {
        /// Where patches are shown.
        display: Box<dyn PatchDisplay>,
        /// What reads them.
        instrument: Box<dyn Instrument>,
        /// The wait before each reading.
        settle: Duration,
        /// The video LUT patches go through.
        lut: Option<VideoLut>,
    },
    /// `--display argyll… --instrument argyll…`.
    Argyll {
        /// The reader.
        reader: argyll::Dispread,
        /// The video LUT patches go through.
        lut: Option<VideoLut>,
    },
}

impl Rig {
    /// Opens the devices of `dev`; `say` prints what they are.
    pub fn open(
        dev: &Devices<'_>,
        say: &mut dyn FnMut(&str) -> specpoly_formats::Result<()>,
    ) -> Result<Rig> {
        if argyll::is_argyll(dev.instrument) {
            let reader = argyll::Dispread::open(
                dev.instrument,
                dev.display,
                dev.settle.map(Duration::from_millis),
            )?;
            say(&format!("display: {}", reader.describe_display()))?;
            say(&format!("instrument: {}", reader.describe()))?;
            return Ok(Rig::Argyll { reader, lut: None });
        }
        if dev.display.starts_with("argyll") {
            return Err(Error::ArgyllDisplayNeedsArgyll);
        }
        let display = patch_display::open(dev.display)?;
        say(&format!("display: {}", display.describe()))?;
        let (display, instrument) = instrument::open(dev.instrument, display)?;
        say(&format!("instrument: {}", instrument.describe()))?;
        let settle = dev
            .settle
            .map(Duration::from_millis)
            .unwrap_or_else(|| display.default_settle());
        Ok(Rig::Patch {
            display,
            instrument,
            settle,
            lut: None,
        })
    }

    /// Patches go through `lut` from now on (`None`: as they are).
    pub fn set_lut(&mut self, l: Option<VideoLut>) {
        match self {
            Rig::Patch { lut, .. } | Rig::Argyll { lut, .. } => *lut = l,
        }
    }

    /// The instrument's description.
    pub fn describe_instrument(&self) -> String {
        match self {
            Rig::Patch { instrument, .. } => instrument.describe(),
            Rig::Argyll { reader, .. } => reader.describe(),
        }
    }

    /// The simulated display's true primaries, if it is simulated.
    pub fn truth(&self) -> Option<[[f64; 3]; 3]> {
        match self {
            Rig::Patch { display, .. } => display.simulation().map(|s| s.model().primaries),
            Rig::Argyll { .. } => None,
        }
    }

    /// With `--display` and `--instrument`: shows `patches` one at a time (their device values
    /// through the LUT) and reads each, calling `save` with the readings so far after every
    /// one. Nothing to show on the ArgyllCMS rig (it reads in batches of its own).
    fn show_and_read(
        &mut self,
        patches: impl Iterator<Item = Patch>,
        save: impl FnMut(&[Measurement]) -> Result<()>,
    ) -> Result<Vec<Measurement>> {
        let Rig::Patch {
            display,
            instrument,
            settle,
            lut,
        } = self
        else {
            return Ok(Vec::new());
        };
        let todo: Vec<Patch> = patches
            .map(|p| Patch {
                device: through(lut, p.device),
                ..p
            })
            .collect();
        measure_all(display.as_mut(), instrument.as_mut(), &todo, *settle, save)
            .map_err(|i| *i.error)
    }

    /// Asks the user to place the instrument (ArgyllCMS's window, on a terminal, not fake).
    fn place_instrument(&self) -> Result<()> {
        use std::io::IsTerminal;
        if let Rig::Argyll { reader, .. } = self {
            if !reader.is_fake() && std::io::stdin().is_terminal() {
                eprintln!(
                    "put the instrument on the middle of the screen (where ArgyllCMS's patch window opens) and press Enter"
                );
                let mut line = String::new();
                std::io::stdin()
                    .read_line(&mut line)
                    .map_err(|e| Error::io("stdin", e))?;
            }
        }
        Ok(())
    }
}

/// The display crate's [`Meter`]: the rig's errors boxed, for the caller to downcast.
impl Meter for Rig {
    fn measure(&mut self, devices: &[[f64; 3]]) -> Result<Vec<[f64; 3]>, MeterError> {
        self.read(devices).map_err(|e| Box::new(e) as MeterError)
    }
}

impl Rig {
    /// [`Meter::measure`]: shows and reads `devices` (through the LUT).
    fn read(&mut self, devices: &[[f64; 3]]) -> Result<Vec<[f64; 3]>> {
        match self {
            Rig::Patch { .. } => {
                let patches = devices.iter().map(|d| Patch {
                    kind: PatchKind::Mixed,
                    device: *d,
                });
                let m = self.show_and_read(patches, |_| Ok(()))?;
                Ok(m.into_iter().map(|m| m.xyz).collect())
            }
            Rig::Argyll { reader, lut } => {
                let through: Vec<[f64; 3]> = devices.iter().map(|d| through(lut, *d)).collect();
                let mut out = Vec::with_capacity(devices.len());
                for chunk in through.chunks(reader.batch().max(1)) {
                    out.extend(reader.measure(chunk)?);
                }
                Ok(out)
            }
        }
    }
}

/// The device values sent for `d`: through the video LUT, if one is loaded.
fn through(lut: &Option<VideoLut>, d: [f64; 3]) -> [f64; 3] {
    lut.as_ref().map_or(d, |l| l.apply(d))
}

/// Measures the patches `session` lacks: one at a time with `--display` and `--instrument`
/// (each saved at once), or a batch at a time with ArgyllCMS's `dispread` (each batch saved
/// before the next starts). `say` prints a line (the devices, the patch count) before
/// measuring starts. Returns the simulated display's true primaries, if it is simulated.
pub fn measure_session(
    dev: &Devices<'_>,
    set: &[Patch],
    session: &mut Session,
    head: &str,
    say: &mut dyn FnMut(&str) -> specpoly_formats::Result<()>,
) -> Result<Option<[[f64; 3]; 3]>> {
    let mut rig = Rig::open(dev, say).map_err(|e| session.stopped(e))?;
    say(head).map_err(|e| session.stopped(e.into()))?;
    record_session(&mut rig, set, session)?;
    Ok(rig.truth())
}

/// Measures the patches `session` lacks on `rig` (through its LUT, if it has one), saving
/// each reading (each batch, with ArgyllCMS) as it is taken, and closes the readings file
/// ([`Session::close`]) however measuring ends. A failure comes as [`Error::Stopped`]: why,
/// and the readings the session kept.
pub fn record_session(rig: &mut Rig, set: &[Patch], session: &mut Session) -> Result<()> {
    let measured = record(rig, set, session);
    let closed = session.close();
    match measured.and(closed) {
        Ok(()) => Ok(()),
        Err(e) => Err(session.stopped(e)),
    }
}

fn record(rig: &mut Rig, set: &[Patch], session: &mut Session) -> Result<()> {
    session.set_instrument(rig.describe_instrument());
    rig.place_instrument()?;
    let missing = session.missing();
    match rig {
        Rig::Patch { .. } => {
            rig.show_and_read(missing.iter().map(|&i| set[i]), |m| {
                let k = m.len() - 1;
                session.record(missing[k], m[k].xyz)
            })?;
            Ok(())
        }
        Rig::Argyll { reader, lut } => {
            let bar = progress::bar(missing.len() as u64, "measuring", "patches");
            let total = set.len();
            for chunk in missing.chunks(reader.batch()) {
                let devices: Vec<[f64; 3]> =
                    chunk.iter().map(|&i| through(lut, set[i].device)).collect();
                let first = chunk[0] + 1;
                let last = chunk[chunk.len() - 1] + 1;
                let xyz = reader.measure(&devices).map_err(|e| {
                    bar.abandon();
                    Error::AtBatch {
                        first,
                        last,
                        total,
                        source: Box::new(e),
                    }
                })?;
                let rows: Vec<(usize, [f64; 3])> = chunk.iter().copied().zip(xyz).collect();
                session.set_instrument(reader.describe());
                session.record_all(&rows)?;
                bar.inc(chunk.len() as u64);
            }
            bar.finish_and_clear();
            Ok(())
        }
    }
}
