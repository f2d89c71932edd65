//! The ant controller on the GPU: `shaders/ant_*.wgsl`, the controller of
//! [`swarm_core::ant`] written once over the scalar `S` and composed with a scalar module
//! ([`SCALAR_FX`]: bit for bit the Rust `plan_checked` and `resolve_checked` for
//! [`Fx`](swarm_core::Fx); [`SCALAR_F32`]: measured), the word layout of its values
//! ([`layout`]), and kernels that run `ant_plan_checked` / `ant_resolve_checked` once per
//! element of packed words ([`AntKernels`]): the harness of the tests, and the controllers of
//! the GPU engine to come. [`sense`] builds the ants' sensor frames on the GPU from the world's
//! words ([`world`]) and the GPU grid, bit for bit over `Fx`.

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

use swarm_core::{Scalar, ScalarKind};

use self::layout::{
    PLAN_INPUT_WORDS, PLAN_OUTPUT_WORDS, RESOLVE_INPUT_WORDS, RESOLVE_OUTPUT_WORDS,
};
use super::Gpu;
use super::kernel::{Kernel, run_chunked};
use super::shaders::{ANT_LAYOUT, ANT_PLAN, ANT_RESOLVE, DISPATCH, Module, SCALAR_F32, SCALAR_FX};
use crate::error::Result;

/// The scalar module of `S`: [`SCALAR_FX`] for `Fx`, [`SCALAR_F32`] for `f32`.
pub fn scalar_module<S: Scalar>() -> &'static Module {
    match S::KIND {
        ScalarKind::I16F16 => &SCALAR_FX,
        ScalarKind::F32 => &SCALAR_F32,
    }
}

/// The plan kernel: thread `i` reads element `i` of `input` ([`layout::write_plan_input`]),
/// runs `ant_plan_checked` and writes the status and the plan
/// ([`layout::write_plan_result`]).
pub const PLAN_KERNEL: &str = "
@group(0) @binding(0) var<storage, read> input: array<u32>;
@group(0) @binding(1) var<storage, read_write> output: array<u32>;
const IN_WORDS: u32 = ANT_STATE_WORDS + ANT_PLAN_FRAME_WORDS + ANT_PARAMS_WORDS + ANT_CTX_WORDS;
const OUT_WORDS: u32 = 1u + ANT_PLAN_WORDS;
@compute @workgroup_size(WORKGROUP)
fn ant_plan_main(@builtin(global_invocation_id) id: vec3<u32>,
                 @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(id, groups);
    if (i >= arrayLength(&input) / IN_WORDS) {
        return;
    }
    var b = i * IN_WORDS;
    var sw: array<u32, ANT_STATE_WORDS>;
    for (var k = 0u; k < ANT_STATE_WORDS; k = k + 1u) {
        sw[k] = input[b + k];
    }
    b = b + ANT_STATE_WORDS;
    var fw: array<u32, ANT_PLAN_FRAME_WORDS>;
    for (var k = 0u; k < ANT_PLAN_FRAME_WORDS; k = k + 1u) {
        fw[k] = input[b + k];
    }
    b = b + ANT_PLAN_FRAME_WORDS;
    var pw: array<u32, ANT_PARAMS_WORDS>;
    for (var k = 0u; k < ANT_PARAMS_WORDS; k = k + 1u) {
        pw[k] = input[b + k];
    }
    b = b + ANT_PARAMS_WORDS;
    var cw: array<u32, ANT_CTX_WORDS>;
    for (var k = 0u; k < ANT_CTX_WORDS; k = k + 1u) {
        cw[k] = input[b + k];
    }
    var frame = ant_plan_frame_from_words(fw);
    let r = ant_plan_checked(
        ant_state_from_words(sw),
        &frame,
        ant_params_from_words(pw),
        ant_ctx_from_words(cw),
    );
    let o = i * OUT_WORDS;
    output[o] = r.status;
    let w = ant_plan_to_words(r.plan);
    for (var k = 0u; k < ANT_PLAN_WORDS; k = k + 1u) {
        output[o + 1u + k] = w[k];
    }
}
";

