//! The wang2014 simulation as an [`Engine`]: two phases (advect, separate), the fields' solves
//! in the run log, and the paper's measures in the summary.

use swarm_core::Checked;
use swarm_core::StepCtx;
use swarm_core::model::{Model, Phases};
use swarm_core::wang::{
    Advect, AdvectReply, AdvectRequest, Separate, SeparateReply, SeparateRequest, WangParams,
};

use super::build::wang_frame_samples;
use super::sim::{WangGroup, WangSim};
use crate::by_scalar;
use crate::engine::{
    Device, Engine, Exchange, ModelGroup, StateNames, exchanges_by_slot, group_of,
};
use crate::error::Result;
use crate::output::{Frame, Summary};
use crate::scalar::{AgentGroup, SimScalar};
use crate::scenario::Action;

/// The wang2014 tick's phases, by name.
const PHASES: &[&str] = <<WangParams<f32> as Model>::Phases as Phases<WangParams<f32>>>::NAMES;

impl<S: SimScalar> WangGroup<S> {
    /// The exchange of the insect in world slot `slot` (of this group) in phase `phase`.
    fn exchange(&self, sim: &WangSim, phase: usize, slot: usize) -> Result<Exchange> {
        let k = slot - self.first;
        let id = self.ids[k];
        let ctx = StepCtx {
            seed: sim.seed,
            agent: id,
            step: sim.step,
        };
        if phase == 0 {
            let request = AdvectRequest {
                state: self.states[k],
                frame: self.advect_frame(&sim.world, &self.states[k]),
                ctx,
            };
            let reply = AdvectReply {
                moved: self.moved[k],
            };
            Exchange::of::<WangParams<S>, Advect>(id, &request, &reply)
        } else {
            let request = SeparateRequest {
                moved: self.placed[k],
                frame: self.separate_frame(&sim.world, slot),
                ctx,
            };
            let reply = SeparateReply {
                state: self.next[k],
                pushes: self.pushes[k],
            };
            Exchange::of::<WangParams<S>, Separate>(id, &request, &reply)
        }
    }
}

impl Engine for WangSim {
    fn model(&self) -> &'static str {
        <WangParams<f32> as Model>::NAME
    }
    fn agents(&self) -> usize {
        WangSim::agents(self)
    }
    fn next_step(&self) -> u32 {
        self.step
    }
    fn apply(&mut self, object: u16, action: &Action) {
        WangSim::apply(self, object, action);
    }
    fn phases(&self) -> &'static [&'static str] {
        PHASES
    }
    fn decide(&mut self, phase: usize) -> Result<()> {
        WangSim::decide(self, phase)
    }
    fn publish(&mut self, phase: usize) -> Result<()> {
        WangSim::publish(self, phase);
        Ok(())
    }
    fn notes(&mut self) -> Vec<String> {
        let grid = self.world.grid.clone();
        self.world
            .solves
            .drain(..)
            .map(|(goal, s)| {
                format!(
                    "cost field of `{goal}` solved (eq. 7, fast marching): {} cells \
                     ({}×{}×{} of {} m), {} reachable, {} in the goal, {:.3} s",
                    s.cells,
                    grid.dims[0],
                    grid.dims[1],
                    grid.dims[2],
                    grid.cell,
                    s.reachable,
                    s.goal_cells,
                    s.seconds
                )
            })
            .collect()
    }
    fn exchanges(&self, phase: usize, agents: &[u32]) -> Result<Vec<Exchange>> {
        exchanges_by_slot(&self.world.id, agents, |slot| {
            let (g, _) = group_of(&self.groups, slot)?;
            Some(by_scalar!(g, g => g.exchange(self, phase, slot)))
        })
    }
    fn device(&self) -> Result<Device> {
        Device::of_groups(&self.groups)
    }
    fn frame(&self) -> Frame {
        wang_frame_samples(self)
    }
    /// No labels; the motion is how many neighbours pushed the insect apart at the step
    /// (minimum distance enforcement, §7).
    fn state_names(&self) -> StateNames {
        StateNames {
            labels: &[],
            motions: &["unpushed", "pushed by 1", "pushed by 2", "pushed by 3"],
        }
    }
    fn collision_distance(&self) -> f32 {
        // Insects are points (§8); d_min is the only size the model knows.
        self.world.d_min
    }
    fn after_tick(&mut self, _summary: &mut Summary) {
        self.measure();
    }
    fn closing(&self, summary: &mut Summary) -> String {
        let m = &self.metrics;
        summary.extra.extend(m.to_json());
        if self.groups.len() > 1 {
            let by_group: serde_json::Map<String, serde_json::Value> = self
                .groups
                .iter()
                .zip(&self.group_metrics)
                .map(|(g, m)| (g.name().to_string(), m.to_json().into()))
                .collect();
            summary.extra.insert("groups".into(), by_group.into());
        }
        let steps = m.steps.max(1) as f64;
        format!(
            "MDE displaced {:.3} % of the insects per step (Table 1: 0.01-0.68 %), polarisation \
             {:.2} on average, the world put insects back out of obstacles {} times and inside \
             the bounds {} times",
            m.mde_percent_sum / steps,
            m.polarisation_sum / steps,
            m.counts.obstacle,
            m.counts.bounds
        )
    }
}

impl<S: SimScalar> ModelGroup for WangGroup<S> {
    type Params = WangParams<S>;
    fn params(&self) -> &Checked<WangParams<S>> {
        &self.params
    }
}
