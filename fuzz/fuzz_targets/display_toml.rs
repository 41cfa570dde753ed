#![no_main]
//! `specpoly::fuzz::display_toml` under libFuzzer (docs/reliability.md, "Fuzzing").
libfuzzer_sys::fuzz_target!(|data: &[u8]| specpoly::fuzz::display_toml(data));
