//! Tests of the wang2014 model (spec §4: W-T1, W-T3-W-T6, the closed form, fixed point, the
//! phases' behaviour, validation, totality).

extern crate std;
use std::vec::Vec;

use super::curl::{perlin_velocity, ramp_slope, random_velocity};
use super::params::{NOISE_PERLIN, NOISE_RANDOM};
use super::*;
use crate::bee::curl::{curl_force, potential};
use crate::bee::perlin::test_points;
use crate::{Error, Fx, Scalar, StepCtx, Vec3};

/// Table 1's (scale, gain) pairs: two blocks / chasing, aggregation, phototaxis / locusts.
const PAIRS: [(f32, f32); 3] = [(0.4, 0.25), (0.2, 0.7), (0.6, 1.0)];

fn ctx(agent: u32, step: u32) -> StepCtx {
    StepCtx {
        seed: 7,
        agent,
        step,
    }
}

fn e(k: usize) -> Vec3<f32> {
    [
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
        Vec3::new(0.0, 0.0, 1.0),
    ][k]
}

/// Central-difference divergence of `f` at `p`, step `h`.
fn divergence(f: impl Fn(Vec3<f32>) -> Vec3<f32>, p: Vec3<f32>, h: f32) -> f32 {
    let d = |k: usize| {
        let (a, b) = (f(p + e(k) * h), f(p - e(k) * h));
        ([a.x, a.y, a.z][k] - [b.x, b.y, b.z][k]) / (2.0 * h)
    };
    d(0) + d(1) + d(2)
}

/// Central-difference curl of `f` at `p`, step `h`.
fn curl_fd(f: impl Fn(Vec3<f32>) -> Vec3<f32>, p: Vec3<f32>, h: f32) -> Vec3<f32> {
    // j[k] = ∂f/∂x_k
    let j: Vec<Vec3<f32>> = (0..3)
        .map(|k| (f(p + e(k) * h) - f(p - e(k) * h)) * (1.0 / (2.0 * h)))
        .collect();
    Vec3::new(j[1].z - j[2].y, j[2].x - j[0].z, j[0].y - j[1].x)
}

/// Unit vectors from test points.
fn directions(seed: u32, n: usize) -> impl Iterator<Item = Vec3<f32>> {
    test_points(seed, n, 1.0).filter_map(|v| v.normalized())
}

/// A uniform number in [0, 1) from a test point's coordinate.
fn frac(x: f32) -> f32 {
    (x * 0.5 + 0.5).clamp(0.0, 0.999)
}

/// A sphere boundary of centre `c` and radius `r` as seen from `x`: with its curvature
/// (host mode) or without (device mode).
fn sphere(x: Vec3<f32>, c: Vec3<f32>, r: f32, curved: bool) -> Boundary<f32> {
    let rho = (x - c).length();
    let n = (x - c) * (1.0 / rho);
    Boundary {
        point: c + n * r,
        normal: n,
        curvature: if curved { 1.0 / rho } else { 0.0 },
        axis: Vec3::zero(),
    }
}

/// The side of a vertical shaft (axis ŷ through `c`, radius `r`) as seen from `x`.
fn shaft(x: Vec3<f32>, c: Vec3<f32>, r: f32) -> Boundary<f32> {
    let mut off = x - c;
    off.y = 0.0;
    let rho = off.length();
    let n = off * (1.0 / rho);
    Boundary {
        point: Vec3::new(c.x, x.y, c.z) + n * r,
        normal: n,
        curvature: 1.0 / rho,
        axis: Vec3::up(),
    }
}

/// W-T1: eq. 3 is the bee's ramp: α(0) = 0, α(1) = 1, α = 1 beyond, monotone on [0, 1], and
/// α' (used for ∇a) is its derivative with α'(1) = 0.
#[test]
fn w_t1_the_ramp_of_eq_3() {
    assert_eq!(ramp(0.0f32), 0.0);
    assert_eq!(ramp(1.0f32), 1.0);
    assert_eq!(ramp(1.5f32), 1.0);
    assert_eq!(ramp_slope(1.0f32), 0.0);
    assert_eq!(ramp_slope(0.0f32), 1.875);
    let mut last = 0.0;
    for i in 1..1000 {
        let r = i as f32 / 1000.0;
        assert!(ramp(r) >= last);
        last = ramp(r);
        let h = 1e-3;
        let fd = (ramp((r + h).min(1.0)) - ramp(r - h)) / ((r + h).min(1.0) - (r - h));
        assert!(
            (fd - ramp_slope(r)).abs() < 2e-3,
            "α'({r}) = {}, fd {fd}",
            ramp_slope(r)
        );
    }
}

