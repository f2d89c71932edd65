//! The bee simulation as an [`Engine`]: one phase (a step), the world's corrections in the
//! summary.

use swarm_core::Checked;
use swarm_core::bee::{BeeDevice, BeeParams, BeeStepReply, BeeStepRequest, Step};
use swarm_core::model::{Model, Phases};
use swarm_core::wire::Endpoint;

use super::build::bee_frame_samples;
use super::sense::bee_frame;
use super::sim::{BeeGroup, BeeSim, bee_frame_time};
use crate::by_scalar;
use crate::engine::{
    Device, Engine, Exchange, ModelGroup, StateNames, exchanges_by_slot, group_of, soft_name,
};
use crate::error::{Result, SimError};
use crate::output::{Frame, Summary};
use crate::scalar::SimScalar;
use crate::scenario::Action;

/// The bee tick's phases, by name.
const PHASES: &[&str] = <<BeeParams<f32> as Model>::Phases as Phases<BeeParams<f32>>>::NAMES;

impl<S: SimScalar> BeeGroup<S> {
    /// The exchange of the bee in world slot `slot` (of this group) this step.
    fn exchange(&self, sim: &BeeSim, slot: usize) -> Result<Exchange> {
        let k = slot - self.first;
        let id = self.ids[k];
        let w = &sim.world;
        let goal = self.goal.and_then(|g| w.target_center(g));
        // The bee's own clock, as the engine gives it.
        let t = S::from_f64(bee_frame_time(
            sim.seed,
            id,
            sim.step,
            self.params.dt.to_f64(),
        ));
        let request = BeeStepRequest {
            state: self.states[k],
            frame: bee_frame::<S>(w, slot, goal, t),
        };
        let reply = BeeStepReply {
            decision: self.decisions[k],
            state: self.decided()[k],
        };
        Exchange::of::<BeeParams<S>, Step>(id, &request, &reply)
    }
}

impl Engine for BeeSim {
    fn model(&self) -> &'static str {
        <BeeParams<f32> as Model>::NAME
    }
    fn agents(&self) -> usize {
        BeeSim::agents(self)
    }
    fn next_step(&self) -> u32 {
        self.step
    }
    fn apply(&mut self, object: u16, action: &Action) {
        BeeSim::apply(self, object, action);
    }
    fn phases(&self) -> &'static [&'static str] {
        PHASES
    }
    fn decide(&mut self, _phase: usize) -> Result<()> {
        self.decide_all()
    }
    fn publish(&mut self, _phase: usize) -> Result<()> {
        BeeSim::publish(self);
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
        bee_frame_samples(self)
    }
    /// No labels; the motion is whether the bee is rolling to avoid (§IV-B).
    fn state_names(&self) -> StateNames {
        StateNames {
            labels: &[],
            motions: &["cruising", "avoiding"],
        }
    }
    fn collision_distance(&self) -> f32 {
        self.collision_distance
    }
    fn closing(&self, summary: &mut Summary) -> String {
        let c = self.contacts;
        summary
            .extra
            .insert("world_contacts_obstacle".into(), c.obstacle.into());
        summary
            .extra
            .insert("world_contacts_bounds".into(), c.bounds.into());
        format!(
            "the world kept bees out of obstacles {} times and inside the bounds {} times",
            c.obstacle, c.bounds
        )
    }
}

impl<S: SimScalar> ModelGroup for BeeGroup<S> {
    type Params = BeeParams<S>;
    fn params(&self) -> &Checked<BeeParams<S>> {
        &self.params
    }
    /// The firmware's endpoint (its buffer sizes).
    fn soft(params: &Checked<BeeParams<S>>) -> Result<Box<dyn Endpoint + Send>> {
        let p: &BeeParams<S> = params;
        let device = BeeDevice::<S>::new(*p, &soft_name::<BeeParams<S>>());
        Ok(Box::new(device.map_err(SimError::Device)?))
    }
}
