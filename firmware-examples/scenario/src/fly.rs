//! The fly scenario (ren2016, `swarm_core::fly`): eight insects in a container (a box, whose
//! walls the insects sense as ORCA obstacle surfaces) with a predator and a target (food),
//! run for [`STEPS`] steps of `fly::step`. Every insect decides on the previous step's states
//! (double-buffered, as in the simulator): its sensor frame holds the insects within r_att,
//! nearest first (ties by id), at most [`N`]; the stimulus within r_res (the predator before
//! the target); and the box walls within [`WALL_SENSE`], at most [`O`]. Then one infeasible
//! frame is solved again with RVO2-3D's `linearProgram4` fallback, and a few deliberately bad
//! frames must be refused with the same typed error on both sides.
//!
//! Parameters: Table 1's "Bats" column (`FlyParams::bats()`, cast from `f32` as the host does),
//! the one column with all three zones (r_rep 2, r_ali 5, r_att 15) and a stimulus response
//! (χ_res 10 within r_res 10); curl noise, the paper's zero-velocity fallback, one-sided
//! escape. (The serial nodes run the "Midge" column, which has no alignment zone and no
//! response; [`cost`] runs with theirs.) The frames have the wire capacities,
//! [`N`] = `WIRE_FLY_NEIGHBOURS` and [`O`] = `WIRE_FLY_SURFACES`.
//!
//! The starting states make the branches run:
//! * insect 0 has a neighbour in each zone of Eq. 5: insect 1 in repulsion (1.5 away),
//!   insect 2 in alignment (3.6, flying across it), the others in attraction (6.2-12.8 away);
//! * insects 0 and 1 fly head-on, 0.5 apart surface to surface: ORCA (feasible) turns them;
//! * insect 3 is 3.6 from the predator: escape, its angle θ drawn at step 0 and kept while the
//!   predator stays in range (`escape_theta`, `escaping`);
//! * insect 4 is 3.3 from the target (pursuit) and 1.4 below the ceiling, flying up at 3:
//!   the wall's hard ORCA plane bounds its climb;
//! * insect 6 is squeezed between 5 and 7, which overlap it by 0.02 and 0.04: the two
//!   collision planes contradict each other, LP3 is infeasible and the paper's fallback stops
//!   it (its neighbours, each overlapping on one side only, get away, and the squeeze is
//!   resolved); after the run the same frame is solved with `FALLBACK_LP4` (the least
//!   penetration: a velocity between the two demands);
//! * curl noise (Eq. 4) and friction act on all.
//!
//! Words per insect and step: `pref.{x,y,z}`, `infeasible`, `next.pos.{x,y,z}`,
//! `next.vel.{x,y,z}`, `next.escape_theta`, `next.escaping` — 12 words ([`WORDS_PER_FLY_STEP`]);
//! then the fallback solved with `linearProgram4` (`infeasible`, `next.vel.{x,y,z}`: 4 words)
//! and the probes (2 words each, see `probes` below).
//!
//! [`cost`] is the other use of this world: a larger swarm with the serial nodes' parameters,
//! timed call by call (the `fly-node-cycles` images).

use crate::{Meter, Sink, Stats, Word, uniform};
use swarm_core::fly::{
    self, FALLBACK_LP4, FlyDecision, FlyFrame, FlyParams, FlyState, Neighbour, STIMULUS_PREDATOR,
    STIMULUS_TARGET, Stimulus, Surface, WIRE_FLY_NEIGHBOURS, WIRE_FLY_SURFACES,
};
use swarm_core::{Checked, Scalar, StepCtx, Vec3};

/// Insects in the scenario.
pub const AGENTS: usize = 8;
/// Steps simulated.
pub const STEPS: u32 = 6;
/// Neighbour capacity of the frames (the wire's, `WIRE_FLY_NEIGHBOURS`).
pub const N: usize = WIRE_FLY_NEIGHBOURS;
/// Surface capacity of the frames (the wire's, `WIRE_FLY_SURFACES`).
pub const O: usize = WIRE_FLY_SURFACES;
/// Words per insect and step.
pub const WORDS_PER_FLY_STEP: usize = 12;
/// Words of the `linearProgram4` fallback after the run.
pub const FALLBACK_WORDS: usize = 4;
/// The seed of every step's randomness (escape angle; white and Gaussian noise if chosen).
pub const SEED: u32 = 0x00f1_1e55;

/// Half the side of the container, a box centred on the origin.
const HALF: f32 = 12.0;
/// A wall is sensed (as an ORCA surface) within this distance: about ORCA's reach, τ times
/// the speed limit (0.5 × 4.9 with Bats, × 4.5 with Midge).
pub const WALL_SENSE: f32 = 2.0;
/// The insect squeezed between two others (infeasible at step 0).
const SQUEEZED: usize = 6;

