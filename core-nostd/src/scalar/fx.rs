//! [`Fx`]: I16F16 fixed point (the `fixed` crate's [`I16F16`]) with total, saturating
//! arithmetic and integer-only transcendental functions.
//!
//! Every operation is defined on the raw 32-bit two's-complement bits so that it gives the same
//! bits on every machine and can be mirrored in a WGSL shader (which has `i32`/`u32` only):
//!
//! * `a + b`, `a - b`, `-a`: saturating 32-bit integer arithmetic.
//! * `a * b = sat((a·b + 2^15) >> 16)`: the 64-bit product rounded to nearest (ties up), then
//!   saturated. In 32-bit pieces: split each operand into 16-bit halves and add the four
//!   partial products (documented for the shader port).
//! * `a / b = sat(trunc((a << 16) / b))`, truncating toward zero; `x / 0` saturates to
//!   `±MAX` by the sign of `x` (`0 / 0 = 0`).
//! * `sqrt`: the floor of the integer square root of `a << 16` (exact digit-by-digit method).
//! * `sin`/`cos`: reduction modulo 2π (in raw units), folding to the first quadrant and an odd
//!   polynomial in `y = 2x/π` (Taylor terms of sin(πy/2) through y^9), error ≤ 4·2^-16.
//! * `atan2`: octant folding and the Abramowitz-Stegun 4.4.49 polynomial (|err| ≤ 1e-5 + rounding).
//! * `exp`: `e^x = 2^k·e^r`, `k = round(x/ln2)`, `|r| ≤ ln2/2`, degree-6 Taylor polynomial in
//!   `r`; saturates above ln(32768) and is 0 below ln(2^-17).

use core::fmt;
use core::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};

pub use fixed::types::I16F16;

use super::{Constant, MathBackend, Scalar, ScalarKind};

/// An I16F16 fixed-point number (range ±32768, step 2^-16 ≈ 1.5e-5) with total, saturating,
/// bit-reproducible arithmetic. The wrapped [`I16F16`] is public for interop with `fixed`.
///
/// On the wire an `Fx` is its raw bits, an `i32` (postcard: zig-zag varint).
#[derive(Clone, Copy, Default, PartialEq, Eq, PartialOrd, Hash)]
#[repr(transparent)]
pub struct Fx(pub I16F16);

const PI_RAW: i32 = 205_887;
const TAU_RAW: i32 = 411_775;
const HALF_PI_RAW: i32 = 102_944;

impl Fx {
    /// The largest value, 32767.99998.
    pub const MAX: Fx = Fx(I16F16::MAX);
    /// The smallest value, −32768.
    pub const MIN: Fx = Fx(I16F16::MIN);

    /// From raw two's-complement bits (value = bits / 65536).
    #[inline]
    pub const fn from_bits(bits: i32) -> Fx {
        Fx(I16F16::from_bits(bits))
    }
    /// From `f32`, rounded to the nearest (ties to even), saturating; NaN gives 0. The same as
    /// [`Scalar::from_f32`] (`I16F16::saturating_from_num`, tested), usable in constants.
    #[inline(always)]
    pub const fn from_f32_const(v: f32) -> Fx {
        Fx::from_bits(super::i16f16_bits(v))
    }
    /// The raw bits.
    #[inline]
    pub const fn to_bits(self) -> i32 {
        self.0.to_bits()
    }
    #[inline]
    const fn sat(v: i64) -> Fx {
        if v > i32::MAX as i64 {
            Fx::MAX
        } else if v < i32::MIN as i64 {
            Fx::MIN
        } else {
            Fx::from_bits(v as i32)
        }
    }
    /// Sine on `[0, π/2]` (raw units), via the polynomial in `y = 2x/π`.
    fn sin_quadrant(x: i32) -> Fx {
        let y = Fx::from_bits(x) * Fx::from_bits(41_722);
        let y2 = y * y;
        let mut p = Fx::from_bits(11);
        p = Fx::from_bits(-307) + y2 * p;
        p = Fx::from_bits(5_223) + y2 * p;
        p = Fx::from_bits(-42_334) + y2 * p;
        p = Fx::from_bits(HALF_PI_RAW) + y2 * p;
        (y * p).min(Fx::ONE)
    }
    /// Sine of a reduced angle in `[0, 2π)` (raw units).
    fn sin_reduced(a: i32) -> Fx {
        let (a, neg) = if a >= PI_RAW {
            (a - PI_RAW, true)
        } else {
            (a, false)
        };
        let a = if a > HALF_PI_RAW { PI_RAW - a } else { a };
        let s = Fx::sin_quadrant(a);
        if neg { -s } else { s }
    }
}

