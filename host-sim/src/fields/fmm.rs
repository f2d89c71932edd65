//! The minimum-cost field C of wang2014 eq. 4 and 7, solved with first-order upwind fast
//! marching (Sethian 1996) on the cells of a [`CellGrid`].

use std::cmp::Ordering;
use std::collections::BinaryHeap;
use std::time::Instant;

use rayon::prelude::*;

use super::{CellGrid, SignedDistance, guide, repulsion};
use crate::error::{Result, SimError};
use crate::huge::HugeSlice;
use crate::space::Shape3;

/// The weights of the path cost (wang2014 eq. 4, `Cost = A∫ds + B∫g ds`) and the cost per unit
/// length inside obstacles.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CostWeights {
    /// `A`, the weight of the path length (paper: 0.6).
    pub a: f32,
    /// `B`, the weight of the repulsion g (paper: 0.4).
    pub b: f32,
    /// The cost per unit length in cells inside an obstacle (φ < 0). The paper's eq. 6 gives
    /// them g = 1, i.e. `A + B` ([`CostWeights::paper`]), which lets a path cross a thin wall;
    /// the default, 1000, makes obstacles effectively impassable while keeping C finite (and its
    /// gradient pointing outward) inside them (spec W8).
    pub inside: f32,
}

impl Default for CostWeights {
    /// A = 0.6, B = 0.4 (wang2014 §5), inside = 1000 (spec W8).
    fn default() -> Self {
        CostWeights {
            a: 0.6,
            b: 0.4,
            inside: 1000.0,
        }
    }
}

impl CostWeights {
    /// The paper's costs throughout: A = 0.6, B = 0.4, and `A + B` inside obstacles (g = 1 there,
    /// eq. 6).
    pub fn paper() -> Self {
        CostWeights {
            inside: 0.6 + 0.4,
            ..CostWeights::default()
        }
    }

    /// The cost per unit length `F` of a cell at signed distance `phi` on a grid of side `cell`:
    /// `A + B·g(φ)` outside obstacles (the integrand of eq. 4, spec W3), `inside` for φ < 0.
    pub fn speed(&self, phi: f32, cell: f32) -> f32 {
        if phi < 0.0 || phi.is_nan() {
            self.inside
        } else {
            self.a + self.b * repulsion(phi, cell)
        }
    }

    fn check(&self) -> Result<()> {
        let ok = [self.a, self.b, self.inside].iter().all(|v| v.is_finite())
            && self.a > 0.0
            && self.b >= 0.0
            && self.inside > 0.0;
        if ok {
            Ok(())
        } else {
            Err(SimError::FieldWeights {
                a: self.a,
                b: self.b,
                inside: self.inside,
            })
        }
    }
}

/// What a solve cost, for the run log.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solve {
    /// Cells of the grid.
    pub cells: usize,
    /// Cells with a finite cost (reachable from a goal).
    pub reachable: usize,
    /// Goal cells.
    pub goal_cells: usize,
    /// Wall-clock seconds of the fast marching and the guide (not the signed distance).
    pub seconds: f64,
}

impl std::fmt::Display for Solve {
    /// `cost field: 1000000 cells (1000000 reachable, 112 goal cells) in 0.331 s`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "cost field: {} cells ({} reachable, {} goal cells) in {:.3} s",
            self.cells, self.reachable, self.goal_cells, self.seconds
        )
    }
}

/// The minimum cost C to reach a goal from every cell (wang2014 eq. 4, 7) and the unit
/// descent direction `−∇C/‖∇C‖` per cell (eq. 8 without the speed `s0`).
#[derive(Clone, Debug, PartialEq)]
pub struct CostField {
    /// The grid.
    pub grid: CellGrid,
    /// C per cell: 0 in goal cells, `+∞` where no goal can be reached.
    pub cost: Vec<f32>,
    /// What a step samples of each cell: its guide and whether it is a goal cell
    /// ([`CostField::guide`], [`CostField::is_goal`]), on huge pages.
    pub(super) cells: HugeSlice<GuideCell>,
    /// What the solve cost.
    pub solve: Solve,
}

/// The step of the quantised guides: a stored component `q` (−127..=127) stands for
/// `q · GUIDE_SCALE` (an `f32` product, so every implementation decodes the same bits; the GPU
/// reads the scale from the field's header).
pub const GUIDE_SCALE: f32 = 1.0 / 127.0;

