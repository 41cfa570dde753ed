#![no_main]
//! `specpoly::fuzz::csv` under libFuzzer (docs/reliability.md, "Fuzzing").
libfuzzer_sys::fuzz_target!(|data: &[u8]| specpoly::fuzz::csv(data));
