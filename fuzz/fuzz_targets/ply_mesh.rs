#![no_main]
//! `specpoly::fuzz::ply_mesh` under libFuzzer (docs/reliability.md, "Fuzzing").
libfuzzer_sys::fuzz_target!(|data: &[u8]| specpoly::fuzz::ply_mesh(data));
