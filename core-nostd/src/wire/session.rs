//! The session messages (kinds `0x01`-`0x08`): handshake, configure, ping and device
//! statistics, the parameter hash, and the host's handshake check.
//!
//! A session is `Hello` → [`Identity`] (the host checks it with [`Identity::check`]), then
//! [`Configure`] → [`Configured`] (the device checks the host's parameter hash and opens the
//! session); only then does a device serve controller requests. [`Ping`] and
//! [`StatsRequest`] are answered in any state. `docs/protocol.md` gives every byte.

use core::fmt;

use serde::{Deserialize, Serialize};

use super::Message;
use super::accumulator::Stats;
use super::frame::max_frame_len;
use super::header::PROTOCOL_VERSION;
use super::message::kind;
use crate::{Error, MathBackend, Result, ScalarKind};

/// The longest device name an [`Identity`] carries, in UTF-8 bytes.
pub const DEVICE_NAME_LEN: usize = 24;

/// A device name: at most [`DEVICE_NAME_LEN`] bytes of UTF-8.
pub type DeviceName = heapless::String<DEVICE_NAME_LEN>;

/// The largest payload of a session message: a [`DeviceStats`] with every counter at
/// `u32::MAX` and a session id (pinned by a test).
pub const MAX_SESSION_PAYLOAD: usize = 71;

/// The longest frame of a session message, delimiter included.
pub const MAX_SESSION_FRAME: usize = max_frame_len(MAX_SESSION_PAYLOAD);

/// Which controller a device runs: a number (a varint on the wire), so that a new model needs
/// no change here. `0` ant, `1` bee, `2` wang, `3` fly, `4` li; `5`-`127` are kept for this project's
/// models, `128` and above are free for applications and tests.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(transparent)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ControllerKind(pub u32);

impl ControllerKind {
    /// The ant controller ([`crate::ant`]): plan and resolve requests.
    pub const ANT: ControllerKind = ControllerKind(0);
    /// The bee controller ([`crate::bee`]): step requests.
    pub const BEE: ControllerKind = ControllerKind(1);
    /// The wang2014 insect ([`crate::wang`]): advect and separate requests.
    pub const WANG: ControllerKind = ControllerKind(2);
    /// The ren2016 flying insect ([`crate::fly`]): step requests.
    pub const FLY: ControllerKind = ControllerKind(3);
    /// The li2015 data-driven insect ([`crate::li`]): step requests.
    pub const LI: ControllerKind = ControllerKind(4);
}

/// The capacity of each list of a sensor frame the device accepts; 0 for a list its
/// controller's frame does not have.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Capacities {
    /// Neighbours (ant plan and resolve frames, bee frame, wang separate frame, fly and li
    /// frames).
    pub neighbours: u16,
    /// Environment objects (ant plan frame; 0 for the others).
    pub objects: u16,
    /// Target particles (bee frame; 0 for the others).
    pub targets: u16,
    /// Obstacle surfaces (ant resolve frame, [`crate::ant::SURFACES`]; fly frame,
    /// [`crate::fly::WIRE_FLY_SURFACES`]; li frame, [`crate::li::WIRE_LI_SURFACES`]; 0 for
    /// the others).
    pub surfaces: u16,
}

impl Capacities {
    /// Every capacity 0: a controller whose frame has none of these lists.
    pub const NONE: Capacities = Capacities {
        neighbours: 0,
        objects: 0,
        targets: 0,
        surfaces: 0,
    };
}

/// Host → device (kind `0x01`): "who are you?". Empty payload. Answered with an
/// [`Identity`] in any state; it closes an open session (a host that re-handshakes sends
/// [`Configure`] again).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Hello;

/// Device → host (kind `0x02`): what the device is, the answer to [`Hello`].
///
/// A host compares it with what it expects ([`Identity::check`]) and refuses a device that
/// differs in anything but its name.
#[derive(Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Identity {
    /// The protocol version the device speaks ([`PROTOCOL_VERSION`]).
    pub protocol: u8,
    /// The controller it runs.
    pub controller: ControllerKind,
    /// Its number type.
    pub scalar: ScalarKind,
    /// The library computing its transcendental functions (`f32` results of two backends
    /// differ in their last bits).
    pub math: MathBackend,
    /// The sensor-frame list capacities it accepts.
    pub capacities: Capacities,
    /// The longest frame it receives, delimiter included; a longer one is dropped unanswered.
    /// For the host's expectation: the longest frame the host will send.
    pub max_frame: u16,
    /// How many bytes of further requests the device takes in while it computes a reply (its
    /// receive ring, or its UART's hardware FIFO when it polls; `u32::MAX`: no limit, e.g. a
    /// device on the host reading a pipe). Not compared by [`Identity::check`]: a host sizes
    /// its pipelining window from it ([`Identity::window`]).
    pub rx_buffer: u32,
    /// [`params_hash`] of its controller parameters.
    pub params_hash: u64,
    /// A free-form name for reports (not compared by [`Identity::check`]).
    pub name: DeviceName,
}

