//! Ant colonies (xiang2018) on the host: the world, the sensor frames, the engine.

mod bench;
mod build;
mod engine;
pub(crate) mod scenario;
mod sense;
mod sim;
mod world;

pub use bench::bench_ant_world;
pub use engine::ANT_COLLISION_DISTANCE;
pub use scenario::{AntParamsOverride, ant_params};
pub use sense::{AntPlanFrame, AntResolveFrame, N, O, plan_frame, resolve_frame};
pub use sim::{AntEvent, AntGroup, AntSim, AnyAntGroup, ROUTE_ADVANCE};
pub(crate) use world::edge_normal;
pub use world::{AntObjectDef, AntObjectKind, AntWorld, Sensed, Shape2};
