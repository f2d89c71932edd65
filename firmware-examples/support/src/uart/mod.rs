//! Polled UART drivers for the two QEMU boards, implementing the `embedded-io` 0.6 traits
//! ([`Read`](embedded_io::Read), [`Write`](embedded_io::Write),
//! [`ErrorType`](embedded_io::ErrorType)), which is all `fw_node::run` needs.
//!
//! * `Lm3sUart0` (feature `lm3s6965evb`): TI Stellaris LM3S6965 UART0 (ARM PL011 with
//!   Luminary extensions) at `0x4000_C000`, pins PA0 (U0Rx) / PA1 (U0Tx);
//! * `CmsdkUart0` (feature `mps2-an386`): ARM CMSDK APB UART0 of the MPS2 AN386 FPGA image at
//!   `0x4000_4000` (QEMU `info mtree`; `0x4020_0000` on that board is the LAN9118 Ethernet).
//!
//! Both are polled (no interrupt handler, no DMA) and 8N1. `read` blocks until one byte is
//! there, then returns every byte the receiver already holds (up to the buffer); `write` blocks
//! until each byte is in the transmitter. While `read` waits the core sleeps (`WFI`): `take`
//! masks every interrupt (PRIMASK) and enables the receiver's interrupt line in the NVIC, so a
//! received byte wakes the core without any handler running (`sleep_until_rx`). A real board
//! draws less current; QEMU stops executing the guest instead of spinning on the status
//! register (a spinning guest takes QEMU's device lock for every poll and starves the thread
//! that feeds the UART from the host: 5-10 times fewer requests per second). Line errors (framing, parity, break, overrun) are not reported:
//! `Error = Infallible`. A damaged byte damages its frame, which the endpoint then drops on its
//! COBS/CRC check (and counts in `DeviceStats.link`); the host retries.
//!
//! Each driver is a singleton: `take` returns it once (a second `take` gives `None`), after
//! configuring the clocks, pins and baud rate.

use core::convert::Infallible;
use core::sync::atomic::{AtomicBool, Ordering};

#[cfg(feature = "mps2-an386")]
mod cmsdk;
#[cfg(feature = "lm3s6965evb")]
mod pl011;

#[cfg(feature = "mps2-an386")]
pub use cmsdk::CmsdkUart0;
#[cfg(feature = "lm3s6965evb")]
pub use pl011::Lm3sUart0;

/// The baud rate the examples use (8N1). QEMU ignores it (its UARTs move bytes as fast as the
/// host reads them); on a real board both ends must agree.
pub const BAUD: u32 = 115_200;

/// Bytes the board's UART0 holds on its own while the polled node computes: the PL011's
/// receive FIFO. A node reports it as `Identity.rx_buffer`, so a host keeps one request in
/// flight (a line without flow control would overrun the FIFO).
#[cfg(feature = "lm3s6965evb")]
pub const RX_FIFO: u32 = 16;

/// Bytes the board's UART0 holds on its own while the polled node computes: the CMSDK UART's
/// one-byte receive buffer. A node reports it as `Identity.rx_buffer`, so a host keeps one
/// request in flight (a line without flow control would overrun it).
#[cfg(feature = "mps2-an386")]
pub const RX_FIFO: u32 = 1;

/// The board's UART0 at [`BAUD`], as the serial nodes use it (see `serial_node!`); `None` if
/// it was taken before. The UART clock is [`Lm3sUart0::RESET_CLOCK_HZ`].
#[cfg(feature = "lm3s6965evb")]
#[inline(always)]
pub fn take_uart0() -> Option<Lm3sUart0> {
    Lm3sUart0::take(Lm3sUart0::RESET_CLOCK_HZ, BAUD)
}

/// The board's UART0 at [`BAUD`], as the serial nodes use it (see `serial_node!`); `None` if
/// it was taken before.
#[cfg(feature = "mps2-an386")]
#[inline(always)]
pub fn take_uart0() -> Option<CmsdkUart0> {
    CmsdkUart0::take(BAUD)
}

/// What a polled UART driver provides (its registers); [`polled_io!`] builds the
/// `embedded-io` implementations on it, the same for every driver.
trait Polled {
    /// A received byte is waiting.
    fn rx_ready() -> bool;
    /// Takes the waiting byte (after [`Polled::rx_ready`]).
    fn rx() -> u8;
    /// After a `read` took its bytes: clears the line-error flags the UART keeps, if any.
    fn rx_done() {}
    /// Waits until the transmitter has room, then hands it `byte`.
    fn tx(byte: u8);
    /// True while the transmitter still holds bytes to send (`flush` waits for false).
    fn tx_busy() -> bool;
    /// The receive interrupt's line in the NVIC.
    const RX_IRQ: u16;
    /// Clears the receive interrupt the UART latched, if it latches one (so that it asserts
    /// its line again for the next byte).
    fn rx_irq_clear() {}
}

