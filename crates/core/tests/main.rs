//! The integration tests of `core`: one test binary, a module per area.

mod accuracy_colorchecker;
mod blob;
mod bradford_lindbloom;
mod ciede2000_sharma;
mod common;
mod light_colour_science;
mod light_luxpy;
mod light_mix_leds;
mod light_published;
mod light_references;
mod light_standards;
mod moments_1nm;
mod multiply_reduce;
mod observers_2015;
mod paper_eq6;
mod paper_path;
mod pixel_cube;
mod srgb_iec61966;
mod tm30_full;
