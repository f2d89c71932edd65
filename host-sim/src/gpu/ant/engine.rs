//! The ant simulation on the GPU: an [`Engine`] whose ticks run on wgpu
//! (`shaders/ant_tick.wgsl`), the ants' states staying on the GPU between ticks.
//!
//! [`GpuAntSim`] keeps the CPU simulation ([`AntSim`]) as its host view: the world's objects,
//! the groups' parameters and ids, what the outputs and the mirror read. A tick sends nothing
//! but its number: the grid, the plan, the resolve, the events, the route and the food are
//! computed on the GPU. The host reads back only when it needs to look (a recorded step through
//! double-buffered staging, [`Engine::snapshot`] and [`Engine::take_snapshot`]; the end of a
//! run, [`Engine::sync`]; [`Engine::exchanges`] for the mirror; a check for refusals every
//! [`CHECK_EVERY`] ticks), and uploads only what a scenario event changed (the world's words,
//! and the ants an obstacle pushed out).
//!
//! In fixed point every word is the CPU engine's: the kernels are `swarm-core`'s controllers
//! and the CPU's sensing function by function (`docs/gpu.md`), the events and the route's
//! draws are integer rules, and the food is counted per tick in any order. Slots are not
//! reordered (the GPU's grid is sorted every tick; results do not depend on slots).

use swarm_core::ant::{
    AntParams, AntPlanReply, AntPlanRequest, AntResolveReply, AntResolveRequest, Plan, Resolve,
};
use swarm_core::{Scalar, ScalarKind, StepCtx};
use wgpu::util::DeviceExt;

use super::layout::{self, PLAN_FRAME_WORDS, PLAN_WORDS, RESOLVE_FRAME_WORDS, STATE_WORDS, Word};
use super::sense::SENSE_KERNEL;
use super::world::{
    GridShape, OBJECT_WORDS, SENSED_WORDS, sensed_ranges, sensed_stride, sensed_words, with_sensed,
    world_words,
};
use crate::ants::{AntGroup, AntObjectKind, AntSim, ROUTE_ADVANCE};
use crate::by_scalar;
use crate::engine::{Device, Engine, Exchange, exchanges_by_slot, group_of};
use crate::error::{Result, SimError};
use crate::gpu::Gpu;
use crate::gpu::grid::GpuGrid;
use crate::gpu::kernel::{Kernel, read_back, storage, zeroed, zeroed_ranges};
use crate::gpu::shaders::{ANT_TICK, DISPATCH, Module, SCALAR_F32, SCALAR_FX};
use crate::output::{Frame, Summary};
use crate::scalar::{AgentGroup, SimScalar};
use crate::scenario::Action;

/// Ticks between two checks for a controller's refusal (a read-back of eight words): a refusal
/// is reported with its own step, at most this many ticks later.
pub const CHECK_EVERY: u32 = 64;

/// Words of the tick's atomics (`ANT_TICK_*` in `ant_tick.wgsl`).
const SHARED_WORDS: usize = 8;
/// The words a tick starts with cleared: the shift and the two phases' refusals.
const SHARED_PER_TICK: u64 = 3 * 4;
const SHARED_KEPT: usize = 3;
const SHARED_KEPT_STEP: usize = 4;
const SHARED_KEPT_PHASE: usize = 5;
const SHARED_KEPT_SLOT: usize = 6;
const SHARED_KEPT_STATUS: usize = 7;

/// Binding numbers of `ant_sense.wgsl` and `ant_tick.wgsl`.
mod binding {
    pub const SENSE_PARAMS: u32 = 0;
    pub const WORLD: u32 = 1;
    pub const PREDICTED: u32 = 3;
    pub const STARTS: u32 = 4;
    pub const ORDER: u32 = 5;
    pub const OUT: u32 = 6;
    pub const TICK: u32 = 7;
    pub const STATES: u32 = 8;
    pub const PLANS: u32 = 9;
    pub const PREDICTED_OUT: u32 = 10;
    pub const NEXT: u32 = 11;
    pub const STATUS: u32 = 12;
    pub const PARAMS: u32 = 13;
    pub const GROUP: u32 = 14;
    pub const SHARED: u32 = 15;
    pub const COUNTS: u32 = 16;
    pub const SENSED_OUT: [u32; 6] = [17, 29, 30, 31, 32, 33];
    pub const WORLD_OUT: u32 = 18;
    pub const CHUNK: u32 = 35;
}

