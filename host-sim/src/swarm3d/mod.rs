//! What the 3D flying models with ORCA share on the host (ren2016's `fly`, li2015's `li`, and
//! any model whose insects sense a box, its obstacles and their neighbours' broadcasts):
//!
//! * [`World3d`]: the container, its obstacles and stimulus sources, what every insect
//!   broadcast at its last step, and the counting-sort neighbour grid; the backstop that keeps
//!   states physical;
//! * [`Swarm3d`]: the groups of insects of one model stepping in that world, in parallel and
//!   deterministically (the same bits on any thread count), as an
//!   [`Engine`](crate::engine::Engine).
//!
//! A model plugs in through [`Step3d`] and [`Model3d`]; its own folder keeps only its frame,
//! its counts and its measures.

mod engine;
mod swarm;
mod world;

pub use swarm::{AnyGroup3d, DecisionOf, Group3d, Insect, Model3d, StateOf, Step3d, Swarm3d};
pub use world::{Kinematic, Sensed, Source, World3d, clear_of, reach};
