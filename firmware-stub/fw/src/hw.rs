//! The few MPS2 (AN385/AN386) peripherals the firmware drives, by raw register access: CMSDK
//! APB UART0 (sample stream), CMSDK APB TIMER0 (output-rate pacing, IRQ 8) and TIMER1
//! (free-running tick counter). Both FPGA images clock the APB at SYSCLK = 25 MHz.

use core::ptr::{read_volatile, write_volatile};

/// Peripheral clock of the timers (Hz).
pub const PCLK_HZ: u32 = 25_000_000;
/// NVIC line of TIMER0 on MPS2.
pub const TIMER0_IRQ: u16 = 8;

const UART0: usize = 0x4000_4000;
const TIMER0: usize = 0x4000_0000;
const TIMER1: usize = 0x4000_1000;

fn rd(addr: usize) -> u32 {
    // SAFETY: `addr` is one of the fixed, aligned MPS2 peripheral registers above.
    unsafe { read_volatile(addr as *const u32) }
}
fn wr(addr: usize, v: u32) {
    // SAFETY: as for `rd`.
    unsafe { write_volatile(addr as *mut u32, v) }
}

/// NVIC interrupt number for `cortex_m::peripheral::NVIC`.
#[derive(Clone, Copy)]
pub struct Irq(pub u16);
// SAFETY: the number is a valid MPS2 interrupt line.
unsafe impl cortex_m::interrupt::InterruptNumber for Irq {
    fn number(self) -> u16 {
        self.0
    }
}

/// UART0: enables the transmitter (BAUDDIV = 16, the smallest the CMSDK UART accepts).
pub fn uart_init() {
    wr(UART0 + 0x10, 16);
    wr(UART0 + 0x08, 0b11); // TX and RX enable
}

/// Writes bytes to UART0, waiting while the transmit buffer is full.
pub fn uart_write(bytes: &[u8]) {
    for b in bytes {
        while rd(UART0 + 0x04) & 1 != 0 {}
        wr(UART0, *b as u32);
    }
}

/// Starts TIMER0 with interrupt every `period` PCLK ticks.
pub fn pacing_start(period: u32) {
    wr(TIMER0, 0);
    wr(TIMER0 + 0x08, period.saturating_sub(1));
    wr(TIMER0 + 0x04, period.saturating_sub(1));
    wr(TIMER0 + 0x0C, 1);
    wr(TIMER0, 0b1001); // enable, interrupt enable
}

/// Stops TIMER0.
pub fn pacing_stop() {
    wr(TIMER0, 0);
}

/// Acknowledges the TIMER0 interrupt.
pub fn pacing_ack() {
    wr(TIMER0 + 0x0C, 1);
}

/// Starts TIMER1 as a free-running 32-bit down-counter at PCLK.
pub fn ticks_start() {
    wr(TIMER1, 0);
    wr(TIMER1 + 0x08, u32::MAX);
    wr(TIMER1 + 0x04, u32::MAX);
    wr(TIMER1, 1);
}

/// Ticks elapsed since [`ticks_start`] (wraps after 2³² ticks, 171 s).
pub fn ticks() -> u32 {
    u32::MAX - rd(TIMER1 + 0x04)
}
