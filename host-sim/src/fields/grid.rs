//! A regular grid of cubic cells covering an axis-aligned box, the support of every global
//! field (signed distance, cost, guide).

use crate::error::{Result, SimError};
use crate::space::Shape3;
use swarm_core::{Scalar, Vec3};

/// The most cells a [`CellGrid`] may have (2²⁶ ≈ 67 million: a few hundred MB per field).
pub const MAX_CELLS: u64 = 1 << 26;

/// A regular grid of cubes of side `cell` whose lower corner is `min`, `dims` cells per axis.
///
/// Cells are numbered x fastest, then y, then z: cell `[i, j, k]` has index
/// `i + dims[0]·(j + dims[1]·k)`, centre `min + (i + ½, j + ½, k + ½)·cell`.
#[derive(Clone, Debug, PartialEq)]
pub struct CellGrid {
    /// The lower corner.
    pub min: [f32; 3],
    /// The cell side `l`.
    pub cell: f32,
    /// Cells per axis (each ≥ 1).
    pub dims: [u32; 3],
}

impl CellGrid {
    /// The grid covering the box `[min, max]` with cubes of side `cell`: `⌈(max − min)/cell⌉`
    /// cells per axis (the last layer may reach past `max`; an extent within 10⁻⁶ relative of a
    /// whole number of cells, the rounding of `f32` inputs such as 0.3/0.1, gets that number).
    ///
    /// Refused ([`SimError::FieldGridInvalid`]): non-finite numbers, `min ≥ max` on an axis,
    /// `cell ≤ 0`; ([`SimError::FieldGridTooLarge`]) more than [`MAX_CELLS`] cells.
    pub fn new(min: [f32; 3], max: [f32; 3], cell: f32) -> Result<CellGrid> {
        let invalid = SimError::FieldGridInvalid { min, max, cell };
        let finite = min.iter().chain(&max).all(|v| v.is_finite()) && cell.is_finite();
        if !finite || cell <= 0.0 || (0..3).any(|k| min[k] >= max[k]) {
            return Err(invalid);
        }
        let mut dims = [0u64; 3];
        for k in 0..3 {
            let ratio = (f64::from(max[k]) - f64::from(min[k])) / f64::from(cell);
            // An extent that is a whole number of cells up to the rounding of its f32 inputs
            // gets that number, not one more.
            let whole = ratio.round();
            let n = if (ratio - whole).abs() <= 1e-6 * whole.max(1.0) {
                whole
            } else {
                ratio.ceil()
            };
            // A side so small the extent overflows: far too many cells.
            dims[k] = if n < 1.0 {
                1
            } else if n > (MAX_CELLS as f64) {
                MAX_CELLS + 1
            } else {
                n as u64
            };
        }
        let cells = dims[0].saturating_mul(dims[1]).saturating_mul(dims[2]);
        if cells > MAX_CELLS {
            return Err(SimError::FieldGridTooLarge {
                min,
                max,
                cell,
                dims,
                cells,
                limit: MAX_CELLS,
            });
        }
        Ok(CellGrid {
            min,
            cell,
            dims: dims.map(|d| d as u32),
        })
    }

    /// `Ok` for a grid [`CellGrid::new`] could have made: finite corner, positive finite
    /// side, 1 to [`MAX_CELLS`] cells (what a solver checks of a grid built by hand).
    pub fn check(&self) -> Result<()> {
        let max = self.max();
        let cells = self
            .dims
            .iter()
            .fold(1u64, |n, &d| n.saturating_mul(u64::from(d)));
        let finite = self.min.iter().chain(&max).all(|v| v.is_finite());
        if !finite || !self.cell.is_finite() || self.cell <= 0.0 || cells == 0 {
            return Err(SimError::FieldGridInvalid {
                min: self.min,
                max,
                cell: self.cell,
            });
        }
        if cells > MAX_CELLS {
            return Err(SimError::FieldGridTooLarge {
                min: self.min,
                max,
                cell: self.cell,
                dims: self.dims.map(u64::from),
                cells,
                limit: MAX_CELLS,
            });
        }
        Ok(())
    }

    /// The number of cells.
    #[inline]
    pub fn len(&self) -> usize {
        self.dims.iter().map(|&d| d as usize).product()
    }

