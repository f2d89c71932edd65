//! Tests of the ren2016 engine across its parts.

use super::*;
use crate::by_scalar;
use crate::scalar::SimScalar;
use crate::scenario::ScalarType;

fn hash(sim: &FlySim) -> u64 {
    let mut h = 0xcbf2_9ce4_8422_2325u64;
    let mut mix = |x: u64| h = (h ^ x).wrapping_mul(0x100_0000_01b3);
    for g in &sim.groups {
        by_scalar!(g, g => for (id, s, d) in g.by_id() {
            mix(u64::from(id));
            for v in [s.pos, s.vel, d.pref] {
                for c in [v.x, v.y, v.z] {
                    mix(c.to_f64().to_bits());
                }
            }
            mix(u64::from(d.infeasible));
        });
    }
    h
}

fn run(threads: usize, every: u32, scalar: ScalarType) -> u64 {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let mut sim = bench_fly_world(400, 5, scalar);
        sim.reorder_every = every;
        for _ in 0..60 {
            sim.step().unwrap();
        }
        hash(&sim)
    })
}

#[test]
fn bit_identical_for_any_thread_count_and_slot_order() {
    for scalar in [ScalarType::F32, ScalarType::Fixed] {
        let base = run(1, 16, scalar);
        assert_eq!(base, run(2, 16, scalar), "{scalar:?}");
        assert_eq!(base, run(3, 0, scalar), "{scalar:?}");
        assert_eq!(base, run(2, 1, scalar), "{scalar:?}");
    }
}

#[test]
fn the_bench_world_flies_without_overlaps_or_corrections() {
    let mut sim = bench_fly_world(1000, 3, ScalarType::F32);
    let d = f64::from(sim.collision_distance);
    for step in 0..200 {
        sim.step().unwrap();
        if step >= 10 {
            let pos = sim.positions_by_id();
            assert_eq!(overlaps(&pos, d), 0, "step {step}");
        }
    }
    assert_eq!(
        (sim.total.obstacle, sim.total.bounds),
        (0, 0),
        "{:?}",
        sim.total
    );
}

/// Pairs closer than `d` (brute force).
pub(super) fn overlaps(pos: &[[f64; 3]], d: f64) -> usize {
    let mut n = 0;
    for (i, a) in pos.iter().enumerate() {
        for b in &pos[i + 1..] {
            let d2: f64 = (0..3).map(|k| (a[k] - b[k]).powi(2)).sum();
            n += usize::from(d2 < d * d);
        }
    }
    n
}

