//! `shaders/geom.wgsl` (composed with `scalar_fx.wgsl`) against `swarm_core::geom` for `Fx`,
//! bit for bit.

use swarm_core::{Fx, Rect, Scalar, Vec2, Vec3};

use super::{FX_EDGES, RANDOM, Rng, check};
use crate::gpu::shaders::{GEOM, Module, SCALAR_FX};

/// `geom.wgsl` over `Fx`.
const FX_GEOM: &[&Module] = &[&SCALAR_FX, &GEOM];

fn fx(w: u32) -> Fx {
    Fx::from_bits(w as i32)
}

fn w(v: Fx) -> u32 {
    v.to_bits() as u32
}

fn v2(x: u32, y: u32) -> Vec2<Fx> {
    Vec2::new(fx(x), fx(y))
}

fn v3(x: u32, y: u32, z: u32) -> Vec3<Fx> {
    Vec3::new(fx(x), fx(y), fx(z))
}

/// `N` `Fx` words: all zero, edge cases in random combinations, the mixture of [`Rng::fx`],
/// and vectors of a few ulps.
fn tuples<const N: usize>(seed: u32) -> Vec<[u32; N]> {
    let mut g = Rng::new(seed);
    let edges = FX_EDGES.len() as u32;
    let mut v = vec![[0; N]];
    v.extend(
        (0..RANDOM / 4).map(|_| std::array::from_fn(|_| FX_EDGES[g.below(edges) as usize] as u32)),
    );
    v.extend((0..RANDOM).map(|_| std::array::from_fn(|_| g.fx() as u32)));
    v.extend(
        (0..RANDOM / 4)
            .map(|_| std::array::from_fn(|_| ((g.next() as i32) >> (24 + g.below(8))) as u32)),
    );
    v
}

/// `N` f32s as bits: random bits, and values within and around the Fx range.
fn f32_tuples<const N: usize>(seed: u32) -> Vec<[u32; N]> {
    let mut g = Rng::new(seed);
    (0..RANDOM)
        .map(|i| {
            std::array::from_fn(|_| {
                let b = g.next();
                if i % 2 == 0 {
                    b
                } else {
                    (b & 0x807f_ffff) | ((0x60 + (g.next() >> 27)) << 23)
                }
            })
        })
        .collect()
}

// ---- Vec2 ----

#[test]
fn from_f32_bits() {
    check(
        "geom_from_f32_bits",
        FX_GEOM,
        "let r = geom_from_f32_bits(vec2<u32>(u0, u1)); put_i32(0u, r.x); put_i32(1u, r.y);",
        &f32_tuples::<2>(60),
        |[x, y]| {
            let v = Vec2::<Fx>::from_f32(f32::from_bits(x), f32::from_bits(y));
            [w(v.x), w(v.y)]
        },
    );
}

#[test]
fn dot() {
    check(
        "geom_dot",
        FX_GEOM,
        "put_i32(0u, geom_dot(vec2<i32>(a0, a1), vec2<i32>(a2, a3)));",
        &tuples::<4>(61),
        |[a, b, c, d]| [w(v2(a, b).dot(v2(c, d)))],
    );
}

#[test]
fn cross() {
    check(
        "geom_cross",
        FX_GEOM,
        "put_i32(0u, geom_cross(vec2<i32>(a0, a1), vec2<i32>(a2, a3)));",
        &tuples::<4>(62),
        |[a, b, c, d]| [w(v2(a, b).cross(v2(c, d)))],
    );
}

#[test]
fn length_sq() {
    check(
        "geom_length_sq",
        FX_GEOM,
        "put_i32(0u, geom_length_sq(vec2<i32>(a0, a1)));",
        &tuples::<2>(63),
        |[a, b]| [w(v2(a, b).length_sq())],
    );
}

#[test]
fn length() {
    check(
        "geom_length",
        FX_GEOM,
        "put_i32(0u, geom_length(vec2<i32>(a0, a1)));",
        &tuples::<2>(64),
        |[a, b]| [w(v2(a, b).length())],
    );
}

