//! The li2015 GPU engine against the CPU engine: the same simulation tick by tick, every
//! insect's state, decision (preferred velocity, proposals, acceptance, infeasible),
//! corrections and truncation, the counts, the recorded frame, the measures and every exchange
//! the mirror would send, over `Fx` bit for bit; `f32` measured; and the two sides of the
//! layout.
//!
//! `cargo test -p swarm-sim --lib gpu::li -- --nocapture` prints what each run covered.

use swarm_core::li::waypoint::{SAMPLING_MESO, SAMPLING_RANDOM};
use swarm_core::li::{BINS, LiParams, WIRE_LI_NEIGHBOURS};
use swarm_core::rand::stream;
use swarm_core::{Fx, Scalar, Vec3};

use super::layout::{self, FIELDS, WGSL_CONSTANTS, status_error, status_of};
use super::{GpuLiSim, modules, wgsl_shared};
use crate::engine::Engine;
use crate::gpu::shaders::{LI_STEP, LI_TICK};
use crate::gpu::tests::harness::{StatusWords, assert_constants, assert_valid_wgsl, fixed};
use crate::gpu::{break_two_inverted, same_refusal, test_gpu};
use crate::li::{LiGroup, LiSim, bench_li_world};
use crate::scalar::ByScalar;
use crate::scenario::{ScalarType, builtin_names};

/// Every insect's words, in id order: its state, its last decision, the corrections and the
/// truncation of the last tick.
fn words(sim: &LiSim) -> Vec<(u32, Vec<u32>)> {
    fn of(g: &LiGroup<Fx>, out: &mut Vec<(u32, Vec<u32>)>) {
        for k in 0..g.states.len() {
            let mut w = Vec::new();
            layout::write_state(&mut w, &g.states[k]);
            let d = g.decisions[k];
            w.extend([d.pref.x, d.pref.y, d.pref.z].map(|v| v.to_bits() as u32));
            w.extend([
                u32::from(d.proposals),
                u32::from(d.accepted),
                u32::from(d.infeasible),
                u32::from(g.corrected[k]),
                u32::from(g.truncated[k]),
            ]);
            out.push((g.ids[k], w));
        }
    }
    let mut out = Vec::new();
    for g in &sim.groups {
        match g {
            ByScalar::Fixed(g) => of(g, &mut out),
            ByScalar::F32(_) => panic!("fixed point only"),
        }
    }
    out.sort_by_key(|e| e.0);
    out
}

/// Runs the simulation `make` builds for `ticks` ticks on both engines and compares them after
/// every `every`-th tick (and the last): every word of every insect, the counts, the recorded
/// frame, the measures, and the exchange of every insect. Returns the CPU's run.
fn same_run(name: &str, make: impl Fn() -> LiSim, ticks: u32, every: u32) -> LiSim {
    let mut cpu = make();
    let mut gpu = GpuLiSim::new(make(), test_gpu()).unwrap();
    let ids: Vec<u32> = (0..cpu.agents() as u32).collect();
    let mut summary = crate::output::Summary::default();
    let mut exchanges = 0;
    for t in 0..ticks {
        let look = (t + 1) % every == 0 || t + 1 == ticks;
        Engine::decide(&mut cpu, 0).unwrap();
        gpu.decide(0).unwrap();
        if look {
            let (a, b) = (
                Engine::exchanges(&cpu, 0, &ids).unwrap(),
                gpu.exchanges(0, &ids).unwrap(),
            );
            assert_eq!(a.len(), b.len());
            for (x, y) in a.iter().zip(&b) {
                let what = format!("{name}: exchange of insect {} in tick {t}", x.agent);
                assert_eq!((x.agent, x.phase), (y.agent, y.phase), "{what}");
                assert!(x.request.bytes == y.request.bytes, "{what}: request");
                assert!(x.reply.bytes == y.reply.bytes, "{what}: reply");
            }
            exchanges += a.len();
        }
        Engine::publish(&mut cpu, 0).unwrap();
        gpu.publish(0).unwrap();
        Engine::after_tick(&mut cpu, &mut summary);
        gpu.after_tick(&mut summary);
        if look {
            gpu.sync().unwrap();
            let g = gpu.sim();
            let (a, b) = (words(&cpu), words(g));
            assert_eq!(a.len(), b.len());
            for (x, y) in a.iter().zip(&b) {
                assert_eq!(x, y, "{name}: insect {} after tick {}", x.0, t + 1);
            }
            assert_eq!(cpu.last, g.last, "{name}: the counts of tick {}", t + 1);
            assert_eq!(cpu.total, g.total, "{name}: counts after tick {}", t + 1);
            assert_eq!(cpu.step, g.step);
            let what = format!("{name}: measures after tick {}", t + 1);
            assert!(cpu.measures == g.measures, "{what}");
            assert_eq!(Engine::frame(&cpu), gpu.frame(), "{name}: recorded frame");
        }
    }
    println!(
        "{name}: {ticks} ticks, {exchanges} exchanges: {:?}",
        cpu.total
    );
    cpu
}

