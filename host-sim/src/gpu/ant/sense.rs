//! Ant sensing on the GPU: every ant's plan frame and resolve frame built by
//! `shaders/ant_sense.wgsl` from the world's words ([`super::world`]), the sensed ants (struct
//! of arrays) and the GPU grid ([`GpuGrid`]) of their positions, written in the layout of
//! [`super::layout`]: over `Fx` the words of `swarm_sim::ants::{plan_frame, resolve_frame}`,
//! bit for bit.
//!
//! A sensing pass ([`AntSense::frames`]) runs three kernels: the cell of every ant
//! (`ant_world_cell` of its sensed position, over the scalar), the grid's sort of the ants by
//! cell, then one thread per ant for the plan frames and one for the resolve frames. The GPU
//! engine to come runs the same functions inside its plan and resolve kernels; like the CPU
//! engine it skips the frames an ant does not read (an ant that stays stopped, a stopped plan),
//! which the functions themselves do not decide.

use swarm_core::Scalar;
use wgpu::util::DeviceExt;

use super::layout::{PLAN_FRAME_WORDS, RESOLVE_FRAME_WORDS, Word};
use super::scalar_module;
use super::world::{GridShape, predicted_words, sensed_words, with_sensed, world_words};
use crate::ants::AntWorld;
use crate::error::Result;
use crate::gpu::Gpu;
use crate::gpu::grid::GpuGrid;
use crate::gpu::kernel::{Kernel, read_back, storage};
use crate::gpu::shaders::{ANT_LAYOUT, ANT_SENSE, DISPATCH, Module};
use crate::scalar::SimScalar;

/// The sensing kernels: entry points `ant_sense_cells_main` (the ants' grid cells),
/// `ant_plan_frames_main` and `ant_resolve_frames_main` (a frame per ant, its words at
/// `i * ANT_PLAN_FRAME_WORDS` or `i * ANT_RESOLVE_FRAME_WORDS` of the output, binding 6).
pub const SENSE_KERNEL: &str = "
@group(0) @binding(6) var<storage, read_write> ant_sense_out: array<u32>;

@compute @workgroup_size(WORKGROUP)
fn ant_sense_cells_main(@builtin(global_invocation_id) id: vec3<u32>,
                        @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(id, groups);
    if (i >= ant_sense_params.n) {
        return;
    }
    ant_sense_out[i] = ant_world_cell(ant_sensed_pos(i));
}

@compute @workgroup_size(WORKGROUP)
fn ant_plan_frames_main(@builtin(global_invocation_id) id: vec3<u32>,
                        @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(id, groups);
    if (i >= ant_sense_params.n) {
        return;
    }
    let w = ant_plan_frame_to_words(ant_plan_frame(i));
    let b = i * ANT_PLAN_FRAME_WORDS;
    for (var k = 0u; k < ANT_PLAN_FRAME_WORDS; k = k + 1u) {
        ant_sense_out[b + k] = w[k];
    }
}

@compute @workgroup_size(WORKGROUP)
fn ant_resolve_frames_main(@builtin(global_invocation_id) id: vec3<u32>,
                           @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(id, groups);
    if (i >= ant_sense_params.n) {
        return;
    }
    let w = ant_resolve_frame_to_words(ant_resolve_frame(i));
    let b = i * ANT_RESOLVE_FRAME_WORDS;
    for (var k = 0u; k < ANT_RESOLVE_FRAME_WORDS; k = k + 1u) {
        ant_sense_out[b + k] = w[k];
    }
}
";

/// The modules of the sensing kernels over the scalar `scalar`.
pub fn modules(scalar: &'static Module) -> [&'static Module; 4] {
    [&DISPATCH, scalar, &ANT_SENSE, &ANT_LAYOUT]
}

/// Binding numbers of `ant_sense.wgsl` and `ant_world.wgsl`.
const PARAMS: u32 = 0;
const WORLD: u32 = 1;
const PREDICTED: u32 = 3;
const STARTS: u32 = 4;
const ORDER: u32 = 5;
const OUT: u32 = 6;

/// Every ant's frames as words: [`PLAN_FRAME_WORDS`] a plan frame, [`RESOLVE_FRAME_WORDS`] a
/// resolve frame, in slot order (read them with [`super::layout::read_plan_frame`] and
/// [`super::layout::read_resolve_frame`]).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct FrameWords {
    /// The plan frames.
    pub plan: Vec<u32>,
    /// The resolve frames.
    pub resolve: Vec<u32>,
    /// The grid cell of every ant (for tests and tools).
    pub cells: Vec<u32>,
}

