//! The bee scenario: six bees around a flower (a goal with virtual target particles sampled on
//! it, chen §V-B) and a round rock (a sphere obstacle, §IV-B), run for [`STEPS`] steps of
//! `bee::step`. Every bee decides on the previous step's states (double-buffered, as in the
//! simulator): its sensor frame holds the bees within the kernel radius h (with the densities
//! they broadcast), the flower's particles within h, the flower as goal, and the rock's closest
//! point and normal when within sensing range. Then a few deliberately bad frames must be
//! refused with the same typed error on both sides.
//!
//! The starting states make the branches run: three bees flying close together (SPH density
//! and repulsion, eq. 10-11), one flying at the rock (visual avoidance: eq. 5-7, sliding along
//! its surface until it is past), one next to the flower (repulsion by target particles, the zig-zag
//! approach), and one with no goal, hovering (the forward axis from its stored heading).
//! Oscillation (eq. 2-4) and curl noise (eq. 8-9) act on all.
//!
//! Words per bee and step: `accel.{x,y,z}`, `velocity.{x,y,z}`, `roll`, `pitch`, `density`,
//! `avoiding`, `next.pos.{x,y,z}` — 13 words; then the probes (see `probes` below).
//!
//! [`cost`] is the other use of this world: a larger swarm, timed call by call (the
//! `bee-node-cycles` images).

use crate::{Meter, Sink, Stats, Word, uniform};
use swarm_core::bee::{self, BeeFrame, BeeNeighbor, BeeParams, BeeState, ObstacleSense};
use swarm_core::{Checked, Scalar, Vec3};

/// Bees in the scenario.
pub const AGENTS: usize = 6;
/// Steps simulated.
pub const STEPS: u32 = 6;
/// Neighbour capacity of the frames (an MCU-sized choice).
pub const N: usize = 16;
/// Target-particle capacity of the frames.
pub const P: usize = 8;
/// Words per bee and step.
pub const WORDS_PER_BEE_STEP: usize = 13;

/// Bees with no goal (they hover on their stored forward axis).
const NO_GOAL: usize = 5;
/// The rock is sensed within this distance of its surface.
const SENSE: f32 = 4.0;

/// The static world, in scalar `S`.
struct World<S> {
    flower: Vec3<S>,
    /// Virtual particles on the flower (a ring of radius 0.8 and its top).
    petals: [Vec3<S>; P],
    rock: (Vec3<S>, S),
}

type Frame<S> = BeeFrame<S, N, P>;

impl<S: Scalar> World<S> {
    fn new() -> Self {
        let v = Vec3::<S>::from_f32;
        let flower = v(6.0, 1.0, 0.0);
        // The ring at 0°, 60°, …, 300° (cos/sin as constants, the same bits on every machine).
        let ring = [
            (1.0, 0.0),
            (0.5, 0.866_025_4),
            (-0.5, 0.866_025_4),
            (-1.0, 0.0),
            (-0.5, -0.866_025_4),
            (0.5, -0.866_025_4),
        ];
        let mut petals = [flower; P];
        for (p, (c, s)) in petals.iter_mut().zip(ring) {
            *p = flower + v(c * 0.8, 0.0, s * 0.8);
        }
        petals[6] = flower + v(0.0, 0.4, 0.0);
        petals[7] = flower + v(0.0, -0.4, 0.0);
        World {
            flower,
            petals,
            rock: (v(3.0, 1.0, -1.3), S::from_f32(1.0)),
        }
    }

    /// What bee `i` senses at step `step`, from the previous step's states.
    fn frame(&self, bees: &[BeeState<S>], i: usize, step: u32) -> Frame<S> {
        self.frame_in(bees, i, step)
    }

    /// [`World::frame`] in a frame of any capacity (neighbours beyond it are dropped).
    fn frame_in<const NN: usize, const PP: usize>(
        &self,
        bees: &[BeeState<S>],
        i: usize,
        step: u32,
    ) -> BeeFrame<S, NN, PP> {
        let p = BeeParams::<S>::default();
        let me = bees[i].pos;
        let mut f = BeeFrame::new(S::from_i32(step as i32) * p.dt);
        for (j, b) in bees.iter().enumerate() {
            if j != i && (b.pos - me).length() < p.h {
                let _ = f.neighbours.push(BeeNeighbor {
                    pos: b.pos,
                    vel: b.vel,
                    density: b.density,
                });
            }
        }
        for &q in &self.petals {
            if (q - me).length() < p.h {
                let _ = f.targets.push(q);
            }
        }
        if i != NO_GOAL {
            f.goal = Some(self.flower);
        }
        let away = me - self.rock.0;
        if let Some(n) = away.normalized()
            && away.length() - self.rock.1 < S::from_f32(SENSE)
        {
            f.obstacle = Some(ObstacleSense {
                point: self.rock.0 + n * self.rock.1,
                normal: n,
            });
        }
        f
    }
}

