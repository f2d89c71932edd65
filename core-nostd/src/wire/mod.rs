//! The wire codec shared by firmware and host (feature `serde`).
//!
//! A frame on the line is
//!
//! ```text
//! COBS( version:u8 ‖ kind:u8 ‖ seq:u16 LE ‖ postcard payload ‖ CRC-16 LE ) ‖ 0x00
//! ```
//!
//! * the 4-byte [`Header`] says which protocol version, which message ([`Message::KIND`]) and
//!   which request ([`Header::seq`]);
//! * the payload is the message in [postcard](https://postcard.jamesmunns.com/) encoding;
//! * [`CRC16`] (CRC-16/IBM-3740, a.k.a. CCITT-FALSE) covers header and payload;
//! * COBS removes every `0x00`, so `0x00` only ever ends a frame, and a receiver that lost
//!   track resynchronises at the next one.
//!
//! Overhead: 8 bytes for payloads up to 248 bytes (4 header + 2 CRC + 1 COBS + 1 delimiter),
//! see [`max_frame_len`]. `docs/protocol.md` specifies every byte, with worked examples that
//! the tests pin.
//!
//! Sending: [`encode_message`] (or [`encode_frame`] for any `Serialize` payload) writes a whole
//! frame into a slice. Receiving: [`Accumulator`] eats bytes in chunks of any size and reports
//! one [`Event`] per frame, good or dropped, with [`Stats`]; [`decode_frame`] checks a single
//! frame that is already delimited. Nothing here allocates or panics on any input.
//!
//! ```
//! use swarm_core::wire::{self, Accumulator, Event, Ping};
//!
//! let mut line = [0u8; 32];
//! let n = wire::encode_message(1, &Ping { nonce: 42 }, &mut line).unwrap();
//!
//! let mut rx = Accumulator::<32>::new();
//! let (event, _rest) = rx.feed(&line[..n]).unwrap();
//! let Event::Frame(frame) = event else { panic!("dropped: {event:?}") };
//! assert_eq!(frame.header.seq, 1);
//! assert_eq!(frame.message::<Ping>(), Ok(Ping { nonce: 42 }));
//! ```
//!
//! # The session
//!
//! On top of the frames, a host talks to a device in sessions (`docs/protocol.md`, section 10):
//!
//! 1. [`Hello`] → [`Identity`]: the device says what it runs (controller, scalar, math
//!    backend, capacities, longest frame, receive buffer, [`params_hash`] of its parameters);
//!    the host compares it with what it expects ([`Identity::check`], an error naming every
//!    difference) and stops there if it differs, then sizes its pipelining window from the
//!    receive buffer ([`Identity::window`]);
//! 2. [`Configure`] → [`Configured`]: the host opens a session (the device checks the
//!    parameter hash once more);
//! 3. controller requests ([`AntPlanRequest`], [`AntResolveRequest`], [`BeeStepRequest`],
//!    [`AdvectRequest`], [`SeparateRequest`], [`FlyStepRequest`], [`LiStepRequest`]),
//!    pipelined, each answered by its reply or an [`ErrorReply`] with the same sequence
//!    number; [`Ping`] → [`Pong`] and [`StatsRequest`] → [`DeviceStats`] at any time.
//!
//! The device side is [`DeviceEndpoint`] (aliases [`AntDevice`], [`BeeDevice`],
//! [`WangDevice`], [`FlyDevice`], [`LiDevice`]): bytes in,
//! reply frames out, fixed buffers, for firmware and for a soft device on a host alike.
//!
//! ```
//! use swarm_core::ant::AntParams;
//! use swarm_core::wire::{self, AntDevice, Configure, Hello, Identity, MAX_ANT_FRAME, Ping};
//!
//! let params = AntParams::<f32>::default();
//! let mut device = AntDevice::<f32>::new(params, "soft-ant").unwrap();
//!
//! // Host: Hello, Configure and a Ping, pipelined in one write.
//! let mut line = [0u8; 64];
//! let mut len = 0;
//! len += wire::encode_message(1, &Hello, &mut line[len..]).unwrap();
//! let hash = wire::params_hash(&params).unwrap();
//! let configure = Configure { session: 7, params_hash: hash, reset_stats: true };
//! len += wire::encode_message(2, &configure, &mut line[len..]).unwrap();
//! len += wire::encode_message(3, &Ping { nonce: 9 }, &mut line[len..]).unwrap();
//!
//! // Device: three replies, in order.
//! let mut replies = Vec::new();
//! device.serve(&line[..len], |r| { replies.push(r.to_vec()); Ok::<_, ()>(()) }).unwrap();
//! assert_eq!(replies.len(), 3);
//!
//! // Host: check the identity.
//! let mut first = replies[0].clone();
//! let (header, identity) = wire::decode_message::<Identity>(&mut first[..replies[0].len() - 1]).unwrap();
//! assert_eq!(header.seq, 1);
//! let expected = Identity::of(&params, MAX_ANT_FRAME, "").unwrap();
//! identity.check(&expected).unwrap();
//! ```

