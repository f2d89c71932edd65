//! The learned data of a li2015 insect (the part of its parameters a device keeps in flash):
//! the segment-length and turning-angle tables of Algorithm 1 (from tracked segments, or the
//! synthetic process of spec §2.1), and the visiting-frequency grid of §4.3 over the world
//! (from tracks, a Gaussian target or a sketch, §5.1), obstacle cells zero.

use swarm_core::Vec3;
use swarm_core::li::density::{DensityGrid, MAX_CELLS};
use swarm_core::li::sampler::Table;
use swarm_core::li::{BINS, LiTable};

use super::fixture::{segment_lengths_mm, turning_angles};
use super::stats::histogram;
use crate::error::{Result, SimError};
use crate::fields::{CellGrid, CostField, CostWeights};
use crate::space::{BeeObstacle, Shape3};

/// Draws of the synthetic process tabulated for its tables.
pub const FIXTURE_DRAWS: usize = 100_000;

/// The table of `samples`: [`BINS`] equal bins over their [min, max] (spec §2.1).
///
/// # Errors
///
/// [`SimError::LiSamples`] when there are none, or they are not finite, or all equal.
pub fn table_of(what: &'static str, samples: &[f64]) -> Result<LiTable<f32>> {
    let bad = || SimError::LiSamples {
        what,
        n: samples.len(),
    };
    if samples.iter().any(|v| !v.is_finite()) {
        return Err(bad());
    }
    let lo = samples.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = samples.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let (lo, hi) = (lo as f32, hi as f32);
    if lo >= hi {
        return Err(bad());
    }
    let counts = histogram(samples, f64::from(lo), f64::from(hi), BINS);
    Table::from_counts(lo, hi, &counts).map_err(|_| bad())
}

/// The tables of the synthetic process (spec §2.1): [`FIXTURE_DRAWS`] segment lengths (m) and
/// turning-angle magnitudes (rad), tabulated by [`table_of`]. The same for every seed of a
/// run: the process is the data, not the run. Computed once per process.
pub fn fixture_tables() -> (LiTable<f32>, LiTable<f32>) {
    static TABLES: std::sync::OnceLock<(LiTable<f32>, LiTable<f32>)> = std::sync::OnceLock::new();
    TABLES.get_or_init(tabulate_fixture).clone()
}

fn tabulate_fixture() -> (LiTable<f32>, LiTable<f32>) {
    let lengths: Vec<f64> = segment_lengths_mm(2015, FIXTURE_DRAWS)
        .into_iter()
        .map(|mm| mm / 1000.0)
        .collect();
    let turns: Vec<f64> = turning_angles(2015, FIXTURE_DRAWS)
        .into_iter()
        .map(f64::abs)
        .collect();
    // 10⁵ draws of continuous distributions: finite, never all equal.
    (
        table_of("segment lengths", &lengths).expect("fixture lengths tabulate"),
        table_of("turning angles", &turns).expect("fixture turns tabulate"),
    )
}

/// The cells of a grid over a box: cubic cells of side (longest side)/`cells`, as many along
/// each axis as cover the box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridShape {
    /// The lower corner (the box's).
    pub origin: [f32; 3],
    /// The side of a cell.
    pub cell: f32,
    /// Cells along x, y and z.
    pub dims: [u16; 3],
}

impl GridShape {
    /// The grid over `[min, max]` with `cells` cells along its longest side.
    ///
    /// # Errors
    ///
    /// [`SimError::LiGrid`] for 0 cells, or more than a device holds ([`MAX_CELLS`]).
    pub fn over(min: [f32; 3], max: [f32; 3], cells: u16) -> Result<GridShape> {
        let side = (0..3).map(|k| max[k] - min[k]).fold(0.0, f32::max);
        let cell = side / f32::from(cells.max(1));
        let dims = [0, 1, 2].map(|k| {
            let n = ((max[k] - min[k]) / cell - 1e-4).ceil();
            n.clamp(1.0, f32::from(u16::MAX)) as u16
        });
        let total: usize = dims.iter().map(|&d| usize::from(d)).product();
        if cells == 0 || total > MAX_CELLS || !(cell.is_finite() && cell > 0.0) {
            return Err(SimError::LiGrid {
                cells: total,
                max: MAX_CELLS,
            });
        }
        Ok(GridShape {
            origin: min,
            cell,
            dims,
        })
    }

