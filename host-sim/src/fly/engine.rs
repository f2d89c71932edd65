//! The ren2016 simulation as an [`Engine`]: one phase (a step), and in the summary what ORCA
//! and the world did (infeasible programs, truncated frames, corrections) and the
//! polarisation.

use swarm_core::Checked;
use swarm_core::fly::{FlyDevice, FlyParams, FlyStep, FlyStepReply, FlyStepRequest};
use swarm_core::model::{Model, Phases};
use swarm_core::wire::Endpoint;

use super::build::fly_frame_samples;
use super::sense::fly_frame;
use super::sim::{FlyGroup, FlySim};
use crate::by_scalar;
use crate::engine::{Device, Engine, Exchange, ModelGroup, exchanges_by_slot, group_of, soft_name};
use crate::error::{Result, SimError};
use crate::output::{Frame, Summary};
use crate::scalar::SimScalar;
use crate::scenario::Action;

/// The ren2016 tick's phases, by name.
const PHASES: &[&str] = <<FlyParams<f32> as Model>::Phases as Phases<FlyParams<f32>>>::NAMES;

impl<S: SimScalar> FlyGroup<S> {
    /// The exchange of the insect in world slot `slot` (of this group) this step.
    fn exchange(&self, sim: &FlySim, slot: usize) -> Result<Exchange> {
        let k = slot - self.first;
        let request = FlyStepRequest {
            state: self.states[k],
            frame: fly_frame(&sim.world, slot, &self.params, self.stimuli).0,
            ctx: self.ctx(sim.seed, sim.step, k),
        };
        let reply = FlyStepReply {
            decision: self.decisions[k],
            state: self.decided()[k],
        };
        Exchange::of::<FlyParams<S>, FlyStep>(self.ids[k], &request, &reply)
    }
}

impl Engine for FlySim {
    fn model(&self) -> &'static str {
        <FlyParams<f32> as Model>::NAME
    }
    fn agents(&self) -> usize {
        FlySim::agents(self)
    }
    fn next_step(&self) -> u32 {
        self.step
    }
    fn apply(&mut self, object: u16, action: &Action) {
        FlySim::apply(self, object, action);
    }
    fn phases(&self) -> &'static [&'static str] {
        PHASES
    }
    fn decide(&mut self, _phase: usize) -> Result<()> {
        self.decide_all()
    }
    fn publish(&mut self, _phase: usize) -> Result<()> {
        FlySim::publish(self);
        Ok(())
    }
    fn exchanges(&self, _phase: usize, agents: &[u32]) -> Result<Vec<Exchange>> {
        exchanges_by_slot(&self.world.sensed.id, agents, |slot| {
            let (g, _) = group_of(&self.groups, slot)?;
            Some(by_scalar!(g, g => g.exchange(self, slot)))
        })
    }
    fn device(&self) -> Result<Device> {
        Device::of_groups(&self.groups)
    }
    fn frame(&self) -> Frame {
        fly_frame_samples(self)
    }
    fn collision_distance(&self) -> f32 {
        self.collision_distance
    }
    fn after_tick(&mut self, _summary: &mut Summary) {
        self.measure();
    }
    fn closing(&self, summary: &mut Summary) -> String {
        let t = self.total;
        let decisions = (self.agents() as u64 * u64::from(self.step)).max(1) as f64;
        let share = |n: u64| 100.0 * n as f64 / decisions;
        let (sum, steps) = self.polarisation;
        let polarisation = sum / steps.max(1) as f64;
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
             the {} nearest of the insects within r_att, polarisation {polarisation:.2} on \
             average; the world put insects back out of obstacles {} times and inside the \
             container {} times",
            share(t.infeasible),
            share(t.truncated),
            super::sense::N,
            t.obstacle,
            t.bounds
        )
    }
}

impl<S: SimScalar> ModelGroup for FlyGroup<S> {
    type Params = FlyParams<S>;
    fn params(&self) -> &Checked<FlyParams<S>> {
        &self.params
    }
    /// The fly node's endpoint (its buffer sizes).
    fn soft(params: &Checked<FlyParams<S>>) -> Result<Box<dyn Endpoint + Send>> {
        let p: &FlyParams<S> = params;
        let device = FlyDevice::<S>::new(*p, &soft_name::<FlyParams<S>>());
        Ok(Box::new(device.map_err(SimError::Device)?))
    }
}
