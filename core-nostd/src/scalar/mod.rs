//! The number type every controller is generic over.
//!
//! Two implementations: `f32` (math from `libm` or `micromath`) and, with feature `fixed`, [`Fx`] (I16F16). Controller
//! code is written once against [`Scalar`]; constants come in through [`Scalar::from_f32`] (for
//! `Fx` a correctly rounded, deterministic conversion).

use core::fmt::Debug;
use core::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};

mod float;
#[cfg(feature = "fixed")]
mod fx;
#[cfg(feature = "fixed")]
pub use fx::{Fx, I16F16};

/// Which number type a controller runs on (carried in the HIL handshake).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ScalarKind {
    /// IEEE-754 binary32.
    F32,
    /// I16F16 fixed point ([`Fx`] with feature `fixed`).
    I16F16,
}

/// Which library computes `f32` transcendental functions (carried in the HIL handshake: two
/// backends give different bits, so they are never compared bit for bit).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum MathBackend {
    /// `libm`: correctly implemented, bit-identical on x86_64 and Cortex-M (soft or hard float).
    Libm,
    /// `micromath`: fast approximations.
    Micromath,
    /// Fixed-point integer math of this crate (for [`ScalarKind::I16F16`]).
    Integer,
}

impl MathBackend {
    /// The f32 backend this build was compiled with.
    pub const F32: MathBackend = if cfg!(feature = "micromath") {
        MathBackend::Micromath
    } else {
        MathBackend::Libm
    };
}

/// A constant in both number types, converted at compile time: what a table of constants
/// shared by every scalar holds (the parameter ranges of [`crate::model`]), so that a device
/// never converts an `f32` at run time. [`Scalar::constant`] gives it in a type.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Constant {
    f32: f32,
    i16f16: i32,
}

impl Constant {
    /// `v` in both types.
    pub const fn new(v: f32) -> Self {
        Constant {
            f32: v,
            i16f16: i16f16_bits(v),
        }
    }
    /// As `f32`.
    pub const fn f32(self) -> f32 {
        self.f32
    }
    /// As I16F16 bits (what `Fx::from_f32` gives).
    pub const fn i16f16_bits(self) -> i32 {
        self.i16f16
    }
}

/// The I16F16 bits of `v`: rounded to the nearest, ties to even, saturating; NaN gives 0 (the
/// conversion of `Fx::from_f32`, equal to the `fixed` crate's `saturating_from_num`, tested).
pub const fn i16f16_bits(v: f32) -> i32 {
    // v · 2^16 is exact (a power-of-two scale), or ±inf, which saturates below.
    let x = v * 65_536.0;
    // Adding and taking away 2^23 rounds |x| < 2^23 to an integer, ties to even (IEEE 754
    // round-to-nearest); larger magnitudes are integers already.
    const BIG: f32 = 8_388_608.0;
    let r = if x >= 0.0 && x < BIG {
        (x + BIG) - BIG
    } else if x < 0.0 && x > -BIG {
        -((-x + BIG) - BIG)
    } else {
        x
    };
    // `as` saturates at the i32 range and maps NaN to 0.
    r as i32
}

/// A real number a controller can compute with: `f32` or [`Fx`].
///
/// All operations are total: no operation panics, whatever the operands (`Fx` saturates,
/// division by zero saturates, `sqrt` of a negative number is zero).
pub trait Scalar:
    Copy
    + Debug
    + Default
    + PartialEq
    + PartialOrd
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign
{
    /// Which type this is.
    const KIND: ScalarKind;
    /// Which math backend computes its transcendental functions.
    const MATH: MathBackend;
    /// 0.
    const ZERO: Self;
    /// 1.
    const ONE: Self;
    /// The smallest positive step between two values (`f32::EPSILON` for `f32`, 2^-16 for
    /// `Fx`): a scale for tolerances.
    const EPS: Self;
    /// Whether the squares of coordinates (up to twice the coordinate limit) and their sums are
    /// held to full relative precision, so lengths are computed directly as √(x² + y²): true for
    /// `f32`. Fixed point scales a vector by its largest component first, which squaring would
    /// otherwise overflow (large vectors) or flush to zero (small ones).
    const DIRECT_LENGTH: bool;

    /// Converts a constant (NaN becomes 0, out-of-range values saturate for `Fx`).
    fn from_f32(v: f32) -> Self;
    /// A [`Constant`] in this type: the same value as `from_f32` of it, converted at compile
    /// time.
    fn constant(c: Constant) -> Self;
    /// Converts to `f32` (for reports and comparisons).
    fn to_f32(self) -> f32;
    /// Converts an integer (saturating for `Fx`).
    fn from_i32(v: i32) -> Self;
    /// The largest integer not above `self`, saturated into `i32`.
    fn floor_i32(self) -> i32;
    /// False for NaN and infinities (always true for `Fx`).
    fn is_finite(self) -> bool;
    /// A uniform number in the open interval (0, 1) from 32 random bits.
    fn unit_open(bits: u32) -> Self;
    /// Square root; 0 for negative input.
    fn sqrt(self) -> Self;
    /// Sine of an angle in radians.
    fn sin(self) -> Self;
    /// Cosine of an angle in radians.
    fn cos(self) -> Self;
    /// `(self.sin(), self.cos())`, bit for bit, computed together where that is cheaper.
    #[inline]
    fn sin_cos(self) -> (Self, Self) {
        (self.sin(), self.cos())
    }
    /// Four-quadrant arctangent of `self / x`, in (-π, π]; `atan2(0, 0) = 0`.
    fn atan2(self, x: Self) -> Self;
    /// e^self (saturating for `Fx`).
    fn exp(self) -> Self;

    /// Absolute value.
    #[inline]
    fn abs(self) -> Self {
        if self < Self::ZERO { -self } else { self }
    }
    /// The smaller of two values.
    #[inline]
    fn min(self, o: Self) -> Self {
        if o < self { o } else { self }
    }
    /// The larger of two values.
    #[inline]
    fn max(self, o: Self) -> Self {
        if o > self { o } else { self }
    }
    /// `self` limited to `[lo, hi]` (never panics, even if `lo > hi`).
    #[inline]
    fn clamp_to(self, lo: Self, hi: Self) -> Self {
        self.max(lo).min(hi)
    }
    /// −1, 0 or +1.
    #[inline]
    fn signum(self) -> Self {
        if self > Self::ZERO {
            Self::ONE
        } else if self < Self::ZERO {
            -Self::ONE
        } else {
            Self::ZERO
        }
    }
    /// `self^n` for a small non-negative integer power (repeated multiplication).
    #[inline]
    fn powi(self, n: u8) -> Self {
        let mut acc = Self::ONE;
        for _ in 0..n {
            acc *= self;
        }
        acc
    }
}

/// π as any scalar.
#[inline]
pub fn pi<S: Scalar>() -> S {
    S::from_f32(core::f32::consts::PI)
}

/// Degrees to radians.
#[inline]
pub fn deg<S: Scalar>(d: S) -> S {
    d * S::from_f32(core::f32::consts::PI / 180.0)
}
