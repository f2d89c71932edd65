//! The bee engine: every bee goes through `swarm_core::bee::step_checked` each step, in
//! parallel (rayon) and deterministically: a step reads only the previous step's sensed world,
//! so any thread count gives the same bits. Then the world keeps the new states physical (no
//! bee inside an obstacle or outside the bounds) and counts every correction it had to make.

use rayon::prelude::*;
use swarm_core::bee::oscillation::{bee_time, wrap_time};
use swarm_core::bee::{self, BeeDecision, BeeFrame, BeeParams, BeeState};
use swarm_core::{Checked, Fx, Scalar, Vec3};

use super::sense::{BlockCache, fill_frame};
use super::world::BeeWorld;
use crate::by_scalar;
use crate::error::{Result, SimError};
use crate::grid::permuted;
use crate::par::for_each_agent_by;
use crate::scalar::{AgentGroup, ByScalar, SimScalar};

/// Corrections the world made because the controller's move would have left a bee inside an
/// obstacle or outside the bounds (one count per bee and kind per step).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Contacts {
    /// Bees put back on an obstacle's surface.
    pub obstacle: u64,
    /// Bees clamped into the bounds.
    pub bounds: u64,
}

impl Contacts {
    /// Both kinds.
    pub fn total(&self) -> u64 {
        self.obstacle + self.bounds
    }
}

impl std::ops::AddAssign for Contacts {
    fn add_assign(&mut self, o: Contacts) {
        self.obstacle += o.obstacle;
        self.bounds += o.bounds;
    }
}

/// The shared clock at step `step`: `step·dt` seconds, wrapped below the controller's input
/// limit by [`wrap_time`] (the same bits as `step·dt` for the first 16000 s; after that the
/// maneuvering functions of eq. 3-4 keep their phase, see [`TIME_WRAP`]).
///
/// [`TIME_WRAP`]: swarm_core::bee::oscillation::TIME_WRAP
pub fn frame_time(step: u32, dt: f64) -> f64 {
    wrap_time(f64::from(step) * dt)
}

/// The frame time of bee `id` at step `step` in a run with seed `seed`: the bee's own clock
/// ([`bee_time`]: `step·dt` plus its clock offset, drawn once from `(seed, id)`, wrapped), so
/// that every bee runs the maneuvering functions of eq. 3-4 in its own phase.
pub fn bee_frame_time(seed: u32, id: u32, step: u32, dt: f64) -> f64 {
    bee_time(seed, id, step, dt)
}

/// A decision before the first step: nothing decided yet.
fn no_decision<S: Scalar>(s: &BeeState<S>) -> BeeDecision<S> {
    BeeDecision {
        accel: Vec3::zero(),
        velocity: s.vel,
        roll: s.roll,
        pitch: s.pitch,
        avoiding: s.avoiding,
        density: s.density,
    }
}

/// A group of bees sharing parameters, a goal and a scalar type. The group owns the world slots
/// `first..first + len`; slots are reordered now and then so that bees near each other in the
/// world are near each other in memory, and `ids` keeps each bee's stable id.
#[derive(Clone, Debug)]
pub struct BeeGroup<S> {
    /// Group name.
    pub name: String,
    /// First world slot of the group.
    pub first: usize,
    /// Controller parameters (validated).
    pub params: Checked<BeeParams<S>>,
    /// Object id of the target the group flies to (its centre is the frames' goal while it is
    /// active).
    pub goal: Option<u16>,
    /// Current states, by slot.
    pub states: Vec<BeeState<S>>,
    /// Stable agent id of each slot.
    pub ids: Vec<u32>,
    /// The last step's decisions, by slot (roll, pitch, avoiding, ...).
    pub decisions: Vec<BeeDecision<S>>,
    /// What the world corrected at the last step, by slot: bit 0 the bee was put back out of
    /// an obstacle, bit 1 into the bounds (see [`BeeWorld::confine`]).
    pub corrected: Vec<u8>,
    next: Vec<BeeState<S>>,
}

