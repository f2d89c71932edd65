// The scalar `S` as f32 (host-sim/src/gpu/shaders.rs, SCALAR_F32): the `swarm_core::Scalar`
// interface of `f32` (core-nostd/src/scalar/float.rs and mod.rs), with the same `s_` names as
// scalar_fx.wgsl, so the generic modules compose with either.
//
// *Measured, not promised* (docs/gpu.md): WGSL gives `sqrt`, `sin`, `cos`, `atan2`, `exp` and
// even `/` to the implementation's precision (libm's functions are correctly rounded or nearly
// so), and a driver may fuse `a * b + c` into one rounding (naga emits no `NoContraction`).
// What is exact here: the conversions, `unit_open`, `floor_i32`, `is_finite`, `abs`, `min`,
// `max` and the comparisons, which work on the bits or have one correct result.

alias S = f32;

// Scalar::ZERO, ONE, EPS (f32::EPSILON, 2^-23).
const S_ZERO: S = 0.0f;
const S_ONE: S = 1.0f;
const S_EPS: S = 1.1920929e-7f;
// Scalar::DIRECT_LENGTH: true, lengths are √(x² + y²) in the normal range (geom.rs).
const S_DIRECT_LENGTH: bool = true;
// `scalar::pi::<f32>()`: core::f32::consts::PI (bits 0x40490fdb).
const S_PI: S = 3.1415927f;

// The bits of an `S` as a storage word, and back.
fn s_to_word(a: S) -> u32 {
    return bitcast<u32>(a);
}
fn s_from_word(w: u32) -> S {
    return bitcast<f32>(w);
}

// Add, Sub, Mul, Div, Neg for f32.
fn s_add(a: S, b: S) -> S {
    return a + b;
}
fn s_sub(a: S, b: S) -> S {
    return a - b;
}
fn s_mul(a: S, b: S) -> S {
    return a * b;
}
fn s_div(a: S, b: S) -> S {
    return a / b;
}
fn s_neg(a: S) -> S {
    return -a;
}

// Whether the bits are a NaN (compilers may assume no NaN in float comparisons: bits only).
fn s_f32_is_nan(v: u32) -> bool {
    return (v & 0x7fffffffu) > 0x7f800000u;
}

// Scalar::from_f32 for f32 (NaN becomes 0), from the f32's bits and from an f32.
fn s_from_f32_bits(v: u32) -> S {
    if (s_f32_is_nan(v)) {
        return 0.0f;
    }
    return bitcast<f32>(v);
}
fn s_from_f32(v: f32) -> S {
    return s_from_f32_bits(bitcast<u32>(v));
}
// Scalar::to_f32, as the f32's bits.
fn s_to_f32_bits(a: S) -> u32 {
    return bitcast<u32>(a);
}
// Scalar::from_i32 for f32: `v as f32`.
fn s_from_i32(v: i32) -> S {
    return f32(v);
}
// Scalar::floor_i32 for f32: `floor(self) as i32`, saturating, NaN gives 0.
fn s_floor_i32(a: S) -> i32 {
    if (s_f32_is_nan(bitcast<u32>(a))) {
        return 0;
    }
    let f = floor(a);
    if (f >= 2147483648.0f) {
        return 2147483647;
    }
    if (f <= -2147483648.0f) {
        return -2147483647 - 1;
    }
    return i32(f);
}
// Scalar::is_finite for f32: false for NaN and ±inf.
fn s_is_finite(a: S) -> bool {
    return (bitcast<u32>(a) & 0x7f800000u) != 0x7f800000u;
}
// Scalar::unit_open for f32: 24 random bits centred in their cell, (k + 0.5) / 2^24 (exact).
fn s_unit_open(bits: u32) -> S {
    return (f32(bits >> 8u) + 0.5f) * (1.0f / 16777216.0f);
}
// Scalar::sqrt for f32: 0 for a ≤ 0 (and NaN).
fn s_sqrt(a: S) -> S {
    if (a > 0.0f) {
        return sqrt(a);
    }
    return 0.0f;
}
// Scalar::sin, cos, sin_cos (as (sin, cos)).
fn s_sin(a: S) -> S {
    return sin(a);
}
fn s_cos(a: S) -> S {
    return cos(a);
}
fn s_sin_cos(a: S) -> vec2<S> {
    return vec2<S>(sin(a), cos(a));
}
// Scalar::atan2 for f32 (`atan2f(y, x)`); the signed zeros as libm: atan2(±0, +0) = ±0,
// atan2(±0, -0) = ±π.
fn s_atan2(y: S, x: S) -> S {
    if (y == 0.0f && x == 0.0f) {
        if ((bitcast<u32>(x) >> 31u) == 0u) {
            return y;
        }
        return select(S_PI, -S_PI, (bitcast<u32>(y) >> 31u) == 1u);
    }
    return atan2(y, x);
}
// Scalar::exp for f32.
fn s_exp(a: S) -> S {
    return exp(a);
}
// Scalar::abs for f32: `f32::abs`, the sign bit cleared (-0 gives +0).
fn s_abs(a: S) -> S {
    return bitcast<f32>(bitcast<u32>(a) & 0x7fffffffu);
}
// Scalar::min, max (provided): `if o < a { o } else { a }`, `if o > a { o } else { a }`.
fn s_min(a: S, o: S) -> S {
    return select(a, o, o < a);
}
fn s_max(a: S, o: S) -> S {
    return select(a, o, o > a);
}
// Scalar::clamp_to (provided): `a.max(lo).min(hi)`.
fn s_clamp_to(a: S, lo: S, hi: S) -> S {
    return s_min(s_max(a, lo), hi);
}
// Scalar::signum (provided): -1, 0 or +1 (0 for ±0 and NaN).
fn s_signum(a: S) -> S {
    if (a > 0.0f) {
        return 1.0f;
    } else if (a < 0.0f) {
        return -1.0f;
    }
    return 0.0f;
}
// Scalar::powi (provided): `a^n` by repeated multiplication.
fn s_powi(a: S, n: u32) -> S {
    var acc = 1.0f;
    for (var i = 0u; i < n; i = i + 1u) {
        acc = acc * a;
    }
    return acc;
}
// scalar::deg: `d * (PI / 180.0)`, the f32 factor (bits 0x3c8efa35).
fn s_deg(d: S) -> S {
    return d * 0.017453292f;
}
