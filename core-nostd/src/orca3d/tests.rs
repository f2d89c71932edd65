//! Tests of 3D ORCA (ren2016 spec §4: R-T7 unit tests and RVO2-3D conformance, R-T8
//! collision-freedom; LP3 against a brute-force optimum; obstacles; validation).

extern crate std;
use std::vec::Vec;

use proptest::prelude::*;

use super::*;
use crate::{Error, Fx, Scalar, Vec3};

/// A simulation of bodies heading for goals, every agent solving with the others as
/// neighbours (nearest first within `neighbor_dist`, at most `max_neighbors`: RVO2-3D's
/// `computeNeighbors`), all velocities updated, then all positions (RVO2-3D `doStep`).
struct Sim<S: Scalar> {
    bodies: Vec<Body<S>>,
    goals: Vec<Vec3<S>>,
    params: OrcaParams<S>,
    neighbor_dist: S,
    walls: Vec<Surface<S>>,
    infeasible: usize,
    /// Infeasible frames answered with a zero velocity.
    stopped: usize,
    /// Use RVO2-3D's kd-tree search (f32 only) instead of the brute-force sort.
    kd: bool,
}

impl<S: Scalar> Sim<S> {
    fn new(starts: &[Vec3<S>], goals: &[Vec3<S>], radius: S, params: OrcaParams<S>) -> Self {
        Sim {
            bodies: starts
                .iter()
                .map(|&pos| Body {
                    pos,
                    vel: Vec3::zero(),
                    radius,
                })
                .collect(),
            goals: goals.to_vec(),
            params,
            neighbor_dist: S::from_f32(15.0),
            walls: Vec::new(),
            infeasible: 0,
            stopped: 0,
            kd: false,
        }
    }

    /// RVO2-3D's neighbour list: others with `|p|² < neighbor_dist²`, sorted by `|p|²`
    /// (ties by index), the first `max_neighbors`.
    fn neighbours(&self, i: usize) -> Vec<Body<S>> {
        let me = self.bodies[i].pos;
        let range = self.neighbor_dist * self.neighbor_dist;
        let mut near: Vec<(S, usize)> = self
            .bodies
            .iter()
            .enumerate()
            .filter(|&(j, _)| j != i)
            .map(|(j, b)| ((me - b.pos).length_sq(), j))
            .filter(|&(d, _)| d < range)
            .collect();
        near.sort_by(|a, b| a.0.partial_cmp(&b.0).unwrap().then(a.1.cmp(&b.1)));
        near.truncate(usize::from(self.params.max_neighbors));
        near.iter().map(|&(_, j)| self.bodies[j]).collect()
    }

    /// Sphere.cc's preferred velocity: toward the goal, normalised when longer than 1.
    fn pref(&self, i: usize) -> Vec3<S> {
        let g = self.goals[i] - self.bodies[i].pos;
        if g.length_sq() > S::ONE {
            plane::div(g, g.length_sq().sqrt())
        } else {
            g
        }
    }

    fn step(&mut self) {
        let kd: Option<(KdTree, Vec<Vec3<f32>>)> = self.kd.then(|| {
            let pos: Vec<Vec3<f32>> = self.bodies.iter().map(|b| b.pos.to_f32()).collect();
            (KdTree::build(&pos), pos)
        });
        let new: Vec<Vec3<S>> = (0..self.bodies.len())
            .map(|i| {
                let walls: Vec<Surface<S>> = self
                    .walls
                    .iter()
                    .map(|w| Surface {
                        // The wall's point closest to the agent.
                        point: self.bodies[i].pos
                            - w.normal * w.normal.dot(self.bodies[i].pos - w.point),
                        normal: w.normal,
                    })
                    .collect();
                let neighbours = match &kd {
                    Some((tree, pos)) => tree
                        .neighbours(
                            pos,
                            i,
                            self.neighbor_dist.to_f32(),
                            usize::from(self.params.max_neighbors),
                        )
                        .into_iter()
                        .map(|j| self.bodies[j])
                        .collect(),
                    None => self.neighbours(i),
                };
                let out = solve::<S, 32>(
                    &self.bodies[i],
                    &neighbours,
                    &walls,
                    self.pref(i),
                    &self.params,
                )
                .unwrap();
                self.infeasible += usize::from(out.infeasible);
                self.stopped += usize::from(out.infeasible && out.velocity == Vec3::zero());
                out.velocity
            })
            .collect();
        for (b, v) in self.bodies.iter_mut().zip(new) {
            b.vel = v;
            b.pos += v * self.params.dt;
        }
    }

