//! The walker's simulation (what would be its folder in `swarm-sim`): every walker steps
//! through [`Walk`], the engine keeps the states and shows them to the generic code.

use swarm_core::model::{Model, Phase, Phases};
use swarm_core::{Checked, StepCtx, Vec2};
use swarm_sim::engine::{Device, Engine, Exchange, StateNames};
use swarm_sim::output::{AgentSample, Frame, Summary};
use swarm_sim::scalar::SimScalar;
use swarm_sim::scenario::Action;
use swarm_sim::{Result, SimError};

use super::core::{Walk, WalkParams, WalkReply, WalkRequest, WalkState};

/// `n` walkers of one parameter set in scalar `S`.
pub struct WalkSim<S> {
    params: Checked<WalkParams<S>>,
    states: Vec<WalkState<S>>,
    next: Vec<WalkState<S>>,
    seed: u32,
    step: u32,
}

impl<S: SimScalar> WalkSim<S> {
    /// `n` walkers spread on a line through the middle, heading +x.
    pub fn new(params: Checked<WalkParams<S>>, n: usize, seed: u32) -> Self {
        let w = params.half_width.to_f32();
        let states = (0..n)
            .map(|i| WalkState {
                pos: Vec2::from_f32(-w + 2.0 * w * (i as f32 + 0.5) / n as f32, 0.0),
                heading: Vec2::from_f32(1.0, 0.0),
                bounces: 0,
            })
            .collect();
        Self::with_states(params, states, seed)
    }

    /// Walkers starting in `states` (agent id = index).
    pub fn with_states(
        params: Checked<WalkParams<S>>,
        states: Vec<WalkState<S>>,
        seed: u32,
    ) -> Self {
        WalkSim {
            params,
            next: states.clone(),
            states,
            seed,
            step: 0,
        }
    }

    fn request(&self, id: usize) -> WalkRequest<S> {
        WalkRequest {
            state: self.states[id],
            ctx: StepCtx {
                seed: self.seed,
                agent: id as u32,
                step: self.step,
            },
        }
    }

    /// The states, in id order.
    pub fn states(&self) -> &[WalkState<S>] {
        &self.states
    }
}

impl<S: SimScalar> Engine for WalkSim<S> {
    fn model(&self) -> &'static str {
        <WalkParams<S> as Model>::NAME
    }
    fn agents(&self) -> usize {
        self.states.len()
    }
    fn next_step(&self) -> u32 {
        self.step
    }
    fn apply(&mut self, _object: u16, _action: &Action) {}
    fn phases(&self) -> &'static [&'static str] {
        <(Walk,) as Phases<WalkParams<S>>>::NAMES
    }
    fn decide(&mut self, _phase: usize) -> Result<()> {
        for id in 0..self.states.len() {
            let reply = Walk::run(&self.params, &self.request(id))
                .map_err(|e| SimError::controller("walk", self.step, id as u32, e))?;
            self.next[id] = reply.state;
        }
        Ok(())
    }
    fn publish(&mut self, _phase: usize) -> Result<()> {
        std::mem::swap(&mut self.states, &mut self.next);
        self.step += 1;
        Ok(())
    }
    fn exchanges(&self, _phase: usize, agents: &[u32]) -> Result<Vec<Exchange>> {
        agents
            .iter()
            .map(|&id| {
                let k = id as usize;
                if k >= self.states.len() {
                    return Err(SimError::NoAgent {
                        id,
                        agents: self.states.len(),
                    });
                }
                let reply = WalkReply {
                    state: self.next[k],
                };
                Exchange::of::<WalkParams<S>, Walk>(id, &self.request(k), &reply)
            })
            .collect()
    }
    fn device(&self) -> Result<Device> {
        Device::of(&self.params)
    }
    fn frame(&self) -> Frame {
        Frame {
            step: self.step,
            agents: self
                .states
                .iter()
                .enumerate()
                .map(|(id, s)| AgentSample {
                    id: id as u32,
                    pos: [s.pos.x.to_f32(), s.pos.y.to_f32(), 0.0],
                    heading: [s.heading.x.to_f32(), s.heading.y.to_f32(), 0.0],
                    ..AgentSample::default()
                })
                .collect(),
        }
    }
    /// A walker's samples carry no states.
    fn state_names(&self) -> StateNames {
        StateNames::default()
    }
    fn collision_distance(&self) -> f32 {
        0.1
    }
    fn closing(&self, summary: &mut Summary) -> String {
        let bounces: u64 = self.states.iter().map(|s| u64::from(s.bounces)).sum();
        summary
            .extra
            .insert("walker_bounces".into(), bounces.into());
        format!("{bounces} bounces off the walls")
    }
}
