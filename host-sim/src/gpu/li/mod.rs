//! The li2015 model on the GPU: `shaders/li_step.wgsl`, the controller of [`swarm_core::li`]
//! (the learned tables' inverse-CDF draws, the density grid, Algorithm 1 with the
//! Metropolis-Hastings screening of §4.3, the preferred velocity) on the fly's 3D ORCA
//! (`fly_orca_frame`), and `shaders/li_tick.wgsl`, the engine's tick (the frame of
//! [`li_frame`](crate::li::li_frame) on the GPU grid: the 16 nearest insects by exact key, the
//! surfaces within ORCA's reach; the world's corrections), driven by the generic 3D engine as
//! [`GpuLiSim`]; the word layout of its values in [`layout`]. A group's data (its tables and its
//! 4 KiB density) lies in its group words; a route of lights changes them between steps
//! ([`GpuModel3d::steps_on_host`]). In fixed point every word is the CPU engine's (the tests
//! run both and compare).

pub mod layout;
#[cfg(test)]
mod tests;

use swarm_core::Error;

use self::layout::{DECISION_WORDS, STATE_WORDS};
use crate::by_scalar;
use crate::error::Result;
use crate::gpu::shaders::{DISPATCH, LI_TICK, Module};
use crate::gpu::swarm3d::{GpuModel3d, GpuSwarm3d, SharedLayout};
use crate::gpu::words::Word;
use crate::li::{Counts, Li, LiSim};
use crate::scalar::SimScalar;
use crate::swarm3d::{DecisionOf, StateOf};

/// A li2015 simulation whose steps run on the GPU.
pub type GpuLiSim = GpuSwarm3d<Li>;

/// The counts of the tick's atomics (`LI_SHARED_*`), in [`Counts`]' order.
const COUNTS: &[&str] = &[
    "ARRIVALS",
    "PROPOSALS",
    "HELD",
    "INFEASIBLE",
    "TRUNCATED",
    "CORRECTED",
];

/// The engine's constants of `li_tick.wgsl` (checked by a test).
pub fn wgsl_shared() -> Vec<(String, u32)> {
    SharedLayout::new(COUNTS.len()).wgsl("LI", COUNTS)
}

/// The modules of the tick's kernels over `scalar`.
pub fn modules(scalar: &'static Module) -> [&'static Module; 3] {
    [&DISPATCH, scalar, &LI_TICK]
}

impl GpuModel3d for Li {
    const KERNELS: [(&'static str, &'static str); 3] = [
        ("li_tick_cells", "li_tick_cells_main"),
        ("li_tick_step", "li_tick_step_main"),
        ("li_tick_commit", "li_tick_commit_main"),
    ];
    const STATE_WORDS: usize = STATE_WORDS;
    const DECISION_WORDS: usize = DECISION_WORDS;
    const COUNTS: &'static [&'static str] = COUNTS;

    fn modules(scalar: &'static Module) -> [&'static Module; 3] {
        modules(scalar)
    }
    /// Every group's words ([`layout::write_group`]) with the density it holds now.
    fn group_words(sim: &LiSim) -> Vec<u32> {
        let mut out = Vec::new();
        for g in &sim.groups {
            by_scalar!(g, g => layout::write_group(&mut out, &g.params));
        }
        out
    }
    fn write_state<S: Word + SimScalar>(out: &mut Vec<u32>, s: &StateOf<Li, S>) {
        layout::write_state(out, s);
    }
    fn read_state<S: Word + SimScalar>(w: &[u32]) -> StateOf<Li, S> {
        layout::read_state(w)
    }
    fn read_decision<S: Word + SimScalar>(w: &[u32]) -> DecisionOf<Li, S> {
        layout::read_decision(w)
    }
    fn status_error(word: u32) -> Result<std::result::Result<(), Error>> {
        layout::status_error(word)
    }
    fn count_words(c: &Counts) -> Vec<u64> {
        vec![
            c.arrivals,
            c.proposals,
            c.held,
            c.infeasible,
            c.truncated,
            c.corrected,
        ]
    }
    fn counts_of(w: &[u64]) -> Counts {
        Counts {
            arrivals: w[0],
            proposals: w[1],
            held: w[2],
            infeasible: w[3],
            truncated: w[4],
            corrected: w[5],
        }
    }
    /// A group on a route of lights not all reached yet: the host sees when it reaches the
    /// next one (and moves its density on).
    fn steps_on_host(sim: &LiSim) -> bool {
        sim.measures.routes.iter().any(|r| {
            r.as_ref()
                .is_some_and(|r| r.reached.len() < r.route.lights.len())
        })
    }
}