/// An NVIC line by number (the boards have no peripheral access crate to name them).
#[derive(Clone, Copy)]
struct Line(u16);

// SAFETY: the lines used are the boards' receive interrupts, below their `IRQS`.
unsafe impl cortex_m::interrupt::InterruptNumber for Line {
    fn number(self) -> u16 {
        self.0
    }
}

/// Lets a received byte wake `WFI` without being taken: masks every configurable interrupt
/// (PRIMASK stays set: the images run no handler, and the vector table has a single entry)
/// and enables the receive line in the NVIC. A pending enabled interrupt wakes `WFI` whatever
/// PRIMASK says (ARMv7-M ARM, B1.5.19). Called by `take` after the UART raises the line on
/// receipt.
fn enable_rx_wakeup(line: u16) {
    cortex_m::interrupt::disable();
    // SAFETY: with PRIMASK set the interrupt is never taken, so no handler runs and no
    // critical section (all of them are PRIMASK-based on these single-core parts) is broken.
    unsafe { cortex_m::peripheral::NVIC::unmask(Line(line)) };
}

/// Sleeps until the receiver may hold a byte: clears the latched interrupt (UART and NVIC),
/// then sleeps unless a byte came meanwhile. A byte arriving after the check pends the line,
/// which wakes the `WFI` (or keeps it from sleeping): none is missed. The caller checks again.
fn sleep_until_rx<P: Polled>() {
    P::rx_irq_clear();
    cortex_m::peripheral::NVIC::unpend(Line(P::RX_IRQ));
    if !P::rx_ready() {
        cortex_m::asm::wfi();
    }
}

/// `embedded_io::{ErrorType, Read, ReadReady, Write}` for a [`Polled`] driver (a macro: the
/// traits and the drivers' types are not this module's, so no blanket implementation).
macro_rules! polled_io {
    ($uart:ty) => {
        impl embedded_io::ErrorType for $uart {
            type Error = Infallible;
        }

        impl embedded_io::Read for $uart {
            fn read(&mut self, buf: &mut [u8]) -> Result<usize, Infallible> {
                if buf.is_empty() {
                    return Ok(0);
                }
                while !<$uart as Polled>::rx_ready() {
                    sleep_until_rx::<$uart>();
                }
                let mut n = 0;
                for slot in buf.iter_mut() {
                    if !<$uart as Polled>::rx_ready() {
                        break;
                    }
                    *slot = <$uart as Polled>::rx();
                    n += 1;
                }
                <$uart as Polled>::rx_done();
                Ok(n)
            }
        }

        impl embedded_io::ReadReady for $uart {
            fn read_ready(&mut self) -> Result<bool, Infallible> {
                Ok(<$uart as Polled>::rx_ready())
            }
        }

        impl embedded_io::Write for $uart {
            fn write(&mut self, buf: &[u8]) -> Result<usize, Infallible> {
                self.write_all(buf).map(|()| buf.len())
            }

            // Overridden: the provided one carries a panic path for `Ok(0)`, which never
            // happens here.
            fn write_all(&mut self, buf: &[u8]) -> Result<(), Infallible> {
                for &b in buf {
                    <$uart as Polled>::tx(b);
                }
                Ok(())
            }

            fn flush(&mut self) -> Result<(), Infallible> {
                while <$uart as Polled>::tx_busy() {}
                Ok(())
            }
        }
    };
}

#[cfg(feature = "mps2-an386")]
polled_io!(CmsdkUart0);
#[cfg(feature = "lm3s6965evb")]
polled_io!(Lm3sUart0);

/// Set once a driver was handed out.
static TAKEN: AtomicBool = AtomicBool::new(false);

/// True the first time only.
fn claim() -> bool {
    !TAKEN.swap(true, Ordering::AcqRel)
}

#[inline(always)]
fn rd(addr: usize) -> u32 {
    // SAFETY: only called with the MMIO register addresses of this module's UARTs, which are
    // always mapped on their board; a volatile read has no other effect than the device's.
    unsafe { core::ptr::read_volatile(addr as *const u32) }
}

#[inline(always)]
fn wr(addr: usize, v: u32) {
    // SAFETY: as for `rd`; the register writes are those the board's manual prescribes.
    unsafe { core::ptr::write_volatile(addr as *mut u32, v) }
}
