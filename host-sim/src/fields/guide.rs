//! The navigation direction of wang2014 eq. 8, `−∇C/‖∇C‖`: on the cells (node gradient), and
//! at any point (trilinear interpolation in the agent's scalar).

use rayon::prelude::*;
use swarm_core::{Scalar, Vec3};

use super::{CellGrid, CostField};

/// The unit descent direction `−∇C/‖∇C‖` of every cell (spec §2.4, W9): per axis the one-sided
/// difference towards the smaller neighbour, `(C(X) − C(X − e))/l` or `(C(X + e) − C(X))/l`
/// (the −e side on a tie), 0 on an axis where neither neighbour is smaller than C(X) (or both
/// are outside the grid or unreachable). Zero in goal cells, unreachable cells and where
/// ‖∇C‖ < 10⁻⁶. Computed in `f64` from the stored `f32` costs; parallel, deterministic.
pub(super) fn descent(grid: &CellGrid, cost: &[f32], goal: &[bool]) -> Vec<[f32; 3]> {
    let l = f64::from(grid.cell);
    (0..grid.len())
        .into_par_iter()
        .with_min_len(1024)
        .map(|x| {
            let cx = f64::from(cost[x]);
            if goal[x] || !cx.is_finite() {
                return [0.0; 3];
            }
            let nb = grid.neighbours(x);
            let at = |f: usize| nb[f].map_or(f64::INFINITY, |y| f64::from(cost[y]));
            let mut grad = [0.0f64; 3];
            for (k, g) in grad.iter_mut().enumerate() {
                let (lower, upper) = (at(2 * k), at(2 * k + 1));
                if lower < cx && lower <= upper {
                    *g = (cx - lower) / l;
                } else if upper < cx {
                    *g = (upper - cx) / l;
                }
            }
            let norm = grad.iter().map(|g| g * g).sum::<f64>().sqrt();
            if norm < 1e-6 {
                return [0.0; 3];
            }
            grad.map(|g| (-g / norm) as f32)
        })
        .collect()
}

/// Per axis: the lower and upper cell of the interpolation and the weight of the upper one.
struct Axis<S> {
    lower: u32,
    upper: u32,
    t: S,
}

/// The interpolation cells of coordinate `p` on an axis of `n` cells starting at `min` with
/// side `cell`, all in `S`: `u = (p − min)/cell − ½`, `i = ⌊u⌋`, `t = u − i`, clamped to the
/// border cells.
fn axis<S: Scalar>(p: S, min: f32, cell: f32, n: u32) -> Axis<S> {
    let half = S::from_f32(0.5);
    let u = (p - S::from_f32(min)) / S::from_f32(cell) - half;
    let i = u.floor_i32();
    let last = n as i32 - 1;
    if i < 0 {
        Axis {
            lower: 0,
            upper: 0,
            t: S::ZERO,
        }
    } else if i >= last {
        Axis {
            lower: last as u32,
            upper: last as u32,
            t: S::ZERO,
        }
    } else {
        Axis {
            lower: i as u32,
            upper: i as u32 + 1,
            t: (u - S::from_i32(i)).clamp_to(S::ZERO, S::ONE),
        }
    }
}

impl CostField {
    /// The unit navigation direction at `p` (wang2014 eq. 8 without the speed `s0`; spec §2.4):
    /// the trilinear interpolation of the 8 surrounding cell-centre unit vectors
    /// ([`CostField::guide`]), renormalised to unit length; where the interpolation is shorter than
    /// 10⁻³ (between opposite vectors, or among goal cells), the vector of the nearest cell
    /// instead (zero in a goal cell).
    ///
    /// Every operation is in `S`, so that another implementation of the same steps (a GPU
    /// kernel) gives the same bits:
    ///
    /// 1. per axis `u = (p − min)/cell − ½` (`min`, `cell` converted with `S::from_f32`),
    ///    `i = ⌊u⌋` ([`Scalar::floor_i32`]); for `i < 0` both cells are 0 and `t = 0`, for
    ///    `i ≥ n − 1` both are `n − 1` and `t = 0` (points beyond the border cell centres take
    ///    the border values), otherwise the cells are `i`, `i + 1` and `t = u − i` clamped to
    ///    [0, 1];
    /// 2. for the corners `c = 0..8` (bit k of c: the upper cell on axis k, so the order is
    ///    (0,0,0), (1,0,0), (0,1,0), (1,1,0), (0,0,1), …) the weight `w = 1·w_x·w_y·w_z`
    ///    (`t` or `1 − t`, multiplied in that order) and `sum += v·w`, `v` the corner's stored
    ///    vector (decoded, [`GuideCell::guide`](super::GuideCell::guide)) converted with
    ///    `S::from_f32`;
    /// 3. if `sum.length() ≥ 10⁻³`: `sum.normalized()`; otherwise the stored vector of the
    ///    nearest cell (per axis the upper cell where `t ≥ ½`), converted, not renormalised.
    ///
    /// Non-finite coordinates give zero. Never panics.
    pub fn guide_at<S: Scalar>(&self, p: Vec3<S>) -> Vec3<S> {
        let Some((sum, nearest, reach)) = self.interpolate(p) else {
            return Vec3::zero();
        };
        if sum.length() >= S::from_f32(1e-3)
            && let Some(unit) = sum.normalized()
        {
            // Within a cell of the goal: faded by the weight of the corners outside it.
            return if reach < S::ONE { unit * reach } else { unit };
        }
        self.cell_guide(nearest)
    }