mod accumulator;
mod endpoint;
mod frame;
mod header;
mod message;
mod serve;
mod session;
#[cfg(test)]
mod test_util;
#[cfg(test)]
mod tests;

pub use accumulator::{Accumulator, Event, Stats};
pub use endpoint::{DeviceEndpoint, Endpoint, SessionState};
pub use frame::{
    CRC_LEN, CRC16, CrcImpl, Frame, MIN_RAW_LEN, decode_frame, decode_payload, encode_frame,
    max_frame_len,
};
pub use header::{HEADER_LEN, Header, PROTOCOL_VERSION};
pub use message::{ErrorReply, MAX_FRAME, MAX_PAYLOAD, kind};
pub use serve::{Controller, Serve};
// The built-in models' messages and devices, defined in their folders, re-exported here where
// a protocol user looks for them.
pub use crate::ant::{
    AntDevice, AntPlanReply, AntPlanRequest, AntResolveReply, AntResolveRequest, MAX_ANT_FRAME,
    MAX_ANT_PAYLOAD, MAX_ANT_REPLY_FRAME, MAX_ANT_REPLY_PAYLOAD, WIRE_ANT_NEIGHBOURS,
    WIRE_ANT_OBJECTS, WirePlanFrame, WireResolveFrame,
};
pub use crate::bee::{
    BeeDevice, BeeStepReply, BeeStepRequest, MAX_BEE_FRAME, MAX_BEE_PAYLOAD, MAX_BEE_REPLY_FRAME,
    MAX_BEE_REPLY_PAYLOAD, WIRE_BEE_NEIGHBOURS, WIRE_BEE_TARGETS, WireBeeFrame,
};
pub use crate::fly::{
    FlyDevice, FlyStepReply, FlyStepRequest, MAX_FLY_FRAME, MAX_FLY_PAYLOAD, MAX_FLY_REPLY_FRAME,
    MAX_FLY_REPLY_PAYLOAD, WIRE_FLY_NEIGHBOURS, WIRE_FLY_SURFACES, WireFlyFrame,
};
pub use crate::li::{
    LiDevice, LiStepReply, LiStepRequest, MAX_LI_FRAME, MAX_LI_PAYLOAD, MAX_LI_REPLY_FRAME,
    MAX_LI_REPLY_PAYLOAD, WIRE_LI_NEIGHBOURS, WIRE_LI_SURFACES, WireLiFrame,
};
pub use crate::wang::{
    AdvectReply, AdvectRequest, MAX_WANG_FRAME, MAX_WANG_PAYLOAD, MAX_WANG_REPLY_FRAME,
    MAX_WANG_REPLY_PAYLOAD, SeparateReply, SeparateRequest, WIRE_WANG_NEIGHBOURS, WangDevice,
    WireSeparateFrame,
};
pub use session::{
    Capacities, Configure, Configured, ControllerKind, DEVICE_NAME_LEN, DeviceName, DeviceStats,
    Difference, FNV1A64_OFFSET, FNV1A64_PRIME, HandshakeMismatch, Hello, Identity,
    MAX_SESSION_FRAME, MAX_SESSION_PAYLOAD, Ping, Pong, StatsRequest, device_name, fnv1a64,
    params_hash,
};

use crate::Result;