/// The resolve kernel: thread `i` reads element `i` of `input`
/// ([`layout::write_resolve_input`]), runs `ant_resolve_checked` and writes the status and the
/// state ([`layout::write_resolve_result`]).
pub const RESOLVE_KERNEL: &str = "
@group(0) @binding(0) var<storage, read> input: array<u32>;
@group(0) @binding(1) var<storage, read_write> output: array<u32>;
const IN_WORDS: u32 = ANT_PLAN_WORDS + ANT_RESOLVE_FRAME_WORDS + ANT_PARAMS_WORDS;
const OUT_WORDS: u32 = 1u + ANT_STATE_WORDS;
@compute @workgroup_size(WORKGROUP)
fn ant_resolve_main(@builtin(global_invocation_id) id: vec3<u32>,
                    @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(id, groups);
    if (i >= arrayLength(&input) / IN_WORDS) {
        return;
    }
    var b = i * IN_WORDS;
    var pl: array<u32, ANT_PLAN_WORDS>;
    for (var k = 0u; k < ANT_PLAN_WORDS; k = k + 1u) {
        pl[k] = input[b + k];
    }
    b = b + ANT_PLAN_WORDS;
    var fw: array<u32, ANT_RESOLVE_FRAME_WORDS>;
    for (var k = 0u; k < ANT_RESOLVE_FRAME_WORDS; k = k + 1u) {
        fw[k] = input[b + k];
    }
    b = b + ANT_RESOLVE_FRAME_WORDS;
    var pw: array<u32, ANT_PARAMS_WORDS>;
    for (var k = 0u; k < ANT_PARAMS_WORDS; k = k + 1u) {
        pw[k] = input[b + k];
    }
    var frame = ant_resolve_frame_from_words(fw);
    let r = ant_resolve_checked(ant_plan_from_words(pl), &frame, ant_params_from_words(pw));
    let o = i * OUT_WORDS;
    output[o] = r.status;
    let w = ant_state_to_words(r.state);
    for (var k = 0u; k < ANT_STATE_WORDS; k = k + 1u) {
        output[o + 1u + k] = w[k];
    }
}
";

/// The modules of the ant kernels over the scalar `scalar`.
pub fn modules(scalar: &'static Module) -> [&'static Module; 5] {
    [&DISPATCH, scalar, &ANT_PLAN, &ANT_RESOLVE, &ANT_LAYOUT]
}

/// The labels of the kernels' input and output buffers.
const LABELS: [&str; 2] = ["ant input", "ant output"];

/// The plan and resolve kernels over one scalar, compiled once: each runs its controller once
/// per element of packed words ([`AntKernels::plan`], [`AntKernels::resolve`]).
pub struct AntKernels {
    plan: Kernel,
    resolve: Kernel,
}

impl AntKernels {
    /// The kernels over `S` (`ant_plan_checked` and `ant_resolve_checked` composed with
    /// [`scalar_module`]).
    ///
    /// # Errors
    ///
    /// As [`Kernel::new`].
    pub fn new<S: Scalar>(gpu: &Gpu) -> Result<AntKernels> {
        let uses = modules(scalar_module::<S>());
        Ok(AntKernels {
            plan: Kernel::new(gpu, "ant_plan", &uses, PLAN_KERNEL, "ant_plan_main")?,
            resolve: Kernel::new(
                gpu,
                "ant_resolve",
                &uses,
                RESOLVE_KERNEL,
                "ant_resolve_main",
            )?,
        })
    }

    /// Runs `ant_plan_checked` once per element of `input` (elements of [`PLAN_INPUT_WORDS`]
    /// words, [`layout::write_plan_input`]); the output words, [`PLAN_OUTPUT_WORDS`] per
    /// element (read them with [`layout::status_error`] and [`layout::read_plan`]).
    ///
    /// # Errors
    ///
    /// As [`run_chunked`].
    pub fn plan(&self, gpu: &Gpu, input: &[u32]) -> Result<Vec<u32>> {
        run_chunked(
            gpu,
            &self.plan,
            LABELS,
            input,
            PLAN_INPUT_WORDS,
            PLAN_OUTPUT_WORDS,
        )
    }

    /// Runs `ant_resolve_checked` once per element of `input` (elements of
    /// [`RESOLVE_INPUT_WORDS`] words, [`layout::write_resolve_input`]); the output words,
    /// [`RESOLVE_OUTPUT_WORDS`] per element ([`layout::status_error`], [`layout::read_state`]).
    ///
    /// # Errors
    ///
    /// As [`run_chunked`].
    pub fn resolve(&self, gpu: &Gpu, input: &[u32]) -> Result<Vec<u32>> {
        run_chunked(
            gpu,
            &self.resolve,
            LABELS,
            input,
            RESOLVE_INPUT_WORDS,
            RESOLVE_OUTPUT_WORDS,
        )
    }
}