/// W-T3: with no boundary the field is exactly the bee's curl noise, divergence-free to
/// rounding (|div| ≤ 1e-2·gain/scale², central differences, h = 1e-3) for Table 1's pairs.
#[test]
fn w_t3_divergence_free_in_free_space() {
    for (i, (scale, gain)) in PAIRS.into_iter().enumerate() {
        let bound = 1e-2 * gain / (scale * scale);
        for p in test_points(100 + i as u32, 100, 20.0) {
            assert_eq!(
                curl_noise(p, scale, gain, 1.0, None),
                curl_force(p, scale, gain)
            );
            let div = divergence(|x| curl_noise(x, scale, gain, 1.0, None), p, 1e-3);
            assert!(div.abs() <= bound, "({scale}, {gain}) at {p:?}: div {div}");
        }
    }
}

/// W-T4: within d0 of a plane (100 random points per pair, random planes) the bounded field
/// keeps the W-T3 bound; beyond d0 it is the free field.
#[test]
fn w_t4_divergence_free_near_a_plane() {
    let d0 = 1.0;
    for (i, (scale, gain)) in PAIRS.into_iter().enumerate() {
        let bound = 1e-2 * gain / (scale * scale);
        let normals = directions(200 + i as u32, 200);
        let offsets = test_points(300 + i as u32, 200, 10.0);
        for (k, (n, q)) in normals.zip(offsets).take(100).enumerate() {
            let b = Boundary::plane(q, n);
            // A point at height d ∈ [0.01, d0) above the plane.
            let d = 0.01 + 0.98 * (k as f32 + 0.5) / 100.0;
            let p = q + Vec3::new(n.y, n.z, n.x).cross(n) * 0.7 + n * d;
            let div = divergence(|x| curl_noise(x, scale, gain, d0, Some(&b)), p, 1e-3);
            assert!(div.abs() <= bound, "({scale}, {gain}) d {d}: div {div}");
            let far = q + n * (d0 + 0.5);
            assert_eq!(
                curl_noise(far, scale, gain, d0, Some(&b)),
                curl_force(far, scale, gain)
            );
        }
    }
}

/// W-T5: near a sphere of radius R = 3 (≥ 5·scale): with the curvature in the frame the
/// W-T3 bound; with curvature 0 (a device that treats the surface as locally planar)
/// |div| ≤ 4·gain/(scale·R) (observed: ≤ 1.8·gain/(scale·R) planar, ≤ 1.5e-3·gain/scale² exact).
#[test]
fn w_t5_divergence_near_a_sphere() {
    let (c, r, d0) = (Vec3::new(1.0, 2.0, -3.0), 3.0, 1.0);
    for (i, (scale, gain)) in PAIRS.into_iter().enumerate() {
        let exact = 1e-2 * gain / (scale * scale);
        let planar = 4.0 * gain / (scale * r);
        let (mut worst_exact, mut worst_planar) = (0.0f32, 0.0f32);
        for (k, n) in directions(400 + i as u32, 200).take(100).enumerate() {
            let d = 0.01 + 0.98 * (k as f32 + 0.5) / 100.0;
            let p = c + n * (r + d);
            let field = |curved: bool| {
                move |x: Vec3<f32>| curl_noise(x, scale, gain, d0, Some(&sphere(x, c, r, curved)))
            };
            let de = divergence(field(true), p, 1e-3);
            let dp = divergence(field(false), p, 1e-3);
            worst_exact = worst_exact.max(de.abs());
            worst_planar = worst_planar.max(dp.abs());
            assert!(de.abs() <= exact, "({scale}, {gain}) d {d}: div {de}");
            assert!(
                dp.abs() <= planar,
                "({scale}, {gain}) d {d}: planar div {dp}"
            );
        }
        // The curvature term matters: without it the divergence is far above rounding.
        assert!(
            worst_planar > 10.0 * worst_exact,
            "{worst_planar} vs {worst_exact}"
        );
    }
}

