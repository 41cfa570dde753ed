//! Decimal numbers on the wire: a parser and a formatter for `f32` that need no `f64`.
//!
//! `core`'s own `str::parse::<f32>` carries ≈ 10 KiB of power-of-five tables and its float
//! `Display` several KiB more, and the Cortex-M4F has no double-precision FPU (soft `f64` made
//! a `refl` line cost 160 000 instructions): the protocol brings its own, in `f32` and integer
//! arithmetic only (docs/performance.md, "## Firmware").
//!
//! Grammar: `[+-]? digits? ('.' digits?)? ([eE] [+-]? digits)?` with at least one digit before
//! the exponent, at most [`MAX_NUMBER_LEN`] characters. `nan` and `inf` are not numbers here.
//! The compact form `0x` followed by exactly eight hexadecimal digits is the f32's IEEE 754
//! bit pattern (`0x3eaaaaab` is 1/3 rounded), exact by construction and a few instructions a
//! digit to read; patterns of NaN or infinity are out of range ([`write_f32_hex`] writes it).
//!
//! Parsing is correctly rounded (to nearest, ties to even) for up to 19 significant digits;
//! further digits count only as "something follows" (a sticky bit). With the decimal mantissa
//! `m` and exponent `e` (value `m · 10^e`): for `m ≤ 2²⁴` and `|e| ≤ 10` one f32 multiply or
//! divide of exact operands (Clinger 1990); for `m < 2³²` (up to nine digits, every number the
//! protocol writes) and `|e| ≤ 27` the top bits of a 32 × 64-bit product with `10^e`, when they
//! decide the rounding (Eisel–Lemire, [`short_decimal`]); otherwise an f32 estimate a few units
//! in the last place off, corrected by comparing `m · 10^e` exactly with the halfway points
//! between neighbouring floats.
//!
//! Formatting writes the shortest digits that read back as the same `f32` (the free-format
//! problem of Steele & White 1990, solved as Ryū does, Adams 2018): the rounding interval
//! scaled exactly to nine integer digits, then `v` rounded to 1, 2, … digits until inside it.
//! Plain decimals for `1e-5 ≤ |v| < 1e9`, `d.ddde±x` otherwise.
//!
//! The exact arithmetic is u128 products of a mantissa and `5^j` (`j ≤ 27`) and shifts, and
//! outside that range (below ≈ 10⁻¹⁹, above 10⁹) a 384-bit integer with 32-bit hardware
//! division only. Hand-written rather than the `ryu` crate: its f32 path links 10.7 KiB of
//! f64 tables (or, with `small`, u128 arithmetic at 1 800 instructions a number on the
//! Cortex-M4) and `memmove`, and it does not parse.

use core::cmp::Ordering;
use core::fmt::{self, Write};

/// Longest number token accepted.
pub const MAX_NUMBER_LEN: usize = 40;

/// Why a token is not a number.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NumberError {
    /// Not of the grammar above (or empty, or too long).
    Syntax,
    /// Overflows f32 (values that underflow read as 0; only overflow fails).
    Range,
}

/// `10^n` for `0 ≤ n ≤ 38`, rounded to f32 (exact up to `10^10`): the first estimate.
const POW10_F32: [f32; 39] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22, 1e23, 1e24, 1e25, 1e26, 1e27, 1e28, 1e29, 1e30, 1e31, 1e32,
    1e33, 1e34, 1e35, 1e36, 1e37, 1e38,
];

/// `10^n` for `0 ≤ n ≤ 9`.
const POW10_U32: [u32; 10] = [
    1,
    10,
    100,
    1_000,
    10_000,
    100_000,
    1_000_000,
    10_000_000,
    100_000_000,
    1_000_000_000,
];

/// `5^n` for `0 ≤ n ≤ 27` (exact in u64).
const fn pow5(n: u32) -> u64 {
    let mut r = 1u64;
    let mut i = 0;
    while i < n {
        r *= 5;
        i += 1;
    }
    r
}

/// `5^n` for `0 ≤ n ≤ 27`.
const POW5: [u64; 28] = {
    let mut t = [1u64; 28];
    let mut i = 1;
    while i < 28 {
        t[i] = pow5(i as u32);
        i += 1;
    }
    t
};

/// The least f32 bit pattern of overflow (`+inf`).
const INF_BITS: u32 = 0x7f80_0000;

