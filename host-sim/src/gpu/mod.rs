//! The GPU backend's foundation (wgpu): the adapter and device ([`Gpu`]), the WGSL modules of
//! `shaders/` and how kernels are put together from them ([`shaders`]), and compiled compute
//! kernels with their buffers ([`kernel`]); the neighbour grid built on the GPU ([`grid`]).
//!
//! The kernels mirror `swarm-core` function by function: `shaders/fx.wgsl` is the I16F16
//! arithmetic of [`swarm_core::Fx`], `shaders/rand.wgsl` its counter-based random numbers,
//! `shaders/geom.wgsl` its vectors, the last two written over the scalar `S` of a scalar module
//! (`scalar_fx.wgsl` or `scalar_f32.wgsl`, see [`shaders`]) as the Rust is over `Scalar`; each
//! is tested bit for bit against the Rust function over `Fx` on the GPU (lavapipe, Mesa's
//! Vulkan driver on the CPU, where there is no GPU; the tests are in `tests/`). [`ant`] and
//! [`bee`] are the ant and bee controllers on these foundations, with the word layouts of their
//! values.
//!
//! ```no_run
//! let gpu = swarm_sim::gpu::Gpu::shared().unwrap(); // an error naming what to install if none
//! println!("{}", gpu.info());
//! ```

pub mod ant;
pub mod bee;
mod context;
pub mod fly;
pub mod grid;
pub mod kernel;
pub mod li;
pub mod shaders;
pub mod space;
pub mod status;
pub mod swarm3d;
#[cfg(test)]
mod tests;
pub mod wang;
pub mod words;

pub use context::{AdapterSummary, Gpu};

/// The GPU of the tests: the process's device, [`Gpu::shared`] (lavapipe on a machine without a GPU).
/// Panics with the install hint if there is none: the test command installs the driver, and a
/// GPU test must fail rather than skip.
#[cfg(test)]
pub(crate) fn test_gpu() -> Gpu {
    Gpu::shared().unwrap_or_else(|e| panic!("the GPU tests need an adapter: {e}"))
}

/// Two slots `(a, b)`, `a < b`, whose agents' ids run the other way (`ids[a] > ids[b]`): where
/// two refusals in one tick tell "the lowest slot" from "the lowest id". Panics if the slots
/// are in id order (the engine must have reordered them for the test to test anything).
#[cfg(test)]
pub(crate) fn inverted_slots(ids: &[u32]) -> (usize, usize) {
    (1..ids.len())
        .find_map(|b| (0..b).find(|&a| ids[a] > ids[b]).map(|a| (a, b)))
        .expect("the slots are in id order: reorder them first")
}

/// Ticks `cpu` (which must refuse) and `gpu` once, syncs the GPU, and checks that both report
/// the same error; returns it.
#[cfg(test)]
pub(crate) fn same_refusal(
    cpu: &mut dyn crate::engine::Engine,
    gpu: &mut dyn crate::engine::Engine,
) -> String {
    let a = cpu.tick().unwrap_err().to_string();
    gpu.tick().unwrap();
    assert_eq!(a, gpu.sync().unwrap_err().to_string());
    a
}

/// Breaks, with `break_one`, the agents of two slots whose ids run the other way
/// ([`inverted_slots`] of `ids`, `states` by slot); returns the lower of their two ids, the
/// one a refusal must name.
#[cfg(test)]
pub(crate) fn break_two_inverted<T>(
    ids: &[u32],
    states: &mut [T],
    break_one: impl Fn(&mut T),
) -> u32 {
    let (a, b) = inverted_slots(ids);
    break_one(&mut states[a]);
    break_one(&mut states[b]);
    ids[b]
}

/// The steps a GPU-against-CPU comparison of a swarm of `agents` runs in the test suites:
/// `agent_steps` agent-steps, between `min` and `max` steps, so that a large swarm costs the GPU
/// no more than a small one (on lavapipe a GPU agent-step costs several CPU ones; docs/gpu.md,
/// "How long the comparisons run"). The environment's `SWARM_GPU_AGENT_STEPS` raises the budget
/// (`SWARM_GPU_AGENT_STEPS=1e12`: every comparison `max` steps long).
#[doc(hidden)]
pub fn comparison_steps(agents: u64, agent_steps: u64, min: u32, max: u32) -> u32 {
    let budget = std::env::var("SWARM_GPU_AGENT_STEPS")
        .ok()
        .and_then(|v| v.parse::<f64>().ok())
        .map_or(agent_steps, |v| (v as u64).max(agent_steps));
    (budget / agents.max(1)).clamp(u64::from(min), u64::from(max)) as u32
}