impl<S: SimScalar> BeeGroup<S> {
    /// A group of bees starting in `states`, occupying slots (and ids) from `first` on.
    pub fn new(
        name: String,
        first: usize,
        params: Checked<BeeParams<S>>,
        goal: Option<u16>,
        states: Vec<BeeState<S>>,
    ) -> Self {
        BeeGroup {
            name,
            first,
            params,
            goal,
            ids: (first as u32..(first + states.len()) as u32).collect(),
            decisions: states.iter().map(no_decision).collect(),
            next: states.clone(),
            corrected: vec![0; states.len()],
            states,
        }
    }

    /// Runs every bee's controller on its frame: the decisions and the next states as the
    /// controller gave them (not yet kept physical: [`BeeGroup::confine`]).
    fn decide(&mut self, w: &BeeWorld, seed: u32, step: u32) -> Result<()> {
        let (first, params) = (self.first, &self.params);
        let goal = self.goal.and_then(|g| w.target_center(g));
        let dt = params.dt.to_f64();
        let ids = &self.ids;
        for_each_agent_by(
            self.next
                .par_iter_mut()
                .zip(self.decisions.par_iter_mut())
                .zip(self.states.par_iter().zip(ids.par_iter())),
            |k| u64::from(ids[k]),
            || (BlockCache::default(), BeeFrame::new(S::ZERO)),
            |(cache, frame), k, ((out, dec), (s, &id))| {
                // Each bee's own clock (its phase of eq. 3-4), hence its own constants.
                let t = S::from_f64(bee_frame_time(seed, id, step, dt));
                fill_frame::<S>(w, first + k, goal, t, cache, frame);
                let consts = bee::StepConsts::new(params, t);
                let (d, next) = bee::step_with(s, frame, params, &consts)
                    .map_err(|e| SimError::controller("bee step", step, id, e))?;
                *dec = d;
                *out = next;
                Ok(())
            },
        )
    }

    /// Keeps the next states physical (see [`BeeWorld::confine`]), noting each correction.
    fn confine(&mut self, w: &BeeWorld) {
        self.next
            .par_iter_mut()
            .zip(self.corrected.par_iter_mut())
            .for_each(|(next, fix)| *fix = w.confine(next));
    }

    /// Makes the new states current, writes the sensed world and counts the corrections.
    fn commit(&mut self, w: &mut BeeWorld) -> Contacts {
        w.sensed.write(self.first, &self.ids, &self.next);
        let (mut obstacle, mut bounds) = (0u64, 0u64);
        for &fix in &self.corrected {
            obstacle += u64::from(fix & 1);
            bounds += u64::from(fix >> 1 & 1);
        }
        std::mem::swap(&mut self.states, &mut self.next);
        Contacts { obstacle, bounds }
    }

    /// Sorts the group's slots by their cell in the world's grid (then by slot): a permutation
    /// of the slots that changes no result, only memory locality. Rewrites the group's part of
    /// the sensed world.
    fn reorder(&mut self, w: &mut BeeWorld) {
        let perm = w.grid.order_of(&self.states, |s| {
            [s.pos.x.to_f32(), s.pos.y.to_f32(), s.pos.z.to_f32()]
        });
        self.states = permuted(&self.states, &perm);
        self.decisions = permuted(&self.decisions, &perm);
        self.corrected = permuted(&self.corrected, &perm);
        self.ids = permuted(&self.ids, &perm);
        w.sensed.write(self.first, &self.ids, &self.states);
    }

    /// This step's next states as the controller gave them, by slot (after
    /// [`BeeSim::decide_all`], before [`BeeSim::publish`]).
    pub(super) fn decided(&self) -> &[BeeState<S>] {
        &self.next
    }

    /// The states in id order, with their last decisions.
    pub fn by_id(&self) -> Vec<(u32, BeeState<S>, BeeDecision<S>)> {
        let mut v: Vec<_> = (0..self.states.len())
            .map(|k| (self.ids[k], self.states[k], self.decisions[k]))
            .collect();
        v.sort_unstable_by_key(|e| e.0);
        v
    }
}

/// A group of either scalar type.
pub type AnyBeeGroup = ByScalar<BeeGroup<f32>, BeeGroup<Fx>>;

crate::scalar::agent_group!(BeeGroup);

