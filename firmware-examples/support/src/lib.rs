//! Target-side plumbing shared by the node images.
//!
//! * [`uart`]: polled `embedded-io` UART drivers for the two QEMU boards (the serial nodes,
//!   `ant-node`, `bee-node`, `fly-node` and their `-fixed` variants, serve `fw_node::run` over
//!   them);
//! * [`node_handlers!`]: the panic and HardFault handlers of a serial node (reset the MCU: the
//!   host sees `NoSession` and handshakes again);
//! * [`check`] and [`selfcheck_handlers!`]: the self-check images (`*-selfcheck`). [`check`]
//!   replays a scenario on the MCU, compares every decision word with the table the host
//!   computed in `build.rs`, prints a one-line summary over semihosting and exits QEMU with
//!   `EXIT_SUCCESS` only if every word matched. It also measures the peak stack use (the stack
//!   is painted before the run and scanned afterwards);
//! * [`paint_stack`]: the serial nodes paint the stack too, so a debugger or QEMU's monitor
//!   can read the peak afterwards (`scripts/qemu-serial.sh --stack`);
//! * [`cycles`]: the measurement images (`*-cycles`): the controllers timed call by call with
//!   SysTick, for instruction counts under QEMU's `-icount` (`scripts/qemu-cycles.sh`).
//!
//! Self-test of the check: run a self-check image with the semihosting argument `corrupt`
//! (`-semihosting-config enable=on,target=native,arg=corrupt`); the checker then flips one bit
//! of one expected word, and the image must exit with failure.
#![no_std]

use core::ptr::addr_of;
use cortex_m_rt::ExceptionFrame;
use cortex_m_semihosting::{debug, hio, nr};
use fw_scenario::Sink;

pub mod cycles;
pub mod mem;
pub mod uart;

#[cfg(all(feature = "lm3s6965evb", feature = "mps2-an386"))]
compile_error!("fw-support: pick one board feature, `lm3s6965evb` or `mps2-an386`");

/// Device interrupt lines of the board's NVIC (QEMU's `num-irq`): what a full table holds.
#[cfg(feature = "lm3s6965evb")]
pub const IRQS: usize = 80;
/// Device interrupt lines of the board's NVIC (QEMU's `num-irq`): what a full table holds.
#[cfg(feature = "mps2-an386")]
pub const IRQS: usize = 48;
#[cfg(not(any(feature = "lm3s6965evb", feature = "mps2-an386")))]
compile_error!("fw-support: enable a board feature, `lm3s6965evb` or `mps2-an386`");

unsafe extern "C" {
    /// cortex-m-rt's default handler (it loops; the images take no interrupt).
    fn DefaultHandler();
}

/// Entries in the device part of the vector table. The images take no device interrupt (the
/// UARTs are polled; their receive line only wakes `WFI`, with PRIMASK set, see [`uart`]), so
/// they carry only the one entry cortex-m-rt's linker script insists on instead of all
/// [`IRQS`]: 4 bytes of flash instead of 320 (lm3s6965evb) or 192 (mps2-an386). No other entry
/// is ever read. An image that takes device interrupt `n` needs `n + 1` entries here (a
/// peripheral access crate provides the whole table, with named handlers).
pub const VECTORS: usize = 1;
const _: () = assert!(VECTORS >= 1 && VECTORS <= IRQS);

/// The device part of the vector table (cortex-m-rt feature `device`; a board support crate
/// would provide this with named handlers). Every line goes to the default handler.
#[unsafe(link_section = ".vector_table.interrupts")]
#[unsafe(no_mangle)]
#[used]
pub static __INTERRUPTS: [unsafe extern "C" fn(); VECTORS] = [DefaultHandler; VECTORS];

/// The pattern painted over the free stack.
pub const PAINT: u32 = 0xC0FF_EE55;
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
        let want = self
            .expected
            .get(self.index)
            .map(|&e| if self.index == self.flip { e ^ 1 } else { e });
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
    let flip = if cmdline_has(b"corrupt") {
        expected.len() / 2
    } else {
        usize::MAX
    };
    let mut c = Checker {
        expected,
        index: 0,
        mismatches: 0,
        first: None,
        flip,
    };
    scenario(&mut c);
    let (peak, capped) = stack_peak(window);
    let n = expected.len();
    let ok = c.mismatches == 0 && c.index == n;
    let mut l = Line::new();
    l.str(name);
    if ok {
        l.str(": PASS ").dec(c.index).str("/").dec(n);
        l.str(" decision words bit-identical to the host");
    } else {
        l.str(": FAIL ")
            .dec(c.mismatches)
            .str(" mismatching of ")
            .dec(c.index);
        l.str(" words produced, ").dec(n).str(" expected");
    }
    l.str(" (stack peak ")
        .str(if capped { ">=" } else { "" })
        .dec(peak)
        .str(" B)")
        .print();
    if let Some((i, got, want)) = c.first {
        let mut l = Line::new();
        l.str(name).str(": first mismatch at word ").dec(i);
        l.str(": device ").hex(got).str(", host ").hex(want).print();
    }
    if flip != usize::MAX {
        let mut l = Line::new();
        l.str(name)
            .str(": (self-test: expected word ")
            .dec(flip)
            .str(" was corrupted on purpose)")
            .print();
    }
    exit(ok)
}

