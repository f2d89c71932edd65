//! Input checks shared by the 3D models (bee, wang): finite numbers within the coordinate
//! limit, with errors naming the field.

use crate::bee::params::LIMIT;
use crate::{Error, Result, Scalar, ScalarKind, Vec3};

/// |v| ≤ l (false for NaN): for `f32` through the sign-clearing `f32::abs`.
#[inline]
pub(crate) fn within<S: Scalar>(v: S, l: S) -> bool {
    if S::KIND == ScalarKind::F32 {
        v.to_f32().abs() <= l.to_f32()
    } else {
        v.abs() <= l
    }
}

/// `Err` unless `v` is finite and `|v| ≤ LIMIT`.
#[inline]
pub(crate) fn check_num<S: Scalar>(v: S, field: &'static str) -> Result<()> {
    // Fast path: NaN fails the comparisons, and an infinity exceeds the limit.
    if within(v, S::from_f32(LIMIT)) {
        Ok(())
    } else if !v.is_finite() {
        Err(Error::non_finite(field))
    } else {
        Err(Error::out_of_range(field))
    }
}

/// [`check_num`] on every component (a non-finite component is reported before an
/// out-of-range one).
#[inline]
pub(crate) fn check_vec<S: Scalar>(v: Vec3<S>, field: &'static str) -> Result<()> {
    let l = S::from_f32(LIMIT);
    if within(v.x, l) & within(v.y, l) & within(v.z, l) {
        return Ok(());
    }
    v.check(field)?;
    [v.x, v.y, v.z]
        .into_iter()
        .try_for_each(|c| check_num(c, field))
}

/// [`check_num`] and `v ≥ 0`.
pub(crate) fn check_nonneg<S: Scalar>(v: S, field: &'static str) -> Result<()> {
    check_num(v, field)?;
    if v < S::ZERO {
        Err(Error::out_of_range(field))
    } else {
        Ok(())
    }
}

/// [`check_vec`], then a length within `[lo, hi]` (limits included), else `OutOfRange`.
pub(crate) fn check_length<S: Scalar>(
    v: Vec3<S>,
    lo: f32,
    hi: f32,
    field: &'static str,
) -> Result<()> {
    check_vec(v, field)?;
    let len = v.length();
    if len >= S::from_f32(lo) && len <= S::from_f32(hi) {
        Ok(())
    } else {
        Err(Error::out_of_range(field))
    }
}

/// A unit vector, length within 1 ± 1 % ([`check_length`]).
pub(crate) fn check_unit<S: Scalar>(v: Vec3<S>, field: &'static str) -> Result<()> {
    check_length(v, 0.99, 1.01, field)
}