/// A bee swarm (or several) in its world.
#[derive(Clone, Debug)]
pub struct BeeSim {
    /// The world and the sensed state of every bee.
    pub world: BeeWorld,
    /// The groups, in agent-index order.
    pub groups: Vec<AnyBeeGroup>,
    /// The run's seed: the spawn draws and every bee's clock offset ([`bee_frame_time`]; the
    /// bee controller itself draws no random numbers).
    pub seed: u32,
    /// The next step to run; a bee's frame time is its own clock, `step · dt` plus its offset
    /// ([`bee_frame_time`]).
    pub step: u32,
    /// Re-sort the slots by grid cell every this many steps (0: never). Changes no result.
    pub reorder_every: u32,
    /// Corrections made at the last step.
    pub last_contacts: Contacts,
    /// Corrections made since the start.
    pub contacts: Contacts,
    /// Bees closer than this count as a collision in the summary: `collision_distance` of the
    /// groups' radii (two capsules of radius r touch when their centres are 2r apart).
    pub collision_distance: f32,
}

/// The distance under which two bees of bodies of radii `radii` (the groups') count as a
/// collision in the summary: two capsules of radius r touch when their centres are 2r apart,
/// with r the largest radius (0 for none).
pub fn collision_distance(radii: impl IntoIterator<Item = f32>) -> f32 {
    2.0 * radii.into_iter().fold(0.0, f32::max)
}

impl BeeSim {
    /// A simulation of `groups` (contiguous agent indices, in order) in `world`.
    pub fn new(mut world: BeeWorld, groups: Vec<AnyBeeGroup>, seed: u32) -> Self {
        let n = groups.iter().map(AnyBeeGroup::len).sum();
        world.sensed.resize(n);
        world.size_grids(n);
        world.index_targets();
        for g in &groups {
            by_scalar!(g, g => for (k, s) in g.states.iter().enumerate() {
                world.sensed.set(g.first + k, g.ids[k], s);
            });
        }
        let mut sim = BeeSim {
            world,
            groups,
            seed,
            step: 0,
            reorder_every: 16,
            last_contacts: Contacts::default(),
            contacts: Contacts::default(),
            collision_distance: 0.0,
        };
        sim.collision_distance = collision_distance(
            sim.groups
                .iter()
                .map(|g| by_scalar!(g, g => g.params.radius.to_f32())),
        );
        // Spatial slot order from the start (changes no result).
        sim.reorder();
        sim
    }

    /// Number of bees.
    pub fn agents(&self) -> usize {
        self.world.len()
    }

    /// Sorts every group's slots by grid cell (memory locality for the neighbour queries).
    pub fn reorder(&mut self) {
        for g in &mut self.groups {
            by_scalar!(g, g => g.reorder(&mut self.world));
        }
    }

    /// One step: every bee runs `bee::step_checked` on its frame (built from the previous
    /// step's sensed world), the world confines the new states (see [`BeeWorld::confine`]),
    /// then the sensed world takes them (positions, velocities, densities broadcast). Returns
    /// the corrections of this step (also added to [`BeeSim::contacts`]). The same as
    /// [`BeeSim::decide_all`] then [`BeeSim::publish`].
    pub fn step(&mut self) -> Result<Contacts> {
        self.decide_all()?;
        Ok(self.publish())
    }

    /// Every bee decides from the previous step's sensed world (nothing is published).
    pub fn decide_all(&mut self) -> Result<()> {
        let step = self.step;
        self.world.index_positions();
        for g in &mut self.groups {
            by_scalar!(g, g => g.decide(&self.world, self.seed, step))?;
        }
        Ok(())
    }

    /// Confines the decided states, makes them current and moves the step on; returns the
    /// corrections made.
    pub fn publish(&mut self) -> Contacts {
        let step = self.step;
        let mut c = Contacts::default();
        for g in &mut self.groups {
            c += by_scalar!(g, g => {
                g.confine(&self.world);
                g.commit(&mut self.world)
            });
        }
        self.last_contacts = c;
        self.contacts += c;
        if self.reorder_every > 0 && (step + 1).is_multiple_of(self.reorder_every) {
            self.reorder();
        }
        self.step += 1;
        c
    }

