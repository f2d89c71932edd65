//! The bee controller on the GPU: `shaders/bee_*.wgsl`, the controller of [`swarm_core::bee`]
//! (chen's roll-to-avoid model: oscillation, curl noise on Perlin noise, SPH, vision) written
//! once over the scalar `S` and composed with a scalar module ([`SCALAR_FX`]: bit for bit the
//! Rust `step_checked` for [`Fx`](swarm_core::Fx); [`SCALAR_F32`]: measured), the word layout of
//! its values ([`layout`]), and a kernel that runs `bee_step_checked` once per element of packed
//! words ([`BeeKernels`]): the harness of the tests, and the controller of the GPU engine to
//! come. [`sense`] builds the bees' sensor frames on the GPU from the world's words
//! ([`world`]) and the GPU grid, bit for bit over `Fx`.
//!
//! [`SCALAR_FX`]: super::shaders::SCALAR_FX
//! [`SCALAR_F32`]: super::shaders::SCALAR_F32

pub mod engine;
#[cfg(test)]
mod engine_tests;
pub mod layout;
pub mod sense;
#[cfg(test)]
mod sense_tests;
#[cfg(test)]
mod tests;
pub mod world;

use swarm_core::Scalar;

use self::layout::{STEP_INPUT_WORDS, STEP_OUTPUT_WORDS};
use super::Gpu;
use super::ant::scalar_module;
use super::kernel::{Kernel, run_chunked};
use super::shaders::{BEE_LAYOUT, BEE_STEP, DISPATCH, Module};
use crate::error::Result;

/// The step kernel: thread `i` reads element `i` of `input` ([`layout::write_step_input`]),
/// runs `bee_step_checked` and writes the status, the decision and the next state
/// ([`layout::write_step_result`]).
pub const STEP_KERNEL: &str = "
@group(0) @binding(0) var<storage, read> input: array<u32>;
@group(0) @binding(1) var<storage, read_write> output: array<u32>;
const IN_WORDS: u32 = BEE_STATE_WORDS + BEE_FRAME_WORDS + BEE_PARAMS_WORDS;
const OUT_WORDS: u32 = 1u + BEE_DECISION_WORDS + BEE_STATE_WORDS;
@compute @workgroup_size(WORKGROUP)
fn bee_step_main(@builtin(global_invocation_id) id: vec3<u32>,
                 @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(id, groups);
    if (i >= arrayLength(&input) / IN_WORDS) {
        return;
    }
    var b = i * IN_WORDS;
    var sw: array<u32, BEE_STATE_WORDS>;
    for (var k = 0u; k < BEE_STATE_WORDS; k = k + 1u) {
        sw[k] = input[b + k];
    }
    b = b + BEE_STATE_WORDS;
    var fw: array<u32, BEE_FRAME_WORDS>;
    for (var k = 0u; k < BEE_FRAME_WORDS; k = k + 1u) {
        fw[k] = input[b + k];
    }
    b = b + BEE_FRAME_WORDS;
    var pw: array<u32, BEE_PARAMS_WORDS>;
    for (var k = 0u; k < BEE_PARAMS_WORDS; k = k + 1u) {
        pw[k] = input[b + k];
    }
    var frame = bee_frame_from_words(&fw);
    let r = bee_step_checked(bee_state_from_words(sw), &frame, bee_params_from_words(pw));
    let o = i * OUT_WORDS;
    output[o] = r.status;
    var d = bee_decision_to_words(r.decision);
    for (var k = 0u; k < BEE_DECISION_WORDS; k = k + 1u) {
        output[o + 1u + k] = d[k];
    }
    var s = bee_state_to_words(r.state);
    for (var k = 0u; k < BEE_STATE_WORDS; k = k + 1u) {
        output[o + 1u + BEE_DECISION_WORDS + k] = s[k];
    }
}
";

/// The modules of the bee kernel over the scalar `scalar`.
pub fn modules(scalar: &'static Module) -> [&'static Module; 4] {
    [&DISPATCH, scalar, &BEE_STEP, &BEE_LAYOUT]
}

/// The step kernel over one scalar, compiled once: it runs the controller once per element of
/// packed words ([`BeeKernels::step`]).
pub struct BeeKernels {
    step: Kernel,
}

impl BeeKernels {
    /// The kernel over `S` (`bee_step_checked` composed with [`scalar_module`]).
    ///
    /// # Errors
    ///
    /// As [`Kernel::new`].
    pub fn new<S: Scalar>(gpu: &Gpu) -> Result<BeeKernels> {
        let uses = modules(scalar_module::<S>());
        Ok(BeeKernels {
            step: Kernel::new(gpu, "bee_step", &uses, STEP_KERNEL, "bee_step_main")?,
        })
    }

    /// Runs `bee_step_checked` once per element of `input` (elements of [`STEP_INPUT_WORDS`]
    /// words, [`layout::write_step_input`]); the output words, [`STEP_OUTPUT_WORDS`] per element
    /// (read them with [`layout::read_step_result`]).
    ///
    /// # Errors
    ///
    /// As [`run_chunked`].
    pub fn step(&self, gpu: &Gpu, input: &[u32]) -> Result<Vec<u32>> {
        run_chunked(
            gpu,
            &self.step,
            ["bee input", "bee output"],
            input,
            STEP_INPUT_WORDS,
            STEP_OUTPUT_WORDS,
        )
    }
}
