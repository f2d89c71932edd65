//! Tests of the ren2016 forces and step (spec §4, R-T1 to R-T6).

use super::force::{Zone, friction, noise_force, response, zone, zone_force};
use super::*;
use crate::bee::curl::curl_force;
use crate::{Fx, StepCtx, Vec3};

fn ctx(agent: u32, step: u32) -> StepCtx {
    StepCtx {
        seed: 11,
        agent,
        step,
    }
}

/// A spread of zones: r_rep 1, r_ali 2, r_att 4.
fn zoned() -> FlyParams<f32> {
    FlyParams {
        r_rep: 1.0,
        r_ali: 2.0,
        r_att: 4.0,
        chi_rep: 3.0,
        chi_ali: 5.0,
        chi_att: 7.0,
        ..FlyParams::fruitfly()
    }
}

fn neighbour(id: u32, pos: [f32; 3], vel: [f32; 3]) -> Neighbour<f32> {
    Neighbour {
        id,
        pos: Vec3::new(pos[0], pos[1], pos[2]),
        vel: Vec3::new(vel[0], vel[1], vel[2]),
    }
}

fn close(a: Vec3<f32>, b: Vec3<f32>) -> bool {
    (a - b).length() < 1e-5
}

/// R-T1: the zone boundaries exactly as g.
#[test]
fn zones_follow_g() {
    let p = zoned();
    let eps = 1e-4;
    assert_eq!(zone(1.0 - eps, &p), Some(Zone::Repulsion));
    assert_eq!(zone(1.0, &p), Some(Zone::Alignment));
    assert_eq!(zone(2.0, &p), Some(Zone::Attraction));
    assert_eq!(zone(4.0, &p), Some(Zone::Attraction));
    assert_eq!(zone(4.0 + eps, &p), None);
    // r_ali = r_rep: the alignment zone is empty.
    let q = FlyParams { r_ali: 1.0, ..p };
    assert_eq!(zone(1.0, &q), Some(Zone::Attraction));
    assert_eq!(zone(1.0 - eps, &q), Some(Zone::Repulsion));
}

/// R-T2: Eq. 5 by hand, one neighbour per zone, then two in one zone (the mean).
#[test]
fn eq_5_by_hand() {
    let p = zoned();
    let me = FlyState::new(Vec3::zero(), Vec3::new(1.0, 0.0, 0.0));
    let ns = [
        neighbour(1, [0.5, 0.0, 0.0], [0.0; 3]),
        neighbour(2, [0.0, 1.5, 0.0], [1.0, 0.0, 2.0]),
        neighbour(3, [0.0, 0.0, -3.0], [0.0; 3]),
    ];
    let f = zone_force(&me, 0, &ns, &p);
    // rep: −r̂ = (−1, 0, 0)·3; ali: v̂ = (0, 0, 1)·5; att: r̂ = (0, 0, −1)·7.
    assert!(close(f, Vec3::new(-3.0, 0.0, 5.0 - 7.0)), "{f:?}");
    let two = [
        neighbour(1, [0.5, 0.0, 0.0], [0.0; 3]),
        neighbour(2, [0.0, -0.5, 0.0], [0.0; 3]),
    ];
    let f = zone_force(&me, 0, &two, &p);
    assert!(close(f, Vec3::new(-1.5, 1.5, 0.0)), "{f:?}");
    // Beyond r_att, the insect itself, and a coincident neighbour add nothing.
    let none = [
        neighbour(1, [5.0, 0.0, 0.0], [0.0; 3]),
        neighbour(0, [0.5, 0.0, 0.0], [0.0; 3]),
        neighbour(4, [0.0, 0.0, 0.0], [0.0; 3]),
    ];
    assert_eq!(zone_force(&me, 0, &none, &p), Vec3::zero());
}

/// R-T3: friction is −γ|v|v, and a lone insect under a constant force reaches √(F/γ).
#[test]
fn friction_gives_the_terminal_speed() {
    let v = Vec3::new(3.0f32, 4.0, 0.0);
    assert!(close(friction(v, 2.0), v * -10.0));
    let (force, gamma, dt) = (14.29f32, 11.16f32, 0.01f32);
    let mut vel = Vec3::<f32>::zero();
    for _ in 0..2000 {
        vel += (Vec3::new(force, 0.0, 0.0) + friction(vel, gamma)) * dt;
    }
    let terminal = (force / gamma).sqrt();
    assert!((vel.length() / terminal - 1.0).abs() < 0.01, "{vel:?}");
}

