//! Sensor frames of an ant, built from the world exactly as a robot would sense it: the
//! nearest neighbours in contact range with their labels and latest arrival positions, the
//! objects in sensing range, the arena; then, for the second phase, the neighbours' broadcast
//! plans. The HIL harness feeds devices with these same functions.

use swarm_core::ant::{AntNeighbor, AntObject, PlanFrame, ResolveFrame, SURFACES, Surface};
use swarm_core::wire::{WIRE_ANT_NEIGHBOURS, WIRE_ANT_OBJECTS};
use swarm_core::{Rect, Vec2};

use super::world::{AntObjectDef, AntObjectKind, AntWorld};
use crate::scalar::{SimScalar, v2};

/// Neighbour capacity of an ant frame (the wire's).
pub const N: usize = WIRE_ANT_NEIGHBOURS;
/// Object capacity of an ant frame (the wire's).
pub const O: usize = WIRE_ANT_OBJECTS;

/// The plan-phase sensor frame of the simulator.
pub type AntPlanFrame<S> = PlanFrame<S, N, O>;
/// The resolve-phase sensor frame of the simulator.
pub type AntResolveFrame<S> = ResolveFrame<S, N>;

/// The `K` smallest `(key, tie)` pairs offered, in increasing order, each with its slot: a
/// deterministic nearest-K selection whatever the order (or slots) candidates arrive in. Keys
/// are distances (or squared distances) in the sensing ant's scalar.
#[derive(Debug)]
struct Nearest<T, const K: usize> {
    items: [(T, u32, u32); K],
    len: usize,
}

impl<T: PartialOrd + Copy, const K: usize> Nearest<T, K> {
    fn new(zero: T) -> Self {
        Nearest {
            items: [(zero, 0, 0); K],
            len: 0,
        }
    }
    fn offer(&mut self, key: T, tie: u32, slot: u32) {
        let item = (key, tie, slot);
        let less = |a: (T, u32, u32), b: (T, u32, u32)| a.0 < b.0 || (a.0 == b.0 && a.1 < b.1);
        if self.len == K {
            if K == 0 || !less(item, self.items[K - 1]) {
                return;
            }
            self.len -= 1;
        }
        let mut k = self.len;
        while k > 0 && less(item, self.items[k - 1]) {
            self.items[k] = self.items[k - 1];
            k -= 1;
        }
        self.items[k] = item;
        self.len += 1;
    }
    /// The selected slots, nearest first.
    fn slots(&self) -> impl Iterator<Item = usize> + '_ {
        self.items[..self.len].iter().map(|&(_, _, s)| s as usize)
    }
}

/// The ants sensed within a radius of an ant in the plan phase (`reach`, at least the
/// collision range plus twice the longest step): every ant whose prediction can come within
/// the collision range of this ant's, so the resolve frame is built from this short list
/// instead of a second grid query. More than [`Around::CAP`] of them: the list is dropped and
/// the resolve frame asks the grid.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Around {
    /// The list, then one scratch slot (where candidates not kept are written).
    slots: [u32; Around::CAP + 1],
    /// Ants found; above `CAP`, the list overflowed.
    len: u8,
}

impl Around {
    /// Slots kept.
    pub(crate) const CAP: usize = 8;

    /// Notes slot `j` as the list's entry number `len` if `keep` (no branch on `keep`: it is
    /// a coin toss); returns the new count. The caller sets [`Around::len`] at the end.
    #[inline]
    fn note(&mut self, len: u8, j: u32, keep: bool) -> u8 {
        self.slots[usize::from(len).min(Self::CAP)] = j;
        len.saturating_add(u8::from(keep))
    }

    /// The list, unless it overflowed.
    pub(crate) fn slots(&self) -> Option<&[u32]> {
        let len = usize::from(self.len);
        (len <= Self::CAP).then(|| &self.slots[..len])
    }
}

/// Squared distance in the plane, from the grid's `f32` copy of the positions: a cheap
/// pre-selection (with [`AntWorld::rounding_margin`] added to its radius) before the exact key.
fn d2f(a: [f32; 3], b: [f32; 3]) -> f32 {
    (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1])
}

/// The selection key of an ant at `q` seen from `p`: the squared distance in the sensing ant's
/// scalar (in fixed point saturating, which keeps every in-range key exact and every other one
/// out of range, the ranges being below 181: `GroupCheck::fixed_range`), so every backend
/// selects the same neighbours (`docs/gpu.md`).
fn key<S: SimScalar>(q: Vec2<S>, p: Vec2<S>) -> S {
    (q - p).length_sq()
}