/// A message type of the protocol: a postcard-serializable value with its own kind byte.
///
/// Every message type has a distinct [`KIND`](Message::KIND); it travels in the frame header,
/// so a receiver knows what the payload is before decoding it.
pub trait Message: serde::Serialize + serde::de::DeserializeOwned {
    /// The header kind byte of this message type.
    const KIND: u8;
}

/// What a message type must be: postcard-encodable both ways (implemented for every such
/// type; the bound [`message_kinds!`](crate::message_kinds) writes without naming serde).
pub trait Encodable: serde::Serialize + serde::de::DeserializeOwned {}
impl<T: serde::Serialize + serde::de::DeserializeOwned> Encodable for T {}

/// Implements [`Message`](crate::wire::Message) for message types generic over their scalar,
/// from `Type = KIND;` lines: a model's requests and replies.
///
/// ```
/// #[derive(serde::Serialize, serde::Deserialize)]
/// struct Hop<S> { height: S }
/// swarm_core::message_kinds! { Hop = 0x90; }
/// assert_eq!(<Hop<f32> as swarm_core::wire::Message>::KIND, 0x90);
/// ```
///
/// The kinds are checked at compile time ([`check_model_kinds`]): two messages of one
/// invocation never share a kind,
///
/// ```compile_fail
/// #[derive(serde::Serialize, serde::Deserialize)]
/// struct Up<S> { by: S }
/// #[derive(serde::Serialize, serde::Deserialize)]
/// struct Down<S> { by: S }
/// swarm_core::message_kinds! { Up = 0x90; Down = 0x90; } // error: two messages share a kind
/// ```
///
/// and none takes a kind of the session protocol (`0x00-0x0F`, see [`kind`]):
///
/// ```compile_fail
/// #[derive(serde::Serialize, serde::Deserialize)]
/// struct Hop<S> { height: S }
/// swarm_core::message_kinds! { Hop = swarm_core::wire::kind::PING; } // error: a session kind
/// ```
#[macro_export]
macro_rules! message_kinds {
    ($($ty:ident = $kind:expr;)*) => {
        $(
            impl<S> $crate::wire::Message for $ty<S>
            where
                $ty<S>: $crate::wire::Encodable,
            {
                const KIND: u8 = $kind;
            }
        )*
        const _: () = $crate::wire::check_model_kinds(&[$($kind),*]);
    };
}

/// The compile-time check of [`message_kinds!`](crate::message_kinds) (it writes
/// `const _: () = check_model_kinds(&[...]);`): panics, so fails the build, if two of `kinds`
/// are equal or one is a kind of the session protocol (`0x00-0x0F`: never used, the session
/// messages, their reserved range and [`ErrorReply`]; see [`kind`]).
pub const fn check_model_kinds(kinds: &[u8]) {
    let mut i = 0;
    while i < kinds.len() {
        // ERROR_REPLY (0x0F) ends the session protocol's range.
        assert!(
            kinds[i] > kind::ERROR_REPLY,
            "message_kinds!: a kind of the session protocol (0x00-0x0F)"
        );
        let mut j = i + 1;
        while j < kinds.len() {
            assert!(
                kinds[i] != kinds[j],
                "message_kinds!: two messages share a kind"
            );
            j += 1;
        }
        i += 1;
    }
}

/// Encodes `msg` as a complete frame (kind `M::KIND`, sequence number `seq`) into `out` and
/// returns the frame's length, trailing `0x00` included. See [`encode_frame`].
pub fn encode_message<M: Message>(seq: u16, msg: &M, out: &mut [u8]) -> Result<usize> {
    encode_frame(M::KIND, seq, msg, out)
}

/// Decodes one delimited frame (the bytes between two `0x00`, decoded in place) as message
/// `M`, returning its header too. Errors as [`decode_frame`], then
/// [`Error::UnexpectedKind`](crate::Error::UnexpectedKind) and
/// [`Error::Payload`](crate::Error::Payload) as [`Frame::message`].
pub fn decode_message<M: Message>(frame: &mut [u8]) -> Result<(Header, M)> {
    let frame = decode_frame(frame)?;
    Ok((frame.header, frame.message()?))
}
