//! `shaders/fx.wgsl` against `swarm_core::Fx` and `Scalar`, bit for bit.

use swarm_core::scalar::{deg, pi};
use swarm_core::{Fx, Scalar};

use super::{RANDOM, Rng, binary, check, edge_words, ternary, unary};
use crate::gpu::shaders::FX;

/// The `Fx` of an input word.
fn fx(w: u32) -> Fx {
    Fx::from_bits(w as i32)
}

/// The output word of an `Fx`.
fn w(v: Fx) -> u32 {
    v.to_bits() as u32
}

/// A `u64` as the two words of the shader (low, high).
fn split(v: u64) -> [u32; 2] {
    [v as u32, (v >> 32) as u32]
}

/// A `u64` from two words (low, high).
fn join(lo: u32, hi: u32) -> u64 {
    (u64::from(hi) << 32) | u64::from(lo)
}

/// `u64` operands: 0, 1, the word and sign boundaries, then random values of every bit length.
fn u64_values(seed: u32, n: usize) -> Vec<u64> {
    let mut g = Rng::new(seed);
    let mut v = vec![
        0,
        1,
        2,
        0xffff_ffff,
        0x1_0000_0000,
        0x1_0000_0001,
        0x7fff_ffff_ffff_ffff,
        0x8000_0000_0000_0000,
        0x8000_0000_0000_0001,
        u64::MAX,
        u64::MAX - 1,
        0x7fff_ffff,
        0x8000_0000,
        0xffff_ffff_8000_0000,
        0xffff_ffff_7fff_ffff,
    ];
    v.extend((0..n).map(|_| {
        let s = g.below(64);
        g.next_u64() >> s
    }));
    v
}

// ---- the 64-bit helpers ----

#[test]
fn u64_from_u32() {
    let inputs: Vec<[u32; 1]> = edge_words().map(|a| [a]).collect();
    check(
        "fx_u64_from_u32",
        &[&FX],
        "let r = fx_u64_from_u32(u0); put(0u, r.x); put(1u, r.y);",
        &inputs,
        |[a]| split(u64::from(a)),
    );
}

#[test]
fn i64_from_i32() {
    check(
        "fx_i64_from_i32",
        &[&FX],
        "let r = fx_i64_from_i32(a0); put(0u, r.x); put(1u, r.y);",
        &unary(1),
        |[a]| split(i64::from(a as i32) as u64),
    );
}

/// Pairs of `u64` as four words.
fn u64_pairs(seed: u32) -> Vec<[u32; 4]> {
    let a = u64_values(seed, RANDOM);
    let b = u64_values(seed ^ 0x5555, RANDOM);
    let mut v: Vec<[u32; 4]> = a[..15]
        .iter()
        .flat_map(|&x| b[..15].iter().map(move |&y| (x, y)))
        .chain(a.iter().copied().zip(b.iter().copied()))
        .map(|(x, y)| {
            let ([x0, x1], [y0, y1]) = (split(x), split(y));
            [x0, x1, y0, y1]
        })
        .collect();
    // Equal high words, where the low words decide.
    v.extend(a.iter().take(1000).map(|&x| {
        let [x0, x1] = split(x);
        [x0, x1, x0 ^ 1, x1]
    }));
    v
}

#[test]
fn u64_add() {
    check(
        "fx_u64_add",
        &[&FX],
        "let r = fx_u64_add(vec2<u32>(u0, u1), vec2<u32>(u2, u3)); put(0u, r.x); put(1u, r.y);",
        &u64_pairs(2),
        |[a0, a1, b0, b1]| split(join(a0, a1).wrapping_add(join(b0, b1))),
    );
}

#[test]
fn u64_sub() {
    check(
        "fx_u64_sub",
        &[&FX],
        "let r = fx_u64_sub(vec2<u32>(u0, u1), vec2<u32>(u2, u3)); put(0u, r.x); put(1u, r.y);",
        &u64_pairs(3),
        |[a0, a1, b0, b1]| split(join(a0, a1).wrapping_sub(join(b0, b1))),
    );
}

