//! Engine tests on the built-in bee scenarios and small worlds, and the throughput
//! measurement. The scenario behaviours of chen Fig. 14 and 15 are tested through the public API
//! in `tests/tests/bee_behaviour.rs`.

use super::*;
use crate::scenario::{self, Action};
use swarm_core::bee::{BeeParams, BeeState};
use swarm_core::{Fx, Vec3};

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

/// One bee of `params` at `pos` flying with `vel`, alone in a 60³ world with the target of
/// Fig. 15 (radius 2.5, 300 virtual particles) at (30, 15, 30) as its goal.
fn bee_at_the_nest<S: crate::scalar::SimScalar>(
    params: BeeParams<f32>,
    pos: [f32; 3],
    vel: [f32; 3],
) -> BeeSim
where
    AnyBeeGroup: From<BeeGroup<S>>,
{
    let mut w = BeeWorld::new(
        [0.0; 3],
        [60.0; 3],
        params.h + 2.0 * params.radius,
        2.0 * params.d0,
    );
    w.targets = vec![BeeTarget::new(0, "nest", [30.0, 15.0, 30.0], 2.5, 300)];
    let bee = BeeState::new(
        Vec3::from_f32(pos[0], pos[1], pos[2]),
        Vec3::from_f32(vel[0], vel[1], vel[2]),
    );
    let params = params.cast::<S>().checked().unwrap();
    let g = BeeGroup::new("one".into(), 0, params, Some(0), vec![bee]);
    BeeSim::new(w, vec![g.into()], 0)
}

/// (d) A bee entering the target's kernel range (h + 2r outside the particle sphere) at the
/// speed limit, flying straight at the target and thrusting toward it (no curl noise to deflect
/// it): the virtual particles stop it well outside the sphere and push it back hard, and it
/// then zig-zags in place without creeping in. Observed (around-nest / optimized presets):
/// first stop 4.07 / 3.92 from the centre (sphere radius 2.5), push-back speed 1.16 / 1.03,
/// never closer afterwards. With the particles mirroring the bee's density (the previous
/// treatment) the around-nest bee first stopped at 3.61 with a push-back of 0.39, then crept
/// through the sphere (0.92 from the centre within 300 steps).
#[test]
fn target_particles_stop_a_bee_at_full_speed_and_push_it_back() {
    for preset in [BeeParams::<f32>::around_nest(), BeeParams::default()] {
        let p = BeeParams {
            kappa2: 0.0,
            ..preset
        };
        let start = 2.5 + 2.0 * p.radius + p.h;
        let mut sim =
            bee_at_the_nest::<f32>(p, [30.0 - start, 15.0, 30.0], [p.max_speed, 0.0, 0.0]);
        let dist = |sim: &BeeSim| {
            let [x, y, z] = sim.world.sensed.pos[0];
            ((x - 30.0).powi(2) + (y - 15.0).powi(2) + (z - 30.0).powi(2)).sqrt()
        };
        // Until the first stop, then the fastest push-back in the next 2 s.
        let mut steps = 0;
        while sim.world.sensed.vel[0][0] > 0.0 && steps < 100 {
            sim.step().unwrap();
            steps += 1;
        }
        let first_stop = dist(&sim);
        let mut push_back = 0.0f64;
        let mut closest = first_stop;
        for k in 0..300 {
            sim.step().unwrap();
            if k < 40 {
                push_back = push_back.max(-sim.world.sensed.vel[0][0]);
            }
            closest = closest.min(dist(&sim));
        }
        println!(
            "first stop {first_stop:.3} after {steps} steps, push-back {push_back:.3}, closest \
             {closest:.3}"
        );
        assert!(first_stop > 3.75, "first stop at {first_stop}");
        assert!(push_back > 0.5, "push-back speed {push_back}");
        assert!(closest > 3.75, "crept in to {closest}");
    }
}

/// (e) Runs longer than 16000 s of frame time (320,000 steps of 0.05 s) go on: the frame time
/// wraps below the controller's input limit ([`frame_time`]), with the same bits before it.
#[test]
fn long_runs_wrap_the_frame_time_below_the_input_limit() {
    for step in [0u32, 1, 12_345, 319_999] {
        assert_eq!(frame_time(step, 0.05), f64::from(step) * 0.05);
    }
    let limit = f64::from(swarm_core::bee::params::LIMIT);
    for step in [320_000u32, 320_001, 1_000_000, u32::MAX] {
        let t = frame_time(step, 0.05);
        assert!(
            t < limit && t >= limit - swarm_core::bee::oscillation::TIME_WRAP,
            "{t}"
        );
    }
    // A bee stepping across the limit, in both scalar types.
    let p = BeeParams::default();
    for mut sim in [
        bee_at_the_nest::<f32>(p, [10.0, 15.0, 30.0], [1.0, 0.0, 0.0]),
        bee_at_the_nest::<Fx>(p, [10.0, 15.0, 30.0], [1.0, 0.0, 0.0]),
    ] {
        sim.step = 319_990;
        for _ in 0..20 {
            sim.step().unwrap();
        }
        assert_eq!(sim.step, 320_010);
    }
}

/// 100,000 bees × 20 steps on 2 threads (`cargo test --release -p swarm-sim bees_throughput --
/// --ignored --nocapture`).
#[test]
#[ignore = "timing; run in release with --ignored --nocapture"]
fn bees_throughput() {
    let r = crate::bench::bench(&crate::bench::BenchSpec {
        threads: Some(2),
        ..crate::bench::BenchSpec::new("bee", 100_000, 20)
    })
    .unwrap();
    println!(
        "{} bees × {} steps on {} threads: {:.3} s, {:.3e} agent-steps/s ({})",
        r.agents, r.steps, r.threads, r.seconds, r.agent_steps_per_s, r.machine
    );
}
