//! Bee sensing on the GPU: every bee's sensor frame built by `shaders/bee_sense.wgsl` from the
//! world's words ([`super::world`]), the sensed bees (struct of arrays), the frames' inputs
//! (each bee's clock and goal) and the GPU grid ([`GpuGrid`]) of their positions, written in
//! the layout of [`super::layout`]: over `Fx` the words of `swarm_sim::bees::bee_frame`, bit for
//! bit.
//!
//! A sensing pass ([`BeeSense::frames`]) runs three kernels: the cell of every bee
//! (`bee_world_cell` of its sensed position, over the scalar), the grid's sort of the bees by
//! cell, then one thread per bee writing its frame's words. The frame itself is one WGSL
//! function, `bee_sense_frame(i, goal, t)`, returning the `BeeFrame` struct of
//! `bee_frame.wgsl`: the GPU engine to come calls it inside its step kernel and hands the frame
//! to `bee_step_checked` without going through words.

use swarm_core::Scalar;
use wgpu::util::DeviceExt;

use super::layout::{FRAME_WORDS, Word};
use super::world::{FrameInput, GridShape3, input_words, sensed_words, world_words};
use crate::bees::BeeWorld;
use crate::error::Result;
use crate::gpu::Gpu;
use crate::gpu::ant::scalar_module;
use crate::gpu::grid::GpuGrid;
use crate::gpu::kernel::{Kernel, read_back, storage};
use crate::gpu::shaders::{BEE_LAYOUT, BEE_SENSE, DISPATCH, Module};
use crate::scalar::SimScalar;

/// The sensing kernels: entry points `bee_sense_cells_main` (the bees' grid cells) and
/// `bee_sense_frames_main` (a frame per bee, its words at `i * BEE_FRAME_WORDS` of the output,
/// binding 6).
pub const SENSE_KERNEL: &str = "
@group(0) @binding(6) var<storage, read_write> bee_sense_out: array<u32>;

@compute @workgroup_size(WORKGROUP)
fn bee_sense_cells_main(@builtin(global_invocation_id) id: vec3<u32>,
                        @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(id, groups);
    if (i >= bee_sense_params.n) {
        return;
    }
    bee_sense_out[i] = bee_world_cell(bee_sensed_pos(i));
}

@compute @workgroup_size(WORKGROUP)
fn bee_sense_frames_main(@builtin(global_invocation_id) id: vec3<u32>,
                         @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(id, groups);
    if (i >= bee_sense_params.n) {
        return;
    }
    var f = bee_sense_frame(i, bee_input_goal(i), bee_input_t(i));
    let w = bee_frame_to_words(&f);
    let b = i * BEE_FRAME_WORDS;
    for (var k = 0u; k < BEE_FRAME_WORDS; k = k + 1u) {
        bee_sense_out[b + k] = w[k];
    }
}
";

/// The modules of the sensing kernels over the scalar `scalar`.
pub fn modules(scalar: &'static Module) -> [&'static Module; 4] {
    [&DISPATCH, scalar, &BEE_SENSE, &BEE_LAYOUT]
}

/// Binding numbers of `bee_sense.wgsl` and `bee_world.wgsl`.
const PARAMS: u32 = 0;
const WORLD: u32 = 1;
const SENSED: u32 = 2;
const INPUTS: u32 = 3;
const STARTS: u32 = 4;
const ORDER: u32 = 5;
const OUT: u32 = 6;

/// Every bee's frame as words, [`FRAME_WORDS`] a frame, in slot order (read them with
/// [`super::layout::read_frame`]).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct FrameWords {
    /// The frames.
    pub frames: Vec<u32>,
    /// The grid cell of every bee (for tests and tools).
    pub cells: Vec<u32>,
}

/// The sensing kernels over one scalar, compiled once, and the grid they sort the bees with
/// (kept for the next pass while the bee count and the grid's shape allow).
pub struct BeeSense {
    cells: Kernel,
    frames: Kernel,
    grid: Option<GpuGrid>,
}

impl BeeSense {
    /// The kernels over `S` (composed with [`scalar_module`]).
    ///
    /// # Errors
    ///
    /// As [`Kernel::new`].
    pub fn new<S: Scalar>(gpu: &Gpu) -> Result<BeeSense> {
        let uses = modules(scalar_module::<S>());
        let kernel = |name, entry| Kernel::new(gpu, name, &uses, SENSE_KERNEL, entry);
        Ok(BeeSense {
            cells: kernel("bee_sense_cells", "bee_sense_cells_main")?,
            frames: kernel("bee_sense_frames", "bee_sense_frames_main")?,
            grid: None,
        })
    }

    /// Every bee's frame of `w` sensed on the GPU over `S` (the bees' scalar), bee `i` with
    /// the time and goal of `inputs[i]`: the words of
    /// [`bee_frame`](crate::bees::bee_frame)`(w, i, goal's centre, t)` for every slot (the
    /// world's targets and particles as [`BeeWorld::index_targets`] left them).
    ///
    /// # Panics
    ///
    /// If `inputs` has not one entry per bee.
    ///
    /// # Errors
    ///
    /// As [`GpuGrid::new`] and [`read_back`].
    pub fn frames<S: Word + SimScalar>(
        &mut self,
        gpu: &Gpu,
        w: &BeeWorld,
        inputs: &[FrameInput<S>],
    ) -> Result<FrameWords> {
        let n = w.len();
        assert_eq!(inputs.len(), n, "one frame input per bee");
        if n == 0 {
            return Ok(FrameWords::default());
        }
        let shape = GridShape3::of(w, n);
        let world = storage(gpu, "bee world", &world_words::<S>(w, &shape));
        let sensed = storage(gpu, "bee sensed", &sensed_words::<S>(w));
        let inputs = storage(gpu, "bee frame inputs", &input_words(inputs));
        let params = gpu
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("bee sense params"),
                contents: bytemuck::cast_slice(&[n as u32, 0, 0, 0]),
                usage: wgpu::BufferUsages::UNIFORM,
            });
        let cells = storage(gpu, "bee cells", &vec![0u32; n]);
        let frames = storage(gpu, "bee frames", &vec![0u32; n * FRAME_WORDS]);
        let grid = match self.grid.take() {
            Some(g) if g.max_agents() as usize >= n && g.n_cells() == shape.cells() => g,
            _ => GpuGrid::new(gpu, n as u32, shape.cells())?,
        };
        let grid = self.grid.insert(grid);

        let mut enc = gpu.device.create_command_encoder(&Default::default());
        {
            let group = self.cells.bind_at(
                gpu,
                &[
                    (PARAMS, &params),
                    (WORLD, &world),
                    (SENSED, &sensed),
                    (OUT, &cells),
                ],
            );
            let mut pass = enc.begin_compute_pass(&Default::default());
            self.cells.dispatch(&mut pass, &group, n as u32);
        }
        grid.record(gpu, &mut enc, &cells, n as u32)?;
        {
            let group = self.frames.bind_at(
                gpu,
                &[
                    (PARAMS, &params),
                    (WORLD, &world),
                    (SENSED, &sensed),
                    (INPUTS, &inputs),
                    (STARTS, grid.starts()),
                    (ORDER, grid.order()),
                    (OUT, &frames),
                ],
            );
            let mut pass = enc.begin_compute_pass(&Default::default());
            self.frames.dispatch(&mut pass, &group, n as u32);
        }
        gpu.queue.submit([enc.finish()]);
        Ok(FrameWords {
            frames: read_back(gpu, "bee frames", &frames, n * FRAME_WORDS)?,
            cells: read_back(gpu, "bee cells", &cells, n)?,
        })
    }
}
