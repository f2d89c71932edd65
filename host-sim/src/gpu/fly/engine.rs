//! The ren2016 simulation on the GPU: an [`Engine`] whose step runs on wgpu
//! (`shaders/fly_tick.wgsl`), the insects' states staying on the GPU between ticks.
//!
//! [`GpuFlySim`] keeps the CPU simulation ([`FlySim`]) as its host view: the container, its
//! obstacles and stimulus sources, the groups' parameters and ids, what the outputs, the
//! measures and the mirror read. A tick is the cells kernel, the GPU grid's sort, the step
//! kernel (the frame of `fly/sense.rs`, then `swarm_core::fly::step_checked` with its 3D ORCA)
//! and the commit kernel (the world's corrections, counted with atomics).
//!
//! In fixed point every word is the CPU engine's: the kernels are `swarm-core`'s controller and
//! the CPU's sensing and confinement function by function, the neighbours are selected by exact
//! keys, and slots are never reordered (results do not depend on slots). The host reads back
//! when it needs to look: [`Engine::sync`], every tick for the polarisation
//! ([`Engine::after_tick`], which `swarm run` calls and `swarm bench` does not), the exchanges
//! of the mirror (whose requests the host's sensing recomputes from the GPU's states, the
//! replies being the GPU's), and a check for refusals every [`CHECK_EVERY`] ticks.

use swarm_core::{Fx, Scalar, ScalarKind};
use wgpu::util::DeviceExt;

use super::layout::{self, DECISION_WORDS, FLAG_TRUNCATED, STATE_WORDS};
use crate::bees::{BeeTarget, BeeWorld};
use crate::by_scalar;
use crate::engine::{Device, Engine, Exchange};
use crate::error::{Result, SimError};
use crate::fly::{Counts, FlyGroup, FlySim};
use crate::gpu::Gpu;
use crate::gpu::bee::world::{GridShape3, world_words};
use crate::gpu::grid::GpuGrid;
use crate::gpu::kernel::{Kernel, read_back, storage};
use crate::gpu::shaders::{DISPATCH, FLY_TICK, Module, SCALAR_F32, SCALAR_FX};
use crate::gpu::space::confine_boxes;
pub use crate::gpu::wang::engine::CHECK_EVERY;
use crate::gpu::words::Word;
use crate::output::{Frame, Summary};
use crate::scalar::{AgentGroup, SimScalar};
use crate::scenario::Action;
use crate::space::SURFACE_OFFSET;
use crate::swarm3d::World3d;

/// Words of the tick's atomics (`FLY_SHARED_*` in `fly_tick.wgsl`).
const SHARED_WORDS: usize = 18;
/// The bytes a tick starts with cleared: its refusal, infeasible programs, truncated frames and
/// corrections.
const SHARED_PER_TICK: u64 = 5 * 4;
const SHARED_INFEASIBLE: usize = 1;
const SHARED_TRUNCATED: usize = 2;
const SHARED_OBSTACLE: usize = 3;
const SHARED_BOUNDS: usize = 4;
const SHARED_KEPT: usize = 5;
const SHARED_KEPT_STEP: usize = 6;
const SHARED_KEPT_SLOT: usize = 7;
const SHARED_KEPT_STATUS: usize = 8;
const SHARED_TOTAL_INFEASIBLE: usize = 10;
const SHARED_TOTAL_TRUNCATED: usize = 12;
const SHARED_TOTAL_OBSTACLE: usize = 14;
const SHARED_TOTAL_BOUNDS: usize = 16;

