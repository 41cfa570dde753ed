//! specpoly-c: the generated header, and a C program against the host staticlib (bit for bit
//! against the Rust API) and against the Cortex-M4F staticlib under QEMU.

mod c_program;
mod cpp;
mod header;
mod spectra;
mod total;