/// Parses a decimal token into a finite `f32`, correctly rounded (see the module docs).
pub fn parse_f32(s: &str) -> Result<f32, NumberError> {
    let b = s.as_bytes();
    if b.is_empty() || b.len() > MAX_NUMBER_LEN {
        return Err(NumberError::Syntax);
    }
    if b.len() == 10 && b[0] == b'0' && b[1] == b'x' {
        return parse_hex(&b[2..]);
    }
    #[cfg(feature = "fast-refl")]
    if let Some((v, len)) = word_f32(b) {
        if len == b.len() {
            // the common token: a plain decimal whose digits fit a u32
            return Ok(v);
        }
    }
    let mut i = 0;
    let negative = match b[0] {
        b'-' => {
            i = 1;
            true
        }
        b'+' => {
            i = 1;
            false
        }
        _ => false,
    };
    #[cfg(not(feature = "fast-refl"))]
    if let Some((m, fraction)) = plain(&b[i..]) {
        // the common token: no exponent, the digits fit a u32
        let v = if m == 0 {
            0.0
        } else {
            decimal_to_f32(m as u64, -(fraction as i32), false).ok_or(NumberError::Range)?
        };
        return Ok(if negative { -v } else { v });
    }
    let mut mantissa: u64 = 0;
    let mut kept = 0u32; // significant digits kept in `mantissa`
    let mut sticky = false; // a non-zero digit was dropped after the 19th
    let mut exp10: i32 = 0; // decimal exponent correction from dropped or fractional digits
    let mut digits = 0u32;
    let mut fraction = false;
    while i < b.len() {
        let c = b[i];
        if c == b'.' && !fraction {
            fraction = true;
            i += 1;
            continue;
        }
        if !c.is_ascii_digit() {
            break;
        }
        let d = (c - b'0') as u64;
        if mantissa == 0 && d == 0 {
            // leading zero: no information
            if fraction {
                exp10 -= 1;
            }
        } else if kept < 19 {
            mantissa = mantissa * 10 + d;
            kept += 1;
            if fraction {
                exp10 -= 1;
            }
        } else {
            sticky |= d != 0;
            if !fraction {
                exp10 += 1;
            }
        }
        digits += 1;
        i += 1;
    }
    if digits == 0 {
        return Err(NumberError::Syntax);
    }
    if i < b.len() && (b[i] == b'e' || b[i] == b'E') {
        i += 1;
        let mut eneg = false;
        if i < b.len() && (b[i] == b'-' || b[i] == b'+') {
            eneg = b[i] == b'-';
            i += 1;
        }
        let start = i;
        let mut e: i32 = 0;
        while i < b.len() && b[i].is_ascii_digit() {
            // saturate: anything beyond ±10000 is over- or underflow anyway
            e = (e * 10 + (b[i] - b'0') as i32).min(10_000);
            i += 1;
        }
        if i == start {
            return Err(NumberError::Syntax);
        }
        exp10 = exp10.saturating_add(if eneg { -e } else { e });
    }
    if i != b.len() {
        return Err(NumberError::Syntax);
    }
    let v = if mantissa == 0 || exp10 + (kept as i32) < -46 {
        // below 10⁻⁴⁶, under half the least subnormal (1.4·10⁻⁴⁵)
        0.0
    } else if exp10 + kept as i32 > 39 {
        // at least 10³⁹ > f32::MAX
        return Err(NumberError::Range);
    } else {
        decimal_to_f32(mantissa, exp10, sticky).ok_or(NumberError::Range)?
    };
    Ok(if negative { -v } else { v })
}

/// Eight hexadecimal digits (either case) as an f32 bit pattern; NaN and infinity are
/// [`NumberError::Range`].
fn parse_hex(b: &[u8]) -> Result<f32, NumberError> {
    let mut bits = 0u32;
    for &c in b {
        // a digit, else a letter: `c | 0x20` is in `a..=f` exactly for `a..=f` and `A..=F`
        // (two compares a digit instead of three ranges)
        let mut d = c.wrapping_sub(b'0');
        if d > 9 {
            d = (c | 0x20).wrapping_sub(b'a');
            if d > 5 {
                return Err(NumberError::Syntax);
            }
            d += 10;
        }
        bits = bits << 4 | d as u32;
    }
    let v = f32::from_bits(bits);
    if v.is_finite() {
        Ok(v)
    } else {
        Err(NumberError::Range)
    }
}

/// Writes `v`'s bit pattern as `0x` and eight lower-case hexadecimal digits (the compact form of
/// the module docs; NaN and infinity are written too, and refused when read).
pub fn write_f32_hex<W: Write>(w: &mut W, v: f32) -> fmt::Result {
    let bits = v.to_bits();
    let mut out = [b'0'; 10];
    out[1] = b'x';
    for i in 0..8 {
        let d = (bits >> (28 - 4 * i)) as u8 & 0xf;
        out[2 + i] = if d < 10 { b'0' + d } else { b'a' + d - 10 };
    }
    // only ASCII was written
    w.write_str(core::str::from_utf8(&out).map_err(|_| fmt::Error)?)
}

/// Without feature `fast-refl` (the 32 KiB firmware build, for flash): [`parse_f32`]'s common
/// token, `digits ('.' digits?)?` or `'.' digits` (no sign, no exponent) whose digits read as one
/// u32 `m`: `(m, digits after the point)`, so the value is `m · 10^−fraction`. `None` for
/// anything else, which [`parse_f32`]'s general loop then reads (or refuses). A loop of a few
/// instructions a digit for the numbers the protocol itself writes.
#[cfg(not(feature = "fast-refl"))]
fn plain(b: &[u8]) -> Option<(u32, u32)> {
    // the integer digits, then (after a point) the fraction's: two loops, so a digit costs a
    // load, a compare, a bound and a multiply-add
    let mut m = 0u32;
    let mut i = 0;
    while i < b.len() {
        let d = b[i].wrapping_sub(b'0');
        if d >= 10 {
            break;
        }
        if m > (u32::MAX - 9) / 10 {
            return None;
        }
        m = m * 10 + d as u32;
        i += 1;
    }
    let int_digits = i;
    if i == b.len() {
        return if i > 0 { Some((m, 0)) } else { None };
    }
    if b[i] != b'.' {
        return None;
    }
    i += 1;
    let start = i;
    while i < b.len() {
        let d = b[i].wrapping_sub(b'0');
        if d >= 10 {
            return None;
        }
        if m > (u32::MAX - 9) / 10 {
            return None;
        }
        m = m * 10 + d as u32;
        i += 1;
    }
    let fraction = (i - start) as u32;
    if int_digits + fraction as usize == 0 {
        return None;
    }
    Some((m, fraction))
}

