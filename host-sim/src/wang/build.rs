//! Builds a [`WangSim`] from a 3D [`Scenario`], applies its timed events (re-solving the fields
//! when an obstacle or a goal changes: Fig. 8's chase), records frames, and builds the
//! synthetic world of `swarm bench --model wang`.

use swarm_core::wang::{WangParams, WangState};
use swarm_core::{Fx, Vec3};

use super::sim::{AnyWangGroup, WangGroup, WangSim};
use super::world::{Goal, GoalArea, WangWorld};
use crate::by_scalar;
use crate::output::{AgentSample, Frame};
use crate::scalar::SimScalar;
use crate::scenario::{Action, Group, ObjectKind, ScalarType, Scenario};
use crate::space::{BeeObstacle, Shape3, confine};
use crate::spawn::{draw, point3};
use crate::{Result, SimError};

impl WangSim {
    /// The wang2014 simulation of `scenario` (a 3D world), with seed `seed`: the obstacles,
    /// the goals the groups name, their fields solved (eq. 4-8), the insects spawned.
    ///
    /// # Errors
    ///
    /// [`SimError::WrongWorld`] for a 2D world, [`SimError::GroupParams`] for parameters the
    /// controller refuses, [`SimError::NoObject`] for a goal the scenario does not have, what
    /// solving a field refuses (a goal no cell lies in).
    pub fn from_scenario(scenario: &Scenario, seed: u32) -> Result<WangSim> {
        let (min, max) = scenario.bounds::<3>("wang")?;
        let params = scenario.group_params(super::wang_params)?;
        let fold = |f: fn(&WangParams<f32>) -> f32, pick: fn(f32, f32) -> f32, init| {
            params.iter().map(f).fold(init, pick)
        };
        // The cost grid's cell is d0 (spec W5: "equivalent to the side length of the grid").
        let cell = fold(|p| p.d0, f32::min, f32::INFINITY);
        let d0 = fold(|p| p.d0, f32::max, 0.0);
        let d_min = fold(|p| p.d_min, f32::max, 0.0);
        let mut world = WangWorld::new(min, max, cell, d0, d_min)?;
        for (id, o) in scenario.objects.iter().enumerate() {
            if let Some(shape) = Shape3::of(&o.kind) {
                world
                    .obstacles
                    .push(BeeObstacle::new(id as u16, &o.name, shape, o.active));
            }
        }
        let mut goal_of = |g: &Group| -> Result<u16> {
            let name = g.goal.as_deref().unwrap_or_default();
            let no_object = || SimError::NoObject {
                group: g.name.clone(),
                what: "goal",
                name: name.to_string(),
            };
            let id = scenario.object_id(name).ok_or_else(no_object)?;
            let o = &scenario.objects[usize::from(id)];
            let area = match o.kind {
                ObjectKind::Zone { center, radius } => GoalArea::Ball { center, radius },
                ObjectKind::Region { min, max } => GoalArea::Box { min, max },
                _ if o.kind.is_obstacle() => GoalArea::Around(id),
                _ => return Err(no_object()),
            };
            if !world.goals.iter().any(|x| x.id == id) {
                world.goals.push(Goal {
                    id,
                    name: o.name.clone(),
                    area,
                    active: o.active,
                });
            }
            Ok(id)
        };
        let groups = crate::spawn::groups(scenario, params, |g, p, first| {
            let goal = goal_of(g)?;
            Ok::<AnyWangGroup, SimError>(match g.scalar {
                ScalarType::F32 => spawn::<f32>(scenario, g, p, goal, first, seed)?.into(),
                ScalarType::Fixed => spawn::<Fx>(scenario, g, p, goal, first, seed)?.into(),
            })
        })?;
        WangSim::new(world, groups, seed)
    }

    /// Applies a timed event of the scenario (`Action` on the object with id `object`): an
    /// obstacle or goal added, removed or moved; the fields are solved again before the next
    /// tick (and the solve reported in the run log).
    pub fn apply(&mut self, object: u16, action: &Action) {
        let w = &mut self.world;
        let on = match action {
            Action::Add(_) | Action::Start(_) => Some(true),
            Action::Remove(_) | Action::Stop(_) => Some(false),
            Action::Move { .. } => None,
        };
        if let Some(o) = w.obstacles.iter_mut().find(|o| o.id == object) {
            match (on, action) {
                (Some(active), _) => o.active = active,
                (None, Action::Move { to, .. }) => {
                    o.set_center(to);
                }
                _ => {}
            }
            w.dirty = true;
        }
        if let Some(g) = w.goals.iter_mut().find(|g| g.id == object) {
            match (on, action, &mut g.area) {
                (Some(active), _, _) => g.active = active,
                (None, Action::Move { to, .. }, GoalArea::Ball { center, .. }) => {
                    if let &[x, y, z] = to.as_slice() {
                        *center = [x, y, z];
                    }
                }
                _ => {}
            }
            w.dirty = true;
        }
    }
}

