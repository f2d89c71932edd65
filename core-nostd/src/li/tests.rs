//! li2015 spec §4: L-T1 and L-T3 to L-T6, and bad input.

use super::density::Density;
use super::sampler::Table;
use super::waypoint::{Screening, Waypoint, accept, direction, next_waypoint};
use crate::rand;
use crate::{Error, StepCtx, Vec3};

fn v(x: f32, y: f32, z: f32) -> Vec3<f32> {
    Vec3::new(x, y, z)
}

fn ctx(agent: u32, step: u32) -> StepCtx {
    StepCtx {
        seed: 2015,
        agent,
        step,
    }
}

/// L-T1: 10⁵ draws of a skewed 32-bin table follow the table's own CDF (Kolmogorov-Smirnov
/// D < 0.01), and every draw lies in [lo, hi].
#[test]
fn table_draws_follow_its_cdf() {
    let counts: [u32; 32] = core::array::from_fn(|k| ((32 - k) * (32 - k)) as u32 + (k % 3) as u32);
    let t = Table::<f32, 32>::from_counts(0.002, 0.09, &counts).unwrap();
    assert_eq!(t.cdf[31], 1.0);
    let mut draws: Vec<f32> = (0..100_000)
        .map(|i| t.sample(rand::unit(ctx(i, 0), 0)))
        .collect();
    assert!(draws.iter().all(|&x| (0.002..=0.09).contains(&x)));
    draws.sort_by(f32::total_cmp);
    let n = draws.len() as f64;
    let d = draws
        .iter()
        .enumerate()
        .map(|(i, &x)| {
            let f = f64::from(t.cdf_at(x));
            (f - i as f64 / n).abs().max((f - (i + 1) as f64 / n).abs())
        })
        .fold(0.0, f64::max);
    assert!(d < 0.01, "KS D = {d}");
    // The ends and bad input.
    assert_eq!(
        (t.sample(0.0), t.sample(f32::NAN), t.sample(1.0)),
        (0.002, 0.002, 0.09)
    );
    assert_eq!(
        Table::<f32, 2>::from_counts(1.0, 1.0, &[1, 1]),
        Err(Error::BadParam { field: "hi" })
    );
    assert_eq!(
        Table::<f32, 2>::from_counts(0.0, 1.0, &[0, 0]),
        Err(Error::BadParam { field: "counts" })
    );
}

/// L-T3: direction(d, θ) is a unit vector at angle |θ| from d̂ (cosine within 1e-6), its
/// azimuth is uniform (χ² over 8 sectors, 8,000 draws, below the p = 0.01 quantile 18.48),
/// and without a direction it is uniform on the sphere.
#[test]
fn direction_turns_by_theta_at_a_uniform_azimuth() {
    let d = v(0.3, -1.2, 0.7);
    let n = d.normalized().unwrap();
    let mut sectors = [0u32; 8];
    // A fixed reference perpendicular to d̂ to measure the azimuth against.
    let e1 = n.cross(v(1.0, 0.0, 0.0)).normalized().unwrap();
    let e2 = n.cross(e1);
    for i in 0..8000u32 {
        let theta = rand::angle(ctx(i, 1), 0, 3.0f32);
        let phi = rand::angle(ctx(i, 2), 0, core::f32::consts::PI);
        let o = direction(d, theta, phi, 0.0);
        assert!((o.length() - 1.0).abs() < 1e-6, "{o:?}");
        assert!(
            (o.dot(n) - theta.abs().cos()).abs() < 1e-6,
            "θ {theta}: {}",
            o.dot(n)
        );
        let side = o - n * o.dot(n);
        if side.length() > 1e-3 {
            let a = side.dot(e2).atan2(side.dot(e1)) + core::f32::consts::PI;
            sectors[((a / core::f32::consts::TAU * 8.0) as usize).min(7)] += 1;
        }
    }
    let total: u32 = sectors.iter().sum();
    let e = f64::from(total) / 8.0;
    let chi2: f64 = sectors
        .iter()
        .map(|&c| (f64::from(c) - e).powi(2) / e)
        .sum();
    assert!(chi2 < 18.48, "χ² {chi2} over {sectors:?}");

    // d = 0: uniform on the sphere (each axis's mean ≈ 0, mean z² ≈ 1/3).
    let mut sum = v(0.0, 0.0, 0.0);
    let mut zz = 0.0f32;
    for i in 0..20_000u32 {
        let z = rand::angle(ctx(i, 3), 0, 1.0f32);
        let phi = rand::angle(ctx(i, 4), 0, core::f32::consts::PI);
        let o = direction(v(0.0, 0.0, 0.0), 0.7, phi, z);
        assert!((o.length() - 1.0).abs() < 1e-5);
        sum += o;
        zz += o.y * o.y;
    }
    let mean = sum * (1.0 / 20_000.0);
    assert!(mean.length() < 0.02, "{mean:?}");
    assert!(
        (zz / 20_000.0 - 1.0 / 3.0).abs() < 0.01,
        "{}",
        zz / 20_000.0
    );
}