/// The bench world in fixed point with `n` insects, parameters `tune`d, and a jam: every 20th
/// insect packed into a ball around the first one's position, flying in from every side
/// (infeasible programs, truncated frames), and every 30th put just outside the container (the
/// world's corrections).
fn jammed(n: usize, seed: u32, tune: impl Fn(&mut LiParams<Fx>)) -> LiSim {
    let mut sim = bench_li_world(n, seed, ScalarType::Fixed);
    let top = sim.world.max[1];
    if let ByScalar::Fixed(g) = &mut sim.groups[0] {
        let mut p: LiParams<Fx> = (*g.params).clone();
        tune(&mut p);
        g.params = p.checked().unwrap();
        let centre = g.states[0].pos.to_f32();
        for (k, s) in g.states.iter_mut().enumerate() {
            let a = k as f32 * 2.399_963;
            let (u, v) = (a.sin(), a.cos());
            if k % 20 == 0 {
                let q = centre + Vec3::new(0.012 * v, 0.01 * u, 0.012 * u * v);
                s.pos = Vec3::from_f32(q.x, q.y, q.z);
                s.vel = Vec3::from_f32(-0.4 * v, -0.3 * u, 0.2 * u * v);
            } else if k % 30 == 7 {
                s.pos.y = Fx::from_f32(top + 0.01);
                s.vel.y = Fx::from_f32(0.1);
            }
        }
    }
    // The states changed: the sensed world too.
    LiSim::new(sim.world, sim.groups, seed)
}

/// The bench world with a jam and a short range (truncated frames), Metropolis-Hastings.
#[test]
fn the_bench_world_is_the_cpus() {
    let cpu = same_run("bench", || jammed(300, 5, |_| {}), 30, 6);
    let t = cpu.total;
    assert!(t.infeasible > 0, "ORCA must be infeasible to test it");
    assert!(t.truncated > 0, "frames must be truncated to test it");
    assert!(t.corrected > 0, "the world must correct to test it");
    assert!(
        t.arrivals > 0 && t.proposals > t.arrivals,
        "rejections to test"
    );
}

/// The other samplings (meso, random), one proposal an arrival (holds), a short patience
/// (waypoints given up), the zero-velocity fallback, fewer ORCA neighbours.
#[test]
fn the_samplings_and_fallbacks_are_the_cpus() {
    let one = |p: &mut LiParams<Fx>| {
        p.proposals = 1;
        p.patience = 3;
        p.fallback = 0;
        p.orca_neighbours = 5;
    };
    let cpu = same_run("one proposal, stop", || jammed(200, 6, one), 20, 5);
    assert!(cpu.total.held > 0, "insects must hold to test it");
    for (name, sampling) in [("meso", SAMPLING_MESO), ("random", SAMPLING_RANDOM)] {
        same_run(name, || jammed(150, 7, |p| p.sampling = sampling), 12, 4);
    }
}

