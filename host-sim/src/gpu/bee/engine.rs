//! The bee simulation on the GPU: an [`Engine`] whose steps run on wgpu
//! (`shaders/bee_tick.wgsl`), the bees' states staying on the GPU between ticks.
//!
//! [`GpuBeeSim`] keeps the CPU simulation ([`BeeSim`]) as its host view: the world's obstacles
//! and targets, the groups' parameters, goals and ids, what the outputs and the mirror read. A
//! tick sends its number and the bees' frame times (below); the grid, the frames, the
//! controller, the world's corrections and their counts are computed on the GPU. The host reads
//! back only when it needs to look ([`Engine::sync`] before a recorded frame and at the end,
//! [`Engine::exchanges`] for the mirror, and a check for refusals every [`CHECK_EVERY`] ticks),
//! and uploads what a scenario event changed (the world's words).
//!
//! **The frame times.** The CPU gives every bee its own clock, computed in `f64`
//! ([`bee_frame_time`](crate::bees::bee_frame_time): `wrap_time(step · dt + clock_offset)`),
//! then converted to the bee's scalar. WGSL has no `f64`, and an integer or `S` formulation
//! would differ from the `f64` one wherever the sum's own rounding decides the conversion's, which
//! no test over realistic ranges can rule out (`docs/gpu.md`). So the host computes every bee's
//! time each tick, exactly as the CPU engine does (each bee's `clock_offset` drawn once, then the
//! same `f64` expression: [`frame_time`], checked against `bee_frame_time` by a test), in
//! parallel, and uploads them with `queue.write_buffer` before the tick's kernels: an upload the
//! host does not wait for (4 bytes a bee a tick), not a round trip.
//!
//! In fixed point every word is the CPU engine's: the kernels are `swarm-core`'s controller and
//! the CPU's sensing and confinement function by function (`docs/gpu.md`), and the corrections
//! are counted with atomic sums. Slots are not reordered (the GPU's grid is sorted every tick;
//! results do not depend on slots).

use rayon::prelude::*;
use swarm_core::bee::oscillation::{clock_offset, wrap_time};
use swarm_core::bee::{BeeParams, BeeStepReply, BeeStepRequest, Step};
use swarm_core::{Fx, Scalar, ScalarKind};
use wgpu::util::DeviceExt;

use super::layout::{self, DECISION_WORDS, FRAME_WORDS, STATE_WORDS, Word};
use super::sense::SENSE_KERNEL;
use super::world::{GridShape3, INPUT_GOAL, INPUT_T, NO_GOAL, sensed_words, world_words};
use crate::bees::{BeeGroup, BeeSim, Contacts, SURFACE_OFFSET};
use crate::by_scalar;
use crate::engine::{Device, Engine, Exchange, exchanges_by_slot, group_of};
use crate::error::{Result, SimError};
use crate::gpu::Gpu;
use crate::gpu::grid::GpuGrid;
use crate::gpu::kernel::{Kernel, read_back, storage};
use crate::gpu::shaders::{BEE_LAYOUT, BEE_TICK, DISPATCH, Module, SCALAR_F32, SCALAR_FX};
use crate::gpu::space::confine_boxes;
use crate::output::{Frame, Summary};
use crate::scalar::{AgentGroup, SimScalar};
use crate::scenario::Action;

/// Ticks between two checks for a controller's refusal (a read-back of a few words): a refusal
/// is reported with its own step, at most this many ticks later.
pub const CHECK_EVERY: u32 = 64;

/// Words of the tick's atomics (`BEE_TICK_*` in `bee_tick.wgsl`).
const SHARED_WORDS: usize = 11;
/// The words a tick starts with cleared: its refusal and its two kinds of corrections.
const SHARED_PER_TICK: u64 = 3 * 4;
const SHARED_OBSTACLE: usize = 1;
const SHARED_BOUNDS: usize = 2;
const SHARED_KEPT: usize = 3;
const SHARED_KEPT_STEP: usize = 4;
const SHARED_KEPT_ID: usize = 5;
const SHARED_KEPT_STATUS: usize = 6;
const SHARED_TOTAL_OBSTACLE: usize = 7;
const SHARED_TOTAL_BOUNDS: usize = 9;