/// `r` squared, in `S`.
fn squared<S: SimScalar>(r: f32) -> S {
    let r = S::from_f32(r);
    r * r
}

/// `r` plus the rounding margin, squared: the radius of the `f32` pre-selection.
fn loose2(w: &AntWorld, r: f32) -> f32 {
    let r = r + w.rounding_margin();
    r * r
}

/// The arena as a robot senses it.
pub(crate) fn bounds<S: SimScalar>(w: &AntWorld) -> Rect<S> {
    Rect::new(
        Vec2::new(S::from_f32(w.min[0]), S::from_f32(w.min[1])),
        Vec2::new(S::from_f32(w.max[0]), S::from_f32(w.max[1])),
    )
}

/// The plan-phase sensor frame of ant `i` (xiang2018 §4.2): its `N` nearest neighbours within
/// the world's contact range (by distance, then id) and its `O` nearest active objects within
/// sensing range (an object the ant is inside counts as distance 0). On a route of way points
/// ([`AntWorld::target_of`]) the ant senses its leg's two ends, the start as a nest and the
/// destination as a food source, and no other way point; the food sources only on the last leg;
/// and only the neighbours on its own leg.
pub fn plan_frame<S: SimScalar>(w: &AntWorld, i: usize) -> AntPlanFrame<S> {
    let mut frame = PlanFrame::new(bounds(w));
    fill_plan_frame(w, i, &mut frame);
    frame
}

/// [`plan_frame`] written into `frame` (whose bounds are the world's), reusing its storage.
pub(crate) fn fill_plan_frame<S: SimScalar>(w: &AntWorld, i: usize, frame: &mut AntPlanFrame<S>) {
    fill_plan_frame_noting(w, i, frame, None);
}

/// [`fill_plan_frame`] for the engine's tick (`engine` given): it also notes in the
/// [`Around`] the ants sensed within the reach (≥ the contact range) of ant `i`, what
/// [`fill_resolve_frame_from`] needs, and visits only the objects this tick's index puts near
/// the ant ([`AntWorld::index_positions`]). The frame is the same either way.
pub(crate) fn fill_plan_frame_noting<S: SimScalar>(
    w: &AntWorld,
    i: usize,
    frame: &mut AntPlanFrame<S>,
    engine: Option<(&mut Around, f32)>,
) {
    frame.neighbours.clear();
    frame.objects.clear();
    let me = w.sensed.pos[i];
    let home = w.sensed.nest[i];
    // On a route, only the ants of the same leg (same nest) have news of this leg's ends.
    let same_leg = |j: usize| w.route.is_empty() || w.sensed.nest[j] == home;
    let (me_s, r2, loose) = (
        v2::<S>(me),
        squared::<S>(w.contact_range),
        loose2(w, w.contact_range),
    );
    let mut near = Nearest::<S, N>::new(S::ZERO);
    let p = [me[0] as f32, me[1] as f32, 0.0];
    // Noting costs nothing when not asked for: a reach of -1 keeps no ant.
    let mut scratch = Around::default();
    let indexed = engine.is_some();
    let contact = w.contact_range + w.rounding_margin();
    let (list, radius, reach2) = match engine {
        Some((list, reach)) => (list, reach.max(contact), reach * reach),
        None => (&mut scratch, contact, -1.0),
    };
    // The slots go straight to the list; the count stays in a register through the scan.
    let mut len = 0u8;
    w.grid.for_each_candidate(p, radius, |j, q| {
        let d = d2f(q, p);
        len = list.note(len, j, (d <= reach2) & (j as usize != i));
        if j as usize != i && d <= loose && same_leg(j as usize) {
            let k = key(S::sensed(q, || w.sensed.pos[j as usize]), me_s);
            if k <= r2 {
                near.offer(k, w.sensed.id[j as usize], j);
            }
        }
    });
    list.len = len;
    for j in near.slots() {
        let s = &w.sensed;
        let _ = frame.neighbours.push(AntNeighbor {
            id: s.id[j],
            pos: v2(s.pos[j]),
            label: s.label[j],
            nest: s.nest[j],
            origin: s.origin[j],
            arrival: v2(s.arrival[j]),
        });
    }

    let mut objects = Nearest::<S, O>::new(S::ZERO);
    let p2 = [me[0] as f32, me[1] as f32];
    let (sense, loose_sense) = (
        S::from_f32(w.sense_range),
        w.sense_range + w.rounding_margin(),
    );
    let target = w.target_of(home);
    let on_leg = |o: &AntObjectDef| match o.kind {
        AntObjectKind::Waypoint { .. } => o.id == home || Some(o.id) == target,
        AntObjectKind::Food { .. } => target.is_none(),
        _ => true,
    };
    let mut visit = |k: usize, o: &AntObjectDef| {
        if !o.active || !o.may_be_within(p2, loose_sense) || !on_leg(o) {
            return;
        }
        let (closest, inside) = o.closest(me_s);
        let dist = if inside {
            S::ZERO
        } else {
            (closest - me_s).length()
        };
        if dist <= sense {
            objects.offer(dist, k as u32, k as u32);
        }
    };
    // The engine's tick visits only the objects indexed near the ant (this tick's index).
    match indexed.then(|| w.objects_near(p2)).flatten() {
        Some(mut near) => {
            while near != 0 {
                let k = near.trailing_zeros() as usize;
                near &= near - 1;
                visit(k, &w.objects[k]);
            }
        }
        None => w.objects.iter().enumerate().for_each(|(k, o)| visit(k, o)),
    }
    for k in objects.slots() {
        let o = &w.objects[k];
        let c = |p: [f32; 2]| Vec2::new(S::from_f32(p[0]), S::from_f32(p[1]));
        let sensed = match (&o.kind, o.circle()) {
            (AntObjectKind::Obstacle, _) => {
                let (closest, normal, _) = o.surface(me_s);
                AntObject::Obstacle(Surface { closest, normal })
            }
            (AntObjectKind::Waypoint { .. }, Some((center, radius))) if o.id == home => {
                AntObject::Nest {
                    id: o.id,
                    center: c(center),
                    radius: S::from_f32(radius),
                }
            }
            (AntObjectKind::Nest, Some((center, radius))) => AntObject::Nest {
                id: o.id,
                center: c(center),
                radius: S::from_f32(radius),
            },
            (
                AntObjectKind::Food { .. } | AntObjectKind::Waypoint { .. },
                Some((center, radius)),
            ) => AntObject::Food {
                id: o.id,
                center: c(center),
                radius: S::from_f32(radius),
            },
            (AntObjectKind::Disturbance, Some((center, radius))) => AntObject::Disturbance {
                center: c(center),
                radius: S::from_f32(radius),
            },
            // Nests, food and disturbances are circles (checked when the world is built).
            _ => continue,
        };
        let _ = frame.objects.push(sensed);
    }
}

