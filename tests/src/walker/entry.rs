//! The walker's entry in the simulator's model table (what would be its line in a team's own
//! `swarm` binary): the rules of a walker group and the engine of a walker scenario. With it
//! registered (`swarm_sim::models::register(&ENTRY)`), scenario files may say
//! `model = "walker"` and `walker = { speed = 0.8 }`, and `swarm run`, `swarm bench` and
//! `swarm-hil loopback` serve it (`src/bin/walker-swarm.rs`, `src/bin/walker-swarm-hil.rs`).

use swarm_core::model::{Model, ModelParams};
use swarm_core::{Fx, Vec2};
use swarm_sim::engine::Engine;
use swarm_sim::models::ModelEntry;
use swarm_sim::scalar::SimScalar;
use swarm_sim::scenario::{
    Group, GroupCheck, ParamsOverride, Problem, ScalarType, Scenario, SpawnRegion,
};
use swarm_sim::spawn::{around_center, draw};
use swarm_sim::{Result, SimError};

use super::core::{WalkParams, WalkState};
use super::sim::WalkSim;

/// `[groups.walker]`: any of the walker's parameters, on top of the defaults.
pub type WalkParamsOverride = ParamsOverride<WalkParams<f32>>;

/// The walker in the model table.
pub static ENTRY: ModelEntry = ModelEntry {
    name: <WalkParams<f32> as Model>::NAME,
    about: "test-only random walkers between four walls, 2D",
    dim: 2,
    params: <WalkParams<f32> as ModelParams>::SPECS,
    check,
    engine: |sc, seed| from_scenario(sc, seed),
    // The walker benchmarks in f32 whatever the scalar asked for (a test model).
    bench_world: |n, seed, _scalar| {
        Box::new(WalkSim::<f32>::new(checked(WalkParams::default()), n, seed))
    },
    gpu: None,
};

/// Parameters the rules have passed.
fn checked<S: SimScalar>(p: WalkParams<S>) -> swarm_core::Checked<WalkParams<S>> {
    p.checked()
        .expect("the walker's defaults and checked overrides are valid")
}

/// The rules of a walker group: valid parameters, the walls inside the world, a spawn region
/// between the walls, and one parameter set and scalar for the whole scenario (a [`WalkSim`]
/// runs one).
fn check(c: &GroupCheck<'_>) -> std::result::Result<(), Problem> {
    let g = c.group;
    for (field, given) in [("nest", g.nest.is_some()), ("goal", g.goal.is_some())] {
        c.not_given(field, given, "walkers have no home and no goal")?;
    }
    let params = c
        .params::<WalkParamsOverride>()?
        .apply(WalkParams::default());
    c.check_params(&params, |p| p.cast::<Fx>().validate())?;
    let first = &c.scenario.groups[0];
    if c.index > 0 && (g.params != first.params || g.scalar != first.scalar) {
        return Err(c.problem(
            "walker",
            "every walker group of a scenario has the same parameters and scalar as groups[0]",
        ));
    }
    let w = params.half_width;
    let world = &c.scenario.world;
    if world.min().iter().any(|&lo| lo > -w) || world.max().iter().any(|&hi| hi < w) {
        return Err(c.problem(
            "walker.half_width",
            format!("the walls at ±{w} stand outside the world"),
        ));
    }
    let (lo, hi) = spawn_square(c.scenario, g);
    if lo.iter().chain(&hi).any(|v| v.abs() > w) {
        return Err(c.problem(
            "spawn",
            format!("walkers must start between the walls at ±{w}"),
        ));
    }
    Ok(())
}

/// The corners of group `g`'s spawn region: its box, or the square around its object (a
/// coordinate a malformed box lacks reads 0; the scenario's spawn rule refuses such a box).
fn spawn_square(sc: &Scenario, g: &Group) -> ([f32; 2], [f32; 2]) {
    match &g.spawn.region {
        SpawnRegion::Box { min, max } => {
            let corner = |p: &[f32]| [0, 1].map(|k| p.get(k).copied().unwrap_or(0.0));
            (corner(min), corner(max))
        }
        SpawnRegion::Around { at, radius } => {
            let c = around_center::<2>(sc, at);
            (c.map(|v| v - radius), c.map(|v| v + radius))
        }
    }
}

/// The walker simulation of `sc`: every group's walkers drawn uniformly in its spawn region
/// (a box, or the square around an object), heading along the spawn heading or +x.
fn from_scenario(sc: &Scenario, seed: u32) -> Result<Box<dyn Engine>> {
    let first = sc.groups.first().ok_or(SimError::NoAgents)?;
    let params = first
        .params_as::<WalkParamsOverride>()?
        .apply(WalkParams::default());
    Ok(match first.scalar {
        ScalarType::F32 => Box::new(build::<f32>(sc, params, seed)?),
        ScalarType::Fixed => Box::new(build::<Fx>(sc, params, seed)?),
    })
}

fn build<S: SimScalar>(sc: &Scenario, params: WalkParams<f32>, seed: u32) -> Result<WalkSim<S>> {
    let params = params
        .cast::<S>()
        .checked()
        .map_err(|source| SimError::GroupParams {
            group: sc.groups[0].name.clone(),
            source,
        })?;
    let mut states = Vec::new();
    for g in &sc.groups {
        let (lo, hi) = spawn_square(sc, g);
        let heading = match g.spawn.heading.as_deref() {
            Some(&[x, y]) => {
                let len = (x * x + y * y).sqrt();
                Vec2::from_f32(x / len, y / len)
            }
            _ => Vec2::from_f32(1.0, 0.0),
        };
        for _ in 0..g.count {
            let id = states.len() as u32;
            let at = |k: usize| lo[k] + (hi[k] - lo[k]) * draw(seed, id, k as u32);
            states.push(WalkState {
                pos: Vec2::from_f32(at(0), at(1)),
                heading,
                bounces: 0,
            });
        }
    }
    Ok(WalkSim::with_states(params, states, seed))
}