/// Binding numbers of `bee_sense.wgsl` and `bee_tick.wgsl`.
mod binding {
    pub const SENSE_PARAMS: u32 = 0;
    pub const WORLD: u32 = 1;
    pub const SENSED: u32 = 2;
    pub const INPUTS: u32 = 3;
    pub const STARTS: u32 = 4;
    pub const ORDER: u32 = 5;
    pub const OUT: u32 = 6;
    pub const TICK: u32 = 7;
    pub const STATES: u32 = 8;
    pub const DECISIONS: u32 = 9;
    pub const NEXT: u32 = 10;
    pub const STATUS: u32 = 11;
    pub const PARAMS: u32 = 12;
    pub const GROUP: u32 = 13;
    pub const SHARED: u32 = 14;
    pub const BOXES: u32 = 15;
    pub const SENSED_OUT: u32 = 16;
    pub const CORRECTED: u32 = 17;
}

/// The frame time of a bee whose clock offset is `offset`, at step `step`, its group's time
/// step `dt`: `bee_time`'s expression ([`swarm_core::bee::oscillation::bee_time`]) with the
/// offset drawn beforehand, the same `f64` bits as
/// [`bee_frame_time`](crate::bees::bee_frame_time).
pub fn frame_time(offset: f64, step: u32, dt: f64) -> f64 {
    wrap_time(f64::from(step) * dt + offset)
}

/// `Fx::from_f64(t)`'s word ([`SimScalar::from_f64`]: the `fixed` crate's conversion, rounding
/// to the nearest with ties to even, saturating; 0 for NaN), computed directly: scaling by 2^16
/// is exact in `f64`, so it is `t · 2^16` rounded to the nearest integer, ties to even, clamped
/// to `i32`. About ten times faster than the crate's generic conversion, which made the frame
/// times of a million bees cost tens of milliseconds a tick; the same bits (a test).
fn fx_word(t: f64) -> u32 {
    if t.is_nan() {
        return 0;
    }
    let r = (t * 65536.0).round_ties_even();
    r.clamp(f64::from(i32::MIN), f64::from(i32::MAX)) as i32 as u32
}

/// The GPU's buffers of one simulation.
struct Buffers {
    sense_params: wgpu::Buffer,
    tick: wgpu::Buffer,
    world: wgpu::Buffer,
    sensed: wgpu::Buffer,
    inputs: wgpu::Buffer,
    cells: wgpu::Buffer,
    states: wgpu::Buffer,
    decisions: wgpu::Buffer,
    next: wgpu::Buffer,
    status: wgpu::Buffer,
    params: wgpu::Buffer,
    group: wgpu::Buffer,
    shared: wgpu::Buffer,
    boxes: wgpu::Buffer,
    corrected: wgpu::Buffer,
}

/// The compiled kernels of the tick.
struct Kernels {
    cells: Kernel,
    step: Kernel,
    commit: Kernel,
    frames: Kernel,
}

/// The tick kernels' bind groups (made again when the world's buffer grows).
struct Bound {
    cells: wgpu::BindGroup,
    step: wgpu::BindGroup,
    commit: wgpu::BindGroup,
}

/// The modules of the engine's kernels over `scalar`.
fn modules(scalar: &'static Module) -> [&'static Module; 4] {
    [&DISPATCH, scalar, &BEE_TICK, &BEE_LAYOUT]
}

/// A bee simulation whose steps run on the GPU (see the module's documentation).
pub struct GpuBeeSim {
    sim: BeeSim,
    gpu: Gpu,
    n: usize,
    scalar: ScalarKind,
    shape: GridShape3,
    b: Buffers,
    k: Kernels,
    bound: Bound,
    grid: GpuGrid,
    /// The world buffer's size in words (it grows when an event adds target particles).
    world_cap: usize,
    /// Each slot's clock offset and its group's time step (`f64`, as the CPU's).
    offsets: Vec<f64>,
    dts: Vec<f64>,
    /// The frame times of the tick, as words (reused).
    times: Vec<u32>,
    /// Ticks since the last check for refusals.
    unchecked: u32,
    /// A failure to report at the next fallible call (from [`Engine::apply`], which cannot).
    failed: Option<SimError>,
}

/// The scalar of a group.
fn scalar_of<S: Scalar>(_: &BeeGroup<S>) -> ScalarKind {
    S::KIND
}

