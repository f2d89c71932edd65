//! The visiting-frequency density of li2015 §4.3: the simulation space cut into cells, each
//! with how often the tracked insects visited it, one byte a cell (ours: a device keeps 16³
//! cells in 4 KiB, spec §1.7). Obstacle cells and everything outside the grid are 0.

use crate::check::check_vec;
use crate::{Error, Result, Scalar, Vec3};

/// A borrowed grid of `dims[0] × dims[1] × dims[2]` cubic cells of side `cell` from `origin`,
/// weights x-fastest, then y, then z.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Density<'a, S> {
    origin: Vec3<S>,
    cell: S,
    dims: [u16; 3],
    weights: &'a [u8],
}

impl<'a, S: Scalar> Density<'a, S> {
    /// The grid over `weights` (x fastest).
    ///
    /// # Errors
    ///
    /// `NonFinite`/`OutOfRange("origin")`; `BadParam("cell")` unless the side is finite and
    /// positive; `BadParam("dims")` for a zero dimension; `Inconsistent("weights")` unless
    /// `weights` holds exactly one byte per cell.
    pub fn new(origin: Vec3<S>, cell: S, dims: [u16; 3], weights: &'a [u8]) -> Result<Self> {
        check_vec(origin, "origin")?;
        if !(cell.is_finite() && cell > S::ZERO) {
            return Err(Error::BadParam { field: "cell" });
        }
        if dims.contains(&0) {
            return Err(Error::BadParam { field: "dims" });
        }
        // Checked: 16-bit dimensions can overflow a 32-bit device's usize.
        let cells = dims
            .iter()
            .try_fold(1usize, |n, &d| n.checked_mul(usize::from(d)));
        if cells != Some(weights.len()) {
            return Err(Error::Inconsistent {
                field: "weights",
                index: None,
            });
        }
        Ok(Density {
            origin,
            cell,
            dims,
            weights,
        })
    }

    /// The cell of `p` as (x, y, z) indices, `None` outside the grid (or for a NaN).
    pub fn cell_of(&self, p: Vec3<S>) -> Option<[u16; 3]> {
        let rel = [
            p.x - self.origin.x,
            p.y - self.origin.y,
            p.z - self.origin.z,
        ];
        let mut out = [0u16; 3];
        for ((o, r), d) in out.iter_mut().zip(rel).zip(self.dims) {
            let q = r / self.cell;
            // NaN and negative fail here; floor_i32 saturates far values.
            if !q.is_finite() || q < S::ZERO {
                return None;
            }
            let i = q.floor_i32();
            if i < 0 || i >= i32::from(d) {
                return None;
            }
            *o = i as u16;
        }
        Some(out)
    }

    /// The lower and upper corners of the grid.
    pub fn bounds(&self) -> (Vec3<S>, Vec3<S>) {
        let side = |d: u16| self.cell * S::from_i32(i32::from(d));
        let far = Vec3::new(side(self.dims[0]), side(self.dims[1]), side(self.dims[2]));
        (self.origin, self.origin + far)
    }

    /// w_c of the cell holding `p`: 0 outside the grid.
    pub fn at(&self, p: Vec3<S>) -> u8 {
        self.cell_of(p).map_or(0, |[x, y, z]| {
            let [nx, ny, _] = self.dims.map(usize::from);
            let i = usize::from(x) + nx * (usize::from(y) + ny * usize::from(z));
            self.weights.get(i).copied().unwrap_or(0)
        })
    }
}

/// The most cells an owned grid holds: 16³, one byte each (4 KiB, spec §1.7).
pub const MAX_CELLS: usize = 4096;

wire_type! {
    /// An owned visiting-frequency grid of at most [`MAX_CELLS`] cells (what a model's
    /// parameters carry, and a device keeps in flash); [`DensityGrid::view`] reads it.
    #[derive(Clone, Debug, PartialEq)]
    pub struct DensityGrid<S> {
        /// The lower corner of cell (0, 0, 0).
        pub origin: Vec3<S>,
        /// The side of a cell.
        pub cell: S,
        /// Cells along x, y and z.
        pub dims: [u16; 3],
        /// w_c, x fastest, then y, then z.
        pub weights: heapless::Vec<u8, MAX_CELLS>,
    }
}

impl<S: Scalar> DensityGrid<S> {
    /// A grid over a copy of `weights`.
    ///
    /// # Errors
    ///
    /// As [`Density::new`]; `BadParam("weights")` for more than [`MAX_CELLS`] cells.
    pub fn new(origin: Vec3<S>, cell: S, dims: [u16; 3], weights: &[u8]) -> Result<Self> {
        let weights =
            heapless::Vec::from_slice(weights).map_err(|_| Error::BadParam { field: "weights" })?;
        let grid = DensityGrid {
            origin,
            cell,
            dims,
            weights,
        };
        grid.view()?;
        Ok(grid)
    }

    /// The grid as a [`Density`].
    ///
    /// # Errors
    ///
    /// As [`Density::new`] (a grid deserialized with a wrong shape).
    pub fn view(&self) -> Result<Density<'_, S>> {
        Density::new(self.origin, self.cell, self.dims, &self.weights)
    }
}
