//! The ren2016 engine: a [`Swarm3d`] of insects each going through
//! `swarm_core::fly::step_checked` every step (Algorithm 1: forces, ORCA, move) on the frame
//! [`fly_frame`] builds, with the group's stimuli as its inputs; the world keeps the new
//! states physical (the backstop: ORCA's obstacle planes should leave it nothing to do) and
//! counts every correction. The summary adds the polarisation.

use swarm_core::fly::{
    self, FlyDecision, FlyDevice, FlyParams, FlyState, FlyStep, FlyStepReply, FlyStepRequest,
};
use swarm_core::wire::Endpoint;
use swarm_core::{Checked, StepCtx, Vec3};

use super::sense::{FlySimFrame, N, Stimuli, fly_frame};
use crate::engine::{Exchange, StateNames, soft_name};
use crate::error::{Result, SimError};
use crate::output::Summary;
use crate::scalar::SimScalar;
use crate::swarm3d::{AnyGroup3d, Group3d, Kinematic, Model3d, Step3d, Swarm3d, reach};

/// The ren2016 model over both scalar types (the [`Model3d`] of [`FlySim`]).
#[derive(Clone, Copy, Debug)]
pub enum Fly {}

/// A ren2016 swarm (or several) in its world.
pub type FlySim = Swarm3d<Fly>;
/// A group of ren2016 insects sharing parameters, stimuli and a scalar type.
pub type FlyGroup<S> = Group3d<Fly, S>;
/// A group of either scalar type.
pub type AnyFlyGroup = AnyGroup3d<Fly>;

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

/// The polarisation accumulated over a run.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Polarisation {
    /// Σ of the polarisation after each measured step.
    pub sum: f64,
    /// The steps measured.
    pub steps: u64,
}

impl Polarisation {
    /// The mean (0 before any step).
    pub fn mean(&self) -> f64 {
        self.sum / self.steps.max(1) as f64
    }
}

impl<S: SimScalar> Kinematic<S> for FlyState<S> {
    fn kinematics(&self) -> (Vec3<S>, Vec3<S>) {
        (self.pos, self.vel)
    }
    fn kinematics_mut(&mut self) -> (&mut Vec3<S>, &mut Vec3<S>) {
        (&mut self.pos, &mut self.vel)
    }
}

impl<S: SimScalar> Step3d<S> for FlyParams<S> {
    type Decision = FlyDecision<S>;
    type Frame = FlySimFrame<S>;
    type Inputs = Stimuli;
    type Counts = Counts;
    const STEP: &'static str = "fly step";

    fn frame(
        &self,
        w: &crate::swarm3d::World3d,
        slot: usize,
        stimuli: Stimuli,
    ) -> (Self::Frame, bool) {
        fly_frame(w, slot, self, stimuli)
    }
    fn step(
        params: &Checked<Self>,
        state: &FlyState<S>,
        frame: &Self::Frame,
        ctx: StepCtx,
    ) -> swarm_core::Result<(FlyState<S>, FlyDecision<S>)> {
        fly::step_checked(state, frame, params, ctx)
    }
    fn exchange(
        agent: u32,
        (state, frame, ctx): (FlyState<S>, Self::Frame, StepCtx),
        (decision, next): (FlyDecision<S>, FlyState<S>),
    ) -> Result<Exchange> {
        let request = FlyStepRequest { state, frame, ctx };
        let reply = FlyStepReply {
            decision,
            state: next,
        };
        Exchange::of::<FlyParams<S>, FlyStep>(agent, &request, &reply)
    }
    fn count(d: &FlyDecision<S>, truncated: bool, fix: u8) -> Counts {
        Counts {
            infeasible: u64::from(d.infeasible),
            truncated: u64::from(truncated),
            obstacle: u64::from(fix & 1),
            bounds: u64::from(fix >> 1 & 1),
        }
    }
    const STATE_NAMES: StateNames = StateNames {
        labels: &["calm", "escaping"],
        motions: &["feasible", "infeasible"],
    };
    /// `label` 1 while it escapes a predator, `motion` 1 when its ORCA program was infeasible.
    fn marks(s: &FlyState<S>, d: &FlyDecision<S>) -> (u8, u8) {
        (u8::from(s.escaping), u8::from(d.infeasible))
    }
    fn at(pos: Vec3<S>) -> FlyState<S> {
        FlyState::new(pos, Vec3::zero())
    }
    fn radius(&self) -> f32 {
        self.radius.to_f32()
    }
    fn orca_radius(&self) -> f32 {
        self.orca_radius().to_f32()
    }
    fn range(&self) -> f32 {
        self.r_att.to_f32()
    }
    fn reach(&self) -> f32 {
        reach(self.orca_radius(), self.tau, self.max_speed).to_f32()
    }
    /// The fly node's endpoint (its buffer sizes).
    fn soft(params: &Checked<Self>) -> Result<Box<dyn Endpoint + Send>> {
        let p: &FlyParams<S> = params;
        let device = FlyDevice::<S>::new(*p, &soft_name::<FlyParams<S>>());
        Ok(Box::new(device.map_err(SimError::Device)?))
    }
}

impl Model3d for Fly {
    type Params<S: SimScalar> = FlyParams<S>;
    type Inputs = Stimuli;
    type Counts = Counts;
    type Measures = Polarisation;

    fn cast<S: SimScalar>(p: &FlyParams<f32>) -> FlyParams<S> {
        p.cast()
    }
    /// Adds the polarisation of the current velocities to the running mean.
    fn measure(sim: &mut FlySim) {
        let phi = crate::eval::frame_polarisation(&sim.velocities_by_id());
        sim.measures.sum += phi;
        sim.measures.steps += 1;
    }
    /// What ORCA and the world did (infeasible programs, truncated frames, corrections) and
    /// the polarisation.
    fn closing(sim: &FlySim, summary: &mut Summary) -> String {
        let t = sim.total;
        let decisions = (sim.agents() as u64 * u64::from(sim.step)).max(1) as f64;
        let share = |n: u64| 100.0 * n as f64 / decisions;
        let polarisation = sim.measures.mean();
        for (key, value) in [
            ("orca_infeasible_percent", share(t.infeasible)),
            ("frames_truncated_percent", share(t.truncated)),
            ("polarisation_mean", polarisation),
        ] {
            summary.extra.insert(key.into(), value.into());
        }
        summary
            .extra
            .insert("world_contacts_obstacle".into(), t.obstacle.into());
        summary
            .extra
            .insert("world_contacts_bounds".into(), t.bounds.into());
        format!(
            "ORCA was infeasible for {:.3} % of the decisions, {:.2} % of the frames held only \
             the {N} nearest of the insects within r_att, polarisation {polarisation:.2} on \
             average; the world put insects back out of obstacles {} times and inside the \
             container {} times",
            share(t.infeasible),
            share(t.truncated),
            t.obstacle,
            t.bounds
        )
    }
}
