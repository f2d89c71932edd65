//! Each agent's nearest neighbours: the `k` agents nearest to it strictly within the
//! neighbour distance, nearest first, ties by id — exactly what
//! [`nearest::select`](crate::nearest::select) selects (tested), found with less work for a
//! crowd stepped in grid order:
//!
//! * the grid's cells are at least as large as the neighbour distance, so an agent's
//!   neighbours lie in the 3×3×3 block of cells around its own; the block's positions are
//!   copied once into a worker's [`Block`] (struct of arrays) and serve every agent of the
//!   cell (the crowd keeps its agents in grid order, so they come one after the other);
//! * the squared distances to the whole block are computed in one loop the compiler
//!   vectorises, and only the candidates within the bound are looked at (sixteen comparisons
//!   to a bit mask);
//! * the bound is first a hint (the crowd passes the distance of last step's `k`-th
//!   neighbour plus what two agents can have moved since), and only if fewer than `k` lie
//!   within it is the whole range looked at. The result does not depend on the hint: a
//!   search that keeps `k` within a bound has seen every agent closer;
//! * the few candidates within the bound (about `k`, thanks to the hint) are ranked all at
//!   once, without a branch on the data; when there are many (a first step, a dense crowd),
//!   they are kept one by one with a bound that shrinks to the `k`-th kept, as RVO2-3D's
//!   kd-tree query does.

use swarm_core::Vec3;

use super::MAX_NEIGHBORS;
use crate::grid::Grid;

/// A neighbour grid of cells at least as large as the neighbour distance.
#[derive(Clone, Debug, Default)]
pub(crate) struct Search {
    /// Whether the grid was built (a default `Search` covers nothing).
    built: bool,
    grid: Grid,
    /// The box the grid covers.
    lo: [f32; 3],
    hi: [f32; 3],
    /// The neighbour distance, squared.
    range2: f32,
}

impl Search {
    /// A grid over `[lo, hi]` for the neighbour distance `range` with at most about
    /// `budget` cells.
    pub(crate) fn new(lo: [f32; 3], hi: [f32; 3], range: f32, budget: usize) -> Search {
        // A little larger than the range: two points closer than the range are at most one
        // cell apart along every axis, whatever the rounding of their cell coordinates.
        let cell = fitted_cell(lo, hi, range * 1.001 + 1e-5 * extent(lo, hi), budget);
        Search {
            built: true,
            grid: Grid::new(lo, hi, cell),
            lo,
            hi,
            range2: range * range,
        }
    }

    /// Whether the grid's box holds `[lo, hi]`.
    pub(crate) fn covers(&self, lo: [f32; 3], hi: [f32; 3]) -> bool {
        self.built && (0..3).all(|k| self.lo[k] <= lo[k] && hi[k] <= self.hi[k])
    }

    /// Puts `items` (agent `i` at `pos(&items[i])`, all inside the box) in the grid.
    pub(crate) fn rebuild<T: Sync>(&mut self, items: &[T], pos: impl Fn(&T) -> [f32; 3] + Sync) {
        self.grid.rebuild(items, pos);
    }

    /// The agents sorted by cell (then index), as of the last [`Search::rebuild`].
    pub(crate) fn order(&self) -> &[u32] {
        self.grid.order()
    }

    /// After the caller renumbered its agents in [`Search::order`]'s order.
    pub(crate) fn renumber_in_order(&mut self) {
        self.grid.renumber_in_order();
    }

    /// The `k ≤ MAX_NEIGHBORS` agents nearest to `me` strictly within the range (slot `skip`
    /// excluded), nearest first, ties by id (`ids[slot]`), looking within `hint` first.
    /// `block` is the worker's scratch.
    #[inline]
    pub(crate) fn nearest(
        &self,
        block: &mut Block,
        me: Vec3<f32>,
        k: usize,
        hint: f32,
        skip: u32,
        ids: &[u32],
    ) -> Found {
        let cap = k.min(MAX_NEIGHBORS);
        if cap == 0 {
            return Found::new(0, self.range2);
        }
        self.load(block, [me.x, me.y, me.z]);
        block.distances(me);
        let hint2 = hint * hint;
        if hint2 < self.range2 {
            let found = block.keep(cap, hint2, skip, ids);
            if found.len == cap {
                return found;
            }
        }
        block.keep(cap, self.range2, skip, ids)
    }