#[test]
fn i64_neg() {
    let inputs: Vec<[u32; 2]> = u64_values(4, RANDOM).into_iter().map(split).collect();
    check(
        "fx_i64_neg",
        &[&FX],
        "let r = fx_i64_neg(vec2<u32>(u0, u1)); put(0u, r.x); put(1u, r.y);",
        &inputs,
        |[a0, a1]| split((join(a0, a1) as i64).wrapping_neg() as u64),
    );
}

#[test]
fn u64_lt() {
    check(
        "fx_u64_lt",
        &[&FX],
        "put_bool(0u, fx_u64_lt(vec2<u32>(u0, u1), vec2<u32>(u2, u3)));",
        &u64_pairs(5),
        |[a0, a1, b0, b1]| [u32::from(join(a0, a1) < join(b0, b1))],
    );
}

/// A `u64` and a shift amount below 64 (every amount for the edges).
fn u64_shifts(seed: u32) -> Vec<[u32; 3]> {
    let mut g = Rng::new(seed);
    let values = u64_values(seed, RANDOM);
    let mut v: Vec<[u32; 3]> = values[..15]
        .iter()
        .flat_map(|&x| (0..64).map(move |k| (x, k)))
        .map(|(x, k)| {
            let [x0, x1] = split(x);
            [x0, x1, k]
        })
        .collect();
    v.extend(values.iter().map(|&x| {
        let [x0, x1] = split(x);
        [x0, x1, g.below(64)]
    }));
    v
}

#[test]
fn u64_shl() {
    check(
        "fx_u64_shl",
        &[&FX],
        "let r = fx_u64_shl(vec2<u32>(u0, u1), u2); put(0u, r.x); put(1u, r.y);",
        &u64_shifts(6),
        |[a0, a1, k]| split(join(a0, a1) << k),
    );
}

#[test]
fn u64_shr() {
    check(
        "fx_u64_shr",
        &[&FX],
        "let r = fx_u64_shr(vec2<u32>(u0, u1), u2); put(0u, r.x); put(1u, r.y);",
        &u64_shifts(7),
        |[a0, a1, k]| split(join(a0, a1) >> k),
    );
}

#[test]
fn i64_shr() {
    check(
        "fx_i64_shr",
        &[&FX],
        "let r = fx_i64_shr(vec2<u32>(u0, u1), u2); put(0u, r.x); put(1u, r.y);",
        &u64_shifts(8),
        |[a0, a1, k]| split(((join(a0, a1) as i64) >> k) as u64),
    );
}

#[test]
fn u64_mul() {
    let mut g = Rng::new(9);
    let mut inputs: Vec<[u32; 2]> = [0u32, 1, 0xffff, 0x1_0000, 0x8000_0000, u32::MAX]
        .iter()
        .flat_map(|&a| [0u32, 1, 0xffff, 0x1_0000, 0x8000_0000, u32::MAX].map(|b| [a, b]))
        .collect();
    inputs.extend((0..RANDOM).map(|_| {
        let (sa, sb) = (g.below(32), g.below(32));
        [g.next() >> sa, g.next() >> sb]
    }));
    check(
        "fx_u64_mul",
        &[&FX],
        "let r = fx_u64_mul(u0, u1); put(0u, r.x); put(1u, r.y);",
        &inputs,
        |[a, b]| split(u64::from(a) * u64::from(b)),
    );
}

#[test]
fn i64_mul() {
    check(
        "fx_i64_mul",
        &[&FX],
        "let r = fx_i64_mul(a0, a1); put(0u, r.x); put(1u, r.y);",
        &binary(10),
        |[a, b]| split((i64::from(a as i32) * i64::from(b as i32)) as u64),
    );
}

#[test]
fn sat() {
    // Around the bounds of the i32 range, and anywhere.
    let mut v: Vec<u64> = u64_values(11, RANDOM);
    for d in -3i64..=3 {
        for c in [
            0i64,
            i64::from(i32::MAX),
            i64::from(i32::MIN),
            1 << 32,
            -(1 << 32),
        ] {
            v.push(c.wrapping_add(d) as u64);
        }
    }
    let mut g = Rng::new(11);
    v.extend((0..RANDOM).map(|_| i64::from(g.next() as i32 >> g.below(32)) as u64));
    v.extend((0..RANDOM).map(|_| ((g.next_u64() as i64) >> (g.below(34) + 30)) as u64));
    let inputs: Vec<[u32; 2]> = v.into_iter().map(split).collect();
    check(
        "fx_sat",
        &[&FX],
        "put_i32(0u, fx_sat(vec2<u32>(u0, u1)));",
        &inputs,
        |[lo, hi]| {
            let v = join(lo, hi) as i64;
            [v.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as u32]
        },
    );
}

