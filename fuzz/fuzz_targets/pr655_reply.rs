#![no_main]
//! `specpoly::fuzz::pr655_reply` under libFuzzer (docs/reliability.md, "Fuzzing").
libfuzzer_sys::fuzz_target!(|data: &[u8]| specpoly::fuzz::pr655_reply(data));
