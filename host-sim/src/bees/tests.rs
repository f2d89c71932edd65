//! Behaviour tests on the built-in bee scenarios, and the throughput measurement.

use super::*;
use crate::scenario::{self, ObjectKind};

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

/// chen Fig. 14: 600 steps through the shaft field. The world must never leave a bee inside a
/// shaft; how often it had to put one back (the controller alone failing to avoid) is printed.
#[test]
fn fig14_no_bee_passes_through_a_shaft() {
    let (sc, mut sim) = scenario_sim("bees-fig14-shafts");
    let shafts: Vec<(f64, f64, f64)> = sc
        .objects
        .iter()
        .filter_map(|o| match o.kind {
            ObjectKind::Shaft { center, radius, .. } => {
                Some((f64::from(center[0]), f64::from(center[1]), f64::from(radius)))
            }
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
                assert!(gap >= 0.0, "a bee inside a shaft at step {}: {p:?}", sim.step);
                min_gap = min_gap.min(gap);
            }
        }
        for g in &sim.groups {
            avoiding += with_group_avoiding(g);
        }
    }
    let passed = sim
        .world
        .sensed
        .pos
        .iter()
        .filter(|p| p[0] > 40.0)
        .count();
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

/// chen Fig. 15: the mean distance of the bees to the nest centre oscillates (the zig-zag
/// approach, §V-B): it neither collapses onto the nest nor keeps growing.
#[test]
fn fig15_bees_approach_the_nest_repeatedly() {
    let (sc, mut sim) = scenario_sim("bees-fig15-nest");
    let (c, r) = match sc.object("nest").map(|o| &o.kind) {
        Some(&ObjectKind::Target { center, radius, .. }) => (center.map(f64::from), radius),
        _ => panic!("no nest"),
    };
    let mut mean = Vec::new();
    let mut min_single = f64::INFINITY;
    for _ in 0..1000 {
        sim.step().unwrap();
        let d: Vec<f64> = sim
            .world
            .sensed
            .pos
            .iter()
            .map(|p| ((p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2) + (p[2] - c[2]).powi(2)).sqrt())
            .collect();
        min_single = d.iter().copied().fold(min_single, f64::min);
        mean.push(d.iter().sum::<f64>() / d.len() as f64);
    }
    let turns = turning_points(&mean, 0.25);
    let lowest = mean.iter().copied().fold(f64::INFINITY, f64::min);
    let sample: Vec<String> = mean.iter().step_by(50).map(|m| format!("{m:.2}")).collect();
    println!(
        "fig15 mean distance to the nest centre every 50 steps: [{}]; lowest mean {lowest:.3}, \
         closest single bee {min_single:.3} (nest radius {r}); turning points (swing >= 0.25): \
         {:?}; contacts {:?}",
        sample.join(", "),
        turns
            .iter()
            .map(|(i, m)| format!("{i}:{m:.2}"))
            .collect::<Vec<_>>(),
        sim.contacts,
    );
    assert!(lowest > f64::from(r), "the swarm collapsed onto the nest");
    assert!(
        turns.len() >= 4,
        "the mean distance does not oscillate: {} turning points",
        turns.len()
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

#[test]
#[ignore]
fn scratch_breakdown() {
    use std::time::Instant;
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
    pool.install(|| {
        let mut sim = bench_bee_world(100_000, 1);
        sim.step().unwrap();
        sim.world.index_positions();
        let w = &sim.world;
        let n = w.len();
        let t0 = Instant::now();
        let mut cand = 0usize;
        for i in 0..n {
            let me = w.sensed.pos[i];
            let p = [me[0] as f32, me[1] as f32, me[2] as f32];
            w.grid.for_each_candidate(p, w.range, |_, _| cand += 1);
        }
        let t_cand = t0.elapsed().as_secs_f64();
        let t0 = Instant::now();
        let mut sx = 0.0f32;
        let mut sj = 0u32;
        for i in 0..n {
            let me = w.sensed.pos[i];
            let p = [me[0] as f32, me[1] as f32, me[2] as f32];
            w.grid.for_each_candidate(p, w.range, |j, q| { sx += q[0]; sj ^= j; });
        }
        println!("sum scan {:.0} ns {sx} {sj}", t0.elapsed().as_secs_f64() / n as f64 * 1e9);
        let t0 = Instant::now();
        for i in 0..n {
            let me = w.sensed.pos[i];
            let p = [me[0] as f32, me[1] as f32, me[2] as f32];
            w.grid.for_each_candidate(p, w.range, |j, _| { sj ^= j; });
        }
        println!("xor scan {:.0} ns {sj}", t0.elapsed().as_secs_f64() / n as f64 * 1e9);
        let t0 = Instant::now();
        let mut inr = 0usize;
        let r2 = w.range * w.range;
        for i in 0..n {
            let me = w.sensed.pos[i];
            let p = [me[0] as f32, me[1] as f32, me[2] as f32];
            w.grid.for_each_candidate(p, w.range, |j, q| {
                let d = (q[0]-p[0])*(q[0]-p[0]) + (q[1]-p[1])*(q[1]-p[1]) + (q[2]-p[2])*(q[2]-p[2]);
                if d < r2 && j as usize != i { inr += 1; }
            });
        }
        let t_inr = t0.elapsed().as_secs_f64();
        println!("in-range count {:.0} ns {inr}", t_inr / n as f64 * 1e9);
        let t0 = Instant::now();
        let mut k = 0usize;
        for i in 0..n {
            k += neighbour_slots(w, i).count();
        }
        let t_nb = t0.elapsed().as_secs_f64();
        let t0 = Instant::now();
        let mut acc2 = 0usize;
        for i in 0..n {
            let f = bee_frame::<f32>(w, i, Some([100.0, 30.0, 100.0]), 1.0);
            acc2 += f.neighbours.len() + f.targets.len() + f.obstacle.is_some() as usize;
        }
        let t_f2 = t0.elapsed().as_secs_f64();
        let t0 = Instant::now();
        for i in 0..n {
            let me = w.sensed.pos[i];
            for o in w.obstacles.iter().filter(|o| o.active) {
                if o.may_be_within(me, 4.0) {
                    let s = w.surface(o, me);
                    acc2 += s.inside as usize;
                }
            }
        }
        let t_ob = t0.elapsed().as_secs_f64();
        println!("frame w/o store {:.0} ns, obstacles {:.0} ns {acc2}", t_f2 / n as f64 * 1e9, t_ob / n as f64 * 1e9);
        let t0 = Instant::now();
        let mut frames = Vec::with_capacity(n);
        for i in 0..n {
            frames.push(bee_frame::<f32>(w, i, Some([100.0, 30.0, 100.0]), 1.0));
        }
        let t_frame = t0.elapsed().as_secs_f64();
        let AnyBeeGroup::F32(g) = &sim.groups[0] else { panic!() };
        let t0 = Instant::now();
        let mut acc = 0.0f32;
        for (i, f) in frames.iter().enumerate() {
            let (d, _) = swarm_core::bee::step_checked(&g.states[i], f, &g.params).unwrap();
            acc += d.density;
        }
        let t_step = t0.elapsed().as_secs_f64();
        let per = |t: f64| t / n as f64 * 1e9;
        println!(
            "candidates/bee {:.1}, neighbours/bee {:.1}: scan {:.0} ns, select {:.0} ns, frame {:.0} ns, controller {:.0} ns ({acc})",
            cand as f64 / n as f64, k as f64 / n as f64, per(t_cand), per(t_nb), per(t_frame), per(t_step)
        );
    });
}

#[test]
#[ignore]
fn scratch_threads() {
    use std::time::Instant;
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| {
            let mut sim = bench_bee_world(100_000, 1);
            sim.step().unwrap();
            let t0 = Instant::now();
            for _ in 0..20 { sim.step().unwrap(); }
            let t = t0.elapsed().as_secs_f64();
            let t0 = Instant::now();
            for _ in 0..20 { sim.world.index_positions(); }
            let ti = t0.elapsed().as_secs_f64();
            let t0 = Instant::now();
            for _ in 0..20 { sim.reorder(); }
            let tr = t0.elapsed().as_secs_f64();
            println!("{threads} threads: {:.0} ns/bee-step, grid {:.0} ns/bee, reorder {:.0} ns/bee", t / 2e6 * 1e9, ti / 2e6 * 1e9, tr / 2e6 * 1e9);
        });
    }
}