    /// Whether the grid has no cells (never, for a grid from [`CellGrid::new`]).
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The upper corner of the last cell (`min + dims·cell`, at or past the `max` asked for).
    pub fn max(&self) -> [f32; 3] {
        std::array::from_fn(|k| self.min[k] + self.dims[k] as f32 * self.cell)
    }

    /// The index of cell `[i, j, k]` (which must lie in the grid).
    #[inline]
    pub fn index(&self, c: [u32; 3]) -> usize {
        debug_assert!(
            (0..3).all(|k| c[k] < self.dims[k]),
            "cell {c:?} outside the grid"
        );
        let [nx, ny, _] = self.dims.map(|d| d as usize);
        c[0] as usize + nx * (c[1] as usize + ny * c[2] as usize)
    }

    /// The cell `[i, j, k]` of an index (below [`len`](CellGrid::len)).
    #[inline]
    pub fn coords(&self, index: usize) -> [u32; 3] {
        let [nx, ny, _] = self.dims.map(|d| d as usize);
        [
            (index % nx) as u32,
            ((index / nx) % ny) as u32,
            (index / (nx * ny)) as u32,
        ]
    }

    /// The centre of a cell (by index).
    #[inline]
    pub fn center(&self, index: usize) -> [f32; 3] {
        let c = self.coords(index);
        std::array::from_fn(|k| self.min[k] + (c[k] as f32 + 0.5) * self.cell)
    }

    /// The centre of a cell (by index) as a vector of `S`.
    #[inline]
    pub fn center_vec<S: Scalar>(&self, index: usize) -> Vec3<S> {
        let [x, y, z] = self.center(index);
        Vec3::from_f32(x, y, z)
    }

    /// The cell containing `p` (`floor((p − min)/cell)` per axis), `None` outside the grid or for
    /// non-finite coordinates.
    pub fn cell_of(&self, p: [f32; 3]) -> Option<[u32; 3]> {
        let mut c = [0u32; 3];
        for k in 0..3 {
            let u = ((f64::from(p[k]) - f64::from(self.min[k])) / f64::from(self.cell)).floor();
            // NaN fails both comparisons.
            if !(u >= 0.0 && u < f64::from(self.dims[k])) {
                return None;
            }
            c[k] = u as u32;
        }
        Some(c)
    }

    /// The cell nearest to `p`: [`cell_of`](CellGrid::cell_of) clamped to the grid (non-finite
    /// coordinates: cell 0 on that axis).
    pub fn nearest_cell(&self, p: [f32; 3]) -> [u32; 3] {
        std::array::from_fn(|k| {
            let u = ((f64::from(p[k]) - f64::from(self.min[k])) / f64::from(self.cell)).floor();
            if u >= 0.0 {
                (u.min(f64::from(self.dims[k] - 1))) as u32
            } else {
                0
            }
        })
    }

    /// The 6-neighbours of cell `index` that lie in the grid, by axis: `[−x, +x, −y, +y, −z, +z]`
    /// (`None` past the border).
    #[inline]
    pub fn neighbours(&self, index: usize) -> [Option<usize>; 6] {
        let c = self.coords(index);
        let stride = [
            1,
            self.dims[0] as usize,
            self.dims[0] as usize * self.dims[1] as usize,
        ];
        std::array::from_fn(|f| {
            let k = f / 2;
            if f % 2 == 0 {
                (c[k] > 0).then(|| index - stride[k])
            } else {
                (c[k] + 1 < self.dims[k]).then(|| index + stride[k])
            }
        })
    }

