//! The sensor frame of a bee, built from the world exactly as a robot would sense it: the
//! nearest neighbours within the SPH range with their broadcast velocity and density, the
//! nearest target particles, the goal, and the nearest obstacle. The HIL harness feeds devices
//! with this same function.

use swarm_core::Vec3;
use swarm_core::bee::{BeeFrame, BeeNeighbor, ObstacleSense};
use swarm_core::wire::{WIRE_BEE_NEIGHBOURS, WIRE_BEE_TARGETS};

use super::world::BeeWorld;
use crate::nearest::{Selected, d2f, key, loose2, select, squared};
use crate::scalar::{SimScalar, v3};

/// Neighbour capacity of a bee frame (the wire's).
pub const N: usize = WIRE_BEE_NEIGHBOURS;
/// Target-particle capacity of a bee frame (the wire's).
pub const P: usize = WIRE_BEE_TARGETS;

/// The sensor frame of the simulator (and of the wire).
pub type BeeSimFrame<S> = BeeFrame<S, N, P>;

/// Sorts entries with distinct keys by key: insertion sort when there are few (the usual
/// handful of neighbours), else the standard sort.
fn sort_small(items: &mut [(u64, u32)]) {
    if items.len() > 24 {
        items.sort_unstable_by_key(|e| e.0);
        return;
    }
    for a in 1..items.len() {
        let x = items[a];
        let mut b = a;
        while b > 0 && items[b - 1].0 > x.0 {
            items[b] = items[b - 1];
            b -= 1;
        }
        items[b] = x;
    }
}

/// Writes the (at most `N`) entries of `keyed` into `out` sorted by key, placing each by its
/// rank among the distances (the high halves of the keys, compared 16 at a time without a
/// data-dependent branch). Returns `false`, writing nothing meaningful, when there are more
/// than `N` entries or two equal distances (then the caller sorts by the full key).
fn rank_distinct(keyed: &[(u64, u32)], out: &mut [(u64, u32); N]) -> bool {
    const { assert!(N <= 16) };
    if keyed.len() > N {
        return false;
    }
    let mut dist = [u32::MAX; 16];
    for (d, &(k, _)) in dist.iter_mut().zip(keyed) {
        *d = (k >> 32) as u32;
    }
    let mut placed = 0u32;
    for (&d, &e) in dist.iter().zip(keyed) {
        let rank = dist.iter().map(|&x| u32::from(x < d)).sum::<u32>() as usize;
        if let Some(slot) = out.get_mut(rank) {
            *slot = e;
        }
        placed |= 1 << rank;
    }
    placed == (1u32 << keyed.len()) - 1
}

/// The `N` bees nearest to slot `i` within the world's neighbour range (strictly: capsule gap
/// below h), nearest first, ties by stable id: the same bees whatever the slot order.
fn neighbours<S: SimScalar>(w: &BeeWorld, i: usize) -> Selected<N> {
    let me = v3::<S>(w.sensed.pos[i]);
    let ids = &w.sensed.id;
    let at = |j: u32, q: [f32; 3]| S::sensed3(q, || w.sensed.pos[j as usize]);
    select::<S, N>(&w.grid, me, w.range, i as u32, at, |j| ids[j as usize])
}

/// The sensed slots of the `N` bees nearest to slot `i` within the world's neighbour range
/// (strictly: capsule gap below h), nearest first, ties by stable id: the same bees whatever
/// the slot order.
pub fn neighbour_slots<S: SimScalar>(w: &BeeWorld, i: usize) -> impl Iterator<Item = usize> {
    let near = neighbours::<S>(w, i);
    (0..near.len).map(move |k| near.items[k].1 as usize)
}

/// The candidates of one grid cell's 3×3×3 block, gathered once and shared by the bees of that
/// cell (slots are sorted by cell, so consecutive bees mostly share one). Gives exactly the
/// neighbours [`neighbour_slots`] gives: the grid's cells are a little larger than the range,
/// so a bee two cells away is never in range, even after `f32` rounding. The engine's frames
/// go through it ([`bee_frame`] is the same frame without it).
#[derive(Debug, Default)]
pub(crate) struct BlockCache {
    cell: Option<u32>,
    /// The block's candidates, struct of arrays (the distance loop vectorizes): positions and
    /// slots.
    xs: Vec<f32>,
    ys: Vec<f32>,
    zs: Vec<f32>,
    slots: Vec<u32>,
    /// How many of them there are (the vectors are longer: room for a block).
    n: usize,
    /// Squared distances of the candidates to the current bee.
    d: Vec<f32>,
    /// (selection key, slot) of the candidates in range.
    keyed: Vec<(u64, u32)>,
}

