//! The neighbour grid built on the GPU: agents sorted by cell, the structure of the CPU grid
//! ([`crate::grid::Grid`]) in the same deterministic order.
//!
//! Given each agent's cell (a `u32` key below `n_cells`), [`GpuGrid`] builds
//!
//! * `starts` (`n_cells + 1` words): `starts[c]..starts[c + 1]` are the slots of cell `c`, the
//!   exclusive prefix sum of the cell counts;
//! * `order` (`n` words): the agent in each slot, sorted by (cell, agent index), exactly what a
//!   stable counting sort gives, whatever the GPU's scheduling.
//!
//! The passes (`shaders/grid.wgsl` says more): the cell counts by atomic addition, and their
//! exclusive scan in blocks of 1,024, the block totals scanned the same way level by level
//! (three levels for 16 million cells); `order` by a stable least-significant-digit radix sort
//! of the agents by cell, 6 bits a pass (`ceil(log2(n_cells) / 6)` passes, at least one), each
//! pass a histogram of the digits of each block of 2,048 agents, the scan of those histograms,
//! and a scatter in which every thread places its own 32 agents in order. No pass depends on
//! which thread runs first, so the result is the same bit for bit on every run and every GPU.
//!
//! Why a radix sort rather than an atomic scatter followed by a sort of each cell's agents (one
//! thread per cell): that sort is serial work on the most crowded cell (`O(k log k)` in one
//! thread for `k` agents), swarms crowd (ants start at their nest), and on lavapipe a loop
//! stops after 65,535 iterations, so it would even come back unsorted. The radix sort does the
//! same work for any distribution of the agents, at the price of a pass per 6 bits of the cell
//! index. Measured on lavapipe (2 cores) for a million agents over a million cells: about 165
//! ms of CPU time for the whole grid (35 for `starts`, 130 for the 4 radix passes), where the
//! atomic scatter and per-cell sort would take about 95.

use super::Gpu;
use super::kernel::{Kernel, zeroed};
use super::shaders::{GRID, WORKGROUP};
use crate::error::{Result, SimError};

/// Elements one workgroup scans (`GRID_SCAN_BLOCK` in `grid.wgsl`).
const SCAN_BLOCK: u32 = 1024;
/// Agents of one radix-sort block (`GRID_RADIX_BLOCK`).
const RADIX_BLOCK: u32 = 2048;
/// Bits of the cell index sorted per pass (`GRID_RADIX_BITS`).
const RADIX_BITS: u32 = 6;
/// Digits per pass (`GRID_RADIX`).
const RADIX: u32 = 1 << RADIX_BITS;
/// `GRID_VALS_ARE_INDICES`: the pass reads no values, agent `i`'s value is `i`.
const VALS_ARE_INDICES: u32 = 1;
/// `GRID_WRITE_KEYS`: the pass writes the keys for the next pass.
const WRITE_KEYS: u32 = 2;

/// The parameters of one dispatch (`GridParams` in `grid.wgsl`): `len`, `last`, `shift`,
/// `blocks`, `flags` and padding to 32 bytes.
type Params = [u32; 8];

fn params(len: u32, last: u32, shift: u32, blocks: u32, flags: u32) -> Params {
    [len, last, shift, blocks, flags, 0, 0, 0]
}

/// The GPU neighbour grid for up to `max_agents` agents over `n_cells` cells: its kernels and
/// buffers, created once and reused by every sort (nothing is allocated per sort).
///
/// Memory, for `P = max(1, ceil(log2(n_cells) / 6))` radix passes:
///
/// * per cell: 4 bytes (`starts`), and 4 bytes per 1,024 cells for the scan's block totals;
/// * per agent: 4 bytes (`order`), and the radix sort's buffers between passes: none for
///   `P = 1` (up to 64 cells), 8 bytes for `P = 2` (up to 4,096 cells), 12 bytes for `P >= 3`
///   (the values and two key buffers); and the histograms, 64 words per 2,048 agents (1/8 byte
///   per agent): at most 16.2 bytes per agent;
/// * besides, the caller's `cells` (4 bytes per agent), and another such buffer inside the grid
///   once [`GpuGrid::sort`] is used.
///
/// For 1,000,000 agents over 1,000,000 cells (4 passes): 16.1 MB and 4 MB.
pub struct GpuGrid {
    max_agents: u32,
    n_cells: u32,
    count: Kernel,
    scans: Scans,
    radix_count: Kernel,
    radix_scatter: Kernel,
    starts: wgpu::Buffer,
    order: wgpu::Buffer,
    /// The radix sort's values between passes (the last pass writes `order`).
    vals: wgpu::Buffer,
    /// The radix sort's keys between passes.
    keys: [wgpu::Buffer; 2],
    /// Per pass: each (digit, block)'s count, then its first slot.
    hist: wgpu::Buffer,
    starts_scan: Scan,
    hist_scan: Scan,
    count_params: wgpu::Buffer,
    /// Per radix pass: its parameters, and the bind groups of passes after the first (the first
    /// reads the caller's `cells`).
    passes: Vec<Pass>,
    /// The bind groups that read the caller's `cells`, for the buffer they were made for.
    bound: Option<Bound>,
    /// The agents the parameter buffers hold.
    params_for: Option<u32>,
    /// [`GpuGrid::sort`]'s upload of the keys.
    upload: Option<wgpu::Buffer>,
}

