//! R-T10: the metrics on analytic tracks; reading track files.

use super::*;
use crate::SimError;

fn rel(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * b.abs().max(1e-12)
}

/// A straight line at speed u: v = u, a = ω = α = μ = 0.
#[test]
fn a_straight_line() {
    let u = 2.5;
    let dt = 0.01;
    let t = Tracks::from_samples(
        dt,
        (0..100).map(|k| (7, k, [1.0 + u * dt * k as f64, 2.0, -u * 0.0])),
    );
    let s = samples(&t);
    assert_eq!(s.0[0].len(), 99);
    assert!(s.0[0].iter().all(|&v| rel(v, u)), "{:?}", &s.0[0][..3]);
    for (set, name) in s.0.iter().zip(METRICS).take(5).skip(1) {
        assert!(set.iter().all(|&v| v.abs() < 1e-5), "{name}");
    }
    // One insect: no d, no η.
    assert!(s.0[5].is_empty() && s.0[6].is_empty());
}

/// A circle of radius ρ sampled at angular step θ (chord velocities): v = 2ρ sin(θ/2)/Δt,
/// ω = θ/Δt, α = 0, a = 4ρ sin²(θ/2)/Δt², μ = 8ρ sin³(θ/2)/Δt³.
#[test]
fn a_circle() {
    let (rho, u, dt) = (3.0f64, 1.5f64, 0.02f64);
    let theta = u * dt / rho;
    let t = Tracks::from_samples(
        dt,
        (0..200).map(|k| {
            let a = theta * k as f64;
            (1, k, [rho * a.cos(), 0.5, rho * a.sin()])
        }),
    );
    let s = samples(&t);
    let h = (theta / 2.0).sin();
    let want = [
        2.0 * rho * h / dt,
        4.0 * rho * h * h / (dt * dt),
        theta / dt,
        0.0,
        8.0 * rho * h * h * h / (dt * dt * dt),
    ];
    for ((set, name), want) in s.0.iter().zip(METRICS).zip(want) {
        assert!(!set.is_empty());
        for &v in set {
            let ok = if want == 0.0 {
                v.abs() < 1e-6
            } else {
                (v - want).abs() <= 1e-9 * want
            };
            assert!(ok, "{name}: {v} vs {want}");
        }
    }
}

/// d and η on a hand-made frame: three insects, velocities known.
#[test]
fn shortest_distance_and_velocity_difference() {
    // Frame 0 → 1: insect 0 moves at 1, insect 1 at 3, insect 2 at 2 (all along x).
    let dt = 1.0;
    let t = Tracks::from_samples(
        dt,
        [
            (0, 0, [0.0, 0.0, 0.0]),
            (0, 1, [1.0, 0.0, 0.0]),
            (1, 0, [0.0, 2.0, 0.0]),
            (1, 1, [3.0, 2.0, 0.0]),
            (2, 0, [0.0, 0.0, 5.0]),
            (2, 1, [2.0, 0.0, 5.0]),
        ],
    );
    let s = samples(&t);
    // Frame 0: pairs 2, 5, √29 → d = 2; frame 1: |(1,0,0)−(3,2,0)| = √8, → d = √8.
    let mut d = s.0[5].clone();
    d.sort_by(f64::total_cmp);
    assert!(rel(d[0], 2.0) && rel(d[1], 8f64.sqrt()), "{d:?}");
    // η in frame 0 only (velocities exist there): 0↔1 (|3 − 1|/2), 1↔0 (|1 − 3|/2),
    // 2's nearest is 0 at 5: |1 − 2|/5.
    let mut eta = s.0[6].clone();
    eta.sort_by(f64::total_cmp);
    assert_eq!(eta.len(), 3);
    assert!(
        rel(eta[0], 0.2) && rel(eta[1], 1.0) && rel(eta[2], 1.0),
        "{eta:?}"
    );
}

/// A gap in a track starts a new run: no difference spans it.
#[test]
fn gaps_split_runs() {
    let t = Tracks::from_samples(0.1, [0, 1, 2, 5, 6].map(|k| (3, k, [k as f64, 0.0, 0.0])));
    assert_eq!(t.runs().len(), 2);
    let s = samples(&t);
    // Speeds: two in the first run, one in the second, all 10 (1 per 0.1 s).
    assert_eq!(s.0[0].len(), 3);
    assert!(s.0[0].iter().all(|&v| rel(v, 10.0)));
}

