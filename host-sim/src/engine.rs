//! The seam between a model's simulation and everything generic: the run loop, the benchmark,
//! the outputs and the HIL mirror drive any model through [`Engine`], one phase at a time, and
//! learn what a device must answer through [`Exchange`]s and [`Device`].
//!
//! A tick is the model's phases in order ([`Model::Phases`](swarm_core::model::Model)): for
//! each, [`Engine::decide`] runs the phase's controller for every agent from what the previous
//! phase published (the part a backend computes: the CPU today, the GPU next), then
//! [`Engine::publish`] makes the decisions visible (predictions, states, world corrections,
//! events). Between the two, [`Engine::exchanges`] gives, for chosen agents, the request the
//! phase ran on and the reply the engine computed: what a mirror sends to a device and compares
//! its answer with.

use serde::Serialize;
use serde::de::DeserializeOwned;
use swarm_core::Checked;
use swarm_core::wire::{Controller, DeviceEndpoint, Endpoint, Identity, Message, params_hash};

use crate::error::{Result, SimError};
use crate::output::{Frame, Summary};
use crate::scalar::{AgentGroup, ByScalar};
use crate::scenario::Action;

/// A model's whole simulation, as the generic code drives it.
pub trait Engine: Send {
    /// The model's name (`ant`, `bee`).
    fn model(&self) -> &'static str;
    /// Number of agents.
    fn agents(&self) -> usize;
    /// The next tick to run.
    fn next_step(&self) -> u32;
    /// Applies a scenario event to object `object` (its index in the scenario).
    fn apply(&mut self, object: u16, action: &Action);
    /// The names of the phases of a tick, in order.
    fn phases(&self) -> &'static [&'static str];
    /// Who computes [`Engine::decide`]: `cpu` (rayon, deterministic for any thread count)
    /// for every engine today; a GPU engine of a model reuses the model's world (sensing for
    /// the mirror, events, frames, summary) and decides on the device.
    fn backend(&self) -> &'static str {
        "cpu"
    }
    /// Runs phase `phase` of the current tick for every agent, from what the previous phase
    /// published; publishes nothing.
    ///
    /// # Errors
    ///
    /// [`SimError::Controller`] if a controller refused its frame.
    fn decide(&mut self, phase: usize) -> Result<()>;
    /// Publishes the decisions of phase `phase`; the last phase ends the tick.
    ///
    /// # Errors
    ///
    /// A model's own failure to apply its decisions (none today).
    fn publish(&mut self, phase: usize) -> Result<()>;
    /// One tick: every phase decided and published.
    ///
    /// # Errors
    ///
    /// As [`Engine::decide`].
    fn tick(&mut self) -> Result<()> {
        for phase in 0..self.phases().len() {
            self.decide(phase)?;
            self.publish(phase)?;
        }
        Ok(())
    }
    /// For each of `agents` (ids), the request phase `phase` ran on and the engine's reply
    /// (call between [`Engine::decide`] and [`Engine::publish`] of that phase).
    ///
    /// # Errors
    ///
    /// [`SimError::NoAgent`] for an id the simulation does not have.
    fn exchanges(&self, phase: usize, agents: &[u32]) -> Result<Vec<Exchange>>;
    /// The device that mirrors this simulation: what it must report, and a soft one.
    ///
    /// # Errors
    ///
    /// [`SimError::MixedScalars`], [`SimError::DifferentParams`]: the groups do not share one
    /// parameter set in one scalar type, so no one device runs them all.
    fn device(&self) -> Result<Device>;
    /// Every agent, in id order, as recorded.
    fn frame(&self) -> Frame;
    /// Agents closer than this count as a collision in the summary.
    fn collision_distance(&self) -> f32;
    /// Fills the model's fields of a new run's summary.
    fn begin_summary(&self, _summary: &mut Summary) {}
    /// Counts what the tick just ended did into `summary`.
    fn after_tick(&mut self, _summary: &mut Summary) {}
    /// Called at each recorded step.
    fn on_record(&self, _summary: &mut Summary, _step: u32) {}
    /// Completes the summary at the end of a run; returns the run log's closing words.
    fn closing(&self, summary: &mut Summary) -> String;
}

