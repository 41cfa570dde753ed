//! The header-only C++ wrapper `include/specpoly.hpp` and the examples built on it: a
//! freestanding firmware file using every class (`tests/cpp/wrapper_firmware.cpp`), the ESPHome
//! component (`examples/esphome/components/specpoly_light/specpoly_light.h`, instantiated by
//! `tests/cpp/esphome_component.cpp`) and the Arduino sketch
//! (`examples/arduino/specpoly/examples/Lamp/Lamp.ino`) compile with the host's `g++`
//! (x86-64), `arm-none-eabi-g++` (Cortex-M4F) and `riscv64-unknown-elf-g++` (RV32IMC),
//! warnings as errors, without exceptions, RTTI or a C++ library; ESPHome's and Arduino's
//! interfaces are stubs of exactly what the examples call (`tests/cpp/stub/`). Compiled, not
//! run: the wrapper only forwards to the C functions the C program checks (on the host too,
//! `c_program::*`).

use crate::c_program::{crate_dir, out_dir, run};
use std::process::Command;

#[test]
fn the_wrapper_and_the_examples_compile_for_the_host_a_cortex_m4f_and_an_rv32imc() {
    let c = crate_dir();
    let examples = c.join("../../examples");
    let dir = out_dir("cpp");
    let sources = [
        c.join("tests/cpp/wrapper_firmware.cpp"),
        c.join("tests/cpp/esphome_component.cpp"),
        examples.join("arduino/specpoly/examples/Lamp/Lamp.ino"),
    ];
    for (gxx, flags) in [
        ("g++", &[][..]),
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
        for (i, src) in sources.iter().enumerate() {
            run(
                Command::new(gxx)
                    .args([
                        "-x",
                        "c++",
                        "-std=c++11",
                        "-Wall",
                        "-Wextra",
                        "-Werror",
                        "-O2",
                    ])
                    .args(["-ffreestanding", "-fno-exceptions", "-fno-rtti", "-c"])
                    .args(flags)
                    .arg("-I")
                    .arg(c.join("include"))
                    .arg("-I")
                    .arg(c.join("tests/cpp/stub"))
                    .arg("-I")
                    .arg(examples.join("esphome/components/specpoly_light"))
                    .arg(src)
                    .arg("-o")
                    .arg(dir.join(format!("{gxx}-{i}.o"))),
                gxx,
            );
        }
    }
}
