//! Target-side plumbing shared by the node images.
//!
//! [`check`] replays a scenario on the MCU, compares every decision word with the table the
//! host computed in `build.rs`, prints a one-line summary over semihosting and exits QEMU with
//! `EXIT_SUCCESS` only if every word matched. It also measures the peak stack use (the stack is
//! painted before the run and scanned afterwards).
//!
//! Self-test of the check: run an image with the semihosting argument `corrupt`
//! (`-semihosting-config enable=on,target=native,arg=corrupt`); the checker then flips one bit
//! of one expected word, and the image must exit with failure.
#![no_std]

use core::ptr::addr_of;
use cortex_m_rt::{ExceptionFrame, exception};
use cortex_m_semihosting::{debug, hprintln, nr};
use fw_scenario::Sink;

/// The pattern painted over the free stack.
const PAINT: u32 = 0xC0FF_EE55;
/// How far below the stack pointer at start-up the stack is painted (bytes). Must exceed the
/// deepest stack use of a scenario; if the peak reaches it, the report says so.
const PAINT_WINDOW: usize = 32 * 1024;

unsafe extern "C" {
    /// End of the statics (.data/.bss/.uninit): the stack must never reach it (cortex-m-rt).
    static _stack_end: u32;
    /// Initial stack pointer: the end of RAM (cortex-m-rt).
    static _stack_start: u32;
}

/// Compares the stream of decision words with the expected table.
pub struct Checker<'a> {
    expected: &'a [u32],
    index: usize,
    mismatches: usize,
    first: Option<(usize, u32, u32)>,
    /// Index of the expected word to corrupt (self-test), or `usize::MAX`.
    flip: usize,
}

impl Sink for Checker<'_> {
    #[inline(never)]
    fn put(&mut self, w: u32) {
        let want = self.expected.get(self.index).map(|&e| if self.index == self.flip { e ^ 1 } else { e });
        if want != Some(w) {
            self.mismatches += 1;
            if self.first.is_none() {
                self.first = Some((self.index, w, want.unwrap_or(0)));
            }
        }
        self.index += 1;
    }
}

/// Runs `scenario` against `expected` and exits QEMU: success only if the scenario produced
/// exactly `expected.len()` words, all bit-identical to the host's.
pub fn check(name: &str, expected: &[u32], scenario: impl FnOnce(&mut Checker<'_>)) -> ! {
    let window = paint_stack();
    let flip = if cmdline_has(b"corrupt") { expected.len() / 2 } else { usize::MAX };
    let mut c = Checker { expected, index: 0, mismatches: 0, first: None, flip };
    scenario(&mut c);
    let (peak, capped) = stack_peak(window);
    let cap = if capped { ">=" } else { "" };
    let n = expected.len();
    let ok = c.mismatches == 0 && c.index == n;
    if ok {
        hprintln!("{}: PASS {}/{} decision words bit-identical to the host (stack peak {}{} B)", name, c.index, n, cap, peak);
    } else {
        hprintln!(
            "{}: FAIL {} mismatching of {} words produced, {} expected (stack peak {}{} B)",
            name, c.mismatches, c.index, n, cap, peak
        );
        if let Some((i, got, want)) = c.first {
            hprintln!("{}: first mismatch at word {}: device {:#010x}, host {:#010x}", name, i, got, want);
        }
        if flip != usize::MAX {
            hprintln!("{}: (self-test: expected word {} was corrupted on purpose)", name, flip);
        }
    }
    exit(ok)
}

/// Exits QEMU through semihosting with success or failure.
pub fn exit(ok: bool) -> ! {
    debug::exit(if ok { debug::EXIT_SUCCESS } else { debug::EXIT_FAILURE });
    // Not reached under QEMU; on real hardware without a debugger, park.
    loop {
        cortex_m::asm::wfi();
    }
}

/// True if the semihosting command line (QEMU: the `arg=` values of `-semihosting-config`)
/// contains `needle`.
fn cmdline_has(needle: &[u8]) -> bool {
    let mut buf = [0u8; 96];
    // SYS_GET_CMDLINE: block = {buffer address, buffer length}; the host writes the length used.
    let mut block = [buf.as_mut_ptr() as usize, buf.len()];
    // SAFETY: a valid semihosting operation with a writable block and buffer that outlive it.
    let rc = unsafe { cortex_m_semihosting::syscall1(nr::GET_CMDLINE, block.as_mut_ptr() as usize) };
    if rc != 0 {
        return false;
    }
    // SAFETY: `block` is a live local; the volatile read sees the host's write.
    let len = unsafe { core::ptr::read_volatile(&block[1]) }.min(buf.len());
    let line = &buf[..len];
    line.windows(needle.len()).any(|w| w == needle)
}

/// Paints the free stack below the current frame; returns the lowest painted address.
#[inline(never)]
fn paint_stack() -> usize {
    let here = 0u32;
    let sp = core::hint::black_box(addr_of!(here)) as usize;
    let floor = addr_of!(_stack_end) as usize;
    let lo = floor.max(sp.saturating_sub(PAINT_WINDOW)) & !3;
    let hi = sp.saturating_sub(64) & !3;
    let mut p = lo;
    while p < hi {
        // SAFETY: [lo, hi) lies between the end of the statics and this frame's stack pointer
        // (minus a margin): free stack that nothing is using.
        unsafe { (p as *mut u32).write_volatile(PAINT) };
        p += 4;
    }
    lo
}

/// Peak stack use in bytes (from the initial stack pointer), and whether it reached the painted
/// window's floor (then the true peak may be higher).
fn stack_peak(lo: usize) -> (usize, bool) {
    let top = addr_of!(_stack_start) as usize;
    let mut p = lo;
    // SAFETY: reading the painted region, which is RAM.
    while p < top && unsafe { (p as *const u32).read_volatile() } == PAINT {
        p += 4;
    }
    (top - p, p == lo)
}

#[panic_handler]
fn panic(info: &core::panic::PanicInfo<'_>) -> ! {
    if let Some(l) = info.location() {
        hprintln!("PANIC at {}:{}", l.file(), l.line());
    } else {
        hprintln!("PANIC");
    }
    exit(false)
}

#[exception]
unsafe fn HardFault(ef: &ExceptionFrame) -> ! {
    hprintln!("HARD FAULT at pc {:#010x}", ef.pc());
    exit(false)
}
