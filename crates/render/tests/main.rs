//! The integration tests of `render`: one test binary, a module per area.

mod analytic;
mod chain_error;
mod common;
mod cornell_data;
mod gltf;
mod gltf_texture;
mod hero;
mod interaction;
mod mesh_files;
mod path;
#[path = "../../core/tests/common/reference_1nm.rs"]
mod reference_1nm;
mod scenes;
mod soft_shadow;
mod upsample;
