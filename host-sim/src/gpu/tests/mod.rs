//! Bit-for-bit tests of the WGSL modules against their Rust originals, on the GPU (lavapipe
//! where there is none): every function of `shaders/fx.wgsl`, `scalar_fx.wgsl`, `rand.wgsl`
//! and `geom.wgsl` (the last two over `scalar_fx.wgsl`; `scalar_f32.wgsl` where exact) runs
//! once per input in one dispatch ([`map_words`]), over its edge cases and a few hundred
//! thousand pseudo-random inputs, and each output word must equal the Rust function's.

mod fx;
mod geom;
pub(super) mod harness;
mod rand;
mod scalar;

use crate::gpu::kernel::map_words;
use crate::gpu::shaders::Module;
use crate::gpu::test_gpu;

/// Pseudo-random inputs per test (besides the edge cases and the ranges tested exhaustively).
const RANDOM: usize = 200_000;

/// Marsaglia's xorshift32: the inputs' generator (fixed seeds, so a failure reproduces).
pub(super) struct Rng(u32);

impl Rng {
    pub(super) fn new(seed: u32) -> Rng {
        Rng(seed | 1)
    }
    pub(super) fn next(&mut self) -> u32 {
        let mut g = self.0;
        g ^= g << 13;
        g ^= g >> 17;
        g ^= g << 5;
        self.0 = g;
        g
    }
    /// Below `n` (> 0).
    pub(super) fn below(&mut self, n: u32) -> u32 {
        self.next() % n
    }
    /// 64 random bits.
    pub(super) fn next_u64(&mut self) -> u64 {
        (u64::from(self.next()) << 32) | u64::from(self.next())
    }
    /// An `Fx`'s bits: over the whole range (a quarter), of every bit length (a quarter), within
    /// ±64.0 (a quarter), near an integer (an eighth) or near the ends of the range (an eighth).
    pub(super) fn fx(&mut self) -> i32 {
        let r = self.next() as i32;
        match self.below(8) {
            0 | 1 => r,
            2 | 3 => r >> self.below(32),
            4 | 5 => r >> 9,
            6 => ((r >> 20) << 16).wrapping_add((self.next() as i32) >> 28),
            _ => {
                let small = (self.next() >> 20) as i32;
                if r < 0 {
                    i32::MIN + small
                } else {
                    i32::MAX - small
                }
            }
        }
    }
}

/// The edge cases of an `Fx` operand: 0, ±1 bit, ±0.5, ±1.0, ±1.5, the bounds of the range
/// and their neighbours, the values whose products and squares saturate (√32768 ≈ 181.02),
/// π, 2π, π/2, and integers at the bounds of `from_i32`.
pub(super) const FX_EDGES: &[i32] = &[
    0,
    1,
    -1,
    2,
    -2,
    3,
    0x7fff,
    0x8000,
    -0x8000,
    0x8001,
    0xffff,
    0x1_0000,
    -0x1_0000,
    0x1_0001,
    -0x1_0001,
    0x1_8000,
    -0x1_8000,
    0x2_0000,
    0xb5_0000,
    0xb5_04f3,
    0xb5_04f4,
    -0xb5_04f4,
    0xb6_0000,
    0x100_0000,
    -0x100_0000,
    0x4000_0000,
    -0x4000_0000,
    0x7fff_0000,
    i32::MAX,
    i32::MAX - 1,
    i32::MIN,
    i32::MIN + 1,
    205_887,
    -205_887,
    411_775,
    -411_775,
    102_944,
    -102_944,
    32_767,
    32_768,
    -32_768,
    -32_769,
];

/// `FX_EDGES` as input words.
pub(super) fn edge_words() -> impl Iterator<Item = u32> + Clone {
    FX_EDGES.iter().map(|&v| v as u32)
}

/// One `Fx` operand: the edges, then `RANDOM` drawn by [`Rng::fx`].
pub(super) fn unary(seed: u32) -> Vec<[u32; 1]> {
    let mut g = Rng::new(seed);
    edge_words()
        .map(|a| [a])
        .chain((0..RANDOM).map(|_| [g.fx() as u32]))
        .collect()
}