    fn min_distance(&self) -> f32 {
        let mut m = f32::INFINITY;
        for (i, a) in self.bodies.iter().enumerate() {
            for b in &self.bodies[i + 1..] {
                m = m.min((a.pos.to_f32() - b.pos.to_f32()).length());
            }
        }
        m
    }
}

fn params(tau: f32, dt: f32, max_speed: f32, fallback: Fallback) -> OrcaParams<f32> {
    OrcaParams {
        time_horizon: tau,
        dt,
        max_speed,
        max_neighbors: 10,
        fallback,
    }
}

/// R-T7: two agents head-on (a small lateral offset, point-symmetric), τ 2, Δt 0.1: no overlap,
/// both deviate, reciprocal (agent 1's velocity is exactly the negation of agent 0's), both
/// arrive.
#[test]
fn head_on_pair_deviates_symmetrically() {
    // Agent 1 is agent 0 reflected through the origin, start and goal.
    let (a, goal) = (Vec3::new(-5.0, 0.05, 0.0), Vec3::new(5.0, 0.05, 0.0));
    let b = -a;
    let mut sim = Sim::new(
        &[a, b],
        &[goal, -goal],
        0.5,
        params(2.0, 0.1, 1.5, Fallback::Lp4),
    );
    let mut lateral = [0.0f32; 2];
    for _ in 0..200 {
        sim.step();
        assert!(
            sim.min_distance() >= 2.0 * 0.5 * (1.0 - 1e-3),
            "{}",
            sim.min_distance()
        );
        let (v0, v1) = (sim.bodies[0].vel, sim.bodies[1].vel);
        assert!((v0 + v1).length() <= 1e-6, "not reciprocal: {v0:?} {v1:?}");
        lateral[0] = lateral[0].max((sim.bodies[0].pos.y - a.y).abs() + sim.bodies[0].pos.z.abs());
        lateral[1] = lateral[1].max((sim.bodies[1].pos.y - b.y).abs() + sim.bodies[1].pos.z.abs());
    }
    assert!(lateral[0] > 0.3 && lateral[1] > 0.3, "{lateral:?}");
    assert_eq!(sim.infeasible, 0);
    for (body, goal) in sim.bodies.iter().zip(&sim.goals) {
        assert!((body.pos - *goal).length() < 0.05, "{body:?} {goal:?}");
    }
}

/// An exactly collinear head-on pair (RVO2-3D divides by |w| = 0 there): finite velocities,
/// no overlap.
#[test]
fn exact_head_on_stays_finite() {
    let (a, b) = (Vec3::new(-3.0, 0.0, 0.0), Vec3::new(3.0, 0.0, 0.0));
    let mut sim = Sim::new(&[a, b], &[b, a], 0.5, params(2.0, 0.1, 1.5, Fallback::Lp4));
    for _ in 0..100 {
        sim.step();
        for body in &sim.bodies {
            body.vel.check("vel").unwrap();
        }
        assert!(sim.min_distance() >= 1.0 * (1.0 - 1e-3));
    }
}

/// `n` agents on a ring of radius `r` (a small out-of-plane offset), each heading for the
/// antipodal point: the starts and the goals.
fn ring(n: usize, r: f32) -> (Vec<Vec3<f32>>, Vec<Vec3<f32>>) {
    let starts: Vec<Vec3<f32>> = (0..n)
        .map(|k| {
            let a = k as f32 * core::f32::consts::TAU / n as f32;
            Vec3::new(r * a.cos(), 0.02 * (3.0 * a).sin(), r * a.sin())
        })
        .collect();
    let goals = starts.iter().map(|&p| -p).collect();
    (starts, goals)
}

/// R-T8: 16 agents on a ring swapping to antipodal points (a small out-of-plane offset),
/// LP4 fallback: no overlap after any step, all arrive.
#[test]
fn ring_swap_is_collision_free() {
    let (starts, goals) = ring(16, 8.0);
    let mut sim = Sim::new(&starts, &goals, 0.5, params(2.0, 0.1, 1.0, Fallback::Lp4));
    sim.params.max_neighbors = 15;
    let mut arrived_at = None;
    for step in 0..2000 {
        sim.step();
        let d = sim.min_distance();
        assert!(d >= 1.0 * (1.0 - 1e-3), "step {step}: overlap {d}");
        if sim
            .bodies
            .iter()
            .zip(&sim.goals)
            .all(|(b, g)| (b.pos - *g).length() < 0.1)
        {
            arrived_at = Some(step);
            break;
        }
    }
    assert!(arrived_at.is_some(), "not all arrived");
}

