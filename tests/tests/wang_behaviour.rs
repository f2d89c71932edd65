//! The wang2014 behaviours (issue 15, spec §4 W-T12..W-T20) on the built-in scenarios with
//! their fixed seeds (or `SWARM_TEST_SEED`), through the whole simulator (scenario → fields →
//! engine → controller). The numbers quoted in the comments were measured with these seeds.

use swarm_sim::engine::{Engine, apply_due_events};
use swarm_sim::scalar::a3;
use swarm_sim::scenario::{self, ObjectKind, Scenario};
use swarm_sim::wang::{AnyWangGroup, WangSim};
use swarm_tests::{centroid, dist};

fn load(name: &str) -> (Scenario, WangSim) {
    let sc = scenario::builtin(name).expect("built-in scenario");
    let sim = WangSim::from_scenario(&sc, swarm_tests::seed(sc.seed)).expect("builds");
    (sc, sim)
}

/// One tick with the scenario's events, and the measures counted.
fn tick(sc: &Scenario, sim: &mut WangSim) {
    apply_due_events(sim, sc);
    Engine::tick(sim).expect("tick");
    sim.measure();
}

/// The share of `pos` for which `f` holds.
fn share(pos: &[[f64; 3]], f: impl Fn(&[f64; 3]) -> bool) -> f64 {
    pos.iter().filter(|p| f(p)).count() as f64 / pos.len().max(1) as f64
}

/// W-T12 and W-T13 after a run: nobody ever ended a step inside an obstacle (the world's
/// backstop moved no insect out of one: it puts such an insect back on the surface, so its
/// position afterwards cannot show it), the world's corrections (back into the box) ≤ 1e-4 per
/// insect-step, MDE below 1 % of the insects per step.
#[track_caller]
fn physical_and_mde(sim: &WangSim) {
    let m = sim.metrics.to_json();
    let per = m["world_corrections_per_agent_step"].as_f64().unwrap();
    let mde = m["mde_percent_mean"].as_f64().unwrap();
    eprintln!(
        "out of an obstacle {}, world corrections per insect-step {per:.2e}, MDE {mde:.3} % \
         per step",
        sim.total.obstacle
    );
    assert_eq!(sim.total.obstacle, 0, "insects moved out of an obstacle");
    assert!(per <= 1e-4, "world corrections per insect-step: {per}");
    assert!(mde < 1.0, "MDE share {mde} %");
}

/// Fig. 6 (W-T14): ≥ 95 % of the insects in the goal box by the end, every one that got past
/// the blocks went through the passage (x in [27, 33] while z in [50, 62]), nobody inside a
/// block at any step.
#[test]
fn fig6_the_swarm_flies_through_the_passage_to_the_goal() {
    let (sc, mut sim) = load("wang-fig6-two-blocks");
    let n = sim.agents();
    let mut outside_passage = 0usize;
    for _ in 0..sc.steps {
        tick(&sc, &mut sim);
        let pos = sim.positions_by_id();
        outside_passage += pos
            .iter()
            .filter(|p| (50.0..=62.0).contains(&p[2]) && !(27.0..=33.0).contains(&p[0]))
            .count();
    }
    let pos = sim.positions_by_id();
    let arrived = share(&pos, |p| (100.0..=110.0).contains(&p[2]));
    eprintln!("fig. 6: {:.1} % of {n} in the goal", 100.0 * arrived);
    assert!(arrived >= 0.95, "{arrived}");
    assert_eq!(outside_passage, 0);
    physical_and_mde(&sim);
}

/// Fig. 7: with routes through, round and over the blocks, insects starting at different
/// places take different ones, and they arrive.
#[test]
fn fig7_insects_take_their_own_minimum_cost_routes() {
    let (sc, mut sim) = load("wang-fig7-min-cost");
    // Route of each insect where it crosses the blocks' slab: 0 passage, 1 round, 2 over.
    let mut route = vec![None; sim.agents()];
    for _ in 0..sc.steps {
        tick(&sc, &mut sim);
        for (r, p) in route.iter_mut().zip(sim.positions_by_id()) {
            if r.is_none() && (55.0..=57.0).contains(&p[2]) {
                *r = Some(if p[1] > 25.0 {
                    2
                } else if (27.0..=33.0).contains(&p[0]) {
                    0
                } else {
                    1
                });
            }
        }
    }
    let counts = [0, 1, 2].map(|k| route.iter().filter(|r| **r == Some(k)).count());
    eprintln!(
        "fig. 7: passage {}, round {}, over {}",
        counts[0], counts[1], counts[2]
    );
    assert!(
        counts.iter().filter(|&&c| c >= 10).count() >= 2,
        "{counts:?}"
    );
    let arrived = share(&sim.positions_by_id(), |p| (100.0..=110.0).contains(&p[2]));
    assert!(arrived >= 0.95, "{arrived}");
    physical_and_mde(&sim);
}

