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
    /// Nothing intact came back from the device for `silent` while requests waited.
    #[error(
        "{waiting_for}: the device sent nothing intact for {silent:.1?} ({unanswered} requests \
         unanswered)"
    )]
    LinkDead {
        /// The kind of the oldest request waiting.
        waiting_for: &'static str,
        /// Requests queued or in flight.
        unanswered: usize,
        /// How long nothing intact came.
        silent: Duration,
    },
    /// A request was sent its limit of times without an answer, while the link lived.
    #[error("{request} #{seq}: no answer after {sends} sends")]
    GaveUp {
        /// Its kind.
        request: &'static str,
        /// Its sequence number.
        seq: u16,
        /// Times it was sent.
        sends: u32,
    },
    /// A message could not be encoded (too large for a frame, or not serializable).
    #[error("encoding {message}: {source}")]
    Encode {
        /// Its kind.
        message: &'static str,
        /// Why.
        source: swarm_core::Error,
    },
    /// A reply the client had checked did not decode as its type.
    #[error("reply {reply} to {request}: {source}")]
    Decode {
        /// The reply's kind.
        reply: &'static str,
        /// The request's kind.
        request: &'static str,
        /// Why.
        source: swarm_core::Error,
    },
    /// The device refused a session request with an error reply.
    #[error("{request}: the device answered with error {name} (code {code})")]
    Refused {
        /// The request.
        request: &'static str,
        /// The error's name.
        name: &'static str,
        /// Its code.
        code: u8,
    },
    /// `Configure` opened another session than the one asked for.
    #[error("Configure: the device opened session {got}, not {asked}")]
    WrongSession {
        /// The session asked for.
        asked: u32,
        /// The session the device reported.
        got: u32,
    },
    /// A `Pong` came back with another nonce than its `Ping`'s.
    #[error("Ping: nonce {sent} came back as {got}")]
    PingNonce {
        /// The ping's nonce.
        sent: u32,
        /// The pong's.
        got: u32,
    },
    /// A mirror run stopped part way: `source` says why; `report` holds what was compared
    /// until then (partial counters, every mismatch found so far, the verdict).
    #[error("{source}")]
    Aborted {
        /// The partial report.
        report: Box<crate::mirror::MirrorReport>,
        /// What stopped the run.
        source: Box<HilError>,
    },
    /// The host simulation failed or cannot be mirrored (its groups do not share one device,
    /// a controller refused a frame, ...).
    #[error("simulation: {0}")]
    Sim(#[from] swarm_sim::SimError),
    /// A `--inject` fault specification that does not parse.
    #[error("--inject `{spec}`: {problem}")]
    FaultSpec {
        /// The specification given.
        spec: String,
        /// What is wrong with it.
        problem: String,
    },
    /// A firmware image that is not there, or not an ELF file.
    #[error("{}: {problem}", path.display())]
    Image {
        /// The image.
        path: std::path::PathBuf,
        /// What is wrong with it.
        problem: String,
    },
    /// A firmware name no board is known for.
    #[error(
        "unknown firmware `{0}` (ant-node, ant-node-fixed, bee-node, bee-node-fixed, fly-node, \
         fly-node-fixed)"
    )]
    UnknownFirmware(String),
    /// QEMU did not start the board as expected.
    #[error("qemu-system-arm did not open a pseudo-terminal; it said: {0}")]
    Qemu(String),
    /// A link this host cannot open (pseudo-terminals on a non-Unix host, a pseudo-terminal
    /// without a path, an address that resolves to nothing).
    #[error("{0}")]
    Unsupported(String),
    /// The soft device's thread panicked.
    #[error("the soft device thread panicked")]
    SoftDevicePanicked,
}

impl HilError {
    /// Applies `f` to the partial report of an [`HilError::Aborted`] (e.g. to add what the
    /// caller knows: fault counts, the image size); other errors pass unchanged.
    pub fn with_report(mut self, f: impl FnOnce(&mut crate::mirror::MirrorReport)) -> Self {
        if let HilError::Aborted { report, .. } = &mut self {
            f(report);
        }
        self
    }

    /// The partial report, when the run stopped part way.
    pub fn report(&self) -> Option<&crate::mirror::MirrorReport> {
        match self {
            HilError::Aborted { report, .. } => Some(report),
            _ => None,
        }
    }

    pub(crate) fn io(transport: &str, op: &'static str, source: std::io::Error) -> Self {
        HilError::Io {
            transport: transport.to_string(),
            op,
            source,
        }
    }
}
