//! The uniform neighbour grid, built by counting sort (cell histogram, prefix sum, scatter):
//! the layout the fastest GPU agent simulators use, and the one the GPU backend will share.
//!
//! Agents are stored cell by cell; within a cell in increasing index order, so every query is
//! deterministic whatever the thread count.

use rayon::prelude::*;

/// A uniform grid over an axis-aligned box, with cells of edge `cell`.
#[derive(Clone, Debug, Default)]
pub struct Grid {
    /// The box.
    min: [f32; 3],
    max: [f32; 3],
    /// The centre of the first cell.
    first_centre: [f32; 3],
    /// `dims - 1`, as floats.
    last: [f32; 3],
    cell: f32,
    inv_cell: f32,
    dims: [u32; 3],
    /// `starts[c]..starts[c + 1]` is the range of `order` holding the agents of cell `c`.
    starts: Vec<u32>,
    /// Agent indices sorted by cell.
    order: Vec<u32>,
    /// Their positions, in the same order (queries read these contiguously).
    sorted: Vec<[f32; 3]>,
    /// Scratch: each agent's cell, and the scatter cursors.
    cells: Vec<u32>,
    fill: Vec<u32>,
}

impl Grid {
    /// An empty grid over `[min, max]` with cells of edge `cell` (> 0). Positions outside the box
    /// are put in the nearest border cell. For a 2D world pass equal z bounds: one layer.
    pub fn new(min: [f32; 3], max: [f32; 3], cell: f32) -> Grid {
        let cell = if cell.is_finite() && cell > 0.0 {
            cell
        } else {
            1.0
        };
        let dims = std::array::from_fn(|k| {
            let n = ((max[k] - min[k]) / cell).ceil();
            // A NaN extent gives one cell.
            (n.clamp(1.0, 65_536.0) as u32).max(1)
        });
        let cells = dims.iter().map(|&d| d as usize).product::<usize>();
        Grid {
            min,
            max,
            first_centre: std::array::from_fn(|k| min[k] + 0.5 * cell),
            last: dims.map(|d| (d - 1) as f32),
            cell,
            inv_cell: 1.0 / cell,
            dims,
            starts: vec![0; cells + 1],
            order: Vec::new(),
            sorted: Vec::new(),
            cells: Vec::new(),
            fill: Vec::new(),
        }
    }

    /// The same geometry with no agents (for computing cells elsewhere).
    pub fn clone_geometry(&self) -> Grid {
        Grid {
            min: self.min,
            max: self.max,
            first_centre: self.first_centre,
            last: self.last,
            cell: self.cell,
            inv_cell: self.inv_cell,
            dims: self.dims,
            ..Grid::default()
        }
    }

    /// The cell index of `p` (row-major; outside the box: the nearest border cell).
    pub fn cell_of(&self, p: [f32; 3]) -> u32 {
        self.index(self.coord(p)) as u32
    }

    /// For `p` inside the grid's box: its cell index (as [`Grid::cell_of`] gives it) and that
    /// cell's centre. `None` outside the box (where points are clamped into border cells).
    #[inline]
    pub fn cell_center(&self, p: [f32; 3]) -> Option<(u32, [f32; 3])> {
        if (0..3).any(|k| !(p[k] >= self.min[k] && p[k] <= self.max[k])) {
            return None;
        }
        let c = self.coord(p);
        let center = std::array::from_fn(|k| self.first_centre[k] + c[k] as f32 * self.cell);
        Some((self.index(c) as u32, center))
    }

    /// The cell edge.
    pub fn cell(&self) -> f32 {
        self.cell
    }

    /// The number of cells.
    pub fn cells(&self) -> usize {
        self.starts.len() - 1
    }

    /// Calls `f` with the index of every cell that overlaps the box `[lo, hi]` (clamped to the
    /// grid like [`Grid::cell_of`]: a point of the box is in one of these cells).
    pub fn for_each_cell_in(&self, lo: [f32; 3], hi: [f32; 3], mut f: impl FnMut(usize)) {
        let (lo, hi) = (self.coord(lo), self.coord(hi));
        for z in lo[2]..=hi[2] {
            for y in lo[1]..=hi[1] {
                for x in lo[0]..=hi[0] {
                    f(self.index([x, y, z]));
                }
            }
        }
    }

