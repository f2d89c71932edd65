//! The sensor frame of a ren2016 insect, built from the world as a drone would sense it (spec
//! §1.5 step 1): neighbours within r_att with their broadcast position and velocity (nearest
//! first, ties by id, at most [`N`]: the wire's capacity, so every run can be mirrored on a
//! device; when more are in range, every zone of Eq. 5 keeps its nearest members, see
//! [`zone_shares`]), the stimulus in range (a predator before a target), and the obstacle
//! surfaces within ORCA's reach. The HIL harness feeds devices with this same function.

use swarm_core::fly::{
    FlyFrame, FlyParams, Neighbour, STIMULUS_PREDATOR, STIMULUS_TARGET, Stimulus,
    WIRE_FLY_NEIGHBOURS, WIRE_FLY_SURFACES,
};
use swarm_core::{Scalar, Vec3};

use crate::nearest::select_bands;
use crate::scalar::{SimScalar, v3};
use crate::space::at;
use crate::swarm3d::{World3d, reach};

/// Neighbour capacity of a fly frame (the wire's).
pub const N: usize = WIRE_FLY_NEIGHBOURS;
/// Surface capacity of a fly frame (the wire's).
pub const O: usize = WIRE_FLY_SURFACES;

/// The sensor frame of the simulator (and of the wire).
pub type FlySimFrame<S> = FlyFrame<S, N, O>;

/// Entries a truncated frame keeps for each of the alignment and attraction zones that has
/// members (ours): Eq. 5 averages each zone over its members, so a frame of the nearest [`N`]
/// alone would leave out the farther zones of a dense swarm, and with them its cohesion. 3
/// leaves the nearest 10 to ORCA in any frame, RVO2-3D's default `maxNeighbors`.
pub const ZONE_QUOTA: usize = 3;

/// How many of each zone's nearest members a frame holds, from the zones' member counts
/// `[repulsion, alignment, attraction]` (spec R15, ours): every member when they all fit in
/// [`N`]; else the alignment and attraction zones keep min([`ZONE_QUOTA`], members) each
/// and the rest goes to the nearer zones first.
pub fn zone_shares(n: [usize; 3]) -> [usize; 3] {
    let quota = |z: usize| n[z].min(ZONE_QUOTA);
    let rep = n[0].min(N - quota(1) - quota(2));
    let ali = n[1].min(N - rep - quota(2));
    let att = n[2].min(N - rep - ali);
    [rep, ali, att]
}

/// The stimulus sources a group responds to (object ids).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stimuli {
    /// The target it pursues (its `goal`).
    pub goal: Option<u16>,
    /// The predator it escapes (its `threat`).
    pub threat: Option<u16>,
}

/// The frame of the insect in slot `slot` with parameters `p` responding to `stimuli`, and
/// whether more than [`N`] insects were within r_att (the frame was truncated: spec §2.1).
/// Neighbours are banded by squared distance into the zones of Eq. 5 (`[0, r_rep)`,
/// `[r_rep, r_ali)`, `[r_ali, r_att)`) and each band gives its nearest [`zone_shares`].
pub fn fly_frame<S: SimScalar>(
    w: &World3d,
    slot: usize,
    p: &FlyParams<S>,
    stimuli: Stimuli,
) -> (FlySimFrame<S>, bool) {
    let me = v3::<S>(w.sensed.pos[slot]);
    let ids = &w.sensed.id;
    let pos = |j: u32, q: [f32; 3]| S::sensed3(q, || w.sensed.pos[j as usize]);
    let bounds = [p.r_rep, p.r_ali, p.r_att].map(|r| r.to_f32());
    let zones = select_bands::<S, N, 3>(&w.grid, me, bounds, slot as u32, pos, |j| ids[j as usize]);
    let within = zones.each_ref().map(|z| z.within);
    let shares = zone_shares(within);
    let mut frame = FlySimFrame::new();
    let near = zones
        .iter()
        .zip(shares)
        .flat_map(|(z, k)| z.slots().take(k));
    for j in near {
        // At most N selected: no push can fail.
        let _ = frame.neighbours.push(Neighbour {
            id: ids[j],
            pos: v3(w.sensed.pos[j]),
            vel: v3(w.sensed.vel[j]),
        });
    }
    frame.stimulus = stimulus(w, me, v3(w.sensed.vel[slot]), p.r_res, stimuli);
    frame.surfaces = w.surfaces(me, reach(p.orca_radius(), p.tau, p.max_speed));
    (frame, within.iter().sum::<usize>() > N)
}