/// The draws of `rand::chance::<f32>(ctx, stream, p)` as an integer rule: the chance is
/// `unit(word) < p`, and `unit` grows with the word's top 24 bits `k`, so it is `k < K` for
/// the first `k` whose `unit` reaches `p` (`K`, returned; 2^24 when none does): the same draws
/// as the CPU's, with no `f32` on the GPU.
fn route_threshold(p: f32) -> u32 {
    let (mut lo, mut hi) = (0u64, 1u64 << 24);
    while lo < hi {
        let mid = (lo + hi) / 2;
        if <f32 as Scalar>::unit_open((mid << 8) as u32) < p {
            lo = mid + 1;
        } else {
            hi = mid;
        }
    }
    lo as u32
}

/// The passes of a tick, as a profiled tick times them ([`Engine::profile_tick`]).
const PASSES: [&str; 5] = ["cells", "grid", "plan", "resolve", "commit"];

/// The timestamp queries of a profiled tick: the start and end of each of [`PASSES`].
struct Profile {
    set: wgpu::QuerySet,
    resolve: wgpu::Buffer,
}

/// The timestamp writes of pass `k` of a profiled tick (none otherwise).
fn writes(profile: Option<&Profile>, k: u32) -> Option<wgpu::ComputePassTimestampWrites<'_>> {
    profile.map(|p| wgpu::ComputePassTimestampWrites {
        query_set: &p.set,
        beginning_of_pass_write_index: Some(2 * k),
        end_of_pass_write_index: Some(2 * k + 1),
    })
}

/// The GPU's buffers of one simulation.
struct Buffers {
    n: usize,
    chunks: Vec<Chunk>,
    sense_params: wgpu::Buffer,
    tick: wgpu::Buffer,
    world: wgpu::Buffer,
    sensed: wgpu::Buffer,
    predicted: wgpu::Buffer,
    cells: wgpu::Buffer,
    states: wgpu::Buffer,
    plans: wgpu::Buffer,
    next: wgpu::Buffer,
    status: wgpu::Buffer,
    params: wgpu::Buffer,
    group: wgpu::Buffer,
    shared: wgpu::Buffer,
    counts: wgpu::Buffer,
}

/// The compiled kernels of the tick and their bind groups (one per chunk for those that bind
/// the states a chunk at a time).
struct Kernels {
    cells: (Kernel, wgpu::BindGroup),
    plan: (Kernel, Vec<wgpu::BindGroup>),
    resolve: (Kernel, Vec<wgpu::BindGroup>),
    commit: (Kernel, Vec<wgpu::BindGroup>),
    end: (Kernel, wgpu::BindGroup),
    plan_frames: Kernel,
    resolve_frames: Kernel,
}

/// The modules of the engine's kernels over `scalar`.
fn modules(scalar: &'static Module) -> [&'static Module; 3] {
    [&DISPATCH, scalar, &ANT_TICK]
}

/// An ant simulation whose ticks run on the GPU (see the module's documentation).
pub struct GpuAntSim {
    sim: AntSim,
    gpu: Gpu,
    n: usize,
    places: usize,
    b: Buffers,
    k: Kernels,
    grid: GpuGrid,
    /// The world's words (the objects' part is rewritten by the GPU: food taken).
    world_len: usize,
    /// Deliveries per place (object id), as of the last [`Engine::sync`].
    delivered: Vec<u32>,
    /// Ticks since the last check for refusals.
    unchecked: u32,
    /// A failure to report at the next fallible call (from [`Engine::apply`], which cannot).
    failed: Option<SimError>,
    /// The timestamp queries of a profiled tick, while it runs.
    profile: Option<Profile>,
    /// The next tick (the host view's `step` is that of its last read-back).
    step: u32,
    /// Recorded steps being read back, oldest first ([`Engine::snapshot`]).
    snapshots: std::collections::VecDeque<Staged>,
    /// Staging buffers free for the next read-back (two in turn while frames are recorded).
    staging: Vec<wgpu::Buffer>,
}

/// A read-back on its way: the step it holds, its staging buffer, the submission that fills
/// it, and the map's answer.
struct Staged {
    step: u32,
    buffer: wgpu::Buffer,
    index: wgpu::SubmissionIndex,
    rx: std::sync::mpsc::Receiver<std::result::Result<(), wgpu::BufferAsyncError>>,
}

impl GpuAntSim {
    /// The simulation `sim` on the GPU `gpu`, from its current state.
    ///
    /// # Errors
    ///
    /// [`SimError::GpuMixedScalars`] if its groups do not all run one scalar type, and what
    /// compiling the kernels and sizing the grid refuse.
    pub fn new(sim: AntSim, gpu: Gpu) -> Result<GpuAntSim> {
        let most = chunk_capacity(&gpu);
        GpuAntSim::chunked(sim, gpu, most)
    }

