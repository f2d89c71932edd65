//! Behaviour tests on the built-in bee scenarios, and the throughput measurement.

use super::*;
use crate::scenario::{self, Action, ObjectKind};

fn scenario_sim(name: &str) -> (crate::scenario::Scenario, BeeSim) {
    let sc = scenario::builtin(name).unwrap_or_else(|| panic!("no built-in {name}"));
    let sim = BeeSim::from_scenario(&sc, sc.seed).unwrap_or_else(|e| panic!("{name}: {e}"));
    (sc, sim)
}

#[test]
fn every_builtin_bee_scenario_builds_and_runs() {
    let names: Vec<&str> = scenario::builtin_names()
        .iter()
        .copied()
        .filter(|n| n.starts_with("bees"))
        .collect();
    assert!(names.len() >= 3, "{names:?}");
    for name in names {
        let (sc, mut sim) = scenario_sim(name);
        assert_eq!(sim.agents() as u64, sc.agent_count(), "{name}");
        for _ in 0..50 {
            sim.step().unwrap_or_else(|e| panic!("{name}: {e}"));
        }
        let f = bee_frame_samples(&sim);
        assert_eq!(f.step, 50);
        assert!(f.agents.iter().enumerate().all(|(i, a)| a.id == i as u32));
        assert!(f.agents.iter().all(|a| sc.world.contains(&a.pos)), "{name}");
    }
}

#[test]
fn events_add_remove_and_move_objects() {
    let (sc, mut sim) = scenario_sim("bees-fig14-shafts");
    let shaft = sc.object_id("shaft-1").unwrap();
    let goal = sc.object_id("goal").unwrap();
    let probe = [24.0, 10.0, 21.5]; // 1 unit from shaft-1's surface
    sim.world.sensed.pos[0] = probe;
    let sensed = |sim: &BeeSim| bee_frame::<f32>(&sim.world, 0, None, 0.0).obstacle;
    assert!(sensed(&sim).is_some());
    sim.apply(shaft, &Action::Remove("shaft-1".into()));
    assert!(sensed(&sim).is_none());
    sim.apply(shaft, &Action::Add("shaft-1".into()));
    assert!(sensed(&sim).is_some());
    sim.apply(
        shaft,
        &Action::Move {
            object: "shaft-1".into(),
            to: vec![10.0, 10.0],
        },
    );
    assert!(sensed(&sim).is_none());
    // A moved target: resampled particles, and the group flies to the new centre.
    let to = vec![40.0, 20.0, 10.0];
    sim.apply(
        goal,
        &Action::Move {
            object: "goal".into(),
            to: to.clone(),
        },
    );
    assert_eq!(sim.world.target_center(goal), Some([40.0, 20.0, 10.0]));
    assert!(sim.world.particles.iter().all(|p| {
        let d = (0..3).map(|k| (p[k] - to[k]).powi(2)).sum::<f32>().sqrt();
        (d - 2.0).abs() < 1e-3
    }));
    sim.apply(goal, &Action::Remove("goal".into()));
    assert!(sim.world.particles.is_empty() && sim.world.target_center(goal).is_none());
    sim.step().unwrap();
}

#[test]
fn an_ant_world_is_not_a_bee_world() {
    let sc = scenario::builtin("ants-fig7a-single-colony").unwrap();
    assert!(BeeSim::from_scenario(&sc, 1).is_err());
}

/// chen Fig. 14: 600 steps through the shaft field. The world must never leave a bee inside a
/// shaft; how often it had to put one back (the controller alone failing to avoid) is printed.
#[test]
fn fig14_no_bee_passes_through_a_shaft() {
    let (sc, mut sim) = scenario_sim("bees-fig14-shafts");
    let shafts: Vec<(f64, f64, f64)> = sc
        .objects
        .iter()
        .filter_map(|o| match o.kind {
            ObjectKind::Shaft { center, radius, .. } => Some((
                f64::from(center[0]),
                f64::from(center[1]),
                f64::from(radius),
            )),
            _ => None,
        })
        .collect();
    assert_eq!(shafts.len(), 7);
    let (mut avoiding, mut steps_with_contact, mut min_gap) = (0u64, 0u32, f64::INFINITY);
    for _ in 0..600 {
        let c = sim.step().unwrap();
        steps_with_contact += u32::from(c.obstacle > 0);
        for p in &sim.world.sensed.pos {
            for &(x, z, r) in &shafts {
                let gap = (p[0] - x).hypot(p[2] - z) - r;
                assert!(
                    gap >= 0.0,
                    "a bee inside a shaft at step {}: {p:?}",
                    sim.step
                );
                min_gap = min_gap.min(gap);
            }
        }
        for g in &sim.groups {
            avoiding += with_group_avoiding(g);
        }
    }
    let passed = sim.world.sensed.pos.iter().filter(|p| p[0] > 40.0).count();
    println!(
        "fig14, 600 steps, {} bees: {} obstacle corrections ({} steps with one), {} bounds \
         corrections, {avoiding} bee-steps avoiding, closest approach {min_gap:.4}, {passed} \
         bees beyond the shafts (x > 40)",
        sim.agents(),
        sim.contacts.obstacle,
        steps_with_contact,
        sim.contacts.bounds,
    );
}

fn with_group_avoiding(g: &AnyBeeGroup) -> u64 {
    match g {
        AnyBeeGroup::F32(g) => g.decisions.iter().filter(|d| d.avoiding).count() as u64,
        AnyBeeGroup::Fixed(g) => g.decisions.iter().filter(|d| d.avoiding).count() as u64,
    }
}

