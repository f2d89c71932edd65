//! The ren2016 model on the GPU: `shaders/fly_step.wgsl`, the controller of
//! [`swarm_core::fly`] (the zone forces of Eq. 5, friction, the stimulus response of Eq. 3 with
//! its escape draw, the noise of Eq. 4 on the bee model's curl noise, v_pref of Algorithm 1) and
//! its 3D ORCA ([`swarm_core::orca3d`]: the planes, RVO2-3D's incremental LP and its
//! `linearProgram4` fallback) written once over the scalar `S`, and `shaders/fly_tick.wgsl`, the
//! engine's tick (the frame on the GPU grid: the 16 nearest insects by exact key, the stimulus,
//! the surfaces within ORCA's reach; the world's corrections), driven by [`GpuFlySim`]; the word
//! layout of its values in [`layout`]. In fixed point every word is the CPU engine's (the tests
//! run both and compare).
//!
//! [`GpuFlySim`]: engine::GpuFlySim

pub mod engine;
pub mod layout;
#[cfg(test)]
mod tests;
