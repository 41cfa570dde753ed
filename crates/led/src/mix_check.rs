//! Is a mix right? The controller's `ok mix` reply against an **independent f64 computation**
//! from the channels' measured spectra, within one table of tolerances ([`MIX_TOLERANCES`]).
//!
//! The controller knows each channel only as the f32 `X Y Z` the host uploaded and solves in
//! f32 with a tabulated Planckian locus (`specpoly_core::light::{channels, locus}`). The oracle
//! works from the spectra instead ([`Source`]: 1 nm sums of the SPD's linear interpolant against
//! the CIE 1931 observer):
//!
//! - the target: `xy` as sent, or a CCT/Duv through Planck's law at 1 nm and the exact locus
//!   normal ([`cct::cct_to_uv`]);
//! - the light the reply's fractions make, `Σ dᵢ·Sᵢ` ([`Source::mix`]), and the light its
//!   quantised duties make, each duty decoded through its curve's definition in f64;
//! - the most light at the target chromaticity and the least weighted drive at the asked
//!   luminance from the host's own mixer ([`solve_mix`], f64, written for the host's
//!   optimiser), for the luminance and the optimality of the device's choice.

use specpoly_core::light::{
    cct::{self, Cct},
    channels::{Curve, Goal},
    mix::{solve_mix, Objective, Target},
    Source,
};
use specpoly_protocol::{ChannelCommand, Command, MixReport};

/// One compared quantity's bound, with the reason for its size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MixTolerance {
    /// What is compared.
    pub quantity: MixQuantity,
    /// The bound.
    pub bound: f64,
    /// Why it is this large.
    pub why: &'static str,
}

/// The quantities of a mix reply.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MixQuantity {
    /// `xy=`: the device's target chromaticity, Δu′v′ to the exact one.
    Target,
    /// Δu′v′ of the light the reply's fractions make to the exact target.
    Chromaticity,
    /// Δu′v′ of the light the quantised duties make to the exact target.
    Quantised,
    /// `|Y / Y_max − L|`, the luminance of the fractions relative to the most at that
    /// chromaticity.
    Luminance,
    /// The weighted drive `Σ cᵢdᵢ` above the host's optimum, relative to `Σ cᵢ`.
    Drive,
}

/// The tolerance table. Measured worst cases (QEMU end-to-end test on `data/leds/` and a
/// random set) are in each reason and in docs/leds.md.
pub const MIX_TOLERANCES: [MixTolerance; 5] = [
    MixTolerance {
        quantity: MixQuantity::Target,
        bound: 3e-5,
        why: "the device's Planckian locus is a 25-node cubic Hermite table, within 2.4e-6 of \
              the 1 nm Planck integration, its normal within 2.8e-4 rad (2.1e-5 at |Duv| = \
              0.05; crates/core/src/light/locus.rs); f32 on top (a few 1e-8)",
    },
    MixTolerance {
        quantity: MixQuantity::Chromaticity,
        bound: 5e-4,
        why: "issue 15's bound before quantisation; the device's f32 vertex solve with f32 \
              channel XYZ reaches ~1e-6 plus the target's locus error",
    },
    MixTolerance {
        quantity: MixQuantity::Quantised,
        bound: 2e-4,
        why: "well inside a 1-step MacAdam ellipse (≈ 9e-4 in u′v′: ANSI C78.377's 7-step \
              circle of 0.006 / 7): 16-bit duties move a channel by ≤ 7.6e-6 of its full light",
    },
    MixTolerance {
        quantity: MixQuantity::Luminance,
        bound: 1e-4,
        why: "f32 vertex enumeration of the brightest mix against the host's f64 one",
    },
    MixTolerance {
        quantity: MixQuantity::Drive,
        bound: 1e-4,
        why: "both take a vertex of the same linear programme (f32 against f64); a tie between \
              vertices may pick another vertex of equal cost",
    },
];

/// The bound of `q`.
pub fn bound(q: MixQuantity) -> f64 {
    MIX_TOLERANCES
        .iter()
        .find(|t| t.quantity == q)
        .map_or(0.0, |t| t.bound)
}

/// What the freedom of a fourth to sixth channel is spent on (the weights uploaded).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Weight {
    /// Least total drive `Σ dᵢ` (weights 1).
    Power,
    /// Greatest luminous efficacy of radiation (weights: each channel's radiant power).
    Efficacy,
}

