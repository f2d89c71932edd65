//! The wang2014 simulation on the GPU: an [`Engine`] whose phases run on wgpu
//! (`shaders/wang_tick.wgsl`), the insects' states staying on the GPU between ticks.
//!
//! [`GpuWangSim`] keeps the CPU simulation ([`WangSim`]) as its host view: the world, its
//! obstacles, goals and solved cost fields, the groups' parameters and ids, what the outputs,
//! the measures and the mirror read. The fast-marching solves stay on the host (they run when
//! an event moved a goal or an obstacle, a few times a run); their fields go to the GPU as
//! storage words ([`layout::field_words`]) and are sampled there exactly as
//! [`CostField::guide_at`](crate::fields::CostField::guide_at) samples them. A tick is the
//! advect kernel (frame, step, the world's corrections of x*, its cell), the GPU grid of the
//! x*, the separate kernel (minimum distance enforcement) and the commit kernel (the world's
//! corrections, counted with atomics).
//!
//! In fixed point every word is the CPU engine's: the kernels are `swarm-core`'s controller
//! and the CPU's sensing and confinement function by function, the neighbours are selected by
//! exact keys, and slots are never reordered (results do not depend on slots). The host reads
//! back when it needs to look: [`Engine::sync`], every tick for the paper's measures
//! ([`Engine::after_tick`], which `swarm run` calls and `swarm bench` does not), the
//! exchanges of the mirror (whose requests the host's sensing recomputes from the GPU's
//! states, the replies being the GPU's), and a check for refusals every [`CHECK_EVERY`] ticks.

use swarm_core::{Fx, Scalar, ScalarKind};
use wgpu::util::DeviceExt;

use super::layout::{self, GroupInputs, NO_FIELD, STATE_WORDS};
use crate::bees::BeeWorld;
use crate::by_scalar;
use crate::engine::{Device, Engine, Exchange};
use crate::error::{Result, SimError};
use crate::gpu::Gpu;
use crate::gpu::bee::world::{GridShape3, world_words};
use crate::gpu::grid::GpuGrid;
use crate::gpu::kernel::{Kernel, read_back, storage};
use crate::gpu::shaders::{DISPATCH, Module, SCALAR_F32, SCALAR_FX, WANG_TICK};
use crate::gpu::space::confine_boxes;
use crate::gpu::words::Word;
use crate::output::{Frame, Summary};
use crate::scalar::{AgentGroup, SimScalar, a3};
use crate::scenario::Action;
use crate::space::SURFACE_OFFSET;
use crate::wang::{Counts, WangGroup, WangSim, WangWorld};

/// Ticks between two checks for a controller's refusal (a read-back of a few words): a refusal
/// is reported with its own step, at most this many ticks later.
pub const CHECK_EVERY: u32 = 64;

/// Words of the tick's atomics (`WANG_SHARED_*` in `wang_tick.wgsl`).
const SHARED_WORDS: usize = 16;
/// The words a tick starts with cleared: its refusals, corrections and pushes.
const SHARED_PER_TICK: u64 = 5 * 4;
const SHARED_OBSTACLE: usize = 2;
const SHARED_BOUNDS: usize = 3;
const SHARED_PUSHED: usize = 4;
const SHARED_KEPT: usize = 5;
const SHARED_KEPT_STEP: usize = 6;
const SHARED_KEPT_ID: usize = 7;
const SHARED_KEPT_PHASE: usize = 8;
const SHARED_KEPT_STATUS: usize = 9;
const SHARED_TOTAL_OBSTACLE: usize = 10;
const SHARED_TOTAL_BOUNDS: usize = 12;
const SHARED_TOTAL_PUSHED: usize = 14;

/// The phases' names in a refusal (as the CPU engine reports them).
const PHASE_NAMES: [&str; 2] = ["wang advect", "wang separate"];

/// Binding numbers of `wang_tick.wgsl` (and of the modules it uses).
mod binding {
    pub const WORLD: u32 = 1;
    pub const STARTS: u32 = 4;
    pub const ORDER: u32 = 5;
    pub const CELLS: u32 = 6;
    pub const TICK: u32 = 7;
    pub const STATES: u32 = 8;
    pub const MOVED: u32 = 9;
    pub const PLACED: u32 = 10;
    pub const NEXT: u32 = 11;
    pub const GROUPS: u32 = 12;
    pub const SLOTS: u32 = 13;
    pub const SHARED: u32 = 14;
    pub const BOXES: u32 = 15;
    pub const FIELDS: u32 = 16;
    pub const FLAGS: u32 = 17;
    pub const STATUS: u32 = 18;
}

