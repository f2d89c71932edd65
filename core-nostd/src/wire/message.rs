//! The registry of message kinds, the error reply, and the largest message of the built-in
//! models.
//!
//! A model's controller messages are its phases' requests and replies, defined in the model's
//! folder ([`crate::ant::AntPlanRequest`], [`crate::bee::BeeStepRequest`], ...): the host
//! sends a request, the device runs the phase on it and answers with the reply of the same
//! sequence number, or with an [`ErrorReply`] when the controller refused the input. Every
//! message is generic over the scalar `S` (`f32` or [`Fx`](crate::Fx)); both ends must agree on
//! it (the session handshake checks that: [`Identity::scalar`](super::Identity::scalar)), since
//! the kind byte does not say which.
//!
//! Sensor-frame capacities on the wire are fixed per model, so every message has a bounded
//! size: [`MAX_PAYLOAD`] bytes at most for the built-in models, [`MAX_FRAME`] on the line.

use serde::{Deserialize, Serialize};

use super::Message;
use super::frame::max_frame_len;
use crate::Error;
use crate::ant::MAX_ANT_PAYLOAD;
use crate::bee::MAX_BEE_PAYLOAD;
use crate::fly::MAX_FLY_PAYLOAD;
use crate::li::MAX_LI_PAYLOAD;
use crate::wang::MAX_WANG_PAYLOAD;

const fn max(a: usize, b: usize) -> usize {
    if a > b { a } else { b }
}

/// The largest payload of any message of the built-in models, for either scalar.
pub const MAX_PAYLOAD: usize = max(
    max(MAX_ANT_PAYLOAD, MAX_BEE_PAYLOAD),
    max(MAX_WANG_PAYLOAD, max(MAX_FLY_PAYLOAD, MAX_LI_PAYLOAD)),
);
/// The longest frame of any message of this module, delimiter included: the size of a send
/// buffer that always suffices, and an [`Accumulator`](super::Accumulator) capacity that
/// always receives.
pub const MAX_FRAME: usize = max_frame_len(MAX_PAYLOAD);

/// The message kinds (header byte 1).
///
/// | range       | use                                                      |
/// |-------------|----------------------------------------------------------|
/// | `0x00`      | never used                                               |
/// | `0x01-0x08` | session protocol (see [`Hello`](crate::wire::Hello)): handshake, configure, ping, statistics; a reply is its request's kind + 1 |
/// | `0x09-0x0E` | reserved for the session protocol                        |
/// | `0x0F`      | [`ErrorReply`]                                           |
/// | `0x10-0x1F` | ant controller; a reply is its request's kind + 1        |
/// | `0x20-0x2F` | bee controller; a reply is its request's kind + 1        |
/// | `0x30-0x3F` | wang controller; a reply is its request's kind + 1       |
/// | `0x40-0x4F` | fly controller; a reply is its request's kind + 1        |
/// | `0x50-0x5F` | li controller; a reply is its request's kind + 1         |
/// | `0x60-0x7F` | reserved                                                 |
/// | `0x80-0xFF` | free for applications and tests; this crate sends none   |
pub mod kind {
    /// [`Hello`](crate::wire::Hello): host → device, opens the handshake.
    pub const HELLO: u8 = 0x01;
    /// [`Identity`](crate::wire::Identity): the device's answer to [`HELLO`].
    pub const IDENTITY: u8 = 0x02;
    /// [`Configure`](crate::wire::Configure): host → device, opens the session.
    pub const CONFIGURE: u8 = 0x03;
    /// [`Configured`](crate::wire::Configured): the answer to [`CONFIGURE`].
    pub const CONFIGURED: u8 = 0x04;
    /// [`Ping`](crate::wire::Ping).
    pub const PING: u8 = 0x05;
    /// [`Pong`](crate::wire::Pong): the answer to [`PING`].
    pub const PONG: u8 = 0x06;
    /// [`StatsRequest`](crate::wire::StatsRequest).
    pub const STATS_REQUEST: u8 = 0x07;
    /// [`DeviceStats`](crate::wire::DeviceStats): the answer to [`STATS_REQUEST`].
    pub const DEVICE_STATS: u8 = 0x08;
    /// [`ErrorReply`](super::ErrorReply).
    pub const ERROR_REPLY: u8 = 0x0F;
    /// [`AntPlanRequest`](crate::ant::AntPlanRequest).
    pub const ANT_PLAN_REQUEST: u8 = 0x10;
    /// [`AntPlanReply`](crate::ant::AntPlanReply).
    pub const ANT_PLAN_REPLY: u8 = 0x11;
    /// [`AntResolveRequest`](crate::ant::AntResolveRequest).
    pub const ANT_RESOLVE_REQUEST: u8 = 0x12;
    /// [`AntResolveReply`](crate::ant::AntResolveReply).
    pub const ANT_RESOLVE_REPLY: u8 = 0x13;
    /// [`BeeStepRequest`](crate::bee::BeeStepRequest).
    pub const BEE_STEP_REQUEST: u8 = 0x20;
    /// [`BeeStepReply`](crate::bee::BeeStepReply).
    pub const BEE_STEP_REPLY: u8 = 0x21;
    /// [`AdvectRequest`](crate::wang::AdvectRequest).
    pub const WANG_ADVECT_REQUEST: u8 = 0x30;
    /// [`AdvectReply`](crate::wang::AdvectReply).
    pub const WANG_ADVECT_REPLY: u8 = 0x31;
    /// [`SeparateRequest`](crate::wang::SeparateRequest).
    pub const WANG_SEPARATE_REQUEST: u8 = 0x32;
    /// [`SeparateReply`](crate::wang::SeparateReply).
    pub const WANG_SEPARATE_REPLY: u8 = 0x33;
    /// [`FlyStepRequest`](crate::fly::FlyStepRequest).
    pub const FLY_STEP_REQUEST: u8 = 0x40;
    /// [`FlyStepReply`](crate::fly::FlyStepReply).
    pub const FLY_STEP_REPLY: u8 = 0x41;
    /// [`LiStepRequest`](crate::li::LiStepRequest).
    pub const LI_STEP_REQUEST: u8 = 0x50;
    /// [`LiStepReply`](crate::li::LiStepReply).
    pub const LI_STEP_REPLY: u8 = 0x51;