struct Pass {
    shift: u32,
    params: wgpu::Buffer,
    /// `grid_radix_count` and `grid_radix_scatter`'s bind groups (none for the first pass).
    groups: Option<(wgpu::BindGroup, wgpu::BindGroup)>,
}

struct Bound {
    cells: wgpu::Buffer,
    count: wgpu::BindGroup,
    radix_count: wgpu::BindGroup,
    radix_scatter: wgpu::BindGroup,
}

impl GpuGrid {
    /// The kernels and buffers for sorting up to `max_agents` agents over `n_cells` cells.
    ///
    /// # Errors
    ///
    /// [`SimError::GpuGridNoCells`] if `n_cells` is 0, [`SimError::GpuTooLarge`] if a buffer
    /// is larger than the adapter's largest storage binding, [`SimError::GpuShader`] if a
    /// kernel does not compile.
    pub fn new(gpu: &Gpu, max_agents: u32, n_cells: u32) -> Result<GpuGrid> {
        if n_cells == 0 {
            return Err(SimError::GpuGridNoCells);
        }
        let kernel = |entry: &'static str| Kernel::new(gpu, entry, &[&GRID], "", entry);
        let count = kernel("grid_count")?;
        let scan_blocks = kernel("grid_scan_blocks")?;
        let scan_add = kernel("grid_scan_add")?;
        let radix_count = kernel("grid_radix_count")?;
        let radix_scatter = kernel("grid_radix_scatter")?;

        let n_passes = passes(n_cells);
        let agents = u64::from(max_agents);
        let starts = zeroed(gpu, "grid starts", u64::from(n_cells) + 1)?;
        let order = zeroed(gpu, "grid order", agents)?;
        let vals = zeroed(gpu, "grid values", if n_passes >= 2 { agents } else { 1 })?;
        let keys = [
            zeroed(gpu, "grid keys", if n_passes >= 2 { agents } else { 1 })?,
            zeroed(gpu, "grid keys", if n_passes >= 3 { agents } else { 1 })?,
        ];
        let max_hist = RADIX * max_agents.div_ceil(RADIX_BLOCK);
        let hist = zeroed(gpu, "grid histograms", u64::from(max_hist))?;
        let scans = Scans {
            blocks: scan_blocks,
            add: scan_add,
        };
        let starts_scan = Scan::new(&scans, gpu, &starts, n_cells + 1)?;
        starts_scan.write(gpu, n_cells + 1);
        let hist_scan = Scan::new(&scans, gpu, &hist, max_hist)?;

        let count_params = uniform(gpu, "grid count params");
        let passes = (0..n_passes)
            .map(|p| {
                let params = uniform(gpu, "grid radix params");
                let groups = (p > 0).then(|| {
                    let io = PassIo::of(p, n_passes, &order, &vals, &keys);
                    let keys_in = &keys[(p as usize - 1) % 2];
                    (
                        radix_count.bind(gpu, &[&params, keys_in, &hist]),
                        radix_scatter.bind(
                            gpu,
                            &[
                                &params,
                                keys_in,
                                io.vals_in,
                                &hist,
                                io.keys_out,
                                io.vals_out,
                            ],
                        ),
                    )
                });
                Pass {
                    shift: p * RADIX_BITS,
                    params,
                    groups,
                }
            })
            .collect();
        Ok(GpuGrid {
            max_agents,
            n_cells,
            count,
            scans,
            radix_count,
            radix_scatter,
            starts,
            order,
            vals,
            keys,
            hist,
            starts_scan,
            hist_scan,
            count_params,
            passes,
            bound: None,
            params_for: None,
            upload: None,
        })
    }

