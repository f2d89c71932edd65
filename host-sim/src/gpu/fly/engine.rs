//! The ren2016 simulation on the GPU: [`GpuFlySim`], the generic 3D engine
//! ([`GpuSwarm3d`]) over `shaders/fly_tick.wgsl`: the cells
//! kernel, the GPU grid's sort, the step kernel (the frame of `fly/sense.rs`, then
//! `swarm_core::fly::step_checked` with its 3D ORCA) and the commit kernel (the world's
//! corrections, counted with atomics). In fixed point every word is the CPU engine's.

use swarm_core::Error;

use super::layout::{self, DECISION_WORDS, STATE_WORDS};
use crate::by_scalar;
use crate::error::Result;
use crate::fly::{Counts, Fly, FlySim};
use crate::gpu::shaders::{DISPATCH, FLY_TICK, Module};
pub use crate::gpu::swarm3d::CHECK_EVERY;
use crate::gpu::swarm3d::{GpuModel3d, GpuSwarm3d, SharedLayout};
use crate::gpu::words::Word;
use crate::scalar::SimScalar;
use crate::swarm3d::{DecisionOf, StateOf};

/// A ren2016 simulation whose steps run on the GPU.
pub type GpuFlySim = GpuSwarm3d<Fly>;

/// The counts of the tick's atomics (`FLY_SHARED_*`), in [`Counts`]' order.
const COUNTS: &[&str] = &["INFEASIBLE", "TRUNCATED", "OBSTACLE", "BOUNDS"];

/// The engine's constants of `fly_tick.wgsl` (checked by a test).
pub fn wgsl_shared() -> Vec<(String, u32)> {
    SharedLayout::new(COUNTS.len()).wgsl("FLY", COUNTS)
}

/// The modules of the tick's kernels over `scalar`.
pub fn modules(scalar: &'static Module) -> [&'static Module; 3] {
    [&DISPATCH, scalar, &FLY_TICK]
}

impl GpuModel3d for Fly {
    const KERNELS: [(&'static str, &'static str); 3] = [
        ("fly_tick_cells", "fly_tick_cells_main"),
        ("fly_tick_step", "fly_tick_step_main"),
        ("fly_tick_commit", "fly_tick_commit_main"),
    ];
    const STATE_WORDS: usize = STATE_WORDS;
    const DECISION_WORDS: usize = DECISION_WORDS;
    const COUNTS: &'static [&'static str] = COUNTS;

    fn modules(scalar: &'static Module) -> [&'static Module; 3] {
        modules(scalar)
    }
    /// Every group's words ([`layout::write_group`]), with the regions its goal and threat have
    /// now (`Engine::apply` shifts a region it moves).
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
    fn write_state<S: Word + SimScalar>(out: &mut Vec<u32>, s: &StateOf<Fly, S>) {
        layout::write_state(out, s);
    }
    fn read_state<S: Word + SimScalar>(w: &[u32]) -> StateOf<Fly, S> {
        layout::read_state(w)
    }
    fn read_decision<S: Word + SimScalar>(w: &[u32]) -> DecisionOf<Fly, S> {
        layout::read_decision(w)
    }
    fn status_error(word: u32) -> Result<std::result::Result<(), Error>> {
        layout::status_error(word)
    }
    fn count_words(c: &Counts) -> Vec<u64> {
        vec![c.infeasible, c.truncated, c.obstacle, c.bounds]
    }
    fn counts_of(w: &[u64]) -> Counts {
        Counts {
            infeasible: w[0],
            truncated: w[1],
            obstacle: w[2],
            bounds: w[3],
        }
    }
}
