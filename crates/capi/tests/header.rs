//! The checked-in header is what cbindgen generates from the crate now.

use std::path::Path;

#[test]
fn the_checked_in_header_is_what_cbindgen_generates() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let config = cbindgen::Config::from_file(dir.join("cbindgen.toml")).expect("cbindgen.toml");
    let mut now = Vec::new();
    cbindgen::generate_with_config(dir, config)
        .expect("cbindgen parses the crate")
        .write(&mut now);
    let path = dir.join("include/specpoly.h");
    if std::env::var_os("SPECPOLY_WRITE_HEADER").is_some() {
        let tmp = path.with_extension("h.tmp");
        std::fs::write(&tmp, &now).unwrap();
        std::fs::rename(&tmp, &path).unwrap();
    }
    let checked_in = std::fs::read(&path).expect("include/specpoly.h");
    assert!(
        checked_in == now,
        "include/specpoly.h differs from cbindgen's output: regenerate it with \
         SPECPOLY_WRITE_HEADER=1 cargo test -p specpoly-c --test main header"
    );
}
