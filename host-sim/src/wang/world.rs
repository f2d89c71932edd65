//! The wang2014 world: the volume, its obstacles, the goals, the global fields solved over it
//! (signed distance, repulsion and the minimum-cost field of each goal, eq. 4-8, by
//! [`crate::fields`]), and the tentative positions x* every insect broadcast for minimum
//! distance enforcement (§6).
//!
//! What an insect senses is computed in its own scalar (`f32`, or `Fx` arithmetic only in
//! fixed point), so another backend can reproduce every bit: the navigation direction sampled
//! from its goal's field ([`CostField::guide_at`]), the nearest boundary of eq. 2 (an obstacle
//! surface or a wall of the world, the "extended boundary" of §4) with the curvature of its
//! distance field, and the neighbours' tentative positions.

use swarm_core::wang::Boundary;
use swarm_core::{Scalar, Vec2, Vec3};

use crate::Result;
use crate::fields::{CellGrid, CostField, CostWeights, SignedDistance, Solve};
use crate::grid::Grid;
use crate::obstacle_index::ObstacleIndex;
use crate::scalar::{SimScalar, a3, a3f};
use crate::space::{BeeObstacle, Shape3, at, axis, with_axis};

/// The area a goal stands for: where the navigation field is zero and toward which it leads.
#[derive(Clone, Debug, PartialEq)]
pub enum GoalArea {
    /// A ball (`zone`).
    Ball {
        /// Centre.
        center: [f32; 3],
        /// Radius.
        radius: f32,
    },
    /// A box (`region`).
    Box {
        /// Lower corner.
        min: [f32; 3],
        /// Upper corner.
        max: [f32; 3],
    },
    /// The shell up to 2 cells around an obstacle (the object id): the chased ball of Fig. 8,
    /// solid itself and a boundary of eq. 2.
    Around(u16),
}

/// A goal of the world: an object some group flies to.
#[derive(Clone, Debug, PartialEq)]
pub struct Goal {
    /// Object id (its index in the scenario).
    pub id: u16,
    /// Name.
    pub name: String,
    /// Its area.
    pub area: GoalArea,
    /// Present now (an absent goal has no field: its insects drift with the noise).
    pub active: bool,
}

/// The volume, obstacles, goals and fields, and the broadcast tentative positions.
#[derive(Clone, Debug)]
pub struct WangWorld {
    /// Lower corner of the volume.
    pub min: [f32; 3],
    /// Upper corner.
    pub max: [f32; 3],
    /// The cost grid (cells of side l = the groups' smallest d0, spec W2/W5).
    pub grid: CellGrid,
    /// Obstacles (inactive ones included).
    pub obstacles: Vec<BeeObstacle>,
    /// Goals (inactive ones included).
    pub goals: Vec<Goal>,
    /// The cost weights of eq. 4.
    pub weights: CostWeights,
    /// The solved field of each active goal, by goal object id.
    pub fields: Vec<(u16, CostField)>,
    /// Whether an event changed the obstacles or goals since the fields were solved.
    pub dirty: bool,
    /// Solves not yet reported in the run log.
    pub solves: Vec<(String, Solve)>,
    /// Boundary sensing range: the groups' largest d0.
    pub d0: f32,
    /// Minimum distance of MDE: the groups' largest d_min.
    pub d_min: f32,
    /// The tentative positions x* of the current step, by slot.
    pub moved: Vec<[f64; 3]>,
    /// Stable agent ids, by slot.
    pub id: Vec<u32>,
    pub(crate) mde_grid: Grid,
    /// The broad phase of the active obstacles for [`WangWorld::boundary`] and the
    /// confinement, rebuilt with the fields ([`WangWorld::solve_if_dirty`]).
    pub near: ObstacleIndex,
}

