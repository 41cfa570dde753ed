#![no_main]
//! `specpoly::fuzz::gltf` under libFuzzer (docs/reliability.md, "Fuzzing").
libfuzzer_sys::fuzz_target!(|data: &[u8]| specpoly::fuzz::gltf(data));
