//! Global fields on a regular grid of cells: the signed distance to the obstacles, the
//! repulsion value, a minimum-cost field solved by fast marching and its unit descent
//! direction, sampled at any point in an agent's scalar.
//!
//! These are the global data of the noise-aware insect swarm of Wang et al. 2014 (wang2014,
//! §5, "global navigation"): an insect flies along `V_g = −∇C/‖∇C‖·s0` (eq. 8), where C is the
//! least cost of a path to a goal, `Cost = A∫ds + B∫g ds` (eq. 4), g the repulsion of the
//! nearest obstacle (eq. 6) computed from the signed distance φ (eq. 5), solved as the eikonal
//! equation `‖∇C‖ = A + B·g` (eq. 7) once per environment, not per frame (§5.2). Nothing here
//! is specific to that model: the grid and the trilinear sampler serve any field on cells.
//!
//! * [`CellGrid`]: cubic cells covering a box, numbered x fastest;
//! * [`SignedDistance`] (eq. 5) and [`repulsion`] (eq. 6, `a = √2·l`, spec W6);
//! * [`CostField`]: fast marching ([`CostField::solve`], eq. 4 and 7 with [`CostWeights`],
//!   spec W3 and W8; [`CostField::build`] does the signed distance and the solve in one call,
//!   for a scenario event that moves a goal or an obstacle), the unit descent direction per
//!   cell (one-sided towards the smaller neighbour, spec W9) and at any point
//!   ([`CostField::guide_at`], spec §2.4).
//!
//! The spec is `wang2014-curl-noise-insect-swarms.md` (§2.2-2.4, §4 W-T8-W-T11).
//!
//! ```
//! use swarm_sim::bees::Shape3;
//! use swarm_sim::fields::{CellGrid, CostField, CostWeights};
//! use swarm_sim::swarm_core::Vec3;
//!
//! // A 20 × 10 × 10 m world with a wall across x = 10 that leaves a gap at the top.
//! let (lo, hi) = ([0.0; 3], [20.0, 10.0, 10.0]);
//! let grid = CellGrid::new(lo, hi, 1.0).unwrap();
//! let wall = Shape3::Box { min: [9.0, 0.0, 0.0], max: [11.0, 7.0, 10.0] };
//! let goal = Shape3::Sphere { center: [17.0, 2.0, 5.0], radius: 1.5 };
//! let (sdf, field) = CostField::build(&grid, &[wall], &[goal], lo, hi, CostWeights::default())
//!     .unwrap();
//! assert!(sdf.phi[grid.index([9, 3, 5])] < 0.0); // inside the wall
//! assert_eq!(field.solve.cells, 2000);
//!
//! // Low behind the wall, the way to the goal is up over it, not into it.
//! let v = field.guide_at(Vec3::new(6.5f32, 2.0, 5.0));
//! assert!(v.y > 0.5 && (v.length() - 1.0).abs() < 1e-3);
//! // In the goal, no guidance.
//! let c = grid.cell_of([17.0, 2.0, 5.0]).unwrap();
//! assert!(field.is_goal(grid.index(c)));
//! assert_eq!(field.guide_at(Vec3::new(17.5f32, 2.5, 5.5)), Vec3::zero());
//! ```

mod fmm;
mod grid;
mod guide;
mod sdf;

pub use fmm::{CostField, CostWeights, GUIDE_SCALE, GuideCell, Solve};
pub use grid::{CellGrid, MAX_CELLS};
pub use sdf::{SignedDistance, repulsion, repulsion_in};