#[test]
fn normalized() {
    check(
        "geom_normalized",
        FX_GEOM,
        "let r = geom_normalized(vec2<i32>(a0, a1));
         put_bool(0u, r.is_some); put_i32(1u, r.value.x); put_i32(2u, r.value.y);",
        &tuples::<2>(65),
        |[a, b]| match v2(a, b).normalized() {
            Some(n) => [1, w(n.x), w(n.y)],
            None => [0, 0, 0],
        },
    );
}

#[test]
fn perp() {
    check(
        "geom_perp",
        FX_GEOM,
        "let r = geom_perp(vec2<i32>(a0, a1)); put_i32(0u, r.x); put_i32(1u, r.y);",
        &tuples::<2>(66),
        |[a, b]| {
            let r = v2(a, b).perp();
            [w(r.x), w(r.y)]
        },
    );
}

#[test]
fn rotated() {
    check(
        "geom_rotated",
        FX_GEOM,
        "let r = geom_rotated(vec2<i32>(a0, a1), a2); put_i32(0u, r.x); put_i32(1u, r.y);",
        &tuples::<3>(67),
        |[a, b, angle]| {
            let r = v2(a, b).rotated(fx(angle));
            [w(r.x), w(r.y)]
        },
    );
}

#[test]
fn from_angle() {
    check(
        "geom_from_angle",
        FX_GEOM,
        "let r = geom_from_angle(a0); put_i32(0u, r.x); put_i32(1u, r.y);",
        &tuples::<1>(68),
        |[angle]| {
            let r = Vec2::<Fx>::from_angle(fx(angle));
            [w(r.x), w(r.y)]
        },
    );
}

#[test]
fn check_finite() {
    check(
        "geom_check",
        FX_GEOM,
        "put_bool(0u, geom_check(vec2<i32>(a0, a1)));",
        &tuples::<2>(69),
        |[a, b]| [u32::from(v2(a, b).check("v").is_ok())],
    );
}

#[test]
fn to_f32_bits() {
    check(
        "geom_to_f32_bits",
        FX_GEOM,
        "let r = geom_to_f32_bits(vec2<i32>(a0, a1)); put(0u, r.x); put(1u, r.y);",
        &tuples::<2>(70),
        |[a, b]| {
            let r = v2(a, b).to_f32();
            [r.x.to_bits(), r.y.to_bits()]
        },
    );
}

#[test]
fn add() {
    check(
        "geom_add",
        FX_GEOM,
        "let r = geom_add(vec2<i32>(a0, a1), vec2<i32>(a2, a3)); put_i32(0u, r.x); put_i32(1u, r.y);",
        &tuples::<4>(71),
        |[a, b, c, d]| {
            let r = v2(a, b) + v2(c, d);
            [w(r.x), w(r.y)]
        },
    );
}

#[test]
fn sub() {
    check(
        "geom_sub",
        FX_GEOM,
        "let r = geom_sub(vec2<i32>(a0, a1), vec2<i32>(a2, a3)); put_i32(0u, r.x); put_i32(1u, r.y);",
        &tuples::<4>(72),
        |[a, b, c, d]| {
            let r = v2(a, b) - v2(c, d);
            [w(r.x), w(r.y)]
        },
    );
}

#[test]
fn neg() {
    check(
        "geom_neg",
        FX_GEOM,
        "let r = geom_neg(vec2<i32>(a0, a1)); put_i32(0u, r.x); put_i32(1u, r.y);",
        &tuples::<2>(73),
        |[a, b]| {
            let r = -v2(a, b);
            [w(r.x), w(r.y)]
        },
    );
}

#[test]
fn mul() {
    check(
        "geom_mul",
        FX_GEOM,
        "let r = geom_mul(vec2<i32>(a0, a1), a2); put_i32(0u, r.x); put_i32(1u, r.y);",
        &tuples::<3>(74),
        |[a, b, k]| {
            let r = v2(a, b) * fx(k);
            [w(r.x), w(r.y)]
        },
    );
}

// ---- Vec3 ----

/// The three words of a `Vec3<Fx>`.
fn out3(v: Vec3<Fx>) -> [u32; 3] {
    [w(v.x), w(v.y), w(v.z)]
}

/// WGSL that writes a `vec3<i32>` `r` as output words 0, 1, 2.
const PUT3: &str = "put_i32(0u, r.x); put_i32(1u, r.y); put_i32(2u, r.z);";