/// The GPU's buffers of one simulation.
struct Buffers {
    tick: wgpu::Buffer,
    world: wgpu::Buffer,
    boxes: wgpu::Buffer,
    cells: wgpu::Buffer,
    states: wgpu::Buffer,
    moved: wgpu::Buffer,
    placed: wgpu::Buffer,
    next: wgpu::Buffer,
    groups: wgpu::Buffer,
    slots: wgpu::Buffer,
    shared: wgpu::Buffer,
    fields: wgpu::Buffer,
    flags: wgpu::Buffer,
    status: wgpu::Buffer,
}

/// The compiled kernels of the tick.
struct Kernels {
    advect: Kernel,
    separate: Kernel,
    commit: Kernel,
}

/// Their bind groups (made again when the fields' buffer grows).
struct Bound {
    advect: wgpu::BindGroup,
    separate: wgpu::BindGroup,
    commit: wgpu::BindGroup,
}

/// The world's obstacles and bounds in the layout of the bee world's words
/// (`bee_world.wgsl`, whose obstacle geometry the 3D models share), with the MDE distance as
/// the neighbour range.
fn space_world(w: &WangWorld) -> BeeWorld {
    let mut b = BeeWorld::new(w.min, w.max, w.d_min, w.d0);
    b.obstacles.clone_from(&w.obstacles);
    b
}

/// The words the host computes in the insects' scalar: the world, the confinement boxes, the
/// groups.
struct HostWords {
    world: Vec<u32>,
    boxes: Vec<u32>,
    groups: Vec<u32>,
}

/// [`HostWords`] of `sim` over `S`, with the MDE grid `shape` and the fields at `fields_at`.
fn host_words<S: Word + SimScalar>(
    sim: &WangSim,
    shape: &GridShape3,
    fields_at: &[(u16, u32)],
) -> HostWords {
    let w = &sim.world;
    let mut groups = Vec::new();
    for g in &sim.groups {
        by_scalar!(g, g => write_group_words(&mut groups, g, w, fields_at));
    }
    HostWords {
        world: world_words::<S>(&space_world(w), shape),
        boxes: confine_boxes::<S>(&w.obstacles),
        groups,
    }
}

/// Appends the words of group `g` in world `w` (its field found in `fields_at`).
fn write_group_words<S: Word + SimScalar>(
    out: &mut Vec<u32>,
    g: &WangGroup<S>,
    w: &WangWorld,
    fields_at: &[(u16, u32)],
) {
    let field = fields_at
        .iter()
        .find(|(goal, _)| *goal == g.goal)
        .map_or(NO_FIELD, |&(_, at)| at);
    let inputs = GroupInputs {
        field,
        lamp: g.lamp(w),
    };
    layout::write_group(out, &g.params, inputs);
}

/// What the GPU decided, read back.
struct Seen {
    states: Vec<u32>,
    moved: Vec<u32>,
    placed: Vec<u32>,
    next: Vec<u32>,
    flags: Vec<u32>,
}

impl Seen {
    /// Writes the words into the host view `sim` (states, replies, corrections, pushes, the
    /// broadcast x*); the MDE grid is rebuilt when `grid`.
    fn fill(&self, sim: &mut WangSim, grid: bool) {
        for g in &mut sim.groups {
            by_scalar!(g, g => self.fill_group(g, &mut sim.world));
        }
        if grid {
            let w = &mut sim.world;
            w.mde_grid
                .rebuild(&w.moved, |p| [p[0] as f32, p[1] as f32, p[2] as f32]);
        }
    }

    fn fill_group<S: Word + SimScalar>(&self, g: &mut WangGroup<S>, w: &mut WangWorld) {
        let at = |words: &[u32], slot: usize| {
            layout::read_state::<S>(&words[slot * STATE_WORDS..(slot + 1) * STATE_WORDS])
        };
        for k in 0..g.states.len() {
            let slot = g.first + k;
            g.states[k] = at(&self.states, slot);
            g.moved[k] = at(&self.moved, slot);
            g.placed[k] = at(&self.placed, slot);
            g.next[k] = at(&self.next, slot);
            g.corrected[k] = (self.flags[slot] & 3) as u8;
            g.pushes[k] = (self.flags[slot] >> 8) as u8;
            w.moved[slot] = a3(g.placed[k].pos);
            w.id[slot] = g.ids[k];
        }
    }
}

