//! The few f32 functions on the firmware's hot path (transfer curves). [`pow_unit`] is this
//! crate's own (below); [`powf`] is `libm`'s. With the opt-in `fast-math` feature both are
//! `micromath`'s approximations instead (colour error measured in docs/performance.md).

/// `x^y` for `x ≥ 0`.
#[inline]
pub fn powf(x: f32, y: f32) -> f32 {
    #[cfg(feature = "fast-math")]
    {
        use micromath::F32Ext;
        if x <= 0.0 {
            return 0.0;
        }
        x.powf(y)
    }
    #[cfg(not(feature = "fast-math"))]
    {
        libm::powf(x, y)
    }
}

/// `x^p` for `x ∈ [0, 1]` and `p > 0`, the transfer curves' power (`x` is clamped to `[0, 1]`;
/// NaN reads as 0). Within 4 units in the last place of the exact result for
/// `0 < p ≤ 3`, `p/3` times that up to `p = 10` (the unit tests below, against f64 `powf`), in about 50 Cortex-M4 instructions
/// where libm's `powf` takes ≈ 235: the sRGB colour's six powers were most of its
/// instructions (docs/performance.md, "Issue 13").
///
/// `x^p = 2^(p·log₂ x)`. With `x = 2^k·m`, `m ∈ [√½, √2)` (the exponent field split off),
/// `ln m = 2 atanh s = 2(s + s³/3 + s⁵/5 + s⁷/7 + s⁹/9 + …)` for `s = (m − 1)/(m + 1)`,
/// `|s| ≤ 0.172`, where the first dropped term is below 2⁻³¹ of `ln m`. Then
/// `y = p·k + p·ln m / ln 2` (`p·k` in two exact-ish parts, so the error does not grow with
/// `|y|`), split `y = n + f` with `n` an integer and `|f| ≤ ½`, and `2^f = e^z`, `z = f ln 2`,
/// by its Taylor series to `z⁷/7!` (remainder below `3·10⁻⁹`); `2^n` goes into the exponent
/// field. A subnormal `x` is first scaled by `2²⁴`; a result below `2⁻¹²⁵` is made as
/// `e·2^(n+64)·2⁻⁶⁴` (one rounding); so no libm `powf` is linked (1.7 KiB of flash). Hand-written: no `no_std` crate offers a `powf` both
/// accurate to a few ulp and cheap on an FPU without double precision.
#[inline]
pub fn pow_unit(x: f32, p: f32) -> f32 {
    #[cfg(feature = "fast-math")]
    {
        powf(x.clamp(0.0, 1.0), p)
    }
    #[cfg(not(feature = "fast-math"))]
    {
        if !(x > 0.0) {
            return 0.0;
        }
        if x >= 1.0 {
            return 1.0;
        }
        // a subnormal x is scaled by 2²⁴ (exact) into the normal range
        let (bits, k0) = if x.to_bits() < 0x0080_0000 {
            ((x * 16_777_216.0).to_bits(), -24)
        } else {
            (x.to_bits(), 0)
        };
        // x = 2^k · m with m ∈ [√½, √2): the significand with the exponent field of 1, halved
        // above √2 (0x3fb504f3 is √2 rounded)
        let mut k = (bits >> 23) as i32 - 127 + k0;
        let mut m_bits = (bits & 0x007f_ffff) | 0x3f80_0000;
        if m_bits > 0x3fb5_04f3 {
            m_bits -= 0x0080_0000;
            k += 1;
        }
        let m = f32::from_bits(m_bits);
        let s = (m - 1.0) / (m + 1.0);
        let s2 = s * s;
        let atanh =
            s + s * s2 * (1.0 / 3.0 + s2 * (1.0 / 5.0 + s2 * (1.0 / 7.0 + s2 * (1.0 / 9.0))));
        let log2_m = atanh * (2.0 * core::f32::consts::LOG2_E); // in [−½, ½]
                                                                // y = p·k + p·log₂ m with p·k in two parts, p = hi + lo where hi keeps 12 bits, so
                                                                // hi·k (|k| ≤ 149) is exact and the rounding of y does not grow with |y|
        let hi = f32::from_bits(p.to_bits() & 0xffff_f000);
        let (a, b) = (hi * k as f32, (p - hi) * k as f32 + p * log2_m);
        let y = a + b;
        if !(y >= -125.0) {
            return exp2_tiny(a, b, y);
        }
        // y < 0: n = ⌈y − ½⌉ (truncation towards zero) and f = y − n ∈ [−½, ½], with a − n
        // exact (both multiples of hi's last bit, under 2 apart)
        let n = (y - 0.5) as i32;
        let e = exp_taylor(((a - n as f32) + b) * core::f32::consts::LN_2);
        // e ∈ [0.7, 1.42] and n ≥ −125: the result is normal
        f32::from_bits((e.to_bits() as i32 + (n << 23)) as u32)
    }
}