impl GpuBeeSim {
    /// The simulation `sim` on the GPU `gpu`, from its current state.
    ///
    /// # Errors
    ///
    /// [`SimError::GpuMixedScalars`] if its groups do not all run one scalar type,
    /// [`SimError::NoAgents`] without groups, and what compiling the kernels and sizing the
    /// grid refuse.
    pub fn new(sim: BeeSim, gpu: Gpu) -> Result<GpuBeeSim> {
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
        let shape = GridShape3::of(&sim.world, n);
        let mut params = Vec::new();
        let mut group = vec![0u32; n];
        let mut offsets = vec![0.0; n];
        let mut dts = vec![0.0; n];
        // The frames' inputs: the times (uploaded every tick), then each bee's goal.
        let mut inputs = vec![0u32; 2 * n];
        for (k, g) in sim.groups.iter().enumerate() {
            let r = g.first()..g.first() + g.len();
            group[r.clone()].fill(k as u32);
            let (dt, goal) = by_scalar!(g, g => {
                layout::write_params(&mut params, &g.params);
                (g.params.dt.to_f64(), g.goal)
            });
            dts[r.clone()].fill(dt);
            inputs[INPUT_GOAL * n + r.start..INPUT_GOAL * n + r.end]
                .fill(goal.map_or(NO_GOAL, u32::from));
        }
        for (slot, o) in offsets.iter_mut().enumerate() {
            *o = clock_offset(sim.seed, sim.world.sensed.id[slot]);
        }
        let world = match scalar {
            ScalarKind::I16F16 => world_words::<Fx>(&sim.world, &shape),
            ScalarKind::F32 => world_words::<f32>(&sim.world, &shape),
        };
        let boxes = match scalar {
            ScalarKind::I16F16 => confine_boxes::<Fx>(&sim.world.obstacles),
            ScalarKind::F32 => confine_boxes::<f32>(&sim.world.obstacles),
        };
        let mut shared = [0u32; SHARED_WORDS];
        let c = sim.contacts;
        shared[SHARED_OBSTACLE] = sim.last_contacts.obstacle as u32;
        shared[SHARED_BOUNDS] = sim.last_contacts.bounds as u32;
        shared[SHARED_TOTAL_OBSTACLE] = c.obstacle as u32;
        shared[SHARED_TOTAL_OBSTACLE + 1] = (c.obstacle >> 32) as u32;
        shared[SHARED_TOTAL_BOUNDS] = c.bounds as u32;
        shared[SHARED_TOTAL_BOUNDS + 1] = (c.bounds >> 32) as u32;
        let d = &gpu.device;
        let uniform = |label, words: &[u32]| {
            d.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents: bytemuck::cast_slice(words),
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            })
        };
        let offset = match scalar {
            ScalarKind::I16F16 => Fx::from_f32(SURFACE_OFFSET).to_word(),
            ScalarKind::F32 => SURFACE_OFFSET.to_word(),
        };
        let b = Buffers {
            sense_params: uniform("bee sense params", &[n as u32, 0, 0, 0]),
            tick: uniform("bee tick params", &[sim.step, offset, 0, 0]),
            world: storage(&gpu, "bee world", &world),
            sensed: storage(&gpu, "bee sensed", &vec![0u32; n * 8]),
            inputs: storage(&gpu, "bee frame inputs", &inputs),
            cells: storage(&gpu, "bee cells", &vec![0u32; n]),
            states: storage(&gpu, "bee states", &vec![0u32; n * STATE_WORDS]),
            decisions: storage(&gpu, "bee decisions", &vec![0u32; n * DECISION_WORDS]),
            next: storage(&gpu, "bee next states", &vec![0u32; n * STATE_WORDS]),
            status: storage(&gpu, "bee status", &vec![0u32; n]),
            params: storage(&gpu, "bee params", &params),
            group: storage(&gpu, "bee groups", &group),
            shared: storage(&gpu, "bee tick atomics", &shared),
            boxes: storage(&gpu, "bee confinement boxes", &boxes),
            corrected: storage(&gpu, "bee corrections", &vec![0u32; n]),
        };
        let grid = GpuGrid::new(&gpu, n as u32, shape.cells())?;
        let k = Kernels::new(&gpu, scalar)?;
        let bound = k.bind(&gpu, &b, &grid);
        let mut out = GpuBeeSim {
            world_cap: world.len().max(1),
            sim,
            gpu,
            n,
            scalar,
            shape,
            b,
            k,
            bound,
            grid,
            offsets,
            dts,
            times: vec![0; n],
            unchecked: 0,
            failed: None,
        };
        out.push_states();
        Ok(out)
    }

    /// The adapter it runs on.
    pub fn gpu(&self) -> &Gpu {
        &self.gpu
    }

    /// The host view (after [`Engine::sync`]: the current states, decisions, corrections and
    /// counts).
    pub fn sim(&self) -> &BeeSim {
        &self.sim
    }

    /// Uploads the host's states, decisions and corrections, and their sensed copy.
    fn push_states(&mut self) {
        let (mut states, mut decisions) = (Vec::new(), Vec::new());
        let mut corrected = Vec::with_capacity(self.n);
        for g in &self.sim.groups {
            by_scalar!(g, g => {
                g.states.iter().for_each(|s| layout::write_state(&mut states, s));
                g.decisions.iter().for_each(|d| layout::write_decision(&mut decisions, d));
                corrected.extend(g.corrected.iter().map(|&c| u32::from(c)));
            });
        }
        let sensed = match self.scalar {
            ScalarKind::I16F16 => sensed_words::<Fx>(&self.sim.world),
            ScalarKind::F32 => sensed_words::<f32>(&self.sim.world),
        };
        let q = &self.gpu.queue;
        q.write_buffer(&self.b.states, 0, bytemuck::cast_slice(&states));
        q.write_buffer(&self.b.decisions, 0, bytemuck::cast_slice(&decisions));
        q.write_buffer(&self.b.corrected, 0, bytemuck::cast_slice(&corrected));
        q.write_buffer(&self.b.sensed, 0, bytemuck::cast_slice(&sensed));
    }

    /// Uploads the host's world (obstacles moved, started, stopped; targets moved, added,
    /// removed, and so their particles): its words, and the obstacles' confinement boxes.
    fn push_world(&mut self) {
        let (world, boxes) = match self.scalar {
            ScalarKind::I16F16 => (
                world_words::<Fx>(&self.sim.world, &self.shape),
                confine_boxes::<Fx>(&self.sim.world.obstacles),
            ),
            ScalarKind::F32 => (
                world_words::<f32>(&self.sim.world, &self.shape),
                confine_boxes::<f32>(&self.sim.world.obstacles),
            ),
        };
        if world.len() > self.world_cap {
            // More particles than the buffer holds: a larger one, bound again.
            self.b.world = storage(&self.gpu, "bee world", &world);
            self.world_cap = world.len();
            self.bound = self.k.bind(&self.gpu, &self.b, &self.grid);
        } else {
            self.gpu
                .queue
                .write_buffer(&self.b.world, 0, bytemuck::cast_slice(&world));
        }
        if !boxes.is_empty() {
            self.gpu
                .queue
                .write_buffer(&self.b.boxes, 0, bytemuck::cast_slice(&boxes));
        }
    }

    /// Reads the states, decisions, corrections and counts back into the host view.
    fn pull(&mut self) -> Result<()> {
        self.check()?;
        let n = self.n;
        let states: Vec<u32> = read_back(&self.gpu, "bee states", &self.b.states, n * STATE_WORDS)?;
        let decisions: Vec<u32> = read_back(
            &self.gpu,
            "bee decisions",
            &self.b.decisions,
            n * DECISION_WORDS,
        )?;
        let corrected: Vec<u32> = read_back(&self.gpu, "bee corrections", &self.b.corrected, n)?;
        let sim = &mut self.sim;
        for g in &mut sim.groups {
            by_scalar!(g, g => {
                for k in 0..g.states.len() {
                    let slot = g.first + k;
                    let s = &states[slot * STATE_WORDS..(slot + 1) * STATE_WORDS];
                    let d = &decisions[slot * DECISION_WORDS..(slot + 1) * DECISION_WORDS];
                    g.states[k] = layout::read_state(s)?;
                    g.decisions[k] = layout::read_decision(d)?;
                    g.corrected[k] = corrected[slot] as u8;
                }
                sim.world.sensed.write(g.first, &g.ids, &g.states);
            });
        }
        let w: Vec<u32> = read_back(&self.gpu, "bee tick atomics", &self.b.shared, SHARED_WORDS)?;
        let u64_at = |at: usize| u64::from(w[at]) | u64::from(w[at + 1]) << 32;
        sim.last_contacts = Contacts {
            obstacle: u64::from(w[SHARED_OBSTACLE]),
            bounds: u64::from(w[SHARED_BOUNDS]),
        };
        sim.contacts = Contacts {
            obstacle: u64_at(SHARED_TOTAL_OBSTACLE),
            bounds: u64_at(SHARED_TOTAL_BOUNDS),
        };
        Ok(())
    }

    /// The first refusal of a controller since the start, as the CPU engine reports it.
    fn check(&mut self) -> Result<()> {
        if let Some(e) = self.failed.take() {
            return Err(e);
        }
        self.unchecked = 0;
        let w: Vec<u32> = read_back(&self.gpu, "bee tick atomics", &self.b.shared, SHARED_WORDS)?;
        if w[SHARED_KEPT] == 0 {
            return Ok(());
        }
        let agent = w[SHARED_KEPT_ID];
        let status = w[SHARED_KEPT_STATUS];
        let Err(e) = layout::status_error(status)? else {
            return Err(SimError::GpuWords {
                word: status,
                what: "refusal",
            });
        };
        Err(SimError::controller(
            "bee step",
            w[SHARED_KEPT_STEP],
            agent,
            e,
        ))
    }

    /// Every bee's frame time at step `step` as words of the bees' scalar (in parallel): the
    /// CPU's `S::from_f64(bee_frame_time(..))`.
    fn times(&mut self, step: u32) {
        fn fill(
            out: &mut [u32],
            offsets: &[f64],
            dts: &[f64],
            step: u32,
            word: impl Fn(f64) -> u32 + Sync,
        ) {
            out.par_iter_mut()
                .zip(offsets.par_iter().zip(dts.par_iter()))
                .with_min_len(4096)
                .for_each(|(w, (&o, &dt))| *w = word(frame_time(o, step, dt)));
        }
        let (out, o, dt) = (&mut self.times, &self.offsets, &self.dts);
        match self.scalar {
            ScalarKind::I16F16 => fill(out, o, dt, step, fx_word),
            ScalarKind::F32 => fill(out, o, dt, step, |t| {
                <f32 as SimScalar>::from_f64(t).to_word()
            }),
        }
    }

    /// Every bee's frame sensed on the GPU this tick, as words (`FRAME_WORDS` a bee).
    fn frames(&self) -> Result<Vec<u32>> {
        use binding::*;
        let out = storage(&self.gpu, "bee frames", &vec![0u32; self.n * FRAME_WORDS]);
        let group = self.k.frames.bind_at(
            &self.gpu,
            &[
                (SENSE_PARAMS, &self.b.sense_params),
                (WORLD, &self.b.world),
                (SENSED, &self.b.sensed),
                (INPUTS, &self.b.inputs),
                (STARTS, self.grid.starts()),
                (ORDER, self.grid.order()),
                (OUT, &out),
            ],
        );
        let mut enc = self.gpu.device.create_command_encoder(&Default::default());
        {
            let mut pass = enc.begin_compute_pass(&Default::default());
            self.k.frames.dispatch(&mut pass, &group, self.n as u32);
        }
        self.gpu.queue.submit([enc.finish()]);
        read_back(&self.gpu, "bee frames", &out, self.n * FRAME_WORDS)
    }
}