/// The stimulus of an insect at `me` flying at `vel` with visual range `r_res` (spec §2.3,
/// R12): the threat if it is active and within r_res (H(0) = 1), else the goal if it is. A
/// source's position is its centre; for a region
/// ([`Source::region`](super::world::Source::region)) a threat is where the insect's heading
/// meets its walls ([`echo_point`]) and a goal its nearest point (none inside it).
fn stimulus<S: SimScalar>(
    w: &World3d,
    me: Vec3<S>,
    vel: Vec3<S>,
    r_res: S,
    stimuli: Stimuli,
) -> Option<Stimulus<S>> {
    let sensed = |id: Option<u16>, kind| {
        let s = w.source(id?)?;
        let pos = match (s.region, kind) {
            (Some([lo, hi]), STIMULUS_PREDATOR) => echo_point(me, vel, at::<S>(lo), at::<S>(hi))?,
            (Some([lo, hi]), _) if s.cave => ahead_point(me, vel, at::<S>(lo), at::<S>(hi), r_res)?,
            (Some([lo, hi]), _) => nearest_outside(me, at::<S>(lo), at::<S>(hi))?,
            (None, _) => at::<S>(s.center),
        };
        ((pos - me).length_sq() <= r_res * r_res).then_some(Stimulus { pos, kind })
    };
    sensed(stimuli.threat, STIMULUS_PREDATOR).or_else(|| sensed(stimuli.goal, STIMULUS_TARGET))
}

/// The point of the box `[lo, hi]` nearest to `p`, or `None` when `p` is inside it (an area
/// the insect has reached).
pub fn nearest_outside<S: Scalar>(p: Vec3<S>, lo: Vec3<S>, hi: Vec3<S>) -> Option<Vec3<S>> {
    let q = Vec3::new(
        p.x.max(lo.x).min(hi.x),
        p.y.max(lo.y).min(hi.y),
        p.z.max(lo.z).min(hi.z),
    );
    (q != p).then_some(q)
}

/// Where a ray from `p` along `vel` leaves the box `[lo, hi]` (`p` inside; from outside, the
/// nearest exit ahead is clamped to `p`): the echo a bat hears ahead of it (Fig. 9, ours).
/// `None` for an insect at rest (`Vec3::normalized`).
pub fn echo_point<S: Scalar>(
    p: Vec3<S>,
    vel: Vec3<S>,
    lo: Vec3<S>,
    hi: Vec3<S>,
) -> Option<Vec3<S>> {
    let dir = vel.normalized()?;
    let exit = |d: S, p: S, lo: S, hi: S| {
        if d > S::ZERO {
            Some((hi - p) / d)
        } else if d < S::ZERO {
            Some((lo - p) / d)
        } else {
            None
        }
    };
    let t = [
        exit(dir.x, p.x, lo.x, hi.x),
        exit(dir.y, p.y, lo.y, hi.y),
        exit(dir.z, p.z, lo.z, hi.z),
    ]
    .into_iter()
    .flatten()
    .fold(None, |m: Option<S>, t| Some(m.map_or(t, |m| m.min(t))))?;
    Some(p + dir * t.max(S::ZERO))
}