/// Host → device (kind `0x03`): opens a session, after [`Hello`].
///
/// The device answers [`Configured`] if `params_hash` is its own, else an
/// [`ErrorReply`](super::ErrorReply) with code
/// [`PARAMS_MISMATCH`](super::ErrorReply::PARAMS_MISMATCH) (and the session stays closed).
/// Before any `Hello` the answer is [`NO_SESSION`](super::ErrorReply::NO_SESSION).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Configure {
    /// A session id chosen by the host; the device reports it in [`DeviceStats::session`],
    /// so a host notices a device that was reset or re-configured by someone else.
    pub session: u32,
    /// The [`params_hash`] the host computed from its own parameters.
    pub params_hash: u64,
    /// Zero every device counter (link and session), so the statistics of a run are those of
    /// this session only. Only an accepted `Configure` resets, after its [`Configured`] was
    /// sent: neither is counted, so right after, every counter is 0.
    pub reset_stats: bool,
}

/// Device → host (kind `0x04`): the session is open.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Configured {
    /// The session id of the [`Configure`].
    pub session: u32,
}

/// Host → device (kind `0x05`): liveness and latency probe, answered in any state.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Ping {
    /// Any value; echoed in the [`Pong`].
    pub nonce: u32,
}

/// Device → host (kind `0x06`): the answer to [`Ping`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Pong {
    /// The ping's nonce.
    pub nonce: u32,
}

/// Host → device (kind `0x07`): "send your counters". Empty payload; answered with
/// [`DeviceStats`] in any state.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct StatsRequest;

/// Device → host (kind `0x08`): the device's counters, the answer to [`StatsRequest`].
///
/// Every counter saturates at `u32::MAX`. The snapshot is taken when the request is handled:
/// the request itself is counted in `link.frames_ok` and `requests`, its reply not yet in
/// `replies`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct DeviceStats {
    /// The receiver's counters: frames received intact, and frames dropped by reason (CRC,
    /// COBS, truncated, version, oversize), empty frames, garbage bytes skipped.
    pub link: Stats,
    /// Intact frames of this protocol version handed to the session layer.
    pub requests: u32,
    /// Replies sent other than [`ErrorReply`](super::ErrorReply): requests served.
    pub replies: u32,
    /// [`ErrorReply`](super::ErrorReply) frames sent.
    pub errors: u32,
    /// Requests of an unknown kind, or whose payload did not decode (each got an error reply).
    pub decode_errors: u32,
    /// Intact frames of kind `0x00` or of a reply kind, of any protocol version, dropped
    /// unanswered (see [`kind::never_answered`]; a frame of another version is counted in
    /// `link.version_errors` too, not in `requests`).
    pub ignored: u32,
    /// The open session's id, `None` when no session is open.
    pub session: Option<u32>,
}

macro_rules! session_kinds {
    ($($ty:ident = $kind:path;)*) => {$(
        impl Message for $ty {
            const KIND: u8 = $kind;
        }
    )*};
}

session_kinds! {
    Hello = kind::HELLO;
    Identity = kind::IDENTITY;
    Configure = kind::CONFIGURE;
    Configured = kind::CONFIGURED;
    Ping = kind::PING;
    Pong = kind::PONG;
    StatsRequest = kind::STATS_REQUEST;
    DeviceStats = kind::DEVICE_STATS;
}

// ---- the parameter hash ----

/// FNV-1a 64-bit offset basis.
pub const FNV1A64_OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
/// FNV-1a 64-bit prime.
pub const FNV1A64_PRIME: u64 = 0x0000_0100_0000_01b3;

/// FNV-1a, 64-bit: `h = 0xcbf29ce484222325; for b in bytes { h = (h ^ b) * 0x100000001b3 mod 2^64 }`.
pub const fn fnv1a64(bytes: &[u8]) -> u64 {
    fnv1a64_update(FNV1A64_OFFSET, bytes)
}

const fn fnv1a64_update(mut h: u64, bytes: &[u8]) -> u64 {
    let mut i = 0;
    while i < bytes.len() {
        h = (h ^ bytes[i] as u64).wrapping_mul(FNV1A64_PRIME);
        i += 1;
    }
    h
}

/// A postcard flavor that hashes instead of storing: no buffer needed.
struct Fnv(u64);