/// W-T6: no flux. |V_l·n| ≤ 1e-4·gain/scale on the surface and
/// ≤ 8·d·gain/(scale·min(scale, d0)) at 0 < d < d0, on planes, spheres (with and without
/// curvature) and shaft sides.
#[test]
fn w_t6_no_flux_through_boundaries() {
    let d0 = 1.0;
    for (i, (scale, gain)) in PAIRS.into_iter().enumerate() {
        let at_surface = 1e-4 * gain / scale;
        let slope = 8.0 * gain / (scale * scale.min(d0));
        let dirs: Vec<_> = directions(500 + i as u32, 100).take(40).collect();
        let pts: Vec<_> = test_points(600 + i as u32, 40, 10.0).collect();
        for (k, (n, q)) in dirs.iter().zip(&pts).enumerate() {
            let (c, r) = (*q, 3.0);
            for d in [0.0, 0.001, 0.01, 0.05, 0.1, 0.3, 0.6, 0.9] {
                let mut cases: Vec<(Vec3<f32>, Boundary<f32>)> = Vec::new();
                // A plane through q.
                cases.push((
                    *q + n.cross(e(k % 3)) * 0.3 + *n * d,
                    Boundary::plane(*q, *n),
                ));
                // A sphere of radius 3 round q, with and without curvature.
                let x = c + *n * (r + d);
                cases.push((x, sphere(x, c, r, true)));
                cases.push((x, sphere(x, c, r, false)));
                // A shaft of radius 0.2 along y through q.
                let mut h = *n;
                h.y = 0.0;
                if let Some(h) = h.normalized() {
                    let x = c + h * (0.2 + d) + Vec3::new(0.0, n.y, 0.0);
                    cases.push((x, shaft(x, c, 0.2)));
                }
                for (x, b) in cases {
                    let v = curl_noise(x, scale, gain, d0, Some(&b));
                    let flux = v.dot(b.normal).abs();
                    let bound = if d == 0.0 { at_surface } else { slope * d };
                    assert!(
                        flux <= bound,
                        "({scale}, {gain}) d {d}: flux {flux} > {bound}, {b:?}"
                    );
                }
            }
        }
    }
}

/// Eq. 2's potential N = αP + (1 − α)(n·P)n for the boundary `b` as seen from `x`.
fn potential_n(x: Vec3<f32>, scale: f32, gain: f32, d0: f32, b: &Boundary<f32>) -> Vec3<f32> {
    let [p1, p2, p3] = potential(x, scale, gain);
    let p = Vec3::new(p1.value, p2.value, p3.value);
    let n = b.normal;
    let a = ramp(((x - b.point).dot(n) / d0).max(0.0));
    p * a + n * ((1.0 - a) * n.dot(p))
}

/// The closed form against central differences of eq. 2's N (f32, h = 1e-3): for a plane,
/// and for a sphere with its curvature. Tolerance 2e-3·gain/scale: the f32 rounding of a
/// difference quotient is about ε·|N|/h ≈ 6e-8·gain/1e-3 (6e-5·gain) per partial derivative
/// (two per component), and the truncation h²/6·|∂³N| ≈ 1.7e-7·gain/scale³ ≤ 2e-5·gain/scale
/// for scale ≥ 0.2: both well inside; observed ≤ 7e-4·gain/scale.
#[test]
fn closed_form_matches_finite_differences_of_eq_2() {
    let d0 = 1.0;
    for (i, (scale, gain)) in PAIRS.into_iter().enumerate() {
        let tol = 2e-3 * gain / scale;
        let dirs: Vec<_> = directions(700 + i as u32, 100).take(50).collect();
        for (k, n) in dirs.iter().enumerate() {
            let d = 0.02 + 0.95 * (k as f32 + 0.5) / 50.0;
            let q = Vec3::new(0.3, -1.2, 2.5);
            let b = Boundary::plane(q, *n);
            let p = q + *n * d + n.cross(e(k % 3)) * 0.4;
            let fd = curl_fd(|x| potential_n(x, scale, gain, d0, &b), p, 1e-3);
            let cf = curl_noise(p, scale, gain, d0, Some(&b));
            assert!(
                (fd - cf).length() <= tol,
                "plane d {d}: fd {fd:?}, closed {cf:?}"
            );
            // A sphere of radius 2 round q: the boundary moves with the point.
            let x = q + *n * (2.0 + d);
            let fd = curl_fd(
                |y| potential_n(y, scale, gain, d0, &sphere(y, q, 2.0, true)),
                x,
                1e-3,
            );
            let cf = curl_noise(x, scale, gain, d0, Some(&sphere(x, q, 2.0, true)));
            assert!(
                (fd - cf).length() <= tol,
                "sphere d {d}: fd {fd:?}, closed {cf:?}"
            );
        }
    }
}