    /// The grid coordinates of the cell whose centre is nearest to `p` (beyond the box: the
    /// nearest border cell; NaN: the first). The map is monotone in each axis, so a box of points
    /// maps into the cells between its corners' cells, which is all the queries rely on.
    #[inline]
    fn coord(&self, p: [f32; 3]) -> [u32; 3] {
        std::array::from_fn(|k| {
            // A flat axis (the ants' z) has one cell: nothing to compute.
            if self.last[k] == 0.0 {
                return 0;
            }
            let c = (p[k] - self.first_centre[k]) * self.inv_cell;
            // Clamped to [0, last] (a NaN fails `c > 0`), then rounded to the nearest integer
            // by adding 2^23, whose float has no fraction bits left: cheaper than a saturating
            // cast, and exact below 2^22.
            let c = if c > 0.0 { c } else { 0.0 };
            let c = if c < self.last[k] { c } else { self.last[k] };
            (c + 8_388_608.0).to_bits() - 0x4b00_0000
        })
    }

    /// The grid coordinates of the cell holding `p` (as [`Grid::cell_of`] finds it).
    #[inline]
    pub fn coords(&self, p: [f32; 3]) -> [u32; 3] {
        self.coord(p)
    }

    /// The number of cells along each axis.
    pub fn dims(&self) -> [u32; 3] {
        self.dims
    }

    /// The index of the cell of coordinates `c` (row-major: `x` fastest, as
    /// [`Grid::cell_of`] numbers cells).
    #[inline]
    pub fn index_of(&self, c: [u32; 3]) -> usize {
        self.index(c)
    }

    /// The agents of the cells `first..=last` (cell indices; one contiguous range of the
    /// grid's order, nothing beyond the last cell): their indices and positions.
    #[inline]
    pub fn cells_agents(&self, first: usize, last: usize) -> (&[u32], &[[f32; 3]]) {
        let n = self.starts.len().saturating_sub(1);
        if first > last || last >= n {
            return (&[], &[]);
        }
        let (a, b) = (self.starts[first] as usize, self.starts[last + 1] as usize);
        (&self.order[a..b], &self.sorted[a..b])
    }

    /// The agent indices of the last [`Grid::rebuild`], sorted by cell then index.
    pub fn order(&self) -> &[u32] {
        &self.order
    }

    /// Tells the grid that the caller renumbered its agents in the grid's order (agent
    /// `order()[k]` is now agent `k`, as [`permuted`] by [`Grid::order`] does): the grid
    /// then holds the same cells without a rebuild.
    pub fn renumber_in_order(&mut self) {
        self.order
            .par_iter_mut()
            .enumerate()
            .for_each(|(k, o)| *o = k as u32);
    }

    fn index(&self, c: [u32; 3]) -> usize {
        (c[2] as usize * self.dims[1] as usize + c[1] as usize) * self.dims[0] as usize
            + c[0] as usize
    }

    /// Rebuilds the grid for `items` (agent `i` at `pos(&items[i])`): counting sort, in
    /// parallel. The cells are computed in parallel; then each worker takes one contiguous range
    /// of cells and, scanning every agent in index order, counts, places and copies the
    /// positions of the agents in its range only. A worker writes only its own part of
    /// `starts`, `order` and `sorted`, and each cell lists its agents in increasing index:
    /// the grid is the same for any number of workers.
    pub fn rebuild<T: Sync>(&mut self, items: &[T], pos: impl Fn(&T) -> [f32; 3] + Sync) {
        let probe = self.clone_geometry();
        items
            .par_iter()
            .map(|t| probe.cell_of(pos(t)))
            .collect_into_vec(&mut self.cells);
        let n_cells = self.starts.len() - 1;
        let workers = rayon::current_num_threads().clamp(1, n_cells);
        let span = n_cells.div_ceil(workers);
        let cells = &self.cells;
        self.fill.resize(n_cells, 0);
        // Per range of cells: the count of each cell, kept as `fill` = the cell's first slot
        // within the range's part of `order` and `starts[c + 1]` = the slot after its last.
        let totals: Vec<u32> = self.starts[1..]
            .par_chunks_mut(span)
            .zip(self.fill.par_chunks_mut(span))
            .enumerate()
            .map(|(w, (ends, fill))| {
                let lo = w * span;
                fill.fill(0);
                for &c in cells {
                    if let Some(k) = (c as usize).checked_sub(lo).filter(|&k| k < fill.len()) {
                        fill[k] += 1;
                    }
                }
                let mut run = 0;
                for (end, f) in ends.iter_mut().zip(fill.iter_mut()) {
                    let count = *f;
                    *f = run;
                    run += count;
                    *end = run;
                }
                run
            })
            .collect();
        // Each range's part of `order`, then, in parallel: its `starts` made global and its
        // agents placed (in index order) with their positions.
        let n = items.len();
        self.order.resize(n, 0);
        self.sorted.resize(n, [0.0; 3]);
        self.starts[0] = 0;
        let mut parts = Vec::with_capacity(totals.len());
        let (mut order, mut sorted) = (&mut self.order[..], &mut self.sorted[..]);
        let mut base = 0;
        for (w, ((ends, fill), &total)) in self.starts[1..]
            .chunks_mut(span)
            .zip(self.fill.chunks_mut(span))
            .zip(&totals)
            .enumerate()
        {
            let (o, o_rest) = order.split_at_mut(total as usize);
            let (p, p_rest) = sorted.split_at_mut(total as usize);
            (order, sorted) = (o_rest, p_rest);
            parts.push((w * span, base, ends, fill, o, p));
            base += total;
        }
        parts
            .into_par_iter()
            .for_each(|(lo, base, ends, fill, order, sorted)| {
                ends.iter_mut().for_each(|e| *e += base);
                for (i, &c) in cells.iter().enumerate() {
                    if let Some(k) = (c as usize).checked_sub(lo).filter(|&k| k < fill.len()) {
                        let slot = fill[k] as usize;
                        fill[k] += 1;
                        order[slot] = i as u32;
                        sorted[slot] = pos(&items[i]);
                    }
                }
            });
    }

