//! Force-based flying insects with 3D ORCA (ren2016) on the host: the world, the sensor
//! frames, the engine.
//!
//! A [`FlySim`] (the shared [`Swarm3d`](crate::swarm3d::Swarm3d) host) holds a
//! [`World3d`](crate::swarm3d::World3d) (the container box, whose walls the insects sense, its
//! obstacles, the stimulus sources, and what every insect broadcast at its last step, with a
//! counting-sort neighbour grid) and the groups of insects, each running
//! `swarm_core::fly::step_checked` (Algorithm 1: zone forces, friction, stimulus response,
//! curl noise, then ORCA) on the frame [`fly_frame`] builds. A step reads only the previous
//! step's broadcast, so it runs in parallel and gives the same bits on any thread count.
//! ORCA's obstacle planes keep the insects out of obstacles and inside the container; the
//! world is the backstop and counts each time it has to act.

mod build;
pub(crate) mod scenario;
mod sense;
mod sim;
pub mod temperature;

#[cfg(test)]
mod tests;

pub use build::bench_fly_world;
pub use scenario::{FlyParamsOverride, FlyPreset, fly_params};
pub use sense::{
    FlySimFrame, N, O, Stimuli, ZONE_QUOTA, ahead_point, echo_point, fly_frame, zone_shares,
};
pub use sim::{AnyFlyGroup, Counts, Fly, FlyGroup, FlySim, Polarisation};