fn uniform_world() -> ([u8; 64], Table<f32, 8>, Table<f32, 8>) {
    let lengths = Table::from_counts(0.01, 0.03, &[1; 8]).unwrap();
    let turns = Table::from_counts(0.0, 0.6, &[1; 8]).unwrap();
    ([100u8; 64], lengths, turns)
}

/// L-T4: the waypoint is unchanged while ‖x − g‖ > ε; on arrival ‖g − s‖ = l ∈ the length
/// table's range, s = x, and the turn from the previous direction is within the turn table's.
#[test]
fn algorithm_1_proposes_only_on_arrival() {
    let (w, lengths, turns) = uniform_world();
    let density = Density::new(v(0.0, 0.0, 0.0), 0.25, [4, 4, 4], &w).unwrap();
    let params = Screening::<f32>::default();
    let current = Waypoint {
        waypoint: v(0.6, 0.5, 0.5),
        seg_start: v(0.3, 0.5, 0.5),
    };
    // Not arrived: 0.01 from the waypoint (ε = 0.00148).
    let pos = v(0.59, 0.5, 0.5);
    let next = next_waypoint(
        pos,
        &current,
        &lengths,
        &turns,
        &density,
        &params,
        ctx(0, 0),
    )
    .unwrap();
    assert_eq!(
        (next.waypoint, next.proposals, next.accepted),
        (current, 0, false)
    );
    // Arrived.
    for step in 0..200 {
        let pos = v(0.6, 0.5, 0.5005);
        let next = next_waypoint(
            pos,
            &current,
            &lengths,
            &turns,
            &density,
            &params,
            ctx(0, step),
        )
        .unwrap();
        assert!(
            next.accepted && next.proposals == 1,
            "uniform density: always accepted"
        );
        assert_eq!(next.waypoint.seg_start, pos);
        let leg = next.waypoint.waypoint - pos;
        assert!(
            (0.01 - 1e-6..=0.03 + 1e-6).contains(&leg.length()),
            "{}",
            leg.length()
        );
        let came = (pos - current.seg_start).normalized().unwrap();
        let turn = (leg.normalized().unwrap().dot(came))
            .clamp(-1.0, 1.0)
            .acos();
        assert!(turn <= 0.6 + 1e-3, "turn {turn}");
    }
}

/// L-T5: the acceptance is min(1, w_g/w_x) (10⁵ trials within ±0.005), never into a zero
/// cell, and from a zero cell exactly into the non-zero ones.
#[test]
fn metropolis_hastings_acceptance() {
    for (w_x, w_g) in [(200u8, 50u8), (90, 60), (255, 1), (40, 40), (10, 200)] {
        let hits = (0..100_000u32)
            .filter(|&i| accept(w_x, w_g, rand::unit::<f32>(ctx(i, 9), 0)))
            .count();
        let want = (f64::from(w_g) / f64::from(w_x)).min(1.0);
        let got = hits as f64 / 1e5;
        assert!((got - want).abs() < 0.005, "{w_x} → {w_g}: {got} vs {want}");
    }
    assert!((0..1000u32).all(|i| !accept(77, 0, rand::unit::<f32>(ctx(i, 10), 0))));
    assert!(accept(0, 1, 0.999f32) && !accept(0, 0, 0.001f32));
}

