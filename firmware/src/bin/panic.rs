//! Panics on purpose, under QEMU: the tests check that a panic reaches the host as a defmt
//! `error` frame with its location and exits QEMU with a failure code (`boards::mps2`).
#![no_std]
#![no_main]
#![deny(unsafe_code)]

use cortex_m_rt::entry;
// links the board support: the defmt logger and the panic handler
use specpoly_firmware as _;

#[entry]
fn main() -> ! {
    defmt::info!("about to panic");
    let limit = core::hint::black_box(3usize);
    panic!("deliberate, limit {}", limit);
}