    /// Makes `block` hold the agents of the 3×3×3 cells around the cell of `p`.
    #[inline]
    fn load(&self, block: &mut Block, p: [f32; 3]) {
        let c = self.grid.coords(p);
        if block.cell == Some(c) {
            return;
        }
        block.clear();
        block.cell = Some(c);
        let dims = self.grid.dims();
        let around = |k: usize| c[k].saturating_sub(1)..=(c[k] + 1).min(dims[k] - 1);
        for z in around(2) {
            for y in around(1) {
                let x = around(0);
                let first = self.grid.index_of([*x.start(), y, z]);
                let last = self.grid.index_of([*x.end(), y, z]);
                let (slots, pts) = self.grid.cells_agents(first, last);
                block.extend(slots, pts);
            }
        }
    }
}

/// The largest extent of the box `[lo, hi]` and its distance from the origin (a scale for
/// rounding).
fn extent(lo: [f32; 3], hi: [f32; 3]) -> f32 {
    (0..3)
        .map(|k| lo[k].abs().max(hi[k].abs()))
        .fold(0.0, f32::max)
}

/// The cell edge, at least `edge`, for which a grid over `[lo, hi]` has at most `budget`
/// cells.
pub(crate) fn fitted_cell(lo: [f32; 3], hi: [f32; 3], edge: f32, budget: usize) -> f32 {
    let cells = |c: f32| {
        (0..3)
            .map(|k| ((hi[k] - lo[k]) / c).ceil().max(1.0) as f64)
            .product::<f64>()
    };
    let mut c = edge;
    while cells(c) > budget as f64 {
        c *= 1.25;
    }
    c
}

/// A worker's scratch: the agents of one block of cells (struct of arrays) and their squared
/// distances to the current agent.
#[derive(Clone, Debug, Default)]
pub(crate) struct Block {
    /// The cell whose block this is.
    cell: Option<[u32; 3]>,
    x: Vec<f32>,
    y: Vec<f32>,
    z: Vec<f32>,
    slots: Vec<u32>,
    d2: Vec<f32>,
}

/// Candidates compared to the bound at once (bits of one mask).
const LANES: usize = 16;

impl Block {
    fn clear(&mut self) {
        self.x.clear();
        self.y.clear();
        self.z.clear();
        self.slots.clear();
    }

    fn extend(&mut self, slots: &[u32], pts: &[[f32; 3]]) {
        self.slots.extend_from_slice(slots);
        self.x.extend(pts.iter().map(|p| p[0]));
        self.y.extend(pts.iter().map(|p| p[1]));
        self.z.extend(pts.iter().map(|p| p[2]));
    }

    /// The squared distances from `me`, computed as `(q − me).length_sq()` is.
    #[inline]
    fn distances(&mut self, me: Vec3<f32>) {
        let n = self.slots.len();
        // Padded to whole masks with distances nothing is below.
        self.d2.resize(n.next_multiple_of(LANES), f32::INFINITY);
        let (x, y, z) = (&self.x[..n], &self.y[..n], &self.z[..n]);
        for (((d, &qx), &qy), &qz) in self.d2[..n].iter_mut().zip(x).zip(y).zip(z) {
            let (a, b, c) = (qx - me.x, qy - me.y, qz - me.z);
            *d = a * a + b * b + c * c;
        }
        self.d2[n..].fill(f32::INFINITY);
    }

    /// The `cap` nearest candidates strictly within the squared distance `bound2`, `skip`
    /// excluded: ranked all at once when there are at most [`RANKED`] within the bound,
    /// else one by one with a shrinking bound.
    #[inline]
    fn keep(&self, cap: usize, bound2: f32, skip: u32, ids: &[u32]) -> Found {
        let mut near = Near::new(bound2);
        if self.collect(&mut near, skip, ids) {
            near.ranked(cap)
        } else {
            self.offer_all(Found::new(cap, bound2), skip, ids)
        }
    }