impl Kernels {
    fn new(gpu: &Gpu, scalar: ScalarKind) -> Result<Kernels> {
        let m = modules(match scalar {
            ScalarKind::I16F16 => &SCALAR_FX,
            ScalarKind::F32 => &SCALAR_F32,
        });
        let kernel = |name, entry| Kernel::new(gpu, name, &m, SENSE_KERNEL, entry);
        Ok(Kernels {
            cells: kernel("bee_sense_cells", "bee_sense_cells_main")?,
            step: kernel("bee_tick_step", "bee_tick_step_main")?,
            commit: kernel("bee_tick_commit", "bee_tick_commit_main")?,
            frames: kernel("bee_sense_frames", "bee_sense_frames_main")?,
        })
    }

    /// The tick kernels' bind groups over `b` and `grid`.
    fn bind(&self, gpu: &Gpu, b: &Buffers, grid: &GpuGrid) -> Bound {
        use binding::*;
        let cells = self.cells.bind_at(
            gpu,
            &[
                (SENSE_PARAMS, &b.sense_params),
                (WORLD, &b.world),
                (SENSED, &b.sensed),
                (OUT, &b.cells),
            ],
        );
        let step = self.step.bind_at(
            gpu,
            &[
                (SENSE_PARAMS, &b.sense_params),
                (WORLD, &b.world),
                (SENSED, &b.sensed),
                (INPUTS, &b.inputs),
                (STARTS, grid.starts()),
                (ORDER, grid.order()),
                (STATES, &b.states),
                (DECISIONS, &b.decisions),
                (NEXT, &b.next),
                (STATUS, &b.status),
                (PARAMS, &b.params),
                (GROUP, &b.group),
                (SHARED, &b.shared),
            ],
        );
        let commit = self.commit.bind_at(
            gpu,
            &[
                (SENSE_PARAMS, &b.sense_params),
                (WORLD, &b.world),
                (TICK, &b.tick),
                (STATES, &b.states),
                (NEXT, &b.next),
                (STATUS, &b.status),
                (SHARED, &b.shared),
                (BOXES, &b.boxes),
                (SENSED_OUT, &b.sensed),
                (CORRECTED, &b.corrected),
            ],
        );
        Bound {
            cells,
            step,
            commit,
        }
    }
}