    /// The message's name, for logs and reports; `None` for a kind this build does not know.
    pub const fn name(kind: u8) -> Option<&'static str> {
        Some(match kind {
            HELLO => "Hello",
            IDENTITY => "Identity",
            CONFIGURE => "Configure",
            CONFIGURED => "Configured",
            PING => "Ping",
            PONG => "Pong",
            STATS_REQUEST => "StatsRequest",
            DEVICE_STATS => "DeviceStats",
            ERROR_REPLY => "ErrorReply",
            ANT_PLAN_REQUEST => "AntPlanRequest",
            ANT_PLAN_REPLY => "AntPlanReply",
            ANT_RESOLVE_REQUEST => "AntResolveRequest",
            ANT_RESOLVE_REPLY => "AntResolveReply",
            BEE_STEP_REQUEST => "BeeStepRequest",
            BEE_STEP_REPLY => "BeeStepReply",
            WANG_ADVECT_REQUEST => "AdvectRequest",
            WANG_ADVECT_REPLY => "AdvectReply",
            WANG_SEPARATE_REQUEST => "SeparateRequest",
            WANG_SEPARATE_REPLY => "SeparateReply",
            FLY_STEP_REQUEST => "FlyStepRequest",
            FLY_STEP_REPLY => "FlyStepReply",
            LI_STEP_REQUEST => "LiStepRequest",
            LI_STEP_REPLY => "LiStepReply",
            _ => return None,
        })
    }

    /// Whether `kind` is a reply of this protocol (sent by a device, never answered by one,
    /// whatever the frame's protocol version: see [`never_answered`]).
    pub const fn is_reply(kind: u8) -> bool {
        matches!(
            kind,
            IDENTITY
                | CONFIGURED
                | PONG
                | DEVICE_STATS
                | ERROR_REPLY
                | ANT_PLAN_REPLY
                | ANT_RESOLVE_REPLY
                | BEE_STEP_REPLY
                | WANG_ADVECT_REPLY
                | WANG_SEPARATE_REPLY
                | FLY_STEP_REPLY
                | LI_STEP_REPLY
        )
    }

    /// Whether a device drops a frame of `kind` unanswered whatever its protocol version:
    /// `0x00` (never used) and the reply kinds ([`is_reply`], [`ERROR_REPLY`] included). So
    /// two devices wired together, of the same version or not, never answer each other. A
    /// frame of another version of any other kind is answered with an
    /// [`ErrorReply::VERSION`](super::ErrorReply::VERSION); one of this version is served
    /// (or refused) by kind.
    #[inline(always)] // two compares and a switch; smaller inlined on a 16 KiB device
    pub const fn never_answered(kind: u8) -> bool {
        kind == 0x00 || is_reply(kind)
    }
}

/// Reply to any request the device could not serve: which [`Error`] it hit, as a code.
///
/// The header's sequence number says which request failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ErrorReply {
    /// One of the associated constants ([`ErrorReply::NON_FINITE`], ...).
    pub code: u8,
}

impl ErrorReply {
    /// [`Error::NonFinite`]: a NaN or infinity in the input.
    pub const NON_FINITE: u8 = 1;
    /// [`Error::OutOfRange`].
    pub const OUT_OF_RANGE: u8 = 2;
    /// [`Error::Inconsistent`].
    pub const INCONSISTENT: u8 = 3;
    /// [`Error::BadParam`]: the device's parameters are invalid.
    pub const BAD_PARAM: u8 = 4;
    /// [`Error::BufferFull`]: the reply did not fit the device's send buffer.
    pub const BUFFER_FULL: u8 = 5;
    /// [`Error::Oversize`]: the request did not fit the device's receive buffer.
    pub const OVERSIZE: u8 = 6;
    /// [`Error::Cobs`].
    pub const COBS: u8 = 7;
    /// [`Error::Truncated`].
    pub const TRUNCATED: u8 = 8;
    /// [`Error::Crc`].
    pub const CRC: u8 = 9;
    /// [`Error::Version`]: the device speaks another protocol version.
    pub const VERSION: u8 = 10;
    /// [`Error::UnknownKind`]: the device does not serve this request kind.
    pub const UNKNOWN_KIND: u8 = 11;
    /// [`Error::UnexpectedKind`].
    pub const UNEXPECTED_KIND: u8 = 12;
    /// [`Error::Payload`]: the request's payload did not decode.
    pub const PAYLOAD: u8 = 13;
    /// [`Error::NoSession`]: a controller request (or `Configure`) before the session was
    /// opened with `Hello` and `Configure`.
    pub const NO_SESSION: u8 = 14;
    /// [`Error::ParamsMismatch`]: the `Configure`'s parameter hash is not the device's.
    pub const PARAMS_MISMATCH: u8 = 15;