/// The insects of group `g`, ids `first..`, spawned uniformly in its region (box, or ball
/// around an object's centre) with the scenario's counter-based random numbers, at rest.
fn spawn<S: SimScalar>(
    scenario: &Scenario,
    g: &Group,
    params: WangParams<f32>,
    goal: u16,
    first: usize,
    seed: u32,
) -> Result<WangGroup<S>> {
    let checked = params
        .cast::<S>()
        .checked()
        .map_err(|source| SimError::GroupParams {
            group: g.name.clone(),
            source,
        })?;
    let states = (0..g.count)
        .map(|k| {
            let id = (first + k as usize) as u32;
            let pos = point3(scenario, &g.spawn.region, seed, id);
            WangState {
                pos: Vec3::from_f32(pos[0], pos[1], pos[2]),
                vel: Vec3::zero(),
            }
        })
        .collect();
    Ok(WangGroup::new(g.name.clone(), first, checked, goal, states))
}

/// Every insect, in id order, as recorded samples: the heading is the unit velocity V of its
/// last step, `label` 0, `motion` the number of neighbours MDE pushed it from (0 mostly).
pub fn wang_frame_samples(sim: &WangSim) -> Frame {
    fn push<S: SimScalar>(out: &mut [AgentSample], group: u16, g: &WangGroup<S>) {
        for (k, s) in g.states.iter().enumerate() {
            let v = s.vel.to_f32();
            let len = v.length();
            let h = if len > 0.0 {
                [v.x / len, v.y / len, v.z / len]
            } else {
                [1.0, 0.0, 0.0]
            };
            let id = g.ids[k];
            out[id as usize] = AgentSample {
                id,
                pos: [s.pos.x.to_f32(), s.pos.y.to_f32(), s.pos.z.to_f32()],
                heading: h,
                group,
                label: 0,
                motion: g.pushes[k],
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

/// How [`bench_wang_world_shaped`] varies the bench world, for W-T21's check that the step
/// does not depend on the grid's size or the number of obstacles. The default, `(1, 1)`, is
/// [`bench_wang_world`]'s world.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WangBenchShape {
    /// Cost-grid cells per axis, as a multiple of the default: the cell is d0 / `grid_refine`
    /// (1: the cell is d0, as the scenarios build it). 0 counts as 1.
    pub grid_refine: u32,
    /// Copies of the 4 obstacles (ground box, two spheres, a shaft): the world has
    /// 4 × `obstacle_copies` of them, each extra copy at a fixed spot clear of the goal (a
    /// ledge box, a sphere, a shaft). 0 counts as 1.
    pub obstacle_copies: u32,
}

impl Default for WangBenchShape {
    fn default() -> Self {
        WangBenchShape {
            grid_refine: 1,
            obstacle_copies: 1,
        }
    }
}

/// A swarm of `n` insects (Table 1's aggregation parameters, in `scalar`) at the density of
/// the aggregation scenario (1000 insects in a ball of radius 3, spread over ~5 m): a cube
/// world scaled with ∛n holding a ball goal, two spheres, a shaft and a ground box, the
/// insects spawned through the whole cube. For `swarm bench --model wang`.
pub fn bench_wang_world(n: usize, seed: u32, scalar: ScalarType) -> WangSim {
    bench_wang_world_shaped(n, seed, scalar, WangBenchShape::default())
}

/// [`bench_wang_world`] with a finer cost grid or more obstacles (`shape`); the default shape
/// is the same world.
///
/// # Panics
///
/// When the cost grid has more than [`MAX_CELLS`](crate::fields::MAX_CELLS) (2²⁶) cells:
/// never at `grid_refine` 1 (the largest world, 400 m, has 400³), from about 1.05·10⁶ insects
/// at 2 (a side over 203 m), 3.1·10⁵ at 3, 1.3·10⁵ at 4. 256k insects (127 m) fit up to 3.
pub fn bench_wang_world_shaped(
    n: usize,
    seed: u32,
    scalar: ScalarType,
    shape: WangBenchShape,
) -> WangSim {
    match scalar {
        ScalarType::F32 => bench_world::<f32>(n, seed, shape),
        ScalarType::Fixed => bench_world::<Fx>(n, seed, shape),
    }
}

/// The 4 obstacles of copy `copy` of the bench world of side `side` (copy 0: the base world's;
/// the others at spots of a low-discrepancy sequence, clear of the goal ball of radius
/// `goal_r` at the centre).
fn bench_obstacles(side: f32, copy: u32, goal_r: f32) -> [Shape3; 4] {
    let c = side / 2.0;
    if copy == 0 {
        return [
            Shape3::Box {
                min: [0.0; 3],
                max: [side, 1.0, side],
            },
            Shape3::Sphere {
                center: [c * 0.5, c, c * 0.5],
                radius: 2.0,
            },
            Shape3::Sphere {
                center: [c * 1.5, c, c * 1.5],
                radius: 2.0,
            },
            Shape3::Shaft {
                center: [c * 1.5, c * 0.5],
                radius: 1.0,
                y_min: 0.0,
                y_max: side,
            },
        ];
    }
    // Points of the R3 sequence (Roberts' generalised golden ratio) in the middle 80 % of the
    // cube, the first `t ≥ start` whose obstacle of bounding radius `r` clears the goal (in
    // x-z only for a shaft, which spans the height).
    const ALPHA: [f64; 3] = [
        0.819_172_513_396_164_4,
        0.671_043_606_703_789_2,
        0.549_700_477_901_970_5,
    ];
    let mut t = u64::from(copy) * 64;
    let mut spot = |r: f32, vertical: bool| -> [f32; 3] {
        loop {
            t += 1;
            let p = ALPHA.map(|a| side * (0.1 + 0.8 * (0.5 + a * t as f64).fract() as f32));
            let d2 = if vertical {
                (p[0] - c).powi(2) + (p[2] - c).powi(2)
            } else {
                p.iter().map(|x| (x - c).powi(2)).sum()
            };
            if d2.sqrt() > goal_r + r + 0.5 {
                return p;
            }
        }
    };
    let ledge = spot(2.2, false);
    let a = spot(2.0, false);
    let b = spot(2.0, false);
    let shaft = spot(1.0, true);
    [
        Shape3::Box {
            min: [ledge[0] - 1.5, ledge[1] - 0.5, ledge[2] - 1.5],
            max: [ledge[0] + 1.5, ledge[1] + 0.5, ledge[2] + 1.5],
        },
        Shape3::Sphere {
            center: a,
            radius: 2.0,
        },
        Shape3::Sphere {
            center: b,
            radius: 2.0,
        },
        Shape3::Shaft {
            center: [shaft[0], shaft[2]],
            radius: 1.0,
            y_min: 0.0,
            y_max: side,
        },
    ]
}

fn bench_world<S: SimScalar>(n: usize, seed: u32, shape: WangBenchShape) -> WangSim
where
    AnyWangGroup: From<WangGroup<S>>,
{
    // 1000 insects per 20³ m³ (Table 1's aggregation).
    let side = (20.0 * (n.max(1) as f32 / 1000.0).cbrt()).clamp(12.0, 400.0);
    let params = WangParams::<f32>::aggregation();
    let cell = params.d0 / shape.grid_refine.max(1) as f32;
    let mut w = WangWorld::new([0.0; 3], [side; 3], cell, params.d0, params.d_min)
        .expect("the bench world's grid is within MAX_CELLS");
    let c = side / 2.0;
    let goal_r = 3.0;
    let copies = shape.obstacle_copies.max(1);
    for copy in 0..copies {
        for shape in bench_obstacles(side, copy, goal_r) {
            let k = w.obstacles.len();
            w.obstacles.push(BeeObstacle::new(
                k as u16,
                format!("obstacle-{k}"),
                shape,
                true,
            ));
        }
    }
    let goal = w.obstacles.len() as u16;
    w.goals.push(Goal {
        id: goal,
        name: "goal".into(),
        area: GoalArea::Ball {
            center: [c; 3],
            radius: goal_r,
        },
        active: true,
    });
    let states: Vec<WangState<S>> = (0..n as u32)
        .map(|i| {
            let r = |k| 1.5 + draw(seed, i, k) * (side - 3.0);
            let mut s = WangState {
                pos: Vec3::from_f32(r(0), r(1), r(2)),
                vel: Vec3::zero(),
            };
            // Spawned inside an obstacle: on its surface instead.
            confine(&w.obstacles, &w.near, w.min, w.max, &mut s.pos, &mut s.vel);
            s
        })
        .collect();
    let params = params
        .cast::<S>()
        .checked()
        .expect("Table 1 parameters are valid");
    let group = WangGroup::new("bench".into(), 0, params, goal, states);
    WangSim::new(w, vec![group.into()], seed).expect("the bench goal has cells")
}
