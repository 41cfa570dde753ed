//! Spectra: the core's default representation ([`DefaultSpectrum`]: 8 uniform spans over
//! 380–780 nm, a cubic Chebyshev series in each, Raso & Fournier 1991 §5), fitted from samples,
//! evaluated, multiplied (the product reduced back to cubics, the paper's eq. 6) and integrated
//! to CIE XYZ under a built-in light and observer.
//!
//! The XYZ is the core's [`Moments::xyz`]: three dot products with the moments of the light
//! and observer, `Mₐ[k][s] = K Σ_λ w(λ) Tₖ(t(λ)) S(λ) ā(λ)` at 1 nm, `K = 100 / Σ S ȳ`
//! (`specpoly_core::moments`). The moments of the 7 lights × 4 observers are compiled in
//! (`src/lights.rs`, 11 KiB of flash, linked only when `sp_spectrum_xyz` or `sp_light_white`
//! is called), the values of [`Moments::new`] to the bit (a test checks), so no f64
//! integration runs on the device.

use crate::display::SpXyz;
use crate::status::{self, finite, of, Status};
use crate::{lights, ptr, SpStatus};
use specpoly_core::{DefaultSpectrum, Moments, Tabulated, DEFAULT_COEFFS, DEFAULT_SPANS};

/// Spans of a spectrum (uniform over 380–780 nm: 50 nm each).
pub const SP_SPECTRUM_SPANS: usize = 8;
/// Chebyshev coefficients per span (cubic).
pub const SP_SPECTRUM_COEFFS: usize = 4;
const _: () = assert!(SP_SPECTRUM_SPANS == DEFAULT_SPANS && SP_SPECTRUM_COEFFS == DEFAULT_COEFFS);

/// A spectrum: span `s` covers `380 + 50 s` to `430 + 50 s` nm and is `Σₖ coef[k][s] Tₖ(t)`,
/// `t = (2λ − (a + b)) / (b − a)` (128 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SpSpectrum {
    /// `coef[k][s]`: the coefficient of `Tₖ` in span `s`.
    pub coef: [[f32; SP_SPECTRUM_SPANS]; SP_SPECTRUM_COEFFS],
}

/// A CIE observer (the `observer` argument): the two standard observers and the CIE 2015
/// cone-fundamental-based ones (CIE 170-2:2015).
#[repr(i32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpObserver {
    /// CIE 1931 2°.
    Cie1931 = 0,
    /// CIE 1964 10°.
    Cie1964 = 1,
    /// CIE 2015 2° (CIE 170-2:2015; zero below 390 nm, where it is undefined).
    Cie2015_2 = 2,
    /// CIE 2015 10° (CIE 170-2:2015; zero below 390 nm).
    Cie2015_10 = 3,
}

/// A built-in light (the `illuminant` argument), tabulated at 5 nm (CIE 015:2018).
#[repr(i32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpIlluminant {
    /// CIE A (2856 K incandescent).
    A = 0,
    /// CIE D50.
    D50 = 1,
    /// CIE D65.
    D65 = 2,
    /// Equal energy.
    E = 3,
    /// CIE FL2 (cool white fluorescent).
    Fl2 = 4,
    /// CIE FL7 (broadband daylight fluorescent).
    Fl7 = 5,
    /// CIE FL11 (three-band fluorescent).
    Fl11 = 6,
}

impl SpSpectrum {
    /// The core's spectrum, [`SpStatus::NotFinite`] for a NaN or infinite coefficient.
    pub fn to_core(&self) -> Status<DefaultSpectrum> {
        finite(self.coef.as_flattened())?;
        Ok(DefaultSpectrum::from_coefficients(self.coef))
    }

    /// The caller's form of a core spectrum.
    pub fn from_core(s: &DefaultSpectrum) -> Self {
        Self {
            coef: *s.coefficients(),
        }
    }
}

/// Fits a spectrum to `n` samples (`nm[i]`, `value[i]`) by least squares in each span against
/// their linear interpolant on a ≤ 1 nm grid, the end values held beyond the data (the core's
/// `Spectrum::fit`; f64 normal equations).
///
/// Returns `SP_STATUS_OK`; `SP_STATUS_NULL_POINTER` (`nm`, `value` or `out` NULL);
/// `SP_STATUS_SIZE` (`n` is 0); `SP_STATUS_NOT_FINITE` (a NaN or infinite sample);
/// `SP_STATUS_DOMAIN` (wavelengths not strictly increasing, or all outside 380–780 nm).
///
/// # Safety
/// `nm` and `value` are NULL or point to `n` floats each; `out` is NULL or points to a
/// writable `SpSpectrum`.
#[no_mangle]
pub unsafe extern "C" fn sp_spectrum_fit(
    nm: *const f32,
    value: *const f32,
    n: usize,
    out: *mut SpSpectrum,
) -> SpStatus {
    if n > isize::MAX as usize / size_of::<f32>() {
        return SpStatus::Size;
    }
    // SAFETY: forwarded contract.
    let args = unsafe { (ptr::slice(nm, n), ptr::slice(value, n), ptr::get_mut(out)) };
    let (Ok(nm), Ok(value), Ok(out)) = args else {
        return SpStatus::NullPointer;
    };
    of(fit(nm, value).map(|s| *out = s))
}

fn fit(nm: &[f32], value: &[f32]) -> Status<SpSpectrum> {
    let data = Tabulated::new(nm, value).map_err(status::core)?;
    let s = DefaultSpectrum::fit(&data).map_err(status::core)?;
    Ok(SpSpectrum::from_core(&s))
}