/// The resolve-phase sensor frame of ant `i` (xiang2018 eq. 2-4): the predictions p*(t+1) of
/// its `N` nearest neighbours within the world's collision range of its own prediction.
pub fn resolve_frame<S: SimScalar>(w: &AntWorld, i: usize) -> AntResolveFrame<S> {
    let mut frame = ResolveFrame::new(bounds(w));
    fill_resolve_frame(w, i, &mut frame);
    frame
}

/// [`fill_resolve_frame`] from the ants noted in the plan phase (see [`Around`]): the same
/// frame, without a grid query unless the list overflowed.
pub(crate) fn fill_resolve_frame_from<S: SimScalar>(
    w: &AntWorld,
    i: usize,
    around: &Around,
    frame: &mut AntResolveFrame<S>,
) {
    let Some(slots) = around.slots() else {
        return fill_resolve_frame(w, i, frame);
    };
    fill_obstacles(w, i, frame);
    frame.neighbours.clear();
    let me = w.predicted[i];
    let (me_s, r2) = (v2::<S>(me), squared::<S>(w.collision_range));
    let mut near = Nearest::<S, N>::new(S::ZERO);
    for &j in slots {
        let k = key(v2(w.predicted[j as usize]), me_s);
        if k < r2 {
            near.offer(k, w.sensed.id[j as usize], j);
        }
    }
    for j in near.slots() {
        let _ = frame.neighbours.push(v2(w.predicted[j]));
    }
}

