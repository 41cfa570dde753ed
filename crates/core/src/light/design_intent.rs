//! ANSI/IES TM-30-20 Annex E: recommended specification criteria for three design intents —
//! **Preference** (P), **Vividness** (V) and **Fidelity** (F) — each at priority levels 1
//! (highest) to 3, from Rf, Rg, the red bin's fidelity Rf,h1 and chroma shift Rcs,h1.
//!
//! | level | Rf | Rg | Rcs,h1 | Rf,h1 |
//! |---|---|---|---|---|
//! | P1 | ≥ 78 | ≥ 95 | −1 % to +15 % | |
//! | P2 | ≥ 75 | ≥ 92 | −7 % to +19 % | |
//! | P3 | ≥ 70 | ≥ 89 | −12 % to +23 % | |
//! | V1 | | ≥ 118 | ≥ +15 % | |
//! | V2 | | ≥ 110 | ≥ +6 % | |
//! | V3 | | ≥ 100 | ≥ 0 % | |
//! | F1 | ≥ 95 | | | |
//! | F2 | ≥ 90 | | | ≥ 90 |
//! | F3 | ≥ 85 | | | ≥ 85 |
//!
//! Source: luxpy 1.12.5 (K. A. G. Smet, a co-author of the TM-30 method),
//! `luxpy/color/cri/iestm30/metrics.py`, `_IES_TM30_ANNEX_E_TABLE` ("default as published";
//! unchanged since luxpy 1.6.8, 2021, which added it). Three rows agree with documents that
//! cite the Annex (read second-hand): the 2020 addendum to ANSI/ASHRAE/ICC/USGBC/IES 189.1
//! (§8.3.5.3) requires "IES-TM-30, Annex E, P2 and F3" as Rf ≥ 85, Rf,h1 ≥ 85, Rg ≥ 92,
//! Rcs,h1 −7 % to +19 %, and LEED v4.1's TM-30 option for interior lighting is P1 (Rf ≥ 78,
//! Rg ≥ 95, Rcs,h1 −1 % to 15 %). The V rows, F1 and F2 rest on luxpy alone: the Annex itself
//! is not held here (`docs/leds.md`).
//!
//! The rule, as luxpy applies it: a light is at level `k` of an intent when it meets the
//! criteria of level `k` **and of every lower level** (so F1 also needs Rf,h1 ≥ 90 through F2);
//! below level 3 it is `P-`, `V-`, `F-`. The figures are compared rounded to 0.01 (Rcs,h1 to
//! 0.01 %), as luxpy rounds them; limits are inclusive.

use super::tm30::Tm30;

/// A closed interval `[lo, hi]` (infinite ends for none).
type Range = (f64, f64);

const ANY: Range = (f64::NEG_INFINITY, f64::INFINITY);

/// The criteria of one priority level.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Criteria {
    /// Rf.
    pub rf: Range,
    /// Rg.
    pub rg: Range,
    /// Rcs,h1 as a fraction (0.15 = 15 %).
    pub rcs_h1: Range,
    /// Rf,h1.
    pub rf_h1: Range,
}

const fn at_least(v: f64) -> Range {
    (v, f64::INFINITY)
}

/// A design intent of Annex E.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Intent {
    /// Preference: pleasantness, naturalness, acceptability.
    Preference,
    /// Vividness: colour saturation.
    Vividness,
    /// Fidelity: closeness to the reference.
    Fidelity,
}

impl Intent {
    /// The three intents, in Annex E's order.
    pub const ALL: [Intent; 3] = [Intent::Preference, Intent::Vividness, Intent::Fidelity];

    /// The letter of the levels (`P`, `V`, `F`).
    pub fn letter(self) -> char {
        match self {
            Intent::Preference => 'P',
            Intent::Vividness => 'V',
            Intent::Fidelity => 'F',
        }
    }

