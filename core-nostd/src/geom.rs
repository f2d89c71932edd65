//! Small vector types over any [`Scalar`] (glam is f32-only; these run on `Fx` too).

use core::ops::{Add, AddAssign, Mul, Neg, Sub, SubAssign};

use crate::{Error, Result, Scalar};

wire_type! {
    /// A 2D vector (ant world: x east, y north).
    #[derive(Clone, Copy, Debug, Default, PartialEq)]
    pub struct Vec2<S> {
        /// x component.
        pub x: S,
        /// y component.
        pub y: S,
    }

    /// A 3D vector (bee world: y is up, as in chen eq. 7).
    #[derive(Clone, Copy, Debug, Default, PartialEq)]
    pub struct Vec3<S> {
        /// x component.
        pub x: S,
        /// y component (up).
        pub y: S,
        /// z component.
        pub z: S,
    }

    /// An axis-aligned rectangle `[min, max]`: the ant arena.
    #[derive(Clone, Copy, Debug, Default, PartialEq)]
    pub struct Rect<S> {
        /// Lower-left corner.
        pub min: Vec2<S>,
        /// Upper-right corner.
        pub max: Vec2<S>,
    }
}

/// The squared length of a vector (`l2`, only called for `f32`), if its length is computed
/// directly from it: in the normal range, where √(x² + y²) is as precise as the scaled
/// computation and saves it two divisions. `None` sends the caller to the scaled one (fixed
/// point, where squares overflow or flush to zero; zero, tiny, huge or non-finite vectors).
#[inline]
fn direct<S: Scalar>(l2: impl FnOnce() -> S) -> Option<S> {
    if !S::DIRECT_LENGTH {
        return None;
    }
    let l2 = l2();
    (l2 > S::from_f32(1e-30) && l2 < S::from_f32(1e30)).then_some(l2)
}

impl<S: Scalar> Vec2<S> {
    /// `(x, y)`.
    #[inline]
    pub const fn new(x: S, y: S) -> Self {
        Vec2 { x, y }
    }
    /// `(0, 0)`.
    #[inline]
    pub fn zero() -> Self {
        Vec2::new(S::ZERO, S::ZERO)
    }
    /// From `f32` components.
    #[inline]
    pub fn from_f32(x: f32, y: f32) -> Self {
        Vec2::new(S::from_f32(x), S::from_f32(y))
    }
    /// Dot product.
    #[inline]
    pub fn dot(self, o: Self) -> S {
        self.x * o.x + self.y * o.y
    }
    /// z component of the 3D cross product (positive when `o` is counter-clockwise of `self`).
    #[inline]
    pub fn cross(self, o: Self) -> S {
        self.x * o.y - self.y * o.x
    }
    /// Squared length.
    #[inline]
    pub fn length_sq(self) -> S {
        self.dot(self)
    }
    /// Length: √(x² + y²) for `f32`; for `Fx` computed without squaring large components (no
    /// overflow below 32768).
    #[inline]
    pub fn length(self) -> S {
        if let Some(l2) = direct(|| self.dot(self)) {
            return l2.sqrt();
        }
        let m = self.x.abs().max(self.y.abs());
        if m == S::ZERO {
            return S::ZERO;
        }
        // Scale by the larger component so the squares stay ≤ 2 (safe for fixed point).
        let (a, b) = (self.x / m, self.y / m);
        m * (a * a + b * b).sqrt()
    }
    /// The unit vector along `self`, or `None` for a zero vector.
    #[inline]
    pub fn normalized(self) -> Option<Self> {
        if let Some(l2) = direct(|| self.dot(self)) {
            let l = l2.sqrt();
            return Some(Vec2::new(self.x / l, self.y / l));
        }
        // Scale by the largest component first: exact for fixed-point vectors of a few ulps,
        // whose length alone would be too coarse to divide by.
        let m = self.x.abs().max(self.y.abs());
        if m == S::ZERO {
            return None;
        }
        let s = Vec2::new(self.x / m, self.y / m);
        let l = s.dot(s).sqrt();
        Some(Vec2::new(s.x / l, s.y / l))
    }
    /// Rotated counter-clockwise by 90°.
    #[inline]
    pub fn perp(self) -> Self {
        Vec2::new(-self.y, self.x)
    }
    /// Rotated counter-clockwise by `angle` radians.
    #[inline]
    pub fn rotated(self, angle: S) -> Self {
        let (s, c) = angle.sin_cos();
        Vec2::new(self.x * c - self.y * s, self.x * s + self.y * c)
    }
    /// The unit vector at `angle` radians from the x axis.
    #[inline]
    pub fn from_angle(angle: S) -> Self {
        let (s, c) = angle.sin_cos();
        Vec2::new(c, s)
    }
    /// `Err(NonFinite(field))` if a component is NaN or infinite.
    #[inline]
    pub fn check(self, field: &'static str) -> Result<Self> {
        if self.x.is_finite() && self.y.is_finite() {
            Ok(self)
        } else {
            Err(Error::non_finite(field))
        }
    }
    /// Converts the components to `f32`.
    #[inline]
    pub fn to_f32(self) -> Vec2<f32> {
        Vec2::new(self.x.to_f32(), self.y.to_f32())
    }
    /// Converts the components from another scalar through `f32`.
    #[inline]
    pub fn cast<T: Scalar>(self) -> Vec2<T> {
        Vec2::new(T::from_f32(self.x.to_f32()), T::from_f32(self.y.to_f32()))
    }
}