/// The static world, in scalar `S`.
struct World<S> {
    /// Half the side of the box.
    half: S,
    predator: Vec3<S>,
    target: Vec3<S>,
}

impl<S: Scalar> World<S> {
    fn new() -> Self {
        let v = Vec3::<S>::from_f32;
        World {
            half: S::from_f32(HALF),
            predator: v(-8.0, -3.0, -6.0),
            target: v(8.0, 9.0, 6.0),
        }
    }

    /// What insect `i` senses, from the insects' states `all` (the previous step's), under
    /// `p`'s radii, in a frame of capacity `NN` neighbours and `OO` surfaces.
    fn frame<const NN: usize, const OO: usize>(
        &self,
        all: &[FlyState<S>],
        i: usize,
        p: &FlyParams<S>,
    ) -> FlyFrame<S, NN, OO> {
        let mut f = FlyFrame::new();
        let me = all[i].pos;
        let dist = |n: &Neighbour<S>| (n.pos - me).length();
        for (j, other) in all.iter().enumerate() {
            let d = (other.pos - me).length();
            if j == i || d > p.r_att {
                continue;
            }
            // Nearest first, ties by id (j grows): insert after every entry at most as far.
            if f.neighbours.is_full() {
                match f.neighbours.last() {
                    Some(last) if dist(last) > d => {
                        f.neighbours.pop();
                    }
                    _ => continue,
                }
            }
            let _ = f.neighbours.push(Neighbour {
                id: j as u32,
                pos: other.pos,
                vel: other.vel,
            });
            let list = f.neighbours.as_mut_slice();
            let mut k = list.len() - 1;
            while k > 0 && dist(&list[k - 1]) > d {
                list.swap(k - 1, k);
                k -= 1;
            }
        }
        let in_range = |q: Vec3<S>| (me - q).length() <= p.r_res;
        f.stimulus = if in_range(self.predator) {
            Some(Stimulus {
                pos: self.predator,
                kind: STIMULUS_PREDATOR,
            })
        } else if in_range(self.target) {
            Some(Stimulus {
                pos: self.target,
                kind: STIMULUS_TARGET,
            })
        } else {
            None
        };
        // The walls within reach: the closest point on each and the inward normal.
        let sense = S::from_f32(WALL_SENSE);
        for axis in 0..3 {
            for side in [S::ONE, -S::ONE] {
                let c = |v: Vec3<S>| [v.x, v.y, v.z][axis];
                if self.half - side * c(me) > sense {
                    continue;
                }
                let mut point = me;
                let mut normal = Vec3::zero();
                let wall = side * self.half;
                match axis {
                    0 => (point.x, normal.x) = (wall, -side),
                    1 => (point.y, normal.y) = (wall, -side),
                    _ => (point.z, normal.z) = (wall, -side),
                }
                let _ = f.surfaces.push(Surface { point, normal });
            }
        }
        f
    }
}

/// What insect `i` senses in this module's world (the box, the predator, the target), from the
/// insects' states `all`, under `params`' radii: the insects within r_att, nearest first (ties
/// by id), at most `NN`; the predator, else the target, within r_res; the walls within
/// [`WALL_SENSE`], at most `OO`. (The serial nodes' session transcripts use it too.)
pub fn sense<S: Scalar, const NN: usize, const OO: usize>(
    all: &[FlyState<S>],
    i: usize,
    params: &FlyParams<S>,
) -> FlyFrame<S, NN, OO> {
    World::new().frame(all, i, params)
}

/// The scenario's parameters: Table 1's "Bats" column (see the module docs).
pub fn params<S: Scalar>() -> FlyParams<S> {
    FlyParams::<f32>::bats().cast::<S>()
}

/// The swarm at step 0 (see the module docs for the roles).
fn initial<S: Scalar>() -> [FlyState<S>; AGENTS] {
    let v = Vec3::<S>::from_f32;
    let s = |p: Vec3<S>, u: Vec3<S>| FlyState::new(p, u);
    [
        // 0, 1: head-on, 1.5 apart (repulsion zone); 2 crosses 0's alignment zone.
        s(v(0.0, 0.0, 0.0), v(1.0, 0.0, 0.0)),
        s(v(1.5, 0.2, 0.0), v(-1.0, 0.0, 0.0)),
        s(v(-0.5, 3.5, 0.5), v(0.0, 0.0, 1.0)),
        // 3: near the predator: escapes.
        s(v(-5.0, -3.0, -4.0), v(0.5, 0.0, 0.5)),
        // 4: near the target (pursuit), climbing toward the ceiling.
        s(v(6.0, 10.6, 4.0), v(0.5, 3.0, 0.0)),
        // 5-7: 6 squeezed between 5 and 7, overlapping them by 0.02 and 0.04 (ORCA radius 0.5
        // each).
        s(v(2.02, -5.0, -3.0), v(0.0, 0.0, 0.0)),
        s(v(3.0, -5.0, -3.0), v(0.0, 0.0, 0.0)),
        s(v(3.96, -5.0, -3.0), v(0.0, 0.0, 0.0)),
    ]
}

