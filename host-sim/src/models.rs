//! The built-in models: the one place in the simulator that names them. Everything else
//! reaches a model through [`Engine`].

use crate::ants::{AntSim, bench_ant_world};
use crate::bees::{BeeSim, bench_bee_world};
use crate::engine::Engine;
use crate::error::Result;
use crate::scenario::{Model, Scenario};

/// The engine of scenario `sc` with seed `seed`.
///
/// # Errors
///
/// What building the model's world refuses (see [`AntSim::from_scenario`],
/// [`BeeSim::from_scenario`]).
pub fn engine(sc: &Scenario, seed: u32) -> Result<Box<dyn Engine>> {
    Ok(match sc.world.model() {
        Model::Ant => Box::new(AntSim::from_scenario(sc, seed)?),
        Model::Bee => Box::new(BeeSim::from_scenario(sc, seed)?),
    })
}

/// The synthetic benchmark world of `model` with `agents` agents ([`bench_ant_world`],
/// [`bench_bee_world`]).
pub fn bench_engine(model: Model, agents: usize, seed: u32) -> Box<dyn Engine> {
    match model {
        Model::Ant => Box::new(bench_ant_world(agents, seed)),
        Model::Bee => Box::new(bench_bee_world(agents, seed)),
    }
}