impl postcard::ser_flavors::Flavor for Fnv {
    type Output = u64;

    fn try_extend(&mut self, data: &[u8]) -> postcard::Result<()> {
        self.0 = fnv1a64_update(self.0, data);
        Ok(())
    }

    fn try_push(&mut self, data: u8) -> postcard::Result<()> {
        self.try_extend(&[data])
    }

    fn finalize(self) -> postcard::Result<u64> {
        Ok(self.0)
    }
}

/// The parameter hash of the handshake: [`fnv1a64`] of the postcard encoding of the
/// parameters (e.g. an [`AntParams<f32>`](crate::ant::AntParams): its fields in declaration
/// order, `f32` as 4 little-endian bytes, `Fx` as a zig-zag varint of its bits, integers as
/// varints). Computed in one pass, with no buffer.
///
/// ```
/// use swarm_core::ant::AntParams;
/// use swarm_core::wire::{fnv1a64, params_hash};
///
/// let p = AntParams::<f32>::default();
/// let mut bytes = [0u8; 64];
/// let encoded = postcard::to_slice(&p, &mut bytes).unwrap();
/// assert_eq!(params_hash(&p), Ok(fnv1a64(encoded)));
/// ```
///
/// # Errors
///
/// [`Error::Payload`] if postcard cannot serialize `params` (never for this crate's
/// parameter types).
pub fn params_hash<P: Serialize + ?Sized>(params: &P) -> Result<u64> {
    postcard::serialize_with_flavor(params, Fnv(FNV1A64_OFFSET)).map_err(|_| Error::Payload)
}

// ---- the host's handshake check ----

/// One field in which a device's [`Identity`] differs from the host's expectation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Difference {
    /// [`Identity::protocol`].
    Protocol,
    /// [`Identity::controller`].
    Controller,
    /// [`Identity::scalar`].
    Scalar,
    /// [`Identity::math`].
    Math,
    /// [`Capacities::neighbours`].
    Neighbours,
    /// [`Capacities::objects`].
    Objects,
    /// [`Capacities::targets`].
    Targets,
    /// [`Capacities::surfaces`].
    Surfaces,
    /// The device's [`Identity::max_frame`] is below the host's (it would drop the host's
    /// longest requests).
    MaxFrame,
    /// [`Identity::params_hash`].
    ParamsHash,
}

impl Difference {
    /// Every difference, in the order [`HandshakeMismatch`] reports them.
    pub const ALL: [Difference; 10] = [
        Difference::Protocol,
        Difference::Controller,
        Difference::Scalar,
        Difference::Math,
        Difference::Neighbours,
        Difference::Objects,
        Difference::Targets,
        Difference::Surfaces,
        Difference::MaxFrame,
        Difference::ParamsHash,
    ];

    /// Whether `device` and `host` differ in this field.
    pub fn between(self, device: &Identity, host: &Identity) -> bool {
        let (d, h) = (device, host);
        match self {
            Difference::Protocol => d.protocol != h.protocol,
            Difference::Controller => d.controller != h.controller,
            Difference::Scalar => d.scalar != h.scalar,
            Difference::Math => d.math != h.math,
            Difference::Neighbours => d.capacities.neighbours != h.capacities.neighbours,
            Difference::Objects => d.capacities.objects != h.capacities.objects,
            Difference::Targets => d.capacities.targets != h.capacities.targets,
            Difference::Surfaces => d.capacities.surfaces != h.capacities.surfaces,
            Difference::MaxFrame => d.max_frame < h.max_frame,
            Difference::ParamsHash => d.params_hash != h.params_hash,
        }
    }
}

/// The error of [`Identity::check`]: the device is not the one the host expects. Its
/// `Display` names every difference, device value first:
/// `device ≠ host: scalar I16F16 ≠ f32, params hash 0x… ≠ 0x…`.
///
/// (A struct beside [`Error`] rather than a variant of it: it carries both identities, which
/// would make every `Result` of the controllers larger. [`HandshakeMismatch::error`] gives
/// the closest [`Error`] when one type is needed.)
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct HandshakeMismatch {
    /// What the device reported.
    pub device: Identity,
    /// What the host expected.
    pub host: Identity,
}

