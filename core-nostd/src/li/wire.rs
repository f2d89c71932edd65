//! The li model as the generic machinery sees it: its one phase (a step, like the fly's),
//! its request and reply, which are also its wire messages, and its wire description.

use crate::model::{Model, Phase};
use crate::orca3d::Neighbour;
use crate::{Checked, Result, Scalar, StepCtx};

use super::{LiDecision, LiFrame, LiParams, LiState};

/// Neighbours in a li sensor frame on the wire (spec §1.7: 16).
pub const WIRE_LI_NEIGHBOURS: usize = 16;
/// Obstacle surfaces in a li sensor frame on the wire (as the fly's: 4).
pub const WIRE_LI_SURFACES: usize = 4;

/// The li sensor frame with the wire capacities.
pub type WireLiFrame<S> = LiFrame<S, WIRE_LI_NEIGHBOURS, WIRE_LI_SURFACES>;

/// A neighbour of a li frame (the shared ORCA neighbour).
pub type LiNeighbour<S> = Neighbour<S>;

wire_type! {
    /// Request: run [`step()`](super::step()).
    #[derive(Clone, Debug, PartialEq)]
    pub struct LiStepRequest<S> {
        /// The insect's state.
        pub state: LiState<S>,
        /// What it senses.
        pub frame: WireLiFrame<S>,
        /// Seed, agent id and step: the inputs of its random numbers (the proposals' lengths,
        /// turns, directions and acceptance), and its own id.
        pub ctx: StepCtx,
    }

    /// Reply to [`LiStepRequest`]: the decision and the insect's next state.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct LiStepReply<S> {
        /// The preferred velocity, the proposals and whether ORCA was infeasible.
        pub decision: LiDecision<S>,
        /// The state for the next step.
        pub state: LiState<S>,
    }
}

impl<S: Scalar> LiStepRequest<S> {
    /// Checks `params`, then runs the [`LiStep`] phase on the request.
    pub fn run(&self, params: &LiParams<S>) -> Result<LiStepReply<S>> {
        LiStep::run(&params.clone().checked()?, self)
    }
}

/// The li insect's one phase (spec §1.6): the waypoint, the preferred velocity, ORCA, the
/// move.
#[derive(Clone, Copy, Debug)]
pub struct LiStep;

impl<S: Scalar> Phase<LiParams<S>> for LiStep {
    const NAME: &'static str = "step";
    type Request = LiStepRequest<S>;
    type Reply = LiStepReply<S>;
    fn run(params: &Checked<LiParams<S>>, req: &LiStepRequest<S>) -> Result<LiStepReply<S>> {
        super::step_checked(&req.state, &req.frame, params, req.ctx)
            .map(|(state, decision)| LiStepReply { decision, state })
    }
}

impl<S: Scalar> Model for LiParams<S> {
    const NAME: &'static str = "li";
    type State = LiState<S>;
    type Phases = (LiStep,);
}

#[cfg(feature = "serde")]
mod on_the_wire {
    use serde::Serialize;
    use serde::de::DeserializeOwned;

    use super::*;
    use crate::wire::{
        Capacities, Controller, ControllerKind, DeviceEndpoint, kind, max_frame_len,
    };

    /// The largest payload of a li message (or [`ErrorReply`](crate::wire::ErrorReply)), for
    /// either scalar ([`LiStepRequest<Fx>`](LiStepRequest) with full lists; pinned by a
    /// test).
    pub const MAX_LI_PAYLOAD: usize = 760;
    /// The largest payload of a li reply ([`LiStepReply<Fx>`](LiStepReply); pinned by a
    /// test).
    pub const MAX_LI_REPLY_PAYLOAD: usize = 81;
    /// The longest frame of a li message (or [`ErrorReply`](crate::wire::ErrorReply)),
    /// delimiter included: buffer size for a node that only runs the li controller.
    pub const MAX_LI_FRAME: usize = max_frame_len(MAX_LI_PAYLOAD);

    crate::message_kinds! {
        LiStepRequest = kind::LI_STEP_REQUEST;
        LiStepReply = kind::LI_STEP_REPLY;
    }

    /// The longest reply frame of a li device (its largest reply, or a session reply),
    /// delimiter included: the `TX` of a [`LiDevice`].
    pub const MAX_LI_REPLY_FRAME: usize = <LiParams<f32> as Controller>::MAX_REPLY_FRAME;

    /// A li device: [`DeviceEndpoint`] sized for every li request and reply.
    pub type LiDevice<S> = DeviceEndpoint<LiParams<S>, MAX_LI_FRAME, MAX_LI_REPLY_FRAME>;

    /// `neighbours` is [`WIRE_LI_NEIGHBOURS`] and `surfaces` [`WIRE_LI_SURFACES`]; the frame
    /// has no objects or targets.
    impl<S: Scalar + Serialize + DeserializeOwned> Controller for LiParams<S> {
        const KIND: ControllerKind = ControllerKind::LI;
        const CAPACITIES: Capacities = Capacities {
            neighbours: WIRE_LI_NEIGHBOURS as u16,
            objects: 0,
            targets: 0,
            surfaces: WIRE_LI_SURFACES as u16,
        };
        const MAX_REQUEST_PAYLOAD: usize = MAX_LI_PAYLOAD;
        const MAX_REPLY_PAYLOAD: usize = MAX_LI_REPLY_PAYLOAD;
    }
}
#[cfg(feature = "serde")]
pub use on_the_wire::{
    LiDevice, MAX_LI_FRAME, MAX_LI_PAYLOAD, MAX_LI_REPLY_FRAME, MAX_LI_REPLY_PAYLOAD,
};
