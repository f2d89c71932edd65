//! The wang2014 model on the GPU: `shaders/wang_step.wgsl`, the controller of
//! [`swarm_core::wang`] (the bounded curl noise on the bee model's Perlin potential, the two
//! phases, their validation) written once over the scalar `S`, and `shaders/wang_tick.wgsl`,
//! the engine's tick (the fields sampled from storage words, the nearest boundary, the world's
//! corrections, minimum distance enforcement on the GPU grid), driven by [`GpuWangSim`]; the
//! word layout of its values in [`layout`]. In fixed point every word is the CPU engine's
//! (the tests run both and compare).
//!
//! [`GpuWangSim`]: engine::GpuWangSim

pub mod engine;
pub mod layout;
#[cfg(test)]
mod tests;
