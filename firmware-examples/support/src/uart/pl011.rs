//! LM3S6965 UART0: a PL011 (Stellaris/Luminary variant) at `0x4000_C000`.
//!
//! Registers (LM3S6965 data sheet, chapter "UART"; QEMU `hw/char/pl011.c`): `DR` 0x00 (data;
//! bits 8-11 are the error flags of the received byte), `RSR/ECR` 0x04, `FR` 0x18 (flags:
//! BUSY bit 3, RXFE bit 4, TXFF bit 5), `IBRD` 0x24 and `FBRD` 0x28 (baud divisor, 16.6 fixed
//! point of `clock / (16 · baud)`), `LCRH` 0x2C (WLEN bits 5-6, FEN bit 4; written after the
//! divisor, which it latches), `CTL` 0x30 (UARTEN bit 0, TXE bit 8, RXE bit 9).
//!
//! Clocks and pins: `RCGC1` bit 0 (UART0) and `RCGC2` bit 0 (GPIO port A) of the system
//! control block at `0x400F_E000`; PA0/PA1 to their alternate function (`GPIOAFSEL` 0x420) and
//! digital enable (`GPIODEN` 0x51C) of port A at `0x4000_4000`. QEMU accepts and ignores these;
//! a real LM3S6965 needs them. Receive interrupts: `IM` 0x038 (RXIM bit 4: FIFO at its trigger
//! level, RTIM bit 6: bytes waiting below it), `ICR` 0x044 (write 1 to clear); UART0 is NVIC
//! line 5 (data sheet, "Interrupts" table).
//!
//! QEMU notes: the PL011 receives from reset, before `CTL` enables it (one byte without FIFO);
//! changing `LCRH.FEN` resets the receive FIFO, so at most one byte that arrived before
//! `take` is lost. With the FIFO on, QEMU holds 16 bytes and leaves the rest in the chardev
//! (TCP socket / pty) until the firmware reads: nothing is lost afterwards, whatever the host's
//! pace.

use super::{Polled, claim, rd, wr};

const BASE: usize = 0x4000_C000;
const DR: usize = BASE;
const FR: usize = BASE + 0x18;
const IBRD: usize = BASE + 0x24;
const FBRD: usize = BASE + 0x28;
const LCRH: usize = BASE + 0x2C;
const CTL: usize = BASE + 0x30;
const IM: usize = BASE + 0x38;
const ICR: usize = BASE + 0x44;

const FR_BUSY: u32 = 1 << 3;
const FR_RXFE: u32 = 1 << 4;
const FR_TXFF: u32 = 1 << 5;
const LCRH_FEN: u32 = 1 << 4;
const LCRH_WLEN_8: u32 = 0b11 << 5;
const CTL_UARTEN: u32 = 1 << 0;
const CTL_TXE: u32 = 1 << 8;
const CTL_RXE: u32 = 1 << 9;
/// Receive (FIFO at its trigger level) and receive-timeout interrupts.
const INT_RX_RT: u32 = (1 << 4) | (1 << 6);

const SYSCTL_RCGC1: usize = 0x400F_E104;
const SYSCTL_RCGC2: usize = 0x400F_E108;
const GPIOA_AFSEL: usize = 0x4000_4420;
const GPIOA_DEN: usize = 0x4000_451C;
/// PA0 = U0Rx, PA1 = U0Tx.
const PA0_PA1: u32 = 0b11;

/// UART0 of the LM3S6965 (QEMU `lm3s6965evb`), polled, 8N1, FIFOs on.
pub struct Lm3sUart0 {
    _private: (),
}

impl Lm3sUart0 {
    /// The UART clock the serial nodes pass to [`Lm3sUart0::take`]: the LM3S6965's 12 MHz
    /// internal oscillator after reset (QEMU ignores it; a real board switches to the crystal
    /// or the PLL first and passes that frequency, see README.md).
    pub const RESET_CLOCK_HZ: u32 = 12_000_000;

    /// Configures UART0 for `baud` from a UART clock of `clock_hz` (the system clock), and
    /// returns it; `None` if it was taken before.
    ///
    /// After reset the LM3S6965 runs from its 12 MHz internal oscillator (±30 %: too coarse
    /// for a UART); a real board first switches to the crystal or the PLL and passes that
    /// frequency. QEMU ignores the divisor.
    pub fn take(clock_hz: u32, baud: u32) -> Option<Self> {
        if !claim() {
            return None;
        }
        wr(SYSCTL_RCGC1, rd(SYSCTL_RCGC1) | 1);
        wr(SYSCTL_RCGC2, rd(SYSCTL_RCGC2) | 1);
        // Three clocks must pass after enabling a peripheral clock: read it back.
        let _ = rd(SYSCTL_RCGC2);
        wr(GPIOA_AFSEL, rd(GPIOA_AFSEL) | PA0_PA1);
        wr(GPIOA_DEN, rd(GPIOA_DEN) | PA0_PA1);

        wr(CTL, 0);
        // 64 · clock / (16 · baud), rounded: the integer part in IBRD, 6 fraction bits in FBRD.
        let div = (clock_hz.saturating_mul(4).saturating_add(baud / 2)) / baud.max(1);
        wr(IBRD, div >> 6);
        wr(FBRD, div & 0x3f);
        wr(LCRH, LCRH_WLEN_8 | LCRH_FEN);
        wr(CTL, CTL_UARTEN | CTL_TXE | CTL_RXE);
        wr(IM, INT_RX_RT);
        super::enable_rx_wakeup(Self::RX_IRQ);
        Some(Lm3sUart0 { _private: () })
    }
}

impl Polled for Lm3sUart0 {
    const RX_IRQ: u16 = 5;

    fn rx_irq_clear() {
        wr(ICR, INT_RX_RT);
    }

    fn rx_ready() -> bool {
        rd(FR) & FR_RXFE == 0
    }

    // The error flags (bits 8-11) are dropped with the data register read.
    fn rx() -> u8 {
        rd(DR) as u8
    }

    fn tx(byte: u8) {
        while rd(FR) & FR_TXFF != 0 {}
        wr(DR, u32::from(byte));
    }

    fn tx_busy() -> bool {
        rd(FR) & FR_BUSY != 0
    }
}