impl HandshakeMismatch {
    /// The fields that differ, in the order of [`Difference::ALL`].
    pub fn differences(&self) -> impl Iterator<Item = Difference> + '_ {
        Difference::ALL
            .into_iter()
            .filter(|d| d.between(&self.device, &self.host))
    }

    /// The closest [`Error`]: [`Error::ParamsMismatch`] if only the parameter hash differs
    /// (or besides it nothing the protocol could report), else the first difference as
    /// [`Error::Version`], or [`Error::BadParam`] naming
    /// the field.
    pub fn error(&self) -> Error {
        let (d, h) = (&self.device, &self.host);
        match self.differences().next() {
            Some(Difference::Protocol) => Error::Version { got: d.protocol },
            Some(Difference::Controller) => Error::BadParam {
                field: "controller",
            },
            Some(Difference::Scalar) => Error::BadParam { field: "scalar" },
            Some(Difference::Math) => Error::BadParam { field: "math" },
            Some(Difference::Neighbours) => Error::BadParam {
                field: "capacities.neighbours",
            },
            Some(Difference::Objects) => Error::BadParam {
                field: "capacities.objects",
            },
            Some(Difference::Targets) => Error::BadParam {
                field: "capacities.targets",
            },
            Some(Difference::Surfaces) => Error::BadParam {
                field: "capacities.surfaces",
            },
            Some(Difference::MaxFrame) => Error::Oversize,
            Some(Difference::ParamsHash) | None => Error::ParamsMismatch {
                device: d.params_hash,
                host: h.params_hash,
            },
        }
    }
}

const fn scalar_name(s: ScalarKind) -> &'static str {
    match s {
        ScalarKind::F32 => "f32",
        ScalarKind::I16F16 => "I16F16",
    }
}

const fn math_name(m: MathBackend) -> &'static str {
    match m {
        MathBackend::Libm => "libm",
        MathBackend::Micromath => "micromath",
        MathBackend::Integer => "integer",
    }
}

impl fmt::Display for ControllerKind {
    /// `ant`, `bee`, `wang`, `fly`, `li`, or `controller N` for any other.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            ControllerKind::ANT => f.write_str("ant"),
            ControllerKind::BEE => f.write_str("bee"),
            ControllerKind::WANG => f.write_str("wang"),
            ControllerKind::FLY => f.write_str("fly"),
            ControllerKind::LI => f.write_str("li"),
            ControllerKind(n) => write!(f, "controller {n}"),
        }
    }
}

impl fmt::Display for HandshakeMismatch {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (d, h) = (&self.device, &self.host);
        write!(f, "device \"{}\" refused (device ≠ host): ", d.name)?;
        let mut first = true;
        for diff in self.differences() {
            if !first {
                f.write_str(", ")?;
            }
            first = false;
            match diff {
                Difference::Protocol => {
                    write!(f, "protocol version {} ≠ {}", d.protocol, h.protocol)
                }
                Difference::Controller => {
                    write!(f, "controller {} ≠ {}", d.controller, h.controller)
                }
                Difference::Scalar => write!(
                    f,
                    "scalar {} ≠ {}",
                    scalar_name(d.scalar),
                    scalar_name(h.scalar)
                ),
                Difference::Math => write!(
                    f,
                    "math backend {} ≠ {}",
                    math_name(d.math),
                    math_name(h.math)
                ),
                Difference::Neighbours => write!(
                    f,
                    "neighbour capacity {} ≠ {}",
                    d.capacities.neighbours, h.capacities.neighbours
                ),
                Difference::Objects => write!(
                    f,
                    "object capacity {} ≠ {}",
                    d.capacities.objects, h.capacities.objects
                ),
                Difference::Targets => write!(
                    f,
                    "target capacity {} ≠ {}",
                    d.capacities.targets, h.capacities.targets
                ),
                Difference::Surfaces => write!(
                    f,
                    "surface capacity {} ≠ {}",
                    d.capacities.surfaces, h.capacities.surfaces
                ),
                Difference::MaxFrame => write!(
                    f,
                    "max frame {} < {} bytes (the host's longest request)",
                    d.max_frame, h.max_frame
                ),
                Difference::ParamsHash => write!(
                    f,
                    "params hash {:#018x} ≠ {:#018x}",
                    d.params_hash, h.params_hash
                ),
            }?;
        }
        if first {
            f.write_str("no difference")?;
        }
        Ok(())
    }
}

impl core::error::Error for HandshakeMismatch {}

impl From<HandshakeMismatch> for Error {
    fn from(m: HandshakeMismatch) -> Error {
        m.error()
    }
}