/// How close the device came (the largest deviations found).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MixAgreement {
    /// Δu′v′ of the target.
    pub target: f64,
    /// Δu′v′ before quantisation.
    pub chromaticity: f64,
    /// Δu′v′ after quantisation.
    pub quantised: f64,
    /// Luminance error.
    pub luminance: f64,
    /// Weighted drive above the optimum.
    pub drive: f64,
}

impl MixAgreement {
    /// The larger of each deviation.
    pub fn max(self, o: MixAgreement) -> MixAgreement {
        MixAgreement {
            target: self.target.max(o.target),
            chromaticity: self.chromaticity.max(o.chromaticity),
            quantised: self.quantised.max(o.quantised),
            luminance: self.luminance.max(o.luminance),
            drive: self.drive.max(o.drive),
        }
    }
}

/// The channels as the host knows them: spectra, curves, weights.
#[derive(Clone, Debug)]
pub struct MixOracle {
    sources: Vec<Source>,
    curves: Vec<Curve>,
    weight: Weight,
}

/// CIE 1976 u′v′ of CIE 1931 xy.
fn uv_prime(xy: [f64; 2]) -> [f64; 2] {
    let [u, v] = cct::xy_to_uv(xy);
    [u, 1.5 * v]
}

fn distance(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// A curve's decoding (device value → light) from its definition, in f64.
fn decode(c: Curve, v: f64) -> f64 {
    match c {
        Curve::Linear => v,
        Curve::Srgb if v <= 0.04045 => v / 12.92,
        Curve::Srgb => ((v + 0.055) / 1.055).powf(2.4),
        Curve::Gamma(g) => v.powf(g as f64),
    }
}

impl MixOracle {
    /// Channels from their spectra (3–6), each with its curve.
    pub fn new(sources: Vec<Source>, curves: Vec<Curve>, weight: Weight) -> Self {
        Self {
            sources,
            curves,
            weight,
        }
    }

    /// The `channel` commands that upload these channels: `X Y Z` relative to the brightest
    /// channel's `Y`, the weights relative to the largest, then each curve.
    pub fn commands(&self) -> Vec<Command> {
        let y_max = self.sources.iter().map(|s| s.xyz()[1]).fold(0.0, f64::max);
        let c_max = self
            .sources
            .iter()
            .map(|s| self.cost(s))
            .fold(0.0, f64::max);
        let mut out = vec![Command::Channel(ChannelCommand::Clear)];
        for (i, s) in self.sources.iter().enumerate() {
            out.push(Command::Channel(ChannelCommand::Set {
                index: i as u8,
                xyz: s.xyz().map(|v| (v / y_max) as f32),
                cost: (self.cost(s) / c_max) as f32,
            }));
        }
        for (i, c) in self.curves.iter().enumerate() {
            out.push(Command::Channel(ChannelCommand::Curve {
                index: i as u8,
                curve: *c,
            }));
        }
        out
    }

    fn cost(&self, s: &Source) -> f64 {
        match self.weight {
            Weight::Power => 1.0,
            Weight::Efficacy => s.radiant_sum(),
        }
    }

    fn objective(&self) -> Objective<'static> {
        match self.weight {
            Weight::Power => Objective::Power,
            Weight::Efficacy => Objective::Efficacy,
        }
    }

    /// The exact target chromaticity `(x, y)` of `goal`.
    pub fn target_xy(goal: &Goal) -> Option<[f64; 2]> {
        match *goal {
            Goal::Xy { xy, .. } => Some(xy.map(f64::from)),
            Goal::Cct { cct, duv, .. } => cct::cct_to_uv(Cct {
                cct: cct as f64,
                duv: duv as f64,
            })
            .ok()
            .map(cct::uv_to_xy),
        }
    }

    fn mix(&self, d: &[f64]) -> Result<Source, String> {
        let parts: Vec<(f64, &Source)> = d.iter().copied().zip(&self.sources).collect();
        Source::mix(&parts).map_err(|e| format!("the reply's mix: {e}"))
    }

    /// CIE 1976 `u′v′` and luminance `Y` (in the units of [`Source::xyz`]) of the light the
    /// duties (out of `max`) make, each decoded through its channel's curve.
    pub fn emitted(&self, duty: &[u16], max: u16) -> Result<([f64; 2], f64), String> {
        let decoded: Vec<f64> = duty
            .iter()
            .zip(&self.curves)
            .map(|(d, c)| decode(*c, *d as f64 / max as f64))
            .collect();
        let m = self.mix(&decoded)?;
        Ok((m.uv_prime(), m.xyz()[1]))
    }

    /// The most light (`Y`, units of [`Source::xyz`]) the channels give at CIE 1976 `u′v′`, by
    /// the host's f64 mixer; `None` outside their gamut.
    pub fn most_light_at(&self, uv: [f64; 2]) -> Option<f64> {
        let [u, v] = uv;
        let d = 6.0 * u - 16.0 * v + 12.0;
        let xy = [9.0 * u / d, 4.0 * v / d];
        let m = solve_mix(&self.sources, Target::Xy(xy), 1.0, Objective::Power).ok()?;
        Some(m.light.xyz()[1])
    }

    /// CIE 1976 `u′v′` of `goal`'s exact chromaticity.
    pub fn target_uv_prime(goal: &Goal) -> Option<[f64; 2]> {
        Self::target_xy(goal).map(uv_prime)
    }

    /// Whether the host's own f64 mixer finds `goal`'s chromaticity outside the channels'
    /// gamut.
    pub fn out_of_gamut(&self, goal: &Goal) -> bool {
        Self::target_xy(goal).is_some_and(|xy| {
            solve_mix(&self.sources, Target::Xy(xy), 1.0, Objective::Power).is_err()
        })
    }

    /// Checks a reply to `goal` ([`MIX_TOLERANCES`]); the deviations, or the first quantity out
    /// of bounds with both values.
    pub fn verify(&self, goal: &Goal, r: &MixReport) -> Result<MixAgreement, String> {
        let n = self.sources.len();
        if r.n as usize != n {
            return Err(format!("{} channels in the reply, {n} uploaded", r.n));
        }
        let xy = Self::target_xy(goal).ok_or("the target is outside its domain")?;
        let lum = match *goal {
            Goal::Xy { lum, .. } | Goal::Cct { lum, .. } => lum as f64,
        };
        let exact = uv_prime(xy);
        let check = |q: MixQuantity, v: f64, what: &str| -> Result<f64, String> {
            if v <= bound(q) && v.is_finite() {
                Ok(v)
            } else {
                Err(format!("{what}: {v:.3e} over {:.1e}", bound(q)))
            }
        };
        let mut a = MixAgreement {
            target: check(
                MixQuantity::Target,
                distance(uv_prime(r.xy.map(f64::from)), exact),
                "target chromaticity (Δu′v′)",
            )?,
            ..MixAgreement::default()
        };
        let light: Vec<f64> = r.light().iter().map(|v| *v as f64).collect();
        let brightest = solve_mix(&self.sources, Target::Xy(xy), 1.0, Objective::Power)
            .map_err(|e| format!("host: {e}"))?;
        let y_max = brightest.light.xyz()[1];
        if lum == 0.0 {
            if light.iter().any(|v| *v != 0.0) || r.duty().iter().any(|d| *d != 0) {
                return Err(format!("luminance 0 but light {light:?}"));
            }
            return Ok(a);
        }
        let made = self.mix(&light)?;
        a.chromaticity = check(
            MixQuantity::Chromaticity,
            distance(made.uv_prime(), exact),
            "chromaticity of the fractions (Δu′v′)",
        )?;
        a.luminance = check(
            MixQuantity::Luminance,
            (made.xyz()[1] / y_max - lum).abs(),
            "relative luminance",
        )?;
        a.quantised = check(
            MixQuantity::Quantised,
            distance(self.emitted(r.duty(), r.max)?.0, exact),
            "chromaticity of the quantised duties (Δu′v′)",
        )?;
        if n > 3 && lum < 1.0 {
            let best = solve_mix(&self.sources, Target::Xy(xy), lum, self.objective())
                .map_err(|e| format!("host: {e}"))?;
            let costs: Vec<f64> = self.sources.iter().map(|s| self.cost(s)).collect();
            let total: f64 = costs.iter().sum();
            let of = |d: &[f64]| d.iter().zip(&costs).map(|(d, c)| d * c).sum::<f64>();
            a.drive = check(
                MixQuantity::Drive,
                ((of(&light) - of(best.duties())) / total).max(0.0),
                "weighted drive above the host's optimum",
            )?;
        }
        Ok(a)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decoding_is_the_curves_definition() {
        assert_eq!(decode(Curve::Linear, 0.25), 0.25);
        assert!((decode(Curve::Gamma(2.0), 0.5) - 0.25).abs() < 1e-15);
        assert!((decode(Curve::Srgb, 0.5) - 0.214_041_140_482_232_5).abs() < 1e-12);
    }
}