    /// The number of cells.
    pub fn len(&self) -> usize {
        self.dims.iter().map(|&d| usize::from(d)).product()
    }

    /// Whether the grid has no cells (never for one [`GridShape::over`] made).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The centre of cell `i` (x fastest).
    pub fn centre(&self, i: usize) -> [f32; 3] {
        let [nx, ny, _] = self.dims.map(usize::from);
        let idx = [i % nx, (i / nx) % ny, i / (nx * ny)];
        [0, 1, 2].map(|k| self.origin[k] + (idx[k] as f32 + 0.5) * self.cell)
    }

    /// The grid with `weights` (one per cell, x fastest).
    ///
    /// # Errors
    ///
    /// [`SimError::LiGrid`] unless there is one weight per cell.
    pub fn with(&self, weights: &[u8]) -> Result<DensityGrid<f32>> {
        let o = self.origin;
        DensityGrid::new(Vec3::new(o[0], o[1], o[2]), self.cell, self.dims, weights).map_err(|_| {
            SimError::LiGrid {
                cells: weights.len(),
                max: MAX_CELLS,
            }
        })
    }
}

/// Whether the cell of side `cell` centred at `c` is clear of every active obstacle (ours):
/// a cell any part of which lies inside an obstacle gets weight 0, so no point inside an
/// obstacle lies in a cell Metropolis-Hastings accepts (L-T13), however coarse the grid.
pub fn cell_clear(obstacles: &[BeeObstacle], c: [f32; 3], cell: f32) -> bool {
    let (lo, hi) = (c.map(|x| x - 0.5 * cell), c.map(|x| x + 0.5 * cell));
    obstacles
        .iter()
        .filter(|o| o.active)
        .all(|o| !o.shape.meets_box(lo, hi))
}

/// The weights of a sum of Gaussian bumps (spec §2.6: w_c = Σ_q exp(−‖c − q‖²/2σ²) over the
/// `points` q, at each cell's centre c), scaled so the largest is 255, and at least 1 in
/// every free cell; a cell that may touch an active obstacle ([`cell_clear`]) is 0. No
/// points: every free cell 255 (a uniform density).
///
/// The floor of 1 (ours, docs/models.md): Metropolis-Hastings never accepts a zero cell, so an
/// insect in a region of zero cells (spawned there, or pushed there by its neighbours) could
/// never leave it; with the floor it walks at random through the free space until it finds
/// the target, and only obstacles (and the outside) are closed.
pub fn gaussian_weights(
    shape: &GridShape,
    points: &[[f32; 3]],
    sigma: f32,
    obstacles: &[BeeObstacle],
) -> Vec<u8> {
    let inv = 1.0 / (2.0 * f64::from(sigma) * f64::from(sigma));
    let raw: Vec<f64> = (0..shape.len())
        .map(|i| {
            let c = shape.centre(i);
            if !cell_clear(obstacles, c, shape.cell) {
                return 0.0;
            }
            if points.is_empty() {
                return 1.0;
            }
            // Positive in a free cell, however far (the floor keeps it open).
            points
                .iter()
                .map(|q| {
                    let d2: f64 = (0..3).map(|k| f64::from(c[k] - q[k]).powi(2)).sum();
                    (-d2 * inv).exp()
                })
                .sum::<f64>()
                .max(f64::MIN_POSITIVE)
        })
        .collect();
    bytes(&raw)
}