    /// Every bee's position, in id order.
    pub fn positions_by_id(&self) -> Vec<[f64; 3]> {
        let s = &self.world.sensed;
        let mut out = vec![[0.0; 3]; s.pos.len()];
        for (p, &id) in s.pos.iter().zip(&s.id) {
            out[id as usize] = *p;
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bees::sense::bee_frame;
    use crate::bees::world::{BeeObstacle, BeeTarget, Shape3};

    /// 600 bees of each scalar type around a nest, between two shafts, over a ground.
    fn world_sim(n: usize) -> BeeSim {
        let p = BeeParams::<f32>::around_nest();
        let mut w = BeeWorld::new([0.0; 3], [40.0, 20.0, 40.0], 3.5, 4.0);
        w.obstacles = vec![
            BeeObstacle::new(
                0,
                "ground",
                Shape3::Box {
                    min: [0.0; 3],
                    max: [40.0, 1.0, 40.0],
                },
                true,
            ),
            BeeObstacle::new(
                1,
                "shaft",
                Shape3::Shaft {
                    center: [20.0, 16.0],
                    radius: 1.5,
                    y_min: 0.0,
                    y_max: 20.0,
                },
                true,
            ),
            BeeObstacle::new(
                2,
                "ball",
                Shape3::Sphere {
                    center: [14.0, 8.0, 24.0],
                    radius: 2.0,
                },
                true,
            ),
        ];
        w.targets = vec![BeeTarget::new(3, "nest", [28.0, 8.0, 20.0], 2.0, 150)];
        let spawn = |i: usize| {
            let r = |k| swarm_core::rand::rand(3, i as u32, u32::MAX, k) as f32 / 4.3e9;
            [4.0 + 12.0 * r(0), 3.0 + 12.0 * r(1), 8.0 + 24.0 * r(2)]
        };
        let f32s: Vec<BeeState<f32>> = (0..n)
            .map(|i| {
                let q = spawn(i);
                BeeState::new(Vec3::from_f32(q[0], q[1], q[2]), Vec3::zero())
            })
            .collect();
        let fxs: Vec<BeeState<Fx>> = (n..2 * n)
            .map(|i| {
                let q = spawn(i);
                BeeState::new(Vec3::from_f32(q[0], q[1], q[2]), Vec3::zero())
            })
            .collect();
        let g1 = BeeGroup::new("f32".into(), 0, p.checked().unwrap(), Some(3), f32s);
        let g2 = BeeGroup::new(
            "fx".into(),
            n,
            p.cast::<Fx>().checked().unwrap(),
            Some(3),
            fxs,
        );
        BeeSim::new(w, vec![g1.into(), g2.into()], 7)
    }

    /// Hash of every bee's full state (f64 bits of the sensed world plus roll/pitch/avoiding of
    /// the decisions), in id order.
    fn hash(sim: &BeeSim) -> u64 {
        let mut h = 0xcbf2_9ce4_8422_2325u64;
        let mut mix = |x: u64| h = (h ^ x).wrapping_mul(0x100_0000_01b3);
        for g in &sim.groups {
            by_scalar!(g, g => for (id, s, d) in g.by_id() {
                mix(u64::from(id));
                for v in [s.pos, s.vel, s.forward, s.u0] {
                    for c in [v.x, v.y, v.z] {
                        mix(c.to_f64().to_bits());
                    }
                }
                for c in [s.density, d.roll, d.pitch] {
                    mix(c.to_f64().to_bits());
                }
                mix(u64::from(d.avoiding));
            });
        }
        mix(sim.contacts.obstacle);
        mix(sim.contacts.bounds);
        h
    }

    fn run(threads: usize, every: u32, steps: u32) -> u64 {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let mut sim = world_sim(300);
            sim.reorder_every = every;
            for _ in 0..steps {
                sim.step().unwrap();
            }
            hash(&sim)
        })
    }

    #[test]
    fn bit_identical_for_any_thread_count() {
        assert_eq!(run(1, 16, 200), run(2, 16, 200));
        assert_eq!(run(1, 16, 200), run(3, 16, 200));
    }