    /// [`GpuAntSim::new`] with the states bound `most` ants at a time.
    pub(super) fn chunked(sim: AntSim, gpu: Gpu, most: usize) -> Result<GpuAntSim> {
        let first = sim.groups.first().ok_or(SimError::NoAgents)?;
        let scalar = by_scalar!(first, g => scalar_of(g));
        if let Some(other) = sim
            .groups
            .iter()
            .find(|g| by_scalar!(g, g => scalar_of(g)) != scalar)
        {
            return Err(SimError::GpuMixedScalars {
                first: first.name().to_string(),
                other: other.name().to_string(),
            });
        }
        let n = sim.agents();
        let shape = GridShape::of(&sim.world, n);
        let places = sim
            .world
            .objects
            .iter()
            .map(|o| usize::from(o.id) + 1)
            .max()
            .unwrap_or(0);
        let world = by_scalar!(first, g => world_words_of(g, &sim, &shape));
        let mut params = Vec::new();
        let mut group = vec![0u32; n];
        for (k, g) in sim.groups.iter().enumerate() {
            by_scalar!(g, g => layout::write_params(&mut params, &g.params));
            group[g.first()..g.first() + g.len()].fill(k as u32);
        }
        let d = &gpu.device;
        let uniform = |label, words: &[u32]| {
            d.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents: bytemuck::cast_slice(words),
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            })
        };
        let tick = [
            sim.seed,
            sim.step,
            route_threshold(ROUTE_ADVANCE),
            places as u32,
        ];
        // `per_ant` words for every ant.
        let words = |per_ant: usize| (n * per_ant) as u64;
        let b = Buffers {
            n,
            chunks: Chunk::split(&gpu, n, most),
            sense_params: uniform("ant sense params", &[n as u32, 0, 0, 0]),
            tick: uniform("ant tick params", &tick),
            world: storage(&gpu, "ant world", &world),
            sensed: zeroed_ranges(&gpu, "ant sensed", (sensed_stride(n) * SENSED_WORDS) as u64)?,
            predicted: zeroed(&gpu, "ant predicted", words(2))?,
            cells: zeroed(&gpu, "ant cells", words(1))?,
            states: zeroed_ranges(&gpu, "ant states", words(STATE_WORDS))?,
            plans: zeroed_ranges(&gpu, "ant plans", words(PLAN_WORDS))?,
            next: zeroed_ranges(&gpu, "ant next states", words(STATE_WORDS))?,
            status: zeroed(&gpu, "ant status", words(2))?,
            params: storage(&gpu, "ant params", &params),
            group: storage(&gpu, "ant groups", &group),
            shared: zeroed(&gpu, "ant tick atomics", SHARED_WORDS as u64)?,
            counts: zeroed(&gpu, "ant counts", 2 * places as u64)?,
        };
        let grid = GpuGrid::new(&gpu, n as u32, shape.cells())?;
        let k = Kernels::new(&gpu, scalar, &b, &grid)?;
        let sim_step = sim.step;
        let mut out = GpuAntSim {
            world_len: world.len(),
            delivered: vec![0; places],
            sim,
            gpu,
            n,
            places,
            b,
            k,
            grid,
            unchecked: 0,
            failed: None,
            profile: None,
            step: sim_step,
            snapshots: std::collections::VecDeque::new(),
            staging: Vec::new(),
        };
        out.push_states();
        Ok(out)
    }

    /// The adapter it runs on.
    pub fn gpu(&self) -> &Gpu {
        &self.gpu
    }

    /// The host view (after [`Engine::sync`]: the current states and counts).
    pub fn sim(&self) -> &AntSim {
        &self.sim
    }

    /// Uploads the host's states (and their sensed copy).
    fn push_states(&mut self) {
        let mut states = Vec::with_capacity(self.n * STATE_WORDS);
        for g in &self.sim.groups {
            by_scalar!(g, g => g.states.iter().for_each(|s| layout::write_state(&mut states, s)));
        }
        let first = &self.sim.groups[0];
        let sensed = by_scalar!(first, g => sensed_of(g, &self.sim));
        self.gpu
            .queue
            .write_buffer(&self.b.states, 0, bytemuck::cast_slice(&states));
        self.gpu
            .queue
            .write_buffer(&self.b.sensed, 0, bytemuck::cast_slice(&sensed));
    }

    /// Uploads the host's world (objects added, removed, moved).
    fn push_world(&mut self) {
        let shape = GridShape::of(&self.sim.world, self.n);
        let first = &self.sim.groups[0];
        let world = by_scalar!(first, g => world_words_of(g, &self.sim, &shape));
        debug_assert_eq!(
            world.len(),
            self.world_len,
            "events move objects, never add any"
        );
        self.gpu
            .queue
            .write_buffer(&self.b.world, 0, bytemuck::cast_slice(&world));
    }

    /// Reads the states, the objects, the counts and the kept refusal back into the host view
    /// now (waits for the GPU).
    fn pull(&mut self) -> Result<()> {
        let staged = self.stage()?;
        self.land(staged)
    }

    /// Starts copying what the host view holds (states, world, counts, the tick's atomics) into
    /// a staging buffer and mapping it, without waiting.
    fn stage(&mut self) -> Result<Staged> {
        let parts = [
            (&self.b.states, self.n * STATE_WORDS),
            (&self.b.world, self.world_len),
            (&self.b.counts, 2 * self.places),
            (&self.b.shared, SHARED_WORDS),
        ];
        let bytes: u64 = parts.iter().map(|(_, w)| 4 * *w as u64).sum();
        let buffer = match self.staging.iter().position(|b| b.size() == bytes) {
            Some(k) => self.staging.swap_remove(k),
            None => self.gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("ant staging"),
                size: bytes,
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
        };
        let mut enc = self.gpu.device.create_command_encoder(&Default::default());
        let mut at = 0;
        for (src, words) in parts {
            let size = 4 * words as u64;
            if size > 0 {
                enc.copy_buffer_to_buffer(src, 0, &buffer, at, size);
            }
            at += size;
        }
        let index = self.gpu.queue.submit([enc.finish()]);
        let (tx, rx) = std::sync::mpsc::channel();
        buffer.slice(..).map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        Ok(Staged {
            step: self.step,
            buffer,
            index,
            rx,
        })
    }

    /// Waits for `staged` and makes it the host view.
    fn land(&mut self, staged: Staged) -> Result<()> {
        self.gpu
            .device
            .poll(wgpu::PollType::Wait {
                submission_index: Some(staged.index),
                timeout: None,
            })
            .map_err(|source| SimError::GpuLost { source })?;
        let failed = |source| SimError::GpuReadback {
            buffer: "ant staging",
            source,
        };
        staged
            .rx
            .recv()
            .unwrap_or(Err(wgpu::BufferAsyncError))
            .map_err(failed)?;
        let words: Vec<u32> = {
            let view = staged
                .buffer
                .slice(..)
                .get_mapped_range()
                .map_err(|_| failed(wgpu::BufferAsyncError))?;
            bytemuck::cast_slice(&view).to_vec()
        };
        staged.buffer.unmap();
        self.staging.push(staged.buffer);
        let (states, rest) = words.split_at(self.n * STATE_WORDS);
        let (world, rest) = rest.split_at(self.world_len);
        let (counts, shared) = rest.split_at(2 * self.places);
        self.check_words(shared)?;
        self.sim.step = staged.step;
        let sim = &mut self.sim;
        for g in &mut sim.groups {
            by_scalar!(g, g => {
                for (k, s) in g.states.iter_mut().enumerate() {
                    let at = (g.first + k) * STATE_WORDS;
                    *s = layout::read_state(&states[at..at + STATE_WORDS])?;
                }
                sim.world.sensed.write(g.first, &g.ids, &g.states);
            });
        }
        let at = world[super::world::H_OBJECTS_AT] as usize;
        for (k, o) in self.sim.world.objects.iter_mut().enumerate() {
            let w = &world[at + k * OBJECT_WORDS..];
            o.active = w[2] != 0;
            if let AntObjectKind::Food { amount: Some(a) } = &mut o.kind {
                *a = w[3];
            }
        }
        self.delivered = counts[self.places..].to_vec();
        self.sim.delivered = self.delivered.iter().map(|&c| u64::from(c)).sum();
        Ok(())
    }

    /// The first refusal of a controller since the start, as the CPU engine reports it.
    fn check(&mut self) -> Result<()> {
        let w: Vec<u32> = read_back(&self.gpu, "ant tick atomics", &self.b.shared, SHARED_WORDS)?;
        self.check_words(&w)
    }

    /// [`GpuAntSim::check`] of the tick's atomics `w` read back.
    fn check_words(&mut self, w: &[u32]) -> Result<()> {
        if let Some(e) = self.failed.take() {
            return Err(e);
        }
        self.unchecked = 0;
        if w[SHARED_KEPT] == 0 {
            return Ok(());
        }
        let slot = w[SHARED_KEPT_SLOT] as usize;
        let agent = self.sim.world.sensed.id.get(slot).copied().unwrap_or(0);
        let phase = if w[SHARED_KEPT_PHASE] == 0 {
            "ant plan"
        } else {
            "ant resolve"
        };
        let status = w[SHARED_KEPT_STATUS];
        let Err(e) = layout::status_error(status)? else {
            return Err(SimError::GpuWords {
                word: status,
                what: "refusal",
            });
        };
        Err(SimError::controller(phase, w[SHARED_KEPT_STEP], agent, e))
    }

    /// Every ant's frames of phase `phase` sensed on the GPU, as words.
    fn frames(&self, phase: usize) -> Result<Vec<u32>> {
        let (kernel, words) = match phase {
            0 => (&self.k.plan_frames, PLAN_FRAME_WORDS),
            _ => (&self.k.resolve_frames, RESOLVE_FRAME_WORDS),
        };
        use binding::*;
        let out = storage(&self.gpu, "ant frames", &vec![0u32; self.n * words]);
        let whole = [
            (SENSE_PARAMS, &self.b.sense_params),
            (WORLD, &self.b.world),
            (STARTS, self.grid.starts()),
            (ORDER, self.grid.order()),
            (PREDICTED, &self.b.predicted),
            (OUT, &out),
        ];
        let group = kernel.bind_resources(&self.gpu, &with_sensed(&self.b.sensed, self.n, &whole));
        let mut enc = self.gpu.device.create_command_encoder(&Default::default());
        {
            let mut pass = enc.begin_compute_pass(&Default::default());
            kernel.dispatch(&mut pass, &group, self.n as u32);
        }
        self.gpu.queue.submit([enc.finish()]);
        read_back(&self.gpu, "ant frames", &out, self.n * words)
    }

    /// Submits what `enc` recorded (the GPU runs it while the host goes on).
    fn submit(&self, enc: wgpu::CommandEncoder) {
        self.gpu.queue.submit([enc.finish()]);
    }

    /// `kernel` over every chunk of ants.
    fn dispatch_chunks(
        &self,
        pass: &mut wgpu::ComputePass<'_>,
        kernel: &(Kernel, Vec<wgpu::BindGroup>),
    ) {
        for (c, g) in self.b.chunks.iter().zip(&kernel.1) {
            kernel.0.dispatch(pass, g, c.len);
        }
    }

    /// Pass `k` of [`PASSES`] in `enc`, timed in a profiled tick.
    fn pass<'e>(&self, enc: &'e mut wgpu::CommandEncoder, k: u32) -> wgpu::ComputePass<'e> {
        enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(PASSES[k as usize]),
            timestamp_writes: writes(self.profile.as_ref(), k),
        })
    }

    /// The bytes of its buffers on the device.
    fn bytes(&self) -> u64 {
        let b = &self.b;
        [
            &b.sense_params,
            &b.tick,
            &b.world,
            &b.sensed,
            &b.predicted,
            &b.cells,
            &b.states,
            &b.plans,
            &b.next,
            &b.status,
            &b.params,
            &b.group,
            &b.shared,
            &b.counts,
        ]
        .into_iter()
        .map(wgpu::Buffer::size)
        .sum::<u64>()
            + self.grid.bytes()
    }
}

