//! li2015 on the host (issue 17): the offline data pipeline of §3.1 that turns tracked
//! trajectories into the model's statistics, and the synthetic tracks that stand in for the
//! paper's data (which are not public).
//!
//! * [`segment`]: piecewise-linear segmentation of a track by the R² = 0.9 rule;
//! * [`stats`]: segment lengths and turning angles of a set of tracks, their moments and
//!   histograms (the tables [`swarm_core::li::sampler::Table`] samples), and the
//!   visiting-frequency density grid;
//! * [`fixture`]: synthetic piecewise-linear tracks from a documented process (spec §2.1).
//!
//! The per-insect controller (Algorithm 1, Metropolis-Hastings) is [`swarm_core::li`].

pub mod fixture;
pub mod segment;
pub mod stats;

#[cfg(test)]
mod tests;