    /// The bytes of its buffers on the device (the caller's `cells` not included).
    pub fn bytes(&self) -> u64 {
        [&self.starts, &self.order, &self.vals, &self.hist]
            .into_iter()
            .chain(&self.keys)
            .map(wgpu::Buffer::size)
            .sum()
    }

    /// The agents it can sort.
    pub fn max_agents(&self) -> u32 {
        self.max_agents
    }

    /// Its cells.
    pub fn n_cells(&self) -> u32 {
        self.n_cells
    }

    /// The radix passes of a sort: one per 6 bits of the largest cell index, at least one.
    pub fn radix_passes(&self) -> u32 {
        self.passes.len() as u32
    }

    /// `starts` (`n_cells + 1` words): the slots of cell `c` are `starts[c]..starts[c + 1]`.
    pub fn starts(&self) -> &wgpu::Buffer {
        &self.starts
    }

    /// `order` (`max_agents` words, the first `n` of them set by a sort of `n` agents): the
    /// agent in each slot, by cell, then by agent index.
    pub fn order(&self) -> &wgpu::Buffer {
        &self.order
    }

    /// Records the sort of the first `n` agents of `cells` (their cell indices; a key at or
    /// above `n_cells` counts as the last cell) into `encoder`: afterwards [`GpuGrid::starts`]
    /// and [`GpuGrid::order`] hold the grid.
    ///
    /// `cells` needs the `STORAGE` usage. The bind groups that read it are made again only
    /// when another buffer is passed than the last time (the grid keeps a handle on it), and
    /// the parameters only when `n` changes; they are written through the queue, which applies
    /// them at the start of the next submission: submit before recording another sort with
    /// another `n`.
    ///
    /// # Errors
    ///
    /// [`SimError::GpuGridCapacity`] if `n` exceeds the grid's capacity,
    /// [`SimError::GpuGridCells`] if `cells` holds fewer than `n` words.
    pub fn record(
        &mut self,
        gpu: &Gpu,
        encoder: &mut wgpu::CommandEncoder,
        cells: &wgpu::Buffer,
        n: u32,
    ) -> Result<()> {
        self.record_timed(gpu, encoder, cells, n, None)
    }