/// Every built-in li scenario (`li-*`): the confined swarm of Fig. 4, the sketched ring and S of
/// Fig. 5, the lights and obstacles of Fig. 6, the coarse grid of Figs. 8-9, and whatever li
/// scenario joins them.
#[test]
fn the_li_scenarios_are_the_cpus() {
    let names: Vec<&str> = builtin_names()
        .iter()
        .copied()
        .filter(|n| n.starts_with("li-"))
        .collect();
    assert!(names.contains(&"li-fig4-confined") && names.contains(&"li-fig6-lights"));
    for name in names {
        let sc = fixed(name, 40);
        same_run(name, || LiSim::from_scenario(&sc, sc.seed).unwrap(), 40, 10);
    }
}

/// A route of lights moves each group's density on between steps (the host sees every step
/// until the last light is reached): lights reached at the same steps, the same insects.
#[test]
fn a_route_is_the_cpus() {
    let mut sc = fixed("li-fig6-lights", 60);
    // Every light reached as soon as a twentieth of the density's own share is within 40 m (the
    // whole room): the density moves on at once.
    for g in &mut sc.groups {
        let mut t: crate::li::LiTable = g.params_as().unwrap();
        let route = t.density.route.as_mut().unwrap();
        route.share = 0.05;
        route.reach = 40.0;
        g.set_params(&t).unwrap();
    }
    let cpu = same_run(
        "route",
        || LiSim::from_scenario(&sc, sc.seed).unwrap(),
        60,
        12,
    );
    let run = cpu.measures.routes[0].as_ref().unwrap();
    assert!(
        run.reached.len() >= 2,
        "the route must move on to test it: {:?}",
        run.reached
    );
}

/// A refusal on the GPU is the CPU's error: the same step, insect and field.
#[test]
fn a_refusal_is_the_cpus() {
    let make = || {
        let mut sim = bench_li_world(100, 3, ScalarType::Fixed);
        if let ByScalar::Fixed(g) = &mut sim.groups[0] {
            // A waypoint far outside every limit: the state is refused.
            let k = g.states.len() / 2;
            g.states[k].waypoint.z = Fx::from_f32(20_000.0);
        }
        LiSim::new(sim.world, sim.groups, 3)
    };
    let mut gpu = GpuLiSim::new(make(), test_gpu()).unwrap();
    let e = same_refusal(&mut make(), &mut gpu);
    assert!(e.contains("state.waypoint"), "{e}");
}

/// Two insects refused in one tick: both engines name the lower id, whatever slots they hold.
#[test]
fn two_refusals_name_the_lower_id() {
    // A neighbour range of 0.2 m splits the 0.91 m cube into cells (the scenario's 1.48 m
    // makes one cell, where slots stay in id order).
    let mut sc = fixed("li-fig4-confined", 1);
    let table = sc.groups[0].params.get_or_insert_with(toml::Table::new);
    table.insert("range".into(), toml::Value::Float(0.2));
    let make = || {
        let mut sim = LiSim::from_scenario(&sc, sc.seed).unwrap();
        let ByScalar::Fixed(g) = &mut sim.groups[0] else {
            panic!("fixed point");
        };
        let lower = break_two_inverted(&g.ids, &mut g.states, |s| {
            s.waypoint.z = Fx::from_f32(20_000.0)
        });
        (sim, lower)
    };
    let (mut cpu, lower) = make();
    let mut gpu = GpuLiSim::new(make().0, test_gpu()).unwrap();
    let e = same_refusal(&mut cpu, &mut gpu);
    assert!(e.contains(&format!("agent {lower} ")), "{e}");
}