/// R-T4: pursuit heads straight at the target inside r_res, nothing outside.
#[test]
fn pursuit_heads_at_the_target() {
    let p = FlyParams::<f32>::mating();
    let me = FlyState::new(Vec3::zero(), Vec3::zero());
    let target = Stimulus {
        pos: Vec3::new(0.0, 1.2, 1.6),
        kind: STIMULUS_TARGET,
    };
    let (f, _, escaping) = response(&me, Some(&target), &p, ctx(0, 0));
    assert!(!escaping);
    assert!(close(f, Vec3::new(0.0, 0.6, 0.8) * p.chi_res), "{f:?}");
    let far = Stimulus {
        pos: Vec3::new(0.0, 0.0, p.r_res + 0.01),
        ..target
    };
    assert_eq!(response(&me, Some(&far), &p, ctx(0, 0)).0, Vec3::zero());
    assert_eq!(response(&me, None, &p, ctx(0, 0)).0, Vec3::zero());
}

/// The angle between two vectors, in degrees.
fn degrees(a: Vec3<f32>, b: Vec3<f32>) -> f32 {
    (a.dot(b) / (a.length() * b.length()))
        .clamp(-1.0, 1.0)
        .acos()
        .to_degrees()
}

/// R-T5: the escape is 90-180° from the threat for 10⁴ draws; θ holds over an episode and
/// is drawn again after the predator leaves and comes back.
#[test]
fn escape_turns_away_from_the_threat() {
    let p = FlyParams::<f32>::escape();
    let threat = Stimulus {
        pos: Vec3::new(3.0, 0.0, 1.0),
        kind: STIMULUS_PREDATOR,
    };
    let me = FlyState::new(Vec3::zero(), Vec3::zero());
    let to_threat = threat.pos - me.pos;
    let mut thetas = [f32::MAX, f32::MIN];
    for agent in 0..10_000 {
        let (f, theta, escaping) = response(&me, Some(&threat), &p, ctx(agent, 3));
        assert!(escaping);
        let a = degrees(f, to_threat);
        assert!(
            (90.0 - 1e-3..=180.0 + 1e-3).contains(&a),
            "agent {agent}: {a}°"
        );
        assert!((f.length() - p.chi_res).abs() < 1e-4);
        thetas = [thetas[0].min(theta), thetas[1].max(theta)];
    }
    // The draws cover [−π/2, 0].
    assert!(thetas[0] < -1.5 && thetas[1] > -0.05, "{thetas:?}");
    // θ holds while the predator stays in range …
    let (_, theta, escaping) = response(&me, Some(&threat), &p, ctx(5, 0));
    let during = FlyState {
        escape_theta: theta,
        escaping,
        ..me
    };
    for step in 1..50 {
        let (_, t, e) = response(&during, Some(&threat), &p, ctx(5, step));
        assert!(e && t == theta);
    }
    // … and is drawn again after it left.
    let (_, _, e) = response(&during, None, &p, ctx(5, 60));
    assert!(!e);
    let after = FlyState {
        escaping: false,
        ..during
    };
    let (_, again, _) = response(&after, Some(&threat), &p, ctx(5, 61));
    assert_ne!(again, theta);
    // Both sides with escape_sides 1.
    let both = FlyParams {
        escape_sides: 1,
        ..p
    };
    let positive = (0..1000).any(|a| response(&me, Some(&threat), &both, ctx(a, 0)).1 > 0.1);
    assert!(positive);
}

/// R-T6: F_ξ is the bee's curl noise bit for bit; the baselines are bounded and vary.
#[test]
fn noise_reuses_the_bee_curl() {
    let p = FlyParams::<f32>::midge();
    for i in 0..100 {
        let pos = Vec3::new(
            i as f32 * 0.37,
            1.0 - i as f32 * 0.11,
            2.5 + i as f32 * 0.05,
        );
        assert_eq!(
            noise_force(pos, &p, ctx(i, 0)),
            curl_force(pos, p.scale, p.gain)
        );
        let pf = p.cast::<Fx>();
        let pos_fx = pos.cast::<Fx>();
        assert_eq!(
            noise_force(pos_fx, &pf, ctx(i, 0)),
            curl_force(pos_fx, pf.scale, pf.gain)
        );
    }
    let white = FlyParams {
        noise: NOISE_WHITE,
        ..p
    };
    let gauss = FlyParams {
        noise: NOISE_GAUSSIAN,
        ..p
    };
    let (mut sum, mut sq) = (0.0f64, 0.0f64);
    let n = 20_000;
    for a in 0..n {
        let w = noise_force(Vec3::zero(), &white, ctx(a, 1));
        assert!(w.x.abs() <= p.gain && w.y.abs() <= p.gain && w.z.abs() <= p.gain);
        let g = noise_force(Vec3::zero(), &gauss, ctx(a, 1)) * (1.0 / p.gain);
        sum += f64::from(g.x);
        sq += f64::from(g.x) * f64::from(g.x);
    }
    let mean = sum / f64::from(n);
    let var = sq / f64::from(n) - mean * mean;
    assert!(
        mean.abs() < 0.03 && (var - 1.0).abs() < 0.05,
        "{mean} {var}"
    );
    let none = FlyParams {
        noise: NOISE_NONE,
        ..p
    };
    assert_eq!(
        noise_force(Vec3::new(1.0, 2.0, 3.0), &none, ctx(0, 0)),
        Vec3::zero()
    );
}

