//! An empirical distribution as an inverse-CDF table (li2015 spec §2.1, ours): up to `M` equal
//! bins over `[lo, hi]`, the cumulative share at each bin's upper edge; a draw finds its bin by
//! binary search and interpolates linearly inside it (a piecewise-constant density).

use core::cmp::Ordering;

use crate::{Error, Result, Scalar};

wire_type! {
    /// Up to `M` bins over `[lo, hi]` with their cumulative shares (the last is 1).
    #[derive(Clone, Debug, PartialEq)]
    pub struct Table<S, const M: usize> {
        /// Lower end of the first bin.
        pub lo: S,
        /// Upper end of the last bin.
        pub hi: S,
        /// The share of the samples at or below each bin's upper edge (non-decreasing, at
        /// least one bin).
        pub cdf: heapless::Vec<S, M>,
    }
}

impl<S: Scalar, const M: usize> Table<S, M> {
    /// The table of a histogram: `counts[k]` samples in bin k of `counts.len()` equal bins
    /// over `[lo, hi]`. The shares are computed in `f64` and rounded once to `f32` (so the
    /// same on every machine), then converted to `S`.
    ///
    /// # Errors
    ///
    /// `BadParam("lo")`/`("hi")` unless both are finite with `lo < hi`; `BadParam("counts")`
    /// when there are no bins, more than `M`, or every count is 0.
    pub fn from_counts(lo: S, hi: S, counts: &[u32]) -> Result<Self> {
        if !lo.is_finite() {
            return Err(Error::BadParam { field: "lo" });
        }
        if !hi.is_finite() || hi <= lo {
            return Err(Error::BadParam { field: "hi" });
        }
        let total: u64 = counts.iter().map(|&c| u64::from(c)).sum();
        if total == 0 || counts.len() > M {
            return Err(Error::BadParam { field: "counts" });
        }
        let mut cdf = heapless::Vec::new();
        let mut sum = 0u64;
        for &c in counts {
            sum += u64::from(c);
            // At most M counts: no push can fail.
            let _ = cdf.push(S::from_f32((sum as f64 / total as f64) as f32));
        }
        Ok(Table { lo, hi, cdf })
    }

    /// Checks a table that did not come from [`Table::from_counts`] (a deserialized one):
    /// `lo < hi`, both finite; at least one bin, shares finite, non-decreasing, in [0, 1],
    /// the last 1. `field` names the table in the error ([`Error::BadParam`]).
    pub fn validate(&self, field: &'static str) -> Result<()> {
        let bad = Err(Error::BadParam { field });
        if !(self.lo.is_finite() && self.hi.is_finite() && self.lo < self.hi) {
            return bad;
        }
        let mut below = S::ZERO;
        for &c in &self.cdf {
            if !(c.is_finite() && c >= below && c <= S::ONE) {
                return bad;
            }
            below = c;
        }
        if self.cdf.last() != Some(&S::ONE) {
            return bad;
        }
        Ok(())
    }

    /// The number of bins.
    pub fn bins(&self) -> usize {
        self.cdf.len()
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
        let m = self.cdf.len();
        let k = self.cdf.partition_point(|&c| c <= u);
        if k >= m {
            return self.hi;
        }
        let below = if k == 0 { S::ZERO } else { self.cdf[k - 1] };
        // cdf[k] > u ≥ below, so the bin has a positive share.
        let within = (u - below) / (self.cdf[k] - below);
        let width = (self.hi - self.lo) / S::from_i32(m as i32);
        self.lo + (S::from_i32(k as i32) + within) * width
    }

    /// The share of the table's distribution at or below `x` (the CDF the draws follow).
    pub fn cdf_at(&self, x: S) -> S {
        if x.partial_cmp(&self.lo) != Some(Ordering::Greater) {
            return S::ZERO;
        }
        let m = self.cdf.len();
        if x >= self.hi || m == 0 {
            return S::ONE;
        }
        let pos = (x - self.lo) / (self.hi - self.lo) * S::from_i32(m as i32);
        let k = (pos.floor_i32().max(0) as usize).min(m - 1);
        let below = if k == 0 { S::ZERO } else { self.cdf[k - 1] };
        below + (self.cdf[k] - below) * (pos - S::from_i32(k as i32))
    }
}