/// Exits QEMU through semihosting with success or failure.
pub fn exit(ok: bool) -> ! {
    debug::exit(if ok {
        debug::EXIT_SUCCESS
    } else {
        debug::EXIT_FAILURE
    });
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
    let rc =
        unsafe { cortex_m_semihosting::syscall1(nr::GET_CMDLINE, block.as_mut_ptr() as usize) };
    if rc != 0 {
        return false;
    }
    // SAFETY: `block` is a live local; the volatile read sees the host's write.
    let len = unsafe { core::ptr::read_volatile(&block[1]) }.min(buf.len());
    let line = &buf[..len];
    line.windows(needle.len()).any(|w| w == needle)
}

/// Paints the free stack below the current frame with [`PAINT`] (at most 32 KiB below it, never
/// into the statics); returns the lowest painted address. The peak use is then the distance
/// from the top of RAM (`_stack_start`) to the lowest word that no longer holds [`PAINT`].
#[inline(never)]
pub fn paint_stack() -> usize {
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

/// Prints a panic's location over semihosting and exits QEMU with failure (the self-check
/// images' panic handler, see [`selfcheck_handlers!`]).
pub fn report_panic(info: &core::panic::PanicInfo<'_>) -> ! {
    let mut l = Line::new();
    l.str("PANIC");
    if let Some(loc) = info.location() {
        l.str(" at ")
            .str(loc.file())
            .str(":")
            .dec(loc.line() as usize);
    }
    l.print();
    exit(false)
}

/// Prints the faulting PC over semihosting and exits QEMU with failure (the self-check images'
/// HardFault handler, see [`selfcheck_handlers!`]).
pub fn report_hard_fault(ef: &ExceptionFrame) -> ! {
    Line::new().str("HARD FAULT at pc ").hex(ef.pc()).print();
    exit(false)
}

/// Resets the MCU (`SCB.AIRCR.SYSRESETREQ`): a serial node's answer to a panic or a fault. QEMU
/// restarts the image (unless started with `-no-reboot`, then it exits).
pub fn reset() -> ! {
    cortex_m::peripheral::SCB::sys_reset()
}

/// Names the macros below use, whatever the binary names its dependencies.
#[doc(hidden)]
pub mod __private {
    pub use fw_scenario;
}

/// Writes a serial node image (`ant-node`, `bee-node`, `fly-node`, their `-fixed` and `-other`
/// variants): the handlers of [`node_handlers!`] and a `main` that paints the stack, takes the
/// board's UART0 ([`uart::take_uart0`]), builds the device with `$device` (a
/// `swarm_core::Result<DeviceEndpoint<..>>`, e.g. `fw_node::ant_device::<f32>("ant-node")`)
/// and serves it with `fw_node::run` forever. A UART taken before or a device error resets the
/// MCU. The binary depends on `cortex-m-rt` and `fw-node`. Use once, at the top level.
#[macro_export]
macro_rules! serial_node {
    ($device:expr) => {
        $crate::node_handlers!();

        #[cortex_m_rt::entry]
        fn main() -> ! {
            $crate::paint_stack();
            let Some(mut uart) = $crate::uart::take_uart0() else {
                $crate::reset()
            };
            let Ok(mut device) = ($device) else {
                $crate::reset()
            };
            device.set_rx_buffer($crate::uart::RX_FIFO);
            fw_node::run(&mut device, &mut uart)
        }
    };
}

/// Writes a self-check image (`*-selfcheck`): the handlers of [`selfcheck_handlers!`], the
/// expected table the node's `build.rs` wrote for the scalar (`OUT_DIR/expected_f32.rs` or
/// `expected_fixed.rs`), and a `main` that runs [`check`] labelled `$name` over
/// `fw_scenario::$model::run` (`$model`: `ant`, `bee` or `fly`; `$scalar`: `f32` or `Fx`). The
/// binary depends on `cortex-m-rt`. Use once, at the top level.
#[macro_export]
macro_rules! selfcheck_image {
    ($name:literal, $model:ident, f32) => {
        $crate::selfcheck_image!(@ $name, $model, f32, "/expected_f32.rs");
    };
    ($name:literal, $model:ident, Fx) => {
        $crate::selfcheck_image!(
            @ $name, $model, $crate::__private::fw_scenario::swarm_core::Fx, "/expected_fixed.rs"
        );
    };
    (@ $name:literal, $model:ident, $scalar:ty, $table:literal) => {
        $crate::selfcheck_handlers!();

        include!(concat!(env!("OUT_DIR"), $table));

        #[cortex_m_rt::entry]
        fn main() -> ! {
            $crate::check($name, &EXPECTED, |c| {
                $crate::__private::fw_scenario::$model::run::<$scalar>(c)
            })
        }
    };
}

/// Defines the panic and HardFault handlers of a self-check image: print over semihosting,
/// exit QEMU with failure. Use once, at the top level of the binary.
#[macro_export]
macro_rules! selfcheck_handlers {
    () => {
        #[panic_handler]
        fn panic(info: &core::panic::PanicInfo<'_>) -> ! {
            $crate::report_panic(info)
        }

        #[cortex_m_rt::exception]
        unsafe fn HardFault(ef: &cortex_m_rt::ExceptionFrame) -> ! {
            $crate::report_hard_fault(ef)
        }
    };
}

/// Defines the panic and HardFault handlers of a serial node: [`reset`] (no semihosting: a
/// node runs without a debugger). Use once, at the top level of the binary.
#[macro_export]
macro_rules! node_handlers {
    () => {
        #[panic_handler]
        fn panic(_: &core::panic::PanicInfo<'_>) -> ! {
            $crate::reset()
        }

        #[cortex_m_rt::exception]
        unsafe fn HardFault(_: &cortex_m_rt::ExceptionFrame) -> ! {
            $crate::reset()
        }
    };
}

/// A line of text for the semihosting console, built without `core::fmt` (which would cost
/// a few KiB of flash): strings, decimal and hex numbers; silently truncated when full
/// (`CAP` bytes, the newline included).
pub struct Line<const CAP: usize = 160> {
    buf: [u8; CAP],
    len: usize,
}

impl Line {
    /// An empty line of the default capacity (160 bytes).
    pub const fn new() -> Self {
        Line::with_capacity()
    }
}

impl<const CAP: usize> Line<CAP> {
    /// An empty line of capacity `CAP`.
    pub const fn with_capacity() -> Self {
        Line {
            buf: [0; CAP],
            len: 0,
        }
    }

    /// Appends bytes (panic-free: no bounds-check failure path, so no `core::fmt` either).
    fn bytes(&mut self, b: &[u8]) -> &mut Self {
        for (dst, &src) in self.buf.iter_mut().skip(self.len).zip(b) {
            *dst = src;
            self.len += 1;
        }
        self
    }

    /// Appends a string.
    pub fn str(&mut self, s: &str) -> &mut Self {
        self.bytes(s.as_bytes())
    }

    /// Appends a number (`usize` or `u64`) in decimal.
    pub fn dec<T: Decimal>(&mut self, v: T) -> &mut Self {
        let mut d = [0u8; 20];
        let mut n = 0;
        let mut v = v;
        for slot in d.iter_mut() {
            let (rest, digit) = v.div10();
            *slot = b'0' + digit;
            n += 1;
            v = rest;
            if v.is_zero() {
                break;
            }
        }
        for &c in d.iter().take(n).rev() {
            self.bytes(&[c]);
        }
        self
    }

    /// Appends a 32-bit word as `0x` and eight hex digits.
    pub fn hex(&mut self, v: u32) -> &mut Self {
        let mut d = *b"0x00000000";
        for (k, c) in d[2..].iter_mut().enumerate() {
            let nib = ((v >> (28 - 4 * k)) & 0xf) as u8;
            *c = if nib < 10 {
                b'0' + nib
            } else {
                b'a' + nib - 10
            };
        }
        self.bytes(&d)
    }

    /// Writes the line and a newline to the host's stdout (semihosting).
    pub fn print(&mut self) {
        self.bytes(b"\n");
        if let Ok(mut out) = hio::hstdout() {
            let _ = out.write_all(self.buf.get(..self.len).unwrap_or(&self.buf));
        }
    }
}

/// An unsigned integer [`Line::dec`] prints (at most 20 digits).
pub trait Decimal: Copy {
    /// `self / 10` and the last digit, `self % 10`.
    fn div10(self) -> (Self, u8);
    /// `self == 0`.
    fn is_zero(self) -> bool;
}

macro_rules! decimal {
    ($($t:ty),*) => {$(
        impl Decimal for $t {
            #[inline(always)]
            fn div10(self) -> (Self, u8) {
                (self / 10, (self % 10) as u8)
            }

            #[inline(always)]
            fn is_zero(self) -> bool {
                self == 0
            }
        }
    )*};
}

decimal!(usize, u64);

impl Default for Line {
    fn default() -> Self {
        Line::new()
    }
}
