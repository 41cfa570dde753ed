//! Targets other than x86-64: no AVX2, so [`Avx2Fma`] has no values and every call takes the
//! portable path.

use crate::Kernels;
use specpoly_core::{DefaultSpectrum, PaperSpectrum, Sampled, Xyz};

/// Proof that this CPU has AVX2 and FMA: on this target there is none.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Avx2Fma {}

impl Avx2Fma {
    /// Always `None` on this target.
    #[inline]
    pub fn detect() -> Option<Self> {
        None
    }
}

macro_rules! no_kernels {
    ($t:ty) => {
        impl Kernels for $t {
            fn mul_with(k: Avx2Fma, _: &Self, _: &Self) -> Self {
                match k {}
            }
            fn xyz_with(k: Avx2Fma, _: &Self, _: &Self::Light) -> Xyz {
                match k {}
            }
            fn mul_xyz_with(k: Avx2Fma, _: &Self, _: &Self, _: &Self::Light) -> Xyz {
                match k {}
            }
            fn mul_each(k: Avx2Fma, _: &[Self], _: &[Self], _: &mut [Self]) {
                match k {}
            }
            fn xyz_each(k: Avx2Fma, _: &[Self], _: &Self::Light, _: &mut [Xyz]) {
                match k {}
            }
        }
    };
}

no_kernels!(DefaultSpectrum);
no_kernels!(PaperSpectrum);
no_kernels!(Sampled<81>);
