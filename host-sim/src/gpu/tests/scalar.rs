//! `shaders/scalar_fx.wgsl` and `scalar_f32.wgsl`: the `s_` interface of the generic modules.
//! Over `Fx` every function gives the bits of the `Scalar` method for `Fx`; over `f32` the
//! functions the GPU computes exactly (conversions, `floor_i32`, `unit_open`, `abs`, `min`,
//! `max`, signs, the correctly rounded `+`, `-`, `·`) give the bits of the `Scalar` method for
//! `f32` (normal operands: a GPU may flush subnormal numbers to zero).

use swarm_core::scalar::{deg, pi};
use swarm_core::{Fx, Scalar};

use super::{RANDOM, Rng, binary, check};
use crate::gpu::shaders::{Module, SCALAR_F32, SCALAR_FX};

/// `nan_word`: an f32's bits, any NaN as 0x7fc00000 (a GPU's NaN need not have Rust's bits).
const NAN_WORD: Module = Module {
    name: "nan_word",
    source: "fn nan_word(v: f32) -> u32 {
    let b = bitcast<u32>(v);
    if ((b & 0x7fffffffu) > 0x7f800000u) {
        return 0x7fc00000u;
    }
    return b;
}",
    uses: &[],
    over_scalar: false,
};

fn fx(w: u32) -> Fx {
    Fx::from_bits(w as i32)
}

fn w(v: Fx) -> u32 {
    v.to_bits() as u32
}

/// Every `s_` function over `Fx` in one dispatch: operands `a`, `b` (the edge pairs and random
/// pairs of [`binary`]).
#[test]
fn scalar_fx_is_the_scalar_of_fx() {
    check(
        "scalar_fx",
        &[&SCALAR_FX],
        "let sc = s_sin_cos(a0);
         put_i32(0u, s_add(a0, a1)); put_i32(1u, s_sub(a0, a1)); put_i32(2u, s_mul(a0, a1));
         put_i32(3u, s_div(a0, a1)); put_i32(4u, s_neg(a0)); put_i32(5u, s_abs(a0));
         put_i32(6u, s_min(a0, a1)); put_i32(7u, s_max(a0, a1)); put_i32(8u, s_sqrt(a0));
         put_i32(9u, s_sin(a0)); put_i32(10u, s_cos(a0)); put_i32(11u, sc.x); put_i32(12u, sc.y);
         put_i32(13u, s_atan2(a0, a1)); put_i32(14u, s_exp(a0)); put_i32(15u, s_from_i32(a0 >> 12u));
         put_i32(16u, s_floor_i32(a0)); put_bool(17u, s_is_finite(a0)); put_i32(18u, s_unit_open(u0));
         put_i32(19u, s_clamp_to(a0, a1, S_ONE)); put_i32(20u, s_signum(a0));
         put_i32(21u, s_powi(a0, u1 % 9u)); put_i32(22u, s_deg(a0)); put(23u, s_to_f32_bits(a0));
         put_i32(24u, s_from_f32_bits(u0)); put_i32(25u, s_from_f32(bitcast<f32>(u1)));
         put(26u, s_to_word(s_from_word(u0))); put_i32(27u, S_ZERO); put_i32(28u, S_ONE);
         put_i32(29u, S_EPS); put_i32(30u, S_PI); put_bool(31u, S_DIRECT_LENGTH);",
        &binary(40),
        |[a, b]| {
            let (x, y) = (fx(a), fx(b));
            let (s, c) = x.sin_cos();
            [
                w(x + y),
                w(x - y),
                w(x * y),
                w(x / y),
                w(-x),
                w(x.abs()),
                w(x.min(y)),
                w(x.max(y)),
                w(x.sqrt()),
                w(x.sin()),
                w(x.cos()),
                w(s),
                w(c),
                w(x.atan2(y)),
                w(x.exp()),
                w(Fx::from_i32((a as i32) >> 12)),
                x.floor_i32() as u32,
                u32::from(x.is_finite()),
                w(Fx::unit_open(a)),
                w(x.clamp_to(y, Fx::ONE)),
                w(x.signum()),
                w(x.powi((b % 9) as u8)),
                w(deg(x)),
                x.to_f32().to_bits(),
                w(Fx::from_f32(f32::from_bits(a))),
                w(Fx::from_f32(f32::from_bits(b))),
                a,
                w(Fx::ZERO),
                w(Fx::ONE),
                w(Fx::EPS),
                w(pi::<Fx>()),
                u32::from(Fx::DIRECT_LENGTH),
            ]
        },
    );
}

