//! Bee swarms (chen) on the host: the world, the sensor frames, the engine.
//!
//! A [`BeeSim`] holds a [`BeeWorld`] (the volume, its obstacles and targets, and the sensed
//! state of every bee in `f64` struct-of-arrays with a counting-sort neighbour grid) and the
//! groups of bees, each running `swarm_core::bee::step_checked` on the frame [`bee_frame`]
//! builds. A step reads only the previous step's sensed world, so it runs in parallel and gives
//! the same bits on any thread count. The controller steers clear of obstacles by itself; the
//! world is the backstop: it keeps bees out of obstacles and inside the bounds and counts each
//! time it has to ([`Contacts`]: none in 2000 steps of `bees-fig14-shafts`).

mod build;
mod engine;
pub(crate) mod scenario;
mod sense;
mod sim;
mod world;

#[cfg(test)]
mod tests;

pub use build::{FIG11_DENSITY, bee_frame_samples, bench_bee_world};
pub use scenario::{BeeParamsOverride, BeePreset, bee_params};
pub use sense::{BeeSimFrame, N, P, bee_frame, neighbour_slots};
pub use sim::{AnyBeeGroup, BeeGroup, BeeSim, Contacts, bee_frame_time, frame_time};
pub use world::{
    BeeObstacle, BeeTarget, BeeWorld, SURFACE_OFFSET, Sensed, Shape3, Surface, box_surface,
    box_surface_open, confine, shaft_surface, shaft_surface_open, sphere_surface,
};
