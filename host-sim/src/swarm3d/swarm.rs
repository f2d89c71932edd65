//! The host of a 3D flying swarm, whatever its controller: groups of insects that each step
//! build their frames from the [`World3d`], run their controller in parallel, are kept
//! physical by the world (every correction counted) and broadcast their new state. A step
//! reads only what every insect broadcast at the previous one (as RVO2 does), so any thread
//! count gives the same bits.
//!
//! A model plugs in with two traits: [`Step3d`] (its parameters in one scalar type: the frame,
//! the step, what a decision counts) and [`Model3d`] (the model over both scalars: the
//! group's inputs, the counts, and the measures the run accumulates).

use std::fmt::Debug;
use std::ops::AddAssign;

use rayon::prelude::*;
use swarm_core::model::Model;
use swarm_core::model::ModelParams;
use swarm_core::wire::{Controller, Endpoint};
use swarm_core::{Checked, Fx, StepCtx, Vec3};

use super::world::{Kinematic, Sensed, World3d, clear_of};
use crate::by_scalar;
use crate::engine::{Exchange, StateNames};
use crate::error::{Result, SimError};
use crate::grid::permuted;
use crate::output::{AgentSample, Frame, Summary};
use crate::par::for_each_agent_by;
use crate::scalar::{AgentGroup, ByScalar, SimScalar};
use crate::scenario::{Group, ScalarType, Scenario};
use crate::space::{BeeObstacle, Shape3};
use crate::spawn::spaced3;

/// A 3D flying model's parameters in scalar `S`: how an insect senses the world and steps.
pub trait Step3d<S: SimScalar>:
    Model<State: Kinematic<S> + Send + Sync> + Controller + Debug + Send + Sync + 'static
{
    /// What a step decides besides the next state.
    type Decision: Copy + Default + Debug + Send + Sync;
    /// The step's sensor frame.
    type Frame;
    /// What a group gives its insects besides the parameters ([`Model3d::Inputs`]).
    type Inputs: Copy;
    /// What a step counts ([`Model3d::Counts`]).
    type Counts;
    /// The step's name in controller errors (`fly step`).
    const STEP: &'static str;
    /// What [`Step3d::marks`]' codes mean.
    const STATE_NAMES: StateNames;

    /// The frame of the insect in world slot `slot`, and whether the world held more
    /// neighbours in range than the frame does.
    fn frame(&self, w: &World3d, slot: usize, inputs: Self::Inputs) -> (Self::Frame, bool);
    /// The controller's step.
    ///
    /// # Errors
    ///
    /// What the controller refuses.
    fn step(
        params: &Checked<Self>,
        state: &Self::State,
        frame: &Self::Frame,
        ctx: StepCtx,
    ) -> swarm_core::Result<(Self::State, Self::Decision)>;
    /// The step as the wire exchanges it (request and reply) for insect `agent`.
    ///
    /// # Errors
    ///
    /// [`SimError::Encode`] if a message cannot be encoded.
    fn exchange(
        agent: u32,
        request: (Self::State, Self::Frame, StepCtx),
        reply: (Self::Decision, Self::State),
    ) -> Result<Exchange>;
    /// What one insect's step counts, given its decision, whether its frame was truncated
    /// and what the world corrected (bit 0 an obstacle, bit 1 a wall).
    fn count(d: &Self::Decision, truncated: bool, corrected: u8) -> Self::Counts;
    /// The recorded sample's `label` and `motion` of an insect.
    fn marks(state: &Self::State, d: &Self::Decision) -> (u8, u8);
    /// A state at rest at `pos`, as spawned.
    fn at(pos: Vec3<S>) -> Self::State;
    /// The body radius (collisions are closer than two).
    fn radius(&self) -> f32;
    /// The radius ORCA keeps (spawned insects start two apart).
    fn orca_radius(&self) -> f32;
    /// The neighbour range of the frame.
    fn range(&self) -> f32;
    /// How far a surface can bind ORCA ([`reach`](super::reach)).
    fn reach(&self) -> f32;
    /// The soft device of these parameters (the model's firmware endpoint).
    ///
    /// # Errors
    ///
    /// [`SimError::Device`] if the endpoint refuses the parameters.
    fn soft(params: &Checked<Self>) -> Result<Box<dyn Endpoint + Send>>;
}

