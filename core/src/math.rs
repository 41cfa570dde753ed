//! The few f32 functions on the firmware's hot path (transfer curves). `libm` by default; with
//! the opt-in `fast-math` feature, `micromath`'s approximations (colour error measured in
//! docs/performance.md).

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