    /// The code of `error`.
    pub const fn new(error: &Error) -> Self {
        let code = match error {
            Error::NonFinite { .. } => Self::NON_FINITE,
            Error::OutOfRange { .. } => Self::OUT_OF_RANGE,
            Error::Inconsistent { .. } => Self::INCONSISTENT,
            Error::BadParam { .. } => Self::BAD_PARAM,
            Error::BufferFull => Self::BUFFER_FULL,
            Error::Oversize => Self::OVERSIZE,
            Error::Cobs => Self::COBS,
            Error::Truncated => Self::TRUNCATED,
            Error::Crc { .. } => Self::CRC,
            Error::Version { .. } => Self::VERSION,
            Error::UnknownKind { .. } => Self::UNKNOWN_KIND,
            Error::UnexpectedKind { .. } => Self::UNEXPECTED_KIND,
            Error::Payload => Self::PAYLOAD,
            Error::NoSession => Self::NO_SESSION,
            Error::ParamsMismatch { .. } => Self::PARAMS_MISMATCH,
        };
        ErrorReply { code }
    }

    /// The name of the code's [`Error`] variant, e.g. `"NonFinite"`; `"unknown"` for a code
    /// this build does not know.
    pub const fn name(&self) -> &'static str {
        match self.code {
            Self::NON_FINITE => "NonFinite",
            Self::OUT_OF_RANGE => "OutOfRange",
            Self::INCONSISTENT => "Inconsistent",
            Self::BAD_PARAM => "BadParam",
            Self::BUFFER_FULL => "BufferFull",
            Self::OVERSIZE => "Oversize",
            Self::COBS => "Cobs",
            Self::TRUNCATED => "Truncated",
            Self::CRC => "Crc",
            Self::VERSION => "Version",
            Self::UNKNOWN_KIND => "UnknownKind",
            Self::UNEXPECTED_KIND => "UnexpectedKind",
            Self::PAYLOAD => "Payload",
            Self::NO_SESSION => "NoSession",
            Self::PARAMS_MISMATCH => "ParamsMismatch",
            _ => "unknown",
        }
    }
}

impl From<Error> for ErrorReply {
    fn from(error: Error) -> Self {
        ErrorReply::new(&error)
    }
}

impl Message for ErrorReply {
    const KIND: u8 = kind::ERROR_REPLY;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ant::{
        AntNeighbor, AntObject, AntParams, AntPlan, AntPlanReply, AntPlanRequest, AntResolveReply,
        AntResolveRequest, AntState, Follow, Label, MAX_ANT_FRAME, MAX_ANT_REPLY_PAYLOAD,
        MotionState, StopReason, StopTimer, Surface, Turn, WirePlanFrame, WireResolveFrame,
    };
    use crate::bee::{
        BeeDecision, BeeNeighbor, BeeParams, BeeState, BeeStepReply, BeeStepRequest, MAX_BEE_FRAME,
        MAX_BEE_REPLY_PAYLOAD, ObstacleSense, WireBeeFrame,
    };
    use crate::fly::{
        FlyDecision, FlyState, FlyStepReply, FlyStepRequest, MAX_FLY_FRAME, MAX_FLY_REPLY_PAYLOAD,
        Neighbour, STIMULUS_PREDATOR, STIMULUS_TARGET, Stimulus, Surface as FlySurface,
        WireFlyFrame,
    };
    use crate::li::{
        LiDecision, LiState, LiStepReply, LiStepRequest, MAX_LI_FRAME, MAX_LI_REPLY_PAYLOAD,
        WireLiFrame,
    };
    use crate::wang::{
        AdvectFrame, AdvectReply, AdvectRequest, Boundary, Close, MAX_WANG_FRAME,
        MAX_WANG_REPLY_PAYLOAD, SeparateReply, SeparateRequest, WangParams, WangState,
        WireSeparateFrame,
    };
    use crate::wire::test_util::{frame_of, hex, payload_len, through_the_wire};
    use crate::wire::{encode_frame, encode_message};
    use crate::{Fx, Rect, Vec2, Vec3};
    use crate::{Scalar, StepCtx};
    use serde::de::DeserializeOwned;

    fn v2<S: Scalar>(x: f32, y: f32) -> Vec2<S> {
        Vec2::new(S::from_f32(x), S::from_f32(y))
    }
    fn v3<S: Scalar>(x: f32, y: f32, z: f32) -> Vec3<S> {
        Vec3::new(S::from_f32(x), S::from_f32(y), S::from_f32(z))
    }

    #[test]
    fn kinds_are_distinct_and_named() {
        let kinds = [
            <ErrorReply as Message>::KIND,
            <AntPlanRequest<f32> as Message>::KIND,
            <AntPlanReply<f32> as Message>::KIND,
            <AntResolveRequest<f32> as Message>::KIND,
            <AntResolveReply<f32> as Message>::KIND,
            <BeeStepRequest<Fx> as Message>::KIND,
            <BeeStepReply<Fx> as Message>::KIND,
            <AdvectRequest<f32> as Message>::KIND,
            <AdvectReply<f32> as Message>::KIND,
            <SeparateRequest<Fx> as Message>::KIND,
            <SeparateReply<Fx> as Message>::KIND,
            <FlyStepRequest<f32> as Message>::KIND,
            <FlyStepReply<Fx> as Message>::KIND,
        ];
        for (i, a) in kinds.iter().enumerate() {
            assert!(kind::name(*a).is_some());
            for b in &kinds[i + 1..] {
                assert_ne!(a, b);
            }
        }
        assert_eq!(kind::ANT_PLAN_REPLY, kind::ANT_PLAN_REQUEST + 1);
        assert_eq!(kind::ANT_RESOLVE_REPLY, kind::ANT_RESOLVE_REQUEST + 1);
        assert_eq!(kind::BEE_STEP_REPLY, kind::BEE_STEP_REQUEST + 1);
        assert_eq!(kind::WANG_ADVECT_REPLY, kind::WANG_ADVECT_REQUEST + 1);
        assert_eq!(kind::WANG_SEPARATE_REPLY, kind::WANG_SEPARATE_REQUEST + 1);
        assert_eq!(
            (kind::WANG_ADVECT_REQUEST, kind::WANG_SEPARATE_REQUEST),
            (0x30, 0x32)
        );
        assert!(
            kind::is_reply(kind::WANG_ADVECT_REPLY) && kind::is_reply(kind::WANG_SEPARATE_REPLY)
        );
        assert!(
            !kind::is_reply(kind::WANG_ADVECT_REQUEST)
                && !kind::is_reply(kind::WANG_SEPARATE_REQUEST)
        );
        assert_eq!(kind::name(0x33), Some("SeparateReply"));
        assert_eq!(kind::FLY_STEP_REPLY, kind::FLY_STEP_REQUEST + 1);
        assert_eq!((kind::FLY_STEP_REQUEST, kind::FLY_STEP_REPLY), (0x40, 0x41));
        assert!(kind::is_reply(kind::FLY_STEP_REPLY) && !kind::is_reply(kind::FLY_STEP_REQUEST));
        assert_eq!(kind::name(0x40), Some("FlyStepRequest"));
        assert_eq!(kind::name(0x41), Some("FlyStepReply"));
        assert_eq!(kind::name(0x42), None);
        assert_eq!(kind::name(0x80), None);
        assert_eq!(kind::name(kind::BEE_STEP_REPLY), Some("BeeStepReply"));
    }