/// Insects spawn at least two ORCA radii apart; a region with no room for the group is refused
/// before the run, naming the group and the first insect that found no place.
#[test]
fn insects_spawn_apart_or_the_scenario_is_refused() {
    let mut sc = crate::scenario::builtin("fly-fig2-fruitfly").unwrap();
    let sim = FlySim::from_scenario(&sc, 7).unwrap();
    let pos = sim.positions_by_id();
    let floor = 2.0 * f64::from(fly_params(&sc.groups[0]).unwrap().orca_radius());
    for (i, p) in pos.iter().enumerate() {
        for q in &pos[i + 1..] {
            let d = (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>().sqrt();
            assert!(d >= floor * (1.0 - 1e-6), "{d} < {floor}");
        }
    }
    sc.groups[0].spawn.region = crate::scenario::SpawnRegion::Box {
        min: vec![9.0, 9.0, 9.0],
        max: vec![11.0, 11.0, 11.0],
    };
    let Err(err) = FlySim::from_scenario(&sc, 7) else {
        panic!("a crowded spawn region must be refused");
    };
    assert!(
        matches!(err, crate::SimError::SpawnCrowded { ref group, .. } if group == "fruitflies"),
        "{err}"
    );
}

/// A spawn region may hold an obstacle: no insect starts inside it or within one ORCA radius
/// of its surface (the moths of Fig. 7 spawned round their lamp).
#[test]
fn insects_spawn_off_the_obstacles_in_their_region() {
    let mut sc = crate::scenario::builtin("fly-fig7-phototaxis").unwrap();
    sc.groups[0].spawn.region = crate::scenario::SpawnRegion::Box {
        min: vec![8.5, 4.5, 8.5],
        max: vec![11.5, 7.5, 11.5],
    };
    let r = f64::from(fly_params(&sc.groups[0]).unwrap().orca_radius());
    let (center, radius) = ([10.0, 6.0, 10.0], 0.5);
    for seed in [7, 8, 9] {
        let sim = FlySim::from_scenario(&sc, seed).unwrap();
        for p in sim.positions_by_id() {
            let d = (0..3)
                .map(|k| (p[k] - center[k]).powi(2))
                .sum::<f64>()
                .sqrt();
            assert!(
                d >= radius + r * (1.0 - 1e-6),
                "seed {seed}: {p:?} is {d} from the lamp"
            );
        }
    }
}

/// Two bats near the +x wall of a 40 × 10 × 40 cave, whose `role` (`threat` or `goal`) is an
/// object of kind `kind`.
fn echo_world(role: &str, kind: &str) -> crate::scenario::Scenario {
    let text = format!(
        r#"
name = "echo"
steps = 10
world = {{ dim = 3, min = [0, 0, 0], max = [40, 10, 40] }}
[[groups]]
name = "bats"
model = "fly"
count = 2
{role} = "cave"
spawn = {{ min = [35.5, 4, 18], max = [37.5, 6, 22] }}
fly = {{ preset = "bats" }}
[[objects]]
name = "cave"
kind = "{kind}"
min = [0, 0, 0]
max = [40, 10, 40]
"#
    );
    crate::scenario::Scenario::from_str(&text, "echo.toml").unwrap()
}

/// A `region` threat is an echo source: the bats hear the wall ahead of them. The stimulus is
/// that wall point while it is within r_res, nothing at rest.
#[test]
fn a_region_threat_echoes_the_wall_ahead() {
    let sc = echo_world("threat", "region");
    let mut sim = FlySim::from_scenario(&sc, 1).unwrap();
    let p = fly_params(&sc.groups[0]).unwrap();
    let stimuli = Stimuli {
        goal: None,
        threat: Some(0),
    };
    let me = sim.world.sensed.pos[0];
    // At rest: no heading, no echo.
    let (f, _) = fly_frame::<f32>(&sim.world, 0, &p, stimuli);
    assert!(f.stimulus.is_none());
    // Heading +x: the wall x = 40 ahead, within r_res = 10.
    sim.world.sensed.vel[0] = [1.0, 0.0, 0.0];
    let (f, _) = fly_frame::<f32>(&sim.world, 0, &p, stimuli);
    let s = f.stimulus.expect("the echo");
    assert_eq!(s.kind, swarm_core::fly::STIMULUS_PREDATOR);
    assert_eq!(
        [s.pos.x, s.pos.y, s.pos.z],
        [40.0, me[1] as f32, me[2] as f32]
    );
    // Heading −x: the wall x = 0 is beyond r_res.
    sim.world.sensed.vel[0] = [-1.0, 0.0, 0.0];
    assert!(
        fly_frame::<f32>(&sim.world, 0, &p, stimuli)
            .0
            .stimulus
            .is_none()
    );
}

/// A `cave` goal is the echo ahead, pursued (the bats of Fig. 9): the wall point while it is
/// within r_res/2, else the point r_res/2 ahead; nothing at rest.
#[test]
fn a_cave_goal_is_the_echo_ahead() {
    let sc = echo_world("goal", "cave");
    let mut sim = FlySim::from_scenario(&sc, 1).unwrap();
    let p = fly_params(&sc.groups[0]).unwrap();
    let stimuli = Stimuli {
        goal: Some(0),
        threat: None,
    };
    let me = sim.world.sensed.pos[0].map(|c| c as f32);
    assert!(
        fly_frame::<f32>(&sim.world, 0, &p, stimuli)
            .0
            .stimulus
            .is_none()
    );
    let sensed = |sim: &FlySim| {
        let s = fly_frame::<f32>(&sim.world, 0, &p, stimuli)
            .0
            .stimulus
            .expect("the echo");
        assert_eq!(s.kind, swarm_core::fly::STIMULUS_TARGET);
        [s.pos.x, s.pos.y, s.pos.z]
    };
    // Heading +x: the wall x = 40 is nearer than r_res/2 = 5.
    sim.world.sensed.vel[0] = [2.0, 0.0, 0.0];
    assert_eq!(sensed(&sim), [40.0, me[1], me[2]]);
    // Heading −x: the wall is farther; the point 5 ahead.
    sim.world.sensed.vel[0] = [-2.0, 0.0, 0.0];
    assert_eq!(sensed(&sim), [me[0] - 0.5 * p.r_res, me[1], me[2]]);
}