/// The grid of L-T6: 16³ cells over the 0.91 m cube, a Gaussian of σ = 0.12 m at the centre
/// scaled to 255 and rounded (the far corners round to 0).
fn gaussian_grid() -> (Vec<u8>, f32) {
    let cell = 0.91 / 16.0;
    let w = (0..16 * 16 * 16)
        .map(|i| {
            let c = [i % 16, (i / 16) % 16, i / 256].map(|k| (k as f32 + 0.5) * cell - 0.455);
            let r2 = c.iter().map(|x| x * x).sum::<f32>();
            (255.0 * (-r2 / (2.0 * 0.12 * 0.12)).exp()).round() as u8
        })
        .collect();
    (w, cell)
}

/// The waypoint chains of L-T6 on `grid` (isotropic proposals: s = x at every step), their
/// cell visits after the first 1,000 steps: 200 chains × 8,000 steps from near the centre.
fn chain_visits(grid: &Density<'_, f32>, proposals: u8) -> Vec<u64> {
    let lengths = Table::<f32, 16>::from_counts(0.0, 0.06, &[1; 16]).unwrap();
    let turns = Table::<f32, 4>::from_counts(0.0, 0.1, &[1; 4]).unwrap();
    let params = Screening {
        eps: 0.0,
        proposals,
        ..Screening::default()
    };
    let mut visits = vec![0u64; 16 * 16 * 16];
    for chain in 0..200u32 {
        let u = |k: u32| rand::unit::<f32>(ctx(chain, k), 77);
        let mut x = v(0.355 + 0.2 * u(0), 0.355 + 0.2 * u(1), 0.355 + 0.2 * u(2));
        for step in 0..8000u32 {
            let here = Waypoint {
                waypoint: x,
                seg_start: x,
            };
            let c = StepCtx {
                seed: 6,
                agent: chain,
                step,
            };
            x = next_waypoint(x, &here, &lengths, &turns, grid, &params, c)
                .unwrap()
                .waypoint
                .waypoint;
            if step >= 1000 {
                let [i, j, k] = grid.cell_of(x).expect("inside").map(usize::from);
                visits[i + 16 * (j + 16 * k)] += 1;
            }
        }
    }
    visits
}

/// Total variation between visit counts and weights, both normalised.
fn total_variation(visits: &[u64], w: &[u8]) -> f64 {
    let n: u64 = visits.iter().sum();
    let total: f64 = w.iter().map(|&x| f64::from(x)).sum();
    0.5 * visits
        .iter()
        .zip(w)
        .map(|(&c, &wc)| (c as f64 / n as f64 - f64::from(wc) / total).abs())
        .sum::<f64>()
}

/// L-T6: with isotropic proposals the waypoint chain's law is the density's: 200 chains ×
/// 8,000 steps on the Gaussian grid come within total variation 0.08 of the normalised
/// weights (spec prototype 0.05-0.07; measured 0.03), in standard Metropolis-Hastings
/// (K = 1) and in the paper's resampling mode (K = 32). Without the screening (a uniform
/// grid) the same chains are far from it (over 0.5; measured 0.76).
#[test]
fn the_waypoint_chain_samples_the_density() {
    let (w, cell) = gaussian_grid();
    let gaussian = Density::new(v(0.0, 0.0, 0.0), cell, [16, 16, 16], &w).unwrap();
    for proposals in [1u8, 32] {
        let tv = total_variation(&chain_visits(&gaussian, proposals), &w);
        eprintln!("K = {proposals}: total variation {tv:.4}");
        assert!(tv <= 0.08, "K = {proposals}: total variation {tv}");
    }
    let flat = vec![1u8; w.len()];
    let uniform = Density::new(v(0.0, 0.0, 0.0), cell, [16, 16, 16], &flat).unwrap();
    let tv = total_variation(&chain_visits(&uniform, 1), &w);
    eprintln!("no screening: total variation {tv:.4}");
    assert!(tv > 0.5, "the control must be far from the target: {tv}");
}