/// The swarm at step 0.
fn initial<S: Scalar>() -> [BeeState<S>; AGENTS] {
    let v = Vec3::<S>::from_f32;
    [
        // 0-2: a tight group flying toward the flower (SPH density and repulsion).
        BeeState::new(v(0.0, 1.0, 0.0), v(1.0, 0.0, 0.0)),
        BeeState::new(v(0.6, 1.2, 0.4), v(1.0, 0.0, 0.1)),
        BeeState::new(v(0.3, 0.7, -0.5), v(0.9, 0.1, 0.0)),
        // 3: the rock stands between it and the flower, slightly left: avoids it.
        BeeState::new(v(1.2, 1.0, -2.4), v(1.0, 0.0, 0.3)),
        // 4: at the flower's edge: repelled by its particles.
        BeeState::new(v(5.0, 1.1, 0.5), v(0.5, 0.0, 0.0)),
        // 5: no goal, nearly still: hovers on its stored forward axis.
        BeeState {
            forward: v(0.0, 0.0, 1.0),
            ..BeeState::new(v(-6.0, 2.0, 6.0), v(0.0, 0.01, 0.0))
        },
    ]
}

/// Runs the scenario, emitting every decision word.
pub fn run<S: Word>(out: &mut impl Sink) {
    let w = World::<S>::new();
    let params = BeeParams::<S>::default();
    let mut bees = initial::<S>();
    for step in 0..STEPS {
        let prev = bees;
        for (i, bee) in bees.iter_mut().enumerate() {
            match bee::step(&prev[i], &w.frame(&prev, i, step), &params) {
                Ok((d, next)) => {
                    out.vec3(d.accel);
                    out.vec3(d.velocity);
                    out.scalar(d.roll);
                    out.scalar(d.pitch);
                    out.scalar(d.density);
                    out.put(u32::from(d.avoiding));
                    out.vec3(next.pos);
                    *bee = next;
                }
                Err(e) => out.error(&e),
            }
        }
    }
    probes(&w, &bees, &params, out);
}

/// Bees in the swarm of [`cost`].
pub const COST_AGENTS: usize = 20;
/// Steps of [`cost`]: `COST_AGENTS * COST_STEPS` bee steps are timed.
pub const COST_STEPS: u32 = 16;

/// What [`cost`] measured, in the meter's ticks.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BeeCost {
    /// One `bee::step_checked` call.
    pub step: Stats,
    /// Neighbours in the frames, summed (the mean is `neighbours / step.n`).
    pub neighbours: u32,
    /// Target particles in the frames, summed.
    pub targets: u32,
    /// Frames holding as many neighbours as they can.
    pub full_frames: u32,
    /// Steps whose bee was avoiding the obstacle (eq. 5-7) afterwards.
    pub avoiding: u32,
    /// Controller calls that returned an error (0 expected: only decisions are timed).
    pub errors: u32,
}

/// The swarm of [`cost`] at step 0: a cloud between the rock and the flower, flying toward
/// the flower at varied speeds; every seventh bee has no goal.
fn cost_swarm<S: Scalar>() -> [BeeState<S>; COST_AGENTS] {
    core::array::from_fn(|i| {
        let k = 100 + i as u32;
        let pos = Vec3::new(
            uniform(k, 1, -3.0, 7.0),
            uniform(k, 2, 0.3, 2.5),
            uniform(k, 3, -3.0, 3.0),
        );
        let vel = Vec3::new(
            uniform(k, 4, 0.0, 1.5),
            uniform(k, 5, -0.2, 0.2),
            uniform(k, 6, -0.5, 0.5),
        );
        BeeState::new(pos, vel)
    })
}

/// Times the bee controller as a serial node runs it, call by call: [`COST_AGENTS`] bees in
/// this module's world for [`COST_STEPS`] steps, every bee's `bee::step_checked` on a frame of
/// capacity `NN` neighbours and `PP` target particles (the node's wire capacities), built from
/// the previous step's states (the call `BeeDevice` makes for a `BeeStepRequest`, parameters
/// validated once). The frames are built outside the timed blocks; only the controller call
/// (its input validation included) is timed.
pub fn cost<S: Scalar, const NN: usize, const PP: usize>(
    params: &Checked<BeeParams<S>>,
    meter: &mut impl Meter,
) -> BeeCost {
    let w = World::<S>::new();
    let mut bees = cost_swarm::<S>();
    let mut c = BeeCost::default();
    for step in 0..COST_STEPS {
        let prev = bees;
        for (i, bee) in bees.iter_mut().enumerate() {
            let mut frame: BeeFrame<S, NN, PP> = w.frame_in(&prev, i, step);
            if i % 7 == 6 {
                frame.goal = None;
            }
            c.neighbours += frame.neighbours.len() as u32;
            c.targets += frame.targets.len() as u32;
            c.full_frames += u32::from(frame.neighbours.len() == NN);
            let (r, t) =
                meter.measure((&prev[i], &frame), |(s, f)| bee::step_checked(s, f, params));
            c.step.add(t);
            match r {
                Ok((d, next)) => {
                    c.avoiding += u32::from(d.avoiding);
                    *bee = next;
                }
                Err(_) => c.errors += 1,
            }
        }
    }
    c
}

