//! The ant simulation as an [`Engine`]: two phases (plan, resolve), the deliveries in the
//! summary.

use swarm_core::ant::{
    AntDevice, AntParams, AntPlanReply, AntPlanRequest, AntResolveReply, AntResolveRequest,
    AntState, Plan, Resolve,
};
use swarm_core::model::{Model, Phases};
use swarm_core::wire::Endpoint;
use swarm_core::{Checked, StepCtx};

use super::sense::{plan_frame, resolve_frame};
use super::sim::{AntEvent, AntGroup, AntSim};
use super::world::{AntObjectDef, AntObjectKind};
use crate::by_scalar;
use crate::engine::{
    Device, Engine, Exchange, ModelGroup, StateNames, exchanges_by_slot, group_of, soft_name,
};
use crate::error::{Result, SimError};
use crate::output::{AgentSample, Frame, Summary};
use crate::scalar::SimScalar;
use crate::scenario::Action;

/// Ants closer than this (body lengths) count as a collision in the summary.
pub const ANT_COLLISION_DISTANCE: f32 = 0.5;

/// The ant tick's phases, by name.
const PHASES: &[&str] = <<AntParams<f32> as Model>::Phases as Phases<AntParams<f32>>>::NAMES;

impl<S: SimScalar> AntGroup<S> {
    /// The exchange of the ant in world slot `slot` (of this group) in phase `phase` (`None`
    /// for a phase the ant tick does not have).
    fn exchange(&self, sim: &AntSim, slot: usize, phase: usize) -> Option<Result<Exchange>> {
        let k = slot - self.first;
        let id = self.ids[k];
        let w = &sim.world;
        match phase {
            0 => {
                let request = AntPlanRequest {
                    state: self.states[k],
                    frame: plan_frame::<S>(w, slot),
                    ctx: StepCtx {
                        seed: sim.seed,
                        agent: id,
                        step: sim.step,
                    },
                };
                let reply = AntPlanReply {
                    plan: self.plans()[k],
                };
                Some(Exchange::of::<AntParams<S>, Plan>(id, &request, &reply))
            }
            1 => {
                let request = AntResolveRequest {
                    plan: self.plans()[k],
                    frame: resolve_frame::<S>(w, slot),
                };
                let reply = AntResolveReply {
                    state: self.resolved()[k],
                };
                Some(Exchange::of::<AntParams<S>, Resolve>(id, &request, &reply))
            }
            _ => None,
        }
    }
}

impl Engine for AntSim {
    fn model(&self) -> &'static str {
        <AntParams<f32> as Model>::NAME
    }
    fn agents(&self) -> usize {
        AntSim::agents(self)
    }
    fn next_step(&self) -> u32 {
        self.step
    }
    fn apply(&mut self, object: u16, action: &Action) {
        AntSim::apply(self, object, action);
    }
    fn phases(&self) -> &'static [&'static str] {
        PHASES
    }
    fn decide(&mut self, phase: usize) -> Result<()> {
        match phase {
            0 => self.plan_all(),
            _ => self.resolve_all(),
        }
    }
    fn publish(&mut self, phase: usize) -> Result<()> {
        match phase {
            0 => self.publish_plans(),
            _ => self.publish_states(),
        }
        Ok(())
    }
    fn exchanges(&self, phase: usize, agents: &[u32]) -> Result<Vec<Exchange>> {
        exchanges_by_slot(&self.world.sensed.id, agents, |slot| {
            let (g, _) = group_of(&self.groups, slot)?;
            by_scalar!(g, g => g.exchange(self, slot, phase))
        })
    }
    fn device(&self) -> Result<Device> {
        Device::of_groups(&self.groups)
    }
    fn frame(&self) -> Frame {
        fn push<S: SimScalar>(out: &mut Vec<AgentSample>, group: u16, g: &AntGroup<S>) {
            out.extend(
                g.states_by_id()
                    .into_iter()
                    .map(|(id, s): (u32, AntState<S>)| AgentSample {
                        id,
                        pos: [s.pos.x.to_f32(), s.pos.y.to_f32(), 0.0],
                        heading: [s.heading.x.to_f32(), s.heading.y.to_f32(), 0.0],
                        group,
                        label: s.label as u8,
                        motion: s.motion as u8,
                        roll: 0.0,
                        pitch: 0.0,
                    }),
            );
        }
        let mut agents = Vec::with_capacity(AntSim::agents(self));
        for (k, g) in self.groups.iter().enumerate() {
            by_scalar!(g, g => push(&mut agents, k as u16, g));
        }
        agents.sort_unstable_by_key(|a| a.id);
        Frame {
            step: self.step,
            agents,
        }
    }
    /// The labels of `swarm_core::ant::Label`, the motion states of
    /// `swarm_core::ant::MotionState`, in code order.
    fn state_names(&self) -> StateNames {
        StateNames {
            labels: &["nothing", "food", "nest"],
            motions: &["stop", "basic", "neighbors", "environment"],
        }
    }
    fn collision_distance(&self) -> f32 {
        ANT_COLLISION_DISTANCE
    }
    fn begin_summary(&self, summary: &mut Summary) {
        summary.deliveries_per_nest = self
            .world
            .objects
            .iter()
            .filter(|o| o.kind == AntObjectKind::Nest)
            .map(|o| (o.name.clone(), 0))
            .collect();
    }
    fn after_tick(&mut self, summary: &mut Summary) {
        for e in &self.events {
            if let AntEvent::Delivered { nest, .. } = *e {
                // Deliveries at a way point (an ant on a later leg of a route) count in the
                // total only.
                let home = |o: &&AntObjectDef| o.id == nest && o.kind == AntObjectKind::Nest;
                if let Some(o) = self.world.objects.iter().find(home) {
                    *summary
                        .deliveries_per_nest
                        .entry(o.name.clone())
                        .or_default() += 1;
                }
            }
        }
    }
    fn on_record(&self, summary: &mut Summary, step: u32) {
        if step > 0 {
            summary.deliveries_over_time.push((step, self.delivered));
        }
    }
    fn closing(&self, summary: &mut Summary) -> String {
        let moved = self.moved_out;
        summary
            .extra
            .insert("ants_moved_out_of_obstacles".into(), moved.into());
        format!(
            "{} deliveries, {moved} ants moved out of obstacles placed on them",
            self.delivered
        )
    }
}

impl<S: SimScalar> ModelGroup for AntGroup<S> {
    type Params = AntParams<S>;
    fn params(&self) -> &Checked<AntParams<S>> {
        &self.params
    }
    /// The firmware's endpoint (its buffer sizes).
    fn soft(params: &Checked<AntParams<S>>) -> Result<Box<dyn Endpoint + Send>> {
        let p: &AntParams<S> = params;
        let device = AntDevice::<S>::new(*p, &soft_name::<AntParams<S>>());
        Ok(Box::new(device.map_err(SimError::Device)?))
    }
}