/// Bad input: a typed error naming the field, never a panic.
#[test]
fn bad_input_is_refused() {
    let (w, lengths, turns) = uniform_world();
    assert_eq!(
        Density::new(v(0.0, 0.0, 0.0), 0.25, [4, 4, 3], &w),
        Err(Error::Inconsistent {
            field: "weights",
            index: None
        })
    );
    assert_eq!(
        Density::<f32>::new(v(0.0, 0.0, 0.0), 0.0, [4, 4, 4], &w),
        Err(Error::BadParam { field: "cell" })
    );
    // A table built by hand with no bins: draws and the CDF stay total.
    let empty = Table::<f32, 4> {
        lo: 0.0,
        hi: 1.0,
        cdf: heapless::Vec::new(),
    };
    assert_eq!(empty.validate("t"), Err(Error::BadParam { field: "t" }));
    assert_eq!((empty.sample(0.5), empty.cdf_at(0.5)), (1.0, 1.0));
    let density = Density::new(v(0.0, 0.0, 0.0), 0.25, [4, 4, 4], &w).unwrap();
    assert_eq!(density.at(v(-0.01, 0.5, 0.5)), 0);
    assert_eq!(density.at(v(f32::NAN, 0.5, 0.5)), 0);
    assert_eq!(density.at(v(0.99, 0.99, 0.99)), 100);
    assert_eq!(density.at(v(1.0, 0.5, 0.5)), 0);
    let here = Waypoint::default();
    let params = Screening::<f32>::default();
    let run = |pos: Vec3<f32>, p: &Screening<f32>| {
        next_waypoint(pos, &here, &lengths, &turns, &density, p, ctx(0, 0))
    };
    assert_eq!(
        run(v(f32::NAN, 0.0, 0.0), &params),
        Err(Error::non_finite("pos"))
    );
    let zero = Screening {
        proposals: 0,
        ..params
    };
    assert_eq!(
        run(v(0.0, 0.0, 0.0), &zero),
        Err(Error::BadParam { field: "proposals" })
    );
}

/// Outside the grid every proposal is a zero cell: the insect holds where it is after K
/// proposals (and keeps its segment start).
#[test]
fn an_insect_with_nowhere_to_go_holds() {
    let (w, lengths, turns) = uniform_world();
    let density = Density::new(v(5.0, 5.0, 5.0), 0.25, [4, 4, 4], &w).unwrap();
    let params = Screening::<f32>::default();
    let here = Waypoint {
        waypoint: v(0.0, 0.0, 0.0),
        seg_start: v(-0.1, 0.0, 0.0),
    };
    let next = next_waypoint(
        v(0.0, 0.0, 0.0),
        &here,
        &lengths,
        &turns,
        &density,
        &params,
        ctx(3, 3),
    )
    .unwrap();
    assert_eq!((next.proposals, next.accepted), (32, false));
    assert_eq!(next.waypoint.waypoint, v(0.0, 0.0, 0.0));
    // K = 32 rejections reversed the heading an even number of times: the next proposal
    // turns from the heading it came with.
    assert_eq!(next.waypoint.seg_start, v(-0.1, 0.0, 0.0));
    // With K odd, from the reversed heading.
    let odd = Screening::<f32> {
        proposals: 31,
        ..params
    };
    let next = next_waypoint(
        v(0.0, 0.0, 0.0),
        &here,
        &lengths,
        &turns,
        &density,
        &odd,
        ctx(3, 3),
    )
    .unwrap();
    assert_eq!((next.proposals, next.accepted), (31, false));
    assert_eq!(next.waypoint.seg_start, v(0.1, 0.0, 0.0));
}

/// The same code in fixed point: a proposal from an arrived insect lies within the length
/// table's range and its cell, and the same inputs give the same bits.
#[cfg(feature = "fixed")]
#[test]
fn fixed_point_proposes_within_the_tables() {
    use crate::{Fx, Scalar};
    let f = Fx::from_f32;
    let lengths = Table::<Fx, 8>::from_counts(f(0.01), f(0.03), &[1; 8]).unwrap();
    let turns = Table::<Fx, 8>::from_counts(f(0.0), f(0.6), &[1; 8]).unwrap();
    let w = [100u8; 64];
    let density = Density::new(Vec3::new(f(0.0), f(0.0), f(0.0)), f(0.25), [4, 4, 4], &w).unwrap();
    let params = Screening::<Fx>::default();
    let pos = Vec3::new(f(0.5), f(0.5), f(0.5));
    let here = Waypoint {
        waypoint: pos,
        seg_start: Vec3::new(f(0.4), f(0.5), f(0.5)),
    };
    for step in 0..100 {
        let next = next_waypoint(
            pos,
            &here,
            &lengths,
            &turns,
            &density,
            &params,
            ctx(1, step),
        )
        .unwrap();
        assert!(next.accepted);
        let l = (next.waypoint.waypoint - pos).length().to_f32();
        assert!((0.0099..=0.0301).contains(&l), "{l}");
        let again = next_waypoint(
            pos,
            &here,
            &lengths,
            &turns,
            &density,
            &params,
            ctx(1, step),
        )
        .unwrap();
        assert_eq!(next, again);
    }
}

