#![no_main]
//! `specpoly_device::fuzz::command_bytes` under libFuzzer (docs/reliability.md, "Fuzzing").
libfuzzer_sys::fuzz_target!(|data: &[u8]| specpoly_device::fuzz::command_bytes(data));
