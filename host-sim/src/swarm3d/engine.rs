//! A 3D flying swarm as an [`Engine`]: one phase (a step); the model's measures after each
//! tick and its figures in the summary ([`Model3d::measure`], [`Model3d::closing`]).

use swarm_core::Checked;
use swarm_core::model::{Model, Phases};
use swarm_core::wire::Endpoint;

use super::swarm::{Group3d, Model3d, Step3d, Swarm3d};
use crate::by_scalar;
use crate::engine::{
    Device, Engine, Exchange, ModelGroup, StateNames, exchanges_by_slot, group_of,
};
use crate::error::Result;
use crate::output::{Frame, Summary};
use crate::scalar::SimScalar;
use crate::scenario::Action;

impl<M: Model3d> Engine for Swarm3d<M> {
    fn model(&self) -> &'static str {
        <M::Params<f32> as Model>::NAME
    }
    fn agents(&self) -> usize {
        Swarm3d::agents(self)
    }
    fn next_step(&self) -> u32 {
        self.step
    }
    fn apply(&mut self, object: u16, action: &Action) {
        Swarm3d::apply(self, object, action);
    }
    fn phases(&self) -> &'static [&'static str] {
        <<M::Params<f32> as Model>::Phases as Phases<M::Params<f32>>>::NAMES
    }
    fn decide(&mut self, _phase: usize) -> Result<()> {
        self.decide_all()
    }
    fn publish(&mut self, _phase: usize) -> Result<()> {
        Swarm3d::publish(self);
        Ok(())
    }
    fn exchanges(&self, _phase: usize, agents: &[u32]) -> Result<Vec<Exchange>> {
        exchanges_by_slot(&self.world.sensed.id, agents, |slot| {
            let (g, _) = group_of(&self.groups, slot)?;
            Some(by_scalar!(g, g => g.exchange(self, slot)))
        })
    }
    fn device(&self) -> Result<Device> {
        M::device_ready(self)?;
        Device::of_groups(&self.groups)
    }
    fn frame(&self) -> Frame {
        self.samples()
    }
    fn state_names(&self) -> StateNames {
        <M::Params<f32> as Step3d<f32>>::STATE_NAMES
    }
    fn collision_distance(&self) -> f32 {
        self.collision_distance
    }
    fn after_tick(&mut self, _summary: &mut Summary) {
        self.measure();
    }
    fn closing(&self, summary: &mut Summary) -> String {
        M::closing(self, summary)
    }
}

impl<M: Model3d, S: SimScalar> ModelGroup for Group3d<M, S> {
    type Params = M::Params<S>;
    fn params(&self) -> &Checked<M::Params<S>> {
        &self.params
    }
    /// The model's firmware endpoint ([`Step3d::soft`]).
    fn soft(params: &Checked<M::Params<S>>) -> Result<Box<dyn Endpoint + Send>> {
        M::Params::<S>::soft(params)
    }
}