/// The scalar of a group.
fn scalar_of<S: Scalar>(_: &AntGroup<S>) -> ScalarKind {
    S::KIND
}

/// The world's words in the scalar of group `_g`.
fn world_words_of<S: Word + SimScalar>(
    _g: &AntGroup<S>,
    sim: &AntSim,
    shape: &GridShape,
) -> Vec<u32> {
    world_words::<S>(&sim.world, shape)
}

/// The sensed ants' words in the scalar of group `_g`.
fn sensed_of<S: Word + SimScalar>(_g: &AntGroup<S>, sim: &AntSim) -> Vec<u32> {
    sensed_words::<S>(&sim.world)
}

impl Kernels {
    fn new(gpu: &Gpu, scalar: ScalarKind, b: &Buffers, grid: &GpuGrid) -> Result<Kernels> {
        let m = modules(match scalar {
            ScalarKind::I16F16 => &SCALAR_FX,
            ScalarKind::F32 => &SCALAR_F32,
        });
        let kernel = |name, entry| Kernel::new(gpu, name, &m, SENSE_KERNEL, entry);
        use binding::*;
        // Every buffer at its binding (each kernel binds those it uses), the sensed ants'
        // arrays read and written, and the chunk's ranges.
        let whole = [
            (SENSE_PARAMS, &b.sense_params),
            (WORLD, &b.world),
            (PREDICTED, &b.predicted),
            (STARTS, grid.starts()),
            (ORDER, grid.order()),
            (OUT, &b.cells),
            (TICK, &b.tick),
            (PREDICTED_OUT, &b.predicted),
            (STATUS, &b.status),
            (PARAMS, &b.params),
            (GROUP, &b.group),
            (SHARED, &b.shared),
            (COUNTS, &b.counts),
            (WORLD_OUT, &b.world),
        ];
        let mut all = with_sensed(&b.sensed, b.n, &whole);
        all.extend(sensed_ranges(&b.sensed, b.n, SENSED_OUT));
        let chunked = |k: Kernel| {
            let groups = b
                .chunks
                .iter()
                .map(|c| {
                    let mut entries = all.clone();
                    entries.extend([
                        (CHUNK, c.uniform.as_entire_binding()),
                        (STATES, c.range(&b.states, STATE_WORDS)),
                        (PLANS, c.range(&b.plans, PLAN_WORDS)),
                        (NEXT, c.range(&b.next, STATE_WORDS)),
                    ]);
                    k.bind_resources(gpu, &entries)
                })
                .collect();
            (k, groups)
        };
        let single = |k: Kernel| {
            let g = k.bind_resources(gpu, &all);
            (k, g)
        };
        Ok(Kernels {
            cells: single(kernel("ant_sense_cells", "ant_sense_cells_main")?),
            plan: chunked(kernel("ant_tick_plan", "ant_tick_plan_main")?),
            resolve: chunked(kernel("ant_tick_resolve", "ant_tick_resolve_main")?),
            commit: chunked(kernel("ant_tick_commit", "ant_tick_commit_main")?),
            end: single(kernel("ant_tick_end", "ant_tick_end_main")?),
            plan_frames: kernel("ant_plan_frames", "ant_plan_frames_main")?,
            resolve_frames: kernel("ant_resolve_frames", "ant_resolve_frames_main")?,
        })
    }
}

