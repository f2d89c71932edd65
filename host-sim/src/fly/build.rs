//! Builds a [`FlySim`] from a 3D [`Scenario`], applies its timed events (obstacles and stimulus
//! sources added, removed and moved: the predator crossing the swarm of Fig. 8), records
//! frames, and builds the synthetic world of `swarm bench --model fly`.

use swarm_core::fly::{FlyParams, FlyState};
use swarm_core::{Fx, Vec3};

use super::sense::Stimuli;
use super::sim::{AnyFlyGroup, FlyGroup, FlySim};
use super::world::{FlyWorld, Source, clear_of, reach};
use crate::by_scalar;
use crate::output::{AgentSample, Frame};
use crate::scalar::SimScalar;
use crate::scenario::{Action, Group, ObjectKind, ScalarType, Scenario};
use crate::space::{BeeObstacle, Shape3};
use crate::spawn::{draw, spaced3};
use crate::{Result, SimError};

impl FlySim {
    /// The ren2016 simulation of `scenario` (a 3D world, whose box is the container), with
    /// seed `seed`: the obstacles, the stimulus sources the groups name, the insects spawned
    /// at rest.
    ///
    /// # Errors
    ///
    /// [`SimError::WrongWorld`] for a 2D world, [`SimError::GroupParams`] for parameters the
    /// controller refuses, [`SimError::NoObject`] for a goal the scenario does not have or
    /// that has no centre.
    pub fn from_scenario(scenario: &Scenario, seed: u32) -> Result<FlySim> {
        let (min, max) = scenario.bounds::<3>("fly")?;
        let params = scenario.group_params(super::fly_params)?;
        let range = params.iter().map(|p| p.r_att).fold(0.0, f32::max);
        let far = params
            .iter()
            .map(|p| reach(p.orca_radius(), p.tau, p.max_speed))
            .fold(0.0, f32::max);
        let mut world = FlyWorld::new(min, max, range, far);
        for (id, o) in scenario.objects.iter().enumerate() {
            if let Some(shape) = Shape3::of(&o.kind) {
                world
                    .obstacles
                    .push(BeeObstacle::new(id as u16, &o.name, shape, o.active));
            }
        }
        let mut source_of = |g: &Group, what: &'static str, name: Option<&str>| {
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
                ObjectKind::Region { min, max } => (
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
                });
            }
            Ok(Some(id))
        };
        let groups = crate::spawn::groups(scenario, params, |g, p, first| {
            let stimuli = Stimuli {
                goal: source_of(g, "goal", g.goal.as_deref())?,
                threat: source_of(g, "threat", g.threat.as_deref())?,
            };
            let r = p.orca_radius();
            let clear = |q: [f32; 3]| clear_of(&world.obstacles, min, max, r, q);
            let at = || spaced3(scenario, g, seed, first, 2.0 * r, clear);
            Ok::<AnyFlyGroup, SimError>(match g.scalar {
                ScalarType::F32 => spawn::<f32>(g, p, stimuli, first, at)?.into(),
                ScalarType::Fixed => spawn::<Fx>(g, p, stimuli, first, at)?.into(),
            })
        })?;
        Ok(FlySim::new(world, groups, seed))
    }

    /// Applies a timed event of the scenario ([`FlyWorld::apply`]).
    pub fn apply(&mut self, object: u16, action: &Action) {
        self.world.apply(object, action);
    }
}

/// The insects of group `g`, ids `first..`, at rest at the places `at` gives once the
/// parameters are checked: spawned uniformly in its region
/// (box, or ball around an object's centre) with the scenario's counter-based random numbers,
/// at least two ORCA radii apart and clear of the obstacles ([`spaced3`],
/// [`clear_of`]): ORCA
/// keeps apart only insects that start apart.
fn spawn<S: SimScalar>(
    g: &Group,
    params: FlyParams<f32>,
    stimuli: Stimuli,
    first: usize,
    at: impl FnOnce() -> Result<Vec<[f32; 3]>>,
) -> Result<FlyGroup<S>> {
    let checked = params
        .cast::<S>()
        .checked()
        .map_err(|source| SimError::GroupParams {
            group: g.name.clone(),
            source,
        })?;
    let states = at()?
        .into_iter()
        .map(|p| FlyState::new(Vec3::from_f32(p[0], p[1], p[2]), Vec3::zero()))
        .collect();
    Ok(FlyGroup::new(
        g.name.clone(),
        first,
        checked,
        stimuli,
        states,
    ))
}

/// Every insect, in id order, as recorded samples: the heading is the unit actual velocity,
/// `label` 1 while it escapes a predator, `motion` 1 when its ORCA program was infeasible.
pub fn fly_frame_samples(sim: &FlySim) -> Frame {
    fn push<S: SimScalar>(out: &mut [AgentSample], group: u16, g: &FlyGroup<S>) {
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
            out[id as usize] = AgentSample {
                id,
                pos: [p.x, p.y, p.z],
                heading,
                group,
                label: u8::from(s.escaping),
                motion: u8::from(g.decisions[k].infeasible),
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
    let mut w = FlyWorld::new([0.0; 3], [side; 3], params.r_att, far);
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
