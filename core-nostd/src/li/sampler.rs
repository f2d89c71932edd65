//! An empirical distribution as an inverse-CDF table (li2015 spec §2.1, ours): `M` equal bins
//! over `[lo, hi]`, the cumulative share at each bin's upper edge; a draw finds its bin by
//! binary search and interpolates linearly inside it (a piecewise-constant density).

use core::cmp::Ordering;

use crate::{Error, Result, Scalar};

/// `M` bins over `[lo, hi]` with their cumulative shares (`cdf[M − 1]` = 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Table<S, const M: usize> {
    /// Lower end of the first bin.
    pub lo: S,
    /// Upper end of the last bin.
    pub hi: S,
    /// The share of the samples at or below each bin's upper edge (non-decreasing).
    pub cdf: [S; M],
}

impl<S: Scalar, const M: usize> Table<S, M> {
    /// The table of a histogram: `counts[k]` samples in bin k of `M` equal bins over
    /// `[lo, hi]`. The shares are computed in `f32` (exactly rounded, so the same on every
    /// machine) and converted to `S`.
    ///
    /// # Errors
    ///
    /// `BadParam("lo")`/`("hi")` unless both are finite with `lo < hi`; `BadParam("counts")`
    /// when `M` is 0 or every count is 0.
    pub fn from_counts(lo: S, hi: S, counts: &[u32; M]) -> Result<Self> {
        if !lo.is_finite() {
            return Err(Error::BadParam { field: "lo" });
        }
        if !hi.is_finite() || hi <= lo {
            return Err(Error::BadParam { field: "hi" });
        }
        let total: u64 = counts.iter().map(|&c| u64::from(c)).sum();
        if total == 0 {
            return Err(Error::BadParam { field: "counts" });
        }
        let mut cdf = [S::ONE; M];
        let mut sum = 0u64;
        for (slot, &c) in cdf.iter_mut().zip(counts) {
            sum += u64::from(c);
            *slot = S::from_f32((sum as f64 / total as f64) as f32);
        }
        Ok(Table { lo, hi, cdf })
    }

    /// The value at cumulative share `u` ∈ (0, 1): the first bin whose upper edge's share
    /// exceeds `u`, interpolated linearly between its edges; `hi` when `u` is at or beyond the
    /// last share, `lo` for `u` ≤ 0 or NaN.
    pub fn sample(&self, u: S) -> S {
        // u ≤ 0 or NaN: the lowest value.
        if u.partial_cmp(&S::ZERO) != Some(Ordering::Greater) {
            return self.lo;
        }
        // The first k with cdf[k] > u (binary search over a non-decreasing array).
        let k = self.cdf.partition_point(|&c| c <= u);
        if k >= M {
            return self.hi;
        }
        let below = if k == 0 { S::ZERO } else { self.cdf[k - 1] };
        // cdf[k] > u ≥ below, so the bin has a positive share.
        let within = (u - below) / (self.cdf[k] - below);
        let width = (self.hi - self.lo) / S::from_i32(M as i32);
        self.lo + (S::from_i32(k as i32) + within) * width
    }

    /// The share of the table's distribution at or below `x` (the CDF the draws follow).
    pub fn cdf_at(&self, x: S) -> S {
        if x.partial_cmp(&self.lo) != Some(Ordering::Greater) {
            return S::ZERO;
        }
        if x >= self.hi || M == 0 {
            return S::ONE;
        }
        let pos = (x - self.lo) / (self.hi - self.lo) * S::from_i32(M as i32);
        let k = (pos.floor_i32().max(0) as usize).min(M - 1);
        let below = if k == 0 { S::ZERO } else { self.cdf[k - 1] };
        below + (self.cdf[k] - below) * (pos - S::from_i32(k as i32))
    }
}
