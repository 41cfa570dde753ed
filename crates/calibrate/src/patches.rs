//! The patches a calibration run shows, in the order it shows them.
//!
//! For `--ramp-steps N` and `--verify V`:
//!
//! 1. black `(0, 0, 0)` and white `(1, 1, 1)`;
//! 2. a ramp per channel — red, green, blue — at the levels `k / (N − 1)`, `k = 1 … N − 1`
//!    (the other channels at 0; level 0 is the black patch);
//! 3. a grey ramp `(v, v, v)` at the same levels except 1 (the white patch);
//! 4. `V` verification patches spread over the RGB cube (the Halton sequence in bases 2, 3, 5,
//!    skipping its first point): colours the fit did not see, used to check it.
//!
//! Every value is rounded to the 8-bit grid `k / 255` (what a browser, a video card or the
//! LED controller can show), and duplicates after rounding are dropped. The default,
//! `N = 9, V = 16`, gives 2 + 3·8 + 7 + 16 = 49 patches.

use crate::error::{Error, Result};

/// What a patch is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PatchKind {
    /// All channels off.
    Black,
    /// All channels full.
    White,
    /// One channel (0 red, 1 green, 2 blue) ramp.
    Ramp(usize),
    /// Equal channels.
    Grey,
    /// A verification colour (not used by the fit).
    Verify,
    /// Any other colour of a patch set read from a file (used by the fit).
    Mixed,
}

impl PatchKind {
    /// Short name for ids and messages.
    pub fn name(self) -> &'static str {
        match self {
            PatchKind::Black => "black",
            PatchKind::White => "white",
            PatchKind::Ramp(0) => "red",
            PatchKind::Ramp(1) => "green",
            PatchKind::Ramp(_) => "blue",
            PatchKind::Grey => "grey",
            PatchKind::Verify => "verify",
            PatchKind::Mixed => "mixed",
        }
    }

    /// Whether the fit uses patches of this kind (all but verification).
    pub fn for_fit(self) -> bool {
        self != PatchKind::Verify
    }
}

/// One patch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Patch {
    /// What it is for.
    pub kind: PatchKind,
    /// Device values, each `k / 255`.
    pub device: [f64; 3],
}

/// Rounds to the 8-bit grid.
pub fn quantize(v: f64) -> f64 {
    (v.clamp(0.0, 1.0) * 255.0).round() / 255.0
}

fn halton(mut i: u64, base: u64) -> f64 {
    let (mut f, mut r) = (1.0, 0.0);
    while i > 0 {
        f /= base as f64;
        r += f * (i % base) as f64;
        i /= base;
    }
    r
}

/// The patch set for `ramp_steps` levels per ramp (2–256) and `verify` verification patches.
pub fn standard(ramp_steps: usize, verify: usize) -> Result<Vec<Patch>> {
    if !(2..=256).contains(&ramp_steps) {
        return Err(Error::RampSteps(ramp_steps));
    }
    if verify > 10_000 {
        return Err(Error::VerifyCount(verify));
    }
    let mut out: Vec<Patch> = Vec::new();
    // adds a patch unless one with the same (rounded) values is there; true if added
    fn push(out: &mut Vec<Patch>, kind: PatchKind, device: [f64; 3]) -> bool {
        let device = device.map(quantize);
        if out.iter().any(|p| p.device == device) {
            return false;
        }
        out.push(Patch { kind, device });
        true
    }
    push(&mut out, PatchKind::Black, [0.0; 3]);
    push(&mut out, PatchKind::White, [1.0; 3]);
    let levels: Vec<f64> = (1..ramp_steps)
        .map(|k| k as f64 / (ramp_steps - 1) as f64)
        .collect();
    for ch in 0..3 {
        for &v in &levels {
            let mut d = [0.0; 3];
            d[ch] = v;
            push(&mut out, PatchKind::Ramp(ch), d);
        }
    }
    for &v in &levels {
        push(&mut out, PatchKind::Grey, [v; 3]);
    }
    let mut i = 1u64;
    let mut added = 0;
    while added < verify {
        let d = [halton(i, 2), halton(i, 3), halton(i, 5)].map(quantize);
        i += 1;
        if push(&mut out, PatchKind::Verify, d) {
            added += 1;
        }
    }
    Ok(out)
}

/// The kind of a patch given by its device values: black, white, a single-channel ramp step,
/// grey, or mixed.
pub fn classify(d: [f64; 3]) -> PatchKind {
    let lit: Vec<usize> = (0..3).filter(|&k| d[k] > 0.0).collect();
    match lit.as_slice() {
        [] => PatchKind::Black,
        [ch] => PatchKind::Ramp(*ch),
        _ if d[0] == d[1] && d[1] == d[2] && d[0] >= 1.0 => PatchKind::White,
        _ if d[0] == d[1] && d[1] == d[2] => PatchKind::Grey,
        _ => PatchKind::Mixed,
    }
}

/// A patch set read from a file (an ArgyllCMS `.ti1`, e.g. from `targen`): the patches in file
/// order, each classified by [`classify`] and all used by the fit. Fails on an empty set.
pub fn from_devices(devices: &[[f64; 3]]) -> Result<Vec<Patch>> {
    if devices.is_empty() {
        return Err(Error::EmptyPatchSet);
    }
    Ok(devices
        .iter()
        .map(|&device| Patch {
            kind: classify(device),
            device,
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_set() {
        let p = standard(9, 16).unwrap();
        assert_eq!(p.len(), 49);
        assert_eq!(p[0].device, [0.0; 3]);
        assert_eq!(p[1].device, [1.0; 3]);
        assert_eq!(p.iter().filter(|p| p.kind == PatchKind::Ramp(1)).count(), 8);
        assert_eq!(p.iter().filter(|p| p.kind == PatchKind::Verify).count(), 16);
        for q in &p {
            for v in q.device {
                assert_eq!((v * 255.0).round() / 255.0, v);
            }
        }
        assert_eq!(standard(2, 0).unwrap().len(), 5);
        assert!(standard(1, 0).is_err());
    }
}