/// Bad frames are refused with the field and index named.
#[test]
fn bad_frames_name_the_field() {
    let mut f: FlyFrame<f32, 4, 2> = FlyFrame::new();
    f.neighbours.push(neighbour(1, [0.0; 3], [0.0; 3])).unwrap();
    f.neighbours.push(neighbour(1, [1.0; 3], [0.0; 3])).unwrap();
    assert_eq!(
        f.validate(),
        Err(crate::Error::inconsistent("frame.neighbours.id").at(1))
    );
    f.neighbours.pop();
    f.neighbours
        .push(neighbour(2, [f32::NAN, 0.0, 0.0], [0.0; 3]))
        .unwrap();
    assert_eq!(
        f.validate(),
        Err(crate::Error::non_finite("frame.neighbours.pos").at(1))
    );
    f.neighbours.pop();
    f.stimulus = Some(Stimulus {
        pos: Vec3::zero(),
        kind: 2,
    });
    assert_eq!(
        f.validate(),
        Err(crate::Error::out_of_range("frame.stimulus.kind"))
    );
    f.stimulus = None;
    f.surfaces
        .push(Surface {
            point: Vec3::zero(),
            normal: Vec3::new(0.0, 2.0, 0.0),
        })
        .unwrap();
    assert_eq!(
        f.validate(),
        Err(crate::Error::out_of_range("frame.surfaces.normal").at(0))
    );
}

/// A frame holding `others` as neighbours (ids 1..), no stimulus, no surfaces.
fn frame_of(others: &[FlyState<f32>]) -> FlyFrame<f32, 16, 4> {
    let mut f = FlyFrame::new();
    for (i, o) in others.iter().enumerate() {
        f.neighbours
            .push(Neighbour {
                id: i as u32 + 1,
                pos: o.pos,
                vel: o.vel,
            })
            .unwrap();
    }
    f
}

/// Algorithm 1 for a lone insect: v_pref from the forces, ORCA leaves it (within the speed
/// limit), the insect moves by v·Δt; the same in fixed point within 1e-3.
#[test]
fn a_lone_insect_follows_its_forces() {
    let p = FlyParams::<f32>::midge();
    let mut s = FlyState::new(Vec3::new(1.0, 2.0, 3.0), Vec3::new(0.5, 0.0, 0.0));
    let mut s_fx = s.cast::<Fx>();
    let p_fx = p.cast::<Fx>();
    for k in 0..200 {
        let (next, d) = step(&s, &frame_of(&[]), &p, ctx(0, k)).unwrap();
        let want = s.vel + (friction(s.vel, p.gamma) + noise_force(s.pos, &p, ctx(0, k))) * p.dt;
        assert!(close(d.pref, want));
        assert!(!d.infeasible);
        assert!(next.vel.length() <= p.max_speed * 1.0001);
        assert_eq!(next.pos, s.pos + next.vel * p.dt);
        let (next_fx, _) = step(&s_fx, &FlyFrame::<Fx, 16, 4>::new(), &p_fx, ctx(0, k)).unwrap();
        s = next;
        s_fx = next_fx;
    }
    assert!(
        (s.pos - s_fx.pos.cast()).length() < 2e-3,
        "{:?} {:?}",
        s.pos,
        s_fx.pos
    );
}