#[test]
fn vec3_up() {
    check(
        "geom_vec3_up",
        FX_GEOM,
        &format!("let r = geom_vec3_up(); {PUT3}"),
        &[[0]],
        |_| out3(Vec3::<Fx>::up()),
    );
}

#[test]
fn vec3_from_f32_bits() {
    check(
        "geom_vec3_from_f32_bits",
        FX_GEOM,
        &format!("let r = geom_vec3_from_f32_bits(vec3<u32>(u0, u1, u2)); {PUT3}"),
        &f32_tuples::<3>(80),
        |[x, y, z]| {
            let [x, y, z] = [x, y, z].map(f32::from_bits);
            out3(Vec3::<Fx>::from_f32(x, y, z))
        },
    );
}

#[test]
fn vec3_dot() {
    check(
        "geom_vec3_dot",
        FX_GEOM,
        "put_i32(0u, geom_vec3_dot(vec3<i32>(a0, a1, a2), vec3<i32>(a3, a4, a5)));",
        &tuples::<6>(81),
        |[a, b, c, d, e, f]| [w(v3(a, b, c).dot(v3(d, e, f)))],
    );
}

#[test]
fn vec3_cross() {
    check(
        "geom_vec3_cross",
        FX_GEOM,
        &format!("let r = geom_vec3_cross(vec3<i32>(a0, a1, a2), vec3<i32>(a3, a4, a5)); {PUT3}"),
        &tuples::<6>(82),
        |[a, b, c, d, e, f]| out3(v3(a, b, c).cross(v3(d, e, f))),
    );
}

#[test]
fn vec3_length_sq() {
    check(
        "geom_vec3_length_sq",
        FX_GEOM,
        "put_i32(0u, geom_vec3_length_sq(vec3<i32>(a0, a1, a2)));",
        &tuples::<3>(83),
        |[a, b, c]| [w(v3(a, b, c).length_sq())],
    );
}

#[test]
fn vec3_length() {
    check(
        "geom_vec3_length",
        FX_GEOM,
        "put_i32(0u, geom_vec3_length(vec3<i32>(a0, a1, a2)));",
        &tuples::<3>(84),
        |[a, b, c]| [w(v3(a, b, c).length())],
    );
}

#[test]
fn vec3_normalized() {
    check(
        "geom_vec3_normalized",
        FX_GEOM,
        "let n = geom_vec3_normalized(vec3<i32>(a0, a1, a2)); let r = n.value;
         put_bool(3u, n.is_some); put_i32(0u, r.x); put_i32(1u, r.y); put_i32(2u, r.z);",
        &tuples::<3>(85),
        |[a, b, c]| match v3(a, b, c).normalized() {
            Some(n) => [w(n.x), w(n.y), w(n.z), 1],
            None => [0, 0, 0, 0],
        },
    );
}

#[test]
fn vec3_check() {
    check(
        "geom_vec3_check",
        FX_GEOM,
        "put_bool(0u, geom_vec3_check(vec3<i32>(a0, a1, a2)));",
        &tuples::<3>(86),
        |[a, b, c]| [u32::from(v3(a, b, c).check("v").is_ok())],
    );
}

#[test]
fn vec3_to_f32_bits() {
    check(
        "geom_vec3_to_f32_bits",
        FX_GEOM,
        "let r = geom_vec3_to_f32_bits(vec3<i32>(a0, a1, a2)); put(0u, r.x); put(1u, r.y); put(2u, r.z);",
        &tuples::<3>(87),
        |[a, b, c]| {
            let r = v3(a, b, c).to_f32();
            [r.x, r.y, r.z].map(f32::to_bits)
        },
    );
}

#[test]
fn vec3_add() {
    check(
        "geom_vec3_add",
        FX_GEOM,
        &format!("let r = geom_vec3_add(vec3<i32>(a0, a1, a2), vec3<i32>(a3, a4, a5)); {PUT3}"),
        &tuples::<6>(88),
        |[a, b, c, d, e, f]| out3(v3(a, b, c) + v3(d, e, f)),
    );
}