/// Fixed point within 2e-3·gain/scale of f32 (at the same, Fx-representable, inputs) for the
/// free and the bounded field (observed ≤ 6e-4·gain/scale).
#[test]
fn fixed_point_curl_noise_is_close_to_f32() {
    let mut worst = 0.0f32;
    for (i, (scale, gain)) in PAIRS.into_iter().enumerate() {
        let tol = 2e-3 * gain / scale;
        let (sx, gx, dx) = (Fx::from_f32(scale), Fx::from_f32(gain), Fx::ONE);
        let dirs: Vec<_> = directions(800 + i as u32, 100).take(50).collect();
        for (k, (n, q)) in dirs.iter().zip(test_points(900, 50, 30.0)).enumerate() {
            let d = (k as f32 + 0.5) / 50.0 * 1.2;
            let p = q + *n * d;
            let sph = sphere(p, q - *n * 2.0, 2.0, k % 2 == 0);
            for b in [None, Some(Boundary::plane(q, *n)), Some(sph)] {
                let bx = b.as_ref().map(Boundary::cast::<Fx>);
                let fx = curl_noise(p.cast::<Fx>(), sx, gx, dx, bx.as_ref()).to_f32();
                let bf = bx.as_ref().map(Boundary::cast::<f32>);
                // The same inputs: scale and gain as Fx holds them (0.2 is not exact, and at
                // 150 lattice cells from the origin that alone moves x/scale by 2e-3 cells).
                let (sf, gf) = (sx.to_f32(), gx.to_f32());
                let fl = curl_noise(p.cast::<Fx>().to_f32(), sf, gf, 1.0, bf.as_ref());
                worst = worst.max((fx - fl).length() / (gain / scale));
                assert!((fx - fl).length() <= tol, "Fx {fx:?} vs f32 {fl:?} ({b:?})");
            }
        }
    }
    assert!(worst > 0.0, "fixed point is not f32");
}

/// advect: V = V_l + s0·guide, x* = x + V·Δt; the baselines: P(x), and a fresh uniform
/// vector in [−gain, gain]³ per insect and step.
#[test]
fn advect_sums_the_fields_and_takes_an_euler_step() {
    let p = WangParams::<f32>::default();
    let state = WangState::new(Vec3::new(1.0, 2.0, 3.0));
    let guide = Vec3::new(0.0, 0.6, 0.8);
    let mut frame = AdvectFrame::new(guide);
    let moved = advect(&state, &frame, &p, ctx(0, 0)).unwrap();
    let v = curl_force(state.pos, p.scale, p.gain) + guide * p.s0;
    assert_eq!(moved.vel, v);
    assert_eq!(moved.pos, state.pos + v * p.dt);
    // A boundary within d0 changes V_l, not the sum rule.
    let b = Boundary::plane(Vec3::new(0.0, 1.8, 0.0), Vec3::up());
    frame.boundary = Some(b);
    let moved = advect(&state, &frame, &p, ctx(0, 0)).unwrap();
    let vl = curl_noise(state.pos, p.scale, p.gain, p.d0, Some(&b));
    assert_eq!(moved.vel, vl + guide * p.s0);
    // Perlin baseline.
    let pp = WangParams {
        noise: NOISE_PERLIN,
        ..p
    };
    let moved = advect(&state, &AdvectFrame::new(Vec3::zero()), &pp, ctx(0, 0)).unwrap();
    assert_eq!(moved.vel, perlin_velocity(state.pos, p.scale, p.gain));
    // Random baseline: in the cube, different per step and insect, mean ≈ 0, spread ≈ uniform.
    let pr = WangParams {
        noise: NOISE_RANDOM,
        ..p
    };
    let (mut sum, mut sq) = (Vec3::<f32>::zero(), 0.0f32);
    let n = 4000;
    for step in 0..n {
        let m = advect(&state, &AdvectFrame::new(Vec3::zero()), &pr, ctx(3, step)).unwrap();
        assert_eq!(m.vel, random_velocity(p.gain, ctx(3, step)));
        for c in [m.vel.x, m.vel.y, m.vel.z] {
            assert!(c.abs() < p.gain);
            sq += c * c;
        }
        sum += m.vel;
    }
    let mean = sum * (1.0 / n as f32);
    assert!(mean.length() < 0.03 * p.gain, "mean {mean:?}");
    // Var of U(−g, g) is g²/3.
    let var = sq / (3.0 * n as f32);
    assert!(
        (var / (p.gain * p.gain / 3.0) - 1.0).abs() < 0.06,
        "var {var}"
    );
    assert_ne!(
        random_velocity::<f32>(1.0, ctx(3, 1)),
        random_velocity(1.0, ctx(4, 1))
    );
}

