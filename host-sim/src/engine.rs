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

use swarm_core::Checked;
use swarm_core::model::{Model, Phase};
use swarm_core::wire::{Controller, DeviceEndpoint, Endpoint, Identity, Message, params_hash};

use crate::error::{Result, SimError};
use crate::output::{Frame, Summary};
use crate::scalar::{AgentGroup, ByScalar};
use crate::scenario::{Action, Event, Scenario};

/// What the codes of a recorded sample mean ([`AgentSample`](crate::output::AgentSample)'s
/// `label` and `motion`): the name of each code, by code. The summary counts the agents under
/// these names (every name, 0 if unused; a code past the end as `label<N>` / `motion<N>`); a
/// model whose samples carry no labels (or no motions) gives an empty list and none are counted.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StateNames {
    /// The names of the `label` codes.
    pub labels: &'static [&'static str],
    /// The names of the `motion` codes.
    pub motions: &'static [&'static str],
}

/// A model's whole simulation, as the generic code drives it.
pub trait Engine: Send {
    /// The model's name (`ant`, `bee`).
    fn model(&self) -> &'static str;
    /// Number of agents.
    fn agents(&self) -> usize;
    /// The next tick to run.
    fn next_step(&self) -> u32;
    /// Applies a scenario event to object `object` (its index in the scenario). The run loop
    /// and the mirror apply a scenario's events through [`apply_due_events`].
    fn apply(&mut self, object: u16, action: &Action);
    /// The names of the phases of a tick, in order.
    fn phases(&self) -> &'static [&'static str];
    /// Who computes [`Engine::decide`]: `cpu` (rayon, deterministic for any thread count)
    /// for every engine today; a GPU engine of a model reuses the model's world (sensing for
    /// the mirror, events, frames, summary) and decides on the device.
    fn backend(&self) -> &'static str {
        "cpu"
    }
    /// What the engine has to say in the run log since it was last asked (e.g. a global field
    /// it solved, with what the solve cost); the run loop asks after building the engine and
    /// after each step's events.
    fn notes(&mut self) -> Vec<String> {
        Vec::new()
    }
    /// The GPU adapter a GPU engine runs on (name, API, driver); `None` on the CPU.
    fn adapter(&self) -> Option<String> {
        None
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
    /// Brings the host's view of the simulation up to date now (a GPU engine waits for its
    /// states and counts): before the closing, and for a look between ticks. A CPU engine's
    /// view is always current.
    ///
    /// # Errors
    ///
    /// A backend's failure to read back, or a controller's refusal it noticed since.
    fn sync(&mut self) -> Result<()> {
        Ok(())
    }
    /// How many recorded steps may be on their way back ([`Engine::snapshot`]) before the run
    /// loop takes the oldest ([`Engine::take_snapshot`]): 0 for a CPU engine (its view is the
    /// step's), 1 for a GPU engine (two staging buffers in turn: the GPU goes on with the next
    /// ticks while the host writes a recorded frame).
    fn frames_in_flight(&self) -> usize {
        0
    }
    /// Starts reading back the simulation as it is now, a recorded step, without waiting.
    ///
    /// # Errors
    ///
    /// A backend's failure to start the read-back.
    fn snapshot(&mut self) -> Result<()> {
        Ok(())
    }
    /// Makes the oldest snapshot not yet taken the host's view (what [`Engine::frame`] and
    /// [`Engine::on_record`] see), waiting for it if needed. By default [`Engine::sync`]: an
    /// engine that takes no snapshots brings its view up to date at the recorded step.
    ///
    /// # Errors
    ///
    /// As [`Engine::sync`].
    fn take_snapshot(&mut self) -> Result<()> {
        self.sync()
    }
    /// One tick with each of its GPU passes timed (timestamp queries): the passes' names and
    /// milliseconds; `None` (and no tick) for a CPU engine or an adapter without timestamps.
    ///
    /// # Errors
    ///
    /// As [`Engine::tick`] and [`Engine::sync`].
    fn profile_tick(&mut self) -> Result<Option<Vec<(&'static str, f64)>>> {
        Ok(None)
    }
    /// The bytes a GPU engine holds on the device (states, grid, world); `None` on the CPU.
    fn device_bytes(&self) -> Option<u64> {
        None
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
    /// What the codes of [`Engine::frame`]'s samples mean.
    fn state_names(&self) -> StateNames;
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
    ///
    /// # Errors
    ///
    /// [`SimError::Encode`] if postcard cannot encode it (a message type postcard cannot
    /// describe: none of the models' own).
    pub fn of<M: Message>(msg: &M) -> Result<Payload> {
        fn decodes<M: Message>(b: &[u8]) -> bool {
            swarm_core::wire::decode_payload::<M>(b).is_ok()
        }
        fn json<M: Message>(b: &[u8]) -> serde_json::Value {
            swarm_core::wire::decode_payload::<M>(b)
                .ok()
                .and_then(|m| serde_json::to_value(m).ok())
                .unwrap_or(serde_json::Value::Null)
        }
        let bytes = postcard::to_allocvec(msg).map_err(|source| SimError::Encode {
            message: std::any::type_name::<M>(),
            kind: M::KIND,
            source,
        })?;
        Ok(Payload {
            kind: M::KIND,
            bytes,
            decodes: decodes::<M>,
            json: json::<M>,
        })
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
    /// Agent `agent`'s exchange in phase `Ph` of model `M`: the phase's request and its
    /// reply, so a request is never paired with another phase's reply, and the phase's name
    /// (`Exchange::of::<AntParams<S>, Plan>(id, &request, &reply)`).
    ///
    /// # Errors
    ///
    /// [`SimError::Encode`] if a message cannot be encoded (see [`Payload::of`]).
    pub fn of<M, Ph>(agent: u32, request: &Ph::Request, reply: &Ph::Reply) -> Result<Exchange>
    where
        M: Model,
        Ph: Phase<M>,
        Ph::Request: Message,
        Ph::Reply: Message,
    {
        Ok(Exchange {
            agent,
            phase: Ph::NAME,
            request: Payload::of(request)?,
            reply: Payload::of(reply)?,
        })
    }
}

/// Applies the events of `sc` due before the engine's next tick ([`Engine::next_step`]), in
/// the scenario's order, and returns them (to log): what `swarm run`'s loop
/// ([`run`](crate::run)) does before each tick, and what the mirror does,
/// so a mirrored scenario sees its objects added, removed and moved and its disturbances
/// started at the same steps as its run. An event naming an object the scenario does not
/// have is skipped (a validated scenario has none). The events must be in step order, as a
/// validated scenario's are.
pub fn apply_due_events<'s, E: Engine + ?Sized>(
    engine: &mut E,
    sc: &'s Scenario,
) -> Vec<&'s Event> {
    let step = engine.next_step();
    let from = sc.events.partition_point(|e| e.step < step);
    let mut applied = Vec::new();
    for e in sc.events[from..].iter().take_while(|e| e.step == step) {
        if let Some(id) = sc.object_id(e.action.object()) {
            engine.apply(id, &e.action);
            applied.push(e);
        }
    }
    applied
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

    /// The device running `params`, served on the host by `soft`, which reads a pipe and so
    /// reports an unbounded receive buffer (`Identity::rx_buffer` = `u32::MAX`).
    fn with<C: Controller>(
        params: &Checked<C>,
        mut soft: Box<dyn Endpoint + Send>,
    ) -> Result<Device> {
        soft.set_rx_buffer(u32::MAX);
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
/// [`SimError::NoAgent`] for an id no slot has; `exchange`'s error (a message that cannot be
/// encoded).
pub fn exchanges_by_slot(
    ids: &[u32],
    agents: &[u32],
    exchange: impl Fn(usize) -> Option<Result<Exchange>>,
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
                .unwrap_or(Err(SimError::NoAgent {
                    id,
                    agents: ids.len(),
                }))
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

#[cfg(test)]
mod tests {
    use swarm_core::ant::{AntPlanReply, AntPlanRequest, AntResolveReply, AntResolveRequest};

    use super::*;

    /// An engine of no agents that records the events applied to it.
    #[derive(Default)]
    struct Recorder {
        step: u32,
        applied: Vec<(u16, &'static str)>,
    }

    impl Engine for Recorder {
        fn model(&self) -> &'static str {
            "recorder"
        }
        fn agents(&self) -> usize {
            0
        }
        fn next_step(&self) -> u32 {
            self.step
        }
        fn apply(&mut self, object: u16, action: &Action) {
            self.applied.push((object, action.verb()));
        }
        fn phases(&self) -> &'static [&'static str] {
            &["tick"]
        }
        fn decide(&mut self, _phase: usize) -> Result<()> {
            Ok(())
        }
        fn publish(&mut self, _phase: usize) -> Result<()> {
            self.step += 1;
            Ok(())
        }
        fn exchanges(&self, _phase: usize, _agents: &[u32]) -> Result<Vec<Exchange>> {
            Ok(Vec::new())
        }
        fn device(&self) -> Result<Device> {
            Err(SimError::NoAgents)
        }
        fn frame(&self) -> Frame {
            Frame::default()
        }
        fn state_names(&self) -> StateNames {
            StateNames::default()
        }
        fn collision_distance(&self) -> f32 {
            0.0
        }
        fn closing(&self, _summary: &mut Summary) -> String {
            String::new()
        }
    }

    #[test]
    fn the_events_due_at_the_next_step_are_applied_in_order_and_no_others() {
        // Fig. 11: rocks 1-3 (objects 2-4) added at 1500, removed at 2500, 3000, 3500.
        let mut sc = crate::scenario::builtin("ants-fig11-dynamic-obstacles").unwrap();
        sc.events.insert(
            3,
            Event {
                step: 1500,
                action: Action::Start("no-such-object".into()),
            },
        );
        let mut e = Recorder::default();
        for step in [0, 1499, 1501, 2499] {
            e.step = step;
            assert!(apply_due_events(&mut e, &sc).is_empty(), "{step}");
        }
        e.step = 1500;
        let applied = apply_due_events(&mut e, &sc);
        assert_eq!(applied.len(), 3, "the unknown object is skipped");
        assert_eq!(e.applied, [(2, "add"), (3, "add"), (4, "add")]);
        e.step = 3000;
        assert_eq!(apply_due_events(&mut e, &sc), [&sc.events[5]]);
        assert_eq!(e.applied[3..], [(4, "remove")]);
    }

    /// A message postcard cannot encode.
    #[derive(serde::Deserialize)]
    struct Unencodable;

    impl serde::Serialize for Unencodable {
        fn serialize<S: serde::Serializer>(&self, _: S) -> std::result::Result<S::Ok, S::Error> {
            Err(serde::ser::Error::custom("refused"))
        }
    }

    impl Message for Unencodable {
        const KIND: u8 = 0xF0;
    }

    #[test]
    fn a_message_that_cannot_be_encoded_is_an_error_naming_it() {
        let e = Payload::of(&Unencodable).unwrap_err();
        assert!(matches!(e, SimError::Encode { kind: 0xF0, .. }), "{e}");
        let msg = e.to_string();
        assert!(msg.contains("Unencodable") && msg.contains("0xf0"), "{msg}");
    }

    #[test]
    fn an_exchange_is_typed_and_named_by_its_phase() {
        let sc = crate::scenario::builtin("ants-fig7a-single-colony").unwrap();
        let mut engine = crate::models::engine(&sc, sc.seed).unwrap();
        for (phase, name) in engine.phases().iter().enumerate() {
            engine.decide(phase).unwrap();
            let ex = engine.exchanges(phase, &[3]).unwrap();
            assert_eq!((ex.len(), ex[0].agent, ex[0].phase), (1, 3, *name));
            let kinds = (ex[0].request.kind, ex[0].reply.kind);
            let want = match phase {
                0 => (
                    <AntPlanRequest<f32> as Message>::KIND,
                    <AntPlanReply<f32> as Message>::KIND,
                ),
                _ => (
                    <AntResolveRequest<f32> as Message>::KIND,
                    <AntResolveReply<f32> as Message>::KIND,
                ),
            };
            assert_eq!(kinds, want, "{name}");
            engine.publish(phase).unwrap();
        }
    }
}