#[test]
fn vec3_sub() {
    check(
        "geom_vec3_sub",
        FX_GEOM,
        &format!("let r = geom_vec3_sub(vec3<i32>(a0, a1, a2), vec3<i32>(a3, a4, a5)); {PUT3}"),
        &tuples::<6>(89),
        |[a, b, c, d, e, f]| out3(v3(a, b, c) - v3(d, e, f)),
    );
}

#[test]
fn vec3_neg() {
    check(
        "geom_vec3_neg",
        FX_GEOM,
        &format!("let r = geom_vec3_neg(vec3<i32>(a0, a1, a2)); {PUT3}"),
        &tuples::<3>(90),
        |[a, b, c]| out3(-v3(a, b, c)),
    );
}

#[test]
fn vec3_mul() {
    check(
        "geom_vec3_mul",
        FX_GEOM,
        &format!("let r = geom_vec3_mul(vec3<i32>(a0, a1, a2), a3); {PUT3}"),
        &tuples::<4>(91),
        |[a, b, c, k]| out3(v3(a, b, c) * fx(k)),
    );
}

// ---- Rect ----

/// A rectangle and a point: random words, and points on and next to the rectangle's borders
/// (each coordinate a corner's, one bit off it, or random).
fn rect_points(seed: u32) -> Vec<[u32; 6]> {
    let mut g = Rng::new(seed);
    let mut v = tuples::<6>(seed);
    for t in v.iter_mut().skip(1).step_by(2) {
        for k in 0..2 {
            let d = (g.below(3) as i32 - 1) as u32;
            t[4 + k] = match g.below(3) {
                0 => t[k].wrapping_add(d),
                1 => t[2 + k].wrapping_add(d),
                _ => t[4 + k],
            };
        }
    }
    v
}

/// WGSL: the `GeomRect` of input words 0..4.
const RECT: &str = "GeomRect(vec2<i32>(a0, a1), vec2<i32>(a2, a3))";

fn rect([a, b, c, d]: [u32; 4]) -> Rect<Fx> {
    Rect::new(v2(a, b), v2(c, d))
}

#[test]
fn rect_contains() {
    check(
        "geom_rect_contains",
        FX_GEOM,
        &format!("put_bool(0u, geom_rect_contains({RECT}, vec2<i32>(a4, a5)));"),
        &rect_points(92),
        |[a, b, c, d, x, y]| [u32::from(rect([a, b, c, d]).contains(v2(x, y)))],
    );
}

#[test]
fn rect_clamp() {
    check(
        "geom_rect_clamp",
        FX_GEOM,
        &format!(
            "let r = geom_rect_clamp({RECT}, vec2<i32>(a4, a5)); put_i32(0u, r.x); put_i32(1u, r.y);"
        ),
        &rect_points(93),
        |[a, b, c, d, x, y]| {
            let r = rect([a, b, c, d]).clamp(v2(x, y));
            [w(r.x), w(r.y)]
        },
    );
}

#[test]
fn rect_check() {
    // Random corners, and degenerate ones (min = max on an axis, or one bit apart).
    let mut g = Rng::new(94);
    let mut inputs = tuples::<4>(94);
    for t in inputs.iter_mut().skip(1).step_by(2) {
        let k = g.below(2) as usize;
        t[2 + k] = t[k].wrapping_add((g.below(3) as i32 - 1) as u32);
    }
    check(
        "geom_rect_check",
        FX_GEOM,
        &format!("put_bool(0u, geom_rect_check({RECT}));"),
        &inputs,
        |[a, b, c, d]| [u32::from(rect([a, b, c, d]).check("r").is_ok())],
    );
}

/// Vectors of one or two ulps (`Fx::EPS`): the scaling of `normalized` makes them unit vectors.
#[test]
fn tiny_vectors_normalise() {
    let e = Fx::EPS.to_bits() as u32;
    check(
        "geom_normalized",
        FX_GEOM,
        "let r = geom_normalized(vec2<i32>(a0, a1)); put_i32(0u, r.value.x); put_i32(1u, r.value.y);",
        &[[e, 2 * e], [e, 0], [0, e.wrapping_neg()]],
        |[a, b]| {
            let n = v2(a, b).normalized().unwrap();
            [w(n.x), w(n.y)]
        },
    );
}
