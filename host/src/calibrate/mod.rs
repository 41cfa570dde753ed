//! Monitor calibration: patch sets, where patches are shown, where readings come from, the
//! fit of Cowan's model, calibration files, ICC export and verification.

pub mod measurement;
