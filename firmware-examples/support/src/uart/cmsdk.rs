//! MPS2 AN386 UART0: an ARM CMSDK APB UART at `0x4000_4000`.
//!
//! Registers (ARM DDI0479, "APB UART"; QEMU `hw/char/cmsdk-apb-uart.c`): `DATA` 0x00,
//! `STATE` 0x04 (TXFULL bit 0, RXFULL bit 1, TX/RX overrun bits 2/3, write 1 to clear),
//! `CTRL` 0x08 (TX enable bit 0, RX enable bit 1, RX interrupt enable bit 3), `INTSTATUS` 0x0C
//! (RX bit 1, write 1 to clear), `BAUDDIV` 0x10 (`pclk / baud`, at least 16). The receive
//! interrupt is NVIC line 0 (AN386 application note, "Interrupt map"; QEMU `mps2.c`).
//! One byte of buffer each way, no FIFO, always 8N1. PCLK is the 25 MHz system clock of the
//! MPS2 FPGA images. The UART is inside the FPGA image: no pin multiplexing to set up.
//!
//! QEMU notes: with RX disabled (before `take`) QEMU accepts no byte from the chardev; they
//! wait there, so nothing the host sends early is lost. Afterwards QEMU hands over one byte
//! whenever the receive buffer is empty: no overrun whatever the host's pace. A `BAUDDIV` below
//! 16 makes QEMU log "Tx enabled with invalid baudrate" (and a real UART misbehave).

use super::{Polled, claim, rd, wr};

const BASE: usize = 0x4000_4000;
const DATA: usize = BASE;
const STATE: usize = BASE + 0x04;
const CTRL: usize = BASE + 0x08;
const INTSTATUS: usize = BASE + 0x0C;
const BAUDDIV: usize = BASE + 0x10;

const STATE_TXFULL: u32 = 1 << 0;
const STATE_RXFULL: u32 = 1 << 1;
const STATE_OVERRUNS: u32 = 0b11 << 2;
const CTRL_TX_EN: u32 = 1 << 0;
const CTRL_RX_EN: u32 = 1 << 1;
const CTRL_RX_INT_EN: u32 = 1 << 3;
const INTSTATUS_RX: u32 = 1 << 1;

/// The MPS2 FPGA images' peripheral clock (QEMU `mps2.c`: `SYSCLK_FRQ`).
pub const PCLK_HZ: u32 = 25_000_000;

/// UART0 of the MPS2 AN386 image (QEMU `mps2-an386`), polled, 8N1.
pub struct CmsdkUart0 {
    _private: (),
}

impl CmsdkUart0 {
    /// Configures UART0 for `baud` from the `PCLK_HZ` peripheral clock and returns it;
    /// `None` if it was taken before.
    pub fn take(baud: u32) -> Option<Self> {
        if !claim() {
            return None;
        }
        wr(CTRL, 0);
        wr(BAUDDIV, (PCLK_HZ / baud.max(1)).max(16));
        wr(STATE, STATE_OVERRUNS);
        wr(CTRL, CTRL_TX_EN | CTRL_RX_EN | CTRL_RX_INT_EN);
        super::enable_rx_wakeup(Self::RX_IRQ);
        Some(CmsdkUart0 { _private: () })
    }
}

impl Polled for CmsdkUart0 {
    const RX_IRQ: u16 = 0;

    fn rx_irq_clear() {
        wr(INTSTATUS, INTSTATUS_RX);
    }

    fn rx_ready() -> bool {
        rd(STATE) & STATE_RXFULL != 0
    }

    fn rx() -> u8 {
        rd(DATA) as u8
    }

    // An overrun (real hardware only) lost a byte: its frame fails its CRC. Clear the flag.
    fn rx_done() {
        if rd(STATE) & STATE_OVERRUNS != 0 {
            wr(STATE, STATE_OVERRUNS);
        }
    }

    fn tx(byte: u8) {
        while Self::tx_busy() {}
        wr(DATA, u32::from(byte));
    }

    // The one-byte transmit buffer still holds a byte.
    fn tx_busy() -> bool {
        rd(STATE) & STATE_TXFULL != 0
    }
}