impl BlockCache {
    /// The `N` neighbours of slot `i` (as [`neighbour_slots`]).
    pub(crate) fn neighbours<S: SimScalar>(&mut self, w: &BeeWorld, i: usize) -> Selected<N> {
        let me = w.sensed.pos[i];
        let p = [me[0] as f32, me[1] as f32, me[2] as f32];
        let Some((cell, center)) = w.grid.cell_center(p) else {
            return neighbours::<S>(w, i);
        };
        debug_assert_eq!(cell, w.grid.cell_of(p));
        if self.cell != Some(cell) {
            self.fill(w, cell, center);
        }
        // Distances exactly as `d2f` computes them.
        let n = self.n;
        let (xs, ys, zs) = (&self.xs[..n], &self.ys[..n], &self.zs[..n]);
        for (((d, &x), &y), &z) in self.d[..n].iter_mut().zip(xs).zip(ys).zip(zs) {
            let (dx, dy, dz) = (x - p[0], y - p[1], z - p[2]);
            *d = dx * dx + dy * dy + dz * dz;
        }
        // Keys (distance in `S`, stable id: the order `neighbour_slots` uses) of those in
        // range: an `f32` pre-selection as a bit mask per 64 candidates (vectorizable), then
        // one step per set bit.
        let (loose, me_slot, ids) = (loose2(w.range), i as u32, &w.sensed.id);
        let (me_s, r2) = (v3::<S>(me), squared::<S>(w.range));
        let mut len = 0usize;
        // `d` is padded with +∞ to whole chunks of 64 (see `fill`).
        for (c, ds) in self.d[..n.next_multiple_of(64)]
            .chunks_exact(64)
            .enumerate()
        {
            let mut flags = [0u8; 64];
            for (f, &d) in flags.iter_mut().zip(ds) {
                *f = u8::from(d < loose);
            }
            // Eight 0/1 bytes to eight bits at a time.
            let mut mask = 0u64;
            for (g, bytes) in flags.chunks_exact(8).enumerate() {
                let v = u64::from_le_bytes(bytes.try_into().unwrap_or([0; 8]));
                mask |= (v.wrapping_mul(0x0102_0408_1020_4080) >> 56) << (8 * g);
            }
            while mask != 0 {
                let k = c * 64 + mask.trailing_zeros() as usize;
                mask &= mask - 1;
                let slot = self.slots[k];
                let q = [self.xs[k], self.ys[k], self.zs[k]];
                let d = (S::sensed3(q, || w.sensed.pos[slot as usize]) - me_s).length_sq();
                self.keyed[len] = (key(d.order_bits(), ids[slot as usize]), slot);
                len += usize::from(slot != me_slot && d < r2);
            }
        }
        let keyed = &mut self.keyed[..len];
        let mut out = Selected::new();
        out.len = len.min(N);
        if !rank_distinct(keyed, &mut out.items) {
            sort_small(keyed);
            out.items[..out.len].copy_from_slice(&keyed[..out.len]);
        }
        out
    }

    /// Gathers the candidates of `cell`'s 3×3×3 block.
    fn fill(&mut self, w: &BeeWorld, cell: u32, center: [f32; 3]) {
        self.cell = Some(cell);
        loop {
            // Written by index into slices of the current room (no per-candidate growth
            // check); with too little room, grow and gather again.
            let room = self.slots.len();
            let (xs, ys, zs) = (
                &mut self.xs[..room],
                &mut self.ys[..room],
                &mut self.zs[..room],
            );
            let slots = &mut self.slots[..room];
            let mut n = 0usize;
            w.grid.for_each_candidate(center, w.grid.cell(), |j, q| {
                if n < room {
                    (xs[n], ys[n], zs[n], slots[n]) = (q[0], q[1], q[2], j);
                }
                n += 1;
            });
            if n <= room {
                self.n = n;
                // Padding for the chunks of 64 of the range test: never in range.
                self.d[n..n.next_multiple_of(64)].fill(f32::INFINITY);
                return;
            }
            // A power of two of at least 64: a multiple of 64.
            let room = n.next_power_of_two().max(64);
            self.xs.resize(room, 0.0);
            self.ys.resize(room, 0.0);
            self.zs.resize(room, 0.0);
            self.slots.resize(room, 0);
            self.d.resize(room, 0.0);
            self.keyed.resize(room, (0, 0));
        }
    }
}