/// One encoded message: its kind and postcard payload, and how to show it.
#[derive(Clone, Debug)]
pub struct Payload {
    /// The message kind.
    pub kind: u8,
    /// The postcard payload.
    pub bytes: Vec<u8>,
    /// Whether a payload decodes as a message of this type.
    pub decodes: fn(&[u8]) -> bool,
    /// A payload of this type as JSON (`null` if it does not decode).
    pub json: fn(&[u8]) -> serde_json::Value,
}

impl Payload {
    /// `msg`, encoded.
    pub fn of<M: Message + Serialize + DeserializeOwned>(msg: &M) -> Payload {
        fn decodes<M: Message>(b: &[u8]) -> bool {
            swarm_core::wire::decode_payload::<M>(b).is_ok()
        }
        fn json<M: Message + Serialize>(b: &[u8]) -> serde_json::Value {
            swarm_core::wire::decode_payload::<M>(b)
                .ok()
                .and_then(|m| serde_json::to_value(m).ok())
                .unwrap_or(serde_json::Value::Null)
        }
        Payload {
            kind: M::KIND,
            // A postcard encoding into a Vec fails only for types postcard cannot describe,
            // which no message is.
            bytes: postcard::to_allocvec(msg).unwrap_or_default(),
            decodes: decodes::<M>,
            json: json::<M>,
        }
    }

    /// This payload as JSON.
    pub fn to_json(&self) -> serde_json::Value {
        (self.json)(&self.bytes)
    }
}

/// One agent's request of one phase and the reply the engine computed for it.
#[derive(Clone, Debug)]
pub struct Exchange {
    /// The agent's id.
    pub agent: u32,
    /// The phase's name.
    pub phase: &'static str,
    /// The request (state and sensor frame).
    pub request: Payload,
    /// The engine's reply (the decision).
    pub reply: Payload,
}

impl Exchange {
    /// Agent `agent`'s exchange in phase `phase`.
    pub fn new<Q, A>(agent: u32, phase: &'static str, request: &Q, reply: &A) -> Exchange
    where
        Q: Message + Serialize + DeserializeOwned,
        A: Message + Serialize + DeserializeOwned,
    {
        Exchange {
            agent,
            phase,
            request: Payload::of(request),
            reply: Payload::of(reply),
        }
    }
}

/// The largest frame a soft device receives and sends: larger than any model's message.
pub const SOFT_FRAME: usize = 4096;

/// The device a simulation's agents can be mirrored on.
pub struct Device {
    /// What the device must report (`max_frame`: the host's longest request).
    pub expected: Identity,
    /// The parameter hash the session is configured with.
    pub params_hash: u64,
    /// A soft device running the same parameters.
    pub soft: Box<dyn Endpoint + Send>,
}

impl Device {
    /// The device running `params`, with a soft device of [`SOFT_FRAME`] buffers.
    ///
    /// # Errors
    ///
    /// [`SimError::Device`] if the parameters cannot be encoded (never for a model's own).
    pub fn of<C: Controller + Send + 'static>(params: &Checked<C>) -> Result<Device> {
        Device::with(params, soft_endpoint(params, &soft_name::<C>())?)
    }

    /// The device running `params`, served on the host by `soft`.
    fn with<C: Controller>(params: &Checked<C>, soft: Box<dyn Endpoint + Send>) -> Result<Device> {
        let p: &C = params;
        Ok(Device {
            expected: Identity::of(p, C::MAX_REQUEST_FRAME, "host").map_err(SimError::Device)?,
            params_hash: params_hash(p).map_err(SimError::Device)?,
            soft,
        })
    }

