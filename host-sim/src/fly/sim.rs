//! The ren2016 engine: every insect goes through `swarm_core::fly::step_checked` each step
//! (Algorithm 1: forces, ORCA, move), in parallel and deterministically: a step reads only
//! what every insect broadcast at the previous one (position and actual velocity, as RVO2
//! does), so any thread count gives the same bits. Then the world keeps the new states
//! physical (the backstop: ORCA's obstacle planes should leave it nothing to do) and counts
//! every correction.

use rayon::prelude::*;
use swarm_core::fly::{self, FlyDecision, FlyParams, FlyState};
use swarm_core::{Checked, Fx, Scalar, StepCtx};

use super::sense::{Stimuli, fly_frame};
use super::world::FlyWorld;
use crate::by_scalar;
use crate::error::{Result, SimError};
use crate::grid::permuted;
use crate::par::for_each_agent;
use crate::scalar::{AgentGroup, ByScalar, SimScalar};

/// What happened in one step, or since the start (one count per insect and step).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Counts {
    /// Insects whose ORCA program was infeasible (the fallback acted).
    pub infeasible: u64,
    /// Insects with more than the frame's capacity of neighbours within r_att.
    pub truncated: u64,
    /// Insects the world put back out of an obstacle.
    pub obstacle: u64,
    /// Insects the world put back inside the container.
    pub bounds: u64,
}

impl std::ops::AddAssign for Counts {
    fn add_assign(&mut self, o: Counts) {
        self.infeasible += o.infeasible;
        self.truncated += o.truncated;
        self.obstacle += o.obstacle;
        self.bounds += o.bounds;
    }
}

/// A group of insects sharing parameters, stimuli and a scalar type. The group owns the world
/// slots `first..first + len`; `ids` keeps each insect's stable id while slots are reordered.
#[derive(Clone, Debug)]
pub struct FlyGroup<S> {
    /// Group name.
    pub name: String,
    /// First world slot of the group.
    pub first: usize,
    /// Controller parameters (validated).
    pub params: Checked<FlyParams<S>>,
    /// The sources it pursues and escapes.
    pub stimuli: Stimuli,
    /// Current states, by slot.
    pub states: Vec<FlyState<S>>,
    /// Stable agent id of each slot.
    pub ids: Vec<u32>,
    /// The last step's decisions, by slot.
    pub decisions: Vec<FlyDecision<S>>,
    /// Whether each insect's last frame was truncated.
    pub truncated: Vec<bool>,
    /// What the world corrected at the last step, by slot: bit 0 an obstacle, bit 1 a wall.
    pub corrected: Vec<u8>,
    pub(crate) next: Vec<FlyState<S>>,
}

impl<S: SimScalar> FlyGroup<S> {
    /// A group of insects starting in `states`, occupying slots (and ids) from `first` on.
    pub fn new(
        name: String,
        first: usize,
        params: Checked<FlyParams<S>>,
        stimuli: Stimuli,
        states: Vec<FlyState<S>>,
    ) -> Self {
        let n = states.len();
        FlyGroup {
            name,
            first,
            params,
            stimuli,
            ids: (first as u32..(first + n) as u32).collect(),
            decisions: vec![FlyDecision::default(); n],
            truncated: vec![false; n],
            corrected: vec![0; n],
            next: states.clone(),
            states,
        }
    }

    /// The random-number context of group slot `k` at step `step`.
    pub(super) fn ctx(&self, seed: u32, step: u32, k: usize) -> StepCtx {
        StepCtx {
            seed,
            agent: self.ids[k],
            step,
        }
    }

    /// Runs every insect's step on its frame: the decisions and the next states as the
    /// controller gave them (not yet kept physical).
    fn decide(&mut self, w: &FlyWorld, seed: u32, step: u32) -> Result<()> {
        let (mut next, mut decisions, mut truncated) = (
            std::mem::take(&mut self.next),
            std::mem::take(&mut self.decisions),
            std::mem::take(&mut self.truncated),
        );
        let this = &*self;
        let result = for_each_agent(
            next.par_iter_mut()
                .zip(decisions.par_iter_mut())
                .zip(truncated.par_iter_mut()),
            || (),
            |(), k, ((out, dec), cut)| {
                let (frame, more) = fly_frame(w, this.first + k, &this.params, this.stimuli);
                let ctx = this.ctx(seed, step, k);
                let (s, d) = fly::step_checked(&this.states[k], &frame, &this.params, ctx)
                    .map_err(|e| SimError::controller("fly step", step, ctx.agent, e))?;
                *out = s;
                *dec = d;
                *cut = more;
                Ok(())
            },
        );
        self.next = next;
        self.decisions = decisions;
        self.truncated = truncated;
        result
    }

    /// Keeps the next states physical, makes them current and writes the sensed world;
    /// returns this step's counts.
    fn commit(&mut self, w: &mut FlyWorld) -> Counts {
        let world = &*w;
        self.next
            .par_iter_mut()
            .zip(self.corrected.par_iter_mut())
            .with_min_len(1024)
            .for_each(|(s, fix)| *fix = world.confine(s));
        w.sensed.write(self.first, &self.ids, &self.next);
        std::mem::swap(&mut self.states, &mut self.next);
        self.counts()
    }

    /// What happened to this group at the last step.
    pub fn counts(&self) -> Counts {
        let mut c = Counts::default();
        for ((d, &t), &fix) in self
            .decisions
            .iter()
            .zip(&self.truncated)
            .zip(&self.corrected)
        {
            c.infeasible += u64::from(d.infeasible);
            c.truncated += u64::from(t);
            c.obstacle += u64::from(fix & 1);
            c.bounds += u64::from(fix >> 1 & 1);
        }
        c
    }