/// `f32` on the GPU is measured, not promised: after 40 ticks of the bench world the positions
/// stay within 1e-4 units of the CPU's (printed with `--nocapture`).
#[test]
fn f32_stays_near_the_cpu() {
    let make = || bench_li_world(300, 9, ScalarType::F32);
    let mut cpu = make();
    let mut gpu = GpuLiSim::new(make(), test_gpu()).unwrap();
    for _ in 0..40 {
        Engine::tick(&mut cpu).unwrap();
        Engine::tick(&mut gpu).unwrap();
    }
    gpu.sync().unwrap();
    let (a, b) = (cpu.positions_by_id(), gpu.sim().positions_by_id());
    let worst = a
        .iter()
        .zip(&b)
        .map(|(p, q)| (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>().sqrt())
        .fold(0.0, f64::max);
    println!("f32: after 40 ticks, largest difference {worst:e}");
    assert!(worst < 1e-4, "{worst}");
}

#[test]
fn the_kernels_are_valid_wgsl() {
    assert_valid_wgsl("li tick", modules, "");
}

/// The layout's, the engine's and the controller's constants in the shaders are Rust's.
#[test]
fn the_shaders_constants_are_rusts() {
    let wgsl = format!("{}{}", LI_TICK.source, LI_STEP.source);
    assert_constants(&wgsl, WGSL_CONSTANTS, true);
    let shared = wgsl_shared();
    let shared: Vec<(&str, u32)> = shared.iter().map(|(n, v)| (n.as_str(), *v)).collect();
    assert_constants(&wgsl, &shared, true);
    let step: &[(&str, u32)] = &[
        (
            "LI_SAMPLING_MH",
            u32::from(swarm_core::li::waypoint::SAMPLING_MH),
        ),
        ("LI_SAMPLING_RANDOM", u32::from(SAMPLING_RANDOM)),
        ("LI_BINS", BINS as u32),
        ("RAND_LI_LENGTH", stream::LI_LENGTH),
        ("RAND_LI_TURN", stream::LI_TURN),
        ("RAND_LI_AZIMUTH", stream::LI_AZIMUTH),
        ("RAND_LI_HEIGHT", stream::LI_HEIGHT),
        ("RAND_LI_ACCEPT", stream::LI_ACCEPT),
    ];
    assert_constants(LI_STEP.source, step, true);
    // The table's binary search halves the bins this many times.
    let halvings = usize::BITS - BINS.leading_zeros();
    assert!(
        LI_STEP
            .source
            .contains(&format!("const LI_SEARCH_STEPS: u32 = {halvings}u;"))
    );
    // The frame is the fly's, its capacity the li wire's; its field codes the fly's.
    assert_eq!(WIRE_LI_NEIGHBOURS, swarm_core::fly::WIRE_FLY_NEIGHBOURS);
    for (code, field) in FIELDS.iter().enumerate() {
        if field.starts_with("frame.") || ["pref", "next.pos"].contains(field) {
            assert_eq!(crate::gpu::fly::layout::FIELDS[code], *field);
        }
    }
    assert_eq!(layout::TABLE_WORDS, 3 + BINS);
    // The group's words follow the parameters' fields.
    let p = bench_li_world(10, 1, ScalarType::Fixed);
    let ByScalar::Fixed(g) = &p.groups[0] else {
        panic!("fixed point")
    };
    let mut w = Vec::new();
    layout::write_group(&mut w, &g.params);
    assert_eq!(w.len(), layout::GROUP_WORDS);
    assert_eq!(w[6], g.params.range.to_bits() as u32);
    assert_eq!(w[layout::GROUP_PATIENCE], u32::from(g.params.patience));
    assert_eq!(w[layout::GROUP_PATIENCE + 4], u32::from(g.params.fallback));
    let t = layout::GROUP_TURNS;
    assert_eq!(w[t + 2] as usize, g.params.turns.cdf.len());
    assert_eq!(w[t + 3], g.params.turns.cdf[0].to_bits() as u32);
    let d = layout::GROUP_DENSITY;
    assert_eq!(w[d + 3], g.params.density.cell.to_bits() as u32);
    assert_eq!(w[d + 6], u32::from(g.params.density.dims[2]));
    let weights = &g.params.density.weights;
    let k = weights.len() / 2 + 1;
    let word = w[layout::GROUP_WEIGHTS + k / 4];
    assert_eq!((word >> (8 * (k % 4))) & 0xff, u32::from(weights[k]));
}

#[test]
fn status_words_are_the_shaders() {
    StatusWords {
        wgsl: LI_STEP.source,
        file: "li_step.wgsl",
        prefix: "LI",
        fields: &FIELDS,
        kinds: 3,
        indices: [None, Some(0), Some(15)],
        status_of,
        status_error,
    }
    .check();
}