/// Ants `first..first + len`, a dispatch of the kernels that bind the states a chunk at a time.
struct Chunk {
    first: u32,
    len: u32,
    /// `AntChunk` (`first`, `len`).
    uniform: wgpu::Buffer,
}

impl Chunk {
    /// The chunks of `n` ants, at most `most` (a multiple of 64) each.
    fn split(gpu: &Gpu, n: usize, most: usize) -> Vec<Chunk> {
        (0..n)
            .step_by(most.max(1))
            .map(|first| {
                let len = most.min(n - first);
                let words = [first as u32, len as u32, 0, 0];
                Chunk {
                    first: first as u32,
                    len: len as u32,
                    uniform: gpu
                        .device
                        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                            label: Some("ant chunk"),
                            contents: bytemuck::cast_slice(&words),
                            usage: wgpu::BufferUsages::UNIFORM,
                        }),
                }
            })
            .collect()
    }

    /// The chunk's part of `buffer`, of `words` words an ant.
    fn range<'a>(&self, buffer: &'a wgpu::Buffer, words: usize) -> wgpu::BindingResource<'a> {
        let bytes = 4 * words as u64;
        wgpu::BindingResource::Buffer(wgpu::BufferBinding {
            buffer,
            offset: u64::from(self.first) * bytes,
            size: std::num::NonZeroU64::new(u64::from(self.len) * bytes),
        })
    }
}

