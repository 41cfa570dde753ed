#![no_main]
//! `specpoly_firmware::fuzz::command_bytes` under libFuzzer (docs/reliability.md, "Fuzzing").
libfuzzer_sys::fuzz_target!(|data: &[u8]| specpoly_firmware::fuzz::command_bytes(data));