/// A 3D flying model over both scalar types.
pub trait Model3d: Clone + Debug + Send + Sync + Sized + 'static {
    /// The parameters in each scalar type.
    type Params<S: SimScalar>: Step3d<S, Inputs = Self::Inputs, Counts = Self::Counts> + Clone;
    /// What a group gives its insects besides the parameters (the fly's stimuli).
    type Inputs: Copy + Debug + Send + Sync;
    /// What happened in one step, or since the start (one count per insect and step).
    type Counts: Copy + Default + AddAssign + Debug + PartialEq + Send;
    /// What the run accumulates after each step ([`Model3d::measure`]).
    type Measures: Clone + Debug + Default + Send;

    /// The `f32` parameters in `S`.
    fn cast<S: SimScalar>(p: &Self::Params<f32>) -> Self::Params<S>;
    /// Adds the current step to the measures.
    fn measure(sim: &mut Swarm3d<Self>);
    /// Writes the run's figures into the summary; returns the run log's line.
    fn closing(sim: &Swarm3d<Self>, summary: &mut Summary) -> String;
    /// What the model changes after every insect moved, before the next step (li2015: a
    /// group moves on to the next light of its route); nothing by default.
    fn between_steps(_sim: &mut Swarm3d<Self>) {}
    /// Refuses a device (the mirror) that could not stay in step with the run (li2015: a
    /// route changes the density the device holds); none by default.
    ///
    /// # Errors
    ///
    /// The model's reason.
    fn device_ready(_sim: &Swarm3d<Self>) -> Result<()> {
        Ok(())
    }
}

/// The state of model `M`'s insects in scalar `S`.
pub type StateOf<M, S> = <<M as Model3d>::Params<S> as Model>::State;
/// The decision of model `M`'s step in scalar `S`.
pub type DecisionOf<M, S> = <<M as Model3d>::Params<S> as Step3d<S>>::Decision;
/// An insect's id, state and last decision.
pub type Insect<M, S> = (u32, StateOf<M, S>, DecisionOf<M, S>);

/// A group of insects sharing parameters, inputs and a scalar type. The group owns the world
/// slots `first..first + len`; `ids` keeps each insect's stable id while slots are reordered.
#[derive(Clone, Debug)]
pub struct Group3d<M: Model3d, S: SimScalar> {
    /// Group name.
    pub name: String,
    /// First world slot of the group.
    pub first: usize,
    /// Controller parameters (validated).
    pub params: Checked<M::Params<S>>,
    /// What the group gives its insects besides the parameters.
    pub inputs: M::Inputs,
    /// Current states, by slot.
    pub states: Vec<StateOf<M, S>>,
    /// Stable agent id of each slot.
    pub ids: Vec<u32>,
    /// The last step's decisions, by slot.
    pub decisions: Vec<DecisionOf<M, S>>,
    /// Whether each insect's last frame was truncated.
    pub truncated: Vec<bool>,
    /// What the world corrected at the last step, by slot: bit 0 an obstacle, bit 1 a wall.
    pub corrected: Vec<u8>,
    pub(crate) next: Vec<StateOf<M, S>>,
}

impl<M: Model3d, S: SimScalar> Group3d<M, S> {
    /// A group of insects starting in `states`, occupying slots (and ids) from `first` on.
    pub fn new(
        name: String,
        first: usize,
        params: Checked<M::Params<S>>,
        inputs: M::Inputs,
        states: Vec<StateOf<M, S>>,
    ) -> Self {
        let n = states.len();
        Group3d {
            name,
            first,
            params,
            inputs,
            ids: (first as u32..(first + n) as u32).collect(),
            decisions: vec![DecisionOf::<M, S>::default(); n],
            truncated: vec![false; n],
            corrected: vec![0; n],
            next: states.clone(),
            states,
        }
    }

