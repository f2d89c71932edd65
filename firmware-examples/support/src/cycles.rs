//! The measurement images (`ant-node-cycles`, `bee-node-cycles`, `fly-node-cycles` and their
//! `-fixed` variants):
//! what one controller step costs on the emulated core, in instructions.
//!
//! # What is measured
//!
//! `fw_scenario::ant::cost`, `fw_scenario::bee::cost` and `fw_scenario::fly::cost` call the
//! controllers the way a serial node does per request (`ant::plan_checked`,
//! `ant::resolve_checked`, `bee::step_checked`, `fly::step_checked` with parameters validated
//! once; input validation included; no UART, no decoding or
//! encoding), a few hundred times over varied frames, and time every call with a
//! [`SysTickMeter`]. The images are built with the same release profile and the same
//! `fw-support` memory routines as the serial nodes.
//!
//! # How
//!
//! SysTick counts the processor clock (`SYST_CSR.CLKSOURCE = 1`) down from
//! `SYST_RVR = 0xFF_FFFF`, with no interrupt. A timed block passes its input (references to
//! the state and the frame) through an optimisation barrier, reads `SYST_CVR`, passes the input
//! through a barrier again, runs the call, passes the result through a barrier and reads
//! `SYST_CVR` again; the difference (modulo 2^24) less the overhead of an empty block
//! (the smallest of 16, measured at start-up) is the block's count of ticks. `SYST_CSR` is
//! read before and after each block (outside it): a `COUNTFLAG` with no visible wrap means the
//! block took 2^24 ticks or more, which is counted as an overflow and fails the run.
//!
//! Under QEMU with `-icount shift=S`, virtual time advances by exactly 2^S ns per guest
//! instruction, and QEMU's SysTick counts that virtual time at the board's system clock
//! ([`clock_hz`]), so `instructions = ticks × (10^9 / clock_hz) / 2^S`. The image prints
//! ticks and its clock; `scripts/qemu-cycles.sh` knows S and converts. The image also times
//! two hand-counted loops of `N1` and `N2` iterations ([`spin2`]: 2 instructions an
//! iteration, [`spin4`]: 4), so the script can check the conversion independently:
//! `ticks(N2) − ticks(N1)`, converted, must be `2 (N2 − N1)` (resp. `4 (N2 − N1)`)
//! instructions.
//!
//! It also probes the DWT cycle counter (`DEMCR.TRCENA`, `DWT_CTRL.CYCCNTENA`, then
//! `DWT_CYCCNT` read around a counted loop) and prints what it saw: QEMU 7.2 does not
//! emulate it (`DWT_CTRL` reads 0 after the enable, `DWT_CYCCNT` does not advance).
//!
//! # Output
//!
//! One line over semihosting, `cycles key=value ...`, then QEMU exits over semihosting:
//! success only if every controller call returned a decision and no block overflowed.
//! Values `n:min:max:sum` are [`Stats`] in ticks; `spin2=N1:T1,N2:T2` the loop timings.

use crate::{Line, exit};
use core::hint::black_box;
use cortex_m::peripheral::{DWT, SYST, syst::SystClkSource};
use fw_scenario::ant::AntCost;
use fw_scenario::bee::BeeCost;
use fw_scenario::fly::FlyCost;
use fw_scenario::{Meter, Stats};

/// The SysTick counter's mask (a 24-bit down-counter).
const MASK: u32 = 0xFF_FFFF;
/// `SYST_CSR.COUNTFLAG`.
const COUNTFLAG: u32 = 1 << 16;
/// Iterations of the calibration loops: the difference of the two is what is checked.
pub const SPIN: [u32; 2] = [1_000, 11_000];

/// The frequency SysTick counts with `CLKSOURCE = 1` on QEMU's `lm3s6965evb`: its system
/// clock, which QEMU 7.2 (`hw/arm/stellaris.c`, `ssys_calculate_system_clock`) derives from
/// SYSCTL's RCC (or RCC2 when `RCC2.USERCC2` is set) as 200 MHz / (SYSDIV + 1), ignoring
/// BYPASS and USESYSDIV. After reset RCC = 0x078E_3AC0 (SYSDIV = 15): 12.5 MHz. (A real
/// LM3S6965 runs from its 12 MHz internal oscillator after reset.)
#[cfg(feature = "lm3s6965evb")]
pub fn clock_hz() -> u32 {
    const RCC: *const u32 = 0x400F_E060 as *const u32;
    const RCC2: *const u32 = 0x400F_E070 as *const u32;
    // SAFETY: SYSCTL's RCC and RCC2 registers, always readable on this board.
    let (rcc, rcc2) = unsafe { (RCC.read_volatile(), RCC2.read_volatile()) };
    let sysdiv = if rcc2 >> 31 != 0 {
        (rcc2 >> 23) & 0x3f
    } else {
        (rcc >> 23) & 0xf
    };
    200_000_000 / (sysdiv + 1)
}

