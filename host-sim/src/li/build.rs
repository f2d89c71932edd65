//! Builds a [`LiSim`] from a 3D [`Scenario`], and the synthetic world of `swarm bench
//! --model li`.

use swarm_core::li::{LiParams, LiState};
use swarm_core::{Fx, Vec3};

use super::data::{GridShape, fixture_tables, gaussian_weights};
use super::scenario::{li_params, route_of};
use super::sim::{AnyLiGroup, LiGroup, LiSim, RouteRun};
use crate::Result;
use crate::scalar::SimScalar;
use crate::scenario::{ScalarType, Scenario};
use crate::spawn::draw;
use crate::swarm3d::{World3d, reach};

impl LiSim {
    /// The li2015 simulation of `scenario` (a 3D world, whose box is the container and the
    /// density grid's domain), with seed `seed`: the obstacles, the insects spawned at rest,
    /// each arrived at its start (its first step proposes a waypoint). The density grids are
    /// data: an obstacle a timed event moves later does not empty its new cells.
    ///
    /// # Errors
    ///
    /// [`SimError::WrongWorld`](crate::SimError::WrongWorld) for a 2D world,
    /// [`SimError::GroupParams`](crate::SimError::GroupParams) for parameters the controller
    /// refuses, [`SimError::LiGrid`](crate::SimError::LiGrid) for a density grid a device
    /// cannot hold.
    pub fn from_scenario(scenario: &Scenario, seed: u32) -> Result<LiSim> {
        let mut sim = LiSim::build(scenario, seed, |g| li_params(scenario, g), |_, _| Ok(()))?;
        for g in &scenario.groups {
            let route = route_of(scenario, g)?.map(|(route, shape, weights)| {
                let held = route
                    .lights
                    .iter()
                    .zip(&weights)
                    .map(|(l, w)| held_within(&shape, w, *l, route.reach))
                    .collect();
                RouteRun {
                    route,
                    weights,
                    held,
                    leg: 0,
                    reached: Vec::new(),
                }
            });
            sim.measures.routes.push(route);
        }
        Ok(sim)
    }
}

/// The share of the density `weights` on `shape` within `reach` of `light` (cells by their
/// centres).
fn held_within(shape: &GridShape, weights: &[u8], light: [f32; 3], reach: f32) -> f64 {
    let (mut near, mut all) = (0.0, 0.0);
    for (i, &w) in weights.iter().enumerate() {
        let c = shape.centre(i);
        let d2: f32 = (0..3).map(|k| (c[k] - light[k]).powi(2)).sum();
        all += f64::from(w);
        if d2 <= reach * reach {
            near += f64::from(w);
        }
    }
    if all > 0.0 { near / all } else { 0.0 }
}

/// A swarm of `n` insects at the density of Fig. 4 (100 in the 0.91 m cube): a cube of side
/// 0.91·∛(n/100) with a Gaussian density at its centre (σ = 0.12·∛(n/100), 16³ cells), the
/// synthetic process's tables, spawned uniformly at rest. For `swarm bench --model li`.
pub fn bench_li_world(n: usize, seed: u32, scalar: ScalarType) -> LiSim {
    match scalar {
        ScalarType::F32 => bench_world::<f32>(n, seed),
        ScalarType::Fixed => bench_world::<Fx>(n, seed),
    }
}

fn bench_world<S: SimScalar>(n: usize, seed: u32) -> LiSim
where
    AnyLiGroup: From<LiGroup<S>>,
{
    let scale = (n.max(1) as f32 / 100.0).cbrt();
    let side = 0.91 * scale;
    let shape = GridShape::over([0.0; 3], [side; 3], 16).expect("16³ cells fit");
    let weights = gaussian_weights(&shape, &[[side / 2.0; 3]], 0.12 * scale, &[]);
    let (lengths, turns) = fixture_tables();
    let params = LiParams {
        lengths,
        turns,
        density: shape.with(&weights).expect("16³ cells fit"),
        ..LiParams::default()
    };
    let far = reach(params.orca_radius(), params.tau, params.speed);
    let w = World3d::new([0.0; 3], [side; 3], params.range, far);
    let states = (0..n as u32)
        .map(|i| {
            let r = |k| 0.05 * side + draw(seed, i, k) * 0.9 * side;
            LiState::at(Vec3::from_f32(r(0), r(1), r(2)))
        })
        .collect();
    let params = params
        .cast::<S>()
        .checked()
        .expect("the bench parameters are valid");
    let group = LiGroup::new("bench".into(), 0, params, (), states);
    LiSim::new(w, vec![group.into()], seed)
}
