//! The LED colour controller on an STM32F401/F411 board (feature `stm32f4`): the board
//! ([`Stm32f4`]: USART2, six PWM channels on TIM3 CH1–4 and TIM4 CH1–2, TIM5 as the clock,
//! settings in flash sectors 6–7) and the application loop ([`app::run`]). Pins, clock and
//! wiring: `specpoly_firmware::boards::stm32f4` and firmware/README.md.
#![no_std]
#![no_main]
#![deny(unsafe_code)]

use cortex_m_rt::entry;
use specpoly_firmware::{app, boards::stm32f4::Stm32f4};

#[entry]
fn main() -> ! {
    app::run(Stm32f4::take())
}
