//! Builds a [`BeeSim`] from a 3D [`Scenario`], applies its timed events, records frames, and
//! builds the synthetic world of `swarm bench --model bees`.

use swarm_core::bee::{BeeParams, BeeState};
use swarm_core::{Fx, Vec3};

use super::sim::{AnyBeeGroup, BeeGroup, BeeSim};
use super::world::{BeeObstacle, BeeTarget, BeeWorld, Shape3};
use crate::by_scalar;
use crate::output::{AgentSample, Frame};
use crate::scalar::SimScalar;
use crate::scenario::{Action, Group, ObjectKind, ScalarType, Scenario};
use crate::spawn::{draw, point3};
use crate::{Result, SimError};

/// The neighbour range h + 2r and the obstacle sensing range 2·d0 of `params`.
fn ranges(params: &BeeParams<f32>) -> (f32, f32) {
    (params.h + 2.0 * params.radius, 2.0 * params.d0)
}

impl BeeSim {
    /// The bee simulation of `scenario` (a 3D world), with seed `seed`.
    pub fn from_scenario(scenario: &Scenario, seed: u32) -> Result<BeeSim> {
        let (min, max) = scenario.bounds::<3>("bee")?;
        let params = scenario.group_params(super::bee_params)?;
        let (range, sense) = params
            .iter()
            .map(ranges)
            .fold((0.0f32, 0.0f32), |(a, b), (r, s)| (a.max(r), b.max(s)));
        let mut world = BeeWorld::new(min, max, range, sense);
        for (id, o) in scenario.objects.iter().enumerate() {
            let id = id as u16;
            if let Some(shape) = Shape3::of(&o.kind) {
                world
                    .obstacles
                    .push(BeeObstacle::new(id, &o.name, shape, o.active));
            } else if let ObjectKind::Target {
                center,
                radius,
                particles,
            } = o.kind
            {
                world.targets.push(BeeTarget {
                    id,
                    name: o.name.clone(),
                    center,
                    radius,
                    particles,
                    active: o.active,
                });
            }
        }

        // The scenario's own radius, not its conversion to a fixed-point group's scalar.
        let collision = super::sim::collision_distance(params.iter().map(|p| p.radius));
        let groups = crate::spawn::groups(scenario, params, |g, p, first| {
            let goal = match g.goal.as_deref() {
                Some(name) => Some(scenario.object_id(name).ok_or_else(|| SimError::NoObject {
                    group: g.name.clone(),
                    what: "goal",
                    name: name.to_string(),
                })?),
                None => None,
            };
            Ok::<AnyBeeGroup, SimError>(match g.scalar {
                ScalarType::F32 => spawn::<f32>(scenario, g, p, goal, first, seed)?.into(),
                ScalarType::Fixed => spawn::<Fx>(scenario, g, p, goal, first, seed)?.into(),
            })
        })?;
        let mut sim = BeeSim::new(world, groups, seed);
        sim.collision_distance = collision;
        Ok(sim)
    }

    /// Applies a timed event of the scenario (`Action` on the object with id `object`):
    /// add/start, remove/stop, move (spheres, shafts and targets; a moved target is sampled
    /// again and its groups fly to the new centre).
    pub fn apply(&mut self, object: u16, action: &Action) {
        let w = &mut self.world;
        if let Some(o) = w.obstacles.iter_mut().find(|o| o.id == object) {
            match action {
                Action::Add(_) | Action::Start(_) => o.active = true,
                Action::Remove(_) | Action::Stop(_) => o.active = false,
                Action::Move { to, .. } => {
                    o.set_center(to);
                }
            }
        } else if let Some(t) = w.targets.iter_mut().find(|t| t.id == object) {
            match action {
                Action::Add(_) | Action::Start(_) => t.active = true,
                Action::Remove(_) | Action::Stop(_) => t.active = false,
                Action::Move { to, .. } => {
                    if let &[x, y, z] = to.as_slice() {
                        t.center = [x, y, z];
                    }
                }
            }
            w.index_targets();
        }
    }
}

/// The bees of group `g`, ids `first..`, spawned uniformly in its region (box, or ball around
/// an object's centre) with the scenario's counter-based random numbers. They start at rest,
/// or flying at 1 unit/s along the spawn heading when the group has one.
fn spawn<S: SimScalar>(
    scenario: &Scenario,
    g: &Group,
    params: BeeParams<f32>,
    goal: Option<u16>,
    first: usize,
    seed: u32,
) -> Result<BeeGroup<S>> {
    let checked = params
        .cast::<S>()
        .checked()
        .map_err(|source| SimError::GroupParams {
            group: g.name.clone(),
            source,
        })?;
    let velocity = match g.spawn.heading.as_deref() {
        Some(&[x, y, z]) => {
            let len = (x * x + y * y + z * z).sqrt();
            if len > 0.0 {
                [x / len, y / len, z / len]
            } else {
                [0.0; 3]
            }
        }
        _ => [0.0; 3],
    };
    let states = (0..g.count)
        .map(|k| {
            let id = (first + k as usize) as u32;
            let pos = point3(scenario, &g.spawn.region, seed, id);
            BeeState::new(
                Vec3::from_f32(pos[0], pos[1], pos[2]),
                Vec3::from_f32(velocity[0], velocity[1], velocity[2]),
            )
        })
        .collect();
    Ok(BeeGroup::new(g.name.clone(), first, checked, goal, states))
}