/// The number word at the start of `b`, found and read in one pass: `Some((value, length))`
/// when the word (the bytes up to the first ASCII whitespace or the end of `b`) is the compact
/// hex form of a finite f32, or a plain decimal `[+-]? (digits ('.' digits?)? | '.' digits)`
/// (no exponent) of at most 9 digits, read as one u32 `m`; the value is then
/// `±m · 10^−fraction` rounded by [`decimal_to_f32`] (correctly rounded, as every path of
/// [`parse_f32`], which calls this first). `None` for any other word, which [`parse_f32`]'s
/// general loop then reads (or refuses). Every number the protocol itself writes is such a
/// word, so a `refl` line's 64 coefficients cost a few instructions a byte: a load, a compare
/// and a multiply-add a digit, with no separate pass to split the line into words.
#[cfg(feature = "fast-refl")]
#[inline(always)]
pub(crate) fn word_f32(b: &[u8]) -> Option<(f32, usize)> {
    let ends = |i: usize| i == b.len() || b[i].is_ascii_whitespace();
    let (negative, mut i) = match b.first() {
        Some(b'-') => (true, 1),
        Some(b'+') => (false, 1),
        _ => (false, 0),
    };
    // the integer digits, then (after a point) the fraction's, at most 9 in all after a leading
    // zero (so `m < 10⁹` needs no overflow check: a 10th digit ends the loops and the word goes
    // to the general reader): a digit is a load, a compare and a multiply-add
    let first = i;
    let lead = (b.get(i) == Some(&b'0')) as usize;
    if lead == 1 && b.get(1) == Some(&b'x') && b.len() >= 10 && ends(10) {
        // `0x` and 8 hexadecimal digits (no sign: `i` is 0)
        return Some((parse_hex(&b[2..10]).ok()?, 10));
    }
    i += lead;
    let mut m = 0u32;
    let mut stop = b.len().min(i + 9);
    while i < stop {
        let d = (b[i] as u32).wrapping_sub(b'0' as u32);
        if d >= 10 {
            break;
        }
        m = m * 10 + d;
        i += 1;
    }
    let mut digits = i - first;
    let mut fraction = 0;
    if i < b.len() && b[i] == b'.' {
        i += 1;
        let start = i;
        stop = b.len().min(start + 9 + lead - digits);
        while i < stop {
            let d = (b[i] as u32).wrapping_sub(b'0' as u32);
            if d >= 10 {
                break;
            }
            m = m * 10 + d;
            i += 1;
        }
        fraction = i - start;
        digits += fraction;
    }
    if digits == 0 || !ends(i) {
        return None;
    }
    let v = if m == 0 {
        0.0
    } else if m <= 1 << 24 && fraction <= 10 {
        // `decimal_to_f32`'s first case (Clinger: both operands exact, one rounding), here
        // without the call
        m as f32 / POW10_F32[fraction]
    } else if let Some(v) = short_decimal(m, -(fraction as i32)) {
        // its second (`fraction ≤ 9 < 27`), also without the call
        v
    } else {
        decimal_to_f32(m as u64, -(fraction as i32), false)?
    };
    Some((if negative { -v } else { v }, i))
}

/// `m · 10^e` (plus a little when `sticky`) as the nearest f32, `None` on overflow; `m > 0`,
/// `−65 ≤ e ≤ 38`.
fn decimal_to_f32(m: u64, e: i32, sticky: bool) -> Option<f32> {
    if !sticky && m <= 1 << 24 && (-10..=10).contains(&e) {
        // both operands exact: one correctly rounded operation (Clinger 1990); from u32, one
        // `vcvt` (u64 → f32 is a library call on 32-bit targets)
        let v = m as u32 as f32;
        return Some(if e >= 0 {
            v * POW10_F32[e as usize]
        } else {
            v / POW10_F32[(-e) as usize]
        });
    }
    if !sticky && m <= u32::MAX as u64 && (-POW10_MAX..=POW10_MAX).contains(&e) {
        if let Some(v) = short_decimal(m as u32, e) {
            return Some(v);
        }
    }
    // an estimate within a few units in the last place, then corrected exactly
    let v = m as f32;
    let estimate = if e >= 0 {
        v * POW10_F32[e as usize]
    } else if e >= -38 {
        v / POW10_F32[(-e) as usize]
    } else {
        v / POW10_F32[38] / POW10_F32[(-e - 38) as usize]
    };
    let mut c = estimate.to_bits().min(INF_BITS - 1);
    // x against the halfway point between patterns c and c + 1 (`halfway = h · 2^g`), with the
    // power of five on whichever side keeps the scaling a product (no division)
    let above = |c: u32| -> Ordering {
        let (h, g) = halfway(c);
        let o = if e >= 0 {
            let (floor, fraction) = scale(m, e, -g);
            floor.cmp(&h).then(if fraction {
                Ordering::Greater
            } else {
                Ordering::Equal
            })
        } else {
            let (floor, fraction) = scale(h, -e, g);
            m.cmp(&floor).then(if fraction {
                Ordering::Less
            } else {
                Ordering::Equal
            })
        };
        match o {
            Ordering::Equal if sticky => Ordering::Greater,
            o => o,
        }
    };
    loop {
        if above(c) == Ordering::Greater {
            c += 1;
            if c == INF_BITS {
                return None;
            }
        } else if c > 0 && above(c - 1) != Ordering::Greater {
            c -= 1;
        } else {
            break;
        }
    }
    // halfway(c − 1) < x ≤ halfway(c): a tie goes to the even pattern
    if c & 1 == 1 && above(c) == Ordering::Equal {
        c += 1;
        if c == INF_BITS {
            return None;
        }
    }
    Some(f32::from_bits(c))
}

/// Largest `|e|` of [`POW10_NORM`].
const POW10_MAX: i32 = 27;