/// Track files: the interval inferred, rows in any order, errors with line and field.
#[test]
fn reading_track_files() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("tracks.csv");
    std::fs::write(
        &path,
        "id,time,x,y,z\n2,0.04,1,1,1\n1,0.00,0,0,0\n1,0.02,0.1,0,0\n2,0.02,1,1,0.9\n",
    )
    .unwrap();
    let t = Tracks::read_csv(&path, None).unwrap();
    assert!((t.dt - 0.02).abs() < 1e-12);
    assert_eq!(t.len(), 4);
    assert_eq!(
        t.by_id[&2],
        vec![(1, [1.0, 1.0, 0.9]), (2, [1.0, 1.0, 1.0])]
    );
    std::fs::write(&path, "id,time,x,y,z\n1,0,0,0,0\n1,0.02,0,zero,0\n").unwrap();
    let e = Tracks::read_csv(&path, None).unwrap_err().to_string();
    assert!(e.contains(":3:") && e.contains("\"y\""), "{e}");
    std::fs::write(
        &path,
        "id,time,x,y,z\n1,0,0,0,0\n1,0.02,0,0,0\n1,0.03,0,0\n",
    )
    .unwrap();
    let e = Tracks::read_csv(&path, None).unwrap_err().to_string();
    assert!(
        e.contains(":4:") && e.contains("missing field \"z\""),
        "{e}"
    );
    std::fs::write(
        &path,
        "id,time,x,y,z\n1,0,0,0,0\n1,0.02,0,0,0\n1,0.05,0,0,0\n",
    )
    .unwrap();
    let e = Tracks::read_csv(&path, None).unwrap_err().to_string();
    assert!(
        e.contains(":4:") && e.contains("not on the frame grid"),
        "{e}"
    );
    std::fs::write(&path, "id,t,x,y,z\n").unwrap();
    assert!(Tracks::read_csv(&path, None).is_err());
    std::fs::write(&path, "id,time,x,y,z\n1,0,0,0,0\n2,0,1,1,1\n").unwrap();
    let e = Tracks::read_csv(&path, None).unwrap_err().to_string();
    assert!(e.contains("--dt"), "{e}");
    assert_eq!(Tracks::read_csv(&path, Some(0.5)).unwrap().dt, 0.5);
    for dt in [0.0, -0.1, f64::NAN, f64::INFINITY] {
        let e = Tracks::read_csv(&path, Some(dt)).unwrap_err();
        assert!(matches!(e, SimError::TrackDt { .. }), "{e}");
        assert!(e.to_string().contains("positive number of seconds"), "{e}");
    }
}

/// The truth scores above a distorted copy: the same process against the same process
/// with twice the turning.
#[test]
fn the_same_process_scores_higher() {
    let walk = |seed: u32, turn: f64| {
        let mut samples = Vec::new();
        for id in 0..20u64 {
            let (mut p, mut h) = ([id as f64, 0.0, 0.0], 0.0f64);
            for k in 0..200i64 {
                samples.push((id, k, p));
                let r =
                    swarm_core::rand::rand(seed, id as u32, k as u32, 0) as f64 / u32::MAX as f64;
                h += turn * (r - 0.5);
                p = [p[0] + 0.1 * h.cos(), p[1] + 0.1 * h.sin(), p[2]];
            }
        }
        Tracks::from_samples(0.1, samples)
    };
    let reference = walk(1, 0.4);
    let same = walk(2, 0.4);
    let twice = walk(3, 0.8);
    let e = evaluate(&reference, &[&same, &twice], Scaling::Separate);
    assert!(e.weighting.scores[0] > e.weighting.scores[1], "{e:?}");
    assert!(e.polarisation.1.iter().all(|p| (0.0..=1.0).contains(p)));
}

/// Milling is 1 for insects circling a vertical axis the same way (at any height and radius,
/// about the axis; about the centre only in its plane), 0 for half of them circling each way,
/// small for one common heading, 0 without motion.
#[test]
fn milling_about_an_axis() {
    let (c, up) = ([20.0, 5.0, 20.0], Some([0.0, 3.0, 0.0]));
    let ring = |k: usize, way: f64| {
        let th = k as f64 * 0.7;
        let r = 3.0 + k as f64 % 5.0;
        let p = [c[0] + r * th.cos(), k as f64 % 7.0, c[2] + r * th.sin()];
        (p, [-way * th.sin() * 2.0, 0.0, way * th.cos() * 2.0])
    };
    let (pos, vel): (Vec<_>, Vec<_>) = (0..40).map(|k| ring(k, 1.0)).unzip();
    assert!((frame_milling(&pos, &vel, c, up) - 1.0).abs() < 1e-12);
    let free = frame_milling(&pos, &vel, c, None);
    assert!(free > 0.5 && free < 1.0, "{free}");
    let flat: Vec<[f64; 3]> = pos.iter().map(|p| [p[0], c[1], p[2]]).collect();
    assert!((frame_milling(&flat, &vel, c, None) - 1.0).abs() < 1e-12);
    let (pos, vel): (Vec<_>, Vec<_>) = (0..40)
        .map(|k| ring(k, if k % 2 == 0 { 1.0 } else { -1.0 }))
        .unzip();
    assert!(frame_milling(&pos, &vel, c, up) < 0.2);
    let along = vec![[1.0, 0.0, 0.5]; pos.len()];
    assert!(frame_milling(&pos, &along, c, up) < 0.2);
    assert_eq!(frame_milling(&pos, &vec![[0.0; 3]; pos.len()], c, up), 0.0);
    assert_eq!(frame_milling(&pos, &vel, c, Some([0.0; 3])), 0.0);
}