// ---- the whole insect (spec §1.6) ----

use super::density::DensityGrid;
use super::waypoint::{SAMPLING_MESO, SAMPLING_RANDOM};
use super::{LiFrame, LiParams, LiState, preferred, step};
use crate::orca3d::{Neighbour, Surface};

type Frame = LiFrame<f32, 16, 4>;

/// The default parameters with 16-bin tables (lengths 5-40 mm, turns 0-0.8 rad) and the
/// Gaussian grid of L-T6 over the 0.91 m cube (origin at −0.455).
fn gaussian_params() -> LiParams<f32> {
    let (w, cell) = gaussian_grid();
    LiParams {
        lengths: Table::from_counts(0.005, 0.04, &[1; 16]).unwrap(),
        turns: Table::from_counts(0.0, 0.8, &[3, 2, 1, 1]).unwrap(),
        density: DensityGrid::new(v(-0.455, -0.455, -0.455), cell, [16, 16, 16], &w).unwrap(),
        ..LiParams::default()
    }
}

#[test]
fn default_parameters_are_valid_and_bad_data_is_named() {
    assert_eq!(LiParams::<f32>::default().validate(), Ok(()));
    let p = gaussian_params();
    assert_eq!(p.validate(), Ok(()));
    #[cfg(feature = "fixed")]
    assert_eq!(p.cast::<crate::Fx>().validate(), Ok(()));
    let bad = |f: &dyn Fn(&mut LiParams<f32>), field| {
        let mut q = p.clone();
        f(&mut q);
        assert_eq!(q.validate(), Err(Error::BadParam { field }));
    };
    bad(&|q| q.lengths.lo = -0.01, "lengths");
    bad(&|q| q.lengths.cdf[15] = 0.5, "lengths");
    bad(&|q| q.turns.hi = 4.0, "turns");
    bad(&|q| q.density.dims = [16, 16, 15], "density");
    bad(&|q| q.density.cell = 0.0, "density");
    bad(&|q| q.sampling = 3, "sampling");
    bad(&|q| q.proposals = 0, "proposals");
}

#[test]
fn the_preferred_velocity_is_v0_toward_the_waypoint_without_overshoot() {
    let x = v(0.0, 0.0, 0.0);
    assert_eq!(
        preferred(x, v(1.0, 0.0, 0.0), 0.15, 0.01),
        v(0.15, 0.0, 0.0)
    );
    // Closer than one step: exactly there after the step.
    let near = preferred(x, v(0.0, 0.001, 0.0), 0.15, 0.01);
    assert!((near.y - 0.1).abs() < 1e-6 && near.x == 0.0, "{near:?}");
    assert_eq!(preferred(x, x, 0.15, 0.01), v(0.0, 0.0, 0.0));
}

/// A lone insect: every waypoint it accepts is one table length away, in a visited cell; it
/// flies at most v0 and reaches each waypoint (so it proposes often); the same inputs give
/// the same bits.
#[test]
fn a_lone_insect_flies_from_waypoint_to_waypoint() {
    let p = gaussian_params();
    let mut s = LiState::at(v(0.0, 0.0, 0.0));
    let mut arrivals = 0;
    for k in 0..3000 {
        let c = ctx(3, k);
        let (next, d) = step(&s, &Frame::new(), &p, c).unwrap();
        assert_eq!(step(&s, &Frame::new(), &p, c).unwrap(), (next, d));
        assert!(next.vel.length() <= p.speed * 1.0001, "{:?}", next.vel);
        if d.accepted {
            arrivals += 1;
            let l = (next.waypoint - s.pos).length();
            assert!((0.0049..=0.0401).contains(&l), "{l}");
            assert!(p.density.view().unwrap().at(next.waypoint) > 0);
            assert_eq!((next.seg_start, next.age), (s.pos, 0));
        }
        s = next;
    }
    // Mean length 22.5 mm at 0.148 m/s: about 15 steps a segment.
    assert!((120..=260).contains(&arrivals), "{arrivals} arrivals");
}

