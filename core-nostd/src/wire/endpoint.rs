//! The device side of the protocol: a `no_std` state machine that eats bytes and produces
//! reply frames, with fixed buffers.

use super::accumulator::{Accumulator, Event};
use super::frame::decode_payload;
use super::header::Header;
use super::message::{ErrorReply, kind};
use super::serve::{Controller, Serve};
use super::session::{
    Configure, Configured, DeviceName, DeviceStats, Identity, MAX_SESSION_FRAME, Ping, Pong,
    device_name, params_hash,
};
use super::{Message, encode_message};
use crate::{Checked, Error, Result, Scalar};

/// Where a device's session stands.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum SessionState {
    /// No `Hello` yet (after power-up).
    #[default]
    Idle,
    /// `Hello` answered; waiting for `Configure`.
    Greeted,
    /// `Configure` accepted: controller requests are served.
    Open {
        /// The host's session id.
        session: u32,
    },
}

/// The session-layer counters (the link counters live in the accumulator).
#[derive(Clone, Copy, Debug, Default)]
struct Counters {
    requests: u32,
    replies: u32,
    errors: u32,
    decode_errors: u32,
    ignored: u32,
}

fn bump(c: &mut u32) {
    *c = c.saturating_add(1);
}

/// What a received frame asks of the session layer, once its payload is decoded (owned, so
/// the receive buffer is free again).
enum Todo {
    /// Nothing to send.
    Nothing,
    /// A reply of this length is in the send buffer.
    Sent(usize),
    /// Answer with this error.
    Fail(Header, Error),
    Hello(Header),
    Configure(Header, Configure),
    Ping(Header, Ping),
    Stats(Header),
}

/// Everything but the receiver: split off so that a frame borrowed from the receiver can be
/// served while the rest is mutated.
struct Core<C, const TX: usize> {
    params: Checked<C>,
    params_hash: u64,
    name: DeviceName,
    max_frame: u16,
    rx_buffer: u32,
    tx: [u8; TX],
    state: SessionState,
    counters: Counters,
}

impl<C: Controller, const TX: usize> Core<C, TX> {
    /// Encodes `msg` as the reply to `seq`; an [`ErrorReply`] if it does not fit.
    fn reply<M: Message>(&mut self, seq: u16, msg: &M) -> Todo {
        match encode_message(seq, msg, &mut self.tx) {
            Ok(n) => {
                bump(&mut self.counters.replies);
                Todo::Sent(n)
            }
            Err(e) => self.error(seq, &e),
        }
    }

    /// Encodes an [`ErrorReply`] for `error` as the reply to `seq`.
    fn error(&mut self, seq: u16, error: &Error) -> Todo {
        match encode_message(seq, &ErrorReply::new(error), &mut self.tx) {
            Ok(n) => {
                bump(&mut self.counters.errors);
                Todo::Sent(n)
            }
            // Unreachable: `new` checks at compile time that TX holds an ErrorReply.
            Err(_) => Todo::Nothing,
        }
    }

    /// Drops a frame that is never answered ([`kind::never_answered`]), counting it.
    fn ignore(&mut self) -> Todo {
        bump(&mut self.counters.ignored);
        Todo::Nothing
    }

    /// Handles a CRC-valid frame of another protocol version (its header: the payload is
    /// never looked at).
    fn on_foreign(&mut self, h: Header) -> Todo {
        if kind::never_answered(h.kind) {
            return self.ignore();
        }
        Todo::Fail(h, Error::Version { got: h.version })
    }

    /// Handles an intact frame of this protocol version.
    #[cfg_attr(feature = "small", inline(never))]
    fn on_frame(&mut self, header: Header, payload: &[u8]) -> Todo {
        bump(&mut self.counters.requests);
        let seq = header.seq;
        let decoded = match header.kind {
            kind::HELLO => decode_payload::<super::Hello>(payload).map(|_| Todo::Hello(header)),
            kind::CONFIGURE => decode_payload(payload).map(|c| Todo::Configure(header, c)),
            kind::PING => decode_payload(payload).map(|p| Todo::Ping(header, p)),
            kind::STATS_REQUEST => {
                decode_payload::<super::StatsRequest>(payload).map(|_| Todo::Stats(header))
            }
            k if kind::never_answered(k) || C::Phases::replies(k) => return self.ignore(),
            k if !C::Phases::serves(k) => Err(Error::UnknownKind { kind: k }),
            _ if !matches!(self.state, SessionState::Open { .. }) => {
                return Todo::Fail(header, Error::NoSession);
            }
            k => match C::Phases::serve(&self.params, k, seq, payload, &mut self.tx) {
                Ok(n) => {
                    bump(&mut self.counters.replies);
                    return Todo::Sent(n);
                }
                Err(e) => Err(e),
            },
        };
        decoded.unwrap_or_else(|e| {
            if matches!(e, Error::Payload | Error::UnknownKind { .. }) {
                bump(&mut self.counters.decode_errors);
            }
            Todo::Fail(header, e)
        })
    }
}