/// `10^e` for `−27 ≤ e ≤ 27` as `t ∈ [2⁶³, 2⁶⁴)` with `10^e = (t + δ) · 2^b`, `0 ≤ δ < 1`,
/// `b = ⌊e·log₂ 10⌋ − 63` ([`pow10_exp2`], checked against the construction at compile time):
/// exact (`δ = 0`) for `e ≥ 0` (`10^e = 5^e · 2^e`, `5²⁷ < 2⁶³`), the floor of
/// `2^(63 + bitlen 5^n) / 5^n` for `e = −n`. 440 bytes of flash.
const POW10_NORM: [u64; 55] = {
    let mut t = [0u64; 55];
    let mut i = 0;
    while i < 55 {
        let e = i as i32 - POW10_MAX;
        let n = e.unsigned_abs();
        let five = pow5(n) as u128;
        if e >= 0 {
            // 10^e = 5^e · 2^e: normalise 5^e to 64 bits, nothing is lost
            let bits = 128 - five.leading_zeros() as i32;
            t[i] = (five << (64 - bits)) as u64;
            assert!(pow10_exp2(e) == e + bits - 64);
        } else {
            // 10^−n = 2^−n / 5^n = ⌊2^k / 5^n⌋ · 2^(−k−n), k = 63 + bitlen(5^n)
            let k = 63 + (128 - five.leading_zeros() as i32);
            t[i] = ((1u128 << k) / five) as u64;
            assert!(pow10_exp2(e) == -k - n as i32);
        }
        i += 1;
    }
    t
};

/// `⌊e·log₂ 10⌋ − 63`, the binary exponent of [`POW10_NORM`]'s entry for `e` (`217 706 / 2¹⁶`
/// is `log₂ 10` to well within what `|e| ≤ 27` needs).
const fn pow10_exp2(e: i32) -> i32 {
    ((e * 217_706) >> 16) - 63
}

/// `m · 10^e` for `m < 2³²`, `|e| ≤ 27`, correctly rounded to a normal f32, or `None` when
/// the fast computation cannot decide (then the exact path in [`decimal_to_f32`] does).
///
/// The idea of Eisel–Lemire (Lemire 2021, "Number parsing at a gigabyte per second"), cut to
/// f32 and 32 × 64-bit products (two `umull` on the Cortex-M4): with `m` normalised to
/// `m' ∈ [2³¹, 2³²)` and `10^e = (t + δ) · 2^b` ([`POW10_NORM`]), the exact product
/// `m' · (t + δ)` lies in `[P, P + 2³²)` for `P = m' · t`, so its top 64 bits `q` are known to
/// within 2 units. The top 24 bits of `q` are the significand; the bits below decide the
/// rounding unless they are within 2 units of the halfway point (a tie or too close to
/// call), which falls back. The answer is then the same as the exact path's.
fn short_decimal(m: u32, e: i32) -> Option<f32> {
    if m == 0 {
        return Some(0.0);
    }
    let (t, b) = (POW10_NORM[(e + POW10_MAX) as usize], pow10_exp2(e));
    let lz = m.leading_zeros();
    let m = (m << lz) as u64;
    // q = ⌊m · t / 2³²⌋ ∈ [2⁶², 2⁶⁴)
    let q = m * (t >> 32) + ((m * (t & 0xffff_ffff)) >> 32);
    // constant shifts (a variable u64 shift is a library call on the Cortex-M4)
    let (sh, mant, rest, half) = if q >> 63 == 1 {
        (40, (q >> 40) as u32, q & ((1 << 40) - 1), 1u64 << 39)
    } else {
        (39, (q >> 39) as u32, q & ((1 << 39) - 1), 1u64 << 38)
    };
    // mant ∈ [2²³, 2²⁴)
    let up = if rest + 2 <= half {
        false
    } else if rest > half {
        true
    } else {
        return None;
    };
    // value = mant · 2^(sh + 32 + b − lz); the biased exponent of mant · 2^x is x + 150
    let field = sh + 32 + b - lz as i32 + 150;
    if !(1..254).contains(&field) {
        return None; // subnormal, or near overflow: the exact path
    }
    // a carry out of the significand moves into the exponent field, as it should
    let bits = ((field as u32) << 23) + (mant - (1 << 23)) + up as u32;
    Some(f32::from_bits(bits))
}

/// The value of the positive f32 with bit pattern `c` (`c ≤ 0x7f80_0000`, which reads as
/// `2^128`) as `a · 2^e`.
fn float_parts(c: u32) -> (u64, i32) {
    let (exp, frac) = (c >> 23, c & 0x7f_ffff);
    if exp == 0 {
        (frac as u64, -149)
    } else {
        ((frac | 1 << 23) as u64, exp as i32 - 150)
    }
}

/// The halfway point between the positive f32 patterns `c` and `c + 1` as `h · 2^g`.
fn halfway(c: u32) -> (u64, i32) {
    let (a, ea) = float_parts(c);
    let (b, eb) = float_parts(c + 1);
    (a + (b << (eb - ea) as u32), ea - 1)
}

