//! # swarm-sim
//!
//! The std host simulator: whole ant colonies and bee swarms, every agent driven through the
//! same [`swarm_core`] controllers a microcontroller runs. The simulator is the reference a
//! device is checked against, so its sensor frames are built by public functions the HIL
//! harness calls too.
//!
//! Work in progress (issue 3): scenario files, the CPU engine, outputs and the `swarm` CLI.

pub use swarm_core;

pub mod ants;
pub mod bees;
pub mod bench;
mod error;
pub mod grid;
pub mod output;
mod par;
pub mod run;
pub mod scalar;
pub mod scenario;
pub mod spawn;

pub use error::{Result, SimError};
