//! # specpoly-kernels
//!
//! The core's inner loops — the reduced product ([`specpoly_core::Spectrum::mul`], the paper's
//! eq. 6) and the integral to XYZ ([`specpoly_core::Moments::xyz`]) — instantiated as plain,
//! non-generic functions for the two built-in presets (the default, 8 uniform cubic spans, and
//! the paper's 2 spans split at 550 nm), and the display's drive step ([`Display::drive`]).
//!
//! **Why a crate of its own.** Cargo's profile overrides are per crate, and generic code is
//! compiled in the crate that instantiates it. The firmware is built for size
//! (`opt-level = "z"`), which never unrolls a loop: the default's →XYZ takes 1 555 instructions
//! on the Cortex-M4 there and 375 at `opt-level = 3`, but the whole firmware at `3` is 6 KiB
//! larger. Instantiated here, behind `#[inline(never)]`, the kernels — and nothing else — get
//! the firmware's `[profile.release.package.specpoly-kernels] opt-level = 3`
//! (docs/performance.md, "Issue 13"). The code is the core's: one implementation of each step;
//! these functions only name the types.
#![no_std]
#![forbid(unsafe_code)]
#![warn(missing_docs)]

use specpoly_core::{
    DefaultSpectrum, Display, Drive, GamutMap, Moments, Paper, PaperSpectrum, Xyz,
};

/// [`Moments::xyz`] for the default preset (8 uniform cubic spans).
#[inline(never)]
pub fn xyz_default(m: &Moments<8, 4>, r: &DefaultSpectrum) -> Xyz {
    m.xyz(r)
}

/// [`Moments::xyz`] for the paper's preset (2 cubic spans split at 550 nm).
#[inline(never)]
pub fn xyz_paper(m: &Moments<2, 4, Paper>, r: &PaperSpectrum) -> Xyz {
    m.xyz(r)
}

/// [`specpoly_core::Spectrum::mul`] for the default preset.
#[inline(never)]
pub fn mul_default(a: &DefaultSpectrum, b: &DefaultSpectrum) -> DefaultSpectrum {
    a.mul(b)
}

/// [`specpoly_core::Spectrum::mul`] for the paper's preset.
#[inline(never)]
pub fn mul_paper(a: &PaperSpectrum, b: &PaperSpectrum) -> PaperSpectrum {
    a.mul(b)
}

/// [`Display::drive`], the one drive step (target XYZ → gamut → curve → levels → emitted XYZ),
/// with its callees (`#[inline]` in the core) compiled here.
#[inline(never)]
pub fn drive(display: &Display, target: Xyz, map: GamutMap, max: u16) -> Drive {
    display.drive(target, map, max)
}