    fn ant_requests<S: Scalar>() -> (AntPlanRequest<S>, AntParams<S>) {
        let bounds = Rect::new(v2(0.0, 0.0), v2(100.0, 100.0));
        let mut frame = WirePlanFrame::new(bounds);
        frame
            .neighbours
            .push(AntNeighbor {
                id: 7,
                pos: v2(11.0, 10.5),
                label: Label::Food,
                nest: 0,
                origin: 3,
                arrival: v2(80.0, 75.25),
            })
            .unwrap();
        frame
            .objects
            .push(AntObject::Obstacle(Surface {
                closest: v2(14.0, 9.0),
                normal: v2(-0.8, 0.6),
            }))
            .unwrap();
        frame
            .objects
            .push(AntObject::Food {
                id: 3,
                center: v2(80.0, 75.0),
                radius: S::from_f32(4.0),
            })
            .unwrap();
        let state = AntState::exploring(0, v2(10.0, 10.0), v2(0.6, 0.8));
        let ctx = StepCtx {
            seed: 42,
            agent: 1,
            step: 99,
        };
        (AntPlanRequest { state, frame, ctx }, AntParams::default())
    }

    fn ant_round_trip<S: Scalar + Serialize + DeserializeOwned>() {
        let (req, params) = ant_requests::<S>();
        assert_eq!(through_the_wire(1, &req), req);
        let reply = req.run(&params).unwrap();
        assert_eq!(through_the_wire(1, &reply), reply);

        let mut frame = WireResolveFrame::new(req.frame.bounds);
        frame.neighbours.push(v2(10.5, 10.5)).unwrap();
        frame.neighbours.push(v2(9.0, 11.0)).unwrap();
        frame
            .obstacles
            .push(Surface {
                closest: v2(10.5, 9.0),
                normal: v2(0.0, 1.0),
            })
            .unwrap();
        let req = AntResolveRequest {
            plan: reply.plan,
            frame,
        };
        assert_eq!(through_the_wire(2, &req), req);
        let reply = req.run(&params).unwrap();
        assert_eq!(through_the_wire(2, &reply), reply);
    }

    fn bee_round_trip<S: Scalar + Serialize + DeserializeOwned>() {
        let mut frame = WireBeeFrame::new(S::from_f32(0.25));
        for i in 0..3 {
            let d = i as f32;
            frame
                .neighbours
                .push(BeeNeighbor {
                    pos: v3(1.0 + d, 1.0, -d),
                    vel: v3(0.0, 0.1 * d, 1.0),
                    density: S::from_f32(0.05),
                })
                .unwrap();
        }
        frame.targets.push(v3(5.0, 1.0, 5.0)).unwrap();
        frame.goal = Some(v3(10.0, 1.0, 0.0));
        frame.obstacle = Some(ObstacleSense {
            point: v3(2.0, 1.0, 0.5),
            normal: v3(-1.0, 0.0, 0.0),
        });
        let req = BeeStepRequest {
            state: BeeState::new(v3(0.0, 1.0, 0.0), v3(1.0, 0.0, 0.0)),
            frame,
        };
        assert_eq!(through_the_wire(3, &req), req);
        let reply = req.run(&BeeParams::default()).unwrap();
        assert_eq!(through_the_wire(3, &reply), reply);
    }

    fn wang_round_trip<S: Scalar + Serialize + DeserializeOwned>() {
        let mut frame = AdvectFrame::new(v3(0.0, 0.6, 0.8));
        frame.boundary = Some(Boundary {
            point: v3(0.0, 0.0, 0.0),
            normal: v3(0.0, 1.0, 0.0),
            curvature: S::from_f32(0.5),
            axis: v3(1.0, 0.0, 0.0),
        });
        frame.lamp = Some(v3(3.0, 6.5, -1.0));
        let ctx = StepCtx {
            seed: 5,
            agent: 2,
            step: 40,
        };
        let req = AdvectRequest {
            state: WangState::new(v3(1.0, 0.5, 2.0)),
            frame,
            ctx,
        };
        assert_eq!(through_the_wire(4, &req), req);
        let params = WangParams::default();
        let reply = req.run(&params).unwrap();
        assert_eq!(through_the_wire(4, &reply), reply);
        let mut frame = WireSeparateFrame::new();
        frame
            .neighbours
            .push(Close {
                id: 9,
                pos: reply.moved.pos + v3(0.05, 0.0, 0.0),
            })
            .unwrap();
        let req = SeparateRequest {
            moved: reply.moved,
            frame,
            ctx,
        };
        assert_eq!(through_the_wire(5, &req), req);
        let reply = req.run(&params).unwrap();
        assert_eq!(reply.pushes, 1);
        assert_eq!(through_the_wire(5, &reply), reply);
    }