impl Identity {
    /// The identity of a device running `params` on controller `C`, receiving frames of up
    /// to `max_frame` bytes (delimiter included; saturated to `u16::MAX`), named `name`,
    /// with no receive buffer beyond the frame it serves (`rx_buffer` 0).
    ///
    /// A host builds its expectation the same way, with `max_frame` the longest frame it will
    /// send (e.g. [`MAX_ANT_FRAME`](super::MAX_ANT_FRAME)) and any name.
    ///
    /// # Errors
    ///
    /// [`Error::BadParam`] (`"name"`) if `name` is longer than [`DEVICE_NAME_LEN`] bytes.
    pub fn of<C: super::Controller>(params: &C, max_frame: usize, name: &str) -> Result<Self> {
        Ok(Identity {
            protocol: PROTOCOL_VERSION,
            controller: C::KIND,
            scalar: <C::Scalar as crate::Scalar>::KIND,
            math: <C::Scalar as crate::Scalar>::MATH,
            capacities: C::CAPACITIES,
            max_frame: u16::try_from(max_frame).unwrap_or(u16::MAX),
            rx_buffer: 0,
            params_hash: params_hash(params)?,
            name: device_name(name)?,
        })
    }

    /// The most requests a host keeps in flight to this device when its longest request
    /// frame is `request_frame` bytes (delimiter included): the one being served plus as many
    /// whole ones as [`rx_buffer`](Identity::rx_buffer) holds, `1 + rx_buffer / request_frame`
    /// (at least 1; saturating). A line with flow control (the device's receiver holds the
    /// sender back when full, as QEMU's UARTs do) is not bound by it.
    ///
    /// ```
    /// # use swarm_core::ant::AntParams;
    /// # use swarm_core::wire::{Identity, MAX_ANT_FRAME};
    /// let mut id = Identity::of(&AntParams::<f32>::default(), 451, "ant-1").unwrap();
    /// id.rx_buffer = 16; // a polled PL011: its hardware FIFO
    /// assert_eq!(id.window(MAX_ANT_FRAME), 1);
    /// id.rx_buffer = 2048; // a 2 KiB interrupt-filled ring
    /// assert_eq!(id.window(MAX_ANT_FRAME), 5);
    /// ```
    pub fn window(&self, request_frame: usize) -> usize {
        let buffered = usize::try_from(self.rx_buffer).unwrap_or(usize::MAX);
        1usize.saturating_add(buffered / request_frame.max(1))
    }

    /// Compares the device's identity (`self`) with the host's expectation: every field must
    /// be equal, except `name` and `rx_buffer` (not compared) and `max_frame` (the device's
    /// must be at least the host's).
    ///
    /// ```
    /// use swarm_core::ant::AntParams;
    /// use swarm_core::wire::{Identity, MAX_ANT_FRAME};
    ///
    /// let device = Identity::of(&AntParams::<f32>::default(), 451, "ant-1").unwrap();
    /// let mut other = AntParams::<f32>::default();
    /// other.speed = 2.0;
    /// let host = Identity::of(&other, MAX_ANT_FRAME, "").unwrap();
    /// let refused = device.check(&host).unwrap_err();
    /// assert!(refused.to_string().contains("params hash 0x"));
    /// assert!(device.check(&Identity::of(&AntParams::<f32>::default(), MAX_ANT_FRAME, "").unwrap()).is_ok());
    /// ```
    ///
    /// # Errors
    ///
    /// A [`HandshakeMismatch`] naming every difference.
    // Both identities travel in the error (130 bytes, no allocation in no_std); a handshake
    // happens once per session, so the size of its `Result` costs nothing.
    #[allow(clippy::result_large_err)]
    pub fn check(&self, host: &Identity) -> core::result::Result<(), HandshakeMismatch> {
        if Difference::ALL.iter().any(|d| d.between(self, host)) {
            Err(HandshakeMismatch {
                device: self.clone(),
                host: host.clone(),
            })
        } else {
            Ok(())
        }
    }
}

