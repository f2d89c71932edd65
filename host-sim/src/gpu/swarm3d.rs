//! A 3D flying swarm on the GPU, whatever its controller (ren2016's `fly`, li2015's `li`): an
//! [`Engine`] whose step runs on wgpu, the insects' states staying on the GPU between ticks.
//!
//! [`GpuSwarm3d`] keeps the CPU simulation ([`Swarm3d`]) as its host view: the container, its
//! obstacles and stimulus sources, the groups' parameters and ids, what the outputs, the
//! measures and the mirror read. A tick is three kernels of the model's tick module
//! ([`GpuModel3d::modules`]): the cells kernel, the GPU grid's sort, the step kernel (the
//! model's frame on the GPU grid, then its controller) and the commit kernel (the world's
//! corrections, counted with atomics).
//!
//! In fixed point every word is the CPU engine's: the kernels are `swarm-core`'s controller and
//! the CPU's sensing and confinement function by function, the neighbours are selected by exact
//! keys, and slots are never reordered (results do not depend on slots). The host reads back
//! when it needs to look: [`Engine::sync`], every tick for the measures
//! ([`Engine::after_tick`], which `swarm run` calls and `swarm bench` does not), every tick a
//! model's [`Model3d::between_steps`] needs the states ([`GpuModel3d::steps_on_host`]), the
//! exchanges of the mirror (whose requests the host's sensing recomputes from the GPU's states,
//! the replies being the GPU's), and a check for refusals every [`CHECK_EVERY`] ticks.
//!
//! The tick's atomics (`{MODEL}_SHARED_*` in the model's tick module, e.g. `FLY_SHARED_*`;
//! [`SharedLayout`]): word 0 the
//! tick's lowest refused insect id (as `0xffffffff − id`: `par::for_each_agent_by`), then the model's [`GpuModel3d::COUNTS`] counts of this tick
//! (cleared by the host every tick), the first refusal kept (a flag, its step, the insect's id and status
//! word), and the counts since the start, each a `u64` as two words from an even word on.

use swarm_core::{Error, Fx, Scalar, ScalarKind};
use wgpu::util::DeviceExt;

use crate::bees::{BeeTarget, BeeWorld};
use crate::by_scalar;
use crate::engine::{Device, Engine, Exchange};
use crate::error::{Result, SimError};
use crate::gpu::Gpu;
use crate::gpu::bee::world::{GridShape3, world_words};
use crate::gpu::grid::GpuGrid;
use crate::gpu::kernel::{Kernel, read_back, storage};
use crate::gpu::shaders::{Module, SCALAR_F32, SCALAR_FX};
use crate::gpu::space::confine_boxes;
pub use crate::gpu::wang::engine::CHECK_EVERY;
use crate::gpu::words::Word;
use crate::output::{Frame, Summary};
use crate::scalar::{AgentGroup, SimScalar};
use crate::scenario::Action;
use crate::space::SURFACE_OFFSET;
use crate::swarm3d::{DecisionOf, Group3d, Model3d, StateOf, Step3d, Swarm3d, World3d};

/// A slot's flag word: bit 0 the world put the insect out of an obstacle, bit 1 back into the
/// container, and this bit: its frame was truncated (`{MODEL}_FLAG_TRUNCATED` in each tick
/// module).
pub const FLAG_TRUNCATED: u32 = 4;

/// A 3D model whose tick runs on the GPU: its tick module and the word layout of its values.
pub trait GpuModel3d: Model3d {
    /// The (name, entry point) of the cells, step and commit kernels.
    const KERNELS: [(&'static str, &'static str); 3];
    /// Words of a state (`{MODEL}_STATE_WORDS` in the tick module).
    const STATE_WORDS: usize;
    /// Words of a decision (`{MODEL}_DECISION_WORDS`).
    const DECISION_WORDS: usize;
    /// The counts of the tick's atomics ([`SharedLayout`]), in the order of
    /// [`GpuModel3d::count_words`].
    const COUNTS: &'static [&'static str];

    /// The modules of the tick's kernels over the scalar module `scalar`.
    fn modules(scalar: &'static Module) -> [&'static Module; 3];
    /// Every group's words, in group order (uploaded again with the world and whenever
    /// [`Model3d::between_steps`] ran).
    fn group_words(sim: &Swarm3d<Self>) -> Vec<u32>;
    /// Appends the [`GpuModel3d::STATE_WORDS`] words of `s`.
    fn write_state<S: Word + SimScalar>(out: &mut Vec<u32>, s: &StateOf<Self, S>);
    /// The state of [`GpuModel3d::STATE_WORDS`] words.
    fn read_state<S: Word + SimScalar>(w: &[u32]) -> StateOf<Self, S>;
    /// The decision of [`GpuModel3d::DECISION_WORDS`] words.
    fn read_decision<S: Word + SimScalar>(w: &[u32]) -> DecisionOf<Self, S>;
    /// The controller's answer of a status word: `Ok(())` for 0, else its error.
    ///
    /// # Errors
    ///
    /// [`SimError::GpuWords`] for a word no kernel of the model writes.
    fn status_error(word: u32) -> Result<std::result::Result<(), Error>>;
    /// The counts in the order of [`GpuModel3d::COUNTS`].
    fn count_words(c: &Self::Counts) -> Vec<u64>;
    /// The counts of words in the order of [`GpuModel3d::COUNTS`].
    fn counts_of(w: &[u64]) -> Self::Counts;
    /// Whether [`Model3d::between_steps`] needs the host to see every step (li2015: a group
    /// on a route of lights); never by default. The engine runs `between_steps` only when this
    /// says so: a model whose `between_steps` can change anything must say so whenever it can
    /// (the tick-by-tick tests against the CPU engine catch one that does not).
    fn steps_on_host(_sim: &Swarm3d<Self>) -> bool {
        false
    }
}