#[test]
fn unsigned_abs() {
    check(
        "fx_unsigned_abs",
        &[&FX],
        "put(0u, fx_unsigned_abs(a0));",
        &unary(12),
        |[a]| [(a as i32).unsigned_abs()],
    );
}

#[test]
fn rem_euclid() {
    let mut g = Rng::new(13);
    let mut inputs: Vec<[u32; 2]> = edge_words()
        .flat_map(|a| [1i32, 2, 3, 65_536, 411_775, i32::MAX].map(|m| [a, m as u32]))
        .collect();
    inputs.extend((0..RANDOM).map(|_| {
        let m = (g.fx() as u32 & 0x7fff_ffff).max(1);
        [g.fx() as u32, m]
    }));
    check(
        "fx_rem_euclid",
        &[&FX],
        "put_i32(0u, fx_rem_euclid(a0, a1));",
        &inputs,
        |[a, m]| [(a as i32).rem_euclid(m as i32) as u32],
    );
}

#[test]
fn div_q16() {
    // `|a|` and `|b|` of two i32s: the numerator at most 2^31, the divisor in [1, 2^31].
    let edges = [
        0u32,
        1,
        2,
        3,
        0xffff,
        0x1_0000,
        0x1_0001,
        0xff_ffff,
        0x100_0000,
        0x7fff_ffff,
        0x8000_0000,
    ];
    let mut inputs: Vec<[u32; 2]> = edges
        .iter()
        .flat_map(|&n| edges[1..].iter().map(move |&d| [n, d]))
        .collect();
    let mut g = Rng::new(14);
    inputs.extend((0..RANDOM).map(|_| {
        let (n, sn, d, sd) = (g.next(), g.below(32), g.next(), g.below(32));
        [(n >> sn).min(1 << 31), (d >> sd).clamp(1, 1 << 31)]
    }));
    check(
        "fx_div_q16",
        &[&FX],
        "let r = fx_div_q16(u0, u1); put(0u, r.x); put(1u, r.y);",
        &inputs,
        |[n, d]| split((u64::from(n) << 16) / u64::from(d)),
    );
}

#[test]
fn isqrt() {
    // Every u64 (the method is the same at any size), squares and their neighbours, and the
    // operands of `sqrt`: `r << 16`.
    let mut g = Rng::new(15);
    let mut v = u64_values(15, RANDOM);
    for _ in 0..RANDOM / 4 {
        let k = g.next_u64() >> (g.below(32) + 32);
        let s = k * k;
        v.extend([s, s.wrapping_sub(1), s + 1]);
    }
    v.extend((0..RANDOM / 4).map(|_| u64::from(g.next() >> 1) << 16));
    let inputs: Vec<[u32; 2]> = v.into_iter().map(split).collect();
    check(
        "fx_isqrt",
        &[&FX],
        "let r = fx_isqrt(vec2<u32>(u0, u1)); put(0u, r.x); put(1u, r.y);",
        &inputs,
        |[lo, hi]| split(join(lo, hi).isqrt()),
    );
}

#[test]
fn isqrt_q16() {
    // `isqrt(a << 16)` for every u32 `a` (sqrt's operands are the positive i32s): the edges, all
    // values below 2^18, the neighbours of the `a` whose `a << 16` is a square, and the mixture.
    let mut inputs: Vec<[u32; 1]> = [u32::MAX, u32::MAX - 1, 1 << 31, (1 << 31) - 1]
        .into_iter()
        .chain(0..1 << 18)
        .map(|a| [a])
        .collect();
    let mut g = Rng::new(16);
    for _ in 0..RANDOM / 4 {
        // k² = a << 16 for k a multiple of 256.
        let a = (g.next() >> 16) * (g.next() >> 16);
        inputs.extend([a.wrapping_sub(1), a, a.wrapping_add(1)].map(|a| [a]));
    }
    inputs.extend((0..RANDOM).map(|_| [g.next() >> g.below(32)]));
    check(
        "fx_isqrt_q16",
        &[&FX],
        "put(0u, fx_isqrt_q16(u0));",
        &inputs,
        |[a]| [(u64::from(a) << 16).isqrt() as u32],
    );
}