/// What the step reads of a cell, in one 32-bit word: the unit guide `−∇C/‖∇C‖` quantised to
/// 8 bits a component (bits 0-7, 8-15, 16-23: x, y, z as two's-complement `i8` multiples of
/// [`GUIDE_SCALE`]) and the goal flag (bit 24). A trilinear sample touches 8 cells scattered
/// over three rows and two layers of the grid; at 4 bytes a cell a field of 4·10⁶ cells fits a
/// server's last-level cache (it was 16 bytes with `f32` components: docs/benchmarks.md,
/// W-T21). The quantisation moves a component by at most 1/254 before the sample is
/// renormalised (docs/models.md).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(transparent)]
pub struct GuideCell(pub u32);

impl GuideCell {
    /// The record of a cell with unit (or zero) guide `guide`.
    pub fn new(guide: [f32; 3], goal: bool) -> Self {
        let q = |v: f32, shift: u32| {
            let q = (v * 127.0).round().clamp(-127.0, 127.0) as i8;
            u32::from(q as u8) << shift
        };
        GuideCell(q(guide[0], 0) | q(guide[1], 8) | q(guide[2], 16) | u32::from(goal) << 24)
    }

    /// The stored guide, decoded: each component `q · GUIDE_SCALE`.
    #[inline]
    pub fn guide(self) -> [f32; 3] {
        [0, 8, 16].map(|shift| f32::from((self.0 >> shift) as u8 as i8) * GUIDE_SCALE)
    }

    /// Whether the cell is a goal cell.
    #[inline]
    pub fn is_goal(self) -> bool {
        self.0 >> 24 & 1 != 0
    }
}

/// A heap entry: a tentative cost and its cell. Ordered so that `BinaryHeap` pops the smallest
/// cost first, ties by the smaller cell index.
#[derive(Clone, Copy, PartialEq)]
struct Trial {
    cost: f64,
    cell: u32,
}

impl Eq for Trial {}

impl Ord for Trial {
    fn cmp(&self, o: &Self) -> Ordering {
        o.cost
            .total_cmp(&self.cost)
            .then_with(|| o.cell.cmp(&self.cell))
    }
}

impl PartialOrd for Trial {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

/// The first-order upwind update of a cell whose smallest known neighbour per axis are `a`
/// (`+∞` on an axis with none), with cost `lf = l·F` per cell: the solution U of
/// `Σ max(U − a_k, 0)² = (lF)²` (Sethian 1996).
fn upwind(mut a: [f64; 3], lf: f64) -> f64 {
    a.sort_by(f64::total_cmp);
    let [a1, a2, a3] = a;
    let mut u = a1 + lf;
    if u > a2 {
        let d = a1 - a2;
        u = 0.5 * (a1 + a2 + (2.0 * lf * lf - d * d).max(0.0).sqrt());
        if u > a3 {
            let s = a1 + a2 + a3;
            let q = a1 * a1 + a2 * a2 + a3 * a3;
            u = (s + (s * s - 3.0 * (q - lf * lf)).max(0.0).sqrt()) / 3.0;
        }
    }
    u
}

impl CostField {
    /// Solves `‖∇C‖ = F` with `F = A + B·g(φ)` outside obstacles and `F = inside` within them
    /// (eq. 7 read as the cost per unit length of eq. 4, spec W3, W8), `C = 0` on the goal cells
    /// (`goal[i]`), by fast marching: 6-connected, first-order upwind, a binary heap with lazy
    /// deletion keyed by (C, cell index), in `f64` (stored as `f32`).
    ///
    /// Every cell's C is fixed once, in the order of the heap, so the result is the same bits
    /// on every run and for any thread count (only the guide is computed in parallel, each cell
    /// from its own neighbours). Cells no goal can reach (pockets closed by the grid border)
    /// keep `C = +∞`.
    ///
    /// Refused: a grid [`CellGrid::new`] would not make ([`CellGrid::check`]), `sdf` or `goal`
    /// not one value per cell ([`SimError::FieldLength`]), no goal
    /// cell ([`SimError::FieldNoGoal`]), weights that do not give a positive finite `F`
    /// ([`SimError::FieldWeights`]).
    pub fn solve(
        grid: &CellGrid,
        sdf: &SignedDistance,
        goal: &[bool],
        w: CostWeights,
    ) -> Result<CostField> {
        let start = Instant::now();
        grid.check()?;
        let n = grid.len();
        for (what, len) in [
            ("signed distance", sdf.phi.len()),
            ("goal mask", goal.len()),
        ] {
            if len != n {
                return Err(SimError::FieldLength {
                    what,
                    len,
                    cells: n,
                });
            }
        }
        w.check()?;
        let goal_cells = goal.iter().filter(|&&g| g).count();
        if goal_cells == 0 {
            return Err(SimError::FieldNoGoal { cells: n });
        }
        let l = f64::from(grid.cell);
        let lf: Vec<f64> = sdf
            .phi
            .par_iter()
            .with_min_len(4096)
            .map(|&phi| l * f64::from(w.speed(phi, grid.cell)))
            .collect();
        let cost = march(grid, &lf, goal);
        let reachable = cost.iter().filter(|c| c.is_finite()).count();
        let cells: Vec<GuideCell> = guide::descent(grid, &cost, goal)
            .into_iter()
            .zip(goal)
            .map(|(guide, &goal)| GuideCell::new(guide, goal))
            .collect();
        let cells = HugeSlice::from_slice(&cells);
        Ok(CostField {
            grid: grid.clone(),
            cost,
            cells,
            solve: Solve {
                cells: n,
                reachable,
                goal_cells,
                seconds: start.elapsed().as_secs_f64(),
            },
        })
    }