/// Every bee of the simulation, in id order, as recorded samples: the heading is the unit
/// velocity (for a bee at rest, its body's forward axis), `label` 0, `motion` 1 while it avoids
/// an obstacle (else 0), `roll` and `pitch` the last decision's set-points in degrees.
pub fn bee_frame_samples(sim: &BeeSim) -> Frame {
    fn push<S: SimScalar>(out: &mut [AgentSample], group: u16, g: &BeeGroup<S>) {
        for (k, (s, d)) in g.states.iter().zip(&g.decisions).enumerate() {
            let v = s.vel.to_f32();
            let len = v.length();
            let h = if len > 0.0 {
                [v.x / len, v.y / len, v.z / len]
            } else {
                let f = s.forward.to_f32();
                [f.x, f.y, f.z]
            };
            let id = g.ids[k];
            out[id as usize] = AgentSample {
                id,
                pos: [s.pos.x.to_f32(), s.pos.y.to_f32(), s.pos.z.to_f32()],
                heading: h,
                group,
                label: 0,
                motion: u8::from(d.avoiding),
                roll: d.roll.to_f32().to_degrees(),
                pitch: d.pitch.to_f32().to_degrees(),
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

/// Bees per unit³ of chen Fig. 11 (`bees-fig11-grassland`): 1000 bees spawned in a
/// 40 × 12 × 40 box.
pub const FIG11_DENSITY: f32 = 1000.0 / (40.0 * 12.0 * 40.0);

/// A swarm of `n` bees (Table I "over grassland", `f32`) spread uniformly at the density of
/// chen Fig. 11 in a 40:12:40 box, over a ground slab, among four shafts, flying to a nest
/// target in the middle: every kind of interaction happens somewhere. For n = 1000 the volume
/// is the Fig. 11 scenario's (60 × 30 × 60). The bees compute in `scalar`.
pub fn bench_bee_world(n: usize, seed: u32, scalar: ScalarType) -> BeeSim {
    match scalar {
        ScalarType::F32 => bench_world::<f32>(n, seed),
        ScalarType::Fixed => bench_world::<Fx>(n, seed),
    }
}

fn bench_world<S: SimScalar>(n: usize, seed: u32) -> BeeSim
where
    AnyBeeGroup: From<BeeGroup<S>>,
{
    let params = BeeParams::<f32>::grassland();
    let s = ((n.max(1) as f32 / (FIG11_DENSITY * 40.0 * 12.0 * 40.0)).cbrt()).clamp(0.2, 300.0);
    let (sx, sy) = (40.0 * s, 12.0 * s);
    let (wx, wy) = (sx + 20.0, sy + 18.0);
    let (range, sense) = ranges(&params);
    let mut w = BeeWorld::new([0.0; 3], [wx, wy, wx], range, sense);
    w.obstacles.push(BeeObstacle::new(
        0,
        "ground",
        Shape3::Box {
            min: [0.0; 3],
            max: [wx, 1.0, wx],
        },
        true,
    ));
    for (k, (a, b)) in [(1.0, 1.0), (2.0, 1.0), (1.0, 2.0), (2.0, 2.0)]
        .into_iter()
        .enumerate()
    {
        let shaft = Shape3::Shaft {
            center: [wx * a / 3.0, wx * b / 3.0],
            radius: 1.5,
            y_min: 0.0,
            y_max: wy,
        };
        w.obstacles.push(BeeObstacle::new(
            k as u16 + 1,
            format!("shaft-{k}"),
            shaft,
            true,
        ));
    }
    w.targets.push(BeeTarget {
        id: 5,
        name: "nest".into(),
        center: [wx / 2.0, 4.0 + sy / 2.0, wx / 2.0],
        radius: 2.5,
        particles: 300,
        active: true,
    });
    let states = (0..n as u32)
        .map(|i| {
            let r = |k| draw(seed, i, k);
            BeeState::new(
                Vec3::from_f32(10.0 + r(0) * sx, 4.0 + r(1) * sy, 10.0 + r(2) * sx),
                Vec3::zero(),
            )
        })
        .collect();
    let params = BeeParams::<S>::grassland()
        .checked()
        .expect("Table I parameters are valid");
    let group = BeeGroup::new("bench".into(), 0, params, Some(5), states);
    BeeSim::new(w, vec![group.into()], seed)
}
