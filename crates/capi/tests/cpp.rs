//! The header-only C++ wrapper `include/specpoly.hpp`: a freestanding firmware file using
//! every class compiles with `arm-none-eabi-g++` (Cortex-M4F) and `riscv64-unknown-elf-g++`
//! (RV32IMC) without exceptions, RTTI or a C++ library, warnings as errors. (Compiled, not run:
//! the wrapper only forwards to the C functions the C program checks; a host run would need
//! Debian's `g++`, which `./test.sh` does not install.)

use crate::c_program::{crate_dir, out_dir, run};
use std::process::Command;

#[test]
fn the_cpp_wrapper_compiles_for_a_cortex_m4f_and_an_rv32imc() {
    let c = crate_dir();
    let dir = out_dir("cpp");
    for (gxx, flags) in [
        (
            "arm-none-eabi-g++",
            &[
                "-mcpu=cortex-m4",
                "-mthumb",
                "-mfloat-abi=hard",
                "-mfpu=fpv4-sp-d16",
            ][..],
        ),
        (
            "riscv64-unknown-elf-g++",
            &["-march=rv32imc", "-mabi=ilp32"][..],
        ),
    ] {
        run(
            Command::new(gxx)
                .args([
                    "-std=c++11",
                    "-Wall",
                    "-Wextra",
                    "-Werror",
                    "-O2",
                    "-ffreestanding",
                ])
                .args(["-fno-exceptions", "-fno-rtti", "-c"])
                .args(flags)
                .arg("-I")
                .arg(c.join("include"))
                .arg(c.join("tests/cpp/wrapper_firmware.cpp"))
                .arg("-o")
                .arg(dir.join(format!("{gxx}.o"))),
            gxx,
        );
    }
}