impl WangWorld {
    /// An empty world over `[min, max]` with a cost grid of cell `cell`, boundary range `d0`
    /// and MDE distance `d_min`.
    ///
    /// # Errors
    ///
    /// What [`CellGrid::new`] refuses (a cell too small for the world).
    pub fn new(min: [f32; 3], max: [f32; 3], cell: f32, d0: f32, d_min: f32) -> Result<Self> {
        Ok(WangWorld {
            min,
            max,
            grid: CellGrid::new(min, max, cell)?,
            obstacles: Vec::new(),
            goals: Vec::new(),
            weights: CostWeights::default(),
            fields: Vec::new(),
            dirty: true,
            solves: Vec::new(),
            d0,
            d_min,
            moved: Vec::new(),
            id: Vec::new(),
            mde_grid: Grid::default(),
            near: ObstacleIndex::NONE,
        })
    }

    /// Room for `n` insects, and an MDE grid sized for them.
    pub fn resize(&mut self, n: usize) {
        self.moved.resize(n, [0.0; 3]);
        self.id.resize(n, 0);
        let volume: f32 = (0..3)
            .map(|k| (self.max[k] - self.min[k]).max(1e-3))
            .product();
        // Cells a little larger than d_min, and not many more cells than insects (the
        // counting sort walks every cell).
        let cell = (self.d_min * 1.001).max((volume / (2 * n).max(4096) as f32).cbrt());
        self.mde_grid = Grid::new(self.min, self.max, cell);
    }

    /// The shapes of the active obstacles.
    fn shapes(&self) -> Vec<Shape3> {
        self.obstacles
            .iter()
            .filter(|o| o.active)
            .map(|o| o.shape.clone())
            .collect()
    }

    /// Solves the signed distance and every active goal's cost field again (eq. 5-7), if an
    /// event changed the world since the last solve (or it was never solved). Each solve is
    /// kept for the run log ([`WangWorld::solves`]).
    ///
    /// # Errors
    ///
    /// [`CostField::solve`]'s ([`SimError::FieldNoGoal`](crate::SimError::FieldNoGoal) for a goal
    /// with no cell).
    pub fn solve_if_dirty(&mut self) -> Result<()> {
        if !self.dirty {
            return Ok(());
        }
        let sdf = SignedDistance::build(&self.grid, &self.shapes(), self.min, self.max);
        let mut fields = Vec::new();
        for g in self.goals.iter().filter(|g| g.active) {
            let goal = self.goal_cells(g);
            let field = CostField::solve(&self.grid, &sdf, &goal, self.weights)?;
            self.solves.push((g.name.clone(), field.solve));
            fields.push((g.id, field));
        }
        self.fields = fields;
        self.near = ObstacleIndex::build(&self.obstacles, self.min, self.max, self.d0);
        self.dirty = false;
        Ok(())
    }

    /// The goal cells of `g`: cell centres inside its area (for an obstacle, the shell
    /// 0 < φ ≤ 2l around it, spec §2.7).
    fn goal_cells(&self, g: &Goal) -> Vec<bool> {
        let grid = &self.grid;
        let region = match g.area {
            GoalArea::Ball { center, radius } => Shape3::Sphere { center, radius },
            GoalArea::Box { min, max } => Shape3::Box { min, max },
            GoalArea::Around(id) => {
                let shell = 2.0 * grid.cell;
                let around = self.obstacles.iter().find(|o| o.id == id);
                return (0..grid.len())
                    .map(|i| {
                        let c = grid.center(i);
                        around.is_some_and(|o| {
                            let s = o.shape.surface::<f32>(
                                Vec3::new(c[0], c[1], c[2]),
                                self.min,
                                self.max,
                            );
                            !s.inside && s.distance > 0.0 && s.distance <= shell
                        })
                    })
                    .collect();
            }
        };
        // A goal area smaller than a cell still has its nearest cell (`CellGrid::mask`).
        grid.mask(&[region], self.min, self.max)
    }

    /// The field of goal `id`, if the goal is active.
    pub fn field(&self, id: u16) -> Option<&CostField> {
        self.fields.iter().find(|(g, _)| *g == id).map(|(_, f)| f)
    }

