#![no_main]
//! `specpoly::fuzz::obj_mesh` under libFuzzer (docs/reliability.md, "Fuzzing").
libfuzzer_sys::fuzz_target!(|data: &[u8]| specpoly::fuzz::obj_mesh(data));