/// The step context of insect `i` at `step`.
fn ctx(i: usize, step: u32) -> StepCtx {
    StepCtx {
        seed: SEED,
        agent: i as u32,
        step,
    }
}

/// Emits the words of one insect and step.
fn emit_step<S: Word>(next: &FlyState<S>, d: &FlyDecision<S>, out: &mut impl Sink) {
    out.vec3(d.pref);
    out.put(u32::from(d.infeasible));
    out.vec3(next.pos);
    out.vec3(next.vel);
    out.scalar(next.escape_theta);
    out.put(u32::from(next.escaping));
}

/// Runs the scenario, emitting every decision word.
pub fn run<S: Word>(out: &mut impl Sink) {
    let w = World::<S>::new();
    let p = params::<S>();
    let mut flies = initial::<S>();
    for step in 0..STEPS {
        let prev = flies;
        for (i, fly) in flies.iter_mut().enumerate() {
            let frame: FlyFrame<S, N, O> = w.frame(&prev, i, &p);
            if let Some((next, d)) = out.decided(fly::step(&prev[i], &frame, &p, ctx(i, step))) {
                emit_step(&next, &d, out);
                *fly = next;
            }
        }
    }
    // The squeeze of step 0 again, with RVO2-3D's linearProgram4 as the fallback.
    let start = initial::<S>();
    let lp4 = FlyParams {
        fallback: FALLBACK_LP4,
        ..p
    };
    let frame: FlyFrame<S, N, O> = w.frame(&start, SQUEEZED, &lp4);
    emit(
        fly::step(&start[SQUEEZED], &frame, &lp4, ctx(SQUEEZED, 0)),
        out,
    );
    probes(&w, &flies, &p, out);
}

/// An outcome of a single call: `infeasible` and the velocity, or the error's two words.
fn emit<S: Word>(r: swarm_core::Result<(FlyState<S>, FlyDecision<S>)>, out: &mut impl Sink) {
    if let Some((next, d)) = out.decided(r) {
        out.put(u32::from(d.infeasible));
        out.vec3(next.vel);
    }
}

/// Bad input must be refused with the same typed error on the MCU and the host: a neighbour id
/// given twice, a surface normal that is not a unit vector, an unknown stimulus kind, an
/// escape angle beyond ±π/2, a position beyond the limit, and a bad parameter (a speed limit
/// that makes the friction step unstable). Each gives 2 words (4 if wrongly accepted).
fn probes<S: Word>(
    w: &World<S>,
    flies: &[FlyState<S>; AGENTS],
    p: &FlyParams<S>,
    out: &mut impl Sink,
) {
    let near_wall = 4;
    let base: FlyFrame<S, N, O> = w.frame(flies, 0, p);
    let c = ctx(0, STEPS);

    let mut f = base.clone();
    if let [first, second, ..] = f.neighbours.as_mut_slice() {
        second.id = first.id;
    }
    emit(fly::step(&flies[0], &f, p, c), out);

    let mut f: FlyFrame<S, N, O> = w.frame(flies, near_wall, p);
    if let Some(s) = f.surfaces.first_mut() {
        s.normal = s.normal * S::from_f32(0.9);
    }
    emit(
        fly::step(&flies[near_wall], &f, p, ctx(near_wall, STEPS)),
        out,
    );

    let mut f = base.clone();
    f.stimulus = Some(Stimulus {
        pos: w.target,
        kind: 2,
    });
    emit(fly::step(&flies[0], &f, p, c), out);

    let mut turned = flies[0];
    turned.escape_theta = S::from_f32(2.0);
    emit(fly::step(&turned, &base, p, c), out);

    let mut far = flies[0];
    far.pos.y = S::from_f32(-20_000.0);
    emit(fly::step(&far, &base, p, c), out);

    let bad = FlyParams {
        max_speed: p.max_speed * S::from_f32(2.0),
        ..*p
    };
    emit(fly::step(&flies[0], &base, &bad, c), out);
}