/// Two insects flying at each other (attraction pulls them together too) never come closer
/// than two ORCA radii.
#[test]
fn two_insects_head_on_never_overlap() {
    let p = FlyParams {
        noise: NOISE_NONE,
        ..FlyParams::<f32>::fruitfly()
    };
    let mut a = FlyState::new(Vec3::new(-1.5, 0.0, 0.0), Vec3::new(3.0, 0.0, 0.0));
    let mut b = FlyState::new(Vec3::new(1.5, 0.0, 0.01), Vec3::new(-3.0, 0.0, 0.0));
    for k in 0..500 {
        let (na, _) = step(&a, &frame_of(&[b]), &p, ctx(0, k)).unwrap();
        let mut fb = frame_of(&[a]);
        fb.neighbours[0].id = 0;
        let (nb, _) = step(&b, &fb, &p, ctx(1, k)).unwrap();
        (a, b) = (na, nb);
        let d = (a.pos - b.pos).length();
        assert!(d >= 2.0 * p.radius * (1.0 - 1e-3), "step {k}: {d}");
    }
}

/// An insect driven at a wall stays on its side.
#[test]
fn a_wall_holds() {
    let p = FlyParams {
        noise: NOISE_NONE,
        ..FlyParams::<f32>::phototaxis()
    };
    let mut s = FlyState::new(Vec3::new(0.0, 0.0, 0.0), Vec3::new(5.0, 0.0, 0.0));
    let mut f: FlyFrame<f32, 16, 4> = FlyFrame::new();
    let target = Stimulus {
        pos: Vec3::new(3.0, 0.0, 0.0),
        kind: STIMULUS_TARGET,
    };
    f.stimulus = Some(target);
    for k in 0..300 {
        f.surfaces.clear();
        f.surfaces
            .push(Surface {
                point: Vec3::new(1.0, s.pos.y, s.pos.z),
                normal: Vec3::new(-1.0, 0.0, 0.0),
            })
            .unwrap();
        s = step(&s, &f, &p, ctx(0, k)).unwrap().0;
        assert!(s.pos.x <= 1.0 - p.radius + 1e-4, "step {k}: {:?}", s.pos);
    }
}

/// [`FlyParams::scaled`] is a similarity of Algorithm 1: with every position and velocity k
/// times larger, a step (zone forces in all three zones, friction, pursuit or escape, each
/// noise source, ORCA against a neighbour on a collision course and a wall) gives k times
/// the position and velocity, to rounding.
#[test]
fn scaled_parameters_are_a_similarity() {
    let v = |x: f32, y: f32, z: f32| Vec3::new(x, y, z);
    let me = FlyState::new(v(0.3, 0.2, 0.1), v(0.4, -1.5, 0.2));
    let others = [
        (v(1.0, 0.9, 0.1), v(-0.5, -1.0, 0.0)), // repulsion, closing in (ORCA)
        (v(5.0, 1.0, -1.0), v(1.0, 0.5, 0.0)),  // alignment
        (v(-9.0, 4.0, 6.0), v(0.0, 0.0, 1.0)),  // attraction
    ];
    for (base, kind) in [
        (FlyParams::<f32>::mating(), STIMULUS_TARGET),
        (FlyParams::<f32>::escape(), STIMULUS_PREDATOR),
    ] {
        for noise in [NOISE_CURL, NOISE_PERLIN, NOISE_WHITE, NOISE_GAUSSIAN] {
            let p = FlyParams { noise, ..base };
            let run = |k: f32| {
                let mut f: FlyFrame<f32, 16, 4> = FlyFrame::new();
                for (i, (pos, vel)) in others.iter().enumerate() {
                    f.neighbours
                        .push(Neighbour {
                            id: i as u32 + 1,
                            pos: *pos * k,
                            vel: *vel * k,
                        })
                        .unwrap();
                }
                f.stimulus = Some(Stimulus {
                    pos: v(1.5, 1.0, 0.5) * k,
                    kind,
                });
                f.surfaces
                    .push(Surface {
                        point: v(0.3, -0.3, 0.1) * k,
                        normal: v(0.0, 1.0, 0.0),
                    })
                    .unwrap();
                let s = FlyState::new(me.pos * k, me.vel * k);
                step(&s, &f, &p.scaled(k), ctx(0, 5)).unwrap().0
            };
            let one = run(1.0);
            for k in [0.25, 3.0] {
                let big = run(k);
                for (a, b) in [(one.pos, big.pos), (one.vel, big.vel)] {
                    let err = (a * k - b).length() / (k * a.length());
                    assert!(err < 1e-4, "noise {noise}, k {k}: {a:?} × k vs {b:?}");
                }
                assert_eq!(one.escaping, big.escaping);
            }
        }
    }
}