/// The device endpoint: feed it the bytes from the line, send what it returns.
///
/// * `C`: the controller and its parameters ([`AntParams<S>`](crate::ant::AntParams), [`BeeParams<S>`](crate::bee::BeeParams), or any
///   [`Controller`]);
/// * `RX`: the receive buffer, the longest frame accepted without its delimiter
///   ([`Controller::MAX_REQUEST_FRAME`] receives every request; at least
///   [`MAX_SESSION_FRAME`]);
/// * `TX`: the send buffer, at least [`Controller::MAX_REPLY_FRAME`] and
///   [`MAX_SESSION_FRAME`] (both checked at compile time).
///
/// [`AntDevice`](crate::ant::AntDevice), [`BeeDevice`](crate::bee::BeeDevice),
/// [`WangDevice`](crate::wang::WangDevice), [`FlyDevice`](crate::fly::FlyDevice) and
/// [`LiDevice`](crate::li::LiDevice) pick both
/// for you.
///
/// Behaviour (`docs/protocol.md`, section 10, is the normative version):
///
/// * every intact request frame (COBS, length and CRC good) gets exactly one reply, with the
///   request's sequence number, in the order the requests arrived; a request the device
///   cannot serve gets an [`ErrorReply`];
/// * garbage is skipped up to the next `0x00`; frames with a bad CRC, bad COBS, too short or
///   too long (more than `RX` bytes) are dropped unanswered and counted;
/// * a reply is never answered: an intact frame of kind `0x00` or of a reply kind
///   ([`kind::never_answered`]; for this version also the controller's own reply kinds), of
///   any protocol version, is dropped unanswered and counted in
///   [`DeviceStats::ignored`];
/// * a CRC-valid frame of another protocol version of any other kind is answered with
///   [`ErrorReply::VERSION`];
/// * controller requests are refused with [`ErrorReply::NO_SESSION`] until `Hello` and
///   `Configure`;
/// * it keeps no per-request state: a repeated request (a host's retry) is served again, and
///   gives the same reply bytes.
///
/// Work is bounded: O(1) per byte, plus at most one decode, one controller call and one
/// encode per frame. Nothing panics or allocates, whatever the bytes.
///
/// ```
/// use swarm_core::ant::AntParams;
/// use swarm_core::wire::{self, AntDevice, Event, Hello, Identity, Accumulator};
///
/// let mut device = AntDevice::<f32>::new(AntParams::default(), "ant-1").unwrap();
/// let mut line = [0u8; 16];
/// let n = wire::encode_message(1, &Hello, &mut line).unwrap();
///
/// let mut host_rx = Accumulator::<128>::new();
/// let mut replies = 0;
/// device.serve(&line[..n], |reply| {
///     let Some((Event::Frame(frame), _)) = host_rx.feed(reply) else { panic!() };
///     let identity: Identity = frame.message().unwrap();
///     assert_eq!(identity.name, "ant-1");
///     replies += 1;
///     Ok::<(), core::convert::Infallible>(())
/// }).unwrap();
/// assert_eq!(replies, 1);
/// ```
pub struct DeviceEndpoint<C, const RX: usize, const TX: usize> {
    rx: Accumulator<RX>,
    core: Core<C, TX>,
}