/// The paper's zero-velocity fallback (an infeasible program stops the insect) on rings of
/// 20-28 agents swapping sides, dense enough that programs become infeasible: the fallback
/// acts (infeasible frames counted, each answered with a zero velocity) and overlaps stay
/// shallow: within 10 % of the radii's sum (measured 2.8-7.0 %). It is not collision-free: a
/// stopped agent takes no share of the avoidance that ORCA's reciprocity gives it, so an
/// agent heading at it avoids only its own half (docs/models.md, "ORCA's infeasible
/// fallback"); LP4 is (the test above).
#[test]
fn ring_swap_zero_fallback_acts_and_overlaps_stay_shallow() {
    for n in [20, 24, 28] {
        let (starts, goals) = ring(n, 5.0);
        let mut sim = Sim::new(
            &starts,
            &goals,
            0.5,
            params(2.0, 0.1, 1.0, Fallback::ZeroVelocity),
        );
        let mut closest = f32::INFINITY;
        for _ in 0..400 {
            sim.step();
            closest = closest.min(sim.min_distance());
        }
        assert!(sim.infeasible > 0, "n {n}: the fallback never acted");
        assert_eq!(
            sim.stopped, sim.infeasible,
            "n {n}: an infeasible agent moved"
        );
        assert!(
            closest >= 0.9,
            "n {n}: overlap to {closest} of the radii's sum"
        );
    }
}

/// R-T7: without neighbours v_new = v_pref, clamped to the speed sphere.
#[test]
fn no_neighbours_gives_clamped_preference() {
    let me = Body {
        pos: Vec3::new(1.0, 2.0, 3.0),
        vel: Vec3::new(0.3, 0.0, 0.0),
        radius: 0.5,
    };
    let p = params(2.0, 0.1, 2.0, Fallback::ZeroVelocity);
    let slow = Vec3::new(0.5, -1.0, 0.25);
    let out = solve::<f32, 4>(&me, &[], &[], slow, &p).unwrap();
    assert_eq!(out.velocity, slow);
    assert!(!out.infeasible && out.fallback.is_none() && out.planes == 0);
    let fast = Vec3::new(3.0, 4.0, 0.0);
    let out = solve::<f32, 4>(&me, &[], &[], fast, &p).unwrap();
    assert!((out.velocity - Vec3::new(1.2, 1.6, 0.0)).length() < 1e-6);
    // A far neighbour that is no threat changes nothing either.
    let far = Body {
        pos: Vec3::new(100.0, 2.0, 3.0),
        vel: Vec3::zero(),
        radius: 0.5,
    };
    let out = solve::<f32, 4>(&me, &[far], &[], slow, &p).unwrap();
    assert_eq!(out.velocity, slow);
    assert_eq!(out.planes, 1);
}

/// An agent flying at a wall never crosses it (the hard obstacle plane), and slides along it.
#[test]
fn wall_is_never_crossed() {
    for &fallback in &[Fallback::ZeroVelocity, Fallback::Lp4] {
        let mut sim = Sim::new(
            &[Vec3::new(0.0, 0.0, 0.0)],
            &[Vec3::new(20.0, 0.0, 5.0)],
            0.5,
            params(2.0, 0.1, 2.0, fallback),
        );
        sim.walls.push(Surface {
            point: Vec3::new(5.0, 0.0, 0.0),
            normal: Vec3::new(-1.0, 0.0, 0.0),
        });
        for _ in 0..300 {
            sim.step();
            assert!(sim.bodies[0].pos.x <= 4.5 + 1e-4, "{:?}", sim.bodies[0].pos);
        }
        assert!(sim.bodies[0].pos.x > 4.4);
        // It slides along the wall toward the goal's z.
        assert!(sim.bodies[0].pos.z > 3.0, "{:?}", sim.bodies[0].pos);
        assert_eq!(sim.infeasible, 0);
    }
}