/// Fig. 8 (W-T15): after each move of the ball, the swarm's centroid comes within 4 m of it
/// within 20 s; nobody inside the ball or an obstacle.
#[test]
fn fig8_the_swarm_chases_the_ball() {
    let (sc, mut sim) = load("wang-fig8-chasing");
    let ball = |sc: &Scenario, step: u32| {
        let mut c = match sc.object("ball").map(|o| &o.kind) {
            Some(ObjectKind::Sphere { center, .. }) => center.map(f64::from),
            _ => panic!("no ball"),
        };
        for e in sc.events.iter().filter(|e| e.step <= step) {
            if let scenario::Action::Move { object, to } = &e.action
                && object == "ball"
            {
                c = [0, 1, 2].map(|k| f64::from(to[k]));
            }
        }
        c
    };
    let dt = 0.01;
    let mut caught_at: Vec<(u32, Option<u32>)> = std::iter::once(0)
        .chain(sc.events.iter().map(|e| e.step))
        .map(|s| (s, None))
        .collect();
    for _ in 0..sc.steps {
        tick(&sc, &mut sim);
        let step = sim.step;
        let c = centroid(&sim.positions_by_id());
        let d = dist(c, ball(&sc, step - 1));
        for (from, caught) in &mut caught_at {
            let next = sc
                .events
                .iter()
                .map(|e| e.step)
                .find(|&s| s > *from)
                .unwrap_or(sc.steps);
            if caught.is_none() && step > *from && step <= next && d < 4.0 {
                *caught = Some(step - *from);
            }
        }
    }
    eprintln!("fig. 8: caught after (steps) {caught_at:?}");
    for (from, caught) in &caught_at {
        let t = caught.map(|s| f64::from(s) * dt);
        assert!(
            t.is_some_and(|t| t <= 20.0),
            "the ball placed at step {from}: {t:?} s"
        );
    }
    physical_and_mde(&sim);
}

/// Fig. 9 (W-T16): over the run the centroid drifts less than 1 m and at least 90 % of the
/// insects stay within 5 m of the goal's centre.
#[test]
fn fig9_the_swarm_aggregates_where_it_started() {
    let (sc, mut sim) = load("wang-fig9-aggregation");
    let center = [10.0; 3];
    let c0 = centroid(&sim.positions_by_id());
    let (mut drift, mut least) = (0.0f64, 1.0f64);
    for _ in 0..sc.steps {
        tick(&sc, &mut sim);
        if sim.step % 100 == 0 {
            let pos = sim.positions_by_id();
            drift = drift.max(dist(centroid(&pos), c0));
            least = least.min(share(&pos, |p| dist(*p, center) < 5.0));
        }
    }
    eprintln!("fig. 9: centroid drift {drift:.2} m, least share within 5 m {least:.3}");
    assert!(drift < 1.0, "{drift}");
    assert!(least >= 0.9, "{least}");
    physical_and_mde(&sim);
}

/// Fig. 10 (W-T17): the share of moths within 3 m of the lamp head grows from start to end
/// and stays at 50 % or more over the second half of the run.
#[test]
fn fig10_moths_gather_at_the_lamp() {
    let (sc, mut sim) = load("wang-fig10-phototaxis");
    let head = [50.0, 6.5, 50.0];
    let near = |sim: &WangSim| share(&sim.positions_by_id(), |p| dist(*p, head) < 3.0);
    let start = near(&sim);
    let mut least_late = 1.0f64;
    for _ in 0..sc.steps {
        tick(&sc, &mut sim);
        if sim.step >= sc.steps / 2 {
            least_late = least_late.min(near(&sim));
        }
    }
    let end = near(&sim);
    eprintln!(
        "fig. 10: near the lamp {start:.2} → {end:.2}, least over the second half {least_late:.2}"
    );
    assert!(end > start, "{start} → {end}");
    assert!(least_late >= 0.5, "{least_late}");
    physical_and_mde(&sim);
}

