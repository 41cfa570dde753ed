//! One measured patch: the device values shown and the XYZ read back.

/// A measured patch.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Measurement {
    /// Device values shown, each in `[0, 1]` (CGATS `RGB_*` / 100).
    pub device: [f64; 3],
    /// Measured XYZ (absolute cd/m², or relative with white `Y = 100` as ArgyllCMS writes
    /// when `NORMALIZED_TO_Y_100` is `YES`).
    pub xyz: [f64; 3],
}