/// [`resolve_frame`] written into `frame` (whose bounds are the world's), reusing its storage.
pub(crate) fn fill_resolve_frame<S: SimScalar>(
    w: &AntWorld,
    i: usize,
    frame: &mut AntResolveFrame<S>,
) {
    fill_obstacles(w, i, frame);
    frame.neighbours.clear();
    let me = w.predicted[i];
    let (me_s, r2) = (v2::<S>(me), squared::<S>(w.collision_range));
    let loose = loose2(w, w.collision_range);
    let mut near = Nearest::<S, N>::new(S::ZERO);
    let p = [me[0] as f32, me[1] as f32, 0.0];
    // Every prediction lies within `max_shift` of its ant's sensed position, so
    // the ants sensed within `collision_range + max_shift` of p* include every ant predicted
    // within `collision_range` of it.
    let reach = w.collision_range + w.max_shift + w.rounding_margin();
    w.grid.for_each_candidate(p, reach, |j, _| {
        let [x, y] = w.predicted[j as usize];
        if j as usize != i && d2f([x as f32, y as f32, 0.0], p) < loose {
            let k = key(v2(w.predicted[j as usize]), me_s);
            if k < r2 {
                near.offer(k, w.sensed.id[j as usize], j);
            }
        }
    });
    for j in near.slots() {
        let _ = frame.neighbours.push(v2(w.predicted[j]));
    }
}

/// The obstacle surfaces of ant `i`'s resolve frame: every convex piece of an active obstacle
/// within [`AntWorld::step_reach`] of its position (a disc, a polygon edge; from inside an
/// obstacle, the way out), nearest first (ties: object, then edge order), each point once.
fn fill_obstacles<S: SimScalar>(w: &AntWorld, i: usize, frame: &mut AntResolveFrame<S>) {
    frame.obstacles.clear();
    let me = w.sensed.pos[i];
    let p = [me[0] as f32, me[1] as f32];
    let reach = w.step_reach;
    // Indexed: only the active obstacles of the ant's cell (most cells have none).
    let indexed = w
        .objects_near(p)
        .filter(|_| reach <= w.sense_range)
        .map(|m| m & w.obstacle_bits);
    if indexed == Some(0) {
        return;
    }
    let (me_s, reach_s, loose) = (v2::<S>(me), S::from_f32(reach), reach + w.rounding_margin());
    // Pieces offered (more than this many within one step are not sensed).
    let mut found = [(Vec2::<S>::zero(), Vec2::<S>::zero()); 4 * SURFACES];
    let mut len = 0usize;
    let mut near = Nearest::<S, SURFACES>::new(S::ZERO);
    let mut visit = |o: &AntObjectDef| {
        if !o.active || o.kind != AntObjectKind::Obstacle || !o.may_be_within(p, loose) {
            return;
        }
        o.pieces_within(me_s, reach_s, |q, n, d| {
            if len < found.len() && !found[..len].iter().any(|f| f.0 == q) {
                found[len] = (q, n);
                near.offer(d, len as u32, len as u32);
                len += 1;
            }
        });
    };
    match indexed {
        Some(mut mask) => {
            while mask != 0 {
                let k = mask.trailing_zeros() as usize;
                mask &= mask - 1;
                visit(&w.objects[k]);
            }
        }
        None => w.objects.iter().for_each(&mut visit),
    }
    for k in near.slots() {
        let (closest, normal) = found[k];
        let _ = frame.obstacles.push(Surface { closest, normal });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn around_keeps_what_it_is_told_and_gives_up_past_its_capacity() {
        let mut a = Around::default();
        let mut len = 0;
        for j in 0..Around::CAP as u32 {
            len = a.note(len, j, true);
            len = a.note(len, 100 + j, false);
        }
        // Full, and candidates not kept leave the list alone.
        a.len = a.note(len, 99, false);
        assert_eq!(a.slots(), Some(&[0, 1, 2, 3, 4, 5, 6, 7][..]));
        len = a.note(a.len, 8, true);
        a.len = len;
        assert_eq!(a.slots(), None);
        for _ in 0..300 {
            len = a.note(len, 9, true);
        }
        a.len = len;
        assert_eq!(a.slots(), None);
    }

    #[test]
    fn nearest_keeps_the_k_smallest_in_order_whatever_the_arrival_order() {
        let keys = [5.0f32, 1.0, 3.0, 1.0, 9.0, 0.5, 3.0];
        let mut a = Nearest::<f32, 4>::new(0.0);
        let mut b = Nearest::<f32, 4>::new(0.0);
        for (i, k) in keys.iter().enumerate() {
            a.offer(*k, i as u32, i as u32);
        }
        for (i, k) in keys.iter().enumerate().rev() {
            b.offer(*k, i as u32, i as u32);
        }
        assert_eq!(a.slots().collect::<Vec<_>>(), vec![5, 1, 3, 2]);
        assert_eq!(b.slots().collect::<Vec<_>>(), vec![5, 1, 3, 2]);
    }
}