impl<C: Controller, const RX: usize, const TX: usize> DeviceEndpoint<C, RX, TX> {
    /// A device running `params` (validated here, once), reporting `name` in its
    /// [`Identity`]. It starts [`SessionState::Idle`].
    ///
    /// `TX` below `C::MAX_REPLY_FRAME` or [`MAX_SESSION_FRAME`], or `RX` below
    /// [`MAX_SESSION_FRAME`], is a compile-time error:
    ///
    /// ```compile_fail
    /// use swarm_core::ant::AntParams;
    /// use swarm_core::wire::DeviceEndpoint;
    /// let d = DeviceEndpoint::<AntParams<f32>, 450, 16>::new(AntParams::default(), "x");
    /// ```
    ///
    /// # Errors
    ///
    /// The parameters' validation error ([`Error::BadParam`]), or [`Error::BadParam`]
    /// (`"name"`) for a name longer than [`DEVICE_NAME_LEN`](super::DEVICE_NAME_LEN) bytes.
    pub fn new(params: C, name: &str) -> Result<Self> {
        const {
            assert!(
                TX >= C::MAX_REPLY_FRAME && TX >= MAX_SESSION_FRAME,
                "DeviceEndpoint: TX must hold the controller's longest reply (C::MAX_REPLY_FRAME) and every session reply (MAX_SESSION_FRAME)"
            );
            assert!(
                RX >= MAX_SESSION_FRAME,
                "DeviceEndpoint: RX must receive every session request (MAX_SESSION_FRAME)"
            );
        }
        params.validate()?;
        let params_hash = params_hash(&params)?;
        Ok(DeviceEndpoint {
            rx: Accumulator::new(),
            core: Core {
                params: Checked::assume_valid(params),
                params_hash,
                name: device_name(name)?,
                max_frame: u16::try_from(RX.saturating_add(1)).unwrap_or(u16::MAX),
                rx_buffer: 0,
                tx: [0; TX],
                state: SessionState::Idle,
                counters: Counters::default(),
            },
        })
    }

    /// Reports `bytes` as [`Identity::rx_buffer`]: how much of further requests the device
    /// takes in while it computes a reply (its receive ring, or the UART's hardware FIFO when
    /// it polls; `u32::MAX` for no limit). A new endpoint reports 0: a host then sends one
    /// request at a time.
    pub fn set_rx_buffer(&mut self, bytes: u32) {
        self.core.rx_buffer = bytes;
    }

    /// Feeds bytes until the first reply. Returns `None` when every byte was absorbed without
    /// producing a reply, or the reply frame (borrowing the endpoint's send buffer, delimiter
    /// included) and the bytes not yet fed: send the reply, then call again with those.
    ///
    /// ```
    /// # use swarm_core::{ant::AntParams, wire::AntDevice};
    /// # let mut device = AntDevice::<f32>::new(AntParams::default(), "d").unwrap();
    /// # let mut sent = Vec::new();
    /// let mut input: &[u8] = b"\x00 any bytes from the line \x00";
    /// while let Some((reply, rest)) = device.feed(input) {
    ///     sent.extend_from_slice(reply); // e.g. uart.write_all(reply)
    ///     input = rest;
    /// }
    /// # assert!(sent.is_empty());
    /// ```
    pub fn feed<'a, 'b>(&'a mut self, mut input: &'b [u8]) -> Option<(&'a [u8], &'b [u8])> {
        loop {
            let (event, rest) = self.rx.feed(input)?;
            input = rest;
            let todo = match event {
                Event::Frame(frame) => self.core.on_frame(frame.header, frame.payload),
                Event::Dropped {
                    error: Error::Version { .. },
                    ..
                } => match self.rx.foreign_header() {
                    Some(h) => self.core.on_foreign(h),
                    None => Todo::Nothing,
                },
                Event::Dropped { .. } => Todo::Nothing,
            };
            if let Some(n) = self.finish(todo) {
                return Some((self.core.tx.get(..n).unwrap_or_default(), input));
            }
        }
    }

    /// Feeds one byte: `Some(reply)` when it completed a request (for byte-wise UART loops).
    pub fn push(&mut self, byte: u8) -> Option<&[u8]> {
        self.feed(core::slice::from_ref(&byte))
            .map(|(reply, _)| reply)
    }

    /// Feeds `input` whole and hands every reply, in order, to `tx` (e.g.
    /// `|reply| uart.write_all(reply)` with an `embedded_io::Write`, or a `Vec` on a host).
    ///
    /// # Errors
    ///
    /// The first error of `tx`; the bytes of `input` after the request it answered are then
    /// not fed.
    pub fn serve<E>(
        &mut self,
        mut input: &[u8],
        mut tx: impl FnMut(&[u8]) -> core::result::Result<(), E>,
    ) -> core::result::Result<(), E> {
        while let Some((reply, rest)) = self.feed(input) {
            tx(reply)?;
            input = rest;
        }
        Ok(())
    }

    /// Runs the session part of a frame's handling (what needs the receiver too).
    fn finish(&mut self, todo: Todo) -> Option<usize> {
        let core = &mut self.core;
        let done = match todo {
            Todo::Nothing => return None,
            Todo::Sent(n) => return Some(n),
            Todo::Fail(h, e) => core.error(h.seq, &e),
            Todo::Hello(h) => {
                core.state = SessionState::Greeted;
                let identity = self.identity();
                self.core.reply(h.seq, &identity)
            }
            Todo::Configure(h, c) => self.configure(h, c),
            Todo::Ping(h, p) => core.reply(h.seq, &Pong { nonce: p.nonce }),
            Todo::Stats(h) => {
                let stats = self.stats();
                self.core.reply(h.seq, &stats)
            }
        };
        match done {
            Todo::Sent(n) => Some(n),
            _ => None,
        }
    }