    /// [`GpuGrid::record`] in one compute pass whose start and end `timestamps` writes (a
    /// profiled tick).
    ///
    /// # Errors
    ///
    /// As [`GpuGrid::record`].
    pub fn record_timed(
        &mut self,
        gpu: &Gpu,
        encoder: &mut wgpu::CommandEncoder,
        cells: &wgpu::Buffer,
        n: u32,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<()> {
        if n > self.max_agents {
            return Err(SimError::GpuGridCapacity {
                agents: u64::from(n),
                capacity: self.max_agents,
            });
        }
        let needed = 4 * u64::from(n);
        if cells.size() < needed {
            return Err(SimError::GpuGridCells {
                bytes: cells.size(),
                agents: n,
                needed,
            });
        }
        self.bind_cells(gpu, cells);
        self.write_params(gpu, n);
        let Some(bound) = &self.bound else {
            unreachable!("bind_cells sets the cells' bind groups");
        };
        encoder.clear_buffer(&self.starts, 0, None);
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("grid"),
            timestamp_writes: timestamps,
        });
        self.record_starts(bound, &mut pass, n);
        self.record_order(bound, &mut pass, n);
        Ok(())
    }

    /// The count and scan of `starts` (cleared before).
    fn record_starts(&self, bound: &Bound, pass: &mut wgpu::ComputePass<'_>, n: u32) {
        // No agents: the cleared starts are the grid.
        if n > 0 {
            self.count.dispatch(pass, &bound.count, n);
            self.starts_scan.record(&self.scans, pass, self.n_cells + 1);
        }
    }

    /// The radix sort into `order`.
    fn record_order(&self, bound: &Bound, pass: &mut wgpu::ComputePass<'_>, n: u32) {
        if n == 0 {
            return;
        }
        let blocks = n.div_ceil(RADIX_BLOCK);
        for p in &self.passes {
            let (count, scatter) = match &p.groups {
                Some((c, s)) => (c, s),
                None => (&bound.radix_count, &bound.radix_scatter),
            };
            self.radix_count.dispatch(pass, count, blocks * WORKGROUP);
            self.hist_scan.record(&self.scans, pass, RADIX * blocks);
            self.radix_scatter
                .dispatch(pass, scatter, blocks * WORKGROUP);
        }
    }

    /// Sorts `cells` (agent `i` in cell `cells[i]`) on the GPU and reads back `(starts,
    /// order)`: for tests and tools; a simulation records [`GpuGrid::record`] into its own
    /// command buffers instead.
    ///
    /// # Errors
    ///
    /// As [`GpuGrid::record`], and [`read_back`](super::kernel::read_back)'s.
    pub fn sort(&mut self, gpu: &Gpu, cells: &[u32]) -> Result<(Vec<u32>, Vec<u32>)> {
        let n = u32::try_from(cells.len())
            .ok()
            .filter(|&n| n <= self.max_agents)
            .ok_or(SimError::GpuGridCapacity {
                agents: cells.len() as u64,
                capacity: self.max_agents,
            })?;
        let upload = match self.upload.take() {
            Some(b) => b,
            None => zeroed(gpu, "grid cells", u64::from(self.max_agents))?,
        };
        if n > 0 {
            gpu.queue
                .write_buffer(&upload, 0, bytemuck::cast_slice(cells));
        }
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        let recorded = self.record(gpu, &mut encoder, &upload, n);
        self.upload = Some(upload);
        recorded?;
        gpu.queue.submit([encoder.finish()]);
        let starts =
            super::kernel::read_back(gpu, "grid starts", &self.starts, self.n_cells as usize + 1)?;
        let order = super::kernel::read_back(gpu, "grid order", &self.order, n as usize)?;
        Ok((starts, order))
    }

    /// Makes the bind groups that read `cells`, unless they were made for it.
    fn bind_cells(&mut self, gpu: &Gpu, cells: &wgpu::Buffer) {
        if self.bound.as_ref().is_some_and(|b| &b.cells == cells) {
            return;
        }
        let n_passes = self.passes.len() as u32;
        let io = PassIo::of(0, n_passes, &self.order, &self.vals, &self.keys);
        let first = &self.passes[0].params;
        self.bound = Some(Bound {
            cells: cells.clone(),
            count: self
                .count
                .bind(gpu, &[&self.count_params, cells, &self.starts]),
            radix_count: self.radix_count.bind(gpu, &[first, cells, &self.hist]),
            radix_scatter: self.radix_scatter.bind(
                gpu,
                &[
                    first,
                    cells,
                    io.vals_in,
                    &self.hist,
                    io.keys_out,
                    io.vals_out,
                ],
            ),
        });
    }

    /// Writes the parameters of a sort of `n` agents, unless they hold them.
    fn write_params(&mut self, gpu: &Gpu, n: u32) {
        if self.params_for == Some(n) {
            return;
        }
        let last = self.n_cells - 1;
        let blocks = n.div_ceil(RADIX_BLOCK);
        write(gpu, &self.count_params, params(n, last, 0, 0, 0));
        let n_passes = self.passes.len();
        for (p, pass) in self.passes.iter().enumerate() {
            let mut flags = 0;
            if p == 0 {
                flags |= VALS_ARE_INDICES;
            }
            if p + 1 < n_passes {
                flags |= WRITE_KEYS;
            }
            write(
                gpu,
                &pass.params,
                params(n, last, pass.shift, blocks, flags),
            );
        }
        self.hist_scan.write(gpu, RADIX * blocks);
        self.params_for = Some(n);
    }
}

/// The radix passes for `n_cells` cells: one per 6 bits of the largest cell index, at least one.
fn passes(n_cells: u32) -> u32 {
    let bits = u32::BITS - (n_cells - 1).leading_zeros();
    bits.div_ceil(RADIX_BITS).max(1)
}

/// The buffers pass `p` of `n_passes` reads its values from and writes to: the values
/// alternate between `order` and `vals` so that the last pass writes `order`; the keys go to
/// `keys[p % 2]` (the first pass reads the caller's cells, the last writes no keys, and then
/// `keys_out` is only bound).
struct PassIo<'a> {
    vals_in: &'a wgpu::Buffer,
    vals_out: &'a wgpu::Buffer,
    keys_out: &'a wgpu::Buffer,
}

