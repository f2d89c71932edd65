//! Builds a [`LiSim`] from a 3D [`Scenario`], applies its timed events (obstacles added,
//! removed and moved), records frames, and builds the synthetic world of `swarm bench
//! --model li`.

use swarm_core::li::{LiParams, LiState};
use swarm_core::{Fx, Vec3};

use super::data::{GridShape, fixture_tables, gaussian_weights};
use super::scenario::li_params;
use super::sim::{AnyLiGroup, LiGroup, LiSim};
use crate::by_scalar;
use crate::fly::{FlyWorld, clear_of, reach};
use crate::output::{AgentSample, Frame};
use crate::scalar::SimScalar;
use crate::scenario::{Action, Group, ScalarType, Scenario};
use crate::space::{BeeObstacle, Shape3};
use crate::spawn::{draw, spaced3};
use crate::{Result, SimError};

impl LiSim {
    /// The li2015 simulation of `scenario` (a 3D world, whose box is the container and the
    /// density grid's domain), with seed `seed`: the obstacles, the insects spawned at rest,
    /// each arrived at its start (its first step proposes a waypoint).
    ///
    /// # Errors
    ///
    /// [`SimError::WrongWorld`] for a 2D world, [`SimError::GroupParams`] for parameters the
    /// controller refuses, [`SimError::LiGrid`] for a density grid a device cannot hold.
    pub fn from_scenario(scenario: &Scenario, seed: u32) -> Result<LiSim> {
        let (min, max) = scenario.bounds::<3>("li")?;
        let params = scenario.group_params(|g| li_params(scenario, g))?;
        let range = params.iter().map(|p| p.range).fold(0.0, f32::max);
        let far = params
            .iter()
            .map(|p| reach(p.orca_radius(), p.tau, p.speed))
            .fold(0.0, f32::max);
        let mut world = FlyWorld::new(min, max, range, far);
        for (id, o) in scenario.objects.iter().enumerate() {
            if let Some(shape) = Shape3::of(&o.kind) {
                world
                    .obstacles
                    .push(BeeObstacle::new(id as u16, &o.name, shape, o.active));
            }
        }
        let groups = crate::spawn::groups(scenario, params, |g, p, first| {
            let r = p.orca_radius();
            let clear = |q: [f32; 3]| clear_of(&world.obstacles, min, max, r, q);
            let at = || spaced3(scenario, g, seed, first, 2.0 * r, clear);
            Ok::<AnyLiGroup, SimError>(match g.scalar {
                ScalarType::F32 => spawn::<f32>(g, p, first, at)?.into(),
                ScalarType::Fixed => spawn::<Fx>(g, p, first, at)?.into(),
            })
        })?;
        Ok(LiSim::new(world, groups, seed))
    }

    /// Applies a timed event of the scenario ([`FlyWorld::apply`]). The density grids are
    /// data: an obstacle moved later does not empty its new cells.
    pub fn apply(&mut self, object: u16, action: &Action) {
        self.world.apply(object, action);
    }
}

/// The insects of group `g`, ids `first..`, at rest and arrived at the places `at` gives
/// (uniform in its region, two ORCA radii apart, clear of the obstacles) once the parameters
/// are checked.
fn spawn<S: SimScalar>(
    g: &Group,
    params: LiParams<f32>,
    first: usize,
    at: impl FnOnce() -> Result<Vec<[f32; 3]>>,
) -> Result<LiGroup<S>> {
    let checked = params
        .cast::<S>()
        .checked()
        .map_err(|source| SimError::GroupParams {
            group: g.name.clone(),
            source,
        })?;
    let states = at()?
        .into_iter()
        .map(|p| LiState::at(Vec3::from_f32(p[0], p[1], p[2])))
        .collect();
    Ok(LiGroup::new(g.name.clone(), first, checked, states))
}

/// Every insect, in id order, as recorded samples: the heading is the unit actual velocity,
/// `label` 1 on a step it arrived and proposed, `motion` 1 when its ORCA program was
/// infeasible.
pub fn li_frame_samples(sim: &LiSim) -> Frame {
    fn push<S: SimScalar>(out: &mut [AgentSample], group: u16, g: &LiGroup<S>) {
        for (k, s) in g.states.iter().enumerate() {
            let v = s.vel.to_f32();
            let len = v.length();
            let heading = if len > 0.0 {
                [v.x / len, v.y / len, v.z / len]
            } else {
                [1.0, 0.0, 0.0]
            };
            let id = g.ids[k];
            let p = s.pos.to_f32();
            let d = g.decisions[k];
            out[id as usize] = AgentSample {
                id,
                pos: [p.x, p.y, p.z],
                heading,
                group,
                label: u8::from(d.proposals > 0),
                motion: u8::from(d.infeasible),
                roll: 0.0,
                pitch: 0.0,
            };
        }
    }
    let mut agents = vec![AgentSample::default(); sim.agents()];
    for (k, g) in sim.groups.iter().enumerate() {
        by_scalar!(g, g => push(&mut agents, k as u16, g));
    }
    Frame {
        step: sim.step,
        agents,
    }
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
    let weights = gaussian_weights(
        &shape,
        &[[side / 2.0; 3]],
        0.12 * scale,
        &[],
        ([0.0; 3], [side; 3]),
    );
    let (lengths, turns) = fixture_tables();
    let params = LiParams {
        lengths,
        turns,
        density: shape.with(&weights).expect("16³ cells fit"),
        ..LiParams::default()
    };
    let far = reach(params.orca_radius(), params.tau, params.speed);
    let w = FlyWorld::new([0.0; 3], [side; 3], params.range, far);
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
    let group = LiGroup::new("bench".into(), 0, params, states);
    LiSim::new(w, vec![group.into()], seed)
}