/// The most ants of a chunk on `gpu`: a multiple of 64 (every chunk's ranges start 256-byte
/// aligned) whose plans (the largest words an ant) fit one binding.
fn chunk_capacity(gpu: &Gpu) -> usize {
    let limit = gpu.max_binding().min(u64::from(u32::MAX));
    ((limit / (4 * PLAN_WORDS as u64)) as usize / 64 * 64).max(64)
}

impl Engine for GpuAntSim {
    fn model(&self) -> &'static str {
        self.sim.model()
    }
    fn agents(&self) -> usize {
        self.n
    }
    fn next_step(&self) -> u32 {
        self.step
    }
    fn apply(&mut self, object: u16, action: &Action) {
        if let Err(e) = self.pull() {
            self.failed.get_or_insert(e);
            return;
        }
        let moved = self.sim.moved_out;
        self.sim.apply(object, action);
        self.push_world();
        if self.sim.moved_out != moved {
            self.push_states();
        }
    }
    fn phases(&self) -> &'static [&'static str] {
        self.sim.phases()
    }
    fn backend(&self) -> &'static str {
        "gpu"
    }
    fn adapter(&self) -> Option<String> {
        Some(self.gpu.info().to_string())
    }
    fn decide(&mut self, phase: usize) -> Result<()> {
        if let Some(e) = self.failed.take() {
            return Err(e);
        }
        let n = self.n as u32;
        let mut enc = self.gpu.device.create_command_encoder(&Default::default());
        if phase == 0 {
            self.gpu
                .queue
                .write_buffer(&self.b.tick, 4, bytemuck::cast_slice(&[self.step]));
            enc.clear_buffer(&self.b.shared, 0, Some(SHARED_PER_TICK));
            {
                let mut pass = self.pass(&mut enc, 0);
                let (k, g) = &self.k.cells;
                k.dispatch(&mut pass, g, n);
            }
            let timed = writes(self.profile.as_ref(), 1);
            self.grid
                .record_timed(&self.gpu, &mut enc, &self.b.cells, n, timed)?;
            let mut pass = self.pass(&mut enc, 2);
            self.dispatch_chunks(&mut pass, &self.k.plan);
        } else {
            // The tick's largest shift widens the resolve frames' query (AntSenseParams.shift).
            enc.copy_buffer_to_buffer(&self.b.shared, 0, &self.b.sense_params, 4, 4);
            let mut pass = self.pass(&mut enc, 3);
            self.dispatch_chunks(&mut pass, &self.k.resolve);
        }
        self.submit(enc);
        Ok(())
    }
    fn publish(&mut self, phase: usize) -> Result<()> {
        if phase == 0 {
            return Ok(());
        }
        let mut enc = self.gpu.device.create_command_encoder(&Default::default());
        {
            let mut pass = self.pass(&mut enc, 4);
            self.dispatch_chunks(&mut pass, &self.k.commit);
            let (k, g) = &self.k.end;
            k.dispatch(&mut pass, g, self.sim.world.objects.len().max(1) as u32);
        }
        // The collections were counted into the food; the deliveries keep counting.
        if self.places > 0 {
            enc.clear_buffer(&self.b.counts, 0, Some(4 * self.places as u64));
        }
        self.submit(enc);
        self.step += 1;
        self.unchecked += 1;
        if self.unchecked >= CHECK_EVERY {
            self.check()?;
        }
        Ok(())
    }
    fn sync(&mut self) -> Result<()> {
        self.pull()
    }
    fn frames_in_flight(&self) -> usize {
        1
    }
    fn snapshot(&mut self) -> Result<()> {
        let staged = self.stage()?;
        self.snapshots.push_back(staged);
        Ok(())
    }
    fn take_snapshot(&mut self) -> Result<()> {
        match self.snapshots.pop_front() {
            Some(staged) => self.land(staged),
            None => self.pull(),
        }
    }
    fn profile_tick(&mut self) -> Result<Option<Vec<(&'static str, f64)>>> {
        if !self.gpu.has_timestamps() {
            return Ok(None);
        }
        let queries = 2 * PASSES.len() as u32;
        let d = &self.gpu.device;
        let set = d.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("ant tick timestamps"),
            ty: wgpu::QueryType::Timestamp,
            count: queries,
        });
        let resolve = d.create_buffer(&wgpu::BufferDescriptor {
            label: Some("ant tick timestamps"),
            size: 8 * u64::from(queries),
            usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        self.profile = Some(Profile { set, resolve });
        let ticked = self.tick();
        let Some(p) = self.profile.take() else {
            unreachable!("set above");
        };
        ticked?;
        let mut enc = self.gpu.device.create_command_encoder(&Default::default());
        enc.resolve_query_set(&p.set, 0..queries, &p.resolve, 0);
        self.submit(enc);
        let t: Vec<u64> = read_back(
            &self.gpu,
            "ant tick timestamps",
            &p.resolve,
            2 * PASSES.len(),
        )?;
        let ns = f64::from(self.gpu.queue.get_timestamp_period());
        Ok(Some(
            PASSES
                .iter()
                .enumerate()
                .map(|(k, &name)| {
                    (
                        name,
                        t[2 * k + 1].saturating_sub(t[2 * k]) as f64 * ns / 1e6,
                    )
                })
                .collect(),
        ))
    }
    fn device_bytes(&self) -> Option<u64> {
        Some(self.bytes())
    }
    fn exchanges(&self, phase: usize, agents: &[u32]) -> Result<Vec<Exchange>> {
        let frames = self.frames(phase)?;
        let (before, after, words) = match phase {
            0 => (&self.b.states, &self.b.plans, (STATE_WORDS, PLAN_WORDS)),
            _ => (&self.b.plans, &self.b.next, (PLAN_WORDS, STATE_WORDS)),
        };
        let before: Vec<u32> = read_back(&self.gpu, "ant requests", before, self.n * words.0)?;
        let after: Vec<u32> = read_back(&self.gpu, "ant replies", after, self.n * words.1)?;
        let sim = &self.sim;
        let seen = Seen {
            frames: &frames,
            before: &before,
            after: &after,
            seed: sim.seed,
            step: self.step,
        };
        exchanges_by_slot(&sim.world.sensed.id, agents, |slot| {
            let (g, _) = group_of(&sim.groups, slot)?;
            Some(by_scalar!(g, g => seen.exchange(g, slot, phase)))
        })
    }
    fn device(&self) -> Result<Device> {
        self.sim.device()
    }
    fn frame(&self) -> Frame {
        self.sim.frame()
    }
    fn state_names(&self) -> crate::engine::StateNames {
        self.sim.state_names()
    }
    fn collision_distance(&self) -> f32 {
        self.sim.collision_distance()
    }
    fn begin_summary(&self, summary: &mut Summary) {
        self.sim.begin_summary(summary);
    }
    fn on_record(&self, summary: &mut Summary, step: u32) {
        self.sim.on_record(summary, step);
    }
    fn closing(&self, summary: &mut Summary) -> String {
        // The deliveries at each nest (at way points: in the total only), counted on the GPU.
        for (id, &c) in self.delivered.iter().enumerate() {
            let home = |o: &&crate::ants::AntObjectDef| {
                usize::from(o.id) == id && o.kind == AntObjectKind::Nest
            };
            if let Some(o) = self.sim.world.objects.iter().find(home) {
                *summary
                    .deliveries_per_nest
                    .entry(o.name.clone())
                    .or_default() += u64::from(c);
            }
        }
        self.sim.closing(summary)
    }
}

