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

    #[inline]
    fn from_f32(v: f32) -> f32 {
        if v.is_nan() { 0.0 } else { v }
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
    fn atan2(self, x: f32) -> f32 {
        backend::atan2(self, x)
    }
    #[inline]
    fn exp(self) -> f32 {
        backend::exp(self)
    }
}