impl<S: Scalar> Vec3<S> {
    /// `(x, y, z)`.
    #[inline]
    pub const fn new(x: S, y: S, z: S) -> Self {
        Vec3 { x, y, z }
    }
    /// `(0, 0, 0)`.
    #[inline]
    pub fn zero() -> Self {
        Vec3::new(S::ZERO, S::ZERO, S::ZERO)
    }
    /// The up axis `(0, 1, 0)`.
    #[inline]
    pub fn up() -> Self {
        Vec3::new(S::ZERO, S::ONE, S::ZERO)
    }
    /// From `f32` components.
    #[inline]
    pub fn from_f32(x: f32, y: f32, z: f32) -> Self {
        Vec3::new(S::from_f32(x), S::from_f32(y), S::from_f32(z))
    }
    /// Dot product.
    #[inline]
    pub fn dot(self, o: Self) -> S {
        self.x * o.x + self.y * o.y + self.z * o.z
    }
    /// Cross product.
    #[inline]
    pub fn cross(self, o: Self) -> Self {
        Vec3::new(
            self.y * o.z - self.z * o.y,
            self.z * o.x - self.x * o.z,
            self.x * o.y - self.y * o.x,
        )
    }
    /// Squared length.
    #[inline]
    pub fn length_sq(self) -> S {
        self.dot(self)
    }
    /// Length: √(x² + y² + z²) for `f32`; for `Fx` computed without squaring large components.
    #[inline]
    pub fn length(self) -> S {
        if let Some(l2) = direct(|| self.dot(self)) {
            return l2.sqrt();
        }
        let m = self.x.abs().max(self.y.abs()).max(self.z.abs());
        if m == S::ZERO {
            return S::ZERO;
        }
        let (a, b, c) = (self.x / m, self.y / m, self.z / m);
        m * (a * a + b * b + c * c).sqrt()
    }
    /// The unit vector along `self`, or `None` for a zero vector.
    #[inline]
    pub fn normalized(self) -> Option<Self> {
        if let Some(l2) = direct(|| self.dot(self)) {
            let l = l2.sqrt();
            return Some(Vec3::new(self.x / l, self.y / l, self.z / l));
        }
        // Scale by the largest component first (see `Vec2::normalized`).
        let m = self.x.abs().max(self.y.abs()).max(self.z.abs());
        if m == S::ZERO {
            return None;
        }
        let s = Vec3::new(self.x / m, self.y / m, self.z / m);
        let l = s.dot(s).sqrt();
        Some(Vec3::new(s.x / l, s.y / l, s.z / l))
    }
    /// `Err(NonFinite(field))` if a component is NaN or infinite.
    #[inline]
    pub fn check(self, field: &'static str) -> Result<Self> {
        if self.x.is_finite() && self.y.is_finite() && self.z.is_finite() {
            Ok(self)
        } else {
            Err(Error::non_finite(field))
        }
    }
    /// Converts the components to `f32`.
    #[inline]
    pub fn to_f32(self) -> Vec3<f32> {
        Vec3::new(self.x.to_f32(), self.y.to_f32(), self.z.to_f32())
    }
    /// Converts the components from another scalar through `f32`.
    #[inline]
    pub fn cast<T: Scalar>(self) -> Vec3<T> {
        Vec3::new(
            T::from_f32(self.x.to_f32()),
            T::from_f32(self.y.to_f32()),
            T::from_f32(self.z.to_f32()),
        )
    }
}