    /// Handles a `Configure` (10.3).
    fn configure(&mut self, h: Header, c: Configure) -> Todo {
        let core = &mut self.core;
        match core.state {
            SessionState::Idle => core.error(h.seq, &Error::NoSession),
            _ if c.params_hash != core.params_hash => {
                core.state = SessionState::Greeted;
                let e = Error::ParamsMismatch {
                    device: core.params_hash,
                    host: c.params_hash,
                };
                core.error(h.seq, &e)
            }
            _ => {
                core.state = SessionState::Open { session: c.session };
                let done = core.reply(h.seq, &Configured { session: c.session });
                // After the reply, so that neither the Configure nor its reply is counted.
                if c.reset_stats {
                    self.reset_stats();
                }
                done
            }
        }
    }

    /// What the device answers to `Hello`.
    pub fn identity(&self) -> Identity {
        let c = &self.core;
        Identity {
            protocol: super::PROTOCOL_VERSION,
            controller: C::KIND,
            scalar: <C::Scalar as Scalar>::KIND,
            math: <C::Scalar as Scalar>::MATH,
            capacities: C::CAPACITIES,
            max_frame: c.max_frame,
            rx_buffer: c.rx_buffer,
            params_hash: c.params_hash,
            name: c.name.clone(),
        }
    }

    /// The counters, as a `StatsRequest` would report them now.
    pub fn stats(&self) -> DeviceStats {
        let c = &self.core.counters;
        DeviceStats {
            link: self.rx.stats(),
            requests: c.requests,
            replies: c.replies,
            errors: c.errors,
            decode_errors: c.decode_errors,
            ignored: c.ignored,
            session: match self.core.state {
                SessionState::Open { session } => Some(session),
                _ => None,
            },
        }
    }

    /// The session state.
    pub const fn state(&self) -> SessionState {
        self.core.state
    }

    /// The parameters it runs.
    pub fn params(&self) -> &C {
        &self.core.params
    }

    /// Bytes received since the last `0x00` (a request in progress, or noise).
    pub const fn pending(&self) -> usize {
        self.rx.pending()
    }

    /// Back to power-up: session closed, partial frame forgotten, counters zeroed.
    pub fn reset(&mut self) {
        self.rx.clear();
        self.reset_stats();
        self.core.state = SessionState::Idle;
    }

    /// Zeroes every counter (link and session).
    fn reset_stats(&mut self) {
        self.rx.reset_stats();
        self.core.counters = Counters::default();
    }
}

/// A [`DeviceEndpoint`] of any controller and buffer sizes, as a trait object: what a host
/// holds when it serves a model it knows only at run time (a soft device, a test).
pub trait Endpoint {
    /// Feeds `input` whole and hands every reply, in order, to `tx` (see
    /// [`DeviceEndpoint::serve`]).
    fn serve_all(&mut self, input: &[u8], tx: &mut dyn FnMut(&[u8]));
    /// What the device answers to `Hello`.
    fn identity(&self) -> Identity;
    /// The counters, as a `StatsRequest` would report them now.
    fn stats(&self) -> DeviceStats;
    /// Back to power-up (see [`DeviceEndpoint::reset`]).
    fn reset(&mut self);
    /// Sets what `Identity::rx_buffer` reports (see [`DeviceEndpoint::set_rx_buffer`]).
    fn set_rx_buffer(&mut self, bytes: u32);
}

impl<C: Controller, const RX: usize, const TX: usize> Endpoint for DeviceEndpoint<C, RX, TX> {
    fn serve_all(&mut self, input: &[u8], tx: &mut dyn FnMut(&[u8])) {
        let _ = self.serve(input, |reply| {
            tx(reply);
            Ok::<(), core::convert::Infallible>(())
        });
    }
    fn identity(&self) -> Identity {
        DeviceEndpoint::identity(self)
    }
    fn stats(&self) -> DeviceStats {
        DeviceEndpoint::stats(self)
    }
    fn reset(&mut self) {
        DeviceEndpoint::reset(self);
    }
    fn set_rx_buffer(&mut self, bytes: u32) {
        DeviceEndpoint::set_rx_buffer(self, bytes);
    }
}