/// The frequency SysTick counts with `CLKSOURCE = 1` on QEMU's `mps2-an386`: the board's
/// fixed 25 MHz SYSCLK (QEMU 7.2 `hw/arm/mps2.c`, `SYSCLK_FRQ`, wired to the CPU's `cpuclk`).
#[cfg(feature = "mps2-an386")]
pub fn clock_hz() -> u32 {
    25_000_000
}

/// Times blocks of code with SysTick (see the module docs).
pub struct SysTickMeter {
    overhead: u32,
    overflows: u32,
}

impl SysTickMeter {
    /// Starts SysTick on the processor clock, reload 0xFF_FFFF, no interrupt, and measures the
    /// overhead of an empty block with an input of two references, as the cost runs pass
    /// (the smallest of 16).
    pub fn start(syst: &mut SYST) -> Self {
        syst.disable_interrupt();
        syst.set_clock_source(SystClkSource::Core);
        syst.set_reload(MASK);
        syst.clear_current();
        syst.enable_counter();
        let mut m = SysTickMeter {
            overhead: 0,
            overflows: 0,
        };
        let (a, b) = (0u32, 0u32);
        let mut least = u32::MAX;
        for _ in 0..16 {
            least = least.min(m.measure((&a, &b), |_| ()).1);
        }
        m.overhead = least;
        m
    }

    /// The overhead subtracted from every block (ticks).
    pub fn overhead(&self) -> u32 {
        self.overhead
    }

    /// Blocks that took 2^24 ticks or more (their counts are wrong).
    pub fn overflows(&self) -> u32 {
        self.overflows
    }
}

/// `SYST_CSR` (reading it clears `COUNTFLAG`).
#[inline(always)]
fn csr() -> u32 {
    // SAFETY: a read of SysTick's control and status register.
    unsafe { (*SYST::PTR).csr.read() }
}

impl Meter for SysTickMeter {
    #[inline(always)]
    fn measure<I, R>(&mut self, input: I, f: impl FnOnce(I) -> R) -> (R, u32) {
        // The inputs are complete in memory before the first reading (a barrier before it)
        // and no work on them starts before it (a barrier after it).
        let input = black_box(input);
        let _ = csr();
        let t0 = SYST::get_current();
        let input = black_box(input);
        let r = f(input);
        black_box(&r);
        let t1 = SYST::get_current();
        let wrapped = csr() & COUNTFLAG != 0;
        // A down-counter: t1 > t0 means it went through zero once (or more).
        if wrapped && t1 <= t0 {
            self.overflows += 1;
        }
        let ticks = t0.wrapping_sub(t1) & MASK;
        (r, ticks.saturating_sub(self.overhead))
    }
}