    fn fly_round_trip<S: Scalar + Serialize + DeserializeOwned>() {
        let mut frame = WireFlyFrame::<S>::new();
        for i in 0..3u32 {
            let d = i as f32;
            frame
                .neighbours
                .push(Neighbour {
                    id: 10 + i,
                    pos: v3(0.3 + d, 1.0, -d),
                    vel: v3(0.0, 0.1 * d, 1.0),
                })
                .unwrap();
        }
        frame.stimulus = Some(Stimulus {
            pos: v3(3.0, 1.0, 0.5),
            kind: STIMULUS_PREDATOR,
        });
        frame
            .surfaces
            .push(FlySurface {
                point: v3(0.0, 0.0, 0.0),
                normal: v3(0.0, 1.0, 0.0),
            })
            .unwrap();
        let req = FlyStepRequest {
            state: FlyState::new(v3(0.0, 1.0, 0.0), v3(1.0, 0.0, 0.0)),
            frame,
            ctx: StepCtx {
                seed: 5,
                agent: 2,
                step: 40,
            },
        };
        assert_eq!(through_the_wire(6, &req), req);
        let reply = req.run(&crate::fly::FlyParams::escape()).unwrap();
        assert!(reply.state.escaping); // the predator within r_res started an episode
        assert_eq!(through_the_wire(6, &reply), reply);
    }

    #[test]
    fn model_messages_round_trip_in_both_scalars() {
        ant_round_trip::<f32>();
        ant_round_trip::<Fx>();
        bee_round_trip::<f32>();
        bee_round_trip::<Fx>();
        wang_round_trip::<f32>();
        wang_round_trip::<Fx>();
        fly_round_trip::<f32>();
        fly_round_trip::<Fx>();
    }

    #[test]
    fn error_reply() {
        let e = Error::NonFinite {
            field: "state.pos",
            index: None,
        };
        let reply = ErrorReply::from(e);
        assert_eq!(reply, ErrorReply { code: 1 });
        assert_eq!(reply.name(), "NonFinite");
        assert_eq!(through_the_wire(9, &reply), reply);
        assert_eq!(ErrorReply { code: 200 }.name(), "unknown");
        let all = [
            Error::OutOfRange {
                field: "",
                index: None,
            },
            Error::Inconsistent {
                field: "",
                index: None,
            },
            Error::BadParam { field: "" },
            Error::BufferFull,
            Error::Oversize,
            Error::Cobs,
            Error::Truncated,
            Error::Crc {
                got: 0,
                expected: 0,
            },
            Error::Version { got: 0 },
            Error::UnknownKind { kind: 0 },
            Error::UnexpectedKind {
                got: 0,
                expected: 0,
            },
            Error::Payload,
            Error::NoSession,
            Error::ParamsMismatch { device: 1, host: 2 },
        ];
        for (i, e) in all.iter().enumerate() {
            let r = ErrorReply::new(e);
            assert_eq!(usize::from(r.code), i + 2);
            assert_ne!(r.name(), "unknown");
        }
    }

    #[test]
    fn a_reply_is_not_taken_for_another() {
        let mut line = [0u8; 16];
        let n = encode_message(4, &ErrorReply { code: 2 }, &mut line).unwrap();
        let mut body = line[..n - 1].to_vec();
        assert_eq!(
            crate::wire::decode_message::<AntResolveReply<f32>>(&mut body),
            Err(Error::UnexpectedKind {
                got: kind::ERROR_REPLY,
                expected: kind::ANT_RESOLVE_REPLY
            })
        );
    }

    // ---- pinned vectors (docs/protocol.md, section 8), computed with the Python reference ----

    /// Checks a pinned vector: the payload of `msg` is `payload`, its frame with sequence
    /// number `seq` is `frame` (both in hex), and it comes back from the wire unchanged.
    #[track_caller]
    fn pinned<M: Message + PartialEq + core::fmt::Debug>(
        msg: &M,
        seq: u16,
        payload: &str,
        frame: &str,
    ) {
        let mut buf = [0u8; MAX_PAYLOAD];
        assert_eq!(postcard::to_slice(msg, &mut buf).unwrap(), hex(payload));
        assert_eq!(frame_of(seq, msg), hex(frame));
        assert_eq!(through_the_wire(seq, msg), *msg);
    }

    /// The payload of [`vector_state`] in `f32` (vector 7), which vector 9 starts with.
    const STATE_F32: &str = "00 00 20 41 00 00 a0 41 00 00 80 3f 00 00 00 00 02 01 01
        00 00 b0 40 00 00 40 c0 01 00 00 00 3f 00 00 00 40 01 01 00 00 c0 bf
        00 01 01 ac 02 02";
    /// The payload of [`vector_state`] in fixed point (vector 8), which vector 9 starts with.
    const STATE_FX: &str = "80 80 50 80 80 a0 01 80 80 08 00 02 01 01 80 80 2c ff ff 17
        01 80 80 04 80 80 10 01 01 ff ff 0b 00 01 01 ac 02 02";