/// A wang2014 simulation whose steps run on the GPU (see the module's documentation).
pub struct GpuWangSim {
    sim: WangSim,
    gpu: Gpu,
    n: usize,
    scalar: ScalarKind,
    shape: GridShape3,
    b: Buffers,
    k: Kernels,
    bound: Bound,
    grid: GpuGrid,
    /// The fields' buffer's size in words (it grows when a goal becomes present).
    fields_cap: usize,
    /// Ticks since the last check for refusals.
    unchecked: u32,
    /// A failure to report at the next fallible call (from [`Engine::apply`] and
    /// [`Engine::after_tick`], which cannot).
    failed: Option<SimError>,
}

/// The scalar of a group.
fn scalar_of<S: Scalar>(_: &WangGroup<S>) -> ScalarKind {
    S::KIND
}

impl GpuWangSim {
    /// The simulation `sim` on the GPU `gpu`, from its current state.
    ///
    /// # Errors
    ///
    /// [`SimError::GpuMixedScalars`] if its groups do not all run one scalar type,
    /// [`SimError::NoAgents`] without insects, and what compiling the kernels and sizing the
    /// grid refuse.
    pub fn new(sim: WangSim, gpu: Gpu) -> Result<GpuWangSim> {
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
        if n == 0 {
            return Err(SimError::NoAgents);
        }
        let shape = GridShape3::of(&space_world(&sim.world), n);
        let (fields, fields_at) = layout::field_words(&sim.world.fields);
        let words = match scalar {
            ScalarKind::I16F16 => host_words::<Fx>(&sim, &shape, &fields_at),
            ScalarKind::F32 => host_words::<f32>(&sim, &shape, &fields_at),
        };
        let mut slots = vec![0u32; 2 * n];
        for (k, g) in sim.groups.iter().enumerate() {
            let r = g.first()..g.first() + g.len();
            slots[r.clone()].fill(k as u32);
            by_scalar!(g, g => slots[n + r.start..n + r.end].copy_from_slice(&g.ids));
        }
        let offset = match scalar {
            ScalarKind::I16F16 => Fx::from_f32(SURFACE_OFFSET).to_word(),
            ScalarKind::F32 => SURFACE_OFFSET.to_word(),
        };
        let tick = [n as u32, sim.step, sim.seed, offset];
        let states = vec![0u32; n * STATE_WORDS];
        let b = Buffers {
            tick: gpu
                .device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("wang tick params"),
                    contents: bytemuck::cast_slice(&tick),
                    usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                }),
            world: storage(&gpu, "wang world", &words.world),
            boxes: storage(&gpu, "wang confinement boxes", &words.boxes),
            cells: storage(&gpu, "wang cells", &vec![0u32; n]),
            states: storage(&gpu, "wang states", &states),
            moved: storage(&gpu, "wang advect replies", &states),
            placed: storage(&gpu, "wang placed", &states),
            next: storage(&gpu, "wang separate replies", &states),
            groups: storage(&gpu, "wang groups", &words.groups),
            slots: storage(&gpu, "wang slots", &slots),
            shared: storage(&gpu, "wang tick atomics", &[0u32; SHARED_WORDS]),
            fields: storage(&gpu, "wang fields", &fields),
            flags: storage(&gpu, "wang flags", &vec![0u32; n]),
            status: storage(&gpu, "wang status", &vec![0u32; 2 * n]),
        };
        let grid = GpuGrid::new(&gpu, n as u32, shape.cells())?;
        let k = Kernels::new(&gpu, scalar)?;
        let bound = k.bind(&gpu, &b, &grid);
        let mut out = GpuWangSim {
            fields_cap: fields.len().max(1),
            sim,
            gpu,
            n,
            scalar,
            shape,
            b,
            k,
            bound,
            grid,
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

    /// The host view (after [`Engine::sync`]: the current states, replies, corrections and
    /// counts).
    pub fn sim(&self) -> &WangSim {
        &self.sim
    }

    /// Uploads the host's states and the step's counts.
    fn push_states(&mut self) {
        let mut states = Vec::with_capacity(self.n * STATE_WORDS);
        for g in &self.sim.groups {
            by_scalar!(g, g => g.states.iter().for_each(|s| layout::write_state(&mut states, s)));
        }
        let (last, total) = (self.sim.last, self.sim.total);
        let mut shared = [0u32; SHARED_WORDS];
        shared[SHARED_OBSTACLE] = last.obstacle as u32;
        shared[SHARED_BOUNDS] = last.bounds as u32;
        shared[SHARED_PUSHED] = last.pushed as u32;
        for (at, v) in [
            (SHARED_TOTAL_OBSTACLE, total.obstacle),
            (SHARED_TOTAL_BOUNDS, total.bounds),
            (SHARED_TOTAL_PUSHED, total.pushed),
        ] {
            shared[at] = v as u32;
            shared[at + 1] = (v >> 32) as u32;
        }
        let q = &self.gpu.queue;
        q.write_buffer(&self.b.states, 0, bytemuck::cast_slice(&states));
        q.write_buffer(&self.b.shared, 0, bytemuck::cast_slice(&shared));
    }

    /// Uploads the host's world (obstacles moved, started, stopped; goals moved, started,
    /// stopped, and so the groups' fields and lamps), solving the fields first if an event
    /// changed the world.
    fn push_world(&mut self) -> Result<()> {
        self.sim.world.solve_if_dirty()?;
        let (fields, fields_at) = layout::field_words(&self.sim.world.fields);
        let words = match self.scalar {
            ScalarKind::I16F16 => host_words::<Fx>(&self.sim, &self.shape, &fields_at),
            ScalarKind::F32 => host_words::<f32>(&self.sim, &self.shape, &fields_at),
        };
        let q = &self.gpu.queue;
        q.write_buffer(&self.b.world, 0, bytemuck::cast_slice(&words.world));
        q.write_buffer(&self.b.groups, 0, bytemuck::cast_slice(&words.groups));
        if !words.boxes.is_empty() {
            q.write_buffer(&self.b.boxes, 0, bytemuck::cast_slice(&words.boxes));
        }
        if fields.len() > self.fields_cap {
            // A goal became present: a larger buffer, bound again.
            self.b.fields = storage(&self.gpu, "wang fields", &fields);
            self.fields_cap = fields.len();
            self.bound = self.k.bind(&self.gpu, &self.b, &self.grid);
        } else if !fields.is_empty() {
            q.write_buffer(&self.b.fields, 0, bytemuck::cast_slice(&fields));
        }
        Ok(())
    }

    /// Reads back what the GPU decided.
    fn seen(&self) -> Result<Seen> {
        let words = self.n * STATE_WORDS;
        let read = |label, b: &wgpu::Buffer, words| read_back::<u32>(&self.gpu, label, b, words);
        Ok(Seen {
            states: read("wang states", &self.b.states, words)?,
            moved: read("wang advect replies", &self.b.moved, words)?,
            placed: read("wang placed", &self.b.placed, words)?,
            next: read("wang separate replies", &self.b.next, words)?,
            flags: read("wang flags", &self.b.flags, self.n)?,
        })
    }

    /// Reads the states, replies, corrections and counts back into the host view.
    fn pull(&mut self) -> Result<()> {
        self.check()?;
        let seen = self.seen()?;
        seen.fill(&mut self.sim, false);
        let w: Vec<u32> = read_back(&self.gpu, "wang tick atomics", &self.b.shared, SHARED_WORDS)?;
        let u64_at = |at: usize| u64::from(w[at]) | u64::from(w[at + 1]) << 32;
        self.sim.last = Counts {
            obstacle: u64::from(w[SHARED_OBSTACLE]),
            bounds: u64::from(w[SHARED_BOUNDS]),
            pushed: u64::from(w[SHARED_PUSHED]),
        };
        self.sim.total = Counts {
            obstacle: u64_at(SHARED_TOTAL_OBSTACLE),
            bounds: u64_at(SHARED_TOTAL_BOUNDS),
            pushed: u64_at(SHARED_TOTAL_PUSHED),
        };
        Ok(())
    }

    /// The first refusal of a controller since the start, as the CPU engine reports it.
    fn check(&mut self) -> Result<()> {
        if let Some(e) = self.failed.take() {
            return Err(e);
        }
        self.unchecked = 0;
        let w: Vec<u32> = read_back(&self.gpu, "wang tick atomics", &self.b.shared, SHARED_WORDS)?;
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
        let phase = PHASE_NAMES[(w[SHARED_KEPT_PHASE] as usize).min(1)];
        Err(SimError::controller(phase, w[SHARED_KEPT_STEP], agent, e))
    }

    /// Records one kernel over every insect (at least one thread: thread 0 of the commit keeps
    /// the tick's refusal) and submits it, after the grid of the x* when `grid`.
    fn run(&mut self, phase: Phase) -> Result<()> {
        let n = self.n as u32;
        let mut enc = self.gpu.device.create_command_encoder(&Default::default());
        if matches!(phase, Phase::Advect) {
            enc.clear_buffer(&self.b.shared, 0, Some(SHARED_PER_TICK));
        }
        if matches!(phase, Phase::Separate) {
            self.grid.record(&self.gpu, &mut enc, &self.b.cells, n)?;
        }
        {
            let (kernel, group) = match phase {
                Phase::Advect => (&self.k.advect, &self.bound.advect),
                Phase::Separate => (&self.k.separate, &self.bound.separate),
                Phase::Commit => (&self.k.commit, &self.bound.commit),
            };
            let mut pass = enc.begin_compute_pass(&Default::default());
            kernel.dispatch(&mut pass, group, n.max(1));
        }
        self.gpu.queue.submit([enc.finish()]);
        Ok(())
    }
}