/// Writes `pub fn $name(n: u32)`: a counted loop of `n` iterations (`n` ≥ 1) of the
/// instructions `$op`, then `subs; bne`.
macro_rules! counted_loop {
    ($(#[$doc:meta])* $name:ident: $($op:literal),*) => {
        $(#[$doc])*
        #[inline(never)]
        pub fn $name(n: u32) {
            // SAFETY: register-only arithmetic and a local branch.
            unsafe {
                core::arch::asm!(
                    "2:",
                    $($op,)*
                    "subs {n}, {n}, #1",
                    "bne 2b",
                    n = inout(reg) n.max(1) => _,
                    options(nomem, nostack),
                );
            }
        }
    };
}

counted_loop!(
    /// A counted loop: `n` iterations of `subs; bne`, 2 instructions each (`n` ≥ 1).
    spin2:
);
counted_loop!(
    /// A counted loop: `n` iterations of `nop; nop; subs; bne`, 4 instructions each (`n` ≥ 1).
    spin4: "nop", "nop"
);

/// What the DWT cycle counter showed.
pub struct DwtProbe {
    /// `DWT_CTRL` after enabling the counter (`NOCYCCNT` is bit 25, `CYCCNTENA` bit 0).
    pub ctrl: u32,
    /// `DWT_CYCCNT` after minus before a loop of `2 × SPIN[0]` instructions.
    pub delta: u32,
}

/// Enables the DWT cycle counter (`DEMCR.TRCENA`, `DWT_CTRL.CYCCNTENA`) and reads it around
/// a counted loop.
pub fn probe_dwt(dcb: &mut cortex_m::peripheral::DCB, dwt: &mut DWT) -> DwtProbe {
    dcb.enable_trace();
    dwt.enable_cycle_counter();
    let ctrl = dwt.ctrl.read();
    let c0 = DWT::cycle_count();
    spin2(black_box(SPIN[0]));
    let c1 = DWT::cycle_count();
    DwtProbe {
        ctrl,
        delta: c1.wrapping_sub(c0),
    }
}

/// The line the images print.
pub type Report = Line<512>;

/// Appends ` key=n:min:max:sum`.
pub fn put_stats(l: &mut Report, key: &str, s: &Stats) {
    let min = if s.n == 0 { 0 } else { s.min };
    l.str(" ").str(key).str("=").dec(s.n as usize).str(":");
    l.dec(min as usize).str(":").dec(s.max as usize).str(":");
    l.dec(s.sum);
}

/// Appends an ant run's fields; true if every call returned a decision.
pub fn put_ant(l: &mut Report, c: &AntCost) -> bool {
    put_stats(l, "plan", &c.plan);
    put_stats(l, "resolve", &c.resolve);
    put_stats(l, "step", &c.step);
    put_stats(l, "moving", &c.moving);
    l.str(" neighbours=").dec(c.neighbours as usize);
    l.str(" full_frames=").dec(c.full_frames as usize);
    l.str(" errors=").dec(c.errors as usize);
    c.errors == 0
}

/// Appends a bee run's fields; true if every call returned a decision.
pub fn put_bee(l: &mut Report, c: &BeeCost) -> bool {
    put_stats(l, "step", &c.step);
    l.str(" neighbours=").dec(c.neighbours as usize);
    l.str(" targets=").dec(c.targets as usize);
    l.str(" full_frames=").dec(c.full_frames as usize);
    l.str(" avoiding=").dec(c.avoiding as usize);
    l.str(" errors=").dec(c.errors as usize);
    c.errors == 0
}

/// Appends a fly run's fields; true if every call returned a decision.
pub fn put_fly(l: &mut Report, c: &FlyCost) -> bool {
    put_stats(l, "step", &c.step);
    l.str(" neighbours=").dec(c.neighbours as usize);
    l.str(" surfaces=").dec(c.surfaces as usize);
    l.str(" full_frames=").dec(c.full_frames as usize);
    l.str(" infeasible=").dec(c.infeasible as usize);
    l.str(" errors=").dec(c.errors as usize);
    c.errors == 0
}

/// Runs a measurement image: starts the meter, probes the DWT, times the calibration loops,
/// then `body` (which runs the cost scenario and appends its fields, returning whether every
/// call returned a decision), prints the line and exits QEMU (success only if `body` says so
/// and no block overflowed).
pub fn run(
    image: &str,
    scalar: &str,
    body: impl FnOnce(&mut SysTickMeter, &mut Report) -> bool,
) -> ! {
    let Some(mut cp) = cortex_m::Peripherals::take() else {
        Line::new()
            .str(image)
            .str(": FAIL core peripherals taken")
            .print();
        exit(false)
    };
    let mut m = SysTickMeter::start(&mut cp.SYST);
    let dwt = probe_dwt(&mut cp.DCB, &mut cp.DWT);
    let mut l = Report::with_capacity();
    l.str("cycles image=")
        .str(image)
        .str(" scalar=")
        .str(scalar);
    l.str(" core=")
        .str(CORE)
        .str(" clk_hz=")
        .dec(clock_hz() as usize);
    l.str(" overhead=").dec(m.overhead() as usize);
    l.str(" dwt_ctrl=")
        .hex(dwt.ctrl)
        .str(" dwt_cyccnt=")
        .dec(dwt.delta as usize);
    for (key, spin) in [("spin2", spin2 as fn(u32)), ("spin4", spin4 as fn(u32))] {
        l.str(" ").str(key).str("=");
        for (k, &n) in SPIN.iter().enumerate() {
            let ((), t) = m.measure(n, spin);
            if k > 0 {
                l.str(",");
            }
            l.dec(n as usize).str(":").dec(t as usize);
        }
    }
    let ok = body(&mut m, &mut l);
    l.str(" overflows=").dec(m.overflows() as usize);
    l.print();
    exit(ok && m.overflows() == 0)
}

/// Writes a measurement image (`*-cycles`): the handlers of
/// [`selfcheck_handlers!`](crate::selfcheck_handlers) and a `main` that [`run`]s, as image
/// `$image`, the cost run of `$model` (`ant`: `ant::plan_checked` and `ant::resolve_checked`;
/// `bee`: `bee::step_checked`, `fly`: `fly::step_checked`, with the wire frame capacities) in
/// scalar `$scalar` (`f32` or `Fx`) with the serial node's parameters (`fw_node::ant_params`,
/// `fw_node::bee_params`, `fw_node::fly_params`). The binary depends on `cortex-m-rt` and
/// `fw-node`. Use once, at the top level.
#[macro_export]
macro_rules! cycles_image {
    ($image:literal, $model:ident, f32) => {
        $crate::cycles_image!(@ $image, "f32", $model, f32);
    };
    ($image:literal, $model:ident, Fx) => {
        $crate::cycles_image!(
            @ $image, "I16F16", $model, $crate::__private::fw_scenario::swarm_core::Fx
        );
    };
    (@ $image:literal, $label:literal, ant, $scalar:ty) => {
        // The frames of the timed run have the capacities of the node's wire frames.
        const _: () = {
            use fw_node::swarm_core::wire::{WIRE_ANT_NEIGHBOURS, WIRE_ANT_OBJECTS};
            use $crate::__private::fw_scenario::ant::{N, O};
            assert!(N == WIRE_ANT_NEIGHBOURS && O == WIRE_ANT_OBJECTS);
        };
        $crate::cycles_image!(@@ $image, $label, |meter, line| {
            let Ok(params) = fw_node::ant_params::<$scalar>().checked() else {
                return false;
            };
            let cost = $crate::__private::fw_scenario::ant::cost(&params, meter);
            $crate::cycles::put_ant(line, &cost)
        });
    };
    (@ $image:literal, $label:literal, bee, $scalar:ty) => {
        $crate::cycles_image!(@@ $image, $label, |meter, line| {
            use fw_node::swarm_core::wire::{WIRE_BEE_NEIGHBOURS, WIRE_BEE_TARGETS};
            let Ok(params) = fw_node::bee_params::<$scalar>().checked() else {
                return false;
            };
            let cost = $crate::__private::fw_scenario::bee::cost::<
                $scalar,
                WIRE_BEE_NEIGHBOURS,
                WIRE_BEE_TARGETS,
            >(&params, meter);
            $crate::cycles::put_bee(line, &cost)
        });
    };
    (@ $image:literal, $label:literal, fly, $scalar:ty) => {
        $crate::cycles_image!(@@ $image, $label, |meter, line| {
            use fw_node::swarm_core::fly::{WIRE_FLY_NEIGHBOURS, WIRE_FLY_SURFACES};
            let Ok(params) = fw_node::fly_params::<$scalar>().checked() else {
                return false;
            };
            let cost = $crate::__private::fw_scenario::fly::cost::<
                $scalar,
                WIRE_FLY_NEIGHBOURS,
                WIRE_FLY_SURFACES,
            >(&params, meter);
            $crate::cycles::put_fly(line, &cost)
        });
    };
    (@@ $image:literal, $label:literal, $body:expr) => {
        $crate::selfcheck_handlers!();

        #[cortex_m_rt::entry]
        fn main() -> ! {
            $crate::cycles::run($image, $label, $body)
        }
    };
}

/// The core the image runs on, as QEMU's `-cpu` names it.
#[cfg(feature = "lm3s6965evb")]
const CORE: &str = "cortex-m3";
/// The core the image runs on, as QEMU's `-cpu` names it.
#[cfg(feature = "mps2-an386")]
const CORE: &str = "cortex-m4";
