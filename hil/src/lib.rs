//! # swarm-hil
//!
//! The hardware-in-the-loop harness: it proves a device decides what the simulation decides.
//!
//! * [`transport`]: byte links to a device behind one [`Transport`] trait (in memory, serial
//!   ports and pseudo-terminals, TCP) and a fault-injecting wrapper.
//! * [`client`]: the host end of a session (handshake, pipelined requests, retries), a pure
//!   state machine driven over any transport.
//! * [`mirror`]: a simulation of any model (a `swarm_sim::engine::Engine`) run on the host
//!   with every chosen agent's requests sent to the device and its answers compared, bit for
//!   bit, with the decisions the engine made; [`verdict`]: what a run concludes.
//! * [`loopback`]: the mirror against the soft device, in memory or over a pseudo-terminal.
//! * `qemu` (Unix): the firmware images in QEMU, on a pseudo-terminal.
//! * [`soft`]: the soft device, `swarm-core`'s device endpoint served on the host.
//! * `cli` (Unix): the `swarm-hil` command line, as a function a team's own binary calls
//!   after registering its models.
//! * [`wire`]: the frame codec and the session protocol of `swarm_core`, shared with the
//!   firmware.

#[cfg(unix)]
pub mod cli;
pub mod client;
mod error;
pub mod loopback;
pub mod mirror;
#[cfg(unix)]
pub mod qemu;
pub mod soft;
pub mod transport;
pub mod verdict;

pub use client::{Client, ClientOptions, LinkReport};
pub use error::{HilError, Result};
pub use swarm_core::wire;
pub use transport::Transport;
pub use verdict::Verdict;