/// `n · 10^j · 2^k` as (its floor, whether a fraction is left), the floor saturated at
/// `u64::MAX` (then the fraction is reported too). Exact: u128 for `0 ≤ j ≤ 27`, else [`Big`].
fn scale(n: u64, j: i32, k: i32) -> (u64, bool) {
    if (0..=27).contains(&j) {
        let f = POW5[j as usize];
        let s = j + k;
        // in u64 when the product fits (⌈log₂ 5^j⌉ ≤ (149j + 63)/64)
        if (64 - n.leading_zeros() as i32) + ((149 * j + 63) >> 6) <= 64 {
            let p = n * f;
            if s >= 0 {
                if (64 - p.leading_zeros() as i32) + s > 64 {
                    return (u64::MAX, true);
                }
                return (p << s, false);
            }
            let sh = (-s) as u32;
            if sh >= 64 {
                return (0, p != 0);
            }
            return (p >> sh, p & ((1u64 << sh) - 1) != 0);
        }
        let p = n as u128 * f as u128; // < 2^127
        if s >= 0 {
            if 128 - p.leading_zeros() as i32 + s > 64 {
                return (u64::MAX, true);
            }
            return ((p << s) as u64, false);
        }
        let sh = (-s) as u32;
        if sh >= 128 {
            return (0, p != 0);
        }
        let q = p >> sh;
        if q > u64::MAX as u128 {
            return (u64::MAX, true);
        }
        return (q as u64, p & ((1u128 << sh) - 1) != 0);
    }
    let mut b = Big::from_u64(n);
    let mut fraction = false;
    let s = if j >= 0 {
        b.mul_pow5(j as u32);
        j + k
    } else {
        // n · 2^(j+k) / 5^|j|: shift left first, so the division keeps every bit
        let s = j + k;
        if s > 0 {
            if b.bit_len() as i32 + s > Big::BITS {
                return (u64::MAX, true);
            }
            b.shl(s as u32);
        }
        let mut five = (-j) as u32;
        while five > 0 {
            let f = five.min(6); // 5^6 < 2^16
            fraction |= b.div_small(POW5[f as usize] as u32);
            five -= f;
        }
        s.min(0)
    };
    if s > 0 {
        if b.bit_len() as i32 + s > 64 {
            return (u64::MAX, true);
        }
        b.shl(s as u32);
    } else if s < 0 {
        fraction |= b.shr((-s) as u32);
    }
    if b.bit_len() > 64 {
        return (u64::MAX, true);
    }
    (b.w[0] as u64 | (b.w[1] as u64) << 32, fraction)
}

/// A small unsigned integer of 12 × 32 bits (little-endian words) for [`scale`] outside u128's
/// reach: at most a 64-bit mantissa times `5^65 < 2^151`, shifted by up to 133 bits.
#[derive(Clone, Copy)]
struct Big {
    w: [u32; 12],
}

impl Big {
    const BITS: i32 = 12 * 32;

    fn from_u64(v: u64) -> Self {
        let mut w = [0u32; 12];
        w[0] = v as u32;
        w[1] = (v >> 32) as u32;
        Big { w }
    }

    fn mul_pow5(&mut self, mut n: u32) {
        while n > 0 {
            let k = n.min(13); // 5^13 < 2^32
            let f = POW5[k as usize];
            let mut carry = 0u64;
            for x in self.w.iter_mut() {
                let p = *x as u64 * f + carry;
                *x = p as u32;
                carry = p >> 32;
            }
            n -= k;
        }
    }

    /// Divides by `d < 2^16` (in 16-bit steps: 32-bit hardware division only); returns whether
    /// a remainder was left.
    fn div_small(&mut self, d: u32) -> bool {
        let mut r = 0u32;
        for x in self.w.iter_mut().rev() {
            let hi = (r << 16) | (*x >> 16);
            let (qh, rh) = (hi / d, hi % d);
            let lo = (rh << 16) | (*x & 0xffff);
            let (ql, rl) = (lo / d, lo % d);
            *x = (qh << 16) | ql;
            r = rl;
        }
        r != 0
    }

    fn bit_len(&self) -> u32 {
        for i in (0..self.w.len()).rev() {
            if self.w[i] != 0 {
                return 32 * i as u32 + 32 - self.w[i].leading_zeros();
            }
        }
        0
    }

    fn shl(&mut self, n: u32) {
        let (words, bits) = ((n / 32) as usize, n % 32);
        for i in (0..self.w.len()).rev() {
            let lo = if i >= words { self.w[i - words] } else { 0 };
            let below = if i > words { self.w[i - words - 1] } else { 0 };
            self.w[i] = if bits == 0 {
                lo
            } else {
                (lo << bits) | (below >> (32 - bits))
            };
        }
    }

    /// Shifts right by `n`; returns whether a one was shifted out.
    fn shr(&mut self, n: u32) -> bool {
        let (words, bits) = ((n / 32) as usize, n % 32);
        let len = self.w.len();
        let mut lost = false;
        for i in 0..len {
            if i < words.min(len) {
                lost |= self.w[i] != 0;
            } else if i == words && bits > 0 {
                lost |= self.w[i] & ((1 << bits) - 1) != 0;
            }
        }
        for i in 0..len {
            let src = i + words;
            let lo = if src < len { self.w[src] } else { 0 };
            let above = if src + 1 < len { self.w[src + 1] } else { 0 };
            self.w[i] = if bits == 0 {
                lo
            } else {
                (lo >> bits) | (above << (32 - bits))
            };
        }
        lost
    }
}

/// Writes `v` with the shortest digits that [`parse_f32`] (and any correct reader) reads back
/// as the same f32, trailing zeros dropped: plain decimals for `1e-5 ≤ |v| < 1e9`, else
/// `d.ddde±x`. Non-finite values are written `nan`, `inf`, `-inf` (which [`parse_f32`]
/// rejects).
pub fn write_f32<W: Write>(w: &mut W, v: f32) -> fmt::Result {
    if v.is_nan() {
        return w.write_str("nan");
    }
    if v.is_infinite() {
        return w.write_str(if v > 0.0 { "inf" } else { "-inf" });
    }
    let mut out = Small::default();
    if v.is_sign_negative() {
        out.push(b'-');
    }
    if v == 0.0 {
        out.push(b'0');
        return w.write_str(out.as_str());
    }
    let (value, count, e) = shortest(v.abs().to_bits());
    let mut digits = [0u8; 9];
    let mut x = value;
    for d in digits[..count].iter_mut().rev() {
        *d = b'0' + (x % 10) as u8;
        x /= 10;
    }
    let mut n = count;
    while n > 1 && digits[n - 1] == b'0' {
        n -= 1;
    }
    layout(&mut out, &digits[..n], e);
    w.write_str(out.as_str())
}