    /// Sorts the group's slots by their cell in the world's grid: changes no result, only
    /// memory locality. Rewrites the group's part of the sensed world.
    fn reorder(&mut self, w: &mut FlyWorld) {
        let perm = w.grid.order_of(&self.states, |s| {
            let p = s.pos.to_f32();
            [p.x, p.y, p.z]
        });
        self.states = permuted(&self.states, &perm);
        self.decisions = permuted(&self.decisions, &perm);
        self.truncated = permuted(&self.truncated, &perm);
        self.corrected = permuted(&self.corrected, &perm);
        self.ids = permuted(&self.ids, &perm);
        self.next.clone_from(&self.states);
        w.sensed.write(self.first, &self.ids, &self.states);
    }

    /// This step's next states as the controller gave them, by slot (after
    /// [`FlySim::decide_all`], before [`FlySim::publish`]).
    pub(super) fn decided(&self) -> &[FlyState<S>] {
        &self.next
    }

    /// The states in id order, with their last decisions.
    pub fn by_id(&self) -> Vec<(u32, FlyState<S>, FlyDecision<S>)> {
        let mut v: Vec<_> = (0..self.states.len())
            .map(|k| (self.ids[k], self.states[k], self.decisions[k]))
            .collect();
        v.sort_unstable_by_key(|e| e.0);
        v
    }
}

/// A group of either scalar type.
pub type AnyFlyGroup = ByScalar<FlyGroup<f32>, FlyGroup<Fx>>;

crate::scalar::agent_group!(FlyGroup);

/// A ren2016 swarm (or several) in its world.
#[derive(Clone, Debug)]
pub struct FlySim {
    /// The world and the sensed state of every insect.
    pub world: FlyWorld,
    /// The groups, in slot order.
    pub groups: Vec<AnyFlyGroup>,
    /// The run's seed (escape angles, white and Gaussian noise, spawn).
    pub seed: u32,
    /// The next step to run.
    pub step: u32,
    /// Re-sort the slots by grid cell every this many steps (0: never). Changes no result.
    pub reorder_every: u32,
    /// What happened at the last step.
    pub last: Counts,
    /// What happened since the start.
    pub total: Counts,
    /// Σ of the polarisation after each step, and the steps measured.
    pub polarisation: (f64, u64),
    /// Insects closer than this count as a collision: 2·radius (the groups' largest).
    pub collision_distance: f32,
}

impl FlySim {
    /// A simulation of `groups` (contiguous slots, in order) in `world`.
    pub fn new(mut world: FlyWorld, groups: Vec<AnyFlyGroup>, seed: u32) -> Self {
        let n = groups.iter().map(AnyFlyGroup::len).sum();
        world.resize(n);
        for g in &groups {
            by_scalar!(g, g => world.sensed.write(g.first, &g.ids, &g.states));
        }
        let radius = groups
            .iter()
            .map(|g| by_scalar!(g, g => g.params.radius.to_f32()))
            .fold(0.0, f32::max);
        let mut sim = FlySim {
            world,
            groups,
            seed,
            step: 0,
            reorder_every: 16,
            last: Counts::default(),
            total: Counts::default(),
            polarisation: (0.0, 0),
            collision_distance: 2.0 * radius,
        };
        sim.reorder();
        sim
    }

    /// Number of insects.
    pub fn agents(&self) -> usize {
        self.world.len()
    }

    /// Sorts every group's slots by grid cell (memory locality for the neighbour queries).
    pub fn reorder(&mut self) {
        self.world.index_positions();
        for g in &mut self.groups {
            by_scalar!(g, g => g.reorder(&mut self.world));
        }
    }

    /// Every insect decides from the previous step's sensed world (nothing is published).
    ///
    /// # Errors
    ///
    /// [`SimError::Controller`] for a frame or state the controller refused.
    pub fn decide_all(&mut self) -> Result<()> {
        let (seed, step) = (self.seed, self.step);
        self.world.index_positions();
        for g in &mut self.groups {
            by_scalar!(g, g => g.decide(&self.world, seed, step))?;
        }
        Ok(())
    }

    /// Confines the decided states, makes them current (broadcast) and moves the step on;
    /// returns this step's counts.
    pub fn publish(&mut self) -> Counts {
        let mut c = Counts::default();
        for g in &mut self.groups {
            c += by_scalar!(g, g => g.commit(&mut self.world));
        }
        self.last = c;
        self.total += c;
        self.step += 1;
        if self.reorder_every > 0 && self.step.is_multiple_of(self.reorder_every) {
            self.reorder();
        }
        c
    }

    /// One whole step ([`FlySim::decide_all`] then [`FlySim::publish`]).
    ///
    /// # Errors
    ///
    /// As [`FlySim::decide_all`].
    pub fn step(&mut self) -> Result<Counts> {
        self.decide_all()?;
        Ok(self.publish())
    }

    /// Every insect's position, in id order.
    pub fn positions_by_id(&self) -> Vec<[f64; 3]> {
        self.by_id(|s| s.pos.as_slice())
    }

    /// Every insect's actual velocity, in id order.
    pub fn velocities_by_id(&self) -> Vec<[f64; 3]> {
        self.by_id(|s| s.vel.as_slice())
    }

    fn by_id(&self, of: impl Fn(&super::world::Sensed) -> &[[f64; 3]]) -> Vec<[f64; 3]> {
        let s = &self.world.sensed;
        let mut out = vec![[0.0; 3]; s.id.len()];
        for (v, &id) in of(s).iter().zip(&s.id) {
            out[id as usize] = *v;
        }
        out
    }

    /// Adds the polarisation of the current velocities to the running mean.
    pub fn measure(&mut self) {
        let phi = crate::eval::frame_polarisation(&self.velocities_by_id());
        self.polarisation.0 += phi;
        self.polarisation.1 += 1;
    }
}