impl<S: Scalar> Rect<S> {
    /// The rectangle `[min, max]`.
    #[inline]
    pub const fn new(min: Vec2<S>, max: Vec2<S>) -> Self {
        Rect { min, max }
    }
    /// Whether `p` lies inside (borders included).
    #[inline]
    pub fn contains(&self, p: Vec2<S>) -> bool {
        p.x >= self.min.x && p.x <= self.max.x && p.y >= self.min.y && p.y <= self.max.y
    }
    /// `p` moved to the nearest point inside.
    #[inline]
    pub fn clamp(&self, p: Vec2<S>) -> Vec2<S> {
        Vec2::new(
            p.x.clamp_to(self.min.x, self.max.x),
            p.y.clamp_to(self.min.y, self.max.y),
        )
    }
    /// `Err` unless both corners are finite and `min < max` on both axes.
    pub fn check(self, field: &'static str) -> Result<Self> {
        self.min.check(field)?;
        self.max.check(field)?;
        if self.min.x < self.max.x && self.min.y < self.max.y {
            Ok(self)
        } else {
            Err(Error::out_of_range(field))
        }
    }
}

macro_rules! vec_ops {
    ($V:ident { $($f:ident),+ }) => {
        impl<S: Scalar> Add for $V<S> {
            type Output = Self;
            #[cfg_attr(not(feature = "small"), inline)]
            #[cfg_attr(feature = "small", inline(never))]
            fn add(self, o: Self) -> Self { $V { $($f: self.$f + o.$f),+ } }
        }
        impl<S: Scalar> Sub for $V<S> {
            type Output = Self;
            #[cfg_attr(not(feature = "small"), inline)]
            #[cfg_attr(feature = "small", inline(never))]
            fn sub(self, o: Self) -> Self { $V { $($f: self.$f - o.$f),+ } }
        }
        impl<S: Scalar> Neg for $V<S> {
            type Output = Self;
            #[inline]
            fn neg(self) -> Self { $V { $($f: -self.$f),+ } }
        }
        impl<S: Scalar> Mul<S> for $V<S> {
            type Output = Self;
            #[cfg_attr(not(feature = "small"), inline)]
            #[cfg_attr(feature = "small", inline(never))]
            fn mul(self, k: S) -> Self { $V { $($f: self.$f * k),+ } }
        }
        impl<S: Scalar> AddAssign for $V<S> {
            #[inline]
            fn add_assign(&mut self, o: Self) { *self = *self + o; }
        }
        impl<S: Scalar> SubAssign for $V<S> {
            #[inline]
            fn sub_assign(&mut self, o: Self) { *self = *self - o; }
        }
    };
}
vec_ops!(Vec2 { x, y });
vec_ops!(Vec3 { x, y, z });

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn length_does_not_overflow_fixed_point() {
        #[cfg(feature = "fixed")]
        {
            use crate::Fx;
            let v = Vec2::<Fx>::from_f32(3000.0, 4000.0);
            assert!((v.length().to_f32() - 5000.0).abs() < 0.01);
            // A vector of a few ulps still normalises to unit length.
            let tiny = Vec2::<Fx>::new(Fx::EPS, Fx::EPS + Fx::EPS)
                .normalized()
                .unwrap();
            assert!((tiny.length().to_f32() - 1.0).abs() < 1e-3);
            let w = Vec3::<Fx>::from_f32(-2000.0, 0.0, 0.0);
            assert!((w.length().to_f32() - 2000.0).abs() < 0.01);
        }
        assert_eq!(Vec2::<f32>::zero().normalized(), None);
    }

    #[test]
    fn cross_and_perp() {
        let x = Vec3::<f32>::new(1.0, 0.0, 0.0);
        let y = Vec3::<f32>::up();
        assert_eq!(x.cross(y), Vec3::new(0.0, 0.0, 1.0));
        assert_eq!(Vec2::<f32>::new(1.0, 0.0).perp(), Vec2::new(0.0, 1.0));
    }
}