/// The kernels of a tick, in order.
#[derive(Clone, Copy, Debug)]
enum Phase {
    Advect,
    Separate,
    Commit,
}

impl Kernels {
    fn new(gpu: &Gpu, scalar: ScalarKind) -> Result<Kernels> {
        let m = modules(match scalar {
            ScalarKind::I16F16 => &SCALAR_FX,
            ScalarKind::F32 => &SCALAR_F32,
        });
        let kernel = |name, entry| Kernel::new(gpu, name, &m, "", entry);
        Ok(Kernels {
            advect: kernel("wang_tick_advect", "wang_tick_advect_main")?,
            separate: kernel("wang_tick_separate", "wang_tick_separate_main")?,
            commit: kernel("wang_tick_commit", "wang_tick_commit_main")?,
        })
    }

    /// The kernels' bind groups over `b` and `grid` (each takes the bindings it uses).
    fn bind(&self, gpu: &Gpu, b: &Buffers, grid: &GpuGrid) -> Bound {
        use binding::*;
        let all = [
            (WORLD, &b.world),
            (STARTS, grid.starts()),
            (ORDER, grid.order()),
            (CELLS, &b.cells),
            (TICK, &b.tick),
            (STATES, &b.states),
            (MOVED, &b.moved),
            (PLACED, &b.placed),
            (NEXT, &b.next),
            (GROUPS, &b.groups),
            (SLOTS, &b.slots),
            (SHARED, &b.shared),
            (BOXES, &b.boxes),
            (FIELDS, &b.fields),
            (FLAGS, &b.flags),
            (STATUS, &b.status),
        ];
        Bound {
            advect: self.advect.bind_at(gpu, &all),
            separate: self.separate.bind_at(gpu, &all),
            commit: self.commit.bind_at(gpu, &all),
        }
    }
}