    /// The signed distance to `obstacles` and the cost field towards `goals` on `grid`, in a
    /// world with bounds `[lo, hi]`: what to call again when a scenario event moves a goal or
    /// an obstacle. A cell is a goal cell if its centre lies in a goal region, and every region
    /// has at least the cell nearest to its centre ([`CellGrid::mask`]).
    pub fn build(
        grid: &CellGrid,
        obstacles: &[Shape3],
        goals: &[Shape3],
        lo: [f32; 3],
        hi: [f32; 3],
        w: CostWeights,
    ) -> Result<(SignedDistance, CostField)> {
        let sdf = SignedDistance::build(grid, obstacles, lo, hi);
        let goal = grid.mask(goals, lo, hi);
        let field = CostField::solve(grid, &sdf, &goal, w)?;
        Ok((sdf, field))
    }

    /// Whether cell `index` is a goal cell (false past the last cell).
    #[inline]
    pub fn is_goal(&self, index: usize) -> bool {
        self.cells.get(index).is_some_and(|c| c.is_goal())
    }

    /// The record of cell `index` (the zero record past the last cell): what the GPU uploads.
    #[inline]
    pub fn cell(&self, index: usize) -> GuideCell {
        self.cells.get(index).copied().unwrap_or_default()
    }

    /// The unit vector `−∇C/‖∇C‖` of cell `index` (node gradient one-sided towards the
    /// smaller neighbour, spec W9) as stored, quantised ([`GuideCell`]); zero in goal cells,
    /// unreachable cells and past the last cell.
    #[inline]
    pub fn guide(&self, index: usize) -> [f32; 3] {
        self.cells.get(index).map_or([0.0; 3], |c| c.guide())
    }
}

/// Fast marching from the goal cells with per-cell cost `lf` (= l·F); the costs, `f32`.
fn march(grid: &CellGrid, lf: &[f64], goal: &[bool]) -> Vec<f32> {
    let n = grid.len();
    let dims = grid.dims;
    let stride = [1, dims[0] as usize, dims[0] as usize * dims[1] as usize];
    let mut c = vec![f64::INFINITY; n];
    let mut known = vec![false; n];
    let mut heap = BinaryHeap::with_capacity(n.min(1 << 20));
    for (i, _) in goal.iter().enumerate().filter(|(_, g)| **g) {
        c[i] = 0.0;
        heap.push(Trial {
            cost: 0.0,
            cell: i as u32,
        });
    }
    while let Some(Trial { cost, cell }) = heap.pop() {
        let x = cell as usize;
        if known[x] || cost > c[x] {
            continue;
        }
        known[x] = true;
        let cx = grid.coords(x);
        for f in 0..6 {
            let k = f / 2;
            let y = if f % 2 == 0 {
                if cx[k] == 0 {
                    continue;
                }
                x - stride[k]
            } else {
                if cx[k] + 1 >= dims[k] {
                    continue;
                }
                x + stride[k]
            };
            if known[y] {
                continue;
            }
            let mut cy = cx;
            cy[k] = if f % 2 == 0 { cx[k] - 1 } else { cx[k] + 1 };
            // The smallest known neighbour of y per axis.
            let a = std::array::from_fn(|m| {
                let mut best = f64::INFINITY;
                if cy[m] > 0 && known[y - stride[m]] {
                    best = c[y - stride[m]];
                }
                if cy[m] + 1 < dims[m] && known[y + stride[m]] {
                    best = best.min(c[y + stride[m]]);
                }
                best
            });
            let u = upwind(a, lf[y]);
            if u < c[y] {
                c[y] = u;
                heap.push(Trial {
                    cost: u,
                    cell: y as u32,
                });
            }
        }
    }
    c.into_iter().map(|v| v as f32).collect()
}

#[cfg(test)]
mod tests;
