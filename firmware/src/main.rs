//! The LED colour controller on QEMU mps2-an386: the board ([`Mps2`]) and the application loop
//! ([`app::run`]). QEMU has no PWM: the duties are in the defmt log (`duty R G B max=M
//! stack=BYTES`, `mix duty [..]`, `fade K/N duty [..] stack=BYTES`; see `app`).
#![no_std]
#![no_main]
#![deny(unsafe_code)]

use cortex_m_rt::entry;
use specpoly_firmware::{app, boards::mps2::Mps2};

#[entry]
fn main() -> ! {
    app::run(Mps2::take())
}