/// Integer square root (floor) by the digit-by-digit method.
const fn isqrt(n: u64) -> u64 {
    let mut x = n;
    let mut r = 0u64;
    let mut bit = 1u64 << 62;
    while bit > n {
        bit >>= 2;
    }
    while bit != 0 {
        if x >= r + bit {
            x -= r + bit;
            r = (r >> 1) + bit;
        } else {
            r >>= 1;
        }
        bit >>= 2;
    }
    r
}

impl Add for Fx {
    type Output = Fx;
    #[cfg_attr(not(feature = "small"), inline)]
    #[cfg_attr(feature = "small", inline(never))]
    fn add(self, o: Fx) -> Fx {
        Fx::from_bits(self.to_bits().saturating_add(o.to_bits()))
    }
}
impl Sub for Fx {
    type Output = Fx;
    #[cfg_attr(not(feature = "small"), inline)]
    #[cfg_attr(feature = "small", inline(never))]
    fn sub(self, o: Fx) -> Fx {
        Fx::from_bits(self.to_bits().saturating_sub(o.to_bits()))
    }
}
impl Mul for Fx {
    type Output = Fx;
    #[cfg_attr(not(feature = "small"), inline)]
    #[cfg_attr(feature = "small", inline(never))]
    fn mul(self, o: Fx) -> Fx {
        let p = self.to_bits() as i64 * o.to_bits() as i64;
        Fx::sat((p + (1 << 15)) >> 16)
    }
}
impl Div for Fx {
    type Output = Fx;
    #[cfg_attr(not(feature = "small"), inline)]
    #[cfg_attr(feature = "small", inline(never))]
    fn div(self, o: Fx) -> Fx {
        let (a, b) = (self.to_bits(), o.to_bits());
        if b == 0 {
            return match a {
                0 => Fx::ZERO,
                a if a > 0 => Fx::MAX,
                _ => Fx::MIN,
            };
        }
        let q = div_q16(a.unsigned_abs(), b.unsigned_abs()) as i64;
        Fx::sat(if (a < 0) != (b < 0) { -q } else { q })
    }
}

/// `(n << 16) / d`, truncated (`d > 0`): the quotient of `Fx` division before its sign. A
/// 64-bit division where the machine has one; on 32-bit cores (Cortex-M), where it would be a
/// library routine, [`div_q16_words`] (smaller and faster there).
#[inline]
fn div_q16(n: u32, d: u32) -> u64 {
    #[cfg(target_pointer_width = "64")]
    return ((n as u64) << 16) / d as u64;
    #[cfg(not(target_pointer_width = "64"))]
    return div_q16_words(n, d);
}

/// [`div_q16`] without a 64-bit division: long division with the core's
/// 32-bit divide, the integer part in one step, then the 16 fraction bits in digits of as many
/// bits `k` as keep `r << k` within 32 bits (`r < d`; one digit if `d < 2^16`, two below
/// `2^24`). Equal to the 64-bit quotient for every input (tested).
#[cfg(any(not(target_pointer_width = "64"), test))]
fn div_q16_words(n: u32, d: u32) -> u64 {
    let mut q = (n / d) as u64;
    let mut r = n % d;
    // `r < d < 2^(32 - lz)`, so `r << lz` fits; for `d = 2^31` (lz 0), `r << 1` does.
    let digit = d.leading_zeros().max(1);
    let mut left = 16;
    while left > 0 {
        let k = digit.min(left);
        let x = r << k;
        q = (q << k) | (x / d) as u64;
        r = x % d;
        left -= k;
    }
    q
}
impl Neg for Fx {
    type Output = Fx;
    #[inline]
    fn neg(self) -> Fx {
        Fx::from_bits(self.to_bits().saturating_neg())
    }
}
impl AddAssign for Fx {
    #[inline]
    fn add_assign(&mut self, o: Fx) {
        *self = *self + o;
    }
}
impl SubAssign for Fx {
    #[inline]
    fn sub_assign(&mut self, o: Fx) {
        *self = *self - o;
    }
}
impl MulAssign for Fx {
    #[inline]
    fn mul_assign(&mut self, o: Fx) {
        *self = *self * o;
    }
}

