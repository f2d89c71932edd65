//! The ant model as the generic machinery sees it: its two phases (plan, then resolve), their
//! requests and replies, which are also its wire messages, and its wire description.

use crate::model::{Model, Phase};
use crate::{Checked, Result, Scalar, StepCtx};

use super::{AntParams, AntPlan, AntState, PlanFrame, ResolveFrame};

/// Neighbours in an ant sensor frame on the wire (plan and resolve phases).
pub const WIRE_ANT_NEIGHBOURS: usize = 8;
/// Environment objects in an ant plan frame on the wire.
pub const WIRE_ANT_OBJECTS: usize = 4;

/// The ant plan-phase sensor frame with the wire capacities.
pub type WirePlanFrame<S> = PlanFrame<S, WIRE_ANT_NEIGHBOURS, WIRE_ANT_OBJECTS>;
/// The ant resolve-phase sensor frame with the wire capacity.
pub type WireResolveFrame<S> = ResolveFrame<S, WIRE_ANT_NEIGHBOURS>;

wire_type! {
    /// Request: run [`plan`](super::plan) (phase 1 of the ant tick).
    #[derive(Clone, Debug, PartialEq)]
    pub struct AntPlanRequest<S> {
        /// The ant's state at the start of the tick.
        pub state: AntState<S>,
        /// What it senses.
        pub frame: WirePlanFrame<S>,
        /// Seed, agent id and step: the inputs of its random numbers.
        pub ctx: StepCtx,
    }

    /// Reply to [`AntPlanRequest`]: the plan (the predicted position is what the ant
    /// broadcasts).
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct AntPlanReply<S> {
        /// The outcome of [`plan`](super::plan).
        pub plan: AntPlan<S>,
    }

    /// Request: run [`resolve`](super::resolve) (phase 2 of the ant tick).
    #[derive(Clone, Debug, PartialEq)]
    pub struct AntResolveRequest<S> {
        /// The ant's own plan from phase 1.
        pub plan: AntPlan<S>,
        /// The neighbours' predicted positions.
        pub frame: WireResolveFrame<S>,
    }

    /// Reply to [`AntResolveRequest`]: the ant's state for the next tick.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct AntResolveReply<S> {
        /// The outcome of [`resolve`](super::resolve).
        pub state: AntState<S>,
    }
}

impl<S: Scalar> AntPlanRequest<S> {
    /// Checks `params`, then runs the [`Plan`] phase on the request.
    pub fn run(&self, params: &AntParams<S>) -> Result<AntPlanReply<S>> {
        Plan::run(&(*params).checked()?, self)
    }
}

impl<S: Scalar> AntResolveRequest<S> {
    /// Checks `params`, then runs the [`Resolve`] phase on the request.
    pub fn run(&self, params: &AntParams<S>) -> Result<AntResolveReply<S>> {
        Resolve::run(&(*params).checked()?, self)
    }
}

/// Phase 1 of the ant tick (xiang2018 §3-4): every ant plans its move and predicts p*(t+1).
#[derive(Clone, Copy, Debug)]
pub struct Plan;

/// Phase 2 of the ant tick (xiang2018 §3.2, eq. 2-3): every ant resolves its plan against
/// its neighbours' predictions.
#[derive(Clone, Copy, Debug)]
pub struct Resolve;

impl<S: Scalar> Phase<AntParams<S>> for Plan {
    const NAME: &'static str = "plan";
    type Request = AntPlanRequest<S>;
    type Reply = AntPlanReply<S>;
    fn run(params: &Checked<AntParams<S>>, req: &AntPlanRequest<S>) -> Result<AntPlanReply<S>> {
        super::plan_checked(&req.state, &req.frame, params, req.ctx)
            .map(|plan| AntPlanReply { plan })
    }
}

impl<S: Scalar> Phase<AntParams<S>> for Resolve {
    const NAME: &'static str = "resolve";
    type Request = AntResolveRequest<S>;
    type Reply = AntResolveReply<S>;
    fn run(
        params: &Checked<AntParams<S>>,
        req: &AntResolveRequest<S>,
    ) -> Result<AntResolveReply<S>> {
        super::resolve_checked(&req.plan, &req.frame, params).map(|state| AntResolveReply { state })
    }
}

impl<S: Scalar> Model for AntParams<S> {
    const NAME: &'static str = "ant";
    type State = AntState<S>;
    type Phases = (Plan, Resolve);
}

#[cfg(feature = "serde")]
mod on_the_wire {
    use serde::Serialize;
    use serde::de::DeserializeOwned;

    use super::*;
    use crate::wire::{
        Capacities, Controller, ControllerKind, DeviceEndpoint, kind, max_frame_len,
    };

    /// The largest payload of an ant message (or [`ErrorReply`](crate::wire::ErrorReply)),
    /// for either scalar ([`AntPlanRequest<Fx>`](AntPlanRequest) with full lists; pinned by a
    /// test).
    pub const MAX_ANT_PAYLOAD: usize = 441;
    /// The largest payload of an ant reply ([`AntPlanReply<Fx>`](AntPlanReply); pinned by a
    /// test).
    pub const MAX_ANT_REPLY_PAYLOAD: usize = 74;
    /// The longest frame of an ant message (or [`ErrorReply`](crate::wire::ErrorReply)),
    /// delimiter included: buffer size for a node that only runs the ant controller.
    pub const MAX_ANT_FRAME: usize = max_frame_len(MAX_ANT_PAYLOAD);

    crate::message_kinds! {
        AntPlanRequest = kind::ANT_PLAN_REQUEST;
        AntPlanReply = kind::ANT_PLAN_REPLY;
        AntResolveRequest = kind::ANT_RESOLVE_REQUEST;
        AntResolveReply = kind::ANT_RESOLVE_REPLY;
    }

    /// The longest reply frame of an ant device (its largest reply, or a session reply),
    /// delimiter included: the `TX` of an [`AntDevice`].
    pub const MAX_ANT_REPLY_FRAME: usize = <AntParams<f32> as Controller>::MAX_REPLY_FRAME;

    /// An ant device: [`DeviceEndpoint`] sized for every ant request and reply.
    pub type AntDevice<S> = DeviceEndpoint<AntParams<S>, MAX_ANT_FRAME, MAX_ANT_REPLY_FRAME>;

    impl<S: Scalar + Serialize + DeserializeOwned> Controller for AntParams<S> {
        const KIND: ControllerKind = ControllerKind::ANT;
        const CAPACITIES: Capacities = Capacities {
            neighbours: WIRE_ANT_NEIGHBOURS as u16,
            objects: WIRE_ANT_OBJECTS as u16,
            targets: 0,
            surfaces: crate::ant::SURFACES as u16,
        };
        const MAX_REQUEST_PAYLOAD: usize = MAX_ANT_PAYLOAD;
        const MAX_REPLY_PAYLOAD: usize = MAX_ANT_REPLY_PAYLOAD;
    }
}
#[cfg(feature = "serde")]
pub use on_the_wire::{
    AntDevice, MAX_ANT_FRAME, MAX_ANT_PAYLOAD, MAX_ANT_REPLY_FRAME, MAX_ANT_REPLY_PAYLOAD,
};
