//! The model table: the one place in the simulator that names the built-in models, and where
//! a team registers its own ([`register`]). Everything else reaches a model through its
//! [`ModelEntry`], found by the name scenario files give it, and drives it through [`Engine`].

use std::sync::{PoisonError, RwLock};

use swarm_core::model::{ModelParams, ParamSpec};

use crate::ants::{AntSim, bench_ant_world};
use crate::bees::{BeeSim, bench_bee_world};
use crate::engine::Engine;
use crate::error::{Result, SimError};
use crate::fly::{FlySim, bench_fly_world};
use crate::gpu::Gpu;
use crate::gpu::ant::engine::GpuAntSim;
use crate::gpu::fly::engine::GpuFlySim;
use crate::gpu::li::GpuLiSim;
use crate::gpu::wang::engine::GpuWangSim;
use crate::li::{LiSim, bench_li_world};
use crate::scenario::{Backend, GroupCheck, Problem, ScalarType, Scenario};
use crate::wang::{WangSim, bench_wang_world};

/// What the simulator knows of a model: the world it lives in, the rules of its groups, how
/// to build its engine for a scenario, and its benchmark world.
#[derive(Clone, Copy, Debug)]
pub struct ModelEntry {
    /// The model's name, as scenario files write it (`model = "ant"`) and as its groups' parameter
    /// table is called (`ant = { .. }`).
    pub name: &'static str,
    /// One line on what it is (paper, world), for listings and `--help`.
    pub about: &'static str,
    /// The dimension of its world: 2 (`dim = 2`, `[x, y]`) or 3.
    pub dim: usize,
    /// Its parameter table ([`ModelParams::SPECS`]): every name a group's parameter table
    /// may set and the values each may take (what calibration searches within).
    ///
    /// [`ModelParams::SPECS`]: swarm_core::model::ModelParams::SPECS
    pub params: &'static [ParamSpec],
    /// The rules of one of its groups, after those every group follows: the objects it
    /// names, its parameter table ([`GroupCheck::params`]), the parameters' ranges
    /// ([`GroupCheck::check_params`]).
    pub check: fn(&GroupCheck<'_>) -> std::result::Result<(), Problem>,
    /// Its engine for a scenario (every group of which is of this model) and a seed.
    pub engine: fn(&Scenario, u32) -> Result<Box<dyn Engine>>,
    /// Its synthetic benchmark world of `agents` agents, a seed and a scalar type (`swarm
    /// bench`).
    pub bench_world: fn(usize, u32, ScalarType) -> Box<dyn Engine>,
    /// Its GPU engine, if it has one (`--backend gpu`).
    pub gpu: Option<GpuEntry>,
}

/// A model's GPU engine: the same simulation as its CPU engine, decided on the GPU.
#[derive(Clone, Copy, Debug)]
pub struct GpuEntry {
    /// Its GPU engine for a scenario and a seed, on a GPU.
    pub engine: fn(&Scenario, u32, Gpu) -> Result<Box<dyn Engine>>,
    /// Its benchmark world on a GPU, as [`ModelEntry::bench_world`].
    pub bench_world: GpuBenchWorld,
}

/// [`GpuEntry::bench_world`]: agents, seed, scalar type, the GPU.
pub type GpuBenchWorld = fn(usize, u32, ScalarType, Gpu) -> Result<Box<dyn Engine>>;

/// Every built-in model.
pub const BUILTIN: &[ModelEntry] = &[
    ModelEntry {
        name: "ant",
        about: "ant foraging colonies (xiang2018), 2D",
        dim: 2,
        params: <swarm_core::ant::AntParams<f32> as ModelParams>::SPECS,
        check: crate::ants::scenario::check,
        engine: |sc, seed| Ok(Box::new(AntSim::from_scenario(sc, seed)?)),
        bench_world: |n, seed, scalar| Box::new(bench_ant_world(n, seed, scalar)),
        gpu: Some(GpuEntry {
            engine: |sc, seed, gpu| {
                Ok(Box::new(GpuAntSim::new(
                    AntSim::from_scenario(sc, seed)?,
                    gpu,
                )?))
            },
            bench_world: |n, seed, scalar, gpu| {
                Ok(Box::new(GpuAntSim::new(
                    bench_ant_world(n, seed, scalar),
                    gpu,
                )?))
            },
        }),
    },
    ModelEntry {
        name: "bee",
        about: "bee swarms with visual roll-to-avoid (chen), 3D",
        dim: 3,
        params: <swarm_core::bee::BeeParams<f32> as ModelParams>::SPECS,
        check: crate::bees::scenario::check,
        engine: |sc, seed| Ok(Box::new(BeeSim::from_scenario(sc, seed)?)),
        bench_world: |n, seed, scalar| Box::new(bench_bee_world(n, seed, scalar)),
        gpu: Some(GpuEntry {
            engine: |sc, seed, gpu| {
                Ok(Box::new(crate::gpu::bee::engine::GpuBeeSim::new(
                    BeeSim::from_scenario(sc, seed)?,
                    gpu,
                )?))
            },
            bench_world: |n, seed, scalar, gpu| {
                Ok(Box::new(crate::gpu::bee::engine::GpuBeeSim::new(
                    bench_bee_world(n, seed, scalar),
                    gpu,
                )?))
            },
        }),
    },
    ModelEntry {
        name: "wang",
        about: "noise-aware insect swarms: curl noise, fast-marching navigation and minimum \
                distance enforcement (wang2014), 3D",
        dim: 3,
        params: <swarm_core::wang::WangParams<f32> as ModelParams>::SPECS,
        check: crate::wang::scenario::check,
        engine: |sc, seed| Ok(Box::new(WangSim::from_scenario(sc, seed)?)),
        bench_world: |n, seed, scalar| Box::new(bench_wang_world(n, seed, scalar)),
        gpu: Some(GpuEntry {
            engine: |sc, seed, gpu| {
                Ok(Box::new(GpuWangSim::new(
                    WangSim::from_scenario(sc, seed)?,
                    gpu,
                )?))
            },
            bench_world: |n, seed, scalar, gpu| {
                Ok(Box::new(GpuWangSim::new(
                    bench_wang_world(n, seed, scalar),
                    gpu,
                )?))
            },
        }),
    },
    ModelEntry {
        name: "fly",
        about: "force-based flying insects with 3D ORCA (ren2016), 3D",
        dim: 3,
        params: <swarm_core::fly::FlyParams<f32> as ModelParams>::SPECS,
        check: crate::fly::scenario::check,
        engine: |sc, seed| Ok(Box::new(FlySim::from_scenario(sc, seed)?)),
        bench_world: |n, seed, scalar| Box::new(bench_fly_world(n, seed, scalar)),
        gpu: Some(GpuEntry {
            engine: |sc, seed, gpu| {
                Ok(Box::new(GpuFlySim::new(
                    FlySim::from_scenario(sc, seed)?,
                    gpu,
                )?))
            },
            bench_world: |n, seed, scalar, gpu| {
                Ok(Box::new(GpuFlySim::new(
                    bench_fly_world(n, seed, scalar),
                    gpu,
                )?))
            },
        }),
    },
    ModelEntry {
        name: "li",
        about: "data-driven insects: waypoints from measured statistics, Metropolis-Hastings \
                density control and 3D ORCA (li2015), 3D",
        dim: 3,
        params: <swarm_core::li::LiParams<f32> as ModelParams>::SPECS,
        check: crate::li::scenario::check,
        engine: |sc, seed| Ok(Box::new(LiSim::from_scenario(sc, seed)?)),
        bench_world: |n, seed, scalar| Box::new(bench_li_world(n, seed, scalar)),
        gpu: Some(GpuEntry {
            engine: |sc, seed, gpu| {
                Ok(Box::new(GpuLiSim::new(
                    LiSim::from_scenario(sc, seed)?,
                    gpu,
                )?))
            },
            bench_world: |n, seed, scalar, gpu| {
                Ok(Box::new(GpuLiSim::new(
                    bench_li_world(n, seed, scalar),
                    gpu,
                )?))
            },
        }),
    },
];

/// The models registered besides the built-ins, in registration order.
static REGISTERED: RwLock<Vec<&'static ModelEntry>> = RwLock::new(Vec::new());

/// Adds `entry` to the model table of this process: scenario files may then name it, and
/// `swarm run`, `swarm bench` and the HIL mirror serve it (call it before
/// [`cli::main`](crate::cli::main) to build a `swarm` that knows the model). Registering the
/// same entry again does nothing.
///
/// # Errors
///
/// [`SimError::ModelTaken`] when another model has the name.
pub fn register(entry: &'static ModelEntry) -> Result<()> {
    let mut registered = REGISTERED.write().unwrap_or_else(PoisonError::into_inner);
    match find_in(&registered, entry.name) {
        Some(e) if std::ptr::eq(e, entry) => Ok(()),
        Some(_) => Err(SimError::ModelTaken(entry.name)),
        None => {
            registered.push(entry);
            Ok(())
        }
    }
}

fn find_in(registered: &[&'static ModelEntry], name: &str) -> Option<&'static ModelEntry> {
    BUILTIN
        .iter()
        .chain(registered.iter().copied())
        .find(|m| m.name == name)
}

/// The model called `name`: built in or registered.
pub fn find(name: &str) -> Option<&'static ModelEntry> {
    find_in(
        &REGISTERED.read().unwrap_or_else(PoisonError::into_inner),
        name,
    )
}

/// Every model: the built-ins, then the registered ones.
pub fn all() -> Vec<&'static ModelEntry> {
    let registered = REGISTERED.read().unwrap_or_else(PoisonError::into_inner);
    BUILTIN.iter().chain(registered.iter().copied()).collect()
}

/// The models' names: the built-ins, then the registered ones.
pub fn names() -> Vec<&'static str> {
    all().iter().map(|m| m.name).collect()
}