/// `name` as a [`DeviceName`]: [`Error::BadParam`] (`"name"`) if it is longer than
/// [`DEVICE_NAME_LEN`] bytes.
pub fn device_name(name: &str) -> Result<DeviceName> {
    DeviceName::try_from(name).map_err(|_| Error::BadParam { field: "name" })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Fx;
    use crate::ant::AntParams;
    use crate::bee::BeeParams;
    use crate::wire::test_util::{hex, payload_len, through_the_wire};
    use crate::wire::{MAX_ANT_FRAME, MAX_BEE_FRAME};

    fn ant_identity() -> Identity {
        Identity::of(&AntParams::<f32>::default(), 451, "ant-node").unwrap()
    }

    #[test]
    fn every_session_message_round_trips() {
        assert_eq!(through_the_wire(1, &Hello), Hello);
        let id = ant_identity();
        assert_eq!(through_the_wire(0xffff, &id), id);
        let id = Identity::of(&BeeParams::<Fx>::default(), 942, "bee-ünicode-24-bytes-ok").unwrap();
        assert_eq!(id.name.len(), 24);
        assert_eq!(through_the_wire(2, &id), id);
        let c = Configure {
            session: u32::MAX,
            params_hash: u64::MAX,
            reset_stats: true,
        };
        assert_eq!(through_the_wire(3, &c), c);
        assert_eq!(
            through_the_wire(4, &Configured { session: 7 }),
            Configured { session: 7 }
        );
        assert_eq!(through_the_wire(5, &Ping { nonce: 0 }), Ping { nonce: 0 });
        assert_eq!(
            through_the_wire(6, &Pong { nonce: u32::MAX }),
            Pong { nonce: u32::MAX }
        );
        assert_eq!(through_the_wire(7, &StatsRequest), StatsRequest);
        let s = DeviceStats {
            link: Stats {
                frames_ok: 1,
                crc_errors: 2,
                cobs_errors: 3,
                truncated: 4,
                version_errors: 5,
                oversize: 6,
                empty: 7,
                bytes_dropped: 8,
            },
            requests: 9,
            replies: 10,
            errors: 11,
            decode_errors: 12,
            ignored: 13,
            session: Some(14),
        };
        assert_eq!(through_the_wire(8, &s), s);
        let none = DeviceStats::default();
        assert_eq!(through_the_wire(8, &none), none);
    }

    #[test]
    fn kinds_pair_up_and_are_named() {
        let pairs = [
            (Hello::KIND, Identity::KIND),
            (Configure::KIND, Configured::KIND),
            (Ping::KIND, Pong::KIND),
            (StatsRequest::KIND, DeviceStats::KIND),
        ];
        for (i, (req, rep)) in pairs.iter().enumerate() {
            assert_eq!(*req, 2 * i as u8 + 1);
            assert_eq!(*rep, req + 1);
            assert!(!kind::is_reply(*req));
            assert!(kind::is_reply(*rep));
            assert!(kind::name(*req).is_some() && kind::name(*rep).is_some());
        }
        for k in 0x09..=0x0e {
            assert_eq!(kind::name(k), None);
        }
    }

    #[test]
    fn widest_session_message_is_max_session_payload() {
        let s = DeviceStats {
            link: Stats {
                frames_ok: u32::MAX,
                crc_errors: u32::MAX,
                cobs_errors: u32::MAX,
                truncated: u32::MAX,
                version_errors: u32::MAX,
                oversize: u32::MAX,
                empty: u32::MAX,
                bytes_dropped: u32::MAX,
            },
            requests: u32::MAX,
            replies: u32::MAX,
            errors: u32::MAX,
            decode_errors: u32::MAX,
            ignored: u32::MAX,
            session: Some(u32::MAX),
        };
        assert_eq!(payload_len(&s), MAX_SESSION_PAYLOAD);
        let mut id = Identity::of(&AntParams::<Fx>::default(), 65535, "").unwrap();
        id.controller = ControllerKind(u32::MAX);
        id.params_hash = u64::MAX;
        id.capacities = Capacities {
            neighbours: u16::MAX,
            objects: u16::MAX,
            targets: u16::MAX,
            surfaces: u16::MAX,
        };
        id.rx_buffer = u32::MAX;
        id.name = device_name("abcdefghijklmnopqrstuvwx").unwrap();
        assert_eq!(payload_len(&id), 63);
        // 59 for a controller kind below 128 (one varint byte instead of five).
        id.controller = ControllerKind(127);
        assert_eq!(payload_len(&id), 59);
        let c = Configure {
            session: u32::MAX,
            params_hash: u64::MAX,
            reset_stats: true,
        };
        assert_eq!(payload_len(&c), 16);
        assert_eq!(MAX_SESSION_FRAME, 79);
    }

    #[test]
    fn window_is_one_plus_the_whole_requests_rx_buffer_holds() {
        let mut id = ant_identity();
        assert_eq!(id.rx_buffer, 0);
        assert_eq!(id.window(MAX_ANT_FRAME), 1);
        for (rx_buffer, window) in [(1, 1), (16, 1), (449, 1), (450, 2), (1800, 5), (1801, 5)] {
            id.rx_buffer = rx_buffer;
            assert_eq!(id.window(MAX_ANT_FRAME), window, "{rx_buffer}");
        }
        id.rx_buffer = u32::MAX;
        assert_eq!(
            id.window(MAX_ANT_FRAME),
            1 + u32::MAX as usize / MAX_ANT_FRAME
        );
        assert_eq!(id.window(1), (u32::MAX as usize).saturating_add(1));
        // A request frame length of 0 counts as 1.
        assert_eq!(id.window(0), id.window(1));
    }

    #[test]
    fn fnv1a64_reference_values() {
        // From the FNV reference test suite.
        assert_eq!(fnv1a64(b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(fnv1a64(b"a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(fnv1a64(b"foobar"), 0x8594_4171_f739_67e8);
    }

    fn postcard_bytes<T: Serialize>(v: &T) -> Vec<u8> {
        let mut buf = [0u8; 256];
        postcard::to_slice(v, &mut buf).unwrap().to_vec()
    }

    #[test]
    fn params_hash_is_fnv1a64_of_postcard() {
        let a = AntParams::<f32>::default();
        assert_eq!(params_hash(&a), Ok(fnv1a64(&postcard_bytes(&a))));
        let a = AntParams::<Fx>::default();
        assert_eq!(params_hash(&a), Ok(fnv1a64(&postcard_bytes(&a))));
        let b = BeeParams::<f32>::default();
        assert_eq!(params_hash(&b), Ok(fnv1a64(&postcard_bytes(&b))));
        let b = BeeParams::<Fx>::grassland();
        assert_eq!(params_hash(&b), Ok(fnv1a64(&postcard_bytes(&b))));
        // Any change of any parameter changes the hash.
        let c = AntParams::<f32> {
            k: 3,
            ..AntParams::default()
        };
        assert_ne!(params_hash(&c), params_hash(&AntParams::<f32>::default()));
    }

    /// docs/protocol.md, section 10.2 (computed with the Python reference, appendix B).
    #[test]
    fn pinned_ant_params_hash() {
        let a = AntParams::<f32>::default();
        assert_eq!(
            postcard_bytes(&a),
            hex(
                "00 00 80 3f 00 00 80 3f 92 0a 06 3f 0a d7 a3 3b 05 0a 0a 00 00 00 40
                 00 00 00 40 00 00 c0 3f 9a 99 19 3f 00 00 80 3f 02"
            )
        );
        assert_eq!(params_hash(&a), Ok(0x7e34_e3b6_c808_45c3));
    }

    /// docs/protocol.md, section 10.2 (computed with the Python reference, appendix B): the
    /// default fly preset (the midge) and the escape preset, both scalars.
    #[test]
    fn pinned_fly_params_hash() {
        use crate::fly::FlyParams;
        let m = FlyParams::<f32>::midge();
        assert_eq!(FlyParams::<f32>::default(), m);
        assert_eq!(postcard_bytes(&m).len(), 68);
        assert_eq!(params_hash(&m), Ok(0x6fe6_5802_e861_6419));
        let m = FlyParams::<Fx>::midge();
        assert_eq!(postcard_bytes(&m).len(), 43);
        assert_eq!(params_hash(&m), Ok(0xd9cd_f576_c0cf_3e24));
        let e = FlyParams::<f32>::escape();
        assert_eq!(params_hash(&e), Ok(0x349f_43da_c831_c928));
        assert_eq!(params_hash(&e.cast::<Fx>()), Ok(0x26f5_e182_a7dd_30e0));
        // Any one field changed, another hash.
        let n = FlyParams::<f32> {
            noise: 1,
            ..m.cast()
        };
        assert_ne!(params_hash(&n), params_hash(&FlyParams::<f32>::midge()));
    }

    #[test]
    fn check_accepts_the_same_device_whatever_its_name() {
        let device = ant_identity();
        let host = Identity::of(&AntParams::<f32>::default(), MAX_ANT_FRAME, "host").unwrap();
        assert_eq!(device.check(&host), Ok(()));
        // A device that receives longer frames than the host sends is fine too.
        let mut big = device.clone();
        big.max_frame = u16::MAX;
        assert_eq!(big.check(&host), Ok(()));
        // Nor is what it buffers compared: the host sizes its window from it.
        for rx_buffer in [1, 16, u32::MAX] {
            let mut d = device.clone();
            d.rx_buffer = rx_buffer;
            assert_eq!(d.check(&host), Ok(()));
        }
    }

    #[test]
    fn check_names_each_difference() {
        let host = Identity::of(&AntParams::<f32>::default(), MAX_ANT_FRAME, "").unwrap();
        let other = AntParams::<f32> {
            w0: 0.5,
            ..AntParams::default()
        };
        type Case = (fn(&mut Identity), Difference, &'static str);
        let cases: [Case; 10] = [
            (
                |d| d.protocol = 2,
                Difference::Protocol,
                "protocol version 2 ≠ 3",
            ),
            (
                |d| d.controller = ControllerKind::BEE,
                Difference::Controller,
                "controller bee ≠ ant",
            ),
            (
                |d| d.scalar = ScalarKind::I16F16,
                Difference::Scalar,
                "scalar I16F16 ≠ f32",
            ),
            (
                |d| d.math = MathBackend::Micromath,
                Difference::Math,
                "math backend micromath ≠ libm",
            ),
            (
                |d| d.capacities.neighbours = 4,
                Difference::Neighbours,
                "neighbour capacity 4 ≠ 8",
            ),
            (
                |d| d.capacities.objects = 2,
                Difference::Objects,
                "object capacity 2 ≠ 4",
            ),
            (
                |d| d.capacities.targets = 16,
                Difference::Targets,
                "target capacity 16 ≠ 0",
            ),
            (
                |d| d.capacities.surfaces = 4,
                Difference::Surfaces,
                "surface capacity 4 ≠ 6",
            ),
            (
                |d| d.max_frame = 100,
                Difference::MaxFrame,
                "max frame 100 < 450 bytes",
            ),
            (
                |d| d.params_hash = 0x0123_4567_89ab_cdef,
                Difference::ParamsHash,
                "params hash 0x0123456789abcdef ≠ 0x7e34e3b6c80845c3",
            ),
        ];
        for (change, diff, text) in cases {
            let mut device = ant_identity();
            change(&mut device);
            let err = device.check(&host).unwrap_err();
            assert_eq!(err.differences().collect::<Vec<_>>(), vec![diff]);
            let msg = err.to_string();
            assert!(msg.contains(text), "{msg:?} lacks {text:?}");
            assert!(msg.starts_with("device \"ant-node\" refused (device ≠ host): "));
        }
        // A device with other parameters.
        let device = Identity::of(&other, 451, "x").unwrap();
        let err = device.check(&host).unwrap_err();
        assert_eq!(
            err.differences().collect::<Vec<_>>(),
            vec![Difference::ParamsHash]
        );
        assert_eq!(
            Error::from(err.clone()),
            Error::ParamsMismatch {
                device: device.params_hash,
                host: host.params_hash
            }
        );
    }

    #[test]
    fn check_names_every_difference_at_once() {
        let host = Identity::of(&AntParams::<f32>::default(), MAX_ANT_FRAME, "").unwrap();
        let device = Identity::of(&BeeParams::<Fx>::default(), MAX_BEE_FRAME, "bee").unwrap();
        let err = device.check(&host).unwrap_err();
        // Everything but the protocol version and the frame size (the bee device receives
        // longer frames than the ant host sends, which is fine).
        let expected = Difference::ALL
            .into_iter()
            .filter(|d| !matches!(d, Difference::Protocol | Difference::MaxFrame))
            .collect::<Vec<_>>();
        assert_eq!(err.differences().collect::<Vec<_>>(), expected);
        let msg = err.to_string();
        for text in [
            "controller bee ≠ ant",
            "scalar I16F16 ≠ f32",
            "math backend integer ≠ libm",
            "neighbour capacity 16 ≠ 8",
            "object capacity 0 ≠ 4",
            "target capacity 16 ≠ 0",
            "surface capacity 0 ≠ 6",
            "params hash 0x",
        ] {
            assert!(msg.contains(text), "{msg:?} lacks {text:?}");
        }
        assert_eq!(
            err.error(),
            Error::BadParam {
                field: "controller"
            }
        );
    }

    #[test]
    fn names_longer_than_24_bytes_are_refused() {
        assert!(device_name("abcdefghijklmnopqrstuvwx").is_ok());
        assert_eq!(
            device_name("abcdefghijklmnopqrstuvwxy"),
            Err(Error::BadParam { field: "name" })
        );
        assert_eq!(
            Identity::of(&AntParams::<f32>::default(), 1, "ü".repeat(13).as_str()),
            Err(Error::BadParam { field: "name" })
        );
    }

    #[test]
    fn identity_rejects_bad_payloads() {
        // A name longer than 24 bytes, invalid UTF-8, an enum index out of range.
        let id = ant_identity();
        let mut bytes = postcard_bytes(&id);
        let name_at = bytes.len() - 9;
        assert_eq!(bytes[name_at], 8);
        bytes[name_at] = 0xff; // invalid UTF-8 length... and too long
        assert_eq!(
            crate::wire::decode_payload::<Identity>(&bytes),
            Err(Error::Payload)
        );
        let mut bytes = postcard_bytes(&id);
        bytes[name_at + 1] = 0xff; // invalid UTF-8
        assert_eq!(
            crate::wire::decode_payload::<Identity>(&bytes),
            Err(Error::Payload)
        );
        let mut bytes = postcard_bytes(&id);
        bytes[3] = 3; // MathBackend has 3 variants
        assert_eq!(
            crate::wire::decode_payload::<Identity>(&bytes),
            Err(Error::Payload)
        );
    }
}