    fn vector_state<S: Scalar>() -> AntResolveReply<S> {
        AntResolveReply {
            state: AntState {
                pos: v2(10.0, 20.0),
                heading: v2(1.0, 0.0),
                label: Label::Nest,
                nest: 1,
                origin: 1,
                arrival: v2(5.5, -3.0),
                goal: Some(v2(0.5, 2.0)),
                follow: Some(Follow {
                    turn: Turn::Cw,
                    winding: S::from_f32(-1.5),
                }),
                motion: MotionState::Stop,
                stop: Some(StopTimer {
                    reason: StopReason::CollectingFood,
                    remaining: 300,
                    place: 2,
                }),
            },
        }
    }

    #[test]
    fn vector_6_error_reply() {
        let wire = frame_of(
            7,
            &ErrorReply {
                code: ErrorReply::NON_FINITE,
            },
        );
        assert_eq!(wire, hex("04 03 0f 07 04 01 81 be 00"));
    }

    #[test]
    fn vector_7_ant_resolve_reply_f32() {
        pinned(
            &vector_state::<f32>(),
            0x0100,
            STATE_F32,
            "03 03 13 02 01 01 03 20 41 01 03 a0 41 01 03 80 3f 01 01 01 04 02 01 01
                 01 03 b0 40 01 04 40 c0 01 01 01 02 3f 01 01 04 40 01 01 01 03 c0 bf
                 08 01 01 ac 02 02 56 ec 00",
        );
    }

    #[test]
    fn vector_8_ant_resolve_reply_fx() {
        pinned(
            &vector_state::<Fx>(),
            0x0100,
            STATE_FX,
            "03 03 13 0c 01 80 80 50 80 80 a0 01 80 80 08 16 02 01 01 80 80 2c ff ff 17
                 01 80 80 04 80 80 10 01 01 ff ff 0b 08 01 01 ac 02 02 f8 b0 00",
        );
    }

    /// Vector 9: a resolve request around vector 7's state, with one neighbour and one
    /// obstacle surface.
    fn vector_resolve_request<S: Scalar>() -> AntResolveRequest<S> {
        let mut frame = WireResolveFrame::new(Rect::new(v2(0.0, 0.0), v2(100.0, 100.0)));
        frame.neighbours.push(v2(12.0, 20.5)).unwrap();
        frame
            .obstacles
            .push(Surface {
                closest: v2(10.0, 21.5),
                normal: v2(0.0, -1.0),
            })
            .unwrap();
        AntResolveRequest {
            plan: AntPlan {
                state: vector_state::<S>().state,
                predicted: v2(10.0, 20.0),
            },
            frame,
        }
    }

    #[test]
    fn vector_9_ant_resolve_request_f32() {
        pinned(
            &vector_resolve_request::<f32>(),
            0x0102,
            &format!(
                "{STATE_F32}
                 00 00 20 41 00 00 a0 41
                 00 00 00 00 00 00 00 00 00 00 c8 42 00 00 c8 42
                 01 00 00 40 41 00 00 a4 41
                 01 00 00 20 41 00 00 ac 41 00 00 00 00 00 00 80 bf"
            ),
            "05 03 12 02 01 01 03 20 41 01 03 a0 41 01 03 80 3f 01 01 01 04 02 01 01
                 01 03 b0 40 01 04 40 c0 01 01 01 02 3f 01 01 04 40 01 01 01 03 c0 bf
                 06 01 01 ac 02 02 01 03 20 41 01 03 a0 41 01 01 01 01 01 01 01 01 01 03
                 c8 42 01 04 c8 42 01 01 03 40 41 01 04 a4 41 01 01 03 20 41 01 03 ac 41
                 01 01 01 01 01 05 80 bf 9d c9 00",
        );
    }

    #[test]
    fn vector_9_ant_resolve_request_fx() {
        pinned(
            &vector_resolve_request::<Fx>(),
            0x0102,
            &format!(
                "{STATE_FX}
                 80 80 50 80 80 a0 01
                 00 00 80 80 a0 06 80 80 a0 06
                 01 80 80 60 80 80 a4 01
                 01 80 80 50 80 80 ac 01 00 ff ff 07"
            ),
            "0f 03 12 02 01 80 80 50 80 80 a0 01 80 80 08 16 02 01 01 80 80 2c ff ff 17
                 01 80 80 04 80 80 10 01 01 ff ff 0b 0d 01 01 ac 02 02 80 80 50 80 80 a0 01
                 01 19 80 80 a0 06 80 80 a0 06 01 80 80 60 80 80 a4 01 01 80 80 50 80 80 ac
                 01 06 ff ff 07 39 0b 00",
        );
    }

    // ---- sizes ----

    /// A value whose postcard encoding is as long as the type allows.
    trait Widest: Scalar + Serialize + DeserializeOwned {
        fn widest() -> Self;
    }
    impl Widest for f32 {
        fn widest() -> Self {
            -1.0e30
        }
    }
    impl Widest for Fx {
        fn widest() -> Self {
            Fx::from_bits(i32::MIN) // zig-zag u32::MAX: a 5-byte varint
        }
    }

    fn w2<S: Widest>() -> Vec2<S> {
        Vec2::new(S::widest(), S::widest())
    }
    fn w3<S: Widest>() -> Vec3<S> {
        Vec3::new(S::widest(), S::widest(), S::widest())
    }
    fn wide_ant_state<S: Widest>() -> AntState<S> {
        AntState {
            pos: w2(),
            heading: w2(),
            label: Label::Nest,
            nest: u16::MAX,
            origin: u16::MAX,
            arrival: w2(),
            goal: Some(w2()),
            follow: Some(Follow {
                turn: Turn::Cw,
                winding: S::widest(),
            }),
            motion: MotionState::InteractEnvironment,
            stop: Some(StopTimer {
                reason: StopReason::DroppingFood,
                remaining: u16::MAX,
                place: u16::MAX,
            }),
        }
    }
    fn wide_bee_state<S: Widest>() -> BeeState<S> {
        BeeState {
            pos: w3(),
            vel: w3(),
            forward: w3(),
            density: S::widest(),
            avoiding: true,
            u0: w3(),
            roll: S::widest(),
            pitch: S::widest(),
        }
    }