/// The shortest decimal in the rounding interval of the positive finite f32 with pattern
/// `bits`: `(digits, how many, e)` for `d.ddd · 10^e`. The interval `[v − ½ulp⁻, v + ½ulp]`
/// (closed for an even mantissa, which ties read back to) and `v` are scaled by `10^(8−E)`
/// exactly ([`scale`]), so `v` has 9 integer digits; then the candidates `v` rounded to 1, 2,
/// … digits are tried in turn (Steele & White 1990's free-format problem, as Ryū solves it).
fn shortest(bits: u32) -> (u32, usize, i32) {
    let (a, ea) = float_parts(bits);
    // at a power of two (not the least normal) the gap below is half the gap above
    let delta_lo = if bits & 0x7f_ffff == 0 && bits >> 23 > 1 {
        1
    } else {
        2
    };
    let log2 = ea + 63 - a.leading_zeros() as i32; // ⌊log₂ v⌋
    let mut e = (log2 * 78_913) >> 18; // ⌊log₁₀ 2^log2⌋: ⌊log₁₀ v⌋ or one less
    let j = 8 - e;
    let (mut mid, mut mid_f) = scale(4 * a, j, ea - 2);
    let (mut lo, mut lo_f) = scale(4 * a - delta_lo, j, ea - 2);
    let (mut hi, mut hi_f) = scale(4 * a + 2, j, ea - 2);
    if mid >= 1_000_000_000 {
        e += 1;
        for (x, f) in [
            (&mut mid, &mut mid_f),
            (&mut lo, &mut lo_f),
            (&mut hi, &mut hi_f),
        ] {
            *f |= *x % 10 != 0;
            *x /= 10;
        }
    }
    let closed = a % 2 == 0;
    let inside = |c: u64| {
        let above_lo = c > lo || (c == lo && !lo_f && closed);
        let below_hi = c < hi || (c == hi && (hi_f || closed));
        above_lo && below_hi
    };
    let mid = mid as u32; // 10^8 ≤ mid < 10^9
    for count in 1..=9usize {
        let step = POW10_U32[9 - count];
        let (q, r) = (mid / step, mid % step);
        // to nearest; a tie (no fraction left) to even
        let twice = 2 * r as u64;
        let up = twice > step as u64 || (twice == step as u64 && (mid_f || q % 2 == 1));
        let q = q + up as u32;
        if inside(q as u64 * step as u64) || count == 9 {
            // rounding up may carry into another digit: 10^count is 1 · 10^(e+1)
            if q == POW10_U32[count] {
                return (1, 1, e + 1);
            }
            return (q, count, e);
        }
    }
    (mid, 9, e)
}

/// A 24-byte buffer for one formatted number.
#[derive(Default)]
struct Small {
    b: [u8; 24],
    len: usize,
}

impl Small {
    fn as_str(&self) -> &str {
        // only ASCII is written
        core::str::from_utf8(&self.b[..self.len]).unwrap_or("")
    }

    fn push(&mut self, c: u8) {
        if self.len < self.b.len() {
            self.b[self.len] = c;
            self.len += 1;
        }
    }

    fn put(&mut self, d: &[u8]) {
        for c in d {
            self.push(*c);
        }
    }
}

impl Write for Small {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        self.put(s.as_bytes());
        Ok(())
    }
}

/// Significant `digits` (1 to 9, no trailing zeros) of `d.ddd · 10^e` in the protocol's
/// layout (at most 16 bytes).
fn layout(w: &mut Small, digits: &[u8], e: i32) {
    if (0..9).contains(&e) {
        let int = e as usize + 1;
        if digits.len() <= int {
            w.put(digits);
            for _ in digits.len()..int {
                w.push(b'0');
            }
        } else {
            w.put(&digits[..int]);
            w.push(b'.');
            w.put(&digits[int..]);
        }
    } else if (-5..0).contains(&e) {
        w.push(b'0');
        w.push(b'.');
        for _ in 0..(-e - 1) {
            w.push(b'0');
        }
        w.put(digits);
    } else {
        w.put(&digits[..1]);
        if digits.len() > 1 {
            w.push(b'.');
            w.put(&digits[1..]);
        }
        w.push(b'e');
        let _ = write_int(w, e as i64);
    }
}

/// Writes a signed integer in decimal (no `core::fmt` integer machinery needed).
pub fn write_int<W: Write>(w: &mut W, v: i64) -> fmt::Result {
    if v < 0 {
        w.write_char('-')?;
    }
    // u32 arithmetic: the protocol's integers (duties, positions, exponents) are small, and
    // 64-bit division costs the firmware 1 KiB of flash
    let mut u = v.unsigned_abs().min(u32::MAX as u64) as u32;
    let mut buf = [0u8; 10];
    let mut n = 0;
    loop {
        buf[n] = b'0' + (u % 10) as u8;
        u /= 10;
        n += 1;
        if u == 0 {
            break;
        }
    }
    for c in buf[..n].iter().rev() {
        w.write_char(*c as char)?;
    }
    Ok(())
}

/// Parses an unsigned decimal integer that fits `u16`.
pub fn parse_u16(s: &str) -> Option<u16> {
    if s.is_empty() || s.len() > 5 || !s.bytes().all(|c| c.is_ascii_digit()) {
        return None;
    }
    let mut v: u32 = 0;
    for c in s.bytes() {
        v = v * 10 + (c - b'0') as u32;
    }
    u16::try_from(v).ok()
}

/// Writes ` KEY=v1,v2,…`, each value as [`write_f32`] does.
pub(crate) fn write_f32_list<W: Write>(w: &mut W, key: &str, v: &[f32]) -> fmt::Result {
    write_list(w, key, v, |w, x| write_f32(w, *x))
}