/// The words read back for the exchanges of one phase.
struct Seen<'a> {
    frames: &'a [u32],
    before: &'a [u32],
    after: &'a [u32],
    seed: u32,
    step: u32,
}

impl Seen<'_> {
    /// The exchange of the ant in slot `slot` (of group `g`).
    fn exchange<S: Word + SimScalar>(
        &self,
        g: &AntGroup<S>,
        slot: usize,
        phase: usize,
    ) -> Result<Exchange> {
        let id = g.ids[slot - g.first];
        let at = |w: &[u32], words: usize| w[slot * words..(slot + 1) * words].to_vec();
        if phase == 0 {
            let request = AntPlanRequest {
                state: layout::read_state::<S>(&at(self.before, STATE_WORDS))?,
                frame: layout::read_plan_frame::<S>(&at(self.frames, PLAN_FRAME_WORDS))?,
                ctx: StepCtx {
                    seed: self.seed,
                    agent: id,
                    step: self.step,
                },
            };
            let reply = AntPlanReply {
                plan: layout::read_plan::<S>(&at(self.after, PLAN_WORDS))?,
            };
            Exchange::of::<AntParams<S>, Plan>(id, &request, &reply)
        } else {
            let request = AntResolveRequest {
                plan: layout::read_plan::<S>(&at(self.before, PLAN_WORDS))?,
                frame: layout::read_resolve_frame::<S>(&at(self.frames, RESOLVE_FRAME_WORDS))?,
            };
            let reply = AntResolveReply {
                state: layout::read_state::<S>(&at(self.after, STATE_WORDS))?,
            };
            Exchange::of::<AntParams<S>, Resolve>(id, &request, &reply)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarm_core::rand;

    #[test]
    fn the_route_threshold_draws_as_the_cpu() {
        for p in [0.0f32, 1e-9, 0.25, 0.5, 0.7, 0.999_999, 1.0, 2.0] {
            let t = route_threshold(p);
            let edge = t.wrapping_shl(8);
            for word in [
                0u32,
                1,
                255,
                256,
                edge.wrapping_sub(1),
                edge,
                edge | 255,
                u32::MAX,
            ]
            .into_iter()
            .chain((0..4096).map(|k| rand::rand(7, k, 3, 0x5200)))
            {
                let cpu = <f32 as Scalar>::unit_open(word) < p;
                assert_eq!(word >> 8 < t, cpu, "p {p} word {word:#x} threshold {t:#x}");
            }
        }
    }
}