/// The modules of the tick's kernels over `scalar`.
pub fn modules(scalar: &'static Module) -> [&'static Module; 3] {
    [&DISPATCH, scalar, &WANG_TICK]
}

impl Engine for GpuWangSim {
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
        Engine::apply(&mut self.sim, object, action);
        if let Err(e) = self.push_world() {
            self.failed.get_or_insert(e);
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
    fn notes(&mut self) -> Vec<String> {
        self.sim.notes()
    }
    fn decide(&mut self, phase: usize) -> Result<()> {
        if let Some(e) = self.failed.take() {
            return Err(e);
        }
        if phase == 0 {
            if self.sim.world.dirty {
                self.push_world()?;
            }
            let q = &self.gpu.queue;
            q.write_buffer(&self.b.tick, 4, bytemuck::cast_slice(&[self.sim.step]));
            self.run(Phase::Advect)
        } else {
            self.run(Phase::Separate)
        }
    }
    fn publish(&mut self, phase: usize) -> Result<()> {
        if phase == 0 {
            return Ok(());
        }
        self.run(Phase::Commit)?;
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
    fn exchanges(&self, phase: usize, agents: &[u32]) -> Result<Vec<Exchange>> {
        // The requests as the host senses them from the GPU's states (the same words in fixed
        // point), the replies as the GPU gave them.
        let mut view = self.sim.clone();
        self.seen()?.fill(&mut view, phase == 1);
        view.exchanges(phase, agents)
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
    fn after_tick(&mut self, summary: &mut Summary) {
        // The measures need every insect's state of every step.
        match self.pull() {
            Ok(()) => self.sim.after_tick(summary),
            Err(e) => {
                self.failed.get_or_insert(e);
            }
        }
    }
    fn on_record(&self, summary: &mut Summary, step: u32) {
        self.sim.on_record(summary, step);
    }
    fn closing(&self, summary: &mut Summary) -> String {
        self.sim.closing(summary)
    }
}