/// The models' names, as an error lists them (`ant, bee`).
fn known() -> String {
    names().join(", ")
}

/// The model called `name`, or [`SimError::UnknownModel`].
///
/// # Errors
///
/// [`SimError::UnknownModel`], listing the models there are.
pub fn get(name: &str) -> Result<&'static ModelEntry> {
    find(name).ok_or_else(|| SimError::UnknownModel {
        name: name.into(),
        known: known(),
    })
}

/// The engine of scenario `sc` with seed `seed`: its groups' model's.
///
/// # Errors
///
/// [`SimError::NoAgents`] for a scenario without groups, [`SimError::UnknownModel`], what
/// building the model's world refuses (see [`AntSim::from_scenario`],
/// [`BeeSim::from_scenario`]).
pub fn engine(sc: &Scenario, seed: u32) -> Result<Box<dyn Engine>> {
    let model = sc.groups.first().ok_or(SimError::NoAgents)?.model.as_str();
    let entry = get(model)?;
    match sc.backend {
        Backend::Cpu => (entry.engine)(sc, seed),
        Backend::Gpu => (gpu_entry(entry)?.engine)(sc, seed, Gpu::shared()?),
    }
}

/// The GPU engine of `entry`, or [`SimError::NoGpuEngine`].
fn gpu_entry(entry: &ModelEntry) -> Result<GpuEntry> {
    entry.gpu.ok_or_else(|| SimError::NoGpuEngine {
        model: entry.name.into(),
    })
}