/// The engine's constants of `fly_tick.wgsl` (checked by a test).
pub const WGSL_SHARED: &[(&str, u32)] = &[
    ("FLY_SHARED_INFEASIBLE", SHARED_INFEASIBLE as u32),
    ("FLY_SHARED_TRUNCATED", SHARED_TRUNCATED as u32),
    ("FLY_SHARED_OBSTACLE", SHARED_OBSTACLE as u32),
    ("FLY_SHARED_BOUNDS", SHARED_BOUNDS as u32),
    ("FLY_SHARED_KEPT", SHARED_KEPT as u32),
    ("FLY_SHARED_KEPT_STEP", SHARED_KEPT_STEP as u32),
    ("FLY_SHARED_KEPT_SLOT", SHARED_KEPT_SLOT as u32),
    ("FLY_SHARED_KEPT_STATUS", SHARED_KEPT_STATUS as u32),
    (
        "FLY_SHARED_TOTAL_INFEASIBLE",
        SHARED_TOTAL_INFEASIBLE as u32,
    ),
    ("FLY_SHARED_TOTAL_TRUNCATED", SHARED_TOTAL_TRUNCATED as u32),
    ("FLY_SHARED_TOTAL_OBSTACLE", SHARED_TOTAL_OBSTACLE as u32),
    ("FLY_SHARED_TOTAL_BOUNDS", SHARED_TOTAL_BOUNDS as u32),
];

/// Binding numbers of `fly_tick.wgsl` (and of the modules it uses).
mod binding {
    pub const WORLD: u32 = 1;
    pub const STARTS: u32 = 4;
    pub const ORDER: u32 = 5;
    pub const CELLS: u32 = 6;
    pub const TICK: u32 = 7;
    pub const STATES: u32 = 8;
    pub const NEXT: u32 = 9;
    pub const DECISIONS: u32 = 10;
    pub const GROUPS: u32 = 11;
    pub const SLOTS: u32 = 12;
    pub const SHARED: u32 = 13;
    pub const FLAGS: u32 = 14;
    pub const BOXES: u32 = 15;
    pub const STATUS: u32 = 16;
}

/// The GPU's buffers of one simulation.
struct Buffers {
    tick: wgpu::Buffer,
    world: wgpu::Buffer,
    boxes: wgpu::Buffer,
    cells: wgpu::Buffer,
    states: wgpu::Buffer,
    next: wgpu::Buffer,
    decisions: wgpu::Buffer,
    groups: wgpu::Buffer,
    slots: wgpu::Buffer,
    shared: wgpu::Buffer,
    flags: wgpu::Buffer,
    status: wgpu::Buffer,
}

/// The compiled kernels of the tick and their bind groups.
struct Kernels {
    cells: Kernel,
    step: Kernel,
    commit: Kernel,
}

struct Bound {
    cells: wgpu::BindGroup,
    step: wgpu::BindGroup,
    commit: wgpu::BindGroup,
}

/// The container, its obstacles and the stimulus sources in the layout of the bee world's words
/// (`bee_world.wgsl`, whose obstacle geometry the 3D models share): the sources as targets
/// without particles (`bee_world_target_center` is [`World3d::source`]: the first active one of
/// the id), r_att as the neighbour range.
fn space_world(w: &World3d) -> BeeWorld {
    let mut b = BeeWorld::new(w.min, w.max, w.range, w.reach);
    b.obstacles.clone_from(&w.obstacles);
    b.targets = w
        .sources
        .iter()
        .map(|s| BeeTarget {
            active: s.active,
            ..BeeTarget::new(s.id, s.name.clone(), s.center, 0.0, 0)
        })
        .collect();
    b
}

/// The words the host computes in the insects' scalar: the world, the confinement boxes.
fn world_and_boxes<S: Word + SimScalar>(w: &World3d, shape: &GridShape3) -> (Vec<u32>, Vec<u32>) {
    (
        world_words::<S>(&space_world(w), shape),
        confine_boxes::<S>(&w.obstacles),
    )
}

/// Every group's words ([`layout::write_group`]), with the regions its goal and threat have now
/// (uploaded again with the world: `Engine::apply` shifts a region it moves).
fn group_words(sim: &FlySim) -> Vec<u32> {
    // Active or not: the world's words say whether it is present.
    let source = |id: Option<u16>| sim.world.sources.iter().find(|s| Some(s.id) == id);
    let mut out = Vec::new();
    for g in &sim.groups {
        by_scalar!(g, g => {
            let sources = [source(g.inputs.goal), source(g.inputs.threat)];
            layout::write_group(&mut out, &g.params, g.inputs, sources);
        });
    }
    out
}