/// Weights scaled so the largest is 255 and every positive one at least 1; 0 stays 0.
fn bytes(raw: &[f64]) -> Vec<u8> {
    let max = raw.iter().copied().fold(0.0, f64::max);
    if max <= 0.0 {
        return vec![0; raw.len()];
    }
    raw.iter()
        .map(|&w| match w {
            0.0 => 0,
            w => ((w / max * 255.0).round() as u8).max(1),
        })
        .collect()
}

/// The weights of the density that draws a swarm to a light (spec §2.6, Fig. 6, ours):
/// w_c = exp(−C(c)/λ), C the length of the shortest path from the cell's centre to the light
/// around the active obstacles (wang2014's fast marching, `fields::CostField`, with cost 1 per
/// unit length and obstacles impassable), scaled as [`gaussian_weights`] (largest 255, a free
/// cell at least 1, a cell touching an obstacle 0). Metropolis-Hastings then drifts the
/// waypoints down the path, round the obstacles.
///
/// # Errors
///
/// What the fast marching refuses (never for a grid [`GridShape::over`] made).
pub fn light_weights(
    shape: &GridShape,
    light: [f32; 3],
    lambda: f32,
    obstacles: &[BeeObstacle],
) -> Result<Vec<u8>> {
    let grid = CellGrid {
        min: shape.origin,
        cell: shape.cell,
        dims: shape.dims.map(u32::from),
    };
    let max = [0, 1, 2].map(|k| shape.origin[k] + f32::from(shape.dims[k]) * shape.cell);
    let walls: Vec<Shape3> = obstacles
        .iter()
        .filter(|o| o.active)
        .map(|o| o.shape.clone())
        .collect();
    let goal = Shape3::Sphere {
        center: light,
        radius: 0.5 * shape.cell,
    };
    let weights = CostWeights {
        a: 1.0,
        b: 0.0,
        inside: 1000.0,
    };
    let (_, field) = CostField::build(&grid, &walls, &[goal], shape.origin, max, weights)?;
    let inv = 1.0 / f64::from(lambda);
    let raw: Vec<f64> = field
        .cost
        .iter()
        .enumerate()
        .map(|(i, &c)| {
            if !cell_clear(obstacles, shape.centre(i), shape.cell) {
                0.0
            } else {
                // Unreachable (C = ∞) or far: the floor keeps the cell open.
                (-f64::from(c) * inv).exp().max(f64::MIN_POSITIVE)
            }
        })
        .collect();
    Ok(bytes(&raw))
}

/// A polyline sketch sampled every `step` along its length (its vertices included), as the
/// points of a Gaussian density (spec §2.6: every σ/2).
pub fn sketch_points(polyline: &[[f32; 3]], step: f32) -> Vec<[f32; 3]> {
    let mut out: Vec<[f32; 3]> = polyline.first().copied().into_iter().collect();
    for w in polyline.windows(2) {
        let (a, b) = (w[0], w[1]);
        let len = (0..3).map(|k| (b[k] - a[k]).powi(2)).sum::<f32>().sqrt();
        let n = (len / step.max(1e-6)).ceil().max(1.0) as usize;
        out.extend((1..=n).map(|i| {
            let t = i as f32 / n as f32;
            [0, 1, 2].map(|k| a[k] + (b[k] - a[k]) * t)
        }));
    }
    out
}

