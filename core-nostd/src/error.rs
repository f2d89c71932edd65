//! The crate's one error type.

use core::fmt;

/// `Result` with the crate's [`Error`].
pub type Result<T> = core::result::Result<T, Error>;

/// Everything that can go wrong in `swarm-core`: bad controller input and bad wire bytes.
///
/// Input errors name the offending field (a static path such as `"neighbours.pos"`) and, for
/// list entries, its index, so a report can say exactly what was wrong and where. A controller
/// that returns an error leaves its state untouched (it only ever reads its inputs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Error {
    /// A number is NaN or infinite.
    NonFinite {
        /// The field, e.g. `"state.pos"`.
        field: &'static str,
        /// Index in a list field, if any.
        index: Option<u16>,
    },
    /// A number is finite but outside the range the field allows.
    OutOfRange {
        /// The field.
        field: &'static str,
        /// Index in a list field, if any.
        index: Option<u16>,
    },
    /// Ids or labels that contradict each other (e.g. a `Nest` label whose origin is not the
    /// ant's own nest, or the same neighbour id twice).
    Inconsistent {
        /// The field.
        field: &'static str,
        /// Index in a list field, if any.
        index: Option<u16>,
    },
    /// A parameter set is invalid (e.g. a negative speed); names the parameter.
    BadParam {
        /// The parameter.
        field: &'static str,
    },
    /// An output buffer is too small for the encoded frame.
    BufferFull,
    /// A frame is larger than the receiver's buffer; it was dropped whole.
    Oversize,
    /// The COBS layer of a frame is malformed.
    Cobs,
    /// A frame is shorter than header + CRC.
    Truncated,
    /// The CRC of a frame does not match its contents.
    Crc {
        /// CRC carried by the frame.
        got: u16,
        /// CRC computed over the frame's contents.
        expected: u16,
    },
    /// The frame header carries a protocol version this build does not speak.
    Version {
        /// Version in the header.
        got: u8,
    },
    /// The header's message kind is unknown.
    UnknownKind {
        /// The kind byte.
        kind: u8,
    },
    /// The header's message kind is a valid one, but not the one the caller expects (e.g. an
    /// error reply where a plan was awaited).
    UnexpectedKind {
        /// The kind byte in the header.
        got: u8,
        /// The kind the caller asked for.
        expected: u8,
    },
    /// The postcard payload does not decode to the message its kind announces (or has bytes
    /// left over); when encoding, postcard cannot serialize the message.
    Payload,
    /// A controller request (or a `Configure`) arrived before the session was opened: the
    /// device needs `Hello`, then `Configure` (see [`wire`](crate::wire) and
    /// `docs/protocol.md`).
    NoSession,
    /// The parameter hash a host sent in its `Configure` is not the device's: the device runs
    /// other controller parameters, so its decisions cannot be compared with the host's.
    ParamsMismatch {
        /// The device's parameter hash.
        device: u64,
        /// The hash the host expects.
        host: u64,
    },
}

impl Error {
    pub(crate) const fn non_finite(field: &'static str) -> Self {
        Error::NonFinite { field, index: None }
    }
    pub(crate) const fn out_of_range(field: &'static str) -> Self {
        Error::OutOfRange { field, index: None }
    }
    pub(crate) const fn inconsistent(field: &'static str) -> Self {
        Error::Inconsistent { field, index: None }
    }
    /// The same error, pinned to entry `index` of a list field.
    pub(crate) fn at(self, i: usize) -> Self {
        let idx = Some(u16::try_from(i).unwrap_or(u16::MAX));
        match self {
            Error::NonFinite { field, .. } => Error::NonFinite { field, index: idx },
            Error::OutOfRange { field, .. } => Error::OutOfRange { field, index: idx },
            Error::Inconsistent { field, .. } => Error::Inconsistent { field, index: idx },
            other => other,
        }
    }
}

fn at(f: &mut fmt::Formatter<'_>, field: &str, index: &Option<u16>) -> fmt::Result {
    match index {
        Some(i) => write!(f, "`{field}` [{i}]"),
        None => write!(f, "`{field}`"),
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::NonFinite { field, index } => {
                f.write_str("non-finite number (NaN or infinity) in ")?;
                at(f, field, index)
            }
            Error::OutOfRange { field, index } => {
                f.write_str("value out of range in ")?;
                at(f, field, index)
            }
            Error::Inconsistent { field, index } => {
                f.write_str("inconsistent ids or labels in ")?;
                at(f, field, index)
            }
            Error::BadParam { field } => write!(f, "invalid parameter `{field}`"),
            Error::BufferFull => f.write_str("output buffer too small for the frame"),
            Error::Oversize => f.write_str("frame larger than the receive buffer (dropped)"),
            Error::Cobs => f.write_str("malformed COBS encoding"),
            Error::Truncated => f.write_str("frame shorter than header + CRC"),
            Error::Crc { got, expected } => {
                write!(
                    f,
                    "CRC mismatch: frame carries {got:#06x}, contents give {expected:#06x}"
                )
            }
            Error::Version { got } => write!(f, "unsupported protocol version {got}"),
            Error::UnknownKind { kind } => write!(f, "unknown message kind {kind:#04x}"),
            Error::UnexpectedKind { got, expected } => {
                write!(
                    f,
                    "unexpected message kind {got:#04x} (expected {expected:#04x})"
                )
            }
            Error::Payload => f.write_str("payload does not decode to the announced message"),
            Error::NoSession => {
                f.write_str("no open session: send Hello, then Configure, before requests")
            }
            Error::ParamsMismatch { device, host } => write!(
                f,
                "controller parameters differ: params hash {device:#018x} (device) ≠ {host:#018x} (host)"
            ),
        }
    }
}

impl core::error::Error for Error {}
