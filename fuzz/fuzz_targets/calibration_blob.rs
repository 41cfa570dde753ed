#![no_main]
//! `specpoly::fuzz::calibration_blob` under libFuzzer (docs/reliability.md, "Fuzzing").
libfuzzer_sys::fuzz_target!(|data: &[u8]| specpoly::fuzz::calibration_blob(data));
