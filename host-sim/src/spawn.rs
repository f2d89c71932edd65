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
    point3_try(scenario, region, seed, id, 0)
}

/// [`point3`]'s place number `attempt` for agent `id` (attempt 0 is [`point3`]'s), from its
/// own random numbers.
pub fn point3_try(
    scenario: &Scenario,
    region: &SpawnRegion,
    seed: u32,
    id: u32,
    attempt: u32,
) -> [f32; 3] {
    let u = |k| draw(seed, id, 3 * attempt + k);
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

/// Places tried per agent by [`spaced3`].
pub const SPACED_ATTEMPTS: u32 = 64;

/// The start positions of group `g`'s agents, ids `first..`, at least `distance` apart: each
/// agent in id order takes the first of its [`point3_try`] places (at most
/// [`SPACED_ATTEMPTS`]) that is `clear` (off the obstacles, say) and keeps the distance to the
/// agents placed before it.
///
/// # Errors
///
/// [`SimError::SpawnCrowded`](crate::SimError::SpawnCrowded) naming the first agent that
/// found no place.
pub fn spaced3(
    scenario: &Scenario,
    g: &crate::scenario::Group,
    seed: u32,
    first: usize,
    distance: f32,
    clear: impl Fn([f32; 3]) -> bool,
) -> crate::Result<Vec<[f32; 3]>> {
    use std::collections::HashMap;
    let cell = |p: [f32; 3]| p.map(|v| (v / distance.max(1e-6)).floor() as i64);
    let mut grid: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
    let mut placed: Vec<[f32; 3]> = Vec::with_capacity(g.count as usize);
    let d2 = distance * distance;
    for k in 0..g.count {
        let id = (first + k as usize) as u32;
        let free = |p: [f32; 3]| {
            let c = cell(p);
            (0..27).all(|n| {
                let at = [c[0] + n % 3 - 1, c[1] + n / 3 % 3 - 1, c[2] + n / 9 - 1];
                grid.get(&at).is_none_or(|near| {
                    near.iter().all(|&j| {
                        let q = placed[j];
                        (0..3).map(|a| (p[a] - q[a]).powi(2)).sum::<f32>() >= d2
                    })
                })
            })
        };
        let p = (0..SPACED_ATTEMPTS)
            .map(|a| point3_try(scenario, &g.spawn.region, seed, id, a))
            .find(|&p| clear(p) && free(p))
            .ok_or_else(|| crate::SimError::SpawnCrowded {
                group: g.name.clone(),
                agent: k,
                distance,
                attempts: SPACED_ATTEMPTS,
            })?;
        grid.entry(cell(p)).or_default().push(placed.len());
        placed.push(p);
    }
    Ok(placed)
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