    /// The indices of `items` (agent `i` at `pos(&items[i])`) sorted by cell, then by index: the
    /// permutation the engines reorder their slots by, for memory locality (a counting sort on a
    /// fresh grid of the same geometry; this one is left as it is).
    pub fn order_of<T: Sync>(&self, items: &[T], pos: impl Fn(&T) -> [f32; 3] + Sync) -> Vec<u32> {
        let mut sorted = Grid::new(self.min, self.max, self.cell);
        sorted.rebuild(items, pos);
        sorted.order
    }

    /// Calls `f` with every agent whose cell overlaps the cube of half-edge `radius` around
    /// `p` (a superset of the agents within `radius`; the caller checks the distance).
    #[inline]
    pub fn for_each_candidate(&self, p: [f32; 3], radius: f32, mut f: impl FnMut(u32, [f32; 3])) {
        let lo = self.coord([p[0] - radius, p[1] - radius, p[2] - radius]);
        let hi = self.coord([p[0] + radius, p[1] + radius, p[2] + radius]);
        let width = (hi[0] - lo[0]) as usize + 1;
        for z in lo[2]..=hi[2] {
            for y in lo[1]..=hi[1] {
                let row = self.index([lo[0], y, z]);
                let (a, b) = (self.starts[row] as usize, self.starts[row + width] as usize);
                // Cells of one row are contiguous in `order`.
                for (&i, &q) in self.order[a..b].iter().zip(&self.sorted[a..b]) {
                    f(i, q);
                }
            }
        }
    }
}