    /// Loads the cache lines a [`guide_at`](CostField::guide_at) at `p` reads (the lower x
    /// corner of its four rows, an approximation in `f32`) and returns a value made from them,
    /// to be passed to [`std::hint::black_box`]. Touching the cells of a block of insects in one
    /// tight loop, before their steps, puts those loads in flight together (a field larger than
    /// the caches misses at almost every row otherwise, one insect at a time: W-T21's finer
    /// grid). Changes no result; any `p` is safe (clamped into the grid).
    pub fn warm(&self, p: [f32; 3]) -> u32 {
        let g = &self.grid;
        let at = |k: usize| {
            let u = (p[k] - g.min[k]) / g.cell - 0.5;
            // `as` saturates (NaN → 0); the upper row clamps to the last cell.
            let i = (u as u32).min(g.dims[k] - 1);
            (i as usize, (i + 1).min(g.dims[k] - 1) as usize)
        };
        let (x, (y0, y1), (z0, z1)) = (at(0).0, at(1), at(2));
        let (nx, ny) = (g.dims[0] as usize, g.dims[1] as usize);
        let row = |y: usize, z: usize| self.cells[x + nx * (y + ny * z)].0;
        row(y0, z0) ^ row(y1, z0) ^ row(y0, z1) ^ row(y1, z1)
    }

    /// The stored guide of a cell in `S`.
    fn cell_guide<S: Scalar>(&self, cell: [u32; 3]) -> Vec3<S> {
        let [x, y, z] = self.guide(self.grid.index(cell));
        Vec3::from_f32(x, y, z)
    }

    /// The trilinear interpolation of the cell guides at `p` before normalisation, and the
    /// nearest cell (`None` for non-finite `p`): the steps of [`guide_at`](CostField::guide_at).
    pub(super) fn interpolate<S: Scalar>(&self, p: Vec3<S>) -> Option<(Vec3<S>, [u32; 3], S)> {
        if !(p.x.is_finite() && p.y.is_finite() && p.z.is_finite()) {
            return None;
        }
        let g = &self.grid;
        let ax = [
            axis(p.x, g.min[0], g.cell, g.dims[0]),
            axis(p.y, g.min[1], g.cell, g.dims[1]),
            axis(p.z, g.min[2], g.cell, g.dims[2]),
        ];
        // Per axis, the lower and upper cell's part of the cell index and weight (bit k of the
        // corner: the upper one), computed once for the 8 corners.
        let [nx, ny, _] = g.dims.map(|d| d as usize);
        let stride = [1, nx, nx * ny];
        let part: [[(usize, S); 2]; 3] = std::array::from_fn(|k| {
            let a = &ax[k];
            [
                (a.lower as usize * stride[k], S::ONE - a.t),
                (a.upper as usize * stride[k], a.t),
            ]
        });
        let cells: &[_] = &self.cells;
        let mut sum = Vec3::zero();
        let mut reach = S::ZERO;
        for c in 0..8 {
            let (x, y, z) = (part[0][c & 1], part[1][c >> 1 & 1], part[2][c >> 2 & 1]);
            let w = S::ONE * x.1 * y.1 * z.1;
            let i = x.0 + y.0 + z.0;
            let cell = cells[i];
            let [gx, gy, gz] = cell.guide();
            sum += Vec3::from_f32(gx, gy, gz) * w;
            if !cell.is_goal() {
                reach += w;
            }
        }
        let half = S::from_f32(0.5);
        let nearest = std::array::from_fn(|k| {
            if ax[k].t >= half {
                ax[k].upper
            } else {
                ax[k].lower
            }
        });
        Some((sum, nearest, reach))
    }
}