    /// Collects the candidates within `near`'s bound; `false` if more than [`RANKED`].
    #[inline]
    fn collect(&self, near: &mut Near, skip: u32, ids: &[u32]) -> bool {
        let limit = f32::from_bits((near.bound >> 32) as u32);
        for (chunk, d2) in self.d2.chunks_exact(LANES).enumerate() {
            let mut mask = within(d2, limit);
            while mask != 0 {
                let i = chunk * LANES + mask.trailing_zeros() as usize;
                mask &= mask - 1;
                let (Some(&d), Some(&slot)) = (self.d2.get(i), self.slots.get(i)) else {
                    continue;
                };
                let Some(&id) = ids.get(slot as usize) else {
                    continue;
                };
                let key = (u64::from(d.to_bits()) << 32) | u64::from(id);
                if slot != skip && key < near.bound && !near.push(key, slot) {
                    return false;
                }
            }
        }
        true
    }

    /// Offers `found` every candidate whose squared distance is below its bound.
    #[inline]
    fn offer_all(&self, mut found: Found, skip: u32, ids: &[u32]) -> Found {
        for (chunk, d2) in self.d2.chunks_exact(LANES).enumerate() {
            let mut mask = within(d2, found.limit());
            while mask != 0 {
                let i = chunk * LANES + mask.trailing_zeros() as usize;
                mask &= mask - 1;
                if let (Some(&d), Some(&slot)) = (self.d2.get(i), self.slots.get(i)) {
                    found.offer(d, slot, skip, ids);
                }
            }
        }
        found
    }
}

/// Bit `j` set where `d2[j] ≤ limit`.
#[inline]
fn within(d2: &[f32], limit: f32) -> u32 {
    d2.iter()
        .enumerate()
        .fold(0u32, |m, (j, &d)| m | (u32::from(d <= limit) << j))
}

/// The most candidates [`Block::keep`] ranks all at once.
const RANKED: usize = 48;

/// Candidates within a bound, in the order met, to be ranked.
struct Near {
    keys: [u64; RANKED],
    slots: [u32; RANKED],
    len: usize,
    /// Keys at or above this are not candidates.
    bound: u64,
}

impl Near {
    fn new(bound2: f32) -> Near {
        Near {
            keys: [u64::MAX; RANKED],
            slots: [0; RANKED],
            len: 0,
            bound: u64::from(bound2.to_bits()) << 32,
        }
    }

    /// Adds a candidate; `false` if full.
    #[inline]
    fn push(&mut self, key: u64, slot: u32) -> bool {
        let (Some(k), Some(s)) = (self.keys.get_mut(self.len), self.slots.get_mut(self.len)) else {
            return false;
        };
        (*k, *s) = (key, slot);
        self.len += 1;
        true
    }

    /// The `cap` smallest keys, each put where its rank (the number of smaller keys; keys
    /// are unique) says: no branch on the data, and a loop the compiler vectorises.
    #[inline]
    fn ranked(&self, cap: usize) -> Found {
        let mut found = Found::new(cap, 0.0);
        let keys = &self.keys[..self.len];
        // Rank `MAX_NEIGHBORS` and beyond lands in the spare last item.
        let mut items = [(0u64, 0u32); MAX_NEIGHBORS + 1];
        for (&key, &slot) in keys.iter().zip(&self.slots) {
            let rank: usize = keys.iter().map(|&k| usize::from(k < key)).sum();
            items[rank.min(MAX_NEIGHBORS)] = (key, slot);
        }
        found.len = self.len.min(cap);
        found.items.copy_from_slice(&items[..MAX_NEIGHBORS]);
        found
    }
}

/// The neighbours a search found: `(key, slot)` by increasing key, where the key is the
/// squared distance's bits then the id (`nearest::key`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Found {
    items: [(u64, u32); MAX_NEIGHBORS],
    len: usize,
    /// How many to keep.
    cap: usize,
    /// A candidate is kept if its key is below this: the bound's, then the last kept one's.
    bound: u64,
}

impl Found {
    /// Nothing found yet, `cap` to keep, strictly within the squared distance `bound2`.
    fn new(cap: usize, bound2: f32) -> Found {
        Found {
            items: [(0, 0); MAX_NEIGHBORS],
            len: 0,
            cap,
            bound: u64::from(bound2.to_bits()) << 32,
        }
    }

    /// The squared distance beyond which nothing can be kept any more.
    #[inline]
    fn limit(&self) -> f32 {
        f32::from_bits((self.bound >> 32) as u32)
    }

