//! # swarm-hil
//!
//! The hardware-in-the-loop harness (issue 4). For now it re-exports the frame codec of
//! [`swarm_core::wire`], which the session protocol will be built on.

pub use swarm_core::wire;