/// `e^z` for `|z| ≤ ½ ln 2` by its Taylor series to `z⁷/7!` ([`pow_unit`]).
#[inline(always)]
fn exp_taylor(z: f32) -> f32 {
    1.0 + z
        * (1.0
            + z * (1.0 / 2.0
                + z * (1.0 / 6.0
                    + z * (1.0 / 24.0
                        + z * (1.0 / 120.0 + z * (1.0 / 720.0 + z * (1.0 / 5040.0)))))))
}

/// [`pow_unit`]'s `2^y` for `y = a + b < −125` (or NaN): NaN stays, below `2⁻¹⁶⁰` it rounds to 0,
/// else `e · 2^(n+64)` is normal and its product with `2⁻⁶⁴` rounds once to the subnormal
/// result. Out of line: the curves' hot path keeps one compare.
#[cold]
#[inline(never)]
#[cfg_attr(feature = "fast-math", allow(dead_code))]
fn exp2_tiny(a: f32, b: f32, y: f32) -> f32 {
    if y.is_nan() {
        return y;
    }
    if y < -160.0 {
        return 0.0;
    }
    let n = (y - 0.5) as i32;
    let e = exp_taylor(((a - n as f32) + b) * core::f32::consts::LN_2);
    f32::from_bits((e.to_bits() as i32 + ((n + 64) << 23)) as u32) * f32::from_bits(0x1f80_0000)
}

#[cfg(all(test, not(feature = "fast-math")))]
mod tests {
    extern crate std;
    use super::*;

    /// The bound of [`pow_unit`] for `0 < p ≤ 3`, in units in the last place of the exact result.
    /// Measured over every f32 of `(0, 1]`: 1.61 for `p = 1/2.4` and 3.42 for `p = 2.4` (libm:
    /// 0.88); over every 7th, at most 3.58 for the gammas 1.8, 2.2, 2.6, 3 and their inverses.
    /// The error grows like `1 + p` ulp (the rounding of `p·log₂ m`): for the curves' gammas up to
    /// 10 the bound is `POW_UNIT_ULPS · p / 3` (measured 12.7 ulp, 7.6·10⁻⁷ relative, at `p = 10`).
    pub const POW_UNIT_ULPS: f64 = 4.0;

    /// The worst error of `pow_unit(·, p)` in ulp of the f64 power, over every `stride`-th f32
    /// of `(0, 1]`.
    fn worst_ulps(p: f32, stride: usize) -> (f64, f32) {
        let mut worst = (0.0, 0.0);
        for b in (1..=1.0f32.to_bits()).step_by(stride) {
            let x = f32::from_bits(b);
            let exact = (x as f64).powf(p as f64);
            let near = exact as f32;
            let ulp = (f32::from_bits(near.to_bits() + 1) - near) as f64;
            let e = (pow_unit(x, p) as f64 - exact).abs() / ulp;
            if e > worst.0 {
                worst = (e, x);
            }
        }
        worst
    }

    #[test]
    fn the_srgb_powers_are_within_the_bound_of_f64() {
        for p in [2.4, 1.0 / 2.4] {
            let (e, x) = worst_ulps(p, 61);
            assert!(e <= POW_UNIT_ULPS, "p = {p}: {e} ulp at {x:e}");
        }
    }

    #[test]
    fn the_gammas_are_within_the_bound_of_f64() {
        for g in [1.0f32, 1.8, 2.2, 2.6, 3.0, 5.0, 10.0] {
            for p in [g, 1.0 / g] {
                let (e, x) = worst_ulps(p, 1999);
                let bound = POW_UNIT_ULPS * (p as f64 / 3.0).max(1.0);
                assert!(e <= bound, "p = {p}: {e} ulp at {x:e}");
            }
        }
    }

    #[test]
    fn the_ends_and_the_extreme_ranges() {
        for p in [2.4, 1.0 / 2.4] {
            assert_eq!(pow_unit(0.0, p), 0.0);
            assert_eq!(pow_unit(-1.0, p), 0.0);
            assert_eq!(pow_unit(f32::NAN, p), 0.0);
            assert_eq!(pow_unit(1.0, p), 1.0);
            assert_eq!(pow_unit(7.0, p), 1.0);
        }
        // subnormal x (scaled into the normal range), and results below 2⁻¹²⁵ (subnormal or 0),
        // against the f64 power in ulps of the f32 grid there (2⁻¹⁴⁹ for subnormals)
        for p in [2.4f32, 1.0 / 2.4, 1.0, 3.0, 10.0] {
            let bound = POW_UNIT_ULPS * (p as f64 / 3.0).max(1.0);
            let xs = (1..0x0080_0000u32)
                .step_by(4099)
                .map(f32::from_bits)
                .chain((0..300).map(|i| 1e-25f32 * 1.2f32.powi(i)));
            for x in xs {
                let exact = (x as f64).powf(p as f64);
                let near = exact as f32;
                let ulp = (f32::from_bits(near.to_bits() + 1) - near) as f64;
                let e = (pow_unit(x, p) as f64 - exact).abs() / ulp;
                assert!(e <= bound, "p = {p}: {e} ulp at {x:e}");
            }
        }
        assert!(pow_unit(0.5, f32::NAN).is_nan());
    }
}
