//! Decimal numbers on the wire: a small parser and formatter for `f32`.
//!
//! `core`'s own `str::parse::<f32>` carries ≈ 10 KiB of power-of-five tables and its float
//! `Display` several KiB more; the firmware's flash budget is 32 KiB, so the protocol brings
//! its own, in f64 arithmetic.
//!
//! Grammar: `[+-]? digits? ('.' digits?)? ([eE] [+-]? digits)?` with at least one digit before
//! the exponent, at most [`MAX_NUMBER_LEN`] characters. `nan` and `inf` are not numbers here.
//!
//! Parsing: the first 19 significant digits form an integer mantissa `m`, the value is
//! `m · 10^e` computed in f64 with `10^|e|` by exact squaring up to `10^22` (then rounded to
//! f32): the error is below 1 ulp of f32. Formatting writes the fewest of 6–9 significant
//! digits that survive `format → parse` unchanged (9 always do: IEEE 754-2008, §5.12.2).

use core::fmt::{self, Write};

/// Longest number token accepted.
pub const MAX_NUMBER_LEN: usize = 40;

/// Why a token is not a number.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NumberError {
    /// Not of the grammar above (or empty, or too long).
    Syntax,
    /// Overflows f32 (or underflows to a denormal range handled as 0 is fine; only overflow fails).
    Range,
}

/// `10^n` for `0 ≤ n ≤ 22`: exact in f64.
fn pow10_exact(n: u32) -> f64 {
    let mut r = 1.0f64;
    let mut i = 0;
    while i < n {
        r *= 10.0;
        i += 1;
    }
    r
}

/// `m · 10^e` in f64, stepping by exact `10^22` factors when `|e| > 22`.
fn scale10(mut v: f64, mut e: i32) -> f64 {
    while e > 22 {
        v *= 1e22;
        e -= 22;
    }
    while e < -22 {
        v /= 1e22;
        e += 22;
    }
    if e >= 0 {
        v * pow10_exact(e as u32)
    } else {
        v / pow10_exact((-e) as u32)
    }
}

