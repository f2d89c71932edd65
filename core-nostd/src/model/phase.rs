//! The phases of a tick: what a model computes for one agent, as a request (its state and
//! what it senses) and a reply (its decision), so that a simulator, a device and a mirror can
//! all run it one phase at a time.

use crate::{Checked, Result};

use super::Model;

/// One phase of a model's tick: a pure function from a request (the agent's state, or what an
/// earlier phase decided, and the sensor frame of this phase) to a reply (the decision), under
/// the model's checked parameters.
///
/// Every phase of every agent reads only what the previous phase published, so a simulator
/// runs a phase for all agents in parallel and then publishes the replies. With the `serde`
/// feature, the request and reply are also the phase's wire messages (their
/// [`Message::KIND`](crate::wire::Message::KIND)s are the protocol's kinds), which is how a
/// [`DeviceEndpoint`](crate::wire::DeviceEndpoint) serves a model it knows nothing else of.
pub trait Phase<M: Model> {
    /// The phase's name in reports (`plan`, `resolve`, `step`).
    const NAME: &'static str;
    /// What the agent brings: its state and what it senses.
    type Request: Clone;
    /// What it decides.
    type Reply: Clone;

    /// Runs the phase for one agent.
    ///
    /// # Errors
    ///
    /// The model's error for a request it refuses (a value out of range, contradictory ids).
    fn run(params: &Checked<M>, request: &Self::Request) -> Result<Self::Reply>;
}

/// The phases of a model's tick, in order: a tuple of one to four [`Phase`]s.
pub trait Phases<M: Model> {
    /// How many phases a tick has.
    const COUNT: usize;
    /// Their names, in order.
    const NAMES: &'static [&'static str];
}

macro_rules! phases {
    ($($p:ident),+) => {
        impl<M: Model, $($p: Phase<M>),+> Phases<M> for ($($p,)+) {
            const COUNT: usize = [$($p::NAME),+].len();
            const NAMES: &'static [&'static str] = &[$($p::NAME),+];
        }
    };
}
phases!(A);
phases!(A, B);
phases!(A, B, C);
phases!(A, B, C, D);