/// The sensing kernels over one scalar, compiled once, and the grid they sort the ants with
/// (kept for the next pass while the ant count and the grid's shape allow).
pub struct AntSense {
    cells: Kernel,
    plan: Kernel,
    resolve: Kernel,
    grid: Option<GpuGrid>,
}

impl AntSense {
    /// The kernels over `S` (composed with [`scalar_module`]).
    ///
    /// # Errors
    ///
    /// As [`Kernel::new`].
    pub fn new<S: Scalar>(gpu: &Gpu) -> Result<AntSense> {
        let uses = modules(scalar_module::<S>());
        let kernel = |name, entry| Kernel::new(gpu, name, &uses, SENSE_KERNEL, entry);
        Ok(AntSense {
            cells: kernel("ant_sense_cells", "ant_sense_cells_main")?,
            plan: kernel("ant_plan_frames", "ant_plan_frames_main")?,
            resolve: kernel("ant_resolve_frames", "ant_resolve_frames_main")?,
            grid: None,
        })
    }

    /// Every ant's plan frame and resolve frame of `w` sensed on the GPU over `S` (the ants'
    /// scalar): the words of [`crate::ants::plan_frame`] and [`crate::ants::resolve_frame`] for
    /// every slot. The resolve frames read the predictions [`AntWorld::predicted`] (published
    /// by `AntSim::plan_phase`; zeros if the world has none) and widen their query by the
    /// world's `max_shift`, as the CPU's grid query does.
    ///
    /// # Errors
    ///
    /// As [`GpuGrid::new`] and [`read_back`].
    pub fn frames<S: Word + SimScalar>(&mut self, gpu: &Gpu, w: &AntWorld) -> Result<FrameWords> {
        let n = w.len();
        if n == 0 {
            return Ok(FrameWords::default());
        }
        let shape = GridShape::of(w, n);
        let world = storage(gpu, "ant world", &world_words::<S>(w, &shape));
        let sensed = storage(gpu, "ant sensed", &sensed_words::<S>(w));
        let mut predicted = predicted_words::<S>(w);
        predicted.resize(2 * n, 0);
        let predicted = storage(gpu, "ant predicted", &predicted);
        let shift = S::from_f32(w.max_shift).to_word();
        let params = gpu
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("ant sense params"),
                contents: bytemuck::cast_slice(&[n as u32, shift, 0, 0]),
                usage: wgpu::BufferUsages::UNIFORM,
            });
        let cells = storage(gpu, "ant cells", &vec![0u32; n]);
        let plan = storage(gpu, "ant plan frames", &vec![0u32; n * PLAN_FRAME_WORDS]);
        let resolve = storage(
            gpu,
            "ant resolve frames",
            &vec![0u32; n * RESOLVE_FRAME_WORDS],
        );
        let grid = match self.grid.take() {
            Some(g) if g.max_agents() as usize >= n && g.n_cells() == shape.cells() => g,
            _ => GpuGrid::new(gpu, n as u32, shape.cells())?,
        };
        let grid = self.grid.insert(grid);

        let mut enc = gpu.device.create_command_encoder(&Default::default());
        {
            let entries = with_sensed(
                &sensed,
                n,
                &[(PARAMS, &params), (WORLD, &world), (OUT, &cells)],
            );
            let group = self.cells.bind_resources(gpu, &entries);
            let mut pass = enc.begin_compute_pass(&Default::default());
            self.cells.dispatch(&mut pass, &group, n as u32);
        }
        grid.record(gpu, &mut enc, &cells, n as u32)?;
        {
            let common = [
                (PARAMS, &params),
                (WORLD, &world),
                (STARTS, grid.starts()),
                (ORDER, grid.order()),
                (PREDICTED, &predicted),
            ];
            let plan_group = self.plan.bind_resources(
                gpu,
                &with_sensed(&sensed, n, &[common.as_slice(), &[(OUT, &plan)]].concat()),
            );
            let resolve_group = self.resolve.bind_resources(
                gpu,
                &with_sensed(
                    &sensed,
                    n,
                    &[common.as_slice(), &[(OUT, &resolve)]].concat(),
                ),
            );
            let mut pass = enc.begin_compute_pass(&Default::default());
            self.plan.dispatch(&mut pass, &plan_group, n as u32);
            self.resolve.dispatch(&mut pass, &resolve_group, n as u32);
        }
        gpu.queue.submit([enc.finish()]);
        Ok(FrameWords {
            plan: read_back(gpu, "ant plan frames", &plan, n * PLAN_FRAME_WORDS)?,
            resolve: read_back(gpu, "ant resolve frames", &resolve, n * RESOLVE_FRAME_WORDS)?,
            cells: read_back(gpu, "ant cells", &cells, n)?,
        })
    }
}
