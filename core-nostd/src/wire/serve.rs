//! How a device serves a model it knows only through its traits: the [`Controller`]
//! description (kind, capacities, largest messages) and [`Serve`], the dispatch of a request
//! kind to the phase whose request it is, written once for every tuple of phases.

use serde::Serialize;

use super::frame::{decode_payload, max_frame_len};
use super::session::{Capacities, ControllerKind, MAX_SESSION_PAYLOAD};
use super::{Message, encode_message};
use crate::model::{Model, Phase};
use crate::{Checked, Error, Result};

const fn max(a: usize, b: usize) -> usize {
    if a > b { a } else { b }
}

/// A model as a device serves it on the wire: implemented next to each model (for
/// [`AntParams<S>`](crate::ant::AntParams), [`BeeParams<S>`](crate::bee::BeeParams),
/// [`WangParams<S>`](crate::wang::WangParams) and [`FlyParams<S>`](crate::fly::FlyParams)), as a
/// description only; what a request does is the model's [`Phase::run`], dispatched by
/// [`Serve`]. The implementing type *is* the parameter set: its postcard encoding is what
/// [`params_hash`](super::params_hash) hashes.
pub trait Controller: Model<Phases: Serve<Self>> + Serialize {
    /// Which controller it is ([`Identity::controller`](super::Identity::controller)).
    const KIND: ControllerKind;
    /// The sensor-frame list capacities of its requests
    /// ([`Identity::capacities`](super::Identity::capacities)).
    const CAPACITIES: Capacities;
    /// Its largest request payload, for either scalar, with full frames (pinned by a test).
    const MAX_REQUEST_PAYLOAD: usize;
    /// Its largest reply payload, for either scalar (pinned by a test).
    const MAX_REPLY_PAYLOAD: usize;
    /// The longest frame it receives (its largest request, delimiter included): the `RX`
    /// that receives every request.
    const MAX_REQUEST_FRAME: usize = max_frame_len(Self::MAX_REQUEST_PAYLOAD);
    /// The longest frame it sends (its largest reply or any session reply, delimiter
    /// included): the smallest `TX` a [`DeviceEndpoint`](super::DeviceEndpoint) accepts.
    const MAX_REPLY_FRAME: usize = max_frame_len(max(MAX_SESSION_PAYLOAD, Self::MAX_REPLY_PAYLOAD));
}

/// The phases of model `M` served by request kind: implemented for every tuple of
/// [`Phase`]s whose requests and replies are [`Message`]s.
pub trait Serve<M: Model> {
    /// Whether one of the phases has requests of `kind`.
    fn serves(kind: u8) -> bool;
    /// Whether `kind` is the reply of one of the phases.
    fn replies(kind: u8) -> bool;
    /// Serves one request of a kind it [`serves`](Serve::serves): decodes `payload`, runs the
    /// phase and encodes the reply frame (sequence number `seq`) into `out`, returning its
    /// length.
    ///
    /// # Errors
    ///
    /// [`Error::Payload`] if the payload does not decode, [`Error::UnknownKind`] for a kind
    /// no phase has, the phase's error for refused input, [`Error::BufferFull`] if `out` is
    /// too small.
    fn serve(
        params: &Checked<M>,
        kind: u8,
        seq: u16,
        payload: &[u8],
        out: &mut [u8],
    ) -> Result<usize>;
}

macro_rules! serve {
    ($($p:ident),+) => {
        impl<M: Model, $($p),+> Serve<M> for ($($p,)+)
        where
            $($p: Phase<M, Request: Message, Reply: Message>,)+
        {
            fn serves(kind: u8) -> bool {
                $(kind == <$p::Request as Message>::KIND)||+
            }
            fn replies(kind: u8) -> bool {
                $(kind == <$p::Reply as Message>::KIND)||+
            }
            fn serve(
                params: &Checked<M>,
                kind: u8,
                seq: u16,
                payload: &[u8],
                out: &mut [u8],
            ) -> Result<usize> {
                $(
                    if kind == <$p::Request as Message>::KIND {
                        let request: $p::Request = decode_payload(payload)?;
                        return encode_message(seq, &$p::run(params, &request)?, out);
                    }
                )+
                Err(Error::UnknownKind { kind })
            }
        }
    };
}
serve!(A);
serve!(A, B);
serve!(A, B, C);
serve!(A, B, C, D);