impl Scalar for Fx {
    const KIND: ScalarKind = ScalarKind::I16F16;
    const MATH: MathBackend = MathBackend::Integer;
    const ZERO: Fx = Fx::from_bits(0);
    const ONE: Fx = Fx::from_bits(1 << 16);
    const EPS: Fx = Fx::from_bits(1);
    const DIRECT_LENGTH: bool = false;

    #[cfg_attr(not(feature = "small"), inline)]
    #[cfg_attr(feature = "small", inline(never))]
    fn abs(self) -> Fx {
        Fx::from_bits(self.to_bits().saturating_abs())
    }
    // Always inlined: nearly every call converts a constant (a threshold, a limit), which then
    // folds to its bit pattern instead of pulling soft-float code into integer-only firmware.
    #[inline(always)]
    fn from_f32(v: f32) -> Fx {
        Fx::from_f32_const(v)
    }
    #[inline(always)]
    fn constant(c: Constant) -> Fx {
        Fx::from_bits(c.i16f16_bits())
    }
    #[inline]
    fn to_f32(self) -> f32 {
        self.0.to_num::<f32>()
    }
    #[inline]
    fn from_i32(v: i32) -> Fx {
        Fx::sat((v as i64) << 16)
    }
    #[inline]
    fn floor_i32(self) -> i32 {
        self.to_bits() >> 16
    }
    #[inline]
    fn is_finite(self) -> bool {
        true
    }
    #[inline]
    fn unit_open(bits: u32) -> Fx {
        // 15 random bits as an odd 16-bit fraction: (2k + 1) / 2^16, strictly inside (0, 1).
        Fx::from_bits((((bits >> 17) << 1) | 1) as i32)
    }
    fn sqrt(self) -> Fx {
        let r = self.to_bits();
        if r <= 0 {
            return Fx::ZERO;
        }
        Fx::from_bits(isqrt((r as u64) << 16) as i32)
    }
    fn sin(self) -> Fx {
        Fx::sin_reduced(self.to_bits().rem_euclid(TAU_RAW))
    }
    fn cos(self) -> Fx {
        let a = self.to_bits().rem_euclid(TAU_RAW) + HALF_PI_RAW;
        Fx::sin_reduced(if a >= TAU_RAW { a - TAU_RAW } else { a })
    }
    fn atan2(self, x: Fx) -> Fx {
        let (y, x) = (self, x);
        if x == Fx::ZERO && y == Fx::ZERO {
            return Fx::ZERO;
        }
        let (ax, ay) = (x.abs(), y.abs());
        let swap = ay > ax;
        let z = if swap { ax / ay } else { ay / ax };
        let z2 = z * z;
        let mut p = Fx::from_bits(1_365);
        p = Fx::from_bits(-5_579) + z2 * p;
        p = Fx::from_bits(11_806) + z2 * p;
        p = Fx::from_bits(-21_647) + z2 * p;
        p = Fx::from_bits(65_527) + z2 * p;
        let mut r = z * p;
        if swap {
            r = Fx::from_bits(HALF_PI_RAW) - r;
        }
        if x < Fx::ZERO {
            r = Fx::from_bits(PI_RAW) - r;
        }
        if y < Fx::ZERO { -r } else { r }
    }
    fn exp(self) -> Fx {
        let raw = self.to_bits();
        if raw > 681_391 {
            return Fx::MAX;
        }
        if raw < -772_244 {
            return Fx::ZERO;
        }
        // k = round(x / ln 2), r = x - k ln 2.
        let k = (self * Fx::from_bits(94_548) + Fx::from_bits(1 << 15)).floor_i32();
        let r = self - Fx::from_i32(k) * Fx::from_bits(45_426);
        let mut p = Fx::from_bits(91);
        p = Fx::from_bits(546) + r * p;
        p = Fx::from_bits(2_731) + r * p;
        p = Fx::from_bits(10_923) + r * p;
        p = Fx::from_bits(32_768) + r * p;
        p = Fx::ONE + r * p;
        p = Fx::ONE + r * p;
        let bits = p.to_bits() as i64;
        if k >= 0 {
            Fx::sat(bits << k.min(31))
        } else {
            let s = (-k).min(40) as u32;
            Fx::sat((bits + (1i64 << (s - 1))) >> s)
        }
    }
}