impl Engine for GpuBeeSim {
    fn model(&self) -> &'static str {
        self.sim.model()
    }
    fn agents(&self) -> usize {
        self.n
    }
    fn next_step(&self) -> u32 {
        self.sim.step
    }
    fn apply(&mut self, object: u16, action: &Action) {
        if let Err(e) = self.pull() {
            self.failed.get_or_insert(e);
            return;
        }
        self.sim.apply(object, action);
        self.push_world();
        self.push_states();
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
    fn decide(&mut self, _phase: usize) -> Result<()> {
        if let Some(e) = self.failed.take() {
            return Err(e);
        }
        let n = self.n as u32;
        let step = self.sim.step;
        self.times(step);
        let q = &self.gpu.queue;
        q.write_buffer(
            &self.b.inputs,
            (INPUT_T * self.n * 4) as u64,
            bytemuck::cast_slice(&self.times),
        );
        q.write_buffer(&self.b.tick, 0, bytemuck::cast_slice(&[step]));
        let mut enc = self.gpu.device.create_command_encoder(&Default::default());
        enc.clear_buffer(&self.b.shared, 0, Some(SHARED_PER_TICK));
        {
            let mut pass = enc.begin_compute_pass(&Default::default());
            self.k.cells.dispatch(&mut pass, &self.bound.cells, n);
        }
        self.grid.record(&self.gpu, &mut enc, &self.b.cells, n)?;
        {
            let mut pass = enc.begin_compute_pass(&Default::default());
            self.k.step.dispatch(&mut pass, &self.bound.step, n);
        }
        self.gpu.queue.submit([enc.finish()]);
        Ok(())
    }
    fn publish(&mut self, _phase: usize) -> Result<()> {
        let mut enc = self.gpu.device.create_command_encoder(&Default::default());
        {
            let mut pass = enc.begin_compute_pass(&Default::default());
            // At least one thread: thread 0 keeps the tick's refusal.
            self.k
                .commit
                .dispatch(&mut pass, &self.bound.commit, (self.n as u32).max(1));
        }
        self.gpu.queue.submit([enc.finish()]);
        self.sim.step += 1;
        self.unchecked += 1;
        if self.unchecked >= CHECK_EVERY {
            self.check()?;
        }
        Ok(())
    }
    fn sync(&mut self) -> Result<()> {
        self.pull()
    }
    fn exchanges(&self, _phase: usize, agents: &[u32]) -> Result<Vec<Exchange>> {
        let frames = self.frames()?;
        let n = self.n;
        let read = |label, b: &wgpu::Buffer, words| read_back::<u32>(&self.gpu, label, b, words);
        let states = read("bee states", &self.b.states, n * STATE_WORDS)?;
        let decisions = read("bee decisions", &self.b.decisions, n * DECISION_WORDS)?;
        let next = read("bee next states", &self.b.next, n * STATE_WORDS)?;
        let seen = Seen {
            frames: &frames,
            states: &states,
            decisions: &decisions,
            next: &next,
        };
        let sim = &self.sim;
        exchanges_by_slot(&sim.world.sensed.id, agents, |slot| {
            let (g, k) = group_of(&sim.groups, slot)?;
            Some(by_scalar!(g, g => seen.exchange(g.ids[k], g, slot)))
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
        // The corrections were counted on the GPU and read at the last sync.
        self.sim.closing(summary)
    }
}

/// The words read back for the exchanges of a step.
struct Seen<'a> {
    frames: &'a [u32],
    states: &'a [u32],
    decisions: &'a [u32],
    next: &'a [u32],
}

impl Seen<'_> {
    /// The exchange of bee `id` in slot `slot` (of group `_g`, whose scalar it is in).
    fn exchange<S: Word + SimScalar>(
        &self,
        id: u32,
        _g: &BeeGroup<S>,
        slot: usize,
    ) -> Result<Exchange> {
        let at = |w: &[u32], words: usize| w[slot * words..(slot + 1) * words].to_vec();
        let request = BeeStepRequest {
            state: layout::read_state::<S>(&at(self.states, STATE_WORDS))?,
            frame: layout::read_frame::<S>(&at(self.frames, FRAME_WORDS))?,
        };
        let reply = BeeStepReply {
            decision: layout::read_decision::<S>(&at(self.decisions, DECISION_WORDS))?,
            state: layout::read_state::<S>(&at(self.next, STATE_WORDS))?,
        };
        Exchange::of::<BeeParams<S>, Step>(id, &request, &reply)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bees::bee_frame_time;

    /// The offsets drawn once and the per-tick expression give `bee_frame_time`'s bits, and so
    /// the CPU engine's times, over seeds, ids, steps past the wrap and the presets' time steps.
    #[test]
    fn frame_times_are_the_cpus() {
        let mut checked = 0u64;
        for seed in [0u32, 1, 11, 14, 15, 0xdead_beef] {
            for id in (0..2000u32).chain([65_535, 1 << 20, u32::MAX - 1]) {
                let offset = clock_offset(seed, id);
                for dt in [0.05f64, Fx::from_f32(0.05).to_f64(), 0.01, 0.1] {
                    for step in (0..40u32)
                        .chain([1439, 20_000, 319_999, 320_000, 320_001, 4_000_000])
                        .chain([u32::MAX - 1])
                    {
                        let (a, b) = (
                            frame_time(offset, step, dt),
                            bee_frame_time(seed, id, step, dt),
                        );
                        assert_eq!(a.to_bits(), b.to_bits(), "seed {seed} id {id} step {step}");
                        assert_eq!(fx_word(a), Fx::from_f64(b).to_word(), "{b}");
                        checked += 1;
                    }
                }
            }
        }
        assert!(checked > 1_000_000);
    }

    /// `fx_word` is `Fx::from_f64`: on the grid, between its points, at and next to every tie,
    /// past the range, at infinities and NaN.
    #[test]
    fn fx_words_are_from_f64() {
        let ulp = 1.0 / 65536.0;
        let mut xs = vec![
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            1e300,
            -1e300,
            0.0,
            -0.0,
        ];
        for k in (-70_000i64..70_000).chain([i64::from(i32::MAX) - 1, i64::from(i32::MIN)]) {
            let x = k as f64 * ulp;
            for d in [0.0, ulp / 2.0, -ulp / 2.0, ulp / 3.0, 0.49 * ulp] {
                let v = x + d;
                xs.extend([v, v.next_up(), v.next_down()]);
            }
        }
        for k in 0..200_000u32 {
            xs.push(f64::from(k) * 0.0817 + 0.5 * ulp);
            xs.push(16_000.0 - f64::from(k) * 1e-3);
        }
        for x in xs {
            assert_eq!(fx_word(x), Fx::from_f64(x).to_word(), "{x:e}");
        }
    }
}