    /// The insects of scenario group `g`, ids `first..`, at rest at the places `at` gives once
    /// the parameters `p` are checked in `S`.
    fn spawn(
        g: &Group,
        p: &M::Params<f32>,
        inputs: M::Inputs,
        first: usize,
        at: impl FnOnce() -> Result<Vec<[f32; 3]>>,
    ) -> Result<Self> {
        let checked = M::cast::<S>(p)
            .checked()
            .map_err(|source| SimError::GroupParams {
                group: g.name.clone(),
                source,
            })?;
        let states = at()?
            .into_iter()
            .map(|q| M::Params::<S>::at(Vec3::from_f32(q[0], q[1], q[2])))
            .collect();
        Ok(Group3d::new(g.name.clone(), first, checked, inputs, states))
    }

    /// The random-number context of group slot `k` at step `step`.
    pub fn ctx(&self, seed: u32, step: u32, k: usize) -> StepCtx {
        StepCtx {
            seed,
            agent: self.ids[k],
            step,
        }
    }

    /// The frame of the insect in world slot `slot` (of this group).
    pub fn frame(&self, w: &World3d, slot: usize) -> <M::Params<S> as Step3d<S>>::Frame {
        self.params.frame(w, slot, self.inputs).0
    }

    /// Runs every insect's step on its frame: the decisions and the next states as the
    /// controller gave them (not yet kept physical).
    fn decide(&mut self, w: &World3d, seed: u32, step: u32) -> Result<()> {
        let (mut next, mut decisions, mut truncated) = (
            std::mem::take(&mut self.next),
            std::mem::take(&mut self.decisions),
            std::mem::take(&mut self.truncated),
        );
        let this = &*self;
        let result = for_each_agent_by(
            next.par_iter_mut()
                .zip(decisions.par_iter_mut())
                .zip(truncated.par_iter_mut()),
            |k| u64::from(this.ids[k]),
            || (),
            |(), k, ((out, dec), cut)| {
                let (frame, more) = this.params.frame(w, this.first + k, this.inputs);
                let ctx = this.ctx(seed, step, k);
                let (s, d) = M::Params::<S>::step(&this.params, &this.states[k], &frame, ctx)
                    .map_err(|e| SimError::controller(M::Params::<S>::STEP, step, ctx.agent, e))?;
                (*out, *dec, *cut) = (s, d, more);
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
    fn commit(&mut self, w: &mut World3d) -> M::Counts {
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
    pub fn counts(&self) -> M::Counts {
        let mut c = M::Counts::default();
        for ((d, &t), &fix) in self
            .decisions
            .iter()
            .zip(&self.truncated)
            .zip(&self.corrected)
        {
            c += M::Params::<S>::count(d, t, fix);
        }
        c
    }

    /// Sorts the group's slots by their cell in the world's grid: changes no result, only
    /// memory locality. Rewrites the group's part of the sensed world.
    fn reorder(&mut self, w: &mut World3d) {
        let perm = w.grid.order_of(&self.states, |s| {
            let p = s.kinematics().0.to_f32();
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
    /// [`Swarm3d::decide_all`], before [`Swarm3d::publish`]).
    pub fn decided(&self) -> &[StateOf<M, S>] {
        &self.next
    }

    /// The exchange of the insect in world slot `slot` (of this group) at the step `sim` is
    /// deciding.
    pub(crate) fn exchange(&self, sim: &Swarm3d<M>, slot: usize) -> Result<Exchange> {
        let k = slot - self.first;
        let request = (
            self.states[k],
            self.frame(&sim.world, slot),
            self.ctx(sim.seed, sim.step, k),
        );
        M::Params::<S>::exchange(self.ids[k], request, (self.decisions[k], self.next[k]))
    }

    /// The states in id order, with their last decisions.
    pub fn by_id(&self) -> Vec<Insect<M, S>> {
        let mut v: Vec<_> = (0..self.states.len())
            .map(|k| (self.ids[k], self.states[k], self.decisions[k]))
            .collect();
        v.sort_unstable_by_key(|e| e.0);
        v
    }

    /// Writes the group's insects into `out` (by id) as recorded samples: the heading is the
    /// unit actual velocity, `label` and `motion` as the model marks them.
    fn samples(&self, group: u16, out: &mut [AgentSample]) {
        for (k, s) in self.states.iter().enumerate() {
            let (pos, vel) = s.kinematics();
            let v = vel.to_f32();
            let len = v.length();
            let heading = if len > 0.0 {
                [v.x / len, v.y / len, v.z / len]
            } else {
                [1.0, 0.0, 0.0]
            };
            let id = self.ids[k];
            let p = pos.to_f32();
            let (label, motion) = M::Params::<S>::marks(s, &self.decisions[k]);
            out[id as usize] = AgentSample {
                id,
                pos: [p.x, p.y, p.z],
                heading,
                group,
                label,
                motion,
                roll: 0.0,
                pitch: 0.0,
            };
        }
    }
}

impl<M: Model3d, S: SimScalar> AgentGroup for Group3d<M, S> {
    fn name(&self) -> &str {
        &self.name
    }
    fn len(&self) -> usize {
        self.states.len()
    }
    fn first(&self) -> usize {
        self.first
    }
}

/// A group of either scalar type.
pub type AnyGroup3d<M> = ByScalar<Group3d<M, f32>, Group3d<M, Fx>>;

impl<M: Model3d> From<Group3d<M, f32>> for AnyGroup3d<M> {
    fn from(g: Group3d<M, f32>) -> Self {
        ByScalar::F32(g)
    }
}

impl<M: Model3d> From<Group3d<M, Fx>> for AnyGroup3d<M> {
    fn from(g: Group3d<M, Fx>) -> Self {
        ByScalar::Fixed(g)
    }
}

/// A swarm of model `M` (one group or several) in its world.
#[derive(Clone, Debug)]
pub struct Swarm3d<M: Model3d> {
    /// The world and the sensed state of every insect.
    pub world: World3d,
    /// The groups, in slot order.
    pub groups: Vec<AnyGroup3d<M>>,
    /// The run's seed.
    pub seed: u32,
    /// The next step to run.
    pub step: u32,
    /// Re-sort the slots by grid cell every this many steps (0: never). Changes no result.
    pub reorder_every: u32,
    /// What happened at the last step.
    pub last: M::Counts,
    /// What happened since the start.
    pub total: M::Counts,
    /// What the run accumulated after each measured step.
    pub measures: M::Measures,
    /// Insects closer than this count as a collision: 2·radius (the groups' largest).
    pub collision_distance: f32,
}

impl<M: Model3d> Swarm3d<M> {
    /// A simulation of `groups` (contiguous slots, in order) in `world`.
    pub fn new(mut world: World3d, groups: Vec<AnyGroup3d<M>>, seed: u32) -> Self {
        let n = groups.iter().map(AgentGroup::len).sum();
        world.resize(n);
        for g in &groups {
            by_scalar!(g, g => world.sensed.write(g.first, &g.ids, &g.states));
        }
        let radius = groups
            .iter()
            .map(|g| by_scalar!(g, g => g.params.radius()))
            .fold(0.0, f32::max);
        let mut sim = Swarm3d {
            world,
            groups,
            seed,
            step: 0,
            reorder_every: 16,
            last: M::Counts::default(),
            total: M::Counts::default(),
            measures: M::Measures::default(),
            collision_distance: 2.0 * radius,
        };
        sim.reorder();
        sim
    }

    /// The simulation of `scenario` (a 3D world, whose box is the container) with seed `seed`
    /// and each group's parameters as `read` gives them: the obstacles, and each group's insects spawned at
    /// rest, uniformly in its region, two ORCA radii apart and clear of the obstacles (ORCA
    /// keeps apart only insects that start apart), with the inputs `inputs` gives it (which
    /// may add stimulus sources to the world).
    ///
    /// # Errors
    ///
    /// [`SimError::WrongWorld`] for a 2D world, [`SimError::GroupParams`] for parameters the
    /// controller refuses, what `read`, `inputs` and spawning refuse.
    pub fn build(
        scenario: &Scenario,
        seed: u32,
        read: impl Fn(&Group) -> Result<M::Params<f32>>,
        mut inputs: impl FnMut(&Group, &mut World3d) -> Result<M::Inputs>,
    ) -> Result<Self> {
        let (min, max) = scenario.bounds::<3>(<M::Params<f32> as Model>::NAME)?;
        let params = scenario.group_params(read)?;
        let largest = |f: fn(&M::Params<f32>) -> f32| params.iter().map(f).fold(0.0, f32::max);
        let mut world = World3d::new(min, max, largest(|p| p.range()), largest(|p| p.reach()));
        for (id, o) in scenario.objects.iter().enumerate() {
            if let Some(shape) = Shape3::of(&o.kind) {
                world
                    .obstacles
                    .push(BeeObstacle::new(id as u16, &o.name, shape, o.active));
            }
        }
        let groups = crate::spawn::groups(scenario, params, |g, p, first| {
            let inputs = inputs(g, &mut world)?;
            let r = p.orca_radius();
            let clear = |q: [f32; 3]| clear_of(&world.obstacles, min, max, r, q);
            let at = || spaced3(scenario, g, seed, first, 2.0 * r, clear);
            Ok::<AnyGroup3d<M>, SimError>(match g.scalar {
                ScalarType::F32 => Group3d::<M, f32>::spawn(g, &p, inputs, first, at)?.into(),
                ScalarType::Fixed => Group3d::<M, Fx>::spawn(g, &p, inputs, first, at)?.into(),
            })
        })?;
        Ok(Swarm3d::new(world, groups, seed))
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
    pub fn publish(&mut self) -> M::Counts {
        let mut c = M::Counts::default();
        for g in &mut self.groups {
            c += by_scalar!(g, g => g.commit(&mut self.world));
        }
        self.last = c;
        self.total += c;
        self.step += 1;
        M::between_steps(self);
        if self.reorder_every > 0 && self.step.is_multiple_of(self.reorder_every) {
            self.reorder();
        }
        c
    }

    /// One whole step ([`Swarm3d::decide_all`] then [`Swarm3d::publish`]).
    ///
    /// # Errors
    ///
    /// As [`Swarm3d::decide_all`].
    pub fn step(&mut self) -> Result<M::Counts> {
        self.decide_all()?;
        Ok(self.publish())
    }

    /// Adds the current step to the run's measures ([`Model3d::measure`]).
    pub fn measure(&mut self) {
        M::measure(self);
    }

    /// Applies a timed event of the scenario ([`World3d::apply`]).
    pub fn apply(&mut self, object: u16, action: &crate::scenario::Action) {
        self.world.apply(object, action);
    }

    /// Every insect's position, in id order.
    pub fn positions_by_id(&self) -> Vec<[f64; 3]> {
        self.by_id(|s| &s.pos)
    }

    /// Every insect's actual velocity, in id order.
    pub fn velocities_by_id(&self) -> Vec<[f64; 3]> {
        self.by_id(|s| &s.vel)
    }

    fn by_id(&self, of: impl Fn(&Sensed) -> &Vec<[f64; 3]>) -> Vec<[f64; 3]> {
        let s = &self.world.sensed;
        let mut out = vec![[0.0; 3]; s.id.len()];
        for (v, &id) in of(s).iter().zip(&s.id) {
            out[id as usize] = *v;
        }
        out
    }

    /// Every insect, in id order, as recorded samples ([`Step3d::marks`] gives `label` and
    /// `motion`).
    pub fn samples(&self) -> Frame {
        let mut agents = vec![AgentSample::default(); self.agents()];
        for (k, g) in self.groups.iter().enumerate() {
            by_scalar!(g, g => g.samples(k as u16, &mut agents));
        }
        Frame {
            step: self.step,
            agents,
        }
    }
}