    #[test]
    fn the_test_world_exercises_avoidance_targets_and_corrections() {
        let mut sim = world_sim(300);
        let (mut avoiding, mut with_targets) = (0usize, 0usize);
        for _ in 0..200 {
            sim.step().unwrap();
            for g in &sim.groups {
                avoiding += by_scalar!(g, g => g.decisions.iter().filter(|d| d.avoiding).count());
            }
            with_targets += (0..sim.agents())
                .filter(|&i| {
                    !bee_frame::<f32>(&sim.world, i, None, 0.0)
                        .targets
                        .is_empty()
                })
                .count();
        }
        assert!(
            avoiding > 0 && with_targets > 0,
            "{avoiding} {with_targets}"
        );
        assert!(
            sim.contacts.obstacle > 0 && sim.contacts.bounds > 0,
            "{:?}",
            sim.contacts
        );
    }

    #[test]
    fn reordering_slots_changes_no_result() {
        let base = run(2, 0, 200);
        assert_eq!(base, run(2, 1, 200));
        assert_eq!(base, run(2, 16, 200));
    }

    #[test]
    fn no_bee_ends_a_step_inside_an_obstacle_or_outside_the_bounds() {
        let mut sim = world_sim(300);
        for _ in 0..300 {
            sim.step().unwrap();
            for p in &sim.world.sensed.pos {
                assert!(
                    sim.world
                        .inside_obstacle(crate::scalar::v3::<f32>(*p))
                        .is_none(),
                    "{p:?}"
                );
                assert!(
                    (0..3).all(|k| p[k] >= f64::from(sim.world.min[k])
                        && p[k] <= f64::from(sim.world.max[k]))
                );
            }
        }
    }

    /// One bee flying +x at 1 unit/s with a shaft ahead, on its left (−z) or right (+z).
    fn roll_toward_shaft<S: SimScalar>(side_z: f32) -> (f32, f32)
    where
        AnyBeeGroup: From<BeeGroup<S>>,
    {
        let p = BeeParams::<S>::default();
        let mut w = BeeWorld::new([-10.0, 0.0, -10.0], [10.0, 10.0, 10.0], 3.5, 4.0);
        let shaft = Shape3::Shaft {
            center: [2.5, side_z],
            radius: 1.0,
            y_min: 0.0,
            y_max: 10.0,
        };
        w.obstacles = vec![BeeObstacle::new(0, "shaft", shaft, true)];
        let bee = BeeState::new(Vec3::from_f32(0.0, 5.0, 0.0), Vec3::from_f32(1.0, 0.0, 0.0));
        let g = BeeGroup::new("one".into(), 0, p.checked().unwrap(), None, vec![bee]);
        let mut sim = BeeSim::new(w, vec![g.into()], 0);
        sim.step().unwrap();
        let d = by_scalar!(&sim.groups[0], g => (g.decisions[0].avoiding, g.decisions[0].roll.to_f32()));
        assert!(d.0, "the bee avoids the shaft");
        // Eq. 6 at d = |closest point − bee| = hypot(2.5, 0.8) − 1.
        let dist = 2.5f64.hypot(f64::from(side_z)) - 1.0;
        let want = (-(2.0 - dist).powi(2) / 2.0).exp() * 45f64.to_radians();
        (d.1, want as f32)
    }

    #[test]
    fn roll_to_avoidance_has_opposite_signs_left_and_right_and_the_eq6_magnitude() {
        for (tol, (left, want_l), (right, want_r)) in [
            (
                1e-5,
                roll_toward_shaft::<f32>(-0.8),
                roll_toward_shaft::<f32>(0.8),
            ),
            (
                1e-3,
                roll_toward_shaft::<Fx>(-0.8),
                roll_toward_shaft::<Fx>(0.8),
            ),
        ] {
            // Facing +x with y up, −z is the bee's left: roll right (positive), and vice versa.
            assert!(left > 0.0 && right < 0.0, "left {left}, right {right}");
            assert!((left - want_l).abs() < tol, "left {left}, eq. 6 {want_l}");
            assert!(
                (right + want_r).abs() < tol,
                "right {right}, eq. 6 {}",
                -want_r
            );
        }
    }
}