/// Fig. 1a (W-T18): ≥ 95 % of the locusts reach the goal, and they cross the hamlet in a
/// coordinated way (polarisation of those among the houses ≥ 0.8).
#[test]
fn fig1a_locusts_cross_the_hamlet_together() {
    let (sc, mut sim) = load("wang-fig1a-locusts");
    let mut reached = vec![false; sim.agents()];
    let (mut phi_sum, mut phi_steps) = (0.0, 0u32);
    for _ in 0..sc.steps {
        tick(&sc, &mut sim);
        let (pos, vel) = (sim.positions_by_id(), sim.velocities_by_id());
        for (r, p) in reached.iter_mut().zip(&pos) {
            *r |= p[0] >= 105.0;
        }
        let among: Vec<[f64; 3]> = pos
            .iter()
            .zip(&vel)
            .filter(|(p, _)| (40.0..=78.0).contains(&p[0]))
            .map(|(_, v)| *v)
            .collect();
        if among.len() * 5 >= pos.len() {
            phi_sum += swarm_sim::wang::metrics::polarisation(&among);
            phi_steps += 1;
        }
    }
    let arrived = reached.iter().filter(|&&r| r).count() as f64 / reached.len() as f64;
    let phi = phi_sum / f64::from(phi_steps.max(1));
    eprintln!(
        "fig. 1a: {:.1} % reached, polarisation crossing {phi:.3} over {phi_steps} steps",
        100.0 * arrived
    );
    assert!(arrived >= 0.95, "{arrived}");
    assert!(phi_steps > 0 && phi >= 0.8, "{phi} over {phi_steps} steps");
    physical_and_mde(&sim);
}

/// Group `name`'s positions and speeds, by id.
fn group_state(sim: &WangSim, name: &str) -> (Vec<[f64; 3]>, Vec<f64>) {
    let g = sim
        .groups
        .iter()
        .find(|g| swarm_sim::scalar::AgentGroup::name(*g) == name)
        .expect("group");
    let states = match g {
        AnyWangGroup::F32(g) => g.by_id().into_iter().map(|(_, s)| (a3(s.pos), a3(s.vel))),
        AnyWangGroup::Fixed(_) => panic!("an f32 group"),
    };
    states
        .map(|(p, v)| (p, (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()))
        .unzip()
}

fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len().max(1) as f64
}

fn msd(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    mean(
        &a.iter()
            .zip(b)
            .map(|(p, q)| dist(*p, *q).powi(2))
            .collect::<Vec<_>>(),
    )
}

/// Figs. 11 and 13 (W-T19, W-T20), noise only (Δt 0.004 s): after 10 s the mean speed at the insects'
/// positions is ≥ 0.9 of its start value with curl noise (volume-preserving: they keep
/// sampling the field uniformly) and ≤ 0.4 with Perlin noise (they settle at its sinks);
/// curl noise spreads the insects ≥ 3× farther than random noise (mean squared displacement
/// at 1 s and at 10 s). The three groups have the same mean speed at the start (±15 %).
#[test]
fn fig13_curl_noise_keeps_speed_and_spreads_perlin_gathers_random_vibrates() {
    let (sc, mut sim) = load("wang-fig13-noise-compare");
    let names = ["curl", "perlin", "random"];
    let start: Vec<_> = names.iter().map(|n| group_state(&sim, n).0).collect();
    tick(&sc, &mut sim);
    let first: Vec<f64> = names
        .iter()
        .map(|n| mean(&group_state(&sim, n).1))
        .collect();
    eprintln!("mean speeds at the start: {first:?}");
    for s in &first[1..] {
        assert!((s / first[0] - 1.0).abs() < 0.15, "{first:?}");
    }
    let mut msd_1s = [0.0; 3];
    for _ in 1..sc.steps {
        tick(&sc, &mut sim);
        if sim.step == 250 {
            for (k, n) in names.iter().enumerate() {
                msd_1s[k] = msd(&group_state(&sim, n).0, &start[k]);
            }
        }
    }
    let ratio: Vec<f64> = names
        .iter()
        .zip(&first)
        .map(|(n, f)| mean(&group_state(&sim, n).1) / f)
        .collect();
    let msd_end: Vec<f64> = names
        .iter()
        .enumerate()
        .map(|(k, n)| msd(&group_state(&sim, n).0, &start[k]))
        .collect();
    eprintln!("speed ratios {ratio:?}, MSD at 1 s {msd_1s:?}, at 10 s {msd_end:?}");
    assert!(ratio[0] >= 0.9, "curl {}", ratio[0]);
    assert!(ratio[1] <= 0.4, "perlin {}", ratio[1]);
    assert!(msd_1s[0] >= 3.0 * msd_1s[2], "{msd_1s:?}");
    assert!(msd_end[0] >= 3.0 * msd_end[2], "{msd_end:?}");
}
