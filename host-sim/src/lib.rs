//! # swarm-sim
//!
//! The std host simulator (issue 3): whole swarms on the CPU (rayon) and the GPU (wgpu), every
//! agent driven through the same [`swarm_core`] controllers a microcontroller runs. This crate
//! is a seam for now; the engine lands with the simulator issue.

pub use swarm_core;