/// What the GPU decided, read back.
struct Seen {
    states: Vec<u32>,
    next: Vec<u32>,
    decisions: Vec<u32>,
    flags: Vec<u32>,
}

impl Seen {
    /// Writes the words into the host view `sim`: states, next states, decisions, corrections,
    /// truncations, the sensed world.
    fn fill(&self, sim: &mut FlySim) {
        for g in &mut sim.groups {
            by_scalar!(g, g => self.fill_group(g, &mut sim.world));
        }
    }

    fn fill_group<S: Word + SimScalar>(&self, g: &mut FlyGroup<S>, w: &mut World3d) {
        let state = |words: &[u32], slot: usize| {
            layout::read_state::<S>(&words[slot * STATE_WORDS..(slot + 1) * STATE_WORDS])
        };
        for k in 0..g.states.len() {
            let slot = g.first + k;
            g.states[k] = state(&self.states, slot);
            g.next[k] = state(&self.next, slot);
            let d = &self.decisions[slot * DECISION_WORDS..(slot + 1) * DECISION_WORDS];
            g.decisions[k] = layout::read_decision(d);
            g.corrected[k] = (self.flags[slot] & 3) as u8;
            g.truncated[k] = self.flags[slot] & FLAG_TRUNCATED != 0;
        }
        w.sensed.write(g.first, &g.ids, &g.states);
    }
}

/// A ren2016 simulation whose steps run on the GPU (see the module's documentation).
pub struct GpuFlySim {
    sim: FlySim,
    gpu: Gpu,
    n: usize,
    scalar: ScalarKind,
    shape: GridShape3,
    b: Buffers,
    k: Kernels,
    bound: Bound,
    grid: GpuGrid,
    /// Ticks since the last check for refusals.
    unchecked: u32,
    /// A failure to report at the next fallible call (from [`Engine::after_tick`], which
    /// cannot).
    failed: Option<SimError>,
}

/// The scalar of a group.
fn scalar_of<S: SimScalar>(_: &FlyGroup<S>) -> ScalarKind {
    S::KIND
}