impl<'a> PassIo<'a> {
    fn of(
        p: u32,
        n_passes: u32,
        order: &'a wgpu::Buffer,
        vals: &'a wgpu::Buffer,
        keys: &'a [wgpu::Buffer; 2],
    ) -> PassIo<'a> {
        let v = [order, vals];
        PassIo {
            vals_in: v[((n_passes - p) % 2) as usize],
            vals_out: v[((n_passes - 1 - p) % 2) as usize],
            keys_out: &keys[(p % 2) as usize],
        }
    }
}

/// The kernels of an exclusive scan.
struct Scans {
    blocks: Kernel,
    add: Kernel,
}

/// A multi-level exclusive scan in place of up to `max_len` words of a buffer: level 0 is the
/// buffer, level `k + 1` the totals of level `k`'s blocks of 1,024, up to the first level of
/// one block.
struct Scan {
    levels: Vec<Level>,
}

struct Level {
    params: wgpu::Buffer,
    /// `grid_scan_blocks` and `grid_scan_add` over this level and the totals above it.
    group: wgpu::BindGroup,
    add_group: wgpu::BindGroup,
    /// The totals of this level's blocks (the next level's data).
    _sums: wgpu::Buffer,
}

impl Scan {
    /// The levels of a scan of up to `max_len` words of `data` by `kernels`.
    fn new(kernels: &Scans, gpu: &Gpu, data: &wgpu::Buffer, max_len: u32) -> Result<Scan> {
        let mut levels = Vec::new();
        let mut data = data.clone();
        let mut len = max_len;
        loop {
            let blocks = len.div_ceil(SCAN_BLOCK).max(1);
            let sums = zeroed(gpu, "grid scan totals", u64::from(blocks))?;
            let params = uniform(gpu, "grid scan params");
            levels.push(Level {
                group: kernels.blocks.bind(gpu, &[&params, &data, &sums]),
                add_group: kernels.add.bind(gpu, &[&params, &data, &sums]),
                params,
                _sums: sums.clone(),
            });
            if len <= SCAN_BLOCK {
                break;
            }
            data = sums;
            len = blocks;
        }
        Ok(Scan { levels })
    }

    /// The lengths of the levels a scan of `len` words uses.
    fn lengths(len: u32) -> impl Iterator<Item = u32> {
        std::iter::successors(Some(len), |&l| {
            (l > SCAN_BLOCK).then(|| l.div_ceil(SCAN_BLOCK))
        })
    }

    /// Writes the parameters of a scan of `len` words.
    fn write(&self, gpu: &Gpu, len: u32) {
        for (level, l) in self.levels.iter().zip(Self::lengths(len)) {
            write(gpu, &level.params, params(l, 0, 0, 0, 0));
        }
    }

    /// Records the scan of `len` words (the length its parameters were written for): the
    /// blocks of each level up to the first of one block, then the totals added back down.
    fn record(&self, kernels: &Scans, pass: &mut wgpu::ComputePass<'_>, len: u32) {
        let lengths: Vec<u32> = Self::lengths(len).collect();
        for (level, &l) in self.levels.iter().zip(&lengths) {
            kernels
                .blocks
                .dispatch(pass, &level.group, l.div_ceil(SCAN_BLOCK) * WORKGROUP);
        }
        for (level, &l) in self.levels.iter().zip(&lengths).rev().skip(1) {
            kernels.add.dispatch(pass, &level.add_group, l);
        }
    }
}

