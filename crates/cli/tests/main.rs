//! The integration tests of `cli`: one test binary, a module per area.

mod calibrate_argyll;
mod calibrate_cli;
mod calibrate_export;
mod calibrate_icc_input;
mod calibrate_lut3d;
mod calibrate_run_led;
mod calibrate_run_sim;
mod calibrate_serial;
mod calibrate_serial_noise;
mod calibrate_session;
mod calibrate_target;
mod calibrate_vcgt_load;
mod calibrate_verify;
mod calibrate_web;
mod cli_accuracy;
mod cli_commands;
mod cli_convention;
mod cli_errors;
mod cli_output_paths;
mod cli_plausible;
mod cli_safety;
mod cli_xyz;
mod cli_xyz_model;
mod common;
mod csv_files;
mod docs_commands;
mod fuzz_corpora;
mod led_cli;
mod led_lut;
mod led_table;
mod light_cli;
mod light_tm30_cli;
#[path = "../../core/tests/common/reference_1nm.rs"]
mod reference_1nm;
mod render_cli;
mod render_output;
