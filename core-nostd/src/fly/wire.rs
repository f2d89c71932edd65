//! The fly model as the generic machinery sees it: its one phase (a step, like the bee's),
//! its request and reply, which are also its wire messages, and its wire description.

use crate::model::{Model, Phase};
use crate::{Checked, Result, Scalar, StepCtx};

use super::{FlyDecision, FlyFrame, FlyParams, FlyState};

/// Neighbours in a fly sensor frame on the wire (spec §1.6: 16 on devices).
pub const WIRE_FLY_NEIGHBOURS: usize = 16;
/// Obstacle surfaces in a fly sensor frame on the wire (spec §2.5: at most 4).
pub const WIRE_FLY_SURFACES: usize = 4;

/// The fly sensor frame with the wire capacities.
pub type WireFlyFrame<S> = FlyFrame<S, WIRE_FLY_NEIGHBOURS, WIRE_FLY_SURFACES>;

wire_type! {
    /// Request: run [`step()`](super::step()).
    #[derive(Clone, Debug, PartialEq)]
    pub struct FlyStepRequest<S> {
        /// The insect's state.
        pub state: FlyState<S>,
        /// What it senses.
        pub frame: WireFlyFrame<S>,
        /// Seed, agent id and step: the inputs of its random numbers (escape angle, white
        /// and Gaussian noise), and its own id.
        pub ctx: StepCtx,
    }

    /// Reply to [`FlyStepRequest`]: the decision and the insect's next state.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct FlyStepReply<S> {
        /// The preferred velocity and whether ORCA was infeasible.
        pub decision: FlyDecision<S>,
        /// The state for the next step.
        pub state: FlyState<S>,
    }
}

impl<S: Scalar> FlyStepRequest<S> {
    /// Checks `params`, then runs the [`FlyStep`] phase on the request.
    pub fn run(&self, params: &FlyParams<S>) -> Result<FlyStepReply<S>> {
        FlyStep::run(&(*params).checked()?, self)
    }
}

/// The fly's one phase (ren2016 Algorithm 1): every insect integrates its forces into a
/// preferred velocity, ORCA makes it collision-free, and the insect moves.
#[derive(Clone, Copy, Debug)]
pub struct FlyStep;

impl<S: Scalar> Phase<FlyParams<S>> for FlyStep {
    const NAME: &'static str = "step";
    type Request = FlyStepRequest<S>;
    type Reply = FlyStepReply<S>;
    fn run(params: &Checked<FlyParams<S>>, req: &FlyStepRequest<S>) -> Result<FlyStepReply<S>> {
        super::step_checked(&req.state, &req.frame, params, req.ctx)
            .map(|(state, decision)| FlyStepReply { decision, state })
    }
}

impl<S: Scalar> Model for FlyParams<S> {
    const NAME: &'static str = "fly";
    type State = FlyState<S>;
    type Phases = (FlyStep,);
}

#[cfg(feature = "serde")]
mod on_the_wire {
    use serde::Serialize;
    use serde::de::DeserializeOwned;

    use super::*;
    use crate::wire::{
        Capacities, Controller, ControllerKind, DeviceEndpoint, kind, max_frame_len,
    };

    /// The largest payload of a fly message (or [`ErrorReply`](crate::wire::ErrorReply)), for
    /// either scalar ([`FlyStepRequest<Fx>`](FlyStepRequest) with full lists; pinned by a
    /// test).
    pub const MAX_FLY_PAYLOAD: usize = 750;
    /// The largest payload of a fly reply ([`FlyStepReply<Fx>`](FlyStepReply); pinned by a
    /// test).
    pub const MAX_FLY_REPLY_PAYLOAD: usize = 52;
    /// The longest frame of a fly message (or [`ErrorReply`](crate::wire::ErrorReply)),
    /// delimiter included: buffer size for a node that only runs the fly controller.
    pub const MAX_FLY_FRAME: usize = max_frame_len(MAX_FLY_PAYLOAD);

    crate::message_kinds! {
        FlyStepRequest = kind::FLY_STEP_REQUEST;
        FlyStepReply = kind::FLY_STEP_REPLY;
    }

    /// The longest reply frame of a fly device (its largest reply, or a session reply),
    /// delimiter included: the `TX` of a [`FlyDevice`].
    pub const MAX_FLY_REPLY_FRAME: usize = <FlyParams<f32> as Controller>::MAX_REPLY_FRAME;

    /// A fly device: [`DeviceEndpoint`] sized for every fly request and reply.
    pub type FlyDevice<S> = DeviceEndpoint<FlyParams<S>, MAX_FLY_FRAME, MAX_FLY_REPLY_FRAME>;

    /// The stimulus is an `Option`, not a list: it needs no capacity (a frame carries at most
    /// one), so `targets` and `objects` are 0; `neighbours` is [`WIRE_FLY_NEIGHBOURS`] and
    /// `surfaces` [`WIRE_FLY_SURFACES`] (`FlyFrame.surfaces`).
    impl<S: Scalar + Serialize + DeserializeOwned> Controller for FlyParams<S> {
        const KIND: ControllerKind = ControllerKind::FLY;
        const CAPACITIES: Capacities = Capacities {
            neighbours: WIRE_FLY_NEIGHBOURS as u16,
            objects: 0,
            targets: 0,
            surfaces: WIRE_FLY_SURFACES as u16,
        };
        const MAX_REQUEST_PAYLOAD: usize = MAX_FLY_PAYLOAD;
        const MAX_REPLY_PAYLOAD: usize = MAX_FLY_REPLY_PAYLOAD;
    }
}
#[cfg(feature = "serde")]
pub use on_the_wire::{
    FlyDevice, MAX_FLY_FRAME, MAX_FLY_PAYLOAD, MAX_FLY_REPLY_FRAME, MAX_FLY_REPLY_PAYLOAD,
};