/// A uniform buffer for one dispatch's [`Params`].
fn uniform(gpu: &Gpu, label: &'static str) -> wgpu::Buffer {
    gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: std::mem::size_of::<Params>() as u64,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

fn write(gpu: &Gpu, buffer: &wgpu::Buffer, p: Params) {
    gpu.queue.write_buffer(buffer, 0, bytemuck::cast_slice(&p));
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gpu::test_gpu;

    /// The stable counting sort of `cells` over `n_cells` cells: `(starts, order)`.
    fn reference(cells: &[u32], n_cells: u32) -> (Vec<u32>, Vec<u32>) {
        let mut starts = vec![0u32; n_cells as usize + 1];
        for &c in cells {
            starts[c as usize + 1] += 1;
        }
        for c in 0..n_cells as usize {
            starts[c + 1] += starts[c];
        }
        let mut fill = starts.clone();
        let mut order = vec![0; cells.len()];
        for (i, &c) in cells.iter().enumerate() {
            order[fill[c as usize] as usize] = i as u32;
            fill[c as usize] += 1;
        }
        (starts, order)
    }

    /// Sorts `cells` on `grid` and checks the result against the reference.
    fn check(gpu: &Gpu, grid: &mut GpuGrid, cells: &[u32], what: &str) {
        let (starts, order) = grid.sort(gpu, cells).unwrap();
        let (want_starts, want_order) = reference(cells, grid.n_cells());
        if let Some(c) = (0..starts.len()).find(|&c| starts[c] != want_starts[c]) {
            panic!(
                "{what}: starts[{c}] is {}, expected {}",
                starts[c], want_starts[c]
            );
        }
        if let Some(k) = (0..order.len()).find(|&k| order[k] != want_order[k]) {
            panic!(
                "{what}: order[{k}] is {}, expected {}",
                order[k], want_order[k]
            );
        }
        assert_eq!(order.len(), want_order.len(), "{what}");
    }

    /// `n` keys below `n_cells`, a function of `seed`.
    fn random(seed: u32, n: u32, n_cells: u32) -> Vec<u32> {
        (0..n)
            .map(|i| {
                ((u64::from(swarm_core::rand::rand(seed, i, 0, 0)) * u64::from(n_cells)) >> 32)
                    as u32
            })
            .collect()
    }

    #[test]
    fn the_constants_are_the_shaders() {
        for (name, value) in [
            ("GRID_SCAN_BLOCK", SCAN_BLOCK),
            ("GRID_RADIX_BLOCK", RADIX_BLOCK),
            ("GRID_RADIX_BITS", RADIX_BITS),
            ("GRID_RADIX", RADIX),
            ("GRID_VALS_ARE_INDICES", VALS_ARE_INDICES),
            ("GRID_WRITE_KEYS", WRITE_KEYS),
        ] {
            let line = format!("const {name}: u32 = {value}u;");
            assert!(GRID.source.contains(&line), "{line}");
        }
    }

    #[test]
    fn the_radix_passes_cover_the_cell_index() {
        for (cells, passes) in [
            (1, 1),
            (2, 1),
            (64, 1),
            (65, 2),
            (4096, 2),
            (4097, 3),
            (1_000_000, 4),
            (1 << 24, 4),
            ((1 << 24) + 1, 5),
            (u32::MAX, 6),
        ] {
            assert_eq!(super::passes(cells), passes, "{cells} cells");
        }
    }

    #[test]
    fn zero_one_and_two_agents() {
        let gpu = test_gpu();
        let mut grid = GpuGrid::new(&gpu, 8, 5).unwrap();
        for cells in [
            &[][..],
            &[3],
            &[4],
            &[0],
            &[4, 1],
            &[1, 4],
            &[2, 2],
            &[0, 0],
        ] {
            check(&gpu, &mut grid, cells, &format!("{cells:?}"));
        }
        let (starts, order) = grid.sort(&gpu, &[]).unwrap();
        assert_eq!((starts, order), (vec![0; 6], vec![]));
        let (starts, order) = grid.sort(&gpu, &[4, 1]).unwrap();
        assert_eq!((starts, order), (vec![0, 0, 1, 1, 1, 2], vec![1, 0]));
    }

    #[test]
    fn a_cell_holding_every_agent() {
        let gpu = test_gpu();
        let n = 100_000;
        let mut grid = GpuGrid::new(&gpu, n, 1).unwrap();
        let (starts, order) = grid.sort(&gpu, &vec![0; n as usize]).unwrap();
        assert_eq!(starts, vec![0, n]);
        assert!(order.iter().copied().eq(0..n));
        // And one cell of many holding them all: the last, past 6 bits of cell index.
        let mut grid = GpuGrid::new(&gpu, n, 5000).unwrap();
        check(&gpu, &mut grid, &vec![4999; n as usize], "all in cell 4999");
    }

    #[test]
    fn a_million_random_agents_over_a_million_cells_and_over_17() {
        let gpu = test_gpu();
        let n = 1_000_000;
        let mut grid = GpuGrid::new(&gpu, n, 1_000_000).unwrap();
        assert_eq!(grid.radix_passes(), 4);
        check(
            &gpu,
            &mut grid,
            &random(1, n, 1_000_000),
            "1M over 1M cells",
        );
        let mut grid = GpuGrid::new(&gpu, n, 17).unwrap();
        assert_eq!(grid.radix_passes(), 1);
        check(&gpu, &mut grid, &random(2, n, 17), "1M over 17 cells");
    }

    #[test]
    fn half_the_agents_in_cell_0() {
        let gpu = test_gpu();
        let n = 300_000;
        let mut cells = random(3, n, 10_000);
        for (i, c) in cells.iter_mut().enumerate() {
            if swarm_core::rand::rand(4, i as u32, 0, 0).is_multiple_of(2) {
                *c = 0;
            }
        }
        let mut grid = GpuGrid::new(&gpu, n, 10_000).unwrap();
        check(&gpu, &mut grid, &cells, "skewed");
    }

    #[test]
    fn few_agents_over_millions_of_cells() {
        let gpu = test_gpu();
        let mut grid = GpuGrid::new(&gpu, 10_000, 5_000_000).unwrap();
        // Three levels of scan (5,000,001 -> 4,883 -> 5 totals).
        assert_eq!(grid.starts_scan.levels.len(), 3);
        check(&gpu, &mut grid, &random(5, 10_000, 5_000_000), "5M cells");
        // Past 2^24 cells: five radix passes, the scan of 16.8M starts.
        let n_cells = (1 << 24) + 3;
        let mut grid = GpuGrid::new(&gpu, 1000, n_cells).unwrap();
        assert_eq!(grid.radix_passes(), 5);
        let mut cells = random(6, 1000, n_cells);
        cells[17] = n_cells - 1;
        cells[18] = 0;
        check(&gpu, &mut grid, &cells, "16.8M cells");
    }

    #[test]
    fn a_grid_sorts_again_and_for_fewer_agents_without_leftovers() {
        let gpu = test_gpu();
        let cap = 50_000;
        let mut grid = GpuGrid::new(&gpu, cap, 300).unwrap();
        let a = random(7, cap, 300);
        let b = random(8, 12_345, 300);
        let first = grid.sort(&gpu, &a).unwrap();
        check(&gpu, &mut grid, &b, "fewer agents after a full sort");
        check(&gpu, &mut grid, &a[..1], "one agent after 12,345");
        assert_eq!(grid.sort(&gpu, &a).unwrap(), first, "the same sort again");
        assert_eq!(grid.sort(&gpu, &a).unwrap(), first, "and again");
    }

    #[test]
    fn the_order_is_the_cpu_grids() {
        let pts: Vec<[f32; 3]> = (0..50_000u32)
            .map(|i| {
                let u = |k| swarm_core::rand::rand(9, i, 0, k) as f32 / 4_294_967_296.0;
                // A crowd around (20, 20), the rest spread out, some outside the box.
                if i % 3 == 0 {
                    [20.0 + u(0), 20.0 + u(1), 0.0]
                } else {
                    [u(0) * 210.0 - 5.0, u(1) * 100.0, 0.0]
                }
            })
            .collect();
        let cpu = crate::grid::Grid::new([0.0; 3], [200.0, 100.0, 0.0], 1.5);
        let cells: Vec<u32> = pts.iter().map(|&p| cpu.cell_of(p)).collect();
        let gpu = test_gpu();
        let mut grid = GpuGrid::new(&gpu, pts.len() as u32, cpu.cells() as u32).unwrap();
        let (starts, order) = grid.sort(&gpu, &cells).unwrap();
        assert_eq!(order, cpu.order_of(&pts, |p| *p));
        for (c, w) in starts.windows(2).enumerate() {
            assert!(
                order[w[0] as usize..w[1] as usize]
                    .iter()
                    .all(|&i| cells[i as usize] == c as u32),
                "cell {c}"
            );
        }
    }

    #[test]
    fn keys_past_the_last_cell_count_as_the_last_cell() {
        let gpu = test_gpu();
        let mut grid = GpuGrid::new(&gpu, 6, 100).unwrap();
        let (starts, order) = grid.sort(&gpu, &[99, 5, u32::MAX, 100, 0, 7]).unwrap();
        let (want_starts, want_order) = reference(&[99, 5, 99, 99, 0, 7], 100);
        assert_eq!((starts, order), (want_starts, want_order));
    }

    #[test]
    fn sizes_it_was_not_built_for_are_typed_errors() {
        let gpu = test_gpu();
        assert!(matches!(
            GpuGrid::new(&gpu, 10, 0),
            Err(SimError::GpuGridNoCells)
        ));
        assert!(matches!(
            GpuGrid::new(&gpu, 10, u32::MAX),
            Err(SimError::GpuTooLarge {
                buffer: "grid starts",
                ..
            })
        ));
        let mut grid = GpuGrid::new(&gpu, 10, 4).unwrap();
        assert!(matches!(
            grid.sort(&gpu, &[0; 11]),
            Err(SimError::GpuGridCapacity {
                agents: 11,
                capacity: 10
            })
        ));
        let small = super::super::kernel::storage(&gpu, "cells", &[0u32; 3]);
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        assert!(matches!(
            grid.record(&gpu, &mut enc, &small, 4),
            Err(SimError::GpuGridCells {
                bytes: 12,
                agents: 4,
                needed: 16
            })
        ));
        // The grid still sorts.
        check(&gpu, &mut grid, &[3, 1, 3, 0], "after the errors");
    }

    /// Prints how long sorts of a million agents take (run with `--ignored --nocapture`; a
    /// measurement, not a test): the whole sort, and its two halves.
    #[test]
    #[ignore = "a measurement"]
    fn time_a_million_agents() {
        let gpu = test_gpu();
        println!("{}", gpu.info());
        let n = 1_000_000;
        for (n_cells, seed) in [
            (1, 0),
            (17, 0),
            (1_000_000, 0),
            (1_000_000, 1),
            (16_000_000, 0),
        ] {
            let mut grid = GpuGrid::new(&gpu, n, n_cells).unwrap();
            // seed 1: half the agents in cell 0.
            let cells: Vec<u32> = random(10, n, n_cells)
                .into_iter()
                .enumerate()
                .map(|(i, c)| if seed == 1 && i % 2 == 0 { 0 } else { c })
                .collect();
            let upload = crate::gpu::kernel::storage(&gpu, "cells", &cells);
            let mut enc = gpu.device.create_command_encoder(&Default::default());
            grid.record(&gpu, &mut enc, &upload, n).unwrap();
            gpu.queue.submit([enc.finish()]);
            gpu.wait().unwrap();
            let time = |what: &str, stages: [bool; 2]| {
                const RUNS: u32 = 10;
                let mut best = f64::INFINITY;
                let cpu = cpu_ms();
                for _ in 0..RUNS {
                    let mut enc = gpu.device.create_command_encoder(&Default::default());
                    let bound = grid.bound.as_ref().unwrap();
                    if stages[0] {
                        enc.clear_buffer(&grid.starts, 0, None);
                    }
                    {
                        let mut pass = enc.begin_compute_pass(&Default::default());
                        if stages[0] {
                            grid.record_starts(bound, &mut pass, n);
                        }
                        if stages[1] {
                            grid.record_order(bound, &mut pass, n);
                        }
                    }
                    let t = std::time::Instant::now();
                    gpu.queue.submit([enc.finish()]);
                    gpu.wait().unwrap();
                    best = best.min(t.elapsed().as_secs_f64() * 1e3);
                }
                let cpu = cpu_ms().zip(cpu).map(|(b, a)| (b - a) / f64::from(RUNS));
                println!(
                    "{n} agents, {n_cells} cells{}, {} radix passes: {what}: {best:.1} ms \
                     (fastest of {RUNS}), {} ms of CPU time each",
                    if seed == 1 { " (half in cell 0)" } else { "" },
                    grid.radix_passes(),
                    cpu.map_or("?".into(), |c| format!("{c:.0}")),
                );
            };
            time("whole sort", [true, true]);
            time("starts (clear, count, scan)", [true, false]);
            time("order (radix sort)", [false, true]);
        }
    }

    /// The CPU time of this process so far (lavapipe's threads included), in ms, where Linux
    /// tells it: less disturbed than the wall clock on a loaded machine.
    fn cpu_ms() -> Option<f64> {
        let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
        let mut f = stat[stat.rfind(')')? + 2..].split(' ');
        // utime and stime, fields 14 and 15, in clock ticks of (nearly always) 10 ms.
        let utime: f64 = f.nth(11)?.parse().ok()?;
        let stime: f64 = f.next()?.parse().ok()?;
        Some((utime + stime) * 10.0)
    }
}