/// Phototaxis: the bias u_photo·unit(lamp − x) applies in about p_photo of the steps.
#[test]
fn phototaxis_bias_rate_is_p_photo() {
    let p = WangParams::<f32>::phototaxis();
    let state = WangState::new(Vec3::new(0.0, 1.0, 0.0));
    let mut frame = AdvectFrame::new(Vec3::new(1.0, 0.0, 0.0));
    let plain = advect(&state, &frame, &p, ctx(0, 0)).unwrap().vel;
    frame.lamp = Some(Vec3::new(0.0, 6.5, 0.0));
    let n = 20_000;
    let mut biased = 0;
    for step in 0..n {
        let v = advect(&state, &frame, &p, ctx(5, step)).unwrap().vel;
        if v != plain {
            biased += 1;
            assert!((v - plain - Vec3::up() * p.u_photo).length() < 1e-5);
        }
    }
    let rate = biased as f32 / n as f32;
    assert!((rate - 0.05).abs() < 0.005, "rate {rate}");
    // p_photo = 0: never; no lamp: never.
    let off = WangParams { p_photo: 0.0, ..p };
    assert!((0..1000).all(|s| advect(&state, &frame, &off, ctx(5, s)).unwrap().vel == plain));
}

fn close(id: u32, pos: Vec3<f32>) -> Close<f32> {
    Close { id, pos }
}

/// separate: the half-deficit push from each close neighbour, counted, summed in id order
/// (the same bits for any neighbour order), self and far neighbours ignored, d_min = 0 off.
#[test]
fn separate_pushes_apart_in_jacobi_form() {
    let p = WangParams::<f32>::default(); // d_min 0.1
    let moved = WangState {
        pos: Vec3::new(1.0, 1.0, 1.0),
        vel: Vec3::new(0.5, 0.0, 0.0),
    };
    let list = [
        close(4, moved.pos + Vec3::new(0.06, 0.0, 0.0)),
        close(9, moved.pos + Vec3::new(0.0, -0.03, 0.04)),
        close(2, moved.pos + Vec3::new(0.02, 0.02, 0.02)),
        close(11, moved.pos + Vec3::new(0.2, 0.0, 0.0)), // too far
        close(0, moved.pos),                             // itself (ctx.agent 0): ignored
    ];
    let frame: SeparateFrame<f32, 8> = SeparateFrame {
        neighbours: list.iter().copied().collect(),
    };
    let (next, pushes) = separate(&moved, &frame, &p, ctx(0, 3)).unwrap();
    assert_eq!(pushes, 3);
    assert_eq!(next.vel, moved.vel);
    let mut want = moved.pos;
    for c in [list[2], list[0], list[1]] {
        let diff = moved.pos - c.pos;
        let d = diff.length();
        want += diff * ((p.d_min - d) * 0.5 / d);
    }
    assert!((next.pos - want).length() < 1e-6);
    // Every order of the list: the same bits.
    let orders: [[usize; 5]; 4] = [
        [4, 3, 2, 1, 0],
        [1, 0, 2, 4, 3],
        [2, 4, 0, 3, 1],
        [3, 1, 4, 0, 2],
    ];
    for order in orders {
        let f: SeparateFrame<f32, 8> = SeparateFrame {
            neighbours: order.iter().map(|&i| list[i]).collect(),
        };
        assert_eq!(separate(&moved, &f, &p, ctx(0, 3)).unwrap(), (next, 3));
    }
    // The same in fixed point.
    let px = p.cast::<Fx>();
    let base = separate(&moved.cast::<Fx>(), &frame.cast(), &px, ctx(0, 3)).unwrap();
    assert_eq!(base.1, 3);
    assert!((base.0.pos.to_f32() - next.pos).length() < 2e-4);
    for order in orders {
        let f: SeparateFrame<f32, 8> = SeparateFrame {
            neighbours: order.iter().map(|&i| list[i]).collect(),
        };
        assert_eq!(
            separate(&moved.cast::<Fx>(), &f.cast(), &px, ctx(0, 3)).unwrap(),
            base
        );
    }
    // d_min = 0 disables MDE.
    let off = WangParams { d_min: 0.0, ..p };
    assert_eq!(
        separate(&moved, &frame, &off, ctx(0, 3)).unwrap(),
        (moved, 0)
    );
    // A pair exactly d_min apart is not pushed.
    let f: SeparateFrame<f32, 8> = SeparateFrame {
        neighbours: [close(1, moved.pos + Vec3::new(0.0, 0.0, 0.125))]
            .into_iter()
            .collect(),
    };
    let p8 = WangParams { d_min: 0.125, ..p };
    assert_eq!(separate(&moved, &f, &p8, ctx(0, 3)).unwrap(), (moved, 0));
}