// ---- Fx and Scalar ----

#[test]
fn constants() {
    check(
        "the FX_ constants",
        &[&FX],
        "put_i32(0u, FX_MAX); put_i32(1u, FX_MIN); put_i32(2u, FX_ZERO); put_i32(3u, FX_ONE);
         put_i32(4u, FX_EPS); put_i32(5u, FX_PI); put_i32(6u, FX_DEG); put_i32(7u, FX_PI_RAW);
         put_i32(8u, FX_TAU_RAW); put_i32(9u, FX_HALF_PI_RAW);",
        &[[0]],
        |_| {
            [
                w(Fx::MAX),
                w(Fx::MIN),
                w(Fx::ZERO),
                w(Fx::ONE),
                w(Fx::EPS),
                w(pi::<Fx>()),
                w(deg(Fx::ONE)),
                w(pi::<Fx>()),
                w(Fx::from_f32(core::f32::consts::TAU)),
                w(Fx::from_f32(core::f32::consts::FRAC_PI_2)),
            ]
        },
    );
}

#[test]
fn add() {
    check(
        "fx_add",
        &[&FX],
        "put_i32(0u, fx_add(a0, a1));",
        &binary(20),
        |[a, b]| [w(fx(a) + fx(b))],
    );
}

#[test]
fn sub() {
    check(
        "fx_sub",
        &[&FX],
        "put_i32(0u, fx_sub(a0, a1));",
        &binary(21),
        |[a, b]| [w(fx(a) - fx(b))],
    );
}

#[test]
fn mul() {
    check(
        "fx_mul",
        &[&FX],
        "put_i32(0u, fx_mul(a0, a1));",
        &binary(22),
        |[a, b]| [w(fx(a) * fx(b))],
    );
}

#[test]
fn div() {
    check(
        "fx_div",
        &[&FX],
        "put_i32(0u, fx_div(a0, a1));",
        &binary(23),
        |[a, b]| [w(fx(a) / fx(b))],
    );
}

#[test]
fn neg() {
    check(
        "fx_neg",
        &[&FX],
        "put_i32(0u, fx_neg(a0));",
        &unary(24),
        |[a]| [w(-fx(a))],
    );
}

#[test]
fn abs() {
    check(
        "fx_abs",
        &[&FX],
        "put_i32(0u, fx_abs(a0));",
        &unary(25),
        |[a]| [w(fx(a).abs())],
    );
}

#[test]
fn min() {
    check(
        "fx_min",
        &[&FX],
        "put_i32(0u, fx_min(a0, a1));",
        &binary(26),
        |[a, b]| [w(Scalar::min(fx(a), fx(b)))],
    );
}

#[test]
fn max() {
    check(
        "fx_max",
        &[&FX],
        "put_i32(0u, fx_max(a0, a1));",
        &binary(27),
        |[a, b]| [w(Scalar::max(fx(a), fx(b)))],
    );
}

#[test]
fn clamp_to() {
    check(
        "fx_clamp_to",
        &[&FX],
        "put_i32(0u, fx_clamp_to(a0, a1, a2));",
        &ternary(28),
        |[a, lo, hi]| [w(fx(a).clamp_to(fx(lo), fx(hi)))],
    );
}

#[test]
fn signum() {
    check(
        "fx_signum",
        &[&FX],
        "put_i32(0u, fx_signum(a0));",
        &unary(29),
        |[a]| [w(fx(a).signum())],
    );
}

#[test]
fn powi() {
    // Every power of the edges, and random powers of values near ±1 and anywhere.
    let mut g = Rng::new(30);
    let mut inputs: Vec<[u32; 2]> = edge_words()
        .flat_map(|a| (0..=255u32).map(move |n| [a, n]))
        .collect();
    inputs.extend((0..RANDOM / 2).map(|_| {
        let near_one = (0x1_0000 + ((g.next() as i32) >> (g.below(16) + 16))) as u32;
        let a = match g.below(3) {
            0 => near_one,
            1 => near_one.wrapping_neg(),
            _ => g.fx() as u32,
        };
        [a, g.below(256)]
    }));
    check(
        "fx_powi",
        &[&FX],
        "put_i32(0u, fx_powi(a0, u1));",
        &inputs,
        |[a, n]| [w(fx(a).powi(n as u8))],
    );
}

