//! # swarm-sim
//!
//! The std host simulator: whole ant colonies and bee swarms, every agent driven through the
//! same [`swarm_core`] controllers a microcontroller runs. The simulator is the reference a
//! device is checked against, so its sensor frames are built by public functions the HIL
//! harness calls too.
//!
//! * [`scenario`]: scenario files (TOML) and the built-in scenarios, checked before a run;
//! * [`ants`], [`bees`]: each model's world, sensing and deterministic parallel CPU engine;
//! * [`run`]: `swarm run`, a scenario from its first tick to its last into one output folder
//!   ([`output`]: CSV, `.npy`, JSON, PNG, GIF); [`mod@bench`]: `swarm bench`.
//!
//! The GPU backend is not built yet (issue 14).

pub use swarm_core;

pub mod ants;
pub mod bees;
pub mod bench;
pub mod engine;
mod error;
pub mod grid;
pub mod models;
pub mod output;
mod par;
pub mod run;
pub mod scalar;
pub mod scenario;
pub mod spawn;

pub use error::{Result, SimError};