/// The spectrum's value at `nm` (380–780 nm; on an interior breakpoint the mean of the two
/// spans' values).
///
/// Returns `SP_STATUS_OK`; `SP_STATUS_NULL_POINTER` (`spectrum` or `out` NULL);
/// `SP_STATUS_NOT_FINITE` (`nm` or a coefficient NaN or infinite); `SP_STATUS_DOMAIN` (`nm`
/// outside 380–780).
///
/// # Safety
/// `spectrum` is NULL or points to a valid `SpSpectrum`; `out` is NULL or points to a writable
/// float.
#[no_mangle]
pub unsafe extern "C" fn sp_spectrum_eval(
    spectrum: *const SpSpectrum,
    nm: f32,
    out: *mut f32,
) -> SpStatus {
    // SAFETY: forwarded contract.
    let args = unsafe { (ptr::get(spectrum), ptr::get_mut(out)) };
    let (Ok(s), Ok(out)) = args else {
        return SpStatus::NullPointer;
    };
    of(eval(s, nm).map(|v| *out = v))
}

fn eval(s: &SpSpectrum, nm: f32) -> Status<f32> {
    finite(&[nm])?;
    if !(specpoly_core::LAMBDA_MIN..=specpoly_core::LAMBDA_MAX).contains(&nm) {
        return Err(SpStatus::Domain);
    }
    Ok(s.to_core()?.eval(nm))
}

/// The product `a · b` reduced to cubics in every span (the exact product's coefficients of
/// degree 4 to 6 dropped: the paper's eq. 6). `out` may be `a` or `b`.
///
/// Returns `SP_STATUS_OK`; `SP_STATUS_NULL_POINTER` (`a`, `b` or `out` NULL);
/// `SP_STATUS_NOT_FINITE` (a NaN or infinite coefficient, or a product that overflows).
///
/// # Safety
/// `a` and `b` are NULL or point to valid `SpSpectrum`s; `out` is NULL or points to a writable
/// `SpSpectrum` (it may be `a` or `b`).
#[no_mangle]
pub unsafe extern "C" fn sp_spectrum_mul(
    a: *const SpSpectrum,
    b: *const SpSpectrum,
    out: *mut SpSpectrum,
) -> SpStatus {
    // Read both inputs before `out` is borrowed: it may alias either.
    // SAFETY: forwarded contract; the shared borrows end with the copies.
    let (a, b) = match unsafe { (ptr::get(a), ptr::get(b)) } {
        (Ok(a), Ok(b)) => (*a, *b),
        _ => return SpStatus::NullPointer,
    };
    // SAFETY: forwarded contract; no other borrow of `out` is live.
    let Ok(out) = (unsafe { ptr::get_mut(out) }) else {
        return SpStatus::NullPointer;
    };
    of(mul(&a, &b).map(|s| *out = s))
}

fn mul(a: &SpSpectrum, b: &SpSpectrum) -> Status<SpSpectrum> {
    let p = SpSpectrum::from_core(&a.to_core()?.mul(&b.to_core()?));
    finite(p.coef.as_flattened())?;
    Ok(p)
}

/// The compiled-in moments of a light and observer.
fn moments(observer: i32, illuminant: i32) -> Status<&'static Moments<8, 4>> {
    let o = usize::try_from(observer).map_err(|_| SpStatus::Domain)?;
    let i = usize::try_from(illuminant).map_err(|_| SpStatus::Domain)?;
    if o >= lights::OBSERVERS || i >= lights::LIGHTS {
        return Err(SpStatus::Domain);
    }
    Ok(&lights::MOMENTS[o * lights::LIGHTS + i])
}

/// CIE XYZ of `spectrum` (a reflectance) under the light `illuminant` (`SpIlluminant`) seen by
/// `observer` (`SpObserver`), the perfect white at `Y = 100`.
///
/// Returns `SP_STATUS_OK`; `SP_STATUS_NULL_POINTER` (`spectrum` or `out` NULL);
/// `SP_STATUS_NOT_FINITE` (a NaN or infinite coefficient, or an XYZ that overflows);
/// `SP_STATUS_DOMAIN` (an unknown `observer` or `illuminant`).
///
/// # Safety
/// `spectrum` is NULL or points to a valid `SpSpectrum`; `out` is NULL or points to a writable
/// `SpXyz`.
#[no_mangle]
pub unsafe extern "C" fn sp_spectrum_xyz(
    spectrum: *const SpSpectrum,
    observer: i32,
    illuminant: i32,
    out: *mut SpXyz,
) -> SpStatus {
    // SAFETY: forwarded contract.
    let args = unsafe { (ptr::get(spectrum), ptr::get_mut(out)) };
    let (Ok(s), Ok(out)) = args else {
        return SpStatus::NullPointer;
    };
    of(xyz(s, observer, illuminant).map(|v| *out = v))
}

fn xyz(s: &SpSpectrum, observer: i32, illuminant: i32) -> Status<SpXyz> {
    let m = moments(observer, illuminant)?;
    let v = m.xyz(&s.to_core()?);
    finite(&[v.x, v.y, v.z])?;
    Ok(SpXyz::from(v))
}

/// CIE XYZ of the light `illuminant` itself (the perfect white: `Y = 100`) for `observer`.
///
/// Returns `SP_STATUS_OK`; `SP_STATUS_NULL_POINTER` (`out` NULL); `SP_STATUS_DOMAIN` (an
/// unknown `observer` or `illuminant`).
///
/// # Safety
/// `out` is NULL or points to a writable `SpXyz`.
#[no_mangle]
pub unsafe extern "C" fn sp_light_white(
    observer: i32,
    illuminant: i32,
    out: *mut SpXyz,
) -> SpStatus {
    // SAFETY: forwarded contract.
    of(unsafe { ptr::get_mut(out) }.and_then(|out| {
        *out = SpXyz::from(moments(observer, illuminant)?.white());
        Ok(())
    }))
}