    fn wide_wang_state<S: Widest>() -> WangState<S> {
        WangState {
            pos: w3(),
            vel: w3(),
        }
    }

    /// Payload lengths of the widest instance of every wang message: advect request and
    /// reply, separate request and reply.
    fn widest_wang_payloads<S: Widest>() -> [usize; 4] {
        let ctx = StepCtx {
            seed: u32::MAX,
            agent: u32::MAX,
            step: u32::MAX,
        };
        let frame = AdvectFrame {
            guide: w3(),
            boundary: Some(Boundary {
                point: w3(),
                normal: w3(),
                curvature: S::widest(),
                axis: w3(),
            }),
            lamp: Some(w3()),
        };
        let mut near = WireSeparateFrame::<S>::new();
        while near
            .neighbours
            .push(Close {
                id: u32::MAX,
                pos: w3(),
            })
            .is_ok()
        {}
        [
            payload_len(&AdvectRequest {
                state: wide_wang_state(),
                frame,
                ctx,
            }),
            payload_len(&AdvectReply {
                moved: wide_wang_state::<S>(),
            }),
            payload_len(&SeparateRequest {
                moved: wide_wang_state(),
                frame: near,
                ctx,
            }),
            payload_len(&SeparateReply {
                state: wide_wang_state::<S>(),
                pushes: u8::MAX,
            }),
        ]
    }

    #[test]
    fn widest_wang_messages_fit_max_wang_payload() {
        let f = widest_wang_payloads::<f32>();
        let x = widest_wang_payloads::<Fx>();
        assert_eq!(f, [105, 24, 176, 25]);
        assert_eq!(x, [127, 30, 206, 31]);
        assert_eq!(
            f.iter().chain(&x).max(),
            Some(&crate::wang::MAX_WANG_PAYLOAD)
        );
        assert_eq!(
            [f[1], f[3], x[1], x[3]].iter().max(),
            Some(&MAX_WANG_REPLY_PAYLOAD)
        );
        const { assert!(crate::wang::MAX_WANG_PAYLOAD <= MAX_PAYLOAD) };
        assert_eq!(MAX_WANG_FRAME, 214);
    }

    /// Payload lengths of the widest instance of both fly messages: step request and reply.
    fn widest_fly_payloads<S: Widest>() -> [usize; 2] {
        let ctx = StepCtx {
            seed: u32::MAX,
            agent: u32::MAX,
            step: u32::MAX,
        };
        let state = FlyState {
            pos: w3(),
            vel: w3(),
            escape_theta: S::widest(),
            escaping: true,
        };
        let mut frame = WireFlyFrame::<S>::new();
        while frame
            .neighbours
            .push(Neighbour {
                id: u32::MAX,
                pos: w3(),
                vel: w3(),
            })
            .is_ok()
        {}
        frame.stimulus = Some(Stimulus {
            pos: w3(),
            kind: u8::MAX,
        });
        while frame
            .surfaces
            .push(FlySurface {
                point: w3(),
                normal: w3(),
            })
            .is_ok()
        {}
        [
            payload_len(&FlyStepRequest { state, frame, ctx }),
            payload_len(&FlyStepReply {
                decision: FlyDecision {
                    pref: w3(),
                    infeasible: true,
                },
                state,
            }),
        ]
    }

    #[test]
    fn widest_fly_messages_fit_max_fly_payload() {
        let f = widest_fly_payloads::<f32>();
        let x = widest_fly_payloads::<Fx>();
        // Request: state 29 / 36, 1 + 16 neighbours of 29 / 35, stimulus 14 / 17,
        // 1 + 4 surfaces of 24 / 30, ctx 15. Reply: decision 13 / 16, state 29 / 36.
        assert_eq!(f, [620, 42]);
        assert_eq!(x, [750, 52]);
        assert_eq!(f.iter().chain(&x).max(), Some(&crate::fly::MAX_FLY_PAYLOAD));
        assert_eq!(f[1].max(x[1]), MAX_FLY_REPLY_PAYLOAD);
        const { assert!(crate::fly::MAX_FLY_PAYLOAD <= MAX_PAYLOAD) };
        assert_eq!(MAX_FLY_FRAME, 760);
        // The worst-case request frame (Fx, full lists) fits a MAX_FLY_FRAME buffer.
        let mut frame = WireFlyFrame::<Fx>::new();
        while frame
            .neighbours
            .push(Neighbour {
                id: u32::MAX,
                pos: w3(),
                vel: w3(),
            })
            .is_ok()
        {}
        let req = FlyStepRequest {
            state: FlyState::new(w3(), w3()),
            frame,
            ctx: StepCtx::default(),
        };
        assert!(frame_of(1, &req).len() <= MAX_FLY_FRAME);
        let _ = STIMULUS_TARGET;
    }