/// Where the tick's atomics are, for a model with `counts` counts (see the module's
/// documentation).
#[derive(Clone, Copy, Debug)]
pub struct SharedLayout {
    counts: usize,
}

impl SharedLayout {
    /// The layout of a model with `counts` counts.
    pub const fn new(counts: usize) -> Self {
        SharedLayout { counts }
    }
    /// This tick's count `k`.
    pub const fn count(&self, k: usize) -> usize {
        1 + k
    }
    /// The kept refusal's flag; its step, the insect's id and status word follow.
    pub const fn kept(&self) -> usize {
        1 + self.counts
    }
    /// The total of count `k` (low word, then high word).
    pub const fn total(&self, k: usize) -> usize {
        (self.kept() + 4).next_multiple_of(2) + 2 * k
    }
    /// Words of the atomics.
    pub const fn words(&self) -> usize {
        self.total(self.counts)
    }
    /// Bytes a tick starts with cleared: the refusal and this tick's counts.
    pub const fn per_tick_bytes(&self) -> u64 {
        (self.kept() * 4) as u64
    }
    /// The constants of the tick module (`{prefix}_SHARED_{NAME}`) and their values, for the
    /// test that checks the shader against them.
    pub fn wgsl(&self, prefix: &str, counts: &[&str]) -> Vec<(String, u32)> {
        let c = |name: &str, at: usize| (format!("{prefix}_SHARED_{name}"), at as u32);
        let mut out = vec![
            c("REFUSED", 0),
            c("KEPT", self.kept()),
            c("KEPT_STEP", self.kept() + 1),
            c("KEPT_ID", self.kept() + 2),
            c("KEPT_STATUS", self.kept() + 3),
        ];
        for (k, name) in counts.iter().enumerate() {
            out.push(c(name, self.count(k)));
            out.push(c(&format!("TOTAL_{name}"), self.total(k)));
        }
        out
    }
}

/// Binding numbers of the tick modules (and of the modules they use).
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

/// The compiled kernels of the tick.
struct Kernels {
    cells: Kernel,
    step: Kernel,
    commit: Kernel,
}

/// Their bind groups.
struct Bound {
    cells: wgpu::BindGroup,
    step: wgpu::BindGroup,
    commit: wgpu::BindGroup,
}

/// The container, its obstacles and the stimulus sources in the layout of the bee world's words
/// (`bee_world.wgsl`, whose obstacle geometry the 3D models share): the sources as targets
/// without particles (`bee_world_target_center` is [`World3d::source`]: the first active one of
/// the id), the neighbour range.
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
fn world_and_boxes(w: &World3d, shape: &GridShape3, scalar: ScalarKind) -> (Vec<u32>, Vec<u32>) {
    fn of<S: Word + SimScalar>(w: &World3d, shape: &GridShape3) -> (Vec<u32>, Vec<u32>) {
        (
            world_words::<S>(&space_world(w), shape),
            confine_boxes::<S>(&w.obstacles),
        )
    }
    match scalar {
        ScalarKind::I16F16 => of::<Fx>(w, shape),
        ScalarKind::F32 => of::<f32>(w, shape),
    }
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
    fn fill<M: GpuModel3d>(&self, sim: &mut Swarm3d<M>) {
        for g in &mut sim.groups {
            by_scalar!(g, g => self.fill_group(g, &mut sim.world));
        }
    }

    fn fill_group<M: GpuModel3d, S: Word + SimScalar>(
        &self,
        g: &mut Group3d<M, S>,
        w: &mut World3d,
    ) {
        let (sw, dw) = (M::STATE_WORDS, M::DECISION_WORDS);
        for k in 0..g.states.len() {
            let slot = g.first + k;
            g.states[k] = M::read_state(&self.states[slot * sw..(slot + 1) * sw]);
            g.next[k] = M::read_state(&self.next[slot * sw..(slot + 1) * sw]);
            g.decisions[k] = M::read_decision(&self.decisions[slot * dw..(slot + 1) * dw]);
            g.corrected[k] = (self.flags[slot] & 3) as u8;
            g.truncated[k] = self.flags[slot] & FLAG_TRUNCATED != 0;
        }
        w.sensed.write(g.first, &g.ids, &g.states);
    }
}