impl GpuFlySim {
    /// The simulation `sim` on the GPU `gpu`, from its current state.
    ///
    /// # Errors
    ///
    /// [`SimError::GpuMixedScalars`] if its groups do not all run one scalar type,
    /// [`SimError::NoAgents`] without insects, and what compiling the kernels and sizing the
    /// grid refuse.
    pub fn new(sim: FlySim, gpu: Gpu) -> Result<GpuFlySim> {
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
        let (world, boxes) = match scalar {
            ScalarKind::I16F16 => world_and_boxes::<Fx>(&sim.world, &shape),
            ScalarKind::F32 => world_and_boxes::<f32>(&sim.world, &shape),
        };
        let groups = group_words(&sim);
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
                    label: Some("fly tick params"),
                    contents: bytemuck::cast_slice(&tick),
                    usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                }),
            world: storage(&gpu, "fly world", &world),
            // A binding is never empty: one word where there are no obstacles.
            boxes: storage(&gpu, "fly confinement boxes", &[boxes, vec![0]].concat()),
            cells: storage(&gpu, "fly cells", &vec![0u32; n]),
            states: storage(&gpu, "fly states", &states),
            next: storage(&gpu, "fly next states", &states),
            decisions: storage(&gpu, "fly decisions", &vec![0u32; n * DECISION_WORDS]),
            groups: storage(&gpu, "fly groups", &groups),
            slots: storage(&gpu, "fly slots", &slots),
            shared: storage(&gpu, "fly tick atomics", &[0u32; SHARED_WORDS]),
            flags: storage(&gpu, "fly flags", &vec![0u32; n]),
            status: storage(&gpu, "fly status", &vec![0u32; n]),
        };
        let grid = GpuGrid::new(&gpu, n as u32, shape.cells())?;
        let k = Kernels::new(&gpu, scalar)?;
        let bound = k.bind(&gpu, &b, &grid);
        let mut out = GpuFlySim {
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

    /// The host view (after [`Engine::sync`]: the current states, decisions, corrections and
    /// counts).
    pub fn sim(&self) -> &FlySim {
        &self.sim
    }

    /// Uploads the host's states and counts.
    fn push_states(&mut self) {
        let mut states = Vec::with_capacity(self.n * STATE_WORDS);
        for g in &self.sim.groups {
            by_scalar!(g, g => g.states.iter().for_each(|s| layout::write_state(&mut states, s)));
        }
        let (last, total) = (self.sim.last, self.sim.total);
        let mut shared = [0u32; SHARED_WORDS];
        for (at, v) in [
            (SHARED_INFEASIBLE, last.infeasible),
            (SHARED_TRUNCATED, last.truncated),
            (SHARED_OBSTACLE, last.obstacle),
            (SHARED_BOUNDS, last.bounds),
        ] {
            shared[at] = v as u32;
        }
        for (at, v) in [
            (SHARED_TOTAL_INFEASIBLE, total.infeasible),
            (SHARED_TOTAL_TRUNCATED, total.truncated),
            (SHARED_TOTAL_OBSTACLE, total.obstacle),
            (SHARED_TOTAL_BOUNDS, total.bounds),
        ] {
            shared[at] = v as u32;
            shared[at + 1] = (v >> 32) as u32;
        }
        let q = &self.gpu.queue;
        q.write_buffer(&self.b.states, 0, bytemuck::cast_slice(&states));
        q.write_buffer(&self.b.shared, 0, bytemuck::cast_slice(&shared));
    }

    /// Uploads the host's world (obstacles and stimulus sources added, removed, moved).
    fn push_world(&mut self) {
        let (world, boxes) = match self.scalar {
            ScalarKind::I16F16 => world_and_boxes::<Fx>(&self.sim.world, &self.shape),
            ScalarKind::F32 => world_and_boxes::<f32>(&self.sim.world, &self.shape),
        };
        let q = &self.gpu.queue;
        q.write_buffer(&self.b.world, 0, bytemuck::cast_slice(&world));
        q.write_buffer(
            &self.b.groups,
            0,
            bytemuck::cast_slice(&group_words(&self.sim)),
        );
        if !boxes.is_empty() {
            q.write_buffer(&self.b.boxes, 0, bytemuck::cast_slice(&boxes));
        }
    }

    /// Reads back what the GPU decided.
    fn seen(&self) -> Result<Seen> {
        let words = self.n * STATE_WORDS;
        let read = |label, b: &wgpu::Buffer, words| read_back::<u32>(&self.gpu, label, b, words);
        Ok(Seen {
            states: read("fly states", &self.b.states, words)?,
            next: read("fly next states", &self.b.next, words)?,
            decisions: read("fly decisions", &self.b.decisions, self.n * DECISION_WORDS)?,
            flags: read("fly flags", &self.b.flags, self.n)?,
        })
    }

    /// Reads the states, decisions, corrections and counts back into the host view.
    fn pull(&mut self) -> Result<()> {
        self.check()?;
        self.seen()?.fill(&mut self.sim);
        let w: Vec<u32> = read_back(&self.gpu, "fly tick atomics", &self.b.shared, SHARED_WORDS)?;
        let u64_at = |at: usize| u64::from(w[at]) | u64::from(w[at + 1]) << 32;
        self.sim.last = Counts {
            infeasible: u64::from(w[SHARED_INFEASIBLE]),
            truncated: u64::from(w[SHARED_TRUNCATED]),
            obstacle: u64::from(w[SHARED_OBSTACLE]),
            bounds: u64::from(w[SHARED_BOUNDS]),
        };
        self.sim.total = Counts {
            infeasible: u64_at(SHARED_TOTAL_INFEASIBLE),
            truncated: u64_at(SHARED_TOTAL_TRUNCATED),
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
        let w: Vec<u32> = read_back(&self.gpu, "fly tick atomics", &self.b.shared, SHARED_WORDS)?;
        if w[SHARED_KEPT] == 0 {
            return Ok(());
        }
        let slot = w[SHARED_KEPT_SLOT] as usize;
        let agent = self.sim.world.sensed.id.get(slot).copied().unwrap_or(0);
        let status = w[SHARED_KEPT_STATUS];
        let Err(e) = layout::status_error(status)? else {
            return Err(SimError::GpuWords {
                word: status,
                what: "refusal",
            });
        };
        Err(SimError::controller(
            "fly step",
            w[SHARED_KEPT_STEP],
            agent,
            e,
        ))
    }

    /// Records the kernels of one phase over every insect (at least one thread: thread 0 of the
    /// commit keeps the tick's refusal) and submits them: the cells, the grid and the step
    /// (`decide`), or the commit.
    fn run(&mut self, decide: bool) -> Result<()> {
        let n = self.n as u32;
        let mut enc = self.gpu.device.create_command_encoder(&Default::default());
        if decide {
            enc.clear_buffer(&self.b.shared, 0, Some(SHARED_PER_TICK));
            {
                let mut pass = enc.begin_compute_pass(&Default::default());
                self.k
                    .cells
                    .dispatch(&mut pass, &self.bound.cells, n.max(1));
            }
            self.grid.record(&self.gpu, &mut enc, &self.b.cells, n)?;
            let mut pass = enc.begin_compute_pass(&Default::default());
            self.k.step.dispatch(&mut pass, &self.bound.step, n.max(1));
        } else {
            let mut pass = enc.begin_compute_pass(&Default::default());
            self.k
                .commit
                .dispatch(&mut pass, &self.bound.commit, n.max(1));
        }
        self.gpu.queue.submit([enc.finish()]);
        Ok(())
    }
}

impl Kernels {
    fn new(gpu: &Gpu, scalar: ScalarKind) -> Result<Kernels> {
        let m = modules(match scalar {
            ScalarKind::I16F16 => &SCALAR_FX,
            ScalarKind::F32 => &SCALAR_F32,
        });
        let kernel = |name, entry| Kernel::new(gpu, name, &m, "", entry);
        Ok(Kernels {
            cells: kernel("fly_tick_cells", "fly_tick_cells_main")?,
            step: kernel("fly_tick_step", "fly_tick_step_main")?,
            commit: kernel("fly_tick_commit", "fly_tick_commit_main")?,
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
            (NEXT, &b.next),
            (DECISIONS, &b.decisions),
            (GROUPS, &b.groups),
            (SLOTS, &b.slots),
            (SHARED, &b.shared),
            (FLAGS, &b.flags),
            (BOXES, &b.boxes),
            (STATUS, &b.status),
        ];
        Bound {
            cells: self.cells.bind_at(gpu, &all),
            step: self.step.bind_at(gpu, &all),
            commit: self.commit.bind_at(gpu, &all),
        }
    }
}

/// The modules of the tick's kernels over `scalar`.
pub fn modules(scalar: &'static Module) -> [&'static Module; 3] {
    [&DISPATCH, scalar, &FLY_TICK]
}

impl Engine for GpuFlySim {
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
        self.push_world();
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
    fn decide(&mut self, _phase: usize) -> Result<()> {
        if let Some(e) = self.failed.take() {
            return Err(e);
        }
        let q = &self.gpu.queue;
        q.write_buffer(&self.b.tick, 4, bytemuck::cast_slice(&[self.sim.step]));
        self.run(true)
    }
    fn publish(&mut self, _phase: usize) -> Result<()> {
        self.run(false)?;
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
        self.seen()?.fill(&mut view);
        view.world.index_positions();
        Engine::exchanges(&view, phase, agents)
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
        // The polarisation needs every insect's velocity of every step.
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