    /// Offers slot `slot` at squared distance `d` (≥ 0).
    #[inline]
    fn offer(&mut self, d: f32, slot: u32, skip: u32, ids: &[u32]) {
        let bits = d.to_bits();
        if bits > (self.bound >> 32) as u32 || slot == skip {
            return;
        }
        let Some(&id) = ids.get(slot as usize) else {
            return;
        };
        let key = (u64::from(bits) << 32) | u64::from(id);
        if key >= self.bound {
            return;
        }
        if self.len < self.cap {
            self.len += 1;
        }
        let mut i = self.len - 1;
        while i > 0 && self.items[i - 1].0 > key {
            self.items[i] = self.items[i - 1];
            i -= 1;
        }
        self.items[i] = (key, slot);
        if self.len == self.cap {
            self.bound = self.items[self.cap - 1].0;
        }
    }

    /// The distance of the farthest one kept if `k` were found, else infinity.
    pub(crate) fn reach(&self) -> f32 {
        if self.len == self.cap && self.cap > 0 {
            f32::from_bits((self.items[self.cap - 1].0 >> 32) as u32).sqrt()
        } else {
            f32::INFINITY
        }
    }

    /// How many were found.
    pub(crate) fn len(&self) -> usize {
        self.len
    }

    /// Their slots, nearest first.
    pub(crate) fn slots(&self) -> impl Iterator<Item = usize> + '_ {
        self.items[..self.len].iter().map(|&(_, s)| s as usize)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nearest::{Selected, select};

    /// Points on a lattice (many exact distance ties) or jittered.
    fn points(n: u32, jitter: bool) -> Vec<Vec3<f32>> {
        (0..n)
            .map(|i| {
                let u = |k| {
                    if jitter {
                        swarm_core::rand::rand(5, i, 0, k) as f32 / 4_294_967_296.0
                    } else {
                        0.0
                    }
                };
                let c = [i % 13, i / 13 % 11, i / 143].map(|c| c as f32 * 2.0);
                Vec3::new(c[0] + 3.0 * u(0), c[1] + 3.0 * u(1), c[2] - 40.0 * u(2))
            })
            .collect()
    }

    #[test]
    fn finds_exactly_what_nearest_select_selects() {
        for jitter in [false, true] {
            let pts = points(2000, jitter);
            // Ids in another order than slots, so that ties by id and by slot differ.
            let ids: Vec<u32> = (0..pts.len() as u32).map(|s| (s * 7919) % 2000).collect();
            let (lo, hi) = super::super::bounds(&pts, |p| [p.x, p.y, p.z]);
            for range in [1.5f32, 4.0, 7.3] {
                for budget in [1 << 20, 64] {
                    let mut search = Search::new(lo, hi, range, budget);
                    search.rebuild(&pts, |p| [p.x, p.y, p.z]);
                    let mut block = Block::default();
                    for (s, &me) in pts.iter().enumerate().step_by(7) {
                        let want: Selected<MAX_NEIGHBORS> = select::<f32, MAX_NEIGHBORS>(
                            &search.grid,
                            me,
                            range,
                            s as u32,
                            |_, q| Vec3::new(q[0], q[1], q[2]),
                            |j| ids[j as usize],
                        );
                        let want: Vec<usize> = want.slots().collect();
                        for k in [0, 1, 5, 10, 16] {
                            // No hint, a good one, one too small (a second look) and a
                            // useless one.
                            for hint in [f32::INFINITY, range / 2.0, 0.1, f32::NAN] {
                                let got = search.nearest(&mut block, me, k, hint, s as u32, &ids);
                                let got: Vec<usize> = got.slots().collect();
                                let n = k.min(want.len());
                                assert_eq!(
                                    got,
                                    want[..n],
                                    "slot {s} range {range} budget {budget} k {k} hint {hint}"
                                );
                            }
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn fitted_cells_stay_within_the_budget() {
        let (lo, hi) = ([0.0; 3], [1000.0, 10.0, 1e6]);
        let c = fitted_cell(lo, hi, 1.0, 1 << 16);
        let cells: f64 = (0..3)
            .map(|k| ((hi[k] - lo[k]) / c).ceil().max(1.0) as f64)
            .product();
        assert!(cells <= 65536.0, "{c} {cells}");
        assert_eq!(fitted_cell(lo, [3.0; 3], 1.0, 1000), 1.0);
    }
}