/// A simulation of model `M` whose steps run on the GPU (see the module's documentation).
pub struct GpuSwarm3d<M: GpuModel3d> {
    sim: Swarm3d<M>,
    gpu: Gpu,
    n: usize,
    scalar: ScalarKind,
    shape: GridShape3,
    shared: SharedLayout,
    b: Buffers,
    k: Kernels,
    bound: Bound,
    grid: GpuGrid,
    /// Ticks since the last check for refusals.
    unchecked: u32,
    /// Whether the host view holds the GPU's words of the last tick (read back since).
    fresh: bool,
    /// The groups' words on the GPU.
    group_words: Vec<u32>,
    /// A failure to report at the next fallible call (from [`Engine::after_tick`], which
    /// cannot).
    failed: Option<SimError>,
}

/// The scalar of a group.
fn scalar_of<M: Model3d, S: SimScalar>(_: &Group3d<M, S>) -> ScalarKind {
    S::KIND
}

impl<M: GpuModel3d> GpuSwarm3d<M> {
    /// The simulation `sim` on the GPU `gpu`, from its current state.
    ///
    /// # Errors
    ///
    /// [`SimError::GpuMixedScalars`] if its groups do not all run one scalar type,
    /// [`SimError::NoAgents`] without insects, and what compiling the kernels and sizing the
    /// grid refuse.
    pub fn new(sim: Swarm3d<M>, gpu: Gpu) -> Result<Self> {
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
        let (world, boxes) = world_and_boxes(&sim.world, &shape, scalar);
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
        let shared = SharedLayout::new(M::COUNTS.len());
        let states = vec![0u32; n * M::STATE_WORDS];
        let group_words = M::group_words(&sim);
        let buffer = |what: &'static str, words: &[u32]| storage(&gpu, what, words);
        let b = Buffers {
            tick: gpu
                .device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("3d tick params"),
                    contents: bytemuck::cast_slice(&tick),
                    usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                }),
            world: buffer("3d world", &world),
            // A binding is never empty: one word where there are no obstacles.
            boxes: buffer("3d confinement boxes", &[boxes, vec![0]].concat()),
            cells: buffer("3d cells", &vec![0u32; n]),
            states: buffer("3d states", &states),
            next: buffer("3d next states", &states),
            decisions: buffer("3d decisions", &vec![0u32; n * M::DECISION_WORDS]),
            groups: buffer("3d groups", &group_words),
            slots: buffer("3d slots", &slots),
            shared: buffer("3d tick atomics", &vec![0u32; shared.words()]),
            flags: buffer("3d flags", &vec![0u32; n]),
            status: buffer("3d status", &vec![0u32; n]),
        };
        let grid = GpuGrid::new(&gpu, n as u32, shape.cells())?;
        let k = Kernels::new::<M>(&gpu, scalar)?;
        let bound = k.bind(&gpu, &b, &grid);
        let mut out = GpuSwarm3d {
            sim,
            gpu,
            n,
            scalar,
            shape,
            shared,
            b,
            k,
            bound,
            grid,
            unchecked: 0,
            fresh: true,
            group_words,
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
    pub fn sim(&self) -> &Swarm3d<M> {
        &self.sim
    }

    /// Uploads the host's states and counts.
    fn push_states(&mut self) {
        let mut states = Vec::with_capacity(self.n * M::STATE_WORDS);
        for g in &self.sim.groups {
            by_scalar!(g, g => g.states.iter().for_each(|s| M::write_state(&mut states, s)));
        }
        let l = self.shared;
        let mut shared = vec![0u32; l.words()];
        let (last, total) = (
            M::count_words(&self.sim.last),
            M::count_words(&self.sim.total),
        );
        for k in 0..M::COUNTS.len() {
            shared[l.count(k)] = last[k] as u32;
            shared[l.total(k)] = total[k] as u32;
            shared[l.total(k) + 1] = (total[k] >> 32) as u32;
        }
        let q = &self.gpu.queue;
        q.write_buffer(&self.b.states, 0, bytemuck::cast_slice(&states));
        q.write_buffer(&self.b.shared, 0, bytemuck::cast_slice(&shared));
    }

    /// Uploads the groups' words if they changed.
    fn push_groups(&mut self) {
        let words = M::group_words(&self.sim);
        if words != self.group_words {
            let q = &self.gpu.queue;
            q.write_buffer(&self.b.groups, 0, bytemuck::cast_slice(&words));
            self.group_words = words;
        }
    }

    /// Uploads the host's world (obstacles and stimulus sources added, removed, moved) and the
    /// groups (which read the sources' regions).
    fn push_world(&mut self) {
        let (world, boxes) = world_and_boxes(&self.sim.world, &self.shape, self.scalar);
        let q = &self.gpu.queue;
        q.write_buffer(&self.b.world, 0, bytemuck::cast_slice(&world));
        if !boxes.is_empty() {
            q.write_buffer(&self.b.boxes, 0, bytemuck::cast_slice(&boxes));
        }
        self.push_groups();
    }

    /// Reads back what the GPU decided.
    fn seen(&self) -> Result<Seen> {
        let words = self.n * M::STATE_WORDS;
        let read = |what, b: &wgpu::Buffer, words| read_back::<u32>(&self.gpu, what, b, words);
        Ok(Seen {
            states: read("states", &self.b.states, words)?,
            next: read("next states", &self.b.next, words)?,
            decisions: read("decisions", &self.b.decisions, self.n * M::DECISION_WORDS)?,
            flags: read("flags", &self.b.flags, self.n)?,
        })
    }

    /// The tick's atomics, read back.
    fn atomics(&self) -> Result<Vec<u32>> {
        read_back(
            &self.gpu,
            "tick atomics",
            &self.b.shared,
            self.shared.words(),
        )
    }

    /// Reads the states, decisions, corrections and counts back into the host view (once a
    /// tick).
    fn pull(&mut self) -> Result<()> {
        if self.fresh {
            return self.failed.take().map_or(Ok(()), Err);
        }
        let w = self.atomics()?;
        self.check_words(&w)?;
        self.seen()?.fill(&mut self.sim);
        let l = self.shared;
        let counts = 0..M::COUNTS.len();
        let last: Vec<u64> = counts.clone().map(|k| u64::from(w[l.count(k)])).collect();
        let total: Vec<u64> = counts
            .map(|k| u64::from(w[l.total(k)]) | u64::from(w[l.total(k) + 1]) << 32)
            .collect();
        self.sim.last = M::counts_of(&last);
        self.sim.total = M::counts_of(&total);
        self.fresh = true;
        Ok(())
    }

    /// The first refusal of a controller since the start, as the CPU engine reports it.
    fn check(&mut self) -> Result<()> {
        let w = self.atomics()?;
        self.check_words(&w)
    }

    /// [`GpuSwarm3d::check`] on the atomics `w`, read back.
    fn check_words(&mut self, w: &[u32]) -> Result<()> {
        if let Some(e) = self.failed.take() {
            return Err(e);
        }
        self.unchecked = 0;
        let kept = self.shared.kept();
        if w[kept] == 0 {
            return Ok(());
        }
        let agent = w[kept + 2];
        let status = w[kept + 3];
        let Err(e) = M::status_error(status)? else {
            return Err(SimError::GpuWords {
                word: status,
                what: "refusal",
            });
        };
        Err(SimError::controller(
            <M::Params<f32> as Step3d<f32>>::STEP,
            w[kept + 1],
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
            enc.clear_buffer(&self.b.shared, 0, Some(self.shared.per_tick_bytes()));
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
        self.fresh = false;
        Ok(())
    }
}

impl Kernels {
    fn new<M: GpuModel3d>(gpu: &Gpu, scalar: ScalarKind) -> Result<Kernels> {
        let m = M::modules(match scalar {
            ScalarKind::I16F16 => &SCALAR_FX,
            ScalarKind::F32 => &SCALAR_F32,
        });
        let kernel = |(name, entry)| Kernel::new(gpu, name, &m, "", entry);
        let [cells, step, commit] = M::KERNELS;
        Ok(Kernels {
            cells: kernel(cells)?,
            step: kernel(step)?,
            commit: kernel(commit)?,
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

impl<M: GpuModel3d> Engine for GpuSwarm3d<M> {
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
        if M::steps_on_host(&self.sim) {
            // As the CPU's publish: the model's change between steps sees every insect moved.
            self.pull()?;
            M::between_steps(&mut self.sim);
            self.push_groups();
        } else if self.unchecked >= CHECK_EVERY {
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
        // The measures need every insect of every step.
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