/// The synthetic benchmark world of model `name` with `agents` agents ([`bench_ant_world`],
/// [`bench_bee_world`]).
///
/// # Errors
///
/// [`SimError::UnknownModel`] for a model without an entry.
pub fn bench_engine(
    name: &str,
    agents: usize,
    seed: u32,
    scalar: ScalarType,
    backend: Backend,
) -> Result<Box<dyn Engine>> {
    let entry = get(name)?;
    match backend {
        Backend::Cpu => Ok((entry.bench_world)(agents, seed, scalar)),
        Backend::Gpu => (gpu_entry(entry)?.bench_world)(agents, seed, scalar, Gpu::shared()?),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_built_in_model_names_itself() {
        for m in BUILTIN {
            assert_eq!(find(m.name).map(|e| e.name), Some(m.name));
            assert_eq!((m.bench_world)(10, 1, ScalarType::F32).model(), m.name);
        }
        assert!(matches!(
            get("wasp"),
            Err(SimError::UnknownModel { known, .. }) if known.starts_with("ant, bee")
        ));
    }

    #[test]
    fn a_model_without_a_gpu_engine_is_refused_by_name_on_the_gpu() {
        static NO_GPU: ModelEntry = ModelEntry {
            name: "cpu-only",
            gpu: None,
            ..BUILTIN[0]
        };
        register(&NO_GPU).unwrap();
        let e = bench_engine("cpu-only", 10, 1, ScalarType::F32, Backend::Gpu)
            .err()
            .unwrap();
        assert!(
            matches!(&e, SimError::NoGpuEngine { model } if model == "cpu-only"),
            "{e}"
        );
        assert!(e.to_string().contains("--backend cpu"), "{e}");
        assert!(bench_engine("cpu-only", 10, 1, ScalarType::F32, Backend::Cpu).is_ok());
    }

    #[test]
    fn a_name_is_registered_once() {
        static ANT_AGAIN: ModelEntry = BUILTIN[0];
        assert!(matches!(
            register(&ANT_AGAIN),
            Err(SimError::ModelTaken("ant"))
        ));
    }
}
