//! Built-in scenes: the TOML files in `scenes/`, compiled into the binary so
//! `specpoly render example2` runs anywhere. Built-ins and files go through the same parser.

use specpoly_spectra::data::Builtin;

/// Every built-in scene.
pub const SCENES: &[Builtin] = &[
    Builtin::new(
        "example1",
        include_str!("../../../scenes/example1.toml"),
        "the paper's Example 1: two highly specular red spheres (red paint, Phong 60), D65",
    ),
    Builtin::new(
        "example2",
        include_str!("../../../scenes/example2.toml"),
        "the paper's Example 2: the red spheres inside a transparent blue filter cube, D65",
    ),
    Builtin::new(
        "interreflection",
        include_str!("../../../scenes/interreflection.toml"),
        "the paper's Figures 1-2: an orange sphere seen in a cyan mirror under FL11",
    ),
    Builtin::new(
        "cornell",
        include_str!("../../../scenes/cornell.toml"),
        "the Cornell box with its measured reflectances and light spectrum, path traced",
    ),
];

/// The built-in called `name` (case-insensitive).
pub fn find(name: &str) -> Option<&'static Builtin> {
    SCENES.iter().find(|s| s.name.eq_ignore_ascii_case(name))
}

/// The names, for messages.
pub fn names() -> String {
    SCENES.iter().map(|s| s.name).collect::<Vec<_>>().join(", ")
}
