//! li2015 on the host (issue 17): the engine that runs the insects of `swarm_core::li`
//! (waypoints from the learned distributions, Metropolis-Hastings against the density, ORCA),
//! the offline data pipeline of §3.1 that turns tracked trajectories into the model's
//! statistics, and the synthetic tracks that stand in for the paper's data (which are not
//! public).
//!
//! * [`LiSim`]: the engine (the shared [`Swarm3d`](crate::swarm3d::Swarm3d) host: container,
//!   obstacles, sensed insects);
//! * [`data`]: the learned tables and the density grid of a group (Gaussian targets,
//!   sketches, obstacles empty);
//! * [`segment`]: piecewise-linear segmentation of a track (the paper's R² = 0.9 rule, or a
//!   tolerance that follows the noise);
//! * [`stats`]: segment lengths and turning angles of a set of tracks, their moments and
//!   histograms (the tables [`swarm_core::li::sampler::Table`] samples), and the
//!   visiting-frequency density grid;
//! * [`infer`]: indirect inference of the segment process behind the tracks (the bias of the
//!   segmentation cancels);
//! * [`pipeline`]: tracks → [`model`] file (`swarm li fit`), and the synthetic tracks as a
//!   track file (`swarm li synth`);
//! * [`fixture`]: synthetic piecewise-linear tracks from a documented process (spec §2.1).
//!
//! The per-insect controller (Algorithm 1, Metropolis-Hastings) is [`swarm_core::li`].

mod build;
pub mod data;
pub mod fixture;
pub mod infer;
pub mod model;
pub mod pipeline;
pub(crate) mod scenario;
pub mod segment;
mod sim;
pub mod stats;

pub use build::bench_li_world;
pub use model::LiModel;
pub use pipeline::{FitOptions, fit, synthetic_csv};
pub use scenario::{DensitySpec, LiTable, Route, li_params, model_path, route_of};
pub use sim::{
    AnyLiGroup, Counts, Li, LiGroup, LiMeasures, LiSim, LiSimFrame, N, O, RouteRun, li_frame,
    mean_centroid_distance, total_variation,
};

#[cfg(test)]
mod tests;