    /// The name, lower case.
    pub fn name(self) -> &'static str {
        match self {
            Intent::Preference => "preference",
            Intent::Vividness => "vividness",
            Intent::Fidelity => "fidelity",
        }
    }

    /// The criteria of levels 1, 2 and 3 (the table in the module docs).
    pub fn criteria(self) -> [Criteria; 3] {
        match self {
            Intent::Preference => [
                Criteria {
                    rf: at_least(78.0),
                    rg: at_least(95.0),
                    rcs_h1: (-0.01, 0.15),
                    rf_h1: ANY,
                },
                Criteria {
                    rf: at_least(75.0),
                    rg: at_least(92.0),
                    rcs_h1: (-0.07, 0.19),
                    rf_h1: ANY,
                },
                Criteria {
                    rf: at_least(70.0),
                    rg: at_least(89.0),
                    rcs_h1: (-0.12, 0.23),
                    rf_h1: ANY,
                },
            ],
            Intent::Vividness => [
                Criteria {
                    rf: ANY,
                    rg: at_least(118.0),
                    rcs_h1: at_least(0.15),
                    rf_h1: ANY,
                },
                Criteria {
                    rf: ANY,
                    rg: at_least(110.0),
                    rcs_h1: at_least(0.06),
                    rf_h1: ANY,
                },
                Criteria {
                    rf: ANY,
                    rg: at_least(100.0),
                    rcs_h1: at_least(0.0),
                    rf_h1: ANY,
                },
            ],
            Intent::Fidelity => [
                Criteria {
                    rf: at_least(95.0),
                    rg: ANY,
                    rcs_h1: ANY,
                    rf_h1: ANY,
                },
                Criteria {
                    rf: at_least(90.0),
                    rg: ANY,
                    rcs_h1: ANY,
                    rf_h1: at_least(90.0),
                },
                Criteria {
                    rf: at_least(85.0),
                    rg: ANY,
                    rcs_h1: ANY,
                    rf_h1: at_least(85.0),
                },
            ],
        }
    }
}

/// The figures Annex E looks at.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Figures {
    /// Rf.
    pub rf: f64,
    /// Rg.
    pub rg: f64,
    /// Rcs,h1 as a fraction.
    pub rcs_h1: f64,
    /// Rf,h1.
    pub rf_h1: f64,
}

impl Figures {
    /// The figures of a TM-30 result.
    pub fn of(t: &Tm30) -> Self {
        Figures {
            rf: t.rf,
            rg: t.rg,
            rcs_h1: t.rcs_h[0],
            rf_h1: t.rf_h[0],
        }
    }

    /// Rounded as compared: Rf, Rg, Rf,h1 to 0.01; Rcs,h1 to 0.0001 (0.01 %).
    fn rounded(&self) -> Self {
        let r = |v: f64, k: f64| libm::round(v * k) / k;
        Figures {
            rf: r(self.rf, 100.0),
            rg: r(self.rg, 100.0),
            rcs_h1: r(self.rcs_h1, 10_000.0),
            rf_h1: r(self.rf_h1, 100.0),
        }
    }

    fn meet(&self, c: &Criteria) -> bool {
        let inside = |v: f64, (lo, hi): Range| v >= lo && v <= hi;
        inside(self.rf, c.rf)
            && inside(self.rg, c.rg)
            && inside(self.rcs_h1, c.rcs_h1)
            && inside(self.rf_h1, c.rf_h1)
    }

    /// The priority level (1–3) met for `intent`, `None` below level 3 (`P-`, `V-`, `F-`).
    pub fn level(&self, intent: Intent) -> Option<u8> {
        let f = self.rounded();
        let c = intent.criteria();
        let mut level = None;
        for k in (0..3).rev() {
            if !f.meet(&c[k]) {
                break;
            }
            level = Some(k as u8 + 1);
        }
        level
    }
}

/// The levels of the three intents, in [`Intent::ALL`]'s order.
pub fn design_intents(t: &Tm30) -> [Option<u8>; 3] {
    let f = Figures::of(t);
    Intent::ALL.map(|i| f.level(i))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fig(rf: f64, rg: f64, rcs_h1: f64, rf_h1: f64) -> Figures {
        Figures {
            rf,
            rg,
            rcs_h1,
            rf_h1,
        }
    }

    #[test]
    fn limits_are_inclusive_and_levels_nest() {
        let p = |f: Figures| f.level(Intent::Preference);
        assert_eq!(p(fig(78.0, 95.0, -0.01, 0.0)), Some(1));
        assert_eq!(p(fig(78.0, 95.0, 0.15, 0.0)), Some(1));
        assert_eq!(p(fig(77.996, 95.0, 0.15, 0.0)), Some(1)); // rounds to 78.00
        assert_eq!(p(fig(77.99, 95.0, 0.15, 0.0)), Some(2));
        assert_eq!(p(fig(78.0, 95.0, 0.1501, 0.0)), Some(2));
        assert_eq!(p(fig(69.0, 120.0, 0.0, 0.0)), None);
        // F1 also needs F2's Rf,h1 >= 90
        let f = |v: Figures| v.level(Intent::Fidelity);
        assert_eq!(f(fig(96.0, 100.0, 0.0, 95.0)), Some(1));
        assert_eq!(f(fig(96.0, 100.0, 0.0, 89.0)), Some(3));
        assert_eq!(f(fig(96.0, 100.0, 0.0, 84.0)), None);
        let v = |x: Figures| x.level(Intent::Vividness);
        assert_eq!(v(fig(60.0, 118.0, 0.15, 0.0)), Some(1));
        assert_eq!(v(fig(60.0, 117.99, 0.15, 0.0)), Some(2));
        assert_eq!(v(fig(60.0, 130.0, -0.001, 0.0)), None);
    }
}
