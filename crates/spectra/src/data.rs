//! Reference data embedded in the binary, so the CLI runs anywhere: the same files in `data/`
//! that the tests read (see data/README.md for sources). CIE observers and illuminants live in
//! `specpoly-core` (compiled in as constants).

/// A file compiled into the binary: its name on the command line, its text and what it is
/// (spectral tables here, scenes in [`specpoly_render::builtin`]).
pub struct Builtin {
    /// The name used on the command line (`NAME` or `NAME#COLUMN` for a table).
    pub name: &'static str,
    /// The file's text (CSV for a table, TOML for a scene).
    pub text: &'static str,
    /// One-line description.
    pub about: &'static str,
}

impl Builtin {
    /// The file `text` called `name` on the command line, described by `about`.
    pub const fn new(name: &'static str, text: &'static str, about: &'static str) -> Self {
        Builtin { name, text, about }
    }
}

/// Every built-in table besides the illuminants.
pub const TABLES: &[Builtin] = &[
    Builtin::new(
        "colorchecker",
        include_str!("../../../data/reflectances/colorchecker_babelcolor_average.csv"),
        "24 ColorChecker reflectances, BabelColor average, 380-730 nm @ 10 nm",
    ),
    Builtin::new(
        "cornell",
        include_str!("../../../data/cornell/cornell_box_reflectance.csv"),
        "the Cornell box's measured white, green, red wall reflectances, 400-700 nm @ 4 nm",
    ),
    Builtin::new(
        "cornell_light",
        include_str!("../../../data/cornell/cornell_box_light.csv"),
        "the Cornell box light's emission spectrum, 400-700 nm @ 100 nm",
    ),
    Builtin::new(
        "crt",
        include_str!("../../../data/displays/crt_brainard_1997.csv"),
        "a typical CRT's red, green, blue phosphor spectra (Brainard 1997), 380-780 nm @ 5 nm",
    ),
];

/// The shipped ArgyllCMS .ti3 measurements of a real LCD (see data/README.md).
pub const ACER_TI3: &str = include_str!("../../../data/ti3/acer-xb271hu-unit1_dispread_2068.ti3");