    /// The one device of `groups`: they must all have the same scalar type and parameters.
    ///
    /// # Errors
    ///
    /// [`SimError::MixedScalars`], [`SimError::DifferentParams`], [`SimError::NoAgents`].
    pub fn of_groups<F: ModelGroup, X: ModelGroup>(groups: &[ByScalar<F, X>]) -> Result<Device> {
        let Some(first) = groups.first() else {
            return Err(SimError::NoAgents);
        };
        for g in &groups[1..] {
            let (a, b) = (first.name(), g.name());
            let same = match (first, g) {
                (ByScalar::F32(x), ByScalar::F32(y)) => **x.params() == **y.params(),
                (ByScalar::Fixed(x), ByScalar::Fixed(y)) => **x.params() == **y.params(),
                _ => {
                    return Err(SimError::MixedScalars {
                        first: a.to_string(),
                        other: b.to_string(),
                    });
                }
            };
            if !same {
                return Err(SimError::DifferentParams {
                    first: a.to_string(),
                    other: b.to_string(),
                });
            }
        }
        match first {
            ByScalar::F32(g) => Device::with(g.params(), F::soft(g.params())?),
            ByScalar::Fixed(g) => Device::with(g.params(), X::soft(g.params())?),
        }
    }
}

/// A group of agents that run one model's controller with one parameter set.
pub trait ModelGroup: AgentGroup {
    /// The model, in the group's scalar type.
    type Params: Controller + Send + 'static;
    /// The group's parameters.
    fn params(&self) -> &Checked<Self::Params>;
    /// The soft device running `params`: by default an endpoint of [`SOFT_FRAME`] buffers; a
    /// model with firmware gives its firmware's endpoint (the same buffer sizes, so the soft
    /// device drops and counts what the firmware would).
    ///
    /// # Errors
    ///
    /// [`SimError::Device`] if the endpoint refuses the parameters.
    fn soft(params: &Checked<Self::Params>) -> Result<Box<dyn Endpoint + Send>> {
        soft_endpoint(params, &soft_name::<Self::Params>())
    }
}

/// The name a soft device of model `C` reports: `soft-<model>`.
pub fn soft_name<C: Controller>() -> String {
    format!("soft-{}", C::NAME)
}

/// An endpoint of [`SOFT_FRAME`] buffers running `params`, reporting `name`.
fn soft_endpoint<C: Controller + Send + 'static>(
    params: &Checked<C>,
    name: &str,
) -> Result<Box<dyn Endpoint + Send>> {
    let p: &C = params;
    let e = DeviceEndpoint::<C, SOFT_FRAME, SOFT_FRAME>::new(p.clone(), name);
    Ok(Box::new(e.map_err(SimError::Device)?))
}

/// The exchanges of `agents` (ids), each made by `exchange` from the agent's world slot
/// (`None`: no group has that slot); `ids` is the world's id of every slot.
///
/// # Errors
///
/// [`SimError::NoAgent`] for an id no slot has.
pub fn exchanges_by_slot(
    ids: &[u32],
    agents: &[u32],
    exchange: impl Fn(usize) -> Option<Exchange>,
) -> Result<Vec<Exchange>> {
    let slots = slots_by_id(ids);
    agents
        .iter()
        .map(|&id| {
            slots
                .get(id as usize)
                .copied()
                .flatten()
                .and_then(&exchange)
                .ok_or(SimError::NoAgent {
                    id,
                    agents: ids.len(),
                })
        })
        .collect()
}

/// The group of `groups` that holds world slot `slot`, and the slot's index in it.
pub fn group_of<G: AgentGroup>(groups: &[G], slot: usize) -> Option<(&G, usize)> {
    groups
        .iter()
        .find(|g| (g.first()..g.first() + g.len()).contains(&slot))
        .map(|g| (g, slot - g.first()))
}

/// The slot of every agent id (slots move when an engine reorders them).
/// (`None` for an id no slot holds).
fn slots_by_id(ids: &[u32]) -> Vec<Option<usize>> {
    let mut out = vec![None; ids.len()];
    for (slot, &id) in ids.iter().enumerate() {
        if let Some(s) = out.get_mut(id as usize) {
            *s = Some(slot);
        }
    }
    out
}