/// The default width of a sketch's Gaussian (spec §2.6, ours): 0.1 × the diagonal of the
/// sketch's bounding box.
pub fn sketch_sigma(polyline: &[[f32; 3]]) -> f32 {
    let lo = polyline
        .iter()
        .fold([f32::INFINITY; 3], |m, p| [0, 1, 2].map(|k| m[k].min(p[k])));
    let hi = polyline.iter().fold([f32::NEG_INFINITY; 3], |m, p| {
        [0, 1, 2].map(|k| m[k].max(p[k]))
    });
    0.1 * (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f32>().sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_fixture_tables_keep_the_process_moments() {
        let (lengths, turns) = fixture_tables();
        assert_eq!((lengths.bins(), turns.bins()), (BINS, BINS));
        // The table's mean (piecewise-uniform bins) against the process's 14.57 mm.
        let mean = |t: &LiTable<f32>| {
            let w = (t.hi - t.lo) / t.bins() as f32;
            let mut below = 0.0;
            let mut m = 0.0;
            for (k, &c) in t.cdf.iter().enumerate() {
                m += (c - below) * (t.lo + (k as f32 + 0.5) * w);
                below = c;
            }
            m
        };
        let l = mean(&lengths);
        assert!((l - 0.01457).abs() < 0.0015, "{l}");
        // |θ| of Normal(2.34°, 40.02°): mean ≈ 0.559 rad (half-normal 0.557 plus the shift).
        let t = mean(&turns);
        assert!((t - 0.559).abs() < 0.03, "{t}");
        assert!(turns.hi <= std::f32::consts::PI + 1e-6);
    }

    #[test]
    fn grids_cover_the_box_and_refuse_too_many_cells() {
        let g = GridShape::over([0.0; 3], [0.91; 3], 16).unwrap();
        assert_eq!(g.dims, [16, 16, 16]);
        let flat = GridShape::over([0.0; 3], [2.0, 0.5, 1.0], 16).unwrap();
        assert_eq!(flat.dims, [16, 4, 8]);
        assert!((flat.centre(0)[0] - 0.0625).abs() < 1e-6);
        assert!(matches!(
            GridShape::over([0.0; 3], [1.0; 3], 17),
            Err(SimError::LiGrid { cells: 4913, .. })
        ));
        assert!(GridShape::over([0.0; 3], [1.0; 3], 0).is_err());
    }

    #[test]
    fn a_gaussian_density_peaks_at_its_point_and_obstacles_are_empty() {
        let g = GridShape::over([0.0; 3], [1.0; 3], 8).unwrap();
        let ball = BeeObstacle::new(
            0,
            "ball",
            Shape3::Sphere {
                center: [0.8, 0.8, 0.8],
                radius: 0.15,
            },
            true,
        );
        let ball = [ball];
        let w = gaussian_weights(&g, &[[0.5; 3]], 0.1, &ball);
        let at = |p: [usize; 3]| w[p[0] + 8 * (p[1] + 8 * p[2])];
        assert_eq!(at([3, 3, 3]), 255);
        assert!(at([3, 3, 3]) > at([2, 3, 3]) && at([2, 3, 3]) > at([1, 3, 3]));
        assert_eq!(at([0, 0, 0]), 1, "far free cells keep the floor");
        let uniform = gaussian_weights(&g, &[], 0.1, &ball);
        assert_eq!(uniform[6 + 8 * (6 + 8 * 6)], 0, "the ball's cell");
        // The ball (0.65-0.95) reaches into the cells of 0.625-0.75 on every axis, not those
        // of 0.5-0.625: a cell any part of which is inside is empty, and only those.
        assert_eq!(
            uniform[5 + 8 * (6 + 8 * 6)],
            0,
            "a cell the ball reaches into"
        );
        assert_eq!(
            uniform[4 + 8 * (6 + 8 * 6)],
            255,
            "a cell it does not reach"
        );
        assert_eq!(uniform[0], 255);
    }

    #[test]
    fn sketches_are_sampled_along_their_length() {
        let p = sketch_points(&[[0.0; 3], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]], 0.25);
        assert_eq!(p.len(), 9);
        assert_eq!(p[4], [1.0, 0.0, 0.0]);
        assert!((sketch_sigma(&[[0.0; 3], [3.0, 4.0, 0.0]]) - 0.5).abs() < 1e-6);
    }

    #[test]
    fn tables_need_varied_finite_samples() {
        assert!(table_of("x", &[]).is_err());
        assert!(table_of("x", &[1.0, 1.0]).is_err());
        assert!(table_of("x", &[1.0, f64::NAN]).is_err());
        let t = table_of("x", &[0.0, 1.0, 1.0, 3.0]).unwrap();
        assert_eq!((t.lo, t.hi, t.cdf.last().copied()), (0.0, 3.0, Some(1.0)));
    }
}