/// Both insects of a pair, each running separate with the other as its neighbour: pushed
/// apart symmetrically, to d_min (a lone pair), also when they coincide (a random direction
/// shared by both, + for the lower id), in f32 and fixed point.
#[test]
fn pairs_separate_symmetrically_even_when_coincident() {
    fn pair<S: Scalar>(a: Vec3<f32>, b: Vec3<f32>, step: u32) -> (Vec3<f32>, Vec3<f32>) {
        let p = WangParams::<S>::default();
        let (sa, sb) = (WangState::new(a.cast::<S>()), WangState::new(b.cast::<S>()));
        let fa: SeparateFrame<S, 8> = SeparateFrame {
            neighbours: [Close { id: 3, pos: sb.pos }].into_iter().collect(),
        };
        let fb: SeparateFrame<S, 8> = SeparateFrame {
            neighbours: [Close { id: 7, pos: sa.pos }].into_iter().collect(),
        };
        let (na, ka) = separate(&sa, &fa, &p, ctx(7, step)).unwrap();
        let (nb, kb) = separate(&sb, &fb, &p, ctx(3, step)).unwrap();
        assert_eq!((ka, kb), (1, 1));
        (na.pos.to_f32(), nb.pos.to_f32())
    }
    let x = Vec3::new(2.0, 3.0, 4.0);
    for (b, tol) in [
        (x + Vec3::new(0.03, -0.02, 0.01), 1e-6),
        (x, 1e-6),
        (x + Vec3::new(1e-5, 0.0, 0.0), 1e-5),
    ] {
        let (na, nb) = pair::<f32>(x, b, 11);
        let mid = (x + b) * 0.5;
        assert!(((na + nb) * 0.5 - mid).length() < tol, "centre moved");
        assert!(
            ((na - nb).length() - 0.1).abs() < 1e-5,
            "apart {}",
            (na - nb).length()
        );
    }
    // Coincident: the lower id (3, here b) moves along the pair direction, a opposite.
    let (na, nb) = pair::<f32>(x, x, 11);
    let u = step::pair_direction::<f32>(7, 3, 11);
    assert!((u.length() - 1.0).abs() < 1e-5);
    assert!((nb - x - u * 0.05).length() < 1e-6);
    assert!((na - x + u * 0.05).length() < 1e-6);
    // Another step, another direction.
    assert!((step::pair_direction::<f32>(7, 3, 12) - u).length() > 1e-3);
    // Fixed point: coincident, and too close for the squares (3e-3 m apart).
    for b in [
        x,
        x + Vec3::new(0.003, 0.0, 0.0),
        x + Vec3::new(0.0, 0.02, 0.0),
    ] {
        let (na, nb) = pair::<Fx>(x, b, 11);
        assert!(
            ((na - nb).length() - 0.1).abs() < 2e-3,
            "Fx apart {}",
            (na - nb).length()
        );
    }
}

