//! `f32` as a [`Scalar`]: IEEE arithmetic, transcendental functions from `libm` (default) or
//! `micromath` (feature). `libm` results are bit-identical on x86_64 and Cortex-M.

use super::{MathBackend, Scalar, ScalarKind};

#[cfg(feature = "libm")]
mod backend {
    #[inline]
    pub fn sqrt(x: f32) -> f32 {
        libm::sqrtf(x)
    }
    #[inline]
    pub fn sin(x: f32) -> f32 {
        libm::sinf(x)
    }
    #[inline]
    pub fn cos(x: f32) -> f32 {
        libm::cosf(x)
    }
    /// One range reduction for both; the same bits as `sinf` and `cosf` (tested).
    #[inline]
    pub fn sin_cos(x: f32) -> (f32, f32) {
        libm::sincosf(x)
    }
    #[inline]
    pub fn atan2(y: f32, x: f32) -> f32 {
        libm::atan2f(y, x)
    }
    #[inline]
    pub fn exp(x: f32) -> f32 {
        libm::expf(x)
    }
    #[inline]
    pub fn floor(x: f32) -> f32 {
        libm::floorf(x)
    }
}

#[cfg(all(feature = "micromath", not(feature = "libm")))]
mod backend {
    use micromath::F32Ext;
    #[inline]
    pub fn sqrt(x: f32) -> f32 {
        F32Ext::sqrt(x)
    }
    #[inline]
    pub fn sin(x: f32) -> f32 {
        F32Ext::sin(x)
    }
    #[inline]
    pub fn cos(x: f32) -> f32 {
        F32Ext::cos(x)
    }
    #[inline]
    pub fn sin_cos(x: f32) -> (f32, f32) {
        (sin(x), cos(x))
    }
    #[inline]
    pub fn atan2(y: f32, x: f32) -> f32 {
        F32Ext::atan2(y, x)
    }
    #[inline]
    pub fn exp(x: f32) -> f32 {
        F32Ext::exp(x)
    }
    #[inline]
    pub fn floor(x: f32) -> f32 {
        F32Ext::floor(x)
    }
}

impl Scalar for f32 {
    const KIND: ScalarKind = ScalarKind::F32;
    const MATH: MathBackend = MathBackend::F32;
    const ZERO: f32 = 0.0;
    const ONE: f32 = 1.0;
    const EPS: f32 = f32::EPSILON;
    const DIRECT_LENGTH: bool = true;

    #[inline]
    fn from_f32(v: f32) -> f32 {
        if v.is_nan() { 0.0 } else { v }
    }
    #[inline(always)]
    fn constant(c: super::Constant) -> f32 {
        c.f32()
    }
    #[inline]
    fn to_f32(self) -> f32 {
        self
    }
    #[inline]
    fn from_i32(v: i32) -> f32 {
        v as f32
    }
    #[inline]
    fn floor_i32(self) -> i32 {
        // `as` saturates and maps NaN to 0: total.
        backend::floor(self) as i32
    }
    #[inline]
    fn is_finite(self) -> bool {
        f32::is_finite(self)
    }
    /// Clears the sign bit: one instruction, where the trait's default compares (a library
    /// call on a core without an FPU). −0 gives +0.
    #[inline]
    fn abs(self) -> f32 {
        f32::abs(self)
    }
    #[inline]
    fn unit_open(bits: u32) -> f32 {
        // 24 random bits, centred in their cell: (k + 0.5) / 2^24, strictly inside (0, 1).
        ((bits >> 8) as f32 + 0.5) * (1.0 / 16_777_216.0)
    }
    #[inline]
    fn sqrt(self) -> f32 {
        if self > 0.0 { backend::sqrt(self) } else { 0.0 }
    }
    #[inline]
    fn sin(self) -> f32 {
        backend::sin(self)
    }
    #[inline]
    fn cos(self) -> f32 {
        backend::cos(self)
    }
    #[inline]
    fn sin_cos(self) -> (f32, f32) {
        backend::sin_cos(self)
    }
    #[inline]
    fn atan2(self, x: f32) -> f32 {
        backend::atan2(self, x)
    }
    #[inline]
    fn exp(self) -> f32 {
        backend::exp(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sin_cos_gives_the_bits_of_sin_and_cos() {
        // Every 97th float in ±4π (both signs, all the range reductions the controllers reach)
        // and a few far ones.
        let near = (0..(4.0f32 * core::f32::consts::PI).to_bits()).step_by(97);
        let far = [1.0e4f32, 3.0e5, 1.0e9, f32::MAX, f32::MIN_POSITIVE, 0.0];
        for x in near.map(f32::from_bits).chain(far) {
            for x in [x, -x] {
                let (s, c) = Scalar::sin_cos(x);
                assert_eq!(s.to_bits(), Scalar::sin(x).to_bits(), "sin {x}");
                assert_eq!(c.to_bits(), Scalar::cos(x).to_bits(), "cos {x}");
            }
        }
    }
}