/// A waypoint it cannot reach (1 mm from a wall, closer than the insect's radius: ORCA holds
/// it back) is given up after `patience` steps, and a new one is proposed.
#[test]
fn an_unreachable_waypoint_is_given_up_after_patience() {
    let p = LiParams {
        patience: 20,
        ..gaussian_params()
    };
    let mut s = LiState::at(v(0.0, 0.0, 0.0));
    s.waypoint = v(0.03, 0.0, 0.0);
    s.seg_start = v(-0.01, 0.0, 0.0);
    let mut frame = Frame::new();
    frame
        .surfaces
        .push(Surface {
            point: v(0.031, 0.0, 0.0),
            normal: v(-1.0, 0.0, 0.0),
        })
        .unwrap();
    for k in 0..20 {
        let (next, d) = step(&s, &frame, &p, ctx(0, k)).unwrap();
        assert_eq!(
            (d.proposals, next.waypoint, next.age),
            (0, s.waypoint, k as u16 + 1)
        );
        s = next;
    }
    let (next, d) = step(&s, &frame, &p, ctx(0, 20)).unwrap();
    assert!(d.proposals > 0 && next.age == 0, "{d:?}");
}

/// Two insects flying at each other through their waypoints: ORCA keeps them apart.
#[test]
fn two_insects_head_on_keep_their_distance() {
    let p = gaussian_params();
    let mut a = LiState::at(v(-0.1, 0.0, 0.0));
    let mut b = LiState::at(v(0.1, 0.0, 0.0));
    (a.waypoint, b.waypoint) = (v(0.2, 0.0, 0.0), v(-0.2, 0.0, 0.0));
    (a.seg_start, b.seg_start) = (v(-0.2, 0.0, 0.0), v(0.2, 0.0, 0.0));
    let sensed = |id, s: &LiState<f32>| {
        let mut f = Frame::new();
        f.neighbours
            .push(Neighbour {
                id,
                pos: s.pos,
                vel: s.vel,
            })
            .unwrap();
        f
    };
    for k in 0..150 {
        let (na, _) = step(&a, &sensed(1, &b), &p, ctx(0, k)).unwrap();
        let (nb, _) = step(&b, &sensed(0, &a), &p, ctx(1, k)).unwrap();
        (a, b) = (na, nb);
        assert!((a.pos - b.pos).length() >= 2.0 * p.radius, "step {k}");
    }
}

/// Fig. 4's other methods: random waypoints are uniform in the grid's box; mesoscopic ones
/// go anywhere inside the grid, zero cells included.
#[test]
fn random_and_mesoscopic_sampling() {
    let mut p = gaussian_params();
    p.sampling = SAMPLING_RANDOM;
    let here = LiState::at(v(0.0, 0.0, 0.0));
    let n = 4000;
    let mut mean = [0.0f64; 3];
    for k in 0..n {
        let (s, d) = step(&here, &Frame::new(), &p, ctx(k, 0)).unwrap();
        assert!(d.accepted && d.proposals == 1);
        for (m, c) in mean
            .iter_mut()
            .zip([s.waypoint.x, s.waypoint.y, s.waypoint.z])
        {
            assert!((-0.455..=0.455).contains(&c));
            *m += f64::from(c) / f64::from(n);
        }
    }
    assert!(mean.iter().all(|m| m.abs() < 0.02), "{mean:?}");
    p.sampling = SAMPLING_MESO;
    // At a corner cell of zero density, a mesoscopic proposal inside the grid is accepted.
    let corner = LiState::at(v(0.44, 0.44, 0.44));
    assert_eq!(p.density.view().unwrap().at(corner.pos), 0);
    let (s, d) = step(&corner, &Frame::new(), &p, ctx(0, 0)).unwrap();
    assert!(d.accepted, "{d:?}");
    assert!(p.density.view().unwrap().cell_of(s.waypoint).is_some());
}
