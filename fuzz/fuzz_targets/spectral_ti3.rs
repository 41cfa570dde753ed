#![no_main]
//! `specpoly::fuzz::spectral_ti3` under libFuzzer (docs/reliability.md, "Fuzzing").
libfuzzer_sys::fuzz_target!(|data: &[u8]| specpoly::fuzz::spectral_ti3(data));