/// Parses a decimal token into a finite `f32`.
pub fn parse_f32(s: &str) -> Result<f32, NumberError> {
    let b = s.as_bytes();
    if b.is_empty() || b.len() > MAX_NUMBER_LEN {
        return Err(NumberError::Syntax);
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
    let mut mantissa: u64 = 0;
    let mut kept = 0u32; // significant digits kept in `mantissa`
    let mut exp10: i32 = 0; // decimal exponent correction from dropped or fractional digits
    let mut digits = 0u32;
    while i < b.len() && b[i].is_ascii_digit() {
        let d = (b[i] - b'0') as u64;
        if mantissa == 0 && d == 0 {
            // leading zero: no information
        } else if kept < 19 {
            mantissa = mantissa * 10 + d;
            kept += 1;
        } else {
            exp10 += 1;
        }
        digits += 1;
        i += 1;
    }
    if i < b.len() && b[i] == b'.' {
        i += 1;
        while i < b.len() && b[i].is_ascii_digit() {
            let d = (b[i] - b'0') as u64;
            if mantissa == 0 && d == 0 {
                exp10 -= 1;
            } else if kept < 19 {
                mantissa = mantissa * 10 + d;
                kept += 1;
                exp10 -= 1;
            }
            digits += 1;
            i += 1;
        }
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
    let v = if mantissa == 0 {
        0.0
    } else if exp10 + kept as i32 > 40 {
        f64::INFINITY
    } else if exp10 + (kept as i32) < -50 {
        0.0
    } else {
        scale10(mantissa as f64, exp10)
    };
    let v = v as f32;
    if !v.is_finite() {
        return Err(NumberError::Range);
    }
    Ok(if negative { -v } else { v })
}

/// Writes `v` with the fewest significant digits (6 to 9) that [`parse_f32`] reads back as the
/// same f32 (9 always suffice: IEEE 754-2008, §5.12.2), trailing zeros dropped: plain decimals
/// for `1e-5 ≤ |v| < 1e9`, else `d.ddde±x`. Non-finite values are written `nan`, `inf`, `-inf`
/// (which [`parse_f32`] rejects).
pub fn write_f32<W: Write>(w: &mut W, v: f32) -> fmt::Result {
    if v.is_nan() {
        return w.write_str("nan");
    }
    if v.is_infinite() {
        return w.write_str(if v > 0.0 { "inf" } else { "-inf" });
    }
    let mut buf = Small::default();
    for p in 6..=9 {
        buf.len = 0;
        write_digits(&mut buf, v, p);
        if p == 9 || parse_f32(buf.as_str()) == Ok(v) {
            break;
        }
    }
    w.write_str(buf.as_str())
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
}

impl Small {
    fn push(&mut self, c: u8) {
        if self.len < self.b.len() {
            self.b[self.len] = c;
            self.len += 1;
        }
    }
}

impl Write for Small {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        let end = self.len + s.len();
        if end > self.b.len() {
            return Err(fmt::Error);
        }
        self.b[self.len..end].copy_from_slice(s.as_bytes());
        self.len = end;
        Ok(())
    }
}

/// `v` (finite) rounded to `p ≤ 9` significant digits (at most 16 bytes: fits [`Small`]).
fn write_digits(w: &mut Small, v: f32, p: i32) {
    if v < 0.0 || (v == 0.0 && v.is_sign_negative()) {
        w.push(b'-');
    }
    let a = (v as f64).abs();
    if a == 0.0 {
        return w.push(b'0');
    }
    // decimal exponent e with 10^e ≤ a < 10^(e+1)
    let mut e: i32 = 0;
    let mut pw = 1.0f64;
    if a >= 1.0 {
        while a >= pw * 10.0 {
            pw *= 10.0;
            e += 1;
        }
    } else {
        while a < pw {
            pw /= 10.0;
            e -= 1;
        }
    }
    let lo = pow10_exact(p as u32 - 1) as u32;
    let hi = lo * 10;
    // the loop above may be one off near a power of ten (inexact 10^e): correct and redo
    let mut m = (scale10(a, p - 1 - e) + 0.5) as u32;
    if m >= hi {
        e += 1;
        m = (scale10(a, p - 1 - e) + 0.5) as u32;
    } else if m < lo {
        e -= 1;
        m = (scale10(a, p - 1 - e) + 0.5) as u32;
    }
    if m >= hi {
        // rounded up to 10^p exactly
        m /= 10;
        e += 1;
    }
    let mut digits = [0u8; 9];
    let mut n = p as usize;
    for d in digits[..n].iter_mut().rev() {
        *d = b'0' + (m % 10) as u8;
        m /= 10;
    }
    while n > 1 && digits[n - 1] == b'0' {
        n -= 1;
    }
    let digits = &digits[..n];
    let put = |w: &mut Small, d: &[u8]| {
        for c in d {
            w.push(*c);
        }
    };
    if (0..9).contains(&e) {
        let int = e as usize + 1;
        if digits.len() <= int {
            put(w, digits);
            for _ in digits.len()..int {
                w.push(b'0');
            }
        } else {
            put(w, &digits[..int]);
            w.push(b'.');
            put(w, &digits[int..]);
        }
    } else if (-5..0).contains(&e) {
        w.push(b'0');
        w.push(b'.');
        for _ in 0..(-e - 1) {
            w.push(b'0');
        }
        put(w, digits);
    } else {
        put(w, &digits[..1]);
        if digits.len() > 1 {
            w.push(b'.');
            put(w, &digits[1..]);
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
    fn agrees_with_std_parse() {
        for s in [
            "0.123456789",
            "95.047",
            "108.883",
            "1.17549435e-38",
            "3.40282347e38",
            "7e-45",
        ] {
            assert_eq!(parse_f32(s).unwrap(), s.parse::<f32>().unwrap(), "{s}");
        }
    }

    proptest::proptest! {
        #[test]
        fn every_f32_round_trips(bits in proptest::prelude::any::<u32>()) {
            let v = f32::from_bits(bits);
            proptest::prop_assume!(v.is_finite());
            let s = fmt(v);
            proptest::prop_assert_eq!(parse_f32(&s).map(f32::to_bits), Ok(v.to_bits()), "{}", s);
            proptest::prop_assert_eq!(s.parse::<f32>().map(f32::to_bits), Ok(v.to_bits()));
        }

        #[test]
        fn parse_matches_std_on_short_decimals(m in -99_999_999i64..99_999_999, e in -30i32..30) {
            let s = std::format!("{m}e{e}");
            let ours = parse_f32(&s).unwrap();
            let std_v: f32 = s.parse().unwrap();
            // within one ulp (double rounding through f64)
            let d = (ours.to_bits() as i64 - std_v.to_bits() as i64).abs();
            proptest::prop_assert!(d <= 1, "{} {} {}", s, ours, std_v);
        }
    }
}