/// Local extrema of `xs` whose swing to the next extremum is at least `min_swing` (so noise
/// of smaller amplitude does not count).
fn turning_points(xs: &[f64], min_swing: f64) -> Vec<(usize, f64)> {
    let mut out: Vec<(usize, f64)> = Vec::new();
    // Zig-zag filter: track the running extreme until the series moves back by `min_swing`.
    let (mut hi, mut lo) = ((0usize, xs[0]), (0usize, xs[0]));
    let mut dir = 0i8;
    for (i, &x) in xs.iter().enumerate() {
        if x > hi.1 {
            hi = (i, x);
        }
        if x < lo.1 {
            lo = (i, x);
        }
        match dir {
            0 if hi.1 - lo.1 >= min_swing => dir = if hi.0 > lo.0 { 1 } else { -1 },
            1 if hi.1 - x >= min_swing => {
                out.push(hi);
                dir = -1;
                lo = (i, x);
            }
            -1 if x - lo.1 >= min_swing => {
                out.push(lo);
                dir = 1;
                hi = (i, x);
            }
            _ => {}
        }
    }
    out
}

/// chen Fig. 15: the bees approach the nest repeatedly (the zig-zag approach, §V-B) without
/// collapsing onto it or flying off.
///
/// Measured with the current controller (seed 15, 1000 steps): the mean distance to the nest
/// centre falls from 27.9 to 9.06 (step 271), rises to 13.26 (step 845) and turns down again:
/// only two turning points in 1000 steps, whatever the swing threshold (0.02 to 0.5). The mean
/// does not oscillate because each bee zig-zags with its own phase (horizontal distance: a median
/// of 4 approaches per bee with a swing of 2 units or more), while the whole swarm slowly climbs
/// (the lift of eq. 2 is never balanced by a weight: mean altitude 15.5 → 25 by step 1000, the
/// nest at 15, about 50 of the 350 bees pressed against the ceiling), which dominates the 3D
/// mean. This test asserts what
/// holds and prints the numbers; it does not claim the swarm-mean oscillation.
#[test]
fn fig15_bees_approach_the_nest_repeatedly() {
    let (sc, mut sim) = scenario_sim("bees-fig15-nest");
    let (c, r) = match sc.object("nest").map(|o| &o.kind) {
        Some(&ObjectKind::Target { center, radius, .. }) => (center.map(f64::from), radius),
        _ => panic!("no nest"),
    };
    let n = sim.agents();
    let dist = |p: &[f64; 3]| {
        ((p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2) + (p[2] - c[2]).powi(2)).sqrt()
    };
    let start = sim.world.sensed.pos.iter().map(dist).sum::<f64>() / n as f64;
    let mut mean = Vec::new();
    let mut horizontal = vec![Vec::new(); n];
    let mut min_single = f64::INFINITY;
    for _ in 0..1000 {
        sim.step().unwrap();
        let pos = sim.positions_by_id();
        let d: Vec<f64> = pos.iter().map(dist).collect();
        min_single = d.iter().copied().fold(min_single, f64::min);
        mean.push(d.iter().sum::<f64>() / n as f64);
        for (h, p) in horizontal.iter_mut().zip(&pos) {
            h.push((p[0] - c[0]).hypot(p[2] - c[2]));
        }
    }
    let turns = turning_points(&mean, 0.25);
    let lowest = mean.iter().copied().fold(f64::INFINITY, f64::min);
    // Approaches per bee: minima of its horizontal distance with a swing of 2 units or more.
    let mut approaches: Vec<usize> = horizontal
        .iter()
        .map(|h| {
            turning_points(h, 2.0)
                .iter()
                .filter(|&&(i, _)| i > 0 && h[i] <= h[i - 1])
                .count()
        })
        .collect();
    approaches.sort_unstable();
    let sample: Vec<String> = mean.iter().step_by(50).map(|m| format!("{m:.2}")).collect();
    let altitude = sim.world.sensed.pos.iter().map(|p| p[1]).sum::<f64>() / n as f64;
    println!(
        "fig15: mean distance to the nest centre every 50 steps (start {start:.2}): [{}]; \
         lowest mean {lowest:.3}, closest single bee {min_single:.3} (nest radius {r}); \
         turning points of the mean (swing >= 0.25): {:?}; approaches per bee (horizontal, \
         swing >= 2): min {} median {} max {}; mean altitude {altitude:.2} (nest {}); \
         contacts {:?}",
        sample.join(", "),
        turns
            .iter()
            .map(|(i, m)| format!("step {}: {m:.2}", i + 1))
            .collect::<Vec<_>>(),
        approaches[0],
        approaches[n / 2],
        approaches[n - 1],
        c[1],
        sim.contacts,
    );
    assert!(lowest > f64::from(r), "the swarm collapsed onto the nest");
    assert!(
        turns.len() >= 2 && mean[999] < start,
        "the mean distance only falls or only grows: {} turning points",
        turns.len()
    );
    assert!(
        approaches[n / 2] >= 3,
        "bees do not approach repeatedly: median {} approaches",
        approaches[n / 2]
    );
}

/// 100,000 bees × 20 steps on 2 threads (`cargo test --release -p swarm-sim bees_throughput --
/// --ignored --nocapture`).
#[test]
#[ignore = "timing; run in release with --ignored --nocapture"]
fn bees_throughput() {
    let r = bench_bees(100_000, 20, 2).unwrap();
    println!(
        "{} bees × {} steps on {} threads: {:.3} s, {:.3e} agent-steps/s ({})",
        r.agents, r.steps, r.threads, r.seconds, r.agent_steps_per_s, r.machine
    );
}
