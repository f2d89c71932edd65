//! The crate's error type.

use std::time::Duration;

/// `Result` with [`HilError`].
pub type Result<T> = std::result::Result<T, HilError>;

/// Everything that can go wrong in the harness.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum HilError {
    /// The link to the device failed (the transport and the operation in the message).
    #[error("{transport}: {op}: {source}")]
    Io {
        /// Which transport (`memory`, the port path, the TCP address).
        transport: String,
        /// What was being done.
        op: &'static str,
        /// The underlying error.
        source: std::io::Error,
    },
    /// The other end of the link is gone.
    #[error("{0}: the other end closed the link")]
    Closed(String),
    /// Nothing came back in time.
    #[error("{what}: no answer within {timeout:?}")]
    Timeout {
        /// What was awaited.
        what: String,
        /// How long.
        timeout: Duration,
    },
    /// A serial port could not be opened or set up.
    #[error("serial port {path}: {source}")]
    Serial {
        /// The port.
        path: String,
        /// The underlying error.
        source: serialport::Error,
    },
    /// The device is not the one expected (every difference named in the message).
    #[error("handshake: {0}")]
    Handshake(String),
    /// The device broke the protocol (the message says how).
    #[error("protocol: {0}")]
    Protocol(String),
    /// A bad argument (the message says which and why).
    #[error("{0}")]
    Invalid(String),
}

impl HilError {
    pub(crate) fn io(transport: &str, op: &'static str, source: std::io::Error) -> Self {
        HilError::Io {
            transport: transport.to_string(),
            op,
            source,
        }
    }
}
