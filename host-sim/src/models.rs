//! The built-in models: the one place in the simulator that names them. Everything else
//! reaches a model through [`Engine`], and finds it here by name.

use crate::ants::{AntSim, bench_ant_world};
use crate::bees::{BeeSim, bench_bee_world};
use crate::engine::Engine;
use crate::error::{Result, SimError};
use crate::scenario::{Model, Scenario};

/// What the simulator knows of a model: how to build its engine for a scenario, and its
/// benchmark world.
#[derive(Clone, Copy, Debug)]
pub struct ModelEntry {
    /// The model's name, as scenario files write it (`ant`, `bee`).
    pub name: &'static str,
    /// Its engine for a scenario and a seed.
    pub engine: fn(&Scenario, u32) -> Result<Box<dyn Engine>>,
    /// Its synthetic benchmark world of `agents` agents and a seed (`swarm bench`).
    pub bench_world: fn(usize, u32) -> Box<dyn Engine>,
}

/// Every built-in model.
pub const BUILTIN: &[ModelEntry] = &[
    ModelEntry {
        name: "ant",
        engine: |sc, seed| Ok(Box::new(AntSim::from_scenario(sc, seed)?)),
        bench_world: |n, seed| Box::new(bench_ant_world(n, seed)),
    },
    ModelEntry {
        name: "bee",
        engine: |sc, seed| Ok(Box::new(BeeSim::from_scenario(sc, seed)?)),
        bench_world: |n, seed| Box::new(bench_bee_world(n, seed)),
    },
];

/// The built-in model called `name`.
pub fn find(name: &str) -> Option<&'static ModelEntry> {
    BUILTIN.iter().find(|m| m.name == name)
}

fn entry(model: Model) -> Result<&'static ModelEntry> {
    find(model.as_str()).ok_or_else(|| SimError::UnknownModel(model.as_str().into()))
}

/// The engine of scenario `sc` with seed `seed`.
///
/// # Errors
///
/// What building the model's world refuses (see [`AntSim::from_scenario`],
/// [`BeeSim::from_scenario`]).
pub fn engine(sc: &Scenario, seed: u32) -> Result<Box<dyn Engine>> {
    (entry(sc.world.model())?.engine)(sc, seed)
}

/// The synthetic benchmark world of `model` with `agents` agents ([`bench_ant_world`],
/// [`bench_bee_world`]).
///
/// # Errors
///
/// [`SimError::UnknownModel`] for a model without an entry.
pub fn bench_engine(model: Model, agents: usize, seed: u32) -> Result<Box<dyn Engine>> {
    Ok((entry(model)?.bench_world)(agents, seed))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_model_of_the_schema_has_its_entry_and_names_itself() {
        for model in [Model::Ant, Model::Bee] {
            let e = find(model.as_str()).expect("an entry");
            assert_eq!((e.bench_world)(10, 1).model(), model.as_str());
        }
    }
}
