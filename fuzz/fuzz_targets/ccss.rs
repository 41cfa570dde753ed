#![no_main]
//! `specpoly::fuzz::ccss` under libFuzzer (docs/reliability.md, "Fuzzing").
libfuzzer_sys::fuzz_target!(|data: &[u8]| specpoly::fuzz::ccss(data));