#[test]
fn from_i32() {
    check(
        "fx_from_i32",
        &[&FX],
        "put_i32(0u, fx_from_i32(a0));",
        &unary(31),
        |[a]| [w(Fx::from_i32(a as i32))],
    );
}

#[test]
fn floor_i32() {
    check(
        "fx_floor_i32",
        &[&FX],
        "put_i32(0u, fx_floor_i32(a0));",
        &unary(32),
        |[a]| [fx(a).floor_i32() as u32],
    );
}

#[test]
fn is_finite() {
    check(
        "fx_is_finite",
        &[&FX],
        "put_bool(0u, fx_is_finite(a0));",
        &unary(33),
        |[a]| [u32::from(fx(a).is_finite())],
    );
}

#[test]
fn unit_open() {
    check(
        "fx_unit_open",
        &[&FX],
        "put_i32(0u, fx_unit_open(u0));",
        &unary(34),
        |[a]| [w(Fx::unit_open(a))],
    );
}

#[test]
fn from_f32_bits() {
    // Every kind of f32: random bits, magnitudes near the Fx range (where rounding and
    // saturation matter), ties between two Fx values at every scale, and the specials.
    let mut g = Rng::new(35);
    let mut v: Vec<f32> = vec![
        0.0,
        -0.0,
        f32::NAN,
        -f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::MAX,
        f32::MIN,
        f32::MIN_POSITIVE,
        -f32::MIN_POSITIVE,
        1e-45,
        -1e-45,
        32767.99998,
        32768.0,
        -32768.0,
        -32768.00001,
        -32767.99998,
        65536.0,
        0.5 / 65536.0,
        -0.5 / 65536.0,
        1.5 / 65536.0,
        core::f32::consts::PI,
    ];
    for k in -2000i32..2000 {
        v.push(k as f32 / 131_072.0);
        v.push(k as f32 * 0.5 + 0.25 / 65_536.0);
        v.push(k as f32 * 16.0 + 0.5 / 65_536.0);
    }
    for _ in 0..RANDOM {
        let b = g.next();
        v.push(f32::from_bits(b));
        v.push(f32::from_bits(
            (b & 0x807f_ffff) | ((0x60 + (g.next() >> 27)) << 23),
        ));
    }
    let inputs: Vec<[u32; 1]> = v.into_iter().map(|f| [f.to_bits()]).collect();
    check(
        "fx_from_f32_bits",
        &[&FX],
        "put_i32(0u, fx_from_f32_bits(u0));",
        &inputs,
        |[b]| [w(Fx::from_f32(f32::from_bits(b)))],
    );
}

#[test]
fn to_f32_bits() {
    // Ties and near-ties of the rounding to 24 bits above 256.0, and the mixture.
    let mut inputs = unary(36);
    let mut g = Rng::new(36);
    inputs.extend((0..RANDOM).map(|_| {
        let s = g.below(8) + 1;
        let v = ((g.next() as i32) >> (g.below(8))) & !((1 << s) - 1);
        [(v | (1 << (s - 1))).wrapping_add((g.below(3) as i32) - 1) as u32]
    }));
    check(
        "fx_to_f32_bits",
        &[&FX],
        "put(0u, fx_to_f32_bits(a0));",
        &inputs,
        |[a]| [fx(a).to_f32().to_bits()],
    );
}

#[test]
fn degrees() {
    check(
        "fx_deg",
        &[&FX],
        "put_i32(0u, fx_deg(a0));",
        &unary(37),
        |[a]| [w(deg(fx(a)))],
    );
}

#[test]
fn sqrt() {
    // The mixture, every value up to 4.0 and below MAX by as much, and the neighbours of the
    // values whose root is exact (`(r << 16)` a square).
    let mut inputs = unary(40);
    inputs.extend((0..0x4_0000).map(|a| [a]));
    inputs.extend((0..0x4_0000).map(|d| [(i32::MAX - d) as u32]));
    let mut g = Rng::new(40);
    for _ in 0..RANDOM / 4 {
        let k = u64::from(g.next() >> (g.below(24) + 8));
        let r = ((k * k) >> 16) as i64;
        inputs.extend([r - 1, r, r + 1].map(|r| [r as u32]));
    }
    check(
        "fx_sqrt",
        &[&FX],
        "put_i32(0u, fx_sqrt(a0));",
        &inputs,
        |[a]| [w(fx(a).sqrt())],
    );
}

