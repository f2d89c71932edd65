//! Noise-aware insect swarms (wang2014) on the host: the world and its global fields, the
//! sensor frames, the engine.
//!
//! A [`WangSim`] holds a [`WangWorld`] (the volume, its obstacles and goals, the signed
//! distance and the minimum-cost field of each goal solved by fast marching, eq. 4-8, and the
//! tentative positions every insect broadcast) and the groups of insects, each running
//! `swarm_core::wang::advect` then `swarm_core::wang::separate` (minimum distance enforcement,
//! §6) on the frames the world builds. The fields are solved when the simulation is built and
//! again when an event moves, adds or removes an obstacle or a goal (Fig. 8's chase); each
//! solve's cost is written in the run log.

mod build;
mod engine;
pub mod metrics;
pub(crate) mod scenario;
mod sim;
mod world;

pub use build::{WangBenchShape, bench_wang_world, bench_wang_world_shaped, wang_frame_samples};
pub use metrics::Metrics;
pub use scenario::{WangParamsOverride, WangPreset, wang_params};
pub use sim::{AnyWangGroup, Counts, K, WangGroup, WangSeparateFrame, WangSim};
pub use world::{Goal, GoalArea, WangWorld};

#[cfg(test)]
mod tests;