/// Insects in the swarm of [`cost`].
pub const COST_AGENTS: usize = 24;
/// Steps of [`cost`]: `COST_AGENTS * COST_STEPS` fly steps are timed.
pub const COST_STEPS: u32 = 16;

/// What [`cost`] measured, in the meter's ticks.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FlyCost {
    /// One `fly::step_checked` call.
    pub step: Stats,
    /// Neighbours in the frames, summed (the mean is `neighbours / step.n`).
    pub neighbours: u32,
    /// Obstacle surfaces in the frames, summed.
    pub surfaces: u32,
    /// Frames holding as many neighbours as they can.
    pub full_frames: u32,
    /// Steps whose ORCA program was infeasible (the fallback acted).
    pub infeasible: u32,
    /// Controller calls that returned an error (0 expected: only decisions are timed).
    pub errors: u32,
}

/// The swarm of [`cost`] at step 0: a cloud of 8 × 6 × 6 units against the box's +x wall,
/// flying in varied directions at up to 1.5 units/s.
fn cost_swarm<S: Scalar>() -> [FlyState<S>; COST_AGENTS] {
    core::array::from_fn(|i| {
        let k = 200 + i as u32;
        let pos = Vec3::new(
            uniform(k, 1, 3.5, 11.5),
            uniform(k, 2, -3.0, 3.0),
            uniform(k, 3, -3.0, 3.0),
        );
        let vel = Vec3::new(
            uniform(k, 4, -1.0, 1.5),
            uniform(k, 5, -0.5, 0.5),
            uniform(k, 6, -0.5, 0.5),
        );
        FlyState::new(pos, vel)
    })
}

/// Times the fly controller as a serial node runs it, call by call: [`COST_AGENTS`] insects in
/// this module's world for [`COST_STEPS`] steps, every insect's `fly::step_checked` on a frame
/// of capacity `NN` neighbours and `OO` surfaces (the node's wire capacities), built from the
/// previous step's states under `params`' radii (the call `FlyDevice` makes for a
/// `FlyStepRequest`, parameters validated once). The frames are built outside the timed
/// blocks; only the controller call (its input validation included) is timed.
pub fn cost<S: Scalar, const NN: usize, const OO: usize>(
    params: &Checked<FlyParams<S>>,
    meter: &mut impl Meter,
) -> FlyCost {
    let w = World::<S>::new();
    let p: &FlyParams<S> = params;
    let mut flies = cost_swarm::<S>();
    let mut c = FlyCost::default();
    for step in 0..COST_STEPS {
        let prev = flies;
        for (i, fly) in flies.iter_mut().enumerate() {
            let frame: FlyFrame<S, NN, OO> = w.frame(&prev, i, p);
            c.neighbours += frame.neighbours.len() as u32;
            c.surfaces += frame.surfaces.len() as u32;
            c.full_frames += u32::from(frame.neighbours.is_full());
            let (r, t) = meter.measure((&prev[i], &frame), |(s, f)| {
                fly::step_checked(s, f, params, ctx(i, step))
            });
            c.step.add(t);
            match r {
                Ok((next, d)) => {
                    c.infeasible += u32::from(d.infeasible);
                    *fly = next;
                }
                Err(_) => c.errors += 1,
            }
        }
    }
    c
}

#[cfg(all(test, feature = "std"))]
mod tests {
    use super::*;
    use crate::host::{Calls, collect};
    use swarm_core::fly::force::{Zone, noise_force, zone};

