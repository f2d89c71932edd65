//! Builds a [`FlySim`] from a 3D [`Scenario`] (the stimulus sources its groups name), and the
//! synthetic world of `swarm bench --model fly`.

use swarm_core::fly::{FlyParams, FlyState};
use swarm_core::{Fx, Vec3};

use super::sense::Stimuli;
use super::sim::{AnyFlyGroup, FlyGroup, FlySim};
use crate::scalar::SimScalar;
use crate::scenario::{Group, ObjectKind, ScalarType, Scenario};
use crate::space::{BeeObstacle, Shape3};
use crate::spawn::draw;
use crate::swarm3d::{Source, World3d, reach};
use crate::{Result, SimError};

impl FlySim {
    /// The ren2016 simulation of `scenario` (a 3D world, whose box is the container), with
    /// seed `seed`: the obstacles, the stimulus sources the groups name, the insects spawned
    /// at rest ([`FlySim::build`]).
    ///
    /// # Errors
    ///
    /// [`SimError::WrongWorld`] for a 2D world, [`SimError::GroupParams`] for parameters the
    /// controller refuses, [`SimError::NoObject`] for a goal the scenario does not have or
    /// that has no centre.
    pub fn from_scenario(scenario: &Scenario, seed: u32) -> Result<FlySim> {
        FlySim::build(scenario, seed, super::fly_params, |g, world| {
            Ok(Stimuli {
                goal: source_of(scenario, world, g, "goal", g.goal.as_deref())?,
                threat: source_of(scenario, world, g, "threat", g.threat.as_deref())?,
            })
        })
    }
}

/// The id of the object `name` that group `g` names as its `what`, added to the world's
/// stimulus sources (once).
fn source_of(
    scenario: &Scenario,
    world: &mut World3d,
    g: &Group,
    what: &'static str,
    name: Option<&str>,
) -> Result<Option<u16>> {
    let Some(name) = name else {
        return Ok(None);
    };
    let no_object = || SimError::NoObject {
        group: g.name.clone(),
        what,
        name: name.to_string(),
    };
    let id = scenario.object_id(name).ok_or_else(no_object)?;
    let o = &scenario.objects[usize::from(id)];
    let (center, region) = match o.kind {
        ObjectKind::Region { min, max } | ObjectKind::Cave { min, max } => (
            std::array::from_fn(|k| 0.5 * (min[k] + max[k])),
            Some([min, max]),
        ),
        ref kind => {
            let &[x, y, z] = kind.center().ok_or_else(no_object)? else {
                return Err(no_object());
            };
            ([x, y, z], None)
        }
    };
    if !world.sources.iter().any(|s| s.id == id) {
        world.sources.push(Source {
            id,
            name: o.name.clone(),
            center,
            active: o.active,
            region,
            cave: matches!(o.kind, ObjectKind::Cave { .. }),
        });
    }
    Ok(Some(id))
}

/// A swarm of `n` midges (Table 1's Midge column, in `scalar`) at the density of Fig. 1 (100
/// in a 20-unit box): a cube container of side 20·∛(n/100) holding a sphere, the insects
/// spawned through it at rest. For `swarm bench --model fly`.
pub fn bench_fly_world(n: usize, seed: u32, scalar: ScalarType) -> FlySim {
    match scalar {
        ScalarType::F32 => bench_world::<f32>(n, seed),
        ScalarType::Fixed => bench_world::<Fx>(n, seed),
    }
}

fn bench_world<S: SimScalar>(n: usize, seed: u32) -> FlySim
where
    AnyFlyGroup: From<FlyGroup<S>>,
{
    let side = 20.0 * (n.max(1) as f32 / 100.0).cbrt();
    let params = FlyParams::<f32>::midge();
    let far = reach(params.orca_radius(), params.tau, params.max_speed);
    let mut w = World3d::new([0.0; 3], [side; 3], params.r_att, far);
    let c = side / 2.0;
    let ball = Shape3::Sphere {
        center: [c; 3],
        radius: 0.1 * side,
    };
    w.obstacles.push(BeeObstacle::new(0, "ball", ball, true));
    let states: Vec<FlyState<S>> = (0..n as u32)
        .map(|i| {
            let r = |k| 0.5 + draw(seed, i, k) * (side - 1.0);
            let mut s = FlyState::new(Vec3::from_f32(r(0), r(1), r(2)), Vec3::zero());
            // Spawned inside the ball: on its surface instead.
            w.confine(&mut s);
            s
        })
        .collect();
    let params = params
        .cast::<S>()
        .checked()
        .expect("Table 1 parameters are valid");
    let group = FlyGroup::new("bench".into(), 0, params, Stimuli::default(), states);
    FlySim::new(w, vec![group.into()], seed)
}
