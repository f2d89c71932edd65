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
    let err = FlySim::from_scenario(&sc, 7).err().expect("refused");
    assert!(
        matches!(err, crate::SimError::SpawnCrowded { ref group, .. } if group == "fruitflies"),
        "{err}"
    );
}
