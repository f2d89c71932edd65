//! The wang model as the generic machinery sees it: its two phases (advect, then separate,
//! like the ant's plan → resolve), their requests and replies, which are also its wire
//! messages, and its wire description.

use crate::model::{Model, Phase};
use crate::{Checked, Result, Scalar, StepCtx};

use super::{AdvectFrame, SeparateFrame, WangParams, WangState};

/// Neighbours (tentative positions) in a separate-phase frame on the wire.
pub const WIRE_WANG_NEIGHBOURS: usize = 8;

/// The separate-phase sensor frame with the wire capacity.
pub type WireSeparateFrame<S> = SeparateFrame<S, WIRE_WANG_NEIGHBOURS>;

wire_type! {
    /// Request: run [`advect`](super::advect) (phase 1 of the wang step).
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct AdvectRequest<S> {
        /// The insect's state at the start of the step.
        pub state: WangState<S>,
        /// What it senses: the navigation direction, the nearest boundary, the lamp.
        pub frame: AdvectFrame<S>,
        /// Seed, agent id and step: the inputs of its random numbers.
        pub ctx: StepCtx,
    }

    /// Reply to [`AdvectRequest`]: the tentative position x* = x + V·Δt (what the insect
    /// broadcasts) and the velocity V.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct AdvectReply<S> {
        /// The outcome of [`advect`](super::advect).
        pub moved: WangState<S>,
    }

    /// Request: run [`separate`](super::separate) (phase 2 of the wang step).
    #[derive(Clone, Debug, PartialEq)]
    pub struct SeparateRequest<S> {
        /// The insect's own advect reply.
        pub moved: WangState<S>,
        /// The neighbours' tentative positions.
        pub frame: WireSeparateFrame<S>,
        /// Seed, agent id and step (the coincident-pair draw, and the insect's own id).
        pub ctx: StepCtx,
    }

    /// Reply to [`SeparateRequest`]: the insect's state for the next step.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct SeparateReply<S> {
        /// x_{k+1}, and the velocity of the advect phase.
        pub state: WangState<S>,
        /// How many neighbours pushed it (0: MDE not applied).
        pub pushes: u8,
    }
}

impl<S: Scalar> AdvectRequest<S> {
    /// Checks `params`, then runs the [`Advect`] phase on the request.
    pub fn run(&self, params: &WangParams<S>) -> Result<AdvectReply<S>> {
        Advect::run(&(*params).checked()?, self)
    }
}

impl<S: Scalar> SeparateRequest<S> {
    /// Checks `params`, then runs the [`Separate`] phase on the request.
    pub fn run(&self, params: &WangParams<S>) -> Result<SeparateReply<S>> {
        Separate::run(&(*params).checked()?, self)
    }
}

/// Phase 1 of the wang step (wang2014 eq. 9, §7): every insect moves to its tentative
/// position x*.
#[derive(Clone, Copy, Debug)]
pub struct Advect;

/// Phase 2 of the wang step (wang2014 §6): every insect is pushed apart from the neighbours
/// whose x* came closer than d_min.
#[derive(Clone, Copy, Debug)]
pub struct Separate;

impl<S: Scalar> Phase<WangParams<S>> for Advect {
    const NAME: &'static str = "advect";
    type Request = AdvectRequest<S>;
    type Reply = AdvectReply<S>;
    fn run(params: &Checked<WangParams<S>>, req: &AdvectRequest<S>) -> Result<AdvectReply<S>> {
        super::advect_checked(&req.state, &req.frame, params, req.ctx)
            .map(|moved| AdvectReply { moved })
    }
}

impl<S: Scalar> Phase<WangParams<S>> for Separate {
    const NAME: &'static str = "separate";
    type Request = SeparateRequest<S>;
    type Reply = SeparateReply<S>;
    fn run(params: &Checked<WangParams<S>>, req: &SeparateRequest<S>) -> Result<SeparateReply<S>> {
        super::separate_checked(&req.moved, &req.frame, params, req.ctx)
            .map(|(state, pushes)| SeparateReply { state, pushes })
    }
}

impl<S: Scalar> Model for WangParams<S> {
    const NAME: &'static str = "wang";
    type State = WangState<S>;
    type Phases = (Advect, Separate);
}

#[cfg(feature = "serde")]
mod on_the_wire {
    use serde::Serialize;
    use serde::de::DeserializeOwned;

    use super::*;
    use crate::wire::{
        Capacities, Controller, ControllerKind, DeviceEndpoint, kind, max_frame_len,
    };

    /// The largest payload of a wang message (or [`ErrorReply`](crate::wire::ErrorReply)),
    /// for either scalar ([`SeparateRequest<Fx>`](SeparateRequest) with a full list; pinned
    /// by a test).
    pub const MAX_WANG_PAYLOAD: usize = 206;
    /// The largest payload of a wang reply ([`SeparateReply<Fx>`](SeparateReply); pinned by a
    /// test).
    pub const MAX_WANG_REPLY_PAYLOAD: usize = 31;
    /// The longest frame of a wang message (or [`ErrorReply`](crate::wire::ErrorReply)),
    /// delimiter included: buffer size for a node that only runs the wang controller.
    pub const MAX_WANG_FRAME: usize = max_frame_len(MAX_WANG_PAYLOAD);

    crate::message_kinds! {
        AdvectRequest = kind::WANG_ADVECT_REQUEST;
        AdvectReply = kind::WANG_ADVECT_REPLY;
        SeparateRequest = kind::WANG_SEPARATE_REQUEST;
        SeparateReply = kind::WANG_SEPARATE_REPLY;
    }

    /// The longest reply frame of a wang device (its largest reply, or a session reply),
    /// delimiter included: the `TX` of a [`WangDevice`].
    pub const MAX_WANG_REPLY_FRAME: usize = <WangParams<f32> as Controller>::MAX_REPLY_FRAME;

    /// A wang device: [`DeviceEndpoint`] sized for every wang request and reply.
    pub type WangDevice<S> = DeviceEndpoint<WangParams<S>, MAX_WANG_FRAME, MAX_WANG_REPLY_FRAME>;

    impl<S: Scalar + Serialize + DeserializeOwned> Controller for WangParams<S> {
        const KIND: ControllerKind = ControllerKind::WANG;
        const CAPACITIES: Capacities = Capacities {
            neighbours: WIRE_WANG_NEIGHBOURS as u16,
            objects: 0,
            targets: 0,
            surfaces: 0,
        };
        const MAX_REQUEST_PAYLOAD: usize = MAX_WANG_PAYLOAD;
        const MAX_REPLY_PAYLOAD: usize = MAX_WANG_REPLY_PAYLOAD;
    }
}
#[cfg(feature = "serde")]
pub use on_the_wire::{
    MAX_WANG_FRAME, MAX_WANG_PAYLOAD, MAX_WANG_REPLY_FRAME, MAX_WANG_REPLY_PAYLOAD, WangDevice,
};