/// Two `Fx` operands: every pair of edges, then `RANDOM` random pairs.
pub(super) fn binary(seed: u32) -> Vec<[u32; 2]> {
    let mut g = Rng::new(seed);
    let mut v: Vec<[u32; 2]> = edge_words()
        .flat_map(|a| edge_words().map(move |b| [a, b]))
        .collect();
    v.extend((0..RANDOM).map(|_| [g.fx() as u32, g.fx() as u32]));
    v
}

/// Three `Fx` operands: every triple of edges, then `RANDOM` random triples.
pub(super) fn ternary(seed: u32) -> Vec<[u32; 3]> {
    let mut g = Rng::new(seed);
    let mut v: Vec<[u32; 3]> = edge_words()
        .flat_map(|a| edge_words().flat_map(move |b| edge_words().map(move |c| [a, b, c])))
        .collect();
    v.extend((0..RANDOM).map(|_| [g.fx() as u32, g.fx() as u32, g.fx() as u32]));
    v
}

/// Words as hex, for a failure's report.
pub(super) fn hex(words: &[u32]) -> String {
    let w: Vec<String> = words.iter().map(|w| format!("{w:#010x}")).collect();
    format!("[{}]", w.join(", "))
}

/// The kernel of [`check`]: thread `i` reads its `I` input words as `u0, u1, ...` (and as
/// `i32`s `a0, a1, ...`), runs `body`, which writes output word `k` with `put(k, u32)`,
/// `put_i32(k, i32)` or `put_bool(k, bool)`.
fn kernel_source(in_words: usize, out_words: usize, body: &str) -> String {
    let mut args = String::new();
    for k in 0..in_words {
        args.push_str(&format!(
            "    let u{k} = input[i * {in_words}u + {k}u];\n    let a{k} = bitcast<i32>(u{k});\n"
        ));
    }
    format!(
        "
@group(0) @binding(0) var<storage, read> input: array<u32>;
@group(0) @binding(1) var<storage, read_write> output: array<u32>;
var<private> out_base: u32;
fn put(k: u32, v: u32) {{ output[out_base + k] = v; }}
fn put_i32(k: u32, v: i32) {{ put(k, bitcast<u32>(v)); }}
fn put_bool(k: u32, v: bool) {{ put(k, select(0u, 1u, v)); }}
@compute @workgroup_size(WORKGROUP)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {{
    let i = thread_index(id, groups);
    if (i >= arrayLength(&input) / {in_words}u) {{ return; }}
    out_base = i * {out_words}u;
{args}    {body}
}}
"
    )
}

/// Runs `body` (see [`kernel_source`]) on the GPU over every input in one dispatch, and checks
/// each output against `rust` of the same input, word for word; panics naming `function`, how
/// many inputs differ and the first of them (input, GPU and Rust words in hex).
pub(super) fn check<const I: usize, const O: usize>(
    function: &str,
    uses: &[&Module],
    body: &str,
    inputs: &[[u32; I]],
    rust: impl Fn([u32; I]) -> [u32; O],
) {
    let kernel = kernel_source(I, O, body);
    let words: Vec<u32> = inputs.iter().flatten().copied().collect();
    let got = map_words(&test_gpu(), uses, &kernel, "main", &words, I, O)
        .unwrap_or_else(|e| panic!("{function}: {e}"));
    assert_eq!(got.len(), inputs.len() * O, "{function}: output length");
    let mut differ = 0usize;
    let mut first = None;
    for (input, got) in inputs.iter().zip(got.chunks_exact(O)) {
        let want = rust(*input);
        if got != want {
            differ += 1;
            first.get_or_insert((*input, got.to_vec(), want));
        }
    }
    if let Some((input, got, want)) = first {
        panic!(
            "{function}: {differ} of {} inputs differ; the first: input {}, GPU {}, Rust {}",
            inputs.len(),
            hex(&input),
            hex(&got),
            hex(&want)
        );
    }
}