/// The sensor frame of the bee in slot `i` at time `t` (chen §IV-V):
///
/// * `neighbours`: the `N` nearest bees within h + 2r (the world's [`range`](BeeWorld::range)),
///   by distance then stable id, with the position, velocity and density they broadcast;
/// * `targets`: the `P` nearest virtual particles of the active targets within the same range
///   (by distance, then particle index);
/// * `goal`: `group_goal`, the centre of the group's target;
/// * `obstacle`: the nearest active obstacle within the sensing range 2·d0 (a bee inside an
///   obstacle is at distance 0; ties by obstacle order): its closest surface point and outward
///   unit normal.
pub fn bee_frame<S: SimScalar>(
    w: &BeeWorld,
    i: usize,
    group_goal: Option<[f32; 3]>,
    t: S,
) -> BeeSimFrame<S> {
    let mut frame = BeeFrame::new(t);
    fill_with(w, i, &neighbours::<S>(w, i), group_goal, t, &mut frame);
    frame
}

/// [`bee_frame`] with the neighbours found through `cache` (the same frame, faster).
#[cfg(test)]
pub(crate) fn bee_frame_cached<S: SimScalar>(
    w: &BeeWorld,
    i: usize,
    group_goal: Option<[f32; 3]>,
    t: S,
    cache: &mut BlockCache,
) -> BeeSimFrame<S> {
    let mut frame = BeeFrame::new(t);
    fill_frame(w, i, group_goal, t, cache, &mut frame);
    frame
}

/// [`bee_frame_cached`] written into `frame` (the engine reuses one frame per thread).
pub(crate) fn fill_frame<S: SimScalar>(
    w: &BeeWorld,
    i: usize,
    group_goal: Option<[f32; 3]>,
    t: S,
    cache: &mut BlockCache,
    frame: &mut BeeSimFrame<S>,
) {
    let near = cache.neighbours::<S>(w, i);
    fill_with(w, i, &near, group_goal, t, frame);
}