/// `src` in the order `perm` gives (`perm[k]` is the slot that moves to `k`).
pub fn permuted<T: Copy + Send + Sync>(src: &[T], perm: &[u32]) -> Vec<T> {
    perm.par_iter().map(|&k| src[k as usize]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn queries_find_exactly_the_agents_a_brute_force_search_finds() {
        let pts: Vec<[f32; 3]> = (0..2000u32)
            .map(|i| {
                let h = swarm_core::rand::rand(1, i, 0, 0);
                let g = swarm_core::rand::rand(1, i, 0, 1);
                [(h % 10_000) as f32 / 50.0, (g % 10_000) as f32 / 100.0, 0.0]
            })
            .collect();
        let mut grid = Grid::new([0.0, 0.0, 0.0], [200.0, 100.0, 0.0], 3.0);
        grid.rebuild(&pts, |p| *p);
        for (i, p) in pts.iter().enumerate().step_by(37) {
            for r in [0.5f32, 2.0, 7.5] {
                let mut got = Vec::new();
                grid.for_each_candidate(*p, r, |j, q| {
                    assert_eq!(q, pts[j as usize]);
                    if (q[0] - p[0]).hypot(q[1] - p[1]) <= r {
                        got.push(j)
                    }
                });
                got.sort();
                let want: Vec<u32> = (0..pts.len() as u32)
                    .filter(|&j| {
                        let q = pts[j as usize];
                        (q[0] - p[0]).hypot(q[1] - p[1]) <= r
                    })
                    .collect();
                assert_eq!(got, want, "agent {i} radius {r}");
            }
        }
    }

    #[test]
    fn cell_centres_lie_in_their_cells() {
        for (min, max, cell) in [
            ([0.0; 3], [60.0, 30.0, 60.0], 3.5),
            ([-7.5, 0.25, 3.0], [205.7, 73.7, 205.7], 4.43),
            ([0.0; 3], [7.0, 7.0, 7.0], 3.6),
        ] {
            let grid = Grid::new(min, max, cell);
            for i in 0..5000u32 {
                let u = |k| swarm_core::rand::rand(2, i, 0, k) as f32 / 4_294_967_296.0;
                let mut p: [f32; 3] =
                    std::array::from_fn(|k| min[k] + (max[k] - min[k]) * u(k as u32));
                // Some points exactly on cell boundaries and on the box faces.
                if i % 3 == 0 {
                    p[0] = (min[0] + (i % 40) as f32 * cell).min(max[0]);
                }
                if i % 7 == 0 {
                    p[1] = max[1];
                }
                let (c, center) = grid.cell_center(p).unwrap();
                assert_eq!(c, grid.cell_of(p), "{p:?}");
                assert_eq!(grid.cell_of(center), c, "{p:?}");
                // The cell's block of 3×3×3 holds every point within one edge of `p`.
                let mut block = Vec::new();
                grid.for_each_cell_in(center.map(|x| x - cell), center.map(|x| x + cell), |k| {
                    block.push(k as u32)
                });
                let q = [p[0] + 0.999 * cell, p[1] - 0.999 * cell, p[2]];
                assert!(block.contains(&grid.cell_of(q)), "{p:?}");
            }
            assert!(grid.cell_center([min[0] - 1.0, min[1], min[2]]).is_none());
        }
    }

    #[test]
    fn cell_ranges_list_their_agents_and_survive_a_renumbering() {
        let pts: Vec<[f32; 3]> = (0..500u32)
            .map(|i| {
                let u = |k| swarm_core::rand::rand(3, i, 0, k) as f32 / 4_294_967_296.0;
                [10.0 * u(0), 6.0 * u(1), 4.0 * u(2)]
            })
            .collect();
        let mut grid = Grid::new([0.0; 3], [10.0, 6.0, 4.0], 2.0);
        assert_eq!(grid.dims(), [5, 3, 2]);
        grid.rebuild(&pts, |p| *p);
        // Row (y, z) = (1, 1), cells x = 1..=3.
        let (first, last) = (grid.index_of([1, 1, 1]), grid.index_of([3, 1, 1]));
        let (ids, at) = grid.cells_agents(first, last);
        let mut want: Vec<u32> = (0..pts.len() as u32)
            .filter(|&i| {
                let c = grid.coords(pts[i as usize]);
                c[1] == 1 && c[2] == 1 && (1..=3).contains(&c[0])
            })
            .collect();
        let mut got = ids.to_vec();
        got.sort();
        want.sort();
        assert_eq!(got, want);
        assert!(ids.iter().zip(at).all(|(&i, q)| pts[i as usize] == *q));
        assert_eq!(grid.cells_agents(last, first).0.len(), 0);
        assert_eq!(grid.cells_agents(0, grid.cells()).0.len(), 0);

        // Renumbered in the grid's order, the agents keep their cells.
        let moved = permuted(&pts, grid.order());
        grid.renumber_in_order();
        let (ids, at) = grid.cells_agents(first, last);
        assert!(ids.iter().zip(at).all(|(&i, q)| moved[i as usize] == *q));
        assert!(grid.order().iter().enumerate().all(|(k, &o)| o == k as u32));
    }

    #[test]
    fn out_of_box_and_nan_positions_land_in_border_cells() {
        let mut grid = Grid::new([0.0; 3], [10.0, 10.0, 10.0], 1.0);
        grid.rebuild(&[[-5.0, 50.0, 3.0], [f32::NAN, 1.0, 1.0]], |p| *p);
        let mut seen = Vec::new();
        grid.for_each_candidate([0.0, 9.9, 3.0], 0.5, |i, _| seen.push(i));
        assert_eq!(seen, vec![0]);
    }
}