/// Angles: every raw value of one period [0, 2π) and a little around it (the whole domain of
/// the reduced functions), the multiples of π/2 and their neighbours up to the ends of the range,
/// and the mixture (huge arguments included).
fn angles(seed: u32) -> Vec<[u32; 1]> {
    let mut inputs = unary(seed);
    inputs.extend((-1000..411_775 + 1000).map(|a: i32| [a as u32]));
    for k in -20_860i64..=20_860 {
        let c = k * 102_944;
        for d in -2..=2 {
            let a = (c + d).clamp(i64::from(i32::MIN), i64::from(i32::MAX));
            inputs.push([a as i32 as u32]);
        }
    }
    inputs
}

#[test]
fn sin_quadrant() {
    // Private in Rust: on its domain [0, π/2], `sin` is `sin_quadrant`.
    let inputs: Vec<[u32; 1]> = (0..=102_944).map(|a| [a]).collect();
    check(
        "fx_sin_quadrant",
        &[&FX],
        "put_i32(0u, fx_sin_quadrant(a0));",
        &inputs,
        |[a]| [w(fx(a).sin())],
    );
}

#[test]
fn sin_reduced() {
    // Private in Rust: on its domain [0, 2π), `sin` is `sin_reduced`.
    let inputs: Vec<[u32; 1]> = (0..411_775).map(|a| [a]).collect();
    check(
        "fx_sin_reduced",
        &[&FX],
        "put_i32(0u, fx_sin_reduced(a0));",
        &inputs,
        |[a]| [w(fx(a).sin())],
    );
}

#[test]
fn sin() {
    check(
        "fx_sin",
        &[&FX],
        "put_i32(0u, fx_sin(a0));",
        &angles(41),
        |[a]| [w(fx(a).sin())],
    );
}

#[test]
fn cos() {
    check(
        "fx_cos",
        &[&FX],
        "put_i32(0u, fx_cos(a0));",
        &angles(42),
        |[a]| [w(fx(a).cos())],
    );
}

#[test]
fn sin_cos() {
    check(
        "fx_sin_cos",
        &[&FX],
        "let r = fx_sin_cos(a0); put_i32(0u, r.x); put_i32(1u, r.y);",
        &angles(43),
        |[a]| {
            let (s, c) = fx(a).sin_cos();
            [w(s), w(c)]
        },
    );
}

#[test]
fn atan2() {
    // Every pair of edges (both axes, both signs, 0/0), random pairs, points on the diagonals
    // and next to them (where the octant folding switches), and points near the axes.
    let mut inputs = binary(44);
    let mut g = Rng::new(44);
    for _ in 0..RANDOM / 2 {
        let v = g.fx();
        let d = (g.below(5) as i32) - 2;
        let (sy, sx) = (g.below(2) == 0, g.below(2) == 0);
        let y = if sy { v } else { v.saturating_neg() };
        let x = if sx {
            v.wrapping_add(d)
        } else {
            v.wrapping_add(d).saturating_neg()
        };
        inputs.push([y as u32, x as u32]);
        let small = (g.next() as i32) >> 28;
        inputs.push([small as u32, g.fx() as u32]);
        inputs.push([g.fx() as u32, small as u32]);
    }
    check(
        "fx_atan2",
        &[&FX],
        "put_i32(0u, fx_atan2(a0, a1));",
        &inputs,
        |[y, x]| [w(fx(y).atan2(fx(x)))],
    );
}

#[test]
fn exp() {
    // Every value where the result is not fixed by the first tests (-11.78 to 10.4), the
    // bounds, and the mixture (large positive and negative arguments).
    let mut inputs = unary(45);
    inputs.extend((-772_244 - 100..=681_391 + 100).map(|a: i32| [a as u32]));
    check(
        "fx_exp",
        &[&FX],
        "put_i32(0u, fx_exp(a0));",
        &inputs,
        |[a]| [w(fx(a).exp())],
    );
}
