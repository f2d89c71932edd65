//! Spawn draws shared by every engine: where an agent starts is a pure function of the seed
//! and its id, like every other random number of a run.

use swarm_core::rand::rand;

use crate::scenario::{Scenario, SpawnRegion};

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

/// Where agent `id` of a 3D group spawning in `region` starts: uniform in the ball of radius
/// `radius` around the object's centre (radius ∝ ∛u, direction uniform on the sphere) or in
/// the box, from the run's counter-based draws.
pub fn point3(scenario: &Scenario, region: &SpawnRegion, seed: u32, id: u32) -> [f32; 3] {
    let u = |k| draw(seed, id, k);
    match region {
        SpawnRegion::Around { at, radius } => {
            let c: [f32; 3] = around_center(scenario, at);
            let r = radius * u(0).cbrt();
            let cos_t = 1.0 - 2.0 * u(1);
            let sin_t = (1.0 - cos_t * cos_t).max(0.0).sqrt();
            let phi = u(2) * std::f32::consts::TAU;
            [
                c[0] + r * sin_t * phi.cos(),
                c[1] + r * cos_t,
                c[2] + r * sin_t * phi.sin(),
            ]
        }
        SpawnRegion::Box { min, max } => {
            std::array::from_fn(|a| min[a] + (max[a] - min[a]) * u(a as u32))
        }
    }
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
