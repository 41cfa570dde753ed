//! The integration tests of `tests`: one test binary, a module per area.

mod firmware_framebuffer;
mod firmware_qemu;
mod pixel_accuracy;
