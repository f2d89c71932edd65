//! # swarm-hil
//!
//! The hardware-in-the-loop harness: it proves a device decides what the simulation decides.
//!
//! * [`transport`]: byte links to a device behind one [`Transport`] trait (in memory, serial
//!   ports and pseudo-terminals, TCP) and a fault-injecting wrapper.
//! * [`client`]: the host end of a session (handshake, pipelined requests, retries).
//! * [`soft`]: the soft device, `swarm-core`'s device endpoint served on the host.
//! * [`wire`]: the frame codec and the session protocol of `swarm_core`, shared with the
//!   firmware.

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
