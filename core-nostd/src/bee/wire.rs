//! The bee model as the generic machinery sees it: its one phase (a step), its request and
//! reply, which are also its wire messages, and its wire description.

use crate::model::{Model, Phase};
use crate::{Checked, Result, Scalar};

use super::{BeeDecision, BeeFrame, BeeParams, BeeState};

/// Neighbours in a bee sensor frame on the wire.
pub const WIRE_BEE_NEIGHBOURS: usize = 16;
/// Target particles in a bee sensor frame on the wire.
pub const WIRE_BEE_TARGETS: usize = 16;

/// The bee sensor frame with the wire capacities.
pub type WireBeeFrame<S> = BeeFrame<S, WIRE_BEE_NEIGHBOURS, WIRE_BEE_TARGETS>;

wire_type! {
    /// Request: run [`step()`](super::step()).
    #[derive(Clone, Debug, PartialEq)]
    pub struct BeeStepRequest<S> {
        /// The bee's state.
        pub state: BeeState<S>,
        /// What it senses.
        pub frame: WireBeeFrame<S>,
    }

    /// Reply to [`BeeStepRequest`]: the decision and the bee's next state.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct BeeStepReply<S> {
        /// The set-points (and the density to broadcast).
        pub decision: BeeDecision<S>,
        /// The state for the next step.
        pub state: BeeState<S>,
    }
}

impl<S: Scalar> BeeStepRequest<S> {
    /// Checks `params`, then runs the [`Step`] phase on the request.
    pub fn run(&self, params: &BeeParams<S>) -> Result<BeeStepReply<S>> {
        Step::run(&(*params).checked()?, self)
    }
}

/// The bee's one phase (chen eq. 1, §III-V): every bee decides its set-points and moves.
#[derive(Clone, Copy, Debug)]
pub struct Step;

impl<S: Scalar> Phase<BeeParams<S>> for Step {
    const NAME: &'static str = "step";
    type Request = BeeStepRequest<S>;
    type Reply = BeeStepReply<S>;
    fn run(params: &Checked<BeeParams<S>>, req: &BeeStepRequest<S>) -> Result<BeeStepReply<S>> {
        super::step_checked(&req.state, &req.frame, params)
            .map(|(decision, state)| BeeStepReply { decision, state })
    }
}

impl<S: Scalar> Model for BeeParams<S> {
    const NAME: &'static str = "bee";
    type State = BeeState<S>;
    type Phases = (Step,);
}

#[cfg(feature = "serde")]
mod on_the_wire {
    use serde::Serialize;
    use serde::de::DeserializeOwned;

    use super::*;
    use crate::wire::{
        Capacities, Controller, ControllerKind, DeviceEndpoint, kind, max_frame_len,
    };

    /// The largest payload of a bee message (or [`ErrorReply`](crate::wire::ErrorReply)), for
    /// either scalar ([`BeeStepRequest<Fx>`](BeeStepRequest) with full lists; pinned by a
    /// test).
    pub const MAX_BEE_PAYLOAD: usize = 930;
    /// The largest payload of a bee reply ([`BeeStepReply<Fx>`](BeeStepReply); pinned by a
    /// test).
    pub const MAX_BEE_REPLY_PAYLOAD: usize = 122;
    /// The longest frame of a bee message (or [`ErrorReply`](crate::wire::ErrorReply)),
    /// delimiter included.
    pub const MAX_BEE_FRAME: usize = max_frame_len(MAX_BEE_PAYLOAD);

    crate::message_kinds! {
        BeeStepRequest = kind::BEE_STEP_REQUEST;
        BeeStepReply = kind::BEE_STEP_REPLY;
    }

    /// The longest reply frame of a bee device (its largest reply, or a session reply),
    /// delimiter included: the `TX` of a [`BeeDevice`].
    pub const MAX_BEE_REPLY_FRAME: usize = <BeeParams<f32> as Controller>::MAX_REPLY_FRAME;

    /// A bee device: [`DeviceEndpoint`] sized for every bee request and reply.
    pub type BeeDevice<S> = DeviceEndpoint<BeeParams<S>, MAX_BEE_FRAME, MAX_BEE_REPLY_FRAME>;

    impl<S: Scalar + Serialize + DeserializeOwned> Controller for BeeParams<S> {
        const KIND: ControllerKind = ControllerKind::BEE;
        const CAPACITIES: Capacities = Capacities {
            neighbours: WIRE_BEE_NEIGHBOURS as u16,
            objects: 0,
            targets: WIRE_BEE_TARGETS as u16,
            surfaces: 0,
        };
        const MAX_REQUEST_PAYLOAD: usize = MAX_BEE_PAYLOAD;
        const MAX_REPLY_PAYLOAD: usize = MAX_BEE_REPLY_PAYLOAD;
    }
}
#[cfg(feature = "serde")]
pub use on_the_wire::{
    BeeDevice, MAX_BEE_FRAME, MAX_BEE_PAYLOAD, MAX_BEE_REPLY_FRAME, MAX_BEE_REPLY_PAYLOAD,
};