fn fill_with<S: SimScalar>(
    w: &BeeWorld,
    i: usize,
    near: &Selected<N>,
    group_goal: Option<[f32; 3]>,
    t: S,
    frame: &mut BeeSimFrame<S>,
) {
    let s = &w.sensed;
    let me = s.pos[i];
    frame.t = t;
    frame.neighbours.clear();
    frame.targets.clear();
    for j in near.slots() {
        let _ = frame.neighbours.push(BeeNeighbor {
            pos: v3(s.pos[j]),
            vel: v3(s.vel[j]),
            density: S::from_f64(s.density[j]),
        });
    }

    let p = [me[0] as f32, me[1] as f32, me[2] as f32];
    let me_s = v3::<S>(me);
    // Particles lie on their targets' spheres: query only near one (a margin for rounding).
    let near_target = w.target_spheres.iter().any(|&(c, r)| {
        let reach = r + w.range + 1e-3 * (1.0 + r);
        d2f(c, p) <= reach * reach
    });
    if near_target {
        let at = |_, q: [f32; 3]| Vec3::from_f32(q[0], q[1], q[2]);
        let near = select::<S, P>(&w.particle_grid, me_s, w.range, u32::MAX, at, |j| j);
        for j in near.slots() {
            let q = w.particles[j];
            let _ = frame.targets.push(Vec3::from_f32(q[0], q[1], q[2]));
        }
    }

    frame.goal = group_goal.map(|g| Vec3::from_f32(g[0], g[1], g[2]));

    let range = S::from_f32(w.sense_range);
    let mut best: Option<(S, ObstacleSense<S>)> = None;
    for o in w.obstacles.iter().filter(|o| o.active) {
        if !o.may_be_within(me, f64::from(w.sense_range)) {
            continue;
        }
        let surf = w.surface(o, me_s);
        let dist = if surf.inside { S::ZERO } else { surf.distance };
        if dist <= range && best.as_ref().is_none_or(|(b, _)| dist < *b) {
            let sensed = ObstacleSense {
                point: surf.point,
                normal: surf.normal,
            };
            best = Some((dist, sensed));
        }
    }
    frame.obstacle = best.map(|(_, o)| o);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bees::world::{BeeObstacle, BeeTarget, Shape3};
    use crate::grid::Grid;

    fn v(p: [f32; 3]) -> Vec3<f32> {
        Vec3::new(p[0], p[1], p[2])
    }

    #[test]
    fn select_keeps_the_k_nearest_in_order_even_past_the_scan_buffer() {
        // 300 points, many in range and many at exactly equal distances (a lattice), so the
        // buffer overflows and ties are broken by the tie key.
        let pts: Vec<[f32; 3]> = (0..300u32)
            .map(|i| {
                let u = |k| (swarm_core::rand::rand(9, i, 0, k) % 8) as f32 * 0.25;
                [5.0 + u(0), 5.0 + u(1), 5.0 + u(2)]
            })
            .collect();
        let mut grid = Grid::new([0.0; 3], [10.0; 3], 1.0);
        grid.rebuild(&pts, |p| *p);
        let tie = |j: u32| 1000 - j;
        let p = [5.5, 5.5, 5.5];
        for range in [0.3f32, 1.0, 3.0] {
            let at = |j: u32, _| v(pts[j as usize]);
            let got: Vec<usize> = select::<f32, 16>(&grid, v(p), range, 7, at, tie)
                .slots()
                .collect();
            let mut want: Vec<(f32, u32, usize)> = (0..pts.len())
                .filter(|&j| j != 7)
                .map(|j| (d2f(pts[j], p), tie(j as u32), j))
                .filter(|e| e.0 < range * range)
                .collect();
            want.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            let want: Vec<usize> = want.iter().take(16).map(|e| e.2).collect();
            assert_eq!(got, want, "range {range}");
        }
    }

    /// A dense random world: 3000 bees in a 24³ box (about 35 within range of each), stored in
    /// a shuffled slot order with ids unrelated to slots.
    fn dense_world(shuffle: u32) -> BeeWorld {
        let mut w = BeeWorld::new([0.0; 3], [24.0; 3], 3.5, 4.0);
        let n = 3000u32;
        w.sensed.resize(n as usize);
        for slot in 0..n {
            // A permutation of ids over slots.
            let id = (slot * 1237 + shuffle * 17) % n;
            let u = |k| swarm_core::rand::rand(5, id, 0, k) as f64 / 4_294_967_296.0 * 24.0;
            // Snap a few bees onto a lattice so exact distance ties happen.
            let pos = if id.is_multiple_of(10) {
                [(id % 7) as f64, 4.0, 4.0]
            } else {
                [u(0), u(1), u(2)]
            };
            let s = slot as usize;
            w.sensed.pos[s] = pos;
            w.sensed.vel[s] = [id as f64, 0.0, 0.0];
            w.sensed.density[s] = 0.01 * id as f64;
            w.sensed.id[s] = id;
        }
        w.size_grids(n as usize);
        w.index_positions();
        w
    }

    #[test]
    fn neighbour_selection_matches_brute_force_whatever_the_slot_order() {
        let r2 = 3.5f32 * 3.5;
        let ids_of = |w: &BeeWorld, slot: usize| -> Vec<u32> {
            neighbour_slots::<f32>(w, slot)
                .map(|j| w.sensed.id[j])
                .collect()
        };
        let (a, b) = (dense_world(0), dense_world(5));
        let slot_of = |w: &BeeWorld, id: u32| w.sensed.id.iter().position(|&x| x == id).unwrap();
        for id in (0..3000u32).step_by(7) {
            let i = slot_of(&a, id);
            let p = a.sensed.pos[i].map(|x| x as f32);
            let mut want: Vec<(f32, u32)> = (0..a.len())
                .filter(|&j| j != i)
                .map(|j| (d2f(a.sensed.pos[j].map(|x| x as f32), p), a.sensed.id[j]))
                .filter(|&(d, _)| d < r2)
                .collect();
            want.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
            want.truncate(N);
            let want: Vec<u32> = want.into_iter().map(|(_, id)| id).collect();
            assert_eq!(ids_of(&a, i), want, "bee {id}");
            assert_eq!(
                ids_of(&b, slot_of(&b, id)),
                want,
                "bee {id}, other slot order"
            );
            // The frame carries exactly those bees, nearest first, with their broadcast data.
            let f = bee_frame::<f32>(&a, i, None, 0.0);
            let got: Vec<u32> = f.neighbours.iter().map(|n| n.vel.x as u32).collect();
            assert_eq!(got, want);
            for n in &f.neighbours {
                let j = slot_of(&a, n.vel.x as u32);
                assert_eq!(n.density, a.sensed.density[j] as f32);
                assert_eq!(n.pos.x, a.sensed.pos[j][0] as f32);
            }
        }
    }

    #[test]
    fn the_block_cache_gives_the_same_frames() {
        for shuffle in [0, 3] {
            let mut w = dense_world(shuffle);
            // A few bees on the box's faces and outside it (the uncached path).
            w.sensed.pos[10] = [24.0, 24.0, 24.0];
            w.sensed.pos[11] = [0.0, 12.0, 24.0];
            w.sensed.pos[12] = [-3.0, 12.0, 5.0];
            w.sensed.pos[13] = [25.0, 30.0, 5.0];
            w.index_positions();
            let mut cache = BlockCache::default();
            for i in 0..w.len() {
                let a = bee_frame::<f32>(&w, i, None, 1.0);
                let b = bee_frame_cached::<f32>(&w, i, None, 1.0, &mut cache);
                assert_eq!(a, b, "slot {i}");
            }
            let mut cache = BlockCache::default();
            for i in (0..w.len()).rev().step_by(3) {
                let a = bee_frame::<swarm_core::Fx>(
                    &w,
                    i,
                    None,
                    <swarm_core::Fx as swarm_core::Scalar>::ONE,
                );
                let b = bee_frame_cached(
                    &w,
                    i,
                    None,
                    <swarm_core::Fx as swarm_core::Scalar>::ONE,
                    &mut cache,
                );
                assert_eq!(a, b, "slot {i}");
            }
        }
    }

    #[test]
    fn frame_senses_targets_goal_and_the_nearest_obstacle() {
        let mut w = BeeWorld::new([0.0; 3], [40.0, 20.0, 40.0], 3.5, 4.0);
        w.sensed.resize(1);
        w.sensed.pos[0] = [10.0, 5.0, 10.0];
        w.obstacles = vec![
            BeeObstacle::new(
                0,
                "far",
                Shape3::Sphere {
                    center: [30.0, 5.0, 30.0],
                    radius: 2.0,
                },
                true,
            ),
            BeeObstacle::new(
                1,
                "shaft",
                Shape3::Shaft {
                    center: [13.0, 10.0],
                    radius: 1.0,
                    y_min: 0.0,
                    y_max: 20.0,
                },
                true,
            ),
            BeeObstacle::new(
                2,
                "closer but removed",
                Shape3::Box {
                    min: [10.5, 0.0, 9.0],
                    max: [11.0, 20.0, 11.0],
                },
                false,
            ),
        ];
        w.targets = vec![BeeTarget::new(3, "nest", [10.0, 5.0, 14.0], 1.5, 100)];
        w.size_grids(1);
        w.index_positions();
        w.index_targets();
        let f = bee_frame::<f32>(&w, 0, w.target_center(3), 2.5);
        assert_eq!(f.t, 2.5);
        assert!(f.neighbours.is_empty());
        assert_eq!(f.goal, Some(Vec3::new(10.0, 5.0, 14.0)));
        let ob = f.obstacle.unwrap();
        assert_eq!(ob.point, Vec3::new(12.0, 5.0, 10.0));
        assert_eq!(ob.normal, Vec3::new(-1.0, 0.0, 0.0));
        // The P nearest particles, all within range, nearest first.
        assert_eq!(f.targets.len(), P);
        let me = Vec3::new(10.0f32, 5.0, 10.0);
        let d: Vec<f32> = f.targets.iter().map(|&q| (q - me).length()).collect();
        assert!(d.windows(2).all(|x| x[0] <= x[1]) && d[P - 1] < 3.5);
        assert!((d[0] - 2.5).abs() < 0.1);
        // The removed box in place of the shaft once active; inside it: distance 0, normal out.
        w.obstacles[2].active = true;
        w.sensed.pos[0] = [10.9, 5.0, 10.0];
        let f = bee_frame::<f32>(&w, 0, None, 0.0);
        let ob = f.obstacle.unwrap();
        assert_eq!(ob.normal, Vec3::new(1.0, 0.0, 0.0));
        assert_eq!(ob.point, Vec3::new(11.0, 5.0, 10.0));
        // Beyond the sensing range: nothing.
        w.sensed.pos[0] = [3.0, 10.0, 3.0];
        w.index_positions();
        let f = bee_frame::<f32>(&w, 0, None, 0.0);
        assert!(f.obstacle.is_none() && f.targets.is_empty());
    }
}
