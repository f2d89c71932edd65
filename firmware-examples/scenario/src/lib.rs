//! The fixed scenarios replayed by the firmware images.
//!
//! The same code runs twice: on the host, inside the node crates' `build.rs` (a
//! build-dependency with the same `swarm-core` features), where it records every decision word
//! into an `expected_*.rs` table; and on the MCU, where the firmware recomputes the decisions and
//! compares each word with the table, bit for bit.
//!
//! A "decision word" is a `u32`: the raw bits of a scalar (`f32::to_bits`, `Fx::to_bits`) or a
//! small integer code (motion state, label, error kind). Words are produced in a fixed order, so
//! a mismatch index names the step, agent and field (see each scenario's docs).
#![cfg_attr(not(feature = "std"), no_std)]
#![forbid(unsafe_code)]

use swarm_core::{Error, Scalar, Vec2, Vec3};

/// Re-exported for the build scripts (the scalar types).
pub use swarm_core;

/// Host tests of a check generic over the scalar: `#[test] fn $f32()` runs `$check::<f32>()`
/// and, with feature `fixed`, `#[test] fn $fx()` runs `$check::<Fx>()`.
#[cfg(all(test, feature = "std"))]
macro_rules! scalar_tests {
    ($check:ident, $f32:ident, $fx:ident) => {
        #[test]
        fn $f32() {
            $check::<f32>();
        }

        #[cfg(feature = "fixed")]
        #[test]
        fn $fx() {
            $check::<swarm_core::Fx>();
        }
    };
}

pub mod ant;
pub mod bee;
pub mod fly;
#[cfg(feature = "std")]
pub mod host;

/// A scalar whose raw bits can be recorded.
pub trait Word: Scalar {
    /// The raw bits as a `u32` (`f32::to_bits`, or the two's-complement `i32` of an `Fx`).
    fn word(self) -> u32;
}

impl Word for f32 {
    #[inline]
    fn word(self) -> u32 {
        self.to_bits()
    }
}

#[cfg(feature = "fixed")]
impl Word for swarm_core::Fx {
    #[inline]
    fn word(self) -> u32 {
        self.to_bits() as u32
    }
}

/// Where decision words go: the host records them, the firmware compares them.
pub trait Sink {
    /// One decision word.
    fn put(&mut self, w: u32);

    /// A scalar's bits.
    #[inline]
    fn scalar<S: Word>(&mut self, v: S) {
        self.put(v.word());
    }
    /// A 2-vector's bits, x then y.
    #[inline]
    fn vec2<S: Word>(&mut self, v: Vec2<S>) {
        self.put(v.x.word());
        self.put(v.y.word());
    }
    /// A 3-vector's bits, x, y, z.
    #[inline]
    fn vec3<S: Word>(&mut self, v: Vec3<S>) {
        self.put(v.x.word());
        self.put(v.y.word());
        self.put(v.z.word());
    }
    /// A controller call's result: its value, or `None` once its error is emitted.
    #[inline]
    fn decided<T>(&mut self, r: swarm_core::Result<T>) -> Option<T> {
        r.map_err(|e| self.error(&e)).ok()
    }
    /// A controller error, as a marker word followed by a code for its kind and its list index.
    fn error(&mut self, e: &Error) {
        self.put(ERROR_MARKER);
        let (kind, index) = match *e {
            Error::NonFinite { index, .. } => (1, index),
            Error::OutOfRange { index, .. } => (2, index),
            Error::Inconsistent { index, .. } => (3, index),
            Error::BadParam { .. } => (4, None),
            _ => (0xff, None),
        };
        self.put(kind << 16 | index.map_or(0xffff, u32::from));
    }
}

/// The word that announces a controller error in the stream (then one word: kind << 16 | index).
pub const ERROR_MARKER: u32 = 0xE000_0E00;

impl<F: FnMut(u32)> Sink for F {
    #[inline]
    fn put(&mut self, w: u32) {
        self(w)
    }
}

/// Times one block of code (the `*-cycles` images: `fw_support::cycles::SysTickMeter`).
///
/// [`ant::cost`] and [`bee::cost`] call the controllers through a meter, one call per timed
/// block, with the sensor frame built beforehand, so only the controller call is timed.
pub trait Meter {
    /// Runs `f(input)` once and returns its result and what it took, in the meter's ticks,
    /// the meter's own overhead (an empty block) subtracted. Pass references in `input`:
    /// an implementation hides `input` behind an optimisation barrier after its first clock
    /// reading, so no work of `f` can be hoisted out of the timed region.
    fn measure<I, R>(&mut self, input: I, f: impl FnOnce(I) -> R) -> (R, u32);
}

/// Count, minimum, maximum and sum of a series of measurements (ticks).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Stats {
    /// Measurements taken.
    pub n: u32,
    /// The smallest (`u32::MAX` while `n == 0`).
    pub min: u32,
    /// The largest.
    pub max: u32,
    /// Their sum (the mean is `sum / n`).
    pub sum: u64,
}

impl Stats {
    /// No measurement yet.
    pub const EMPTY: Stats = Stats {
        n: 0,
        min: u32::MAX,
        max: 0,
        sum: 0,
    };

    /// Adds one measurement.
    pub fn add(&mut self, v: u32) {
        self.n += 1;
        self.min = self.min.min(v);
        self.max = self.max.max(v);
        self.sum += u64::from(v);
    }
}

impl Default for Stats {
    fn default() -> Self {
        Stats::EMPTY
    }
}

/// A deterministic value in `[lo, hi)` from the scenario's own counter-based hash (used to
/// scatter the initial world; the controllers draw their own randomness from `StepCtx`).
pub fn uniform<S: Scalar>(key: u32, salt: u32, lo: f32, hi: f32) -> S {
    let u: S = S::unit_open(swarm_core::rand::rand(0x5eed_f1e1, key, salt, 0xfe));
    S::from_f32(lo) + u * S::from_f32(hi - lo)
}