/// A probe's outcome: the error's marker and code, or (wrongly accepted) the velocity.
fn emit<S: Word>(r: swarm_core::Result<(bee::BeeDecision<S>, BeeState<S>)>, out: &mut impl Sink) {
    if let Some((d, _)) = out.decided(r) {
        out.vec3(d.velocity);
    }
}

/// Bad input must be refused with the same typed error on the MCU and the host: a negative
/// neighbour density, a non-unit obstacle normal, a negative time, a position beyond the
/// limit, and a bad parameter.
fn probes<S: Word>(
    w: &World<S>,
    bees: &[BeeState<S>; AGENTS],
    params: &BeeParams<S>,
    out: &mut impl Sink,
) {
    let v = Vec3::<S>::from_f32;
    let base = w.frame(bees, 0, STEPS);

    let mut f = base.clone();
    f.neighbours.clear();
    let _ = f.neighbours.push(BeeNeighbor {
        pos: v(1.0, 1.0, 1.0),
        vel: Vec3::zero(),
        density: S::ONE,
    });
    let _ = f.neighbours.push(BeeNeighbor {
        pos: v(1.0, 2.0, 1.0),
        vel: Vec3::zero(),
        density: -S::ONE,
    });
    emit(bee::step(&bees[0], &f, params), out);

    let mut f = base.clone();
    f.obstacle = Some(ObstacleSense {
        point: v(1.0, 1.0, 1.0),
        normal: v(0.0, 0.0, 0.9),
    });
    emit(bee::step(&bees[0], &f, params), out);

    let mut f = base.clone();
    f.t = S::from_f32(-1.0);
    emit(bee::step(&bees[0], &f, params), out);

    let mut far = bees[0];
    far.pos.y = S::from_f32(-20_000.0);
    emit(bee::step(&far, &base, params), out);

    let bad = BeeParams {
        dt: S::ZERO,
        ..*params
    };
    emit(bee::step(&bees[0], &base, &bad), out);
}

#[cfg(all(test, feature = "std"))]
mod tests {
    use super::*;
    use crate::host::{Calls, collect};

    fn coverage<S: Word>() {
        let words = collect(run::<S>);
        let per_step = AGENTS * WORDS_PER_BEE_STEP;
        assert_eq!(words.len(), STEPS as usize * per_step + 10);
        let avoiding = |step: usize, i: usize| words[step * per_step + i * WORDS_PER_BEE_STEP + 9];
        assert!(
            (0..STEPS as usize).all(|s| avoiding(s, 5) == 0),
            "bee 5 (far away) never avoids"
        );
        let avoided = (0..STEPS as usize).filter(|&s| avoiding(s, 3) == 1).count();
        assert!(
            avoided >= 2 && avoiding(0, 3) == 1 && avoiding(STEPS as usize - 1, 3) == 0,
            "bee 3 avoids the rock over several steps ({avoided}), then stops once past it"
        );
        // Probes: negative density [1], non-unit normal, t < 0, far position, bad dt.
        let m = crate::ERROR_MARKER;
        assert_eq!(
            words[STEPS as usize * per_step..],
            [
                m,
                2 << 16 | 1,
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
        let bees = initial::<S>();
        let f = |i| w.frame(&bees, i, 0);
        assert!(
            f(0).neighbours.len() >= 2 && f(1).neighbours.len() >= 2,
            "the group senses itself"
        );
        assert!(
            !f(4).targets.is_empty(),
            "bee 4 senses the flower's particles"
        );
        assert!(f(3).obstacle.is_some() && f(5).goal.is_none());
        let p = BeeParams::<S>::default();
        let (d4, _) = bee::step(&bees[4], &f(4), &p).unwrap();
        assert!(d4.density > S::ZERO, "target particles add density");
    }

    fn cost_covers<S: Scalar>() {
        // The serial nodes' parameters (`fw_node::bee_params`) and wire capacities (16, 16).
        let params = BeeParams::<f32>::default().cast::<S>().checked().unwrap();
        let c = cost::<S, 16, 16>(&params, &mut Calls);
        let steps = COST_AGENTS as u32 * COST_STEPS;
        assert_eq!(c.errors, 0, "only decisions are timed");
        assert_eq!((c.step.n, c.step.min, c.step.max), (steps, 1, 1));
        let mean = c.neighbours as f32 / steps as f32;
        assert!((3.0..12.0).contains(&mean), "mean neighbours {mean}");
        assert!(
            c.targets > 0,
            "some bees sense the flower's particles: {c:?}"
        );
        assert!(
            c.avoiding > 0 && c.avoiding < steps / 2,
            "some bees avoid the rock: {c:?}"
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