    /// The goal mask of a set of regions: a cell is in it if its centre lies inside one of
    /// `regions` (world bounds `[lo, hi]`, see [`Shape3::surface`]), and every region marks at
    /// least the cell nearest to the centre of its bounding box, so that a region smaller than
    /// a cell still has one.
    pub fn mask(&self, regions: &[Shape3], lo: [f32; 3], hi: [f32; 3]) -> Vec<bool> {
        use rayon::prelude::*;
        let mut mask: Vec<bool> = (0..self.len())
            .into_par_iter()
            .map(|i| {
                let p = self.center_vec::<f32>(i);
                regions.iter().any(|r| r.surface(p, lo, hi).inside)
            })
            .collect();
        for r in regions {
            let (a, b) = r.aabb();
            let mid = std::array::from_fn(|k| 0.5 * (a[k] + b[k]));
            mask[self.index(self.nearest_cell(mid))] = true;
        }
        mask
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn covers_the_box_and_numbers_cells_x_fastest() {
        let g = CellGrid::new([0.0, -1.0, 2.0], [3.0, 1.5, 3.0], 0.5).unwrap();
        assert_eq!(g.dims, [6, 5, 2]);
        assert_eq!(g.len(), 60);
        assert_eq!(g.index([1, 0, 0]), 1);
        assert_eq!(g.index([0, 1, 0]), 6);
        assert_eq!(g.index([0, 0, 1]), 30);
        for i in 0..g.len() {
            assert_eq!(g.index(g.coords(i)), i);
            assert_eq!(g.cell_of(g.center(i)), Some(g.coords(i)));
        }
        assert_eq!(g.center(0), [0.25, -0.75, 2.25]);
        assert_eq!(g.cell_of([-0.01, 0.0, 2.5]), None);
        assert_eq!(g.cell_of([3.0, 0.0, 2.5]), None);
        assert_eq!(g.cell_of([f32::NAN, 0.0, 2.5]), None);
        assert_eq!(g.nearest_cell([-5.0, 9.0, f32::NAN]), [0, 4, 0]);
        assert_eq!(
            g.neighbours(0),
            [None, Some(1), None, Some(6), None, Some(30)]
        );
        assert_eq!(
            g.neighbours(59),
            [Some(58), None, Some(53), None, Some(29), None]
        );
        // A partial last layer.
        let g = CellGrid::new([0.0; 3], [2.1, 1.0, 1.0], 1.0).unwrap();
        assert_eq!(g.dims, [3, 1, 1]);
        assert_eq!(g.max(), [3.0, 1.0, 1.0]);
        let g = CellGrid::new([0.0; 3], [0.3, 0.7, 60.0], 0.1).unwrap();
        assert_eq!(g.dims, [3, 7, 600]);
    }

    #[test]
    fn refuses_bad_and_huge_grids() {
        for (min, max, cell) in [
            ([0.0; 3], [1.0; 3], 0.0),
            ([0.0; 3], [1.0; 3], -1.0),
            ([0.0; 3], [1.0; 3], f32::NAN),
            ([0.0; 3], [1.0, 0.0, 1.0], 0.1),
            ([0.0; 3], [1.0, f32::INFINITY, 1.0], 0.1),
        ] {
            let e = CellGrid::new(min, max, cell).unwrap_err();
            assert!(matches!(e, SimError::FieldGridInvalid { .. }), "{e}");
        }
        let e = CellGrid::new([0.0; 3], [1000.0; 3], 0.1).unwrap_err();
        assert!(
            matches!(
                e,
                SimError::FieldGridTooLarge {
                    cells: 1_000_000_000_000,
                    ..
                }
            ),
            "{e}"
        );
        assert!(e.to_string().contains("[10000, 10000, 10000]"), "{e}");
        let e = CellGrid::new([0.0; 3], [1e30; 3], 1e-30).unwrap_err();
        assert!(matches!(e, SimError::FieldGridTooLarge { .. }), "{e}");
        // Grids built by hand.
        let ok = CellGrid::new([0.0; 3], [1.0; 3], 0.5).unwrap();
        assert!(ok.check().is_ok());
        for bad in [
            CellGrid {
                dims: [0, 1, 1],
                ..ok.clone()
            },
            CellGrid {
                cell: 0.0,
                ..ok.clone()
            },
            CellGrid {
                cell: f32::NAN,
                ..ok.clone()
            },
            CellGrid {
                min: [f32::INFINITY, 0.0, 0.0],
                ..ok.clone()
            },
        ] {
            assert!(
                matches!(bad.check(), Err(SimError::FieldGridInvalid { .. })),
                "{bad:?}"
            );
        }
        let huge = CellGrid {
            dims: [u32::MAX; 3],
            ..ok
        };
        assert!(matches!(
            huge.check(),
            Err(SimError::FieldGridTooLarge { .. })
        ));
    }
}