    /// The centre of goal `id` (a phototaxis lamp holder, §2.7): a zone's centre, a region's
    /// middle, an obstacle's centre (a box's middle, a shaft's top).
    pub fn goal_center(&self, id: u16) -> Option<[f32; 3]> {
        let g = self.goals.iter().find(|g| g.id == id && g.active)?;
        Some(match &g.area {
            GoalArea::Ball { center, .. } => *center,
            GoalArea::Box { min, max } => std::array::from_fn(|k| 0.5 * (min[k] + max[k])),
            GoalArea::Around(o) => {
                let o = self.obstacles.iter().find(|b| b.id == *o)?;
                match o.shape {
                    Shape3::Sphere { center, .. } => center,
                    Shape3::Box { min, max } => std::array::from_fn(|k| 0.5 * (min[k] + max[k])),
                    Shape3::Shaft { center, y_max, .. } => [center[0], y_max, center[1]],
                }
            }
        })
    }

    /// The nearest boundary of eq. 2 within `d0` of `p` (strictly closer), in the insect's
    /// scalar: the closest surface point of an active obstacle (an insect inside one is at
    /// distance 0) or of a wall of the world (inward normal), obstacles first in scenario
    /// order, then the walls −x, +x, −y, +y, −z, +z; ties keep the first. The curvature of the
    /// distance field (spec §2.1, H_d) is 1/|p − c| beside a sphere, 1/ρ about the axis beside
    /// a shaft's side, and 0 elsewhere (faces, edges and corners of boxes, caps, walls).
    pub fn boundary<S: SimScalar>(&self, p: Vec3<S>, d0: S) -> Option<Boundary<S>> {
        let mut best: Option<(S, Boundary<S>)> = None;
        let mut offer = |d: S, b: Boundary<S>| {
            if d < d0 && best.as_ref().is_none_or(|(x, _)| d < *x) {
                best = Some((d, b));
            }
        };
        let pf = a3(p);
        self.near.each_near(&self.obstacles, a3f(p), |o| {
            if !o.may_be_within(pf, f64::from(self.d0)) {
                return;
            }
            let s = o.shape.surface(p, self.min, self.max);
            let d = if s.inside { S::ZERO } else { s.distance };
            let (curvature, axis) = curvature(&o.shape, p, s.normal);
            offer(
                d,
                Boundary {
                    point: s.point,
                    normal: s.normal,
                    curvature,
                    axis,
                },
            );
        });
        let (lo, hi) = (at::<S>(self.min), at::<S>(self.max));
        for k in 0..3 {
            for (face, sign) in [(lo, S::ONE), (hi, -S::ONE)] {
                let (x, f) = (axis(p, k), axis(face, k));
                let d = ((x - f) * sign).max(S::ZERO);
                offer(
                    d,
                    Boundary {
                        point: with_axis(p, k, f),
                        normal: with_axis(Vec3::zero(), k, sign),
                        curvature: S::ZERO,
                        axis: Vec3::zero(),
                    },
                );
            }
        }
        best.map(|(_, b)| b)
    }
}

/// The curvature 1/ρ and axis of the distance field of `shape` at `p`, whose closest surface
/// normal is `n` (see [`WangWorld::boundary`]).
fn curvature<S: Scalar>(shape: &Shape3, p: Vec3<S>, n: Vec3<S>) -> (S, Vec3<S>) {
    match *shape {
        Shape3::Sphere { center, .. } => {
            let rho = (p - at::<S>(center)).length();
            if rho > S::ZERO {
                (S::ONE / rho, Vec3::zero())
            } else {
                (S::ZERO, Vec3::zero())
            }
        }
        Shape3::Shaft {
            center,
            y_min,
            y_max,
            ..
        } => {
            // The side: a horizontal normal at a height between the caps.
            let side = n.y == S::ZERO && p.y >= S::from_f32(y_min) && p.y <= S::from_f32(y_max);
            let d = Vec2::new(p.x - S::from_f32(center[0]), p.z - S::from_f32(center[1]));
            let rho = d.length();
            if side && rho > S::ZERO {
                (S::ONE / rho, Vec3::new(S::ZERO, S::ONE, S::ZERO))
            } else {
                (S::ZERO, Vec3::zero())
            }
        }
        Shape3::Box { .. } => (S::ZERO, Vec3::zero()),
    }
}
