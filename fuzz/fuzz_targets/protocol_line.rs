#![no_main]
//! `specpoly::fuzz::protocol_line` under libFuzzer (docs/reliability.md, "Fuzzing").
libfuzzer_sys::fuzz_target!(|data: &[u8]| specpoly::fuzz::protocol_line(data));