/// A penetrating agent is pushed out within one step; a neighbour pressing it against the
/// wall (LP3 infeasible) does not push it through: LP4 keeps the obstacle plane hard.
#[test]
fn lp4_keeps_obstacles_hard() {
    let wall = Surface {
        point: Vec3::new(1.0, 0.0, 0.0),
        normal: Vec3::new(-1.0, 0.0, 0.0),
    };
    let p = params(2.0, 0.1, 2.0, Fallback::Lp4);
    // 0.1 inside the radius: must leave at ≥ 0.1/Δt = 1.
    let me = Body {
        pos: Vec3::new(0.6, 0.0, 0.0),
        vel: Vec3::zero(),
        radius: 0.5,
    };
    let out = solve::<f32, 4>(&me, &[], &[wall], Vec3::zero(), &p).unwrap();
    assert!((out.velocity.x + 1.0).abs() < 1e-5, "{out:?}");
    // A neighbour overlapping from the open side, rushing at the agent.
    let other = Body {
        pos: Vec3::new(-0.2, 0.0, 0.0),
        vel: Vec3::new(2.0, 0.0, 0.0),
        radius: 0.5,
    };
    let out = solve::<f32, 4>(&me, &[other], &[wall], Vec3::zero(), &p).unwrap();
    assert!(out.infeasible && out.fallback == Some(Fallback::Lp4));
    assert!(out.velocity.x <= -1.0 + 1e-4, "{out:?}");
    let out = solve::<f32, 4>(
        &me,
        &[other],
        &[wall],
        Vec3::zero(),
        &OrcaParams {
            fallback: Fallback::ZeroVelocity,
            ..p
        },
    )
    .unwrap();
    assert_eq!(out.velocity, Vec3::zero());
    assert_eq!(out.failed_plane, Some(1));
}

/// Parameters and inputs are validated with typed errors; capacity overflow is an error.
#[test]
fn validation() {
    let me = Body {
        pos: Vec3::zero(),
        vel: Vec3::zero(),
        radius: 0.5,
    };
    let ok = params(2.0, 0.1, 2.0, Fallback::Lp4);
    let bad = |p: OrcaParams<f32>| solve::<f32, 4>(&me, &[], &[], Vec3::zero(), &p).unwrap_err();
    for (p, field) in [
        (
            OrcaParams {
                time_horizon: 0.0,
                ..ok
            },
            "time_horizon",
        ),
        (OrcaParams { dt: f32::NAN, ..ok }, "dt"),
        (OrcaParams { dt: -1.0, ..ok }, "dt"),
        (
            OrcaParams {
                max_speed: -1.0,
                ..ok
            },
            "max_speed",
        ),
        (
            OrcaParams {
                max_speed: f32::INFINITY,
                ..ok
            },
            "max_speed",
        ),
    ] {
        assert_eq!(bad(p), Error::BadParam { field });
    }
    let nb = Body {
        pos: Vec3::new(f32::NAN, 0.0, 0.0),
        ..me
    };
    assert_eq!(
        solve::<f32, 4>(&me, &[me, nb], &[], Vec3::zero(), &ok).unwrap_err(),
        Error::NonFinite {
            field: "neighbours.pos",
            index: Some(1)
        }
    );
    // Beyond max_neighbors, neighbours are not looked at.
    let one = OrcaParams {
        max_neighbors: 1,
        ..ok
    };
    let far = Body {
        pos: Vec3::new(9.0, 0.0, 0.0),
        ..me
    };
    assert!(solve::<f32, 4>(&me, &[far, nb], &[], Vec3::zero(), &one).is_ok());
    assert_eq!(
        solve::<f32, 1>(&me, &[far, far], &[], Vec3::zero(), &ok).unwrap_err(),
        Error::OutOfRange {
            field: "neighbours",
            index: None
        }
    );
    let zero_normal = Surface {
        point: Vec3::zero(),
        normal: Vec3::zero(),
    };
    assert_eq!(
        solve::<f32, 4>(&me, &[], &[zero_normal], Vec3::zero(), &ok).unwrap_err(),
        Error::OutOfRange {
            field: "obstacles.normal",
            index: Some(0)
        }
    );
    assert_eq!(
        solve::<f32, 4>(&me, &[], &[], Vec3::new(0.0, f32::INFINITY, 0.0), &ok).unwrap_err(),
        Error::NonFinite {
            field: "pref",
            index: None
        }
    );
}

// ---------------------------------------------------------------------------------------------
// LP3 against a brute-force optimum.

type V = [f64; 3];