/// Every input check names its field (and the entry's index).
#[test]
fn validation_errors_name_the_field() {
    let p = WangParams::<f32>::default();
    let s = WangState::new(Vec3::new(0.0, 0.0, 0.0));
    let ok = AdvectFrame::new(Vec3::new(0.0, 0.0, 1.0));
    let nan = Vec3::new(f32::NAN, 0.0, 0.0);
    let far = Vec3::new(0.0, 16_001.0, 0.0);
    let c = ctx(0, 0);
    let adv = |s: WangState<f32>, f: AdvectFrame<f32>| advect(&s, &f, &p, c);
    let nf = |field| Err(Error::NonFinite { field, index: None });
    let oor = |field| Err(Error::OutOfRange { field, index: None });
    assert_eq!(adv(WangState { pos: nan, ..s }, ok), nf("state.pos"));
    assert_eq!(adv(WangState { vel: far, ..s }, ok), oor("state.vel"));
    assert_eq!(
        adv(s, AdvectFrame::new(Vec3::new(0.0, 1.02, 0.0))),
        oor("frame.guide")
    );
    assert_eq!(adv(s, AdvectFrame::new(nan)), nf("frame.guide"));
    let plane = Boundary::plane(Vec3::zero(), Vec3::up());
    let with = |b: Boundary<f32>| AdvectFrame {
        boundary: Some(b),
        ..ok
    };
    assert_eq!(
        adv(
            s,
            with(Boundary {
                point: far,
                ..plane
            })
        ),
        oor("frame.boundary.point")
    );
    let short = Vec3::new(0.0, 0.98, 0.0);
    assert_eq!(
        adv(
            s,
            with(Boundary {
                normal: short,
                ..plane
            })
        ),
        oor("frame.boundary.normal")
    );
    assert_eq!(
        adv(
            s,
            with(Boundary {
                curvature: -0.1,
                ..plane
            })
        ),
        oor("frame.boundary.curvature")
    );
    assert_eq!(
        adv(
            s,
            with(Boundary {
                curvature: 101.0,
                ..plane
            })
        ),
        oor("frame.boundary.curvature")
    );
    assert_eq!(
        adv(
            s,
            with(Boundary {
                curvature: f32::INFINITY,
                ..plane
            })
        ),
        nf("frame.boundary.curvature")
    );
    assert_eq!(
        adv(
            s,
            with(Boundary {
                axis: short,
                ..plane
            })
        ),
        oor("frame.boundary.axis")
    );
    assert!(
        adv(
            s,
            with(Boundary {
                axis: Vec3::new(1.0, 0.0, 0.0),
                curvature: 5.0,
                ..plane
            })
        )
        .is_ok()
    );
    assert_eq!(
        adv(
            s,
            AdvectFrame {
                lamp: Some(nan),
                ..ok
            }
        ),
        nf("frame.lamp")
    );
    let bad = WangParams { d0: -1.0, ..p };
    assert_eq!(
        advect(&s, &ok, &bad, c),
        Err(Error::BadParam { field: "d0" })
    );

    let sep = |m: WangState<f32>, list: &[Close<f32>]| {
        let f: SeparateFrame<f32, 8> = SeparateFrame {
            neighbours: list.iter().copied().collect(),
        };
        separate(&m, &f, &p, c)
    };
    assert_eq!(
        sep(WangState { pos: far, ..s }, &[]),
        Err(Error::OutOfRange {
            field: "moved.pos",
            index: None
        })
    );
    assert_eq!(
        sep(WangState { vel: nan, ..s }, &[]),
        Err(Error::NonFinite {
            field: "moved.vel",
            index: None
        })
    );
    assert_eq!(
        sep(s, &[close(1, Vec3::zero()), close(2, nan)]),
        Err(Error::NonFinite {
            field: "frame.neighbours.pos",
            index: Some(1)
        })
    );
    assert_eq!(
        sep(s, &[close(1, Vec3::zero()), close(2, far), close(1, far)]),
        Err(Error::OutOfRange {
            field: "frame.neighbours.pos",
            index: Some(1)
        })
    );
    assert_eq!(
        sep(
            s,
            &[
                close(1, Vec3::zero()),
                close(2, Vec3::zero()),
                close(1, Vec3::zero())
            ]
        ),
        Err(Error::Inconsistent {
            field: "frame.neighbours.id",
            index: Some(2)
        })
    );
}

/// Fixed-point phases close to f32 over random valid requests.
#[test]
fn fixed_point_phases_track_f32() {
    for (i, params) in [
        WangParams::<f32>::two_blocks(),
        WangParams::aggregation(),
        WangParams::phototaxis(),
        WangParams::locusts(),
    ]
    .into_iter()
    .enumerate()
    {
        let px = params.cast::<Fx>();
        // The f32 run gets the parameters as Fx holds them.
        let params = px.cast::<f32>();
        let tol = 2e-3 * params.gain / params.scale;
        let pts: Vec<_> = test_points(1000 + i as u32, 100, 50.0).collect();
        let dirs: Vec<_> = directions(1100 + i as u32, 300).take(100).collect();
        for (k, (q, n)) in pts.iter().zip(&dirs).enumerate() {
            let state = WangState::new(*q).cast::<Fx>().cast::<f32>();
            let mut frame = AdvectFrame::new(*n * frac(q.x));
            if k % 2 == 0 {
                frame.boundary = Some(Boundary::plane(*q - *n * frac(q.y), *n));
            }
            frame.lamp = Some(Vec3::new(0.0, 6.5, 0.0));
            let frame = frame.cast::<Fx>().cast::<f32>();
            let c = ctx(k as u32, 17);
            let f = advect(&state, &frame, &params, c).unwrap();
            let x = advect(&state.cast(), &frame.cast(), &px, c).unwrap();
            assert!(
                (x.vel.to_f32() - f.vel).length() <= tol,
                "{k}: {:?} vs {:?}",
                x.vel,
                f.vel
            );
            assert!((x.pos.to_f32() - f.pos).length() <= tol * params.dt + 1e-4);
        }
    }
}