/// Writes ` KEY=n1,n2,…`, each value as [`write_f32_hex`] does.
pub(crate) fn write_f32_hex_list<W: Write>(w: &mut W, key: &str, v: &[f32]) -> fmt::Result {
    write_list(w, key, v, |w, x| write_f32_hex(w, *x))
}

/// Writes ` KEY=n1,n2,…`, each value as [`write_int`] does.
pub(crate) fn write_int_list<W: Write>(w: &mut W, key: &str, v: &[u16]) -> fmt::Result {
    write_list(w, key, v, |w, n| write_int(w, *n as i64))
}

fn write_list<W: Write, T>(
    w: &mut W,
    key: &str,
    v: &[T],
    mut item: impl FnMut(&mut W, &T) -> fmt::Result,
) -> fmt::Result {
    w.write_char(' ')?;
    w.write_str(key)?;
    w.write_char('=')?;
    for (i, x) in v.iter().enumerate() {
        if i > 0 {
            w.write_char(',')?;
        }
        item(w, x)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::string::String;

    fn fmt(v: f32) -> String {
        let mut s = String::new();
        write_f32(&mut s, v).unwrap();
        s
    }

    #[test]
    fn parses_the_grammar() {
        assert_eq!(parse_f32("0"), Ok(0.0));
        assert_eq!(parse_f32("-1.5"), Ok(-1.5));
        assert_eq!(parse_f32("+.25"), Ok(0.25));
        assert_eq!(parse_f32("3."), Ok(3.0));
        assert_eq!(parse_f32("1e3"), Ok(1000.0));
        assert_eq!(parse_f32("2.5E-3"), Ok(0.0025));
        assert_eq!(parse_f32("0.1"), Ok(0.1));
        assert_eq!(parse_f32("95.047"), Ok(95.047));
        assert_eq!(parse_f32("1e-60"), Ok(0.0));
        for bad in [
            "", ".", "-", "e3", "1e", "1.2.3", "nan", "inf", "0x10", "1 ", "--1",
        ] {
            assert_eq!(parse_f32(bad), Err(NumberError::Syntax), "{bad:?}");
        }
        assert_eq!(parse_f32("1e39"), Err(NumberError::Range));
        assert_eq!(parse_f32("-4e38"), Err(NumberError::Range));
    }

    #[test]
    fn formats_readably() {
        assert_eq!(fmt(0.0), "0");
        assert_eq!(fmt(1.0), "1");
        assert_eq!(fmt(-2.5), "-2.5");
        assert_eq!(fmt(100.0), "100");
        assert_eq!(fmt(0.1), "0.1");
        assert_eq!(fmt(1.0 / 3.0), "0.33333334");
        assert_eq!(fmt(0.5), "0.5");
        assert_eq!(fmt(0.00125), "0.00125");
        assert_eq!(fmt(1.5e-7), "1.5e-7");
        assert_eq!(fmt(3.0e20), "3e20");
        assert_eq!(fmt(65535.0), "65535");
        assert_eq!(fmt(f32::NAN), "nan");
    }

    #[test]
    fn rounds_halfway_cases_to_even_and_reads_subnormals() {
        // 2^24 + 1 is halfway between 2^24 and 2^24 + 2: ties to the even mantissa
        assert_eq!(parse_f32("16777217"), Ok(16_777_216.0));
        assert_eq!(parse_f32("16777219"), Ok(16_777_220.0));
        // a hair above halfway (digits past the 19th count)
        assert_eq!(parse_f32("16777217.00000000000000000001"), Ok(16_777_218.0));
        assert_eq!(parse_f32("1.4e-45"), Ok(f32::from_bits(1)));
        assert_eq!(parse_f32("7.1e-46"), Ok(f32::from_bits(1)));
        assert_eq!(parse_f32("7e-46"), Ok(0.0));
        assert_eq!(parse_f32("7e-47"), Ok(0.0));
        assert_eq!(parse_f32("3.4028235e38"), Ok(f32::MAX));
        assert_eq!(parse_f32("3.40282356e38"), Ok(f32::MAX));
        assert_eq!(parse_f32("3.40282357e38"), Err(NumberError::Range));
        assert_eq!(parse_f32("-0"), Ok(-0.0));
        assert_eq!(
            parse_f32("0.00000000000000000000000000000000000001"),
            Ok(1e-38)
        );
    }

    #[test]
    fn agrees_with_std_parse() {
        for s in [
            "0.123456789",
            "95.047",
            "108.883",
            "1.17549435e-38",
            "3.40282347e38",
            "7e-45",
            "1.17549421e-38",
            "0.1234567890123456789",
            "123456789012345678901234567890",
            "9.99999999999999999999e-40",
            "0.33333334",
            "2.5e-7",
            "1.23456789e-20",
        ] {
            assert_eq!(parse_f32(s).unwrap(), s.parse::<f32>().unwrap(), "{s}");
        }
    }

    #[test]
    fn the_hex_form_is_the_bit_pattern() {
        assert_eq!(parse_f32("0x3eaaaaab"), Ok(1.0 / 3.0));
        assert_eq!(parse_f32("0x3EAAAAAB"), Ok(1.0 / 3.0));
        assert_eq!(parse_f32("0x80000000").map(f32::to_bits), Ok(0x8000_0000));
        assert_eq!(parse_f32("0x00000001"), Ok(f32::from_bits(1)));
        assert_eq!(parse_f32("0x7f800000"), Err(NumberError::Range));
        assert_eq!(parse_f32("0x7fc00000"), Err(NumberError::Range));
        for bad in [
            "0x3eaaaaag",
            "0x3eaaaaa",
            "0x3eaaaaab0",
            "-0x3eaaaaab",
            "0X3eaaaaab",
        ] {
            assert_eq!(parse_f32(bad), Err(NumberError::Syntax), "{bad:?}");
        }
        let mut s = String::new();
        write_f32_hex(&mut s, 1.0 / 3.0).unwrap();
        assert_eq!(s, "0x3eaaaaab");
        // every byte in every digit position: exactly the hexadecimal digits are read, with
        // their value (std's `char::to_digit(16)` as the oracle)
        for pos in 2..10 {
            for c in 0..=255u8 {
                let mut b = *b"0x3f000000";
                b[pos] = c;
                let want = char::from(c)
                    .to_digit(16)
                    .map(|d| (0x3f00_0000u32 & !(0xf << (4 * (9 - pos)))) | d << (4 * (9 - pos)))
                    .map(f32::from_bits)
                    .filter(|v| v.is_finite());
                match (parse_hex(&b[2..]), want) {
                    (Ok(v), Some(w)) => assert_eq!(v.to_bits(), w.to_bits(), "{pos} {c}"),
                    (Err(NumberError::Range), None) => assert!(char::from(c).is_ascii_hexdigit()),
                    (Err(NumberError::Syntax), None) => {
                        assert!(!char::from(c).is_ascii_hexdigit(), "{pos} {c}")
                    }
                    (got, want) => panic!("{pos} {c}: {got:?}, want {want:?}"),
                }
            }
        }
    }

    #[test]
    fn the_short_path_matches_std_on_a_dense_sweep_of_nine_digits() {
        // 9 and 10 decimals below 1 as the protocol writes them, every 997th mantissa:
        // 2 million reads
        for zeros in ["", "0"] {
            for m in (1u32..1_000_000_000).step_by(997) {
                let s = std::format!("0.{zeros}{m:09}");
                let std_v: f32 = s.parse().unwrap();
                assert_eq!(parse_f32(&s).map(f32::to_bits), Ok(std_v.to_bits()), "{s}");
            }
        }
    }

    /// Any bit pattern as a finite f32 (an all-ones exponent loses its top bit).
    fn finite(bits: u32) -> f32 {
        let v = f32::from_bits(bits);
        if v.is_finite() {
            v
        } else {
            f32::from_bits(bits & !0x4000_0000)
        }
    }

    proptest::proptest! {
        #[test]
        fn every_f32_round_trips(bits in proptest::prelude::any::<u32>()) {
            let v = finite(bits);
            let s = fmt(v);
            proptest::prop_assert_eq!(parse_f32(&s).map(f32::to_bits), Ok(v.to_bits()), "{}", s);
            proptest::prop_assert_eq!(s.parse::<f32>().map(f32::to_bits), Ok(v.to_bits()));
        }

        #[test]
        fn parse_matches_std_on_short_decimals(m in -999_999_999i64..999_999_999, e in -30i32..30) {
            let s = std::format!("{m}e{e}");
            let ours = parse_f32(&s).unwrap();
            let std_v: f32 = s.parse().unwrap();
            // correctly rounded, as std's
            proptest::prop_assert_eq!(ours.to_bits(), std_v.to_bits(), "{}", s);
        }

        #[test]
        fn the_short_path_matches_std_on_wire_coefficients(m in 1u32..=999_999_999, n in 1u32..=12) {
            // 1 to 9 significant digits below 1 (a `refl` line's coefficients), the fast path
            let s = std::format!("0.{:0>width$}", m, width = n.max(m.ilog10() + 1) as usize);
            let std_v: f32 = s.parse().unwrap();
            proptest::prop_assert_eq!(parse_f32(&s).map(f32::to_bits), Ok(std_v.to_bits()), "{}", s);
            let neg = std::format!("-{s}");
            proptest::prop_assert_eq!(parse_f32(&neg).map(f32::to_bits), Ok((-std_v).to_bits()));
        }

        #[test]
        fn parse_matches_std_over_the_whole_range(
            m in 1u64..u64::MAX,
            digits in 1usize..20,
            e in -70i32..45,
        ) {
            // up to 19 significant digits at every exponent: all three paths of the parser
            let m = m % 10u64.pow(digits as u32 - 1).max(1) * 10 + m % 9 + 1;
            let s = std::format!("{m}e{e}");
            let std_v: f32 = s.parse().unwrap();
            match parse_f32(&s) {
                Ok(v) => proptest::prop_assert_eq!(v.to_bits(), std_v.to_bits(), "{}", s),
                Err(NumberError::Range) => proptest::prop_assert!(std_v.is_infinite(), "{}", s),
                Err(e) => proptest::prop_assert!(false, "{}: {:?}", s, e),
            }
        }

        #[test]
        fn every_finite_f32_round_trips_through_the_hex_form(bits in proptest::prelude::any::<u32>()) {
            let v = finite(bits);
            let mut s = String::new();
            write_f32_hex(&mut s, v).unwrap();
            // the same pattern as std's formatting of the bits
            proptest::prop_assert_eq!(&s, &std::format!("{:#010x}", v.to_bits()));
            proptest::prop_assert_eq!(parse_f32(&s).map(f32::to_bits), Ok(v.to_bits()));
        }

        #[test]
        fn formats_the_shortest_digits(bits in proptest::prelude::any::<u32>()) {
            // as many significant digits as std's shortest round-trip `Display`
            let v = finite(bits);
            proptest::prop_assume!(v != 0.0);
            let count = |s: &str| {
                let mant = s.split('e').next().unwrap_or("");
                let d: std::string::String = mant.chars().filter(char::is_ascii_digit).collect();
                d.trim_start_matches('0').trim_end_matches('0').len()
            };
            let std_s = std::format!("{:e}", v);
            proptest::prop_assert_eq!(count(&fmt(v)), count(&std_s), "{} {}", fmt(v), std_s);
        }
    }
}
