//! Spawn draws shared by every engine: where an agent starts is a pure function of the seed
//! and its id, like every other random number of a run.

use swarm_core::rand::rand;

use crate::scenario::Scenario;

/// The tick the spawn draws are keyed by: `u32::MAX`, never a simulated tick.
const SPAWN_STEP: u32 = u32::MAX;

/// Spawn draw `k` of agent `id`: uniform in [0, 1).
pub fn draw(seed: u32, id: u32, k: u32) -> f32 {
    rand(seed, id, SPAWN_STEP, k) as f32 / 4_294_967_296.0
}

/// The centre of the object a spawn region is `Around`, as `D` coordinates (the origin if the
/// object has no point centre of that dimension; validation rules that out).
pub fn around_center<const D: usize>(scenario: &Scenario, at: &str) -> [f32; D] {
    scenario
        .object(at)
        .and_then(|o| o.kind.point())
        .and_then(|c| <[f32; D]>::try_from(c).ok())
        .unwrap_or([0.0; D])
}

/// The groups of `scenario`, in order, each made by `make(group, params, first)` from its
/// parameters (`params`, one per group) and its first world slot (the agents before it).
///
/// # Errors
///
/// The first error of `make`.
pub fn groups<P, G: crate::scalar::AgentGroup>(
    scenario: &Scenario,
    params: Vec<P>,
    mut make: impl FnMut(&crate::scenario::Group, P, usize) -> crate::Result<G>,
) -> crate::Result<Vec<G>> {
    let mut out = Vec::with_capacity(params.len());
    let mut first = 0usize;
    for (g, p) in scenario.groups.iter().zip(params) {
        let group = make(g, p, first)?;
        first += group.len();
        out.push(group);
    }
    Ok(out)
}