/// f32 bits without subnormals: zeros, infinities, NaNs, and normal numbers of magnitude 2^-20
/// to 2^20 (products and sums stay normal), a third of them integers or halves.
fn f32_words(seed: u32) -> Vec<[u32; 2]> {
    let mut g = Rng::new(seed);
    let special = [
        0u32,
        0x8000_0000,
        0x7f80_0000,
        0xff80_0000,
        0x7fc0_0000,
        0xffc0_0001,
        0x3f80_0000,
        0xbf80_0000,
        0x3f00_0000,
        0x4f00_0000, // 2^31
        0xcf00_0000, // -2^31
        0x4eff_ffff,
    ];
    let mut one = move || -> u32 {
        match g.below(8) {
            0 => special[g.below(special.len() as u32) as usize],
            1 | 2 => {
                let v = (g.next() as i32 >> g.below(24)) as f32 * [1.0, 0.5][g.below(2) as usize];
                v.to_bits()
            }
            _ => {
                let exp = 127 - 20 + g.below(41);
                (g.next() & 0x807f_ffff) | (exp << 23)
            }
        }
    };
    (0..RANDOM).map(|_| [one(), one()]).collect()
}

/// The exact functions of `scalar_f32.wgsl` against the `f32` `Scalar`.
#[test]
fn scalar_f32_is_exact_where_the_gpu_is() {
    check(
        "scalar_f32",
        &[&SCALAR_F32, &NAN_WORD],
        "let x = bitcast<f32>(u0); let y = bitcast<f32>(u1);
         put(0u, bitcast<u32>(s_from_f32_bits(u0))); put(1u, s_to_f32_bits(x));
         put_i32(2u, s_floor_i32(x)); put_bool(3u, s_is_finite(x));
         put(4u, bitcast<u32>(s_unit_open(u1))); put(5u, bitcast<u32>(s_abs(x)));
         put(6u, bitcast<u32>(s_min(x, y))); put(7u, bitcast<u32>(s_max(x, y)));
         put(8u, bitcast<u32>(s_from_i32(a1))); put(9u, bitcast<u32>(s_signum(x)));
         put(10u, nan_word(s_neg(x))); put(11u, bitcast<u32>(s_clamp_to(x, y, S_ONE)));
         put(12u, nan_word(s_add(x, y))); put(13u, nan_word(s_sub(x, y)));
         put(14u, nan_word(s_mul(x, y))); put(15u, bitcast<u32>(S_PI));
         put(16u, bitcast<u32>(S_EPS)); put_bool(17u, S_DIRECT_LENGTH);
         put(18u, bitcast<u32>(s_from_f32(x))); put(19u, s_to_word(s_from_word(u0)));",
        &f32_words(41),
        |[a, b]| {
            let (x, y) = (f32::from_bits(a), f32::from_bits(b));
            let nan = |v: f32| if v.is_nan() { 0x7fc0_0000 } else { v.to_bits() };
            [
                <f32 as Scalar>::from_f32(x).to_bits(),
                x.to_bits(),
                Scalar::floor_i32(x) as u32,
                u32::from(Scalar::is_finite(x)),
                <f32 as Scalar>::unit_open(b).to_bits(),
                Scalar::abs(x).to_bits(),
                Scalar::min(x, y).to_bits(),
                Scalar::max(x, y).to_bits(),
                <f32 as Scalar>::from_i32(b as i32).to_bits(),
                Scalar::signum(x).to_bits(),
                nan(-x),
                Scalar::clamp_to(x, y, 1.0).to_bits(),
                nan(x + y),
                nan(x - y),
                nan(x * y),
                pi::<f32>().to_bits(),
                f32::EPSILON.to_bits(),
                1,
                <f32 as Scalar>::from_f32(x).to_bits(),
                a,
            ]
        },
    );
}
