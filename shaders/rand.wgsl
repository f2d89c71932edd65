// Counter-based randomness (host-sim/src/gpu/shaders.rs, RAND): `swarm_core::rand`
// (core-nostd/src/rand.rs), function by function. A random number is a pure function of
// `(seed, agent, step, stream)`; the hash is 32-bit integer only (wrapping multiplies of u32,
// xor-shifts), so every word equals the Rust one (host-sim/src/gpu/tests/rand.rs).
// `rand_unit`, `rand_angle` and `rand_chance` are the generic functions of rand.rs over the
// scalar `S` (a kernel composes a scalar module, scalar_fx.wgsl or scalar_f32.wgsl); they take
// a `StepCtx` as its three words `seed, agent, step`.

// swarm_core::StepCtx: where a decision sits in the run, the inputs of the random numbers.
struct StepCtx {
    seed: u32,
    agent: u32,
    step: u32,
}

// rand::stream: named streams, so two draws of one agent in one step never share bits.
// ANT_STOP: ant, casual stop (xiang2018 §4.1).
const RAND_ANT_STOP: u32 = 1u;
// ANT_TURN: ant, basic-movement turn (xiang2018 §4.1).
const RAND_ANT_TURN: u32 = 2u;
// ANT_FALLBACK: ant, direction after a degenerate geometry.
const RAND_ANT_FALLBACK: u32 = 3u;
// ANT_SIDE: ant, its preferred way round an obstacle met head-on (step 0, once per ant).
const RAND_ANT_SIDE: u32 = 4u;
// BEE_PHASE: bee, the bee's own clock offset (step 0, once per bee).
const RAND_BEE_PHASE: u32 = 0x20u;
// BEE_PHASE_BASE: bee, the swarm's base roll phase (agent 0, step 0, once per seed).
const RAND_BEE_PHASE_BASE: u32 = 0x21u;

// rand::mix32: Wellons' `lowbias32` finaliser.
fn rand_mix32(x_in: u32) -> u32 {
    var x = x_in;
    x ^= x >> 16u;
    x = x * 0x7feb352du;
    x ^= x >> 15u;
    x = x * 0x846ca68bu;
    x ^= x >> 16u;
    return x;
}

// rand::rand: the random 32-bit word for (seed, agent, step, stream),
// h = mix(mix(mix(mix(seed ^ 0x9e3779b9) ^ agent) ^ step) ^ stream).
fn rand_rand(seed: u32, agent: u32, step: u32, stream: u32) -> u32 {
    let h0 = rand_mix32(seed ^ 0x9e3779b9u);
    let h1 = rand_mix32(h0 ^ agent);
    let h2 = rand_mix32(h1 ^ step);
    return rand_mix32(h2 ^ stream);
}

// rand::unit: a uniform number in the open interval (0, 1) for this step and stream.
fn rand_unit(seed: u32, agent: u32, step: u32, stream: u32) -> S {
    return s_unit_open(rand_rand(seed, agent, step, stream));
}

// rand::angle: a uniform angle in the open interval (-θ, θ), (u + u - 1) · θ.
fn rand_angle(seed: u32, agent: u32, step: u32, stream: u32, theta: S) -> S {
    let u = rand_unit(seed, agent, step, stream);
    return s_mul(s_sub(s_add(u, u), S_ONE), theta);
}

// rand::chance: a Bernoulli draw, true with probability p (p ≤ 0 never, ≥ 1 always).
fn rand_chance(seed: u32, agent: u32, step: u32, stream: u32, p: S) -> bool {
    return rand_unit(seed, agent, step, stream) < p;
}