mod props {
    use super::*;
    use proptest::prelude::*;

    const SPECIAL: [f32; 8] = [
        f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
        1e30,
        -1e30,
        16_000.0,
        -16_000.0,
        0.0,
    ];

    fn num(normal: core::ops::Range<f32>) -> impl Strategy<Value = f32> {
        prop_oneof![
            30 => normal,
            1 => proptest::num::f32::ANY,
            1 => prop::sample::select(SPECIAL.to_vec()),
        ]
    }

    fn vec(span: f32) -> impl Strategy<Value = Vec3<f32>> {
        [num(-span..span), num(-span..span), num(-span..span)]
            .prop_map(|[x, y, z]| Vec3::new(x, y, z))
    }

    fn unitish() -> impl Strategy<Value = Vec3<f32>> {
        let units = [
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(0.6, 0.0, -0.8),
            Vec3::zero(),
        ];
        prop_oneof![1 => vec(2.0), 3 => prop::sample::select(units.to_vec())]
    }

    fn boundary() -> impl Strategy<Value = Boundary<f32>> {
        (vec(20.0), unitish(), num(0.0..10.0), unitish()).prop_map(
            |(point, normal, curvature, axis)| Boundary {
                point,
                normal,
                curvature,
                axis,
            },
        )
    }

    fn params() -> impl Strategy<Value = WangParams<f32>> {
        (0usize..4, 0u8..4, num(0.0..0.3), num(0.0..1.0)).prop_map(|(i, noise, d_min, p_photo)| {
            let base = [
                WangParams::two_blocks(),
                WangParams::aggregation(),
                WangParams::phototaxis(),
                WangParams::locusts(),
            ][i];
            WangParams {
                noise,
                d_min,
                p_photo,
                u_photo: 0.5,
                ..base
            }
        })
    }

    fn ids() -> impl Strategy<Value = u32> {
        prop_oneof![0u32..6, any::<u32>()]
    }

    fn total<S: Scalar>(
        p: &WangParams<S>,
        state: &WangState<S>,
        frame: &AdvectFrame<S>,
        near: &SeparateFrame<S, 8>,
        c: StepCtx,
    ) {
        if let Ok(moved) = advect(state, frame, p, c) {
            assert_eq!(moved.pos, state.pos + moved.vel * p.dt);
        }
        if let Ok((next, pushes)) = separate(state, near, p, c) {
            assert!(usize::from(pushes) <= near.neighbours.len());
            assert_eq!(next.vel, state.vel);
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(512))]
        /// Raw f32 (NaN, ±inf, huge included) in every field, then the same through
        /// `Fx::from_f32`: `Ok` or `Err`, never a panic.
        #[test]
        fn any_input_gives_ok_or_err_never_a_panic(
            p in params(),
            pos in vec(20.0),
            vel in vec(5.0),
            guide in unitish(),
            b in prop::option::of(boundary()),
            lamp in prop::option::of(vec(20.0)),
            near in prop::collection::vec((ids(), vec(0.2)), 0..=8),
            agent in ids(),
            step in any::<u32>(),
        ) {
            let state = WangState { pos, vel };
            let frame = AdvectFrame { guide, boundary: b, lamp };
            let near: SeparateFrame<f32, 8> = SeparateFrame {
                neighbours: near.into_iter().map(|(id, d)| Close { id, pos: pos + d }).collect(),
            };
            let c = StepCtx { seed: 3, agent, step };
            total(&p, &state, &frame, &near, c);
            total(&p.cast::<Fx>(), &state.cast(), &frame.cast(), &near.cast(), c);
        }
    }
}