    /// Payload lengths of the widest instance of both li messages: step request and reply.
    fn widest_li_payloads<S: Widest>() -> [usize; 2] {
        let ctx = StepCtx {
            seed: u32::MAX,
            agent: u32::MAX,
            step: u32::MAX,
        };
        let state = LiState {
            pos: w3(),
            vel: w3(),
            waypoint: w3(),
            seg_start: w3(),
            age: u16::MAX,
        };
        let mut frame = WireLiFrame::<S>::new();
        while frame
            .neighbours
            .push(Neighbour {
                id: u32::MAX,
                pos: w3(),
                vel: w3(),
            })
            .is_ok()
        {}
        while frame
            .surfaces
            .push(FlySurface {
                point: w3(),
                normal: w3(),
            })
            .is_ok()
        {}
        let request = LiStepRequest { state, frame, ctx };
        // The worst case fits a device's buffer.
        assert!(frame_of(1, &request).len() <= MAX_LI_FRAME);
        [
            payload_len(&request),
            payload_len(&LiStepReply {
                decision: LiDecision {
                    pref: w3(),
                    proposals: u8::MAX,
                    accepted: true,
                    infeasible: true,
                },
                state,
            }),
        ]
    }

    #[test]
    fn widest_li_messages_fit_max_li_payload() {
        let f = widest_li_payloads::<f32>();
        let x = widest_li_payloads::<Fx>();
        // Request: state 51 / 63, 1 + 16 neighbours of 29 / 35, 1 + 4 surfaces of 24 / 30,
        // ctx 15. Reply: decision 15 / 18, state 51 / 63.
        assert_eq!(f, [628, 66]);
        assert_eq!(x, [760, 81]);
        assert_eq!(f.iter().chain(&x).max(), Some(&crate::li::MAX_LI_PAYLOAD));
        assert_eq!(f[1].max(x[1]), MAX_LI_REPLY_PAYLOAD);
        const { assert!(crate::li::MAX_LI_PAYLOAD <= MAX_PAYLOAD) };
        assert_eq!(MAX_LI_FRAME, 771);
    }

    /// Payload lengths of the widest instance of every message.
    fn widest_payloads<S: Widest>() -> [usize; 6] {
        let mut pf = WirePlanFrame::<S>::new(Rect::new(w2(), w2()));
        while pf
            .neighbours
            .push(AntNeighbor {
                id: u32::MAX,
                pos: w2(),
                label: Label::Nest,
                nest: u16::MAX,
                origin: u16::MAX,
                arrival: w2(),
            })
            .is_ok()
        {}
        // An obstacle (four scalars) is the widest object.
        while pf
            .objects
            .push(AntObject::Obstacle(Surface {
                closest: w2(),
                normal: w2(),
            }))
            .is_ok()
        {}
        let ctx = StepCtx {
            seed: u32::MAX,
            agent: u32::MAX,
            step: u32::MAX,
        };
        let plan = AntPlan {
            state: wide_ant_state::<S>(),
            predicted: w2(),
        };
        let mut rf = WireResolveFrame::new(Rect::new(w2(), w2()));
        while rf.neighbours.push(w2()).is_ok() {}
        while rf
            .obstacles
            .push(Surface {
                closest: w2(),
                normal: w2(),
            })
            .is_ok()
        {}
        let mut bf = WireBeeFrame::new(S::widest());
        while bf
            .neighbours
            .push(BeeNeighbor {
                pos: w3(),
                vel: w3(),
                density: S::widest(),
            })
            .is_ok()
        {}
        while bf.targets.push(w3()).is_ok() {}
        bf.goal = Some(w3());
        bf.obstacle = Some(ObstacleSense {
            point: w3(),
            normal: w3(),
        });
        let decision = BeeDecision {
            accel: w3(),
            velocity: w3(),
            roll: S::widest(),
            pitch: S::widest(),
            avoiding: true,
            density: S::widest(),
        };
        [
            payload_len(&AntPlanRequest {
                state: wide_ant_state(),
                frame: pf,
                ctx,
            }),
            payload_len(&AntPlanReply { plan }),
            payload_len(&AntResolveRequest { plan, frame: rf }),
            payload_len(&AntResolveReply {
                state: wide_ant_state::<S>(),
            }),
            payload_len(&BeeStepRequest {
                state: wide_bee_state(),
                frame: bf,
            }),
            payload_len(&BeeStepReply {
                decision,
                state: wide_bee_state(),
            }),
        ]
    }

    #[test]
    fn widest_messages_fit_max_payload() {
        // [plan req, plan reply, resolve req, resolve reply, bee req, bee reply]
        let f = widest_payloads::<f32>();
        let x = widest_payloads::<Fx>();
        assert_eq!(f, [380, 63, 241, 55, 745, 98]);
        assert_eq!(x, [441, 74, 296, 64, 930, 122]);
        assert_eq!(f[..4].iter().chain(&x[..4]).max(), Some(&MAX_ANT_PAYLOAD));
        assert_eq!(f[4..].iter().chain(&x[4..]).max(), Some(&MAX_BEE_PAYLOAD));
        assert_eq!(f.iter().chain(&x).max(), Some(&MAX_PAYLOAD));
        assert_eq!(
            [f[1], f[3]].iter().chain(&[x[1], x[3]]).max(),
            Some(&MAX_ANT_REPLY_PAYLOAD)
        );
        assert_eq!(f[5].max(x[5]), MAX_BEE_REPLY_PAYLOAD);
        assert_eq!(MAX_FRAME, MAX_PAYLOAD + 6 + 4 + 1);
        assert_eq!((MAX_ANT_FRAME, MAX_BEE_FRAME, MAX_FRAME), (450, 941, 941));
        assert_eq!(payload_len(&ErrorReply { code: u8::MAX }), 1);
        // And such a frame really fits a MAX_FRAME buffer (no zero byte: worst COBS case).
        let mut out = [0u8; MAX_FRAME];
        let raw = [0x55u8; MAX_PAYLOAD];
        let n = encode_frame(0x55, 0x5555, &crate::wire::frame::Raw(&raw), &mut out).unwrap();
        assert_eq!(n, MAX_FRAME);
    }
}