/// The echo a bat flying inside the cave `[lo, hi]` pursues (Fig. 9, ours: "a changing
/// stimulus in front of each bat"): the [`echo_point`] ahead, or the point half the visual
/// range `r_res` ahead when the walls are farther (`t = min(t_wall, r_res/2)` along the unit
/// heading, so the stimulus is always in range). Pursued, it drives the bat forward along its
/// heading; the walls turn it. `None` for an insect at rest.
pub fn ahead_point<S: Scalar>(
    p: Vec3<S>,
    vel: Vec3<S>,
    lo: Vec3<S>,
    hi: Vec3<S>,
    r_res: S,
) -> Option<Vec3<S>> {
    let wall = echo_point(p, vel, lo, hi)?;
    let half = r_res * S::from_f32(0.5);
    let dir = vel.normalized()?;
    Some(if (wall - p).length_sq() > half * half {
        p + dir * half
    } else {
        wall
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every member when all fit; else the farther zones keep their quota and the nearer ones
    /// take what is left, always [`N`] in all.
    #[test]
    fn zone_shares_keep_every_zone() {
        assert_eq!(zone_shares([3, 5, 8]), [3, 5, 8]);
        assert_eq!(zone_shares([0, 0, 40]), [0, 0, 16]);
        assert_eq!(zone_shares([30, 0, 40]), [13, 0, 3]);
        assert_eq!(zone_shares([30, 40, 40]), [10, 3, 3]);
        assert_eq!(zone_shares([2, 40, 40]), [2, 11, 3]);
        assert_eq!(zone_shares([2, 40, 1]), [2, 13, 1]);
        assert_eq!(zone_shares([20, 2, 1]), [13, 2, 1]);
        for n in [
            [0, 0, 0],
            [16, 0, 0],
            [17, 17, 17],
            [1, 1, 100],
            [100, 1, 1],
        ] {
            let s = zone_shares(n);
            assert!(s.iter().zip(n).all(|(&s, n)| s <= n), "{n:?}");
            assert_eq!(
                s.iter().sum::<usize>(),
                n.iter().sum::<usize>().min(N),
                "{n:?}"
            );
        }
    }

    /// The echo is where the heading leaves the box, in both scalars, none at rest; an area
    /// pursued gives its nearest point from outside and nothing from inside.
    #[test]
    fn the_echo_is_the_wall_ahead_and_an_area_its_nearest_point() {
        fn check<S: SimScalar>() {
            let v = |x: f32, y: f32, z: f32| Vec3::<S>::from_f32(x, y, z);
            let (lo, hi) = (v(0.0, 0.0, 0.0), v(40.0, 10.0, 40.0));
            let hit = echo_point(v(20.0, 5.0, 20.0), v(3.0, 0.0, 4.0), lo, hi).unwrap();
            for (got, want) in [hit.x, hit.y, hit.z].into_iter().zip([35.0, 5.0, 40.0]) {
                assert!((got.to_f32() - want).abs() < 1e-3, "{got:?} vs {want}");
            }
            let down = echo_point(v(20.0, 5.0, 20.0), v(0.0, -2.0, 0.0), lo, hi).unwrap();
            assert!(down.y.to_f32().abs() < 1e-4 && (down.x.to_f32() - 20.0).abs() < 1e-4);
            assert!(echo_point(v(1.0, 1.0, 1.0), v(0.0, 0.0, 0.0), lo, hi).is_none());
            let near = nearest_outside(v(50.0, 5.0, -3.0), lo, hi).unwrap();
            assert_eq!(near, v(40.0, 5.0, 0.0));
            assert!(nearest_outside(v(20.0, 5.0, 20.0), lo, hi).is_none());
        }
        check::<f32>();
        check::<swarm_core::Fx>();
    }

    /// In a cave the stimulus is r_res/2 ahead while the wall is farther, the wall once it is
    /// nearer, and none at rest.
    #[test]
    fn a_cave_echoes_ahead_within_half_the_range() {
        fn check<S: SimScalar>() {
            let v = |x: f32, y: f32, z: f32| Vec3::<S>::from_f32(x, y, z);
            let (lo, hi, r) = (v(0.0, 0.0, 0.0), v(40.0, 10.0, 40.0), S::from_f32(8.0));
            let close = |a: Vec3<S>, b: [f32; 3]| {
                let d = [
                    a.x.to_f32() - b[0],
                    a.y.to_f32() - b[1],
                    a.z.to_f32() - b[2],
                ];
                assert!(d.iter().all(|d| d.abs() < 1e-3), "{a:?} vs {b:?}");
            };
            let far = ahead_point(v(20.0, 5.0, 20.0), v(3.0, 0.0, 4.0), lo, hi, r).unwrap();
            close(far, [22.4, 5.0, 23.2]);
            let wall = ahead_point(v(20.0, 5.0, 38.0), v(0.0, 0.0, 2.0), lo, hi, r).unwrap();
            close(wall, [20.0, 5.0, 40.0]);
            assert!(ahead_point(v(1.0, 1.0, 1.0), v(0.0, 0.0, 0.0), lo, hi, r).is_none());
        }
        check::<f32>();
        check::<swarm_core::Fx>();
    }
}
