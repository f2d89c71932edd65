//! The nearest entries of a neighbour grid around a point, chosen the same way on every
//! backend: by the squared distance computed in the querying agent's scalar (its order bits,
//! [`SimScalar::order_bits`]), then a stable tie key, whatever order the grid yields them in.
//! Every model's sensing selects its neighbours through [`select`].

use swarm_core::Vec3;

use crate::grid::Grid;
use crate::scalar::SimScalar;

/// Candidates buffered before a merge.
const SCAN: usize = 48;
/// Room for a merge: `SCAN` candidates plus the `K ≤ 16` kept so far.
const KEYED: usize = 64;

/// Selection key: the order bits of the squared distance in the sensing bee's scalar
/// ([`SimScalar::order_bits`]), then the tie key.
#[inline]
pub(crate) fn key(d: u32, tie: u32) -> u64 {
    (u64::from(d) << 32) | u64::from(tie)
}

/// The `K` nearest entries of a query, sorted by squared distance then tie key, each as
/// `(key, slot)`: a deterministic selection whatever the order (or slots) candidates arrive in.
#[derive(Debug)]
pub(crate) struct Selected<const K: usize> {
    /// `(key, slot)`, nearest first; the first `len` are meaningful.
    pub(crate) items: [(u64, u32); K],
    /// How many were selected.
    pub(crate) len: usize,
    /// How many entries were within the range (more than `K`: the selection was truncated).
    pub(crate) within: usize,
}

impl<const K: usize> Selected<K> {
    pub(crate) fn new() -> Self {
        const { assert!(K >= 1 && K + SCAN <= KEYED) };
        Selected {
            items: [(0, 0); K],
            len: 0,
            within: 0,
        }
    }

    /// The selected slots, nearest first.
    pub(crate) fn slots(&self) -> impl Iterator<Item = usize> + '_ {
        self.items[..self.len].iter().map(|&(_, s)| s as usize)
    }

    /// Merges buffered `(squared distance order bits, slot)` candidates: keeps the `K`
    /// smallest `(distance, tie(slot))`.
    fn merge(&mut self, cands: &[(u32, u32)], tie: &impl Fn(u32) -> u32) {
        let mut keyed = [(0u64, 0u32); KEYED];
        keyed[..self.len].copy_from_slice(&self.items[..self.len]);
        // Once K are kept, a candidate not nearer than the K-th cannot be kept.
        let worst = if self.len == K {
            self.items[K - 1].0
        } else {
            u64::MAX
        };
        let mut n = self.len;
        for &(d, j) in cands {
            let k = key(d, tie(j));
            if k < worst {
                keyed[n] = (k, j);
                n += 1;
            }
        }
        if n > self.len {
            self.take(&mut keyed[..n]);
        }
    }

    /// Keeps the `K` smallest of `keyed`, sorted (keys are unique: the tie keys are): the
    /// K-th found first, then only those before it sorted.
    fn take(&mut self, keyed: &mut [(u64, u32)]) {
        if keyed.len() > K {
            keyed.select_nth_unstable_by_key(K - 1, |e| e.0);
        }
        self.len = keyed.len().min(K);
        let kept = &mut keyed[..self.len];
        kept.sort_unstable_by_key(|e| e.0);
        self.items[..self.len].copy_from_slice(kept);
    }
}

/// The `K` entries of `grid` nearest to `me` strictly within `range`, `skip` excluded, ties
/// broken by `tie(slot)`, by squared distance in the scalar `S` (`at(slot, copy)`: an entry's
/// position in `S` from its slot and the grid's `f32` copy `copy`). The grid query and an
/// `f32` pre-selection (`range` plus a rounding margin) only narrow the candidates.
pub(crate) fn select<S: SimScalar, const K: usize>(
    grid: &Grid,
    me: Vec3<S>,
    range: f32,
    skip: u32,
    at: impl Fn(u32, [f32; 3]) -> Vec3<S>,
    tie: impl Fn(u32) -> u32,
) -> Selected<K> {
    let [near] = select_bands::<S, K, 1>(grid, me, [range], skip, at, tie);
    near
}

/// [`select`] in `B` distance bands at once: band `b` holds the `K` nearest entries with
/// `bounds[b − 1] ≤ distance < bounds[b]` (band 0 from 0), the bounds ascending, each band's
/// `within` counting its own entries. One grid query serves every band.
pub(crate) fn select_bands<S: SimScalar, const K: usize, const B: usize>(
    grid: &Grid,
    me: Vec3<S>,
    bounds: [f32; B],
    skip: u32,
    at: impl Fn(u32, [f32; 3]) -> Vec3<S>,
    tie: impl Fn(u32) -> u32,
) -> [Selected<K>; B] {
    let p = me.to_f32();
    let p = [p.x, p.y, p.z];
    let range = bounds[B - 1];
    let r2 = bounds.map(squared::<S>);
    let loose = loose2(range);
    let mut out = core::array::from_fn::<_, B, _>(|_| Selected::new());
    let mut buf = [[(0u32, 0u32); SCAN]; B];
    let mut len = [0usize; B];
    grid.for_each_candidate(p, range + MARGIN, |j, q| {
        if j == skip || d2f(q, p) >= loose {
            return;
        }
        let d = (at(j, q) - me).length_sq();
        let Some(b) = r2.iter().position(|&r2| d < r2) else {
            return;
        };
        out[b].within += 1;
        buf[b][len[b]] = (d.order_bits(), j);
        len[b] += 1;
        if len[b] == SCAN {
            out[b].merge(&buf[b], &tie);
            len[b] = 0;
        }
    });
    for b in 0..B {
        out[b].merge(&buf[b][..len[b]], &tie);
    }
    out
}

/// What the `f32` pre-selections add to a range for the rounding of positions to `f32`.
const MARGIN: f32 = 1e-3;

/// `r` squared, in `S`.
pub(crate) fn squared<S: SimScalar>(r: f32) -> S {
    let r = S::from_f32(r);
    r * r
}

/// `r` plus [`MARGIN`] (relative too), squared: the radius of an `f32` pre-selection.
pub(crate) fn loose2(r: f32) -> f32 {
    let r = r + MARGIN * (1.0 + r);
    r * r
}

/// Squared distance, from the grid's `f32` copy of the positions (pre-selection only).
#[inline]
pub(crate) fn d2f(a: [f32; 3], b: [f32; 3]) -> f32 {
    let d = [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    d[0] * d[0] + d[1] * d[1] + d[2] * d[2]
}