impl From<I16F16> for Fx {
    fn from(v: I16F16) -> Fx {
        Fx(v)
    }
}
impl From<Fx> for I16F16 {
    fn from(v: Fx) -> I16F16 {
        v.0
    }
}

impl fmt::Debug for Fx {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(&self.0, f)
    }
}
impl fmt::Display for Fx {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(&self.0, f)
    }
}

#[cfg(feature = "serde")]
impl serde::Serialize for Fx {
    fn serialize<Se: serde::Serializer>(&self, s: Se) -> Result<Se::Ok, Se::Error> {
        s.serialize_i32(self.to_bits())
    }
}
#[cfg(feature = "serde")]
impl<'de> serde::Deserialize<'de> for Fx {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Fx, D::Error> {
        <i32 as serde::Deserialize>::deserialize(d).map(Fx::from_bits)
    }
}
#[cfg(feature = "defmt")]
impl defmt::Format for Fx {
    fn format(&self, f: defmt::Formatter<'_>) {
        defmt::write!(f, "{=f32}", self.to_f32())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fx(v: f32) -> Fx {
        Fx::from_f32(v)
    }
    fn close(a: Fx, b: f64, tol: f64) -> bool {
        (a.to_f32() as f64 - b).abs() <= tol
    }

    #[test]
    fn const_conversion_equals_the_fixed_crate() {
        let reference = |v: f32| {
            if v.is_nan() {
                0
            } else {
                I16F16::saturating_from_num(v).to_bits()
            }
        };
        let mut specials = vec![
            0.0f32,
            -0.0,
            f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::MAX,
            f32::MIN,
            f32::MIN_POSITIVE,
            -f32::MIN_POSITIVE,
            1e-45,
            32767.99998,
            32768.0,
            -32768.0,
            -32768.00001,
            65536.0,
        ];
        // Ties at every scale: k/2^17 (halfway between two Fx values).
        for k in -40i32..40 {
            specials.push(k as f32 / 131_072.0);
            specials.push(k as f32 * 0.5 + 0.25 / 65_536.0);
        }
        let mut g = 0x2545_F491u32;
        for _ in 0..400_000 {
            g ^= g << 13;
            g ^= g >> 17;
            g ^= g << 5;
            specials.push(f32::from_bits(g));
            // Magnitudes near the Fx range, where rounding and saturation matter.
            specials.push(f32::from_bits(
                (g & 0x807F_FFFF) | ((0x70 + (g >> 27)) << 23),
            ));
        }
        for v in specials {
            assert_eq!(
                Fx::from_f32_const(v).to_bits(),
                reference(v),
                "{v:e} ({:#x})",
                v.to_bits()
            );
        }
    }

    #[test]
    fn word_division_equals_the_64_bit_quotient() {
        let edges = [
            1u32,
            2,
            3,
            0xFFFF,
            0x1_0000,
            0x1_0001,
            0x7FFF_FFFF,
            0x8000_0000,
        ];
        let mut g = 0x9E37_79B9u32;
        let mut next = || {
            g ^= g << 13;
            g ^= g >> 17;
            g ^= g << 5;
            g
        };
        let mut pairs: Vec<(u32, u32)> = Vec::new();
        for &n in edges.iter().chain(&[0u32]) {
            for &d in &edges {
                pairs.push((n, d));
            }
        }
        for _ in 0..200_000 {
            // |a| and |b| of two i32s: at most 2^31; random magnitudes over every bit length.
            let (n, sn, d, sd) = (next(), next() % 32, next(), next() % 32);
            pairs.push(((n >> sn).min(1 << 31), (d >> sd).clamp(1, 1 << 31)));
        }
        for (n, d) in pairs {
            assert_eq!(
                div_q16_words(n, d),
                ((n as u64) << 16) / d as u64,
                "{n} / {d}"
            );
        }
    }

    #[test]
    fn arithmetic_saturates_instead_of_panicking() {
        assert_eq!(Fx::MAX + Fx::ONE, Fx::MAX);
        assert_eq!(Fx::MIN - Fx::ONE, Fx::MIN);
        assert_eq!(-Fx::MIN, Fx::MAX);
        assert_eq!(fx(300.0) * fx(300.0), Fx::MAX);
        assert_eq!(fx(-300.0) * fx(300.0), Fx::MIN);
        assert_eq!(Fx::ONE / Fx::ZERO, Fx::MAX);
        assert_eq!(-Fx::ONE / Fx::ZERO, Fx::MIN);
        assert_eq!(Fx::ZERO / Fx::ZERO, Fx::ZERO);
        assert_eq!(Fx::MIN / -Fx::EPS, Fx::MAX);
        assert_eq!(Fx::from_f32(f32::NAN), Fx::ZERO);
        assert_eq!(Fx::from_f32(f32::INFINITY), Fx::MAX);
    }

    #[test]
    fn multiply_rounds_to_nearest() {
        // 1.5 * 2^-16 → 1.5 ulp → rounds (ties up) to 2 ulp.
        assert_eq!((fx(1.5) * Fx::EPS).to_bits(), 2);
        assert_eq!((fx(1.25) * Fx::EPS).to_bits(), 1);
        assert_eq!(fx(3.0) * fx(-2.5), fx(-7.5));
    }

    #[test]
    fn trig_sqrt_exp_match_f64_within_bounds() {
        let mut x = -40.0f64;
        while x < 40.0 {
            let v = fx(x as f32);
            let xv = v.to_f32() as f64;
            assert!(close(v.sin(), xv.sin(), 8e-5), "sin({xv}) = {}", v.sin());
            assert!(close(v.cos(), xv.cos(), 8e-5), "cos({xv}) = {}", v.cos());
            x += 0.0173;
        }
        let mut x = 0.0f64;
        while x < 32000.0 {
            let v = fx(x as f32);
            let r = v.sqrt().to_f32() as f64;
            assert!(
                (r - (v.to_f32() as f64).sqrt()).abs() <= 2.0 / 65536.0,
                "sqrt({x})"
            );
            x = x * 1.37 + 0.001;
        }
        let mut x = -12.0f64;
        while x < 10.3 {
            let v = fx(x as f32);
            let e = (v.to_f32() as f64).exp();
            assert!(close(v.exp(), e, 4e-5 + e * 2e-4), "exp({x}) = {}", v.exp());
            x += 0.0093;
        }
        assert_eq!(fx(11.0).exp(), Fx::MAX);
        assert_eq!(fx(-20.0).exp(), Fx::ZERO);
    }

    #[test]
    fn atan2_all_quadrants() {
        for i in 0..720 {
            let a = (i as f64 - 360.0) * core::f64::consts::PI / 360.0 + 0.001;
            for r in [0.01f64, 1.0, 25.0, 3000.0] {
                let (y, x) = (fx((r * a.sin()) as f32), fx((r * a.cos()) as f32));
                let want = (y.to_f32() as f64).atan2(x.to_f32() as f64);
                let got = y.atan2(x).to_f32() as f64;
                let d = (got - want).abs();
                let d = d.min((d - 2.0 * core::f64::consts::PI).abs());
                assert!(
                    d < 6e-4 / r.clamp(0.05, 1.0),
                    "atan2({y},{x}) = {got}, want {want}"
                );
            }
        }
        assert_eq!(Fx::ZERO.atan2(Fx::ZERO), Fx::ZERO);
    }

    #[test]
    fn unit_open_is_strictly_inside() {
        for bits in [0u32, 1, u32::MAX, 0x8000_0000, 0x7fff_ffff] {
            let u = Fx::unit_open(bits);
            assert!(u > Fx::ZERO && u < Fx::ONE);
        }
    }
}