fn d3(a: V, b: V) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn sub(a: V, b: V) -> V {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn add(a: V, b: V) -> V {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn mul(a: V, k: f64) -> V {
    [a[0] * k, a[1] * k, a[2] * k]
}
fn cross(a: V, b: V) -> V {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn norm(a: V) -> f64 {
    d3(a, a).sqrt()
}

/// Planes in f64: (point, unit normal).
type P = (V, V);

/// The point of the line {x : n1·x = c1, n2·x = c2} closest to the origin and its direction.
fn pair_line(a: &P, b: &P) -> Option<(V, V)> {
    let dir = cross(a.1, b.1);
    let l2 = d3(dir, dir);
    if l2 < 1e-12 {
        return None;
    }
    let (c1, c2) = (d3(a.0, a.1), d3(b.0, b.1));
    // x = (c1 (n2 × d) + c2 (d × n1)) / |d|²
    let x = mul(
        add(mul(cross(b.1, dir), c1), mul(cross(dir, a.1), c2)),
        1.0 / l2,
    );
    Some((x, mul(dir, 1.0 / l2.sqrt())))
}

/// Every candidate optimum of min ‖v − pref‖ s.t. the planes and ‖v‖ ≤ r (one per possible
/// active set), the feasible ones (slack `tol`) kept: the nearest, or `None`.
fn brute_force(planes: &[P], r: f64, pref: V, tol: f64) -> Option<V> {
    let mut c: Vec<V> = vec![pref];
    let pl = norm(pref);
    if pl > 0.0 {
        c.push(mul(pref, r / pl));
    }
    for a in planes {
        let proj = sub(pref, mul(a.1, d3(sub(pref, a.0), a.1)));
        c.push(proj);
        // The circle plane ∩ sphere: centre n·(n·point), radius √(r² − dist²).
        let dist = d3(a.0, a.1);
        if dist.abs() <= r {
            let centre = mul(a.1, dist);
            let rad = (r * r - dist * dist).sqrt();
            let off = sub(proj, centre);
            let ol = norm(off);
            if ol > 1e-12 {
                c.push(add(centre, mul(off, rad / ol)));
            }
        }
    }
    for (i, a) in planes.iter().enumerate() {
        for (j, b) in planes.iter().enumerate().skip(i + 1) {
            let Some((x, d)) = pair_line(a, b) else {
                continue;
            };
            c.push(add(x, mul(d, d3(sub(pref, x), d))));
            // Line ∩ sphere (x ⟂ d): t = ±√(r² − |x|²).
            let h = r * r - d3(x, x);
            if h >= 0.0 {
                c.push(add(x, mul(d, h.sqrt())));
                c.push(sub(x, mul(d, h.sqrt())));
            }
            for g in planes.iter().skip(j + 1) {
                // Vertex: the line's point where it meets the third plane.
                let den = d3(d, g.1);
                if den.abs() > 1e-9 {
                    let t = d3(sub(g.0, x), g.1) / den;
                    c.push(add(x, mul(d, t)));
                }
            }
        }
    }
    c.into_iter()
        .filter(|v| norm(*v) <= r + tol && planes.iter().all(|p| d3(sub(*v, p.0), p.1) >= -tol))
        .min_by(|a, b| norm(sub(*a, pref)).total_cmp(&norm(sub(*b, pref))))
}

fn unit_vec() -> impl Strategy<Value = V> {
    (-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0)
        .prop_filter("non-degenerate", |v| norm([v.0, v.1, v.2]) > 0.1)
        .prop_map(|v| {
            let l = norm([v.0, v.1, v.2]);
            [v.0 / l, v.1 / l, v.2 / l]
        })
}

fn point(k: f64) -> impl Strategy<Value = V> {
    (-k..k, -k..k, -k..k).prop_map(|v| [v.0, v.1, v.2])
}

fn to_f32(v: V) -> Vec3<f32> {
    Vec3::new(v[0] as f32, v[1] as f32, v[2] as f32)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    /// LP3 finds the brute-force optimum when there is one (within 1e-3), and reports
    /// failure when there is none.
    #[test]
    fn lp3_matches_brute_force(
        raw in prop::collection::vec((point(2.0), unit_vec()), 1..=8),
        r in 0.5f64..3.0,
        pref in point(4.0),
    ) {
        // Round to f32 first: both solvers see the same problem.
        let planes: Vec<P> = raw
            .iter()
            .map(|(p, n)| {
                let (p, n) = (to_f32(*p), to_f32(*n));
                // (The f64 normal renormalised: the f32 one is unit only within 1e-7.)
                let n = [n.x as f64, n.y as f64, n.z as f64];
                ([p.x as f64, p.y as f64, p.z as f64], mul(n, 1.0 / norm(n)))
            })
            .collect();
        // RVO2-3D declares (almost) parallel planes (sin² < 1e-5) that cut each other off
        // infeasible: leave those near-degenerate problems out.
        for (i, a) in planes.iter().enumerate() {
            for b in &planes[i + 1..] {
                let c = cross(a.1, b.1);
                prop_assume!(d3(c, c) > 1e-4);
            }
        }
        let r = r as f32 as f64;
        let pref = { let p = to_f32(pref); [p.x as f64, p.y as f64, p.z as f64] };
        // Decide feasibility robustly: with every constraint tightened, then loosened, by
        // 1e-3 (problems in between are left out).
        let shifted = |m: f64| -> Vec<P> {
            planes.iter().map(|(p, n)| (add(*p, mul(*n, m)), *n)).collect()
        };
        let tight = brute_force(&shifted(1e-3), r - 1e-3, pref, 1e-6);
        let loose = brute_force(&shifted(-1e-3), r + 1e-3, pref, 1e-6);
        prop_assume!(tight.is_some() == loose.is_some());
        let exact = brute_force(&planes, r, pref, 1e-6);
        prop_assert_eq!(exact.is_some(), tight.is_some());

        let lp_planes: Vec<Plane<f32>> = planes
            .iter()
            .map(|(p, n)| Plane::new(to_f32(*p), to_f32(*n)))
            .collect();
        let (v, fail) = linear_program3(&lp_planes, r as f32, to_f32(pref), false);
        match exact {
            Some(best) => {
                prop_assert_eq!(fail, lp_planes.len(), "LP3 failed on a feasible problem");
                let vv = [v.x as f64, v.y as f64, v.z as f64];
                prop_assert!(norm(vv) <= r + 1e-3);
                for p in &planes {
                    prop_assert!(d3(sub(vv, p.0), p.1) >= -1e-3);
                }
                let (got, want) = (norm(sub(vv, pref)), norm(sub(best, pref)));
                prop_assert!((got - want).abs() <= 1e-3, "LP3 {} vs brute force {}", got, want);
            }
            None => prop_assert!(fail < lp_planes.len(), "LP3 succeeded on an infeasible problem"),
        }
    }

    /// solve is total: any finite inputs give a finite velocity within the speed sphere.
    #[test]
    fn solve_is_total(
        others in prop::collection::vec((point(5.0), point(3.0), 0.0f32..1.0), 0..8),
        me in (point(5.0), point(3.0), 0.0f32..1.0),
        pref in point(4.0),
        lp4 in any::<bool>(),
    ) {
        let body = |(p, v, r): (V, V, f32)| Body { pos: to_f32(p), vel: to_f32(v), radius: r };
        let nb: Vec<Body<f32>> = others.into_iter().map(body).collect();
        let fallback = if lp4 { Fallback::Lp4 } else { Fallback::ZeroVelocity };
        let out = solve::<f32, 8>(&body(me), &nb, &[], to_f32(pref), &params(2.0, 0.1, 2.0, fallback)).unwrap();
        prop_assert!(out.velocity.check("v").is_ok());
        prop_assert!(out.velocity.length() <= 2.0 * (1.0 + 1e-4));
    }

    /// The same in fixed point, obstacles included: no panic, a velocity within the sphere.
    #[test]
    fn solve_is_total_fixed(
        others in prop::collection::vec((point(5.0), point(3.0), 0.0f32..1.0), 0..8),
        me in (point(5.0), point(3.0), 0.0f32..1.0),
        wall in (point(5.0), unit_vec()),
        pref in point(4.0),
        lp4 in any::<bool>(),
    ) {
        let body = |(p, v, r): (V, V, f32)| Body {
            pos: to_f32(p).cast::<Fx>(),
            vel: to_f32(v).cast::<Fx>(),
            radius: Fx::from_f32(r),
        };
        let nb: Vec<Body<Fx>> = others.into_iter().map(body).collect();
        let fallback = if lp4 { Fallback::Lp4 } else { Fallback::ZeroVelocity };
        let p = OrcaParams {
            time_horizon: Fx::from_f32(2.0),
            dt: Fx::from_f32(0.1),
            max_speed: Fx::from_f32(2.0),
            max_neighbors: 10,
            fallback,
        };
        let obstacle = Surface { point: to_f32(wall.0).cast(), normal: to_f32(wall.1).cast() };
        let out = solve::<Fx, 9>(&body(me), &nb, &[obstacle], to_f32(pref).cast(), &p).unwrap();
        prop_assert!(out.velocity.length().to_f32() <= 2.0 * (1.0 + 1e-2));
    }
}

// ---------------------------------------------------------------------------------------------
// RVO2-3D's neighbour search (KdTree.cc), ported for the conformance test: the same neighbours
// in the same order, ties included (a brute-force sort breaks exact distance ties differently,
// which changes the LP's rounding by an ulp, and ORCA crowds amplify that).

/// RVO3D_MAX_LEAF_SIZE.
const MAX_LEAF: usize = 10;

#[derive(Clone, Copy, Default)]
struct KdNode {
    begin: usize,
    end: usize,
    left: usize,
    right: usize,
    min: [f32; 3],
    max: [f32; 3],
}

/// std::max(a, b) and std::min(a, b) (`a` on ties).
fn cmax(a: f32, b: f32) -> f32 {
    if a < b { b } else { a }
}
fn cmin(a: f32, b: f32) -> f32 {
    if b < a { b } else { a }
}

fn coords(v: Vec3<f32>) -> [f32; 3] {
    [v.x, v.y, v.z]
}

struct KdTree {
    agents: Vec<usize>,
    nodes: Vec<KdNode>,
}

impl KdTree {
    /// `KdTree::buildAgentTree`.
    fn build(pos: &[Vec3<f32>]) -> Self {
        let mut t = KdTree {
            agents: (0..pos.len()).collect(),
            nodes: vec![KdNode::default(); 2 * pos.len() - 1],
        };
        t.build_rec(pos, 0, pos.len(), 0);
        t
    }

    fn build_rec(&mut self, pos: &[Vec3<f32>], begin: usize, end: usize, node: usize) {
        let first = coords(pos[self.agents[begin]]);
        let (mut min, mut max) = (first, first);
        for i in begin + 1..end {
            let p = coords(pos[self.agents[i]]);
            for k in 0..3 {
                max[k] = cmax(max[k], p[k]);
                min[k] = cmin(min[k], p[k]);
            }
        }
        self.nodes[node] = KdNode {
            begin,
            end,
            left: 0,
            right: 0,
            min,
            max,
        };
        if end - begin > MAX_LEAF {
            let ext = |k: usize| max[k] - min[k];
            let coord = if ext(0) > ext(1) && ext(0) > ext(2) {
                0
            } else if ext(1) > ext(2) {
                1
            } else {
                2
            };
            let split = 0.5 * (max[coord] + min[coord]);
            let c = |t: &Self, i: usize| coords(pos[t.agents[i]])[coord];
            let (mut left, mut right) = (begin, end);
            while left < right {
                while left < right && c(self, left) < split {
                    left += 1;
                }
                while right > left && c(self, right - 1) >= split {
                    right -= 1;
                }
                if left < right {
                    self.agents.swap(left, right - 1);
                    left += 1;
                    right -= 1;
                }
            }
            let mut left_size = left - begin;
            if left_size == 0 {
                left_size += 1;
                left += 1;
            }
            let (l, r) = (node + 1, node + 2 * left_size);
            self.nodes[node].left = l;
            self.nodes[node].right = r;
            self.build_rec(pos, begin, left, l);
            self.build_rec(pos, left, end, r);
        }
    }

    /// `Agent::computeNeighbors`: the indices of agent `me`'s neighbours, nearest first.
    fn neighbours(&self, pos: &[Vec3<f32>], me: usize, range: f32, max: usize) -> Vec<usize> {
        let mut out: Vec<(f32, usize)> = Vec::new();
        let mut range_sq = range * range;
        if max > 0 {
            self.query(pos, me, &mut range_sq, 0, max, &mut out);
        }
        out.into_iter().map(|(_, j)| j).collect()
    }

    fn query(
        &self,
        pos: &[Vec3<f32>],
        me: usize,
        range_sq: &mut f32,
        node: usize,
        max: usize,
        out: &mut Vec<(f32, usize)>,
    ) {
        let n = self.nodes[node];
        if n.end - n.begin <= MAX_LEAF {
            for &j in &self.agents[n.begin..n.end] {
                insert_neighbour(pos, me, j, range_sq, max, out);
            }
            return;
        }
        let p = coords(pos[me]);
        let dist = |c: &KdNode| {
            let mut s = 0.0f32;
            for (k, &pk) in p.iter().enumerate() {
                let lo = cmax(0.0, c.min[k] - pk);
                let hi = cmax(0.0, pk - c.max[k]);
                s = s + lo * lo + hi * hi;
            }
            s
        };
        let (l, r) = (self.nodes[n.left], self.nodes[n.right]);
        let (dl, dr) = (dist(&l), dist(&r));
        if dl < dr {
            if dl < *range_sq {
                self.query(pos, me, range_sq, n.left, max, out);
                if dr < *range_sq {
                    self.query(pos, me, range_sq, n.right, max, out);
                }
            }
        } else if dr < *range_sq {
            self.query(pos, me, range_sq, n.right, max, out);
            if dl < *range_sq {
                self.query(pos, me, range_sq, n.left, max, out);
            }
        }
    }
}

/// `Agent::insertAgentNeighbor`.
fn insert_neighbour(
    pos: &[Vec3<f32>],
    me: usize,
    j: usize,
    range_sq: &mut f32,
    max: usize,
    out: &mut Vec<(f32, usize)>,
) {
    if me == j {
        return;
    }
    let d = (pos[me] - pos[j]).length_sq();
    if d < *range_sq {
        if out.len() < max {
            out.push((d, j));
        }
        let mut i = out.len() - 1;
        while i != 0 && d < out[i - 1].0 {
            out[i] = out[i - 1];
            i -= 1;
        }
        out[i] = (d, j);
        if out.len() == max {
            *range_sq = out[max - 1].0;
        }
    }
}

// ---------------------------------------------------------------------------------------------
// R-T7: conformance with RVO2-3D.

/// The reference file of `scripts/rvo2-sphere-reference.sh`: one line of x y z float bits per
/// agent per step, line 0 the initial positions.
fn reference() -> Vec<Vec<Vec3<f32>>> {
    include_str!("testdata/rvo2_sphere.txt")
        .lines()
        .filter(|l| !l.starts_with('#'))
        .map(|l| {
            let f: Vec<f32> = l
                .split_whitespace()
                .map(|h| f32::from_bits(u32::from_str_radix(h, 16).unwrap()))
                .collect();
            f.chunks(3).map(|c| Vec3::new(c[0], c[1], c[2])).collect()
        })
        .collect()
}

/// R-T7: RVO2-3D's `Sphere` example (scaled to 44 agents, see `scripts/rvo2/sphere_ref.cc`)
/// run through [`solve`] with the LP4 fallback and RVO2-3D's neighbour search (the kd-tree
/// port above) and step order matches the reference library's trajectories bit for bit for
/// 100 steps (tolerance 0; the run has ~600 infeasible frames, so LP4 is covered too).
#[test]
fn conformance_rvo2_sphere() {
    sphere_run(true, 100, 0.0);
}

/// The same with the brute-force neighbour sort (ties by index): exact distance ties in the
/// symmetric start are ordered differently from the kd-tree, which changes LP3's rounding by
/// an ulp; the crowd amplifies it chaotically (1e-6 by step 12, 1e-4 by step ~56, 4e-2 by step
/// 100), so this variant is held to 1e-4 for the first 50 steps only.
#[test]
fn conformance_rvo2_sphere_brute_force_neighbours() {
    sphere_run(false, 50, 1e-4);
}

fn sphere_run(kd: bool, steps: usize, tol: f32) {
    let frames = reference();
    assert_eq!(frames.len(), 101);
    let starts = frames[0].clone();
    let goals: Vec<Vec3<f32>> = starts.iter().map(|&p| -p).collect();
    let p = OrcaParams {
        time_horizon: 10.0,
        dt: 0.125,
        max_speed: 2.0,
        max_neighbors: 10,
        fallback: Fallback::Lp4,
    };
    let mut sim = Sim::new(&starts, &goals, 1.5, p);
    sim.kd = kd;
    let mut worst = 0.0f32;
    for (step, frame) in frames.iter().enumerate().skip(1).take(steps) {
        sim.step();
        for (b, r) in sim.bodies.iter().zip(frame) {
            worst = worst.max((b.pos - *r).length());
        }
        assert!(worst <= tol, "step {step}: deviation {worst}");
    }
    std::println!(
        "RVO2-3D conformance: largest deviation {worst:e}, {} infeasible frames",
        sim.infeasible
    );
}

// ---------------------------------------------------------------------------------------------
// Fixed point.

/// Fx runs the head-on pair in small units: no overlap, and within 1e-3 of f32 for 160 steps
/// (1.8e-4 measured).
#[test]
fn fixed_point_head_on() {
    let (a, goal) = (Vec3::new(-2.0, 0.02, 0.0), Vec3::new(2.0, 0.02, 0.0));
    let b = -a;
    let pf = params(1.0, 0.05, 1.0, Fallback::Lp4);
    let px = OrcaParams {
        time_horizon: Fx::from_f32(1.0),
        dt: Fx::from_f32(0.05),
        max_speed: Fx::ONE,
        max_neighbors: 10,
        fallback: Fallback::Lp4,
    };
    let mut sf = Sim::new(&[a, b], &[goal, -goal], 0.25, pf);
    let mut sx = Sim::<Fx>::new(
        &[a.cast(), b.cast()],
        &[goal.cast(), (-goal).cast()],
        Fx::from_f32(0.25),
        px,
    );
    let mut worst = 0.0f32;
    for _ in 0..160 {
        sf.step();
        sx.step();
        assert!(
            sx.min_distance() >= 0.5 * (1.0 - 1e-2),
            "{}",
            sx.min_distance()
        );
        for (f, x) in sf.bodies.iter().zip(&sx.bodies) {
            worst = worst.max((f.pos - x.pos.to_f32()).length());
        }
    }
    std::println!("Fx vs f32: largest deviation {worst:e}");
    assert!(worst < 1e-3, "{worst}");
}