    fn coverage<S: Word>() {
        let words = collect(run::<S>);
        let per_step = AGENTS * WORDS_PER_FLY_STEP;
        let run_words = STEPS as usize * per_step;
        assert_eq!(words.len(), run_words + FALLBACK_WORDS + 12);
        let word =
            |step: usize, i: usize, k: usize| words[step * per_step + i * WORDS_PER_FLY_STEP + k];
        let steps = 0..STEPS as usize;
        let (infeasible, theta, escaping) = (3, 10, 11);

        // The squeeze: infeasible at step 0 (the paper's fallback: zero velocity), then free.
        assert_eq!(
            word(0, SQUEEZED, infeasible),
            1,
            "the squeezed insect's LP3 fails"
        );
        assert!(
            (7..10).all(|k| word(0, SQUEEZED, k) == S::ZERO.word()),
            "FALLBACK_STOP gives zero velocity"
        );
        assert!(
            steps.clone().any(|s| word(s, SQUEEZED, infeasible) == 0),
            "the squeeze is resolved"
        );
        assert!(
            [5, 7].iter().all(|&i| word(0, i, infeasible) == 0),
            "the outer two are feasible"
        );
        // LP4 on the same frame: infeasible, and a velocity that is not zero.
        let lp4 = &words[run_words..run_words + FALLBACK_WORDS];
        assert_eq!(lp4[0], 1);
        assert!(lp4[1..].iter().any(|&w| w != S::ZERO.word()), "{lp4:x?}");

        // Escape: θ drawn once in [−π/2, 0), kept while the predator is in range.
        assert!(steps.clone().all(|s| word(s, 3, escaping) == 1));
        assert!(
            steps
                .clone()
                .all(|s| word(s, 3, theta) == word(0, 3, theta))
        );
        let others = [0, 1, 2, 4, 5, 6, 7];
        assert!(others.iter().all(|&i| word(0, i, escaping) == 0));

        // Probes: duplicate id [1], non-unit normal [0], stimulus kind, θ, far position, bad
        // max_speed.
        let m = crate::ERROR_MARKER;
        assert_eq!(
            words[run_words + FALLBACK_WORDS..],
            [
                m,
                3 << 16 | 1,
                m,
                2 << 16,
                m,
                2 << 16 | 0xffff,
                m,
                2 << 16 | 0xffff,
                m,
                2 << 16 | 0xffff,
                m,
                4 << 16 | 0xffff
            ]
        );

        // Step 0, branch by branch.
        let w = World::<S>::new();
        let p = params::<S>();
        let flies = initial::<S>();
        let f = |i| -> FlyFrame<S, N, O> { w.frame(&flies, i, &p) };
        let zones: Vec<_> = f(0)
            .neighbours
            .iter()
            .map(|n| zone((n.pos - flies[0].pos).length(), &p))
            .collect();
        for z in [Zone::Repulsion, Zone::Alignment, Zone::Attraction] {
            assert!(
                zones.contains(&Some(z)),
                "insect 0 has a neighbour in {z:?}: {zones:?}"
            );
        }
        assert_eq!(f(0).neighbours.len(), AGENTS - 1);
        assert_eq!(f(0).neighbours[0].id, 1, "nearest first");
        assert!(f(0).stimulus.is_none() && f(0).surfaces.is_empty());
        assert_eq!(f(3).stimulus.map(|s| s.kind), Some(STIMULUS_PREDATOR));
        assert_eq!(f(4).stimulus.map(|s| s.kind), Some(STIMULUS_TARGET));
        assert_eq!(f(4).surfaces.len(), 1, "insect 4 senses the ceiling");
        assert!(
            (0..AGENTS).all(|i| i == 4 || f(i).surfaces.is_empty()),
            "only insect 4 is near a wall"
        );

        // ORCA acts: insects 0 and 1 do not keep their preferred velocities; the ceiling
        // bounds insect 4's climb: it may not reach the wall within τ.
        for i in [0, 1, 4] {
            let (next, d) = fly::step(&flies[i], &f(i), &p, ctx(i, 0)).unwrap();
            assert!(!d.infeasible && next.vel != d.pref, "ORCA turns insect {i}");
        }
        let (next, d) = fly::step(&flies[4], &f(4), &p, ctx(4, 0)).unwrap();
        let gap = w.half - flies[4].pos.y - p.radius;
        assert!(d.pref.y * p.tau > gap && next.vel.y * p.tau <= gap + S::from_f32(1e-3));

        // Curl noise acts.
        assert!(noise_force(flies[0].pos, &p, ctx(0, 0)) != Vec3::zero());
    }

    fn cost_covers<S: Scalar>() {
        // The serial nodes' parameters (`fw_node::fly_params`: Table 1's Midge column) and
        // wire capacities (16, 4).
        let params = FlyParams::<f32>::midge().cast::<S>().checked().unwrap();
        let c = cost::<S, N, O>(&params, &mut Calls);
        let steps = COST_AGENTS as u32 * COST_STEPS;
        assert_eq!(c.errors, 0, "only decisions are timed: {c:?}");
        assert_eq!((c.step.n, c.step.min, c.step.max), (steps, 1, 1));
        let mean = c.neighbours as f32 / steps as f32;
        assert!((8.0..16.0).contains(&mean), "mean neighbours {mean}: {c:?}");
        assert!(c.full_frames > 0, "some frames are full: {c:?}");
        assert!(
            c.surfaces > 0 && c.surfaces < steps,
            "some insects sense the wall: {c:?}"
        );
    }

    scalar_tests!(
        cost_covers,
        f32_cost_run_times_decisions_in_a_swarm,
        fixed_cost_run_times_decisions_in_a_swarm
    );
    scalar_tests!(
        coverage,
        f32_scenario_exercises_every_branch,
        fixed_scenario_exercises_every_branch
    );
}
