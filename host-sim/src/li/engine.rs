//! The li2015 simulation as an [`Engine`]: one phase (a step), and in the summary the
//! metrics of the paper (the accumulated density's total variation to the target, the
//! distance to the swarm's centroid, the polarisation of Eq. 8) and what the waypoint level
//! and ORCA did.

use swarm_core::Checked;
use swarm_core::li::{LiDevice, LiParams, LiStep, LiStepReply, LiStepRequest};
use swarm_core::model::{Model, Phases};
use swarm_core::wire::Endpoint;

use super::build::li_frame_samples;
use super::sim::{LiGroup, LiSim, li_frame};
use crate::by_scalar;
use crate::engine::{Device, Engine, Exchange, ModelGroup, exchanges_by_slot, group_of, soft_name};
use crate::error::{Result, SimError};
use crate::output::{Frame, Summary};
use crate::scalar::SimScalar;
use crate::scenario::Action;

/// The li2015 tick's phases, by name.
const PHASES: &[&str] = <<LiParams<f32> as Model>::Phases as Phases<LiParams<f32>>>::NAMES;

impl<S: SimScalar> LiGroup<S> {
    /// The exchange of the insect in world slot `slot` (of this group) this step.
    fn exchange(&self, sim: &LiSim, slot: usize) -> Result<Exchange> {
        let k = slot - self.first;
        let request = LiStepRequest {
            state: self.states[k],
            frame: li_frame(&sim.world, slot, &self.params).0,
            ctx: self.ctx(sim.seed, sim.step, k),
        };
        let reply = LiStepReply {
            decision: self.decisions[k],
            state: self.decided()[k],
        };
        Exchange::of::<LiParams<S>, LiStep>(self.ids[k], &request, &reply)
    }
}

impl Engine for LiSim {
    fn model(&self) -> &'static str {
        <LiParams<f32> as Model>::NAME
    }
    fn agents(&self) -> usize {
        LiSim::agents(self)
    }
    fn next_step(&self) -> u32 {
        self.step
    }
    fn apply(&mut self, object: u16, action: &Action) {
        LiSim::apply(self, object, action);
    }
    fn phases(&self) -> &'static [&'static str] {
        PHASES
    }
    fn decide(&mut self, _phase: usize) -> Result<()> {
        self.decide_all()
    }
    fn publish(&mut self, _phase: usize) -> Result<()> {
        LiSim::publish(self);
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
        li_frame_samples(self)
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
        let per = |n: f64| n / self.measured.max(1) as f64;
        let (polarisation, centroid) = (per(self.polarisation), per(self.centroid_distance));
        let tv = self.density_tv();
        let proposals = t.proposals as f64 / t.arrivals.max(1) as f64;
        for (key, value) in [
            ("polarisation_mean", polarisation),
            ("centroid_distance_mean", centroid),
            ("proposals_per_arrival", proposals),
            (
                "arrivals_held_percent",
                100.0 * t.held as f64 / t.arrivals.max(1) as f64,
            ),
            ("orca_infeasible_percent", share(t.infeasible)),
            ("frames_truncated_percent", share(t.truncated)),
        ] {
            summary.extra.insert(key.into(), value.into());
        }
        if let Some(tv) = tv {
            summary.extra.insert("density_tv".into(), tv.into());
        }
        summary
            .extra
            .insert("world_corrections".into(), t.corrected.into());
        format!(
            "accumulated density {} from the target (total variation), {centroid:.3} from \
             the centroid and polarisation {polarisation:.2} on average; {proposals:.2} \
             proposals per arrival ({:.2} % held), ORCA infeasible for {:.3} % of the \
             decisions, {} world corrections",
            tv.map_or("not measured".into(), |tv| format!("{tv:.3}")),
            100.0 * t.held as f64 / t.arrivals.max(1) as f64,
            share(t.infeasible),
            t.corrected
        )
    }
}

impl<S: SimScalar> ModelGroup for LiGroup<S> {
    type Params = LiParams<S>;
    fn params(&self) -> &Checked<LiParams<S>> {
        &self.params
    }
    /// The li node's endpoint (its buffer sizes).
    fn soft(params: &Checked<LiParams<S>>) -> Result<Box<dyn Endpoint + Send>> {
        let p: &LiParams<S> = params;
        let device = LiDevice::<S>::new(p.clone(), &soft_name::<LiParams<S>>());
        Ok(Box::new(device.map_err(SimError::Device)?))
    }
}
