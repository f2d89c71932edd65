// The scalar `S` as I16F16 fixed point (host-sim/src/gpu/shaders.rs, SCALAR_FX): the
// `swarm_core::Scalar` interface of `Fx` (core-nostd/src/scalar/mod.rs and fx.rs), one `s_`
// function per operation, mapping to the bit-exact `fx_` functions of fx.wgsl.
//
// The generic modules (geom.wgsl, rand.wgsl's `rand_unit`, the ant controller) are written
// over `S` and these names; a kernel composes them after exactly one scalar module, this one
// or scalar_f32.wgsl, which has the same names. Comparisons of two `S` are WGSL's own (`<`,
// `==`, ...): for `Fx` they compare the bits, as `Fx`'s `PartialOrd` does.

// An `Fx` is its raw bits (value = bits / 65536).
alias S = i32;

// Scalar::ZERO, ONE, EPS.
const S_ZERO: S = FX_ZERO;
const S_ONE: S = FX_ONE;
const S_EPS: S = FX_EPS;
// Scalar::DIRECT_LENGTH: false, vectors are scaled by their largest component (geom.rs).
const S_DIRECT_LENGTH: bool = false;
// `scalar::pi::<Fx>()`.
const S_PI: S = FX_PI;

// The bits of an `S` as a storage word, and back (`Fx::to_bits` / `from_bits`).
fn s_to_word(a: S) -> u32 {
    return bitcast<u32>(a);
}
fn s_from_word(w: u32) -> S {
    return bitcast<i32>(w);
}

// Add, Sub, Mul, Div, Neg for Fx (saturating; x / 0 is ±MAX, 0 / 0 = 0).
fn s_add(a: S, b: S) -> S {
    return fx_add(a, b);
}
fn s_sub(a: S, b: S) -> S {
    return fx_sub(a, b);
}
fn s_mul(a: S, b: S) -> S {
    return fx_mul(a, b);
}
fn s_div(a: S, b: S) -> S {
    return fx_div(a, b);
}
fn s_neg(a: S) -> S {
    return fx_neg(a);
}

// Scalar::from_f32 of an f32 given by its bits (Scalar::constant too: the same bits), and of
// an f32 (written `s_from_f32(0.25f)` where the Rust code has `S::from_f32(0.25)`: the literal
// is the f32 Rust reads, converted exactly as `i16f16_bits`).
fn s_from_f32_bits(v: u32) -> S {
    return fx_from_f32_bits(v);
}
fn s_from_f32(v: f32) -> S {
    return fx_from_f32_bits(bitcast<u32>(v));
}
// Scalar::to_f32, as the f32's bits.
fn s_to_f32_bits(a: S) -> u32 {
    return fx_to_f32_bits(a);
}
// Scalar::from_i32, floor_i32, is_finite, unit_open.
fn s_from_i32(v: i32) -> S {
    return fx_from_i32(v);
}
fn s_floor_i32(a: S) -> i32 {
    return fx_floor_i32(a);
}
fn s_is_finite(a: S) -> bool {
    return fx_is_finite(a);
}
fn s_unit_open(bits: u32) -> S {
    return fx_unit_open(bits);
}
// Scalar::sqrt, sin, cos, sin_cos (as (sin, cos)), atan2 (`y.atan2(x)`), exp.
fn s_sqrt(a: S) -> S {
    return fx_sqrt(a);
}
fn s_sin(a: S) -> S {
    return fx_sin(a);
}
fn s_cos(a: S) -> S {
    return fx_cos(a);
}
fn s_sin_cos(a: S) -> vec2<S> {
    return fx_sin_cos(a);
}
fn s_atan2(y: S, x: S) -> S {
    return fx_atan2(y, x);
}
fn s_exp(a: S) -> S {
    return fx_exp(a);
}
// The provided methods: abs, min, max, clamp_to, signum, powi; `scalar::deg`.
fn s_abs(a: S) -> S {
    return fx_abs(a);
}
fn s_min(a: S, o: S) -> S {
    return fx_min(a, o);
}
fn s_max(a: S, o: S) -> S {
    return fx_max(a, o);
}
fn s_clamp_to(a: S, lo: S, hi: S) -> S {
    return fx_clamp_to(a, lo, hi);
}
fn s_signum(a: S) -> S {
    return fx_signum(a);
}
fn s_powi(a: S, n: u32) -> S {
    return fx_powi(a, n);
}
fn s_deg(d: S) -> S {
    return fx_deg(d);
}
