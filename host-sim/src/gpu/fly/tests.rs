//! The ren2016 GPU engine against the CPU engine: the same simulation tick by tick, every
//! insect's state, decision (preferred velocity, infeasible), corrections and truncation, the
//! counts, the recorded frame and every exchange the mirror would send, over `Fx` bit for bit;
//! `f32` measured; and the two sides of the layout.
//!
//! `cargo test -p swarm-sim --lib gpu::fly -- --nocapture` prints what each run covered.

use swarm_core::fly::{
    FALLBACK_LP4, FlyParams, NOISE_CURL, NOISE_GAUSSIAN, NOISE_NONE, NOISE_PERLIN, NOISE_WHITE,
    STIMULUS_PREDATOR, STIMULUS_TARGET, WIRE_FLY_NEIGHBOURS, WIRE_FLY_SURFACES,
};
use swarm_core::orca3d::RVO_EPSILON;
use swarm_core::rand::stream;
use swarm_core::{Fx, Scalar, Vec3};

use super::engine::{GpuFlySim, modules, wgsl_shared};
use super::layout::{self, FIELDS, WGSL_CONSTANTS, status_error, status_of};
use crate::engine::{Engine, apply_due_events};
use crate::fly::{FlyGroup, FlySim, bench_fly_world};
use crate::gpu::shaders::{FLY_STEP, FLY_TICK};
use crate::gpu::tests::harness::{StatusWords, assert_constants, assert_valid_wgsl, fixed};
use crate::gpu::{break_two_inverted, comparison_steps, same_refusal, test_gpu};
use crate::scalar::ByScalar;
use crate::scenario::{ScalarType, Scenario, builtin, builtin_names};

/// Every insect's words, in id order: its state, its last decision, the corrections and the
/// truncation of the last tick.
fn words(sim: &FlySim) -> Vec<(u32, Vec<u32>)> {
    fn of(g: &FlyGroup<Fx>, out: &mut Vec<(u32, Vec<u32>)>) {
        for k in 0..g.states.len() {
            let mut w = Vec::new();
            layout::write_state(&mut w, &g.states[k]);
            let d = g.decisions[k];
            w.extend([d.pref.x, d.pref.y, d.pref.z].map(|v| v.to_bits() as u32));
            w.extend([
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

/// What a run covered (on the CPU): the ticks and exchanges compared, the insect-ticks with an
/// infeasible program, a truncated frame, an escape, a world correction.
#[derive(Debug, Default)]
struct Covered {
    ticks: u32,
    exchanges: usize,
    infeasible: u64,
    truncated: u64,
    escaping: u64,
    corrected: u64,
}

/// Runs the simulation `make` builds for `ticks` ticks on both engines (with the events of
/// `events`) and compares them after every `every`-th tick (and the last): every word of every
/// insect, the counts, the recorded frame, and the exchange of every insect.
fn same_run(
    name: &str,
    make: impl Fn() -> FlySim,
    ticks: u32,
    every: u32,
    events: Option<&Scenario>,
) -> Covered {
    let mut cpu = make();
    let mut gpu = GpuFlySim::new(make(), test_gpu()).unwrap();
    let ids: Vec<u32> = (0..cpu.agents() as u32).collect();
    let mut covered = Covered::default();
    for t in 0..ticks {
        if let Some(sc) = events {
            apply_due_events(&mut cpu, sc);
            apply_due_events(&mut gpu, sc);
        }
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
            covered.exchanges += a.len();
        }
        Engine::publish(&mut cpu, 0).unwrap();
        gpu.publish(0).unwrap();
        covered.escaping += Engine::frame(&cpu)
            .agents
            .iter()
            .map(|a| u64::from(a.label))
            .sum::<u64>();
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
            assert_eq!(Engine::frame(&cpu), gpu.frame(), "{name}: recorded frame");
            covered.ticks += 1;
        }
    }
    covered.infeasible = cpu.total.infeasible;
    covered.truncated = cpu.total.truncated;
    covered.corrected = cpu.total.obstacle + cpu.total.bounds;
    println!("{name}: {ticks} ticks: {covered:?}");
    covered
}

/// The bench world in fixed point with `n` insects, parameters `tune`d, and a jam: every 25th
/// insect packed into a ball of radius 0.4 around the first one's position, flying in from
/// every side (infeasible programs, truncated frames), and every 60th put just outside the
/// container (the world's corrections).
fn jammed(n: usize, seed: u32, tune: impl Fn(&mut FlyParams<Fx>)) -> FlySim {
    let mut sim = bench_fly_world(n, seed, ScalarType::Fixed);
    let top = sim.world.max[1];
    if let ByScalar::Fixed(g) = &mut sim.groups[0] {
        let mut p: FlyParams<Fx> = *g.params;
        tune(&mut p);
        g.params = p.checked().unwrap();
        let centre = g.states[0].pos.to_f32();
        for (k, s) in g.states.iter_mut().enumerate() {
            let a = k as f32 * 2.399_963;
            let (u, v) = (a.sin(), a.cos());
            if k % 25 == 0 {
                let off = Vec3::new(0.4 * v, 0.3 * u, 0.4 * u * v);
                let p = centre + off;
                s.pos = Vec3::from_f32(p.x, p.y, p.z);
                s.vel = Vec3::from_f32(-6.0 * v, -4.0 * u, 3.0 * u * v);
            } else if k % 60 == 7 {
                s.pos.y = Fx::from_f32(top + 0.2);
                s.vel.y = Fx::from_f32(2.0);
            }
        }
    }
    // The states changed: the sensed world too.
    FlySim::new(sim.world, sim.groups, seed)
}

/// The bench world (midges, curl noise, the paper's zero-velocity fallback) with a jam.
#[test]
fn the_bench_world_is_the_cpus() {
    let c = same_run("bench", || jammed(400, 5, |_| {}), 40, 8, None);
    assert!(
        c.infeasible > 0,
        "ORCA must be infeasible for this test to test it"
    );
    assert!(
        c.truncated > 0,
        "frames must be truncated for this test to test it"
    );
    assert!(
        c.corrected > 0,
        "the world must correct for this test to test it"
    );
}

/// LP4's fallback, alignment, white noise; Gaussian, Perlin and no noise.
#[test]
fn the_fallbacks_and_noises_are_the_cpus() {
    let lp4 = |p: &mut FlyParams<Fx>| {
        p.fallback = FALLBACK_LP4;
        p.noise = NOISE_WHITE;
        p.chi_ali = Fx::from_f32(5.0);
        p.r_ali = Fx::from_f32(1.2);
        p.orca_neighbours = 10;
    };
    let c = same_run("lp4 + white", || jammed(300, 6, lp4), 30, 6, None);
    assert!(c.infeasible > 0, "LP4 must act for this test to test it");
    for (name, noise) in [
        ("gaussian", NOISE_GAUSSIAN),
        ("perlin", NOISE_PERLIN),
        ("none", NOISE_NONE),
    ] {
        same_run(name, || jammed(150, 7, |p| p.noise = noise), 12, 6, None);
    }
}

/// Every built-in fly scenario (`fly-*`, its events moved into the run, 30,000 insect-ticks and
/// 20 to 300 ticks: [`comparison_steps`]): the midges of Fig. 1,
/// the predator of Fig. 8 added, moved through the swarm and removed (escape angles drawn), and
/// whatever fly scenario joins them.
#[test]
fn the_fly_scenarios_are_the_cpus() {
    let names: Vec<&str> = builtin_names()
        .iter()
        .copied()
        .filter(|n| n.starts_with("fly-"))
        .collect();
    assert!(names.contains(&"fly-fig1-midges") && names.contains(&"fly-fig8-escape"));
    for name in names {
        let agents = builtin(name).unwrap().agents();
        let sc = fixed(name, comparison_steps(agents, 30_000, 20, 300));
        let make = || FlySim::from_scenario(&sc, sc.seed).unwrap();
        let c = same_run(name, make, sc.steps, 25, Some(&sc));
        if sc.groups.iter().any(|g| g.threat.is_some()) {
            assert!(
                c.escaping > 0,
                "{name}: the flies must escape for this test to test it"
            );
        }
    }
}

/// Fig. 8 with escape angles drawn on both sides (`escape_sides` 1, U[−π/2, π/2]).
#[test]
fn both_escape_sides_are_the_cpus() {
    let sc = fixed("fly-fig8-escape", 150);
    let make = || {
        let mut sim = FlySim::from_scenario(&sc, sc.seed).unwrap();
        for g in &mut sim.groups {
            if let ByScalar::Fixed(g) = g {
                let mut p: FlyParams<Fx> = *g.params;
                p.escape_sides = 1;
                g.params = p.checked().unwrap();
            }
        }
        sim
    };
    let c = same_run("fig8, both sides", make, 150, 25, Some(&sc));
    assert!(
        c.escaping > 0,
        "the flies must escape for this test to test it"
    );
}

/// A refusal on the GPU is the CPU's error: the same step, insect and field.
#[test]
fn a_refusal_is_the_cpus() {
    let make = || {
        let mut sim = bench_fly_world(200, 3, ScalarType::Fixed);
        if let ByScalar::Fixed(g) = &mut sim.groups[0] {
            // An insect far outside every limit: its state is refused.
            let k = g.states.len() / 2;
            g.states[k].pos.x = Fx::from_f32(20_000.0);
        }
        FlySim::new(sim.world, sim.groups, 3)
    };
    let mut gpu = GpuFlySim::new(make(), test_gpu()).unwrap();
    let e = same_refusal(&mut make(), &mut gpu);
    assert!(e.contains("state.pos"), "{e}");
}

/// Two insects refused in one tick: both engines name the lower id, whatever slots they hold
/// (the CPU reorders its slots by cell, the GPU keeps them).
#[test]
fn two_refusals_name_the_lower_id() {
    let make = || {
        let mut sim = bench_fly_world(200, 3, ScalarType::Fixed);
        let ByScalar::Fixed(g) = &mut sim.groups[0] else {
            panic!("fixed point");
        };
        let lower = break_two_inverted(&g.ids, &mut g.states, |s| s.pos.x = Fx::from_f32(20_000.0));
        (sim, lower)
    };
    let (mut cpu, lower) = make();
    let mut gpu = GpuFlySim::new(make().0, test_gpu()).unwrap();
    let e = same_refusal(&mut cpu, &mut gpu);
    assert!(e.contains(&format!("agent {lower} ")), "{e}");
}

/// The `region` stimuli: a threat's echo where the heading meets its walls (until an event
/// removes the region), a goal's nearest point (the locusts' field of Fig. 4, moved at tick 60
/// by an action a scenario file cannot hold but `Engine::apply` takes) and a `cave` goal's
/// echo ahead (the bats of Fig. 9).
#[test]
fn region_stimuli_are_the_cpus() {
    let text = r#"
name = "regions"
seed = 5
steps = 160
world = { dim = 3, min = [0, 0, 0], max = [30, 10, 30] }
[[groups]]
name = "bats"
model = "fly"
scalar = "fixed"
count = 60
threat = "cave"
spawn = { min = [4, 2, 4], max = [26, 8, 26] }
fly = { preset = "bats", fallback = 1 }
[[groups]]
name = "locusts"
model = "fly"
scalar = "fixed"
count = 60
goal = "field"
spawn = { min = [2, 2, 2], max = [12, 4, 28] }
fly = { preset = "locust", fallback = 1 }
[[groups]]
name = "millers"
model = "fly"
scalar = "fixed"
count = 60
goal = "roost"
spawn = { min = [4, 2, 4], max = [26, 8, 26] }
fly = { preset = "bats", fallback = 1 }
[[objects]]
name = "cave"
kind = "region"
min = [0, 0, 0]
max = [30, 10, 30]
[[objects]]
name = "roost"
kind = "cave"
min = [0, 0, 0]
max = [30, 10, 30]
[[objects]]
name = "field"
kind = "region"
min = [20, 0, 5]
max = [28, 1.5, 25]
[[events]]
step = 100
remove = "cave"
"#;
    let mut sc = Scenario::from_str(text, "regions.toml").unwrap();
    sc.events.insert(
        0,
        crate::scenario::Event {
            step: 60,
            action: crate::scenario::Action::Move {
                object: "field".into(),
                to: vec![23.0, 0.75, 12.0],
            },
        },
    );
    let make = || FlySim::from_scenario(&sc, sc.seed).unwrap();
    let c = same_run("regions", make, sc.steps, 10, Some(&sc));
    assert!(
        c.escaping > 0,
        "the bats must hear an echo for this test to test it"
    );
    let mut cpu = make();
    for _ in 0..sc.steps {
        apply_due_events(&mut cpu, &sc);
        Engine::tick(&mut cpu).unwrap();
    }
    let field = cpu.world.sources.iter().find(|s| s.name == "field");
    let [lo, hi] = field.and_then(|s| s.region).unwrap();
    // Over the field, or at its edge.
    let over = cpu
        .positions_by_id()
        .iter()
        .filter(|p| {
            (0..3).all(|k| p[k] >= f64::from(lo[k]) - 2.0 && p[k] <= f64::from(hi[k]) + 2.0)
        })
        .count();
    assert!(
        over > 0,
        "the locusts must reach the field for this test to test it"
    );
}

/// `f32` on the GPU is measured, not promised: after 50 ticks of the bench world the positions
/// stay within 1e-4 units of the CPU's (measured on lavapipe: under 1e-6; printed with
/// `--nocapture`).
#[test]
fn f32_stays_near_the_cpu() {
    let make = || bench_fly_world(1000, 9, ScalarType::F32);
    let mut cpu = make();
    let mut gpu = GpuFlySim::new(make(), test_gpu()).unwrap();
    for t in 1..=50 {
        Engine::tick(&mut cpu).unwrap();
        Engine::tick(&mut gpu).unwrap();
        if t % 10 == 0 {
            gpu.sync().unwrap();
            let (a, b) = (cpu.positions_by_id(), gpu.sim().positions_by_id());
            let worst = a
                .iter()
                .zip(&b)
                .map(|(p, q)| (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>().sqrt())
                .fold(0.0, f64::max);
            let (ia, ib) = (cpu.total.infeasible, gpu.sim().total.infeasible);
            println!("f32: tick {t}: largest difference {worst:e}, infeasible {ia} / {ib}");
            if t == 50 {
                assert!(worst < 1e-4, "{worst}");
            }
        }
    }
}

#[test]
fn the_kernels_are_valid_wgsl() {
    assert_valid_wgsl("fly tick", modules, "");
}

/// The layout's, the engine's and the controller's constants in the shaders are Rust's.
#[test]
fn the_shaders_constants_are_rusts() {
    let wgsl = format!("{}{}", FLY_TICK.source, FLY_STEP.source);
    assert_constants(&wgsl, WGSL_CONSTANTS, true);
    let shared = wgsl_shared();
    let shared: Vec<(&str, u32)> = shared.iter().map(|(n, v)| (n.as_str(), *v)).collect();
    assert_constants(&wgsl, &shared, true);
    let step: &[(&str, u32)] = &[
        ("FLY_NEIGHBOURS", WIRE_FLY_NEIGHBOURS as u32),
        ("FLY_SURFACES", WIRE_FLY_SURFACES as u32),
        ("FLY_STIMULUS_TARGET", u32::from(STIMULUS_TARGET)),
        ("FLY_STIMULUS_PREDATOR", u32::from(STIMULUS_PREDATOR)),
        ("FLY_NOISE_CURL", u32::from(NOISE_CURL)),
        ("FLY_NOISE_PERLIN", u32::from(NOISE_PERLIN)),
        ("FLY_NOISE_WHITE", u32::from(NOISE_WHITE)),
        ("FLY_NOISE_GAUSSIAN", u32::from(NOISE_GAUSSIAN)),
        ("FLY_FALLBACK_LP4", u32::from(FALLBACK_LP4)),
        ("RAND_FLY_ESCAPE", stream::FLY_ESCAPE),
        ("RAND_FLY_NOISE_X", stream::FLY_NOISE_X),
        ("RAND_FLY_NOISE_Y", stream::FLY_NOISE_Y),
        ("RAND_FLY_NOISE_Z", stream::FLY_NOISE_Z),
    ];
    assert_constants(FLY_STEP.source, step, true);
    assert_eq!(
        u32::from(NOISE_NONE),
        4,
        "fly_step.wgsl: anything else is no noise"
    );
    // The f32 constants, as Rust prints them (WGSL reads the same f32 back).
    for (name, v) in [
        ("FLY_THETA_LIMIT", core::f32::consts::FRAC_PI_2 + 1e-3),
        ("FLY_RVO_EPSILON", RVO_EPSILON),
        ("FLY_GAUSS_NORM", 0.866_025_4),
    ] {
        let decl = format!("const {name}: f32 = {v}f;");
        assert!(
            FLY_STEP.source.contains(&decl),
            "{decl} is not in fly_step.wgsl"
        );
    }
    // The group's words follow the parameters' fields.
    let p = FlyParams::<Fx>::escape();
    let mut w = Vec::new();
    let stimuli = crate::fly::Stimuli {
        goal: None,
        threat: Some(3),
    };
    let cave = crate::swarm3d::Source {
        id: 3,
        name: "cave".into(),
        center: [2.5, 3.5, 4.75],
        active: true,
        region: Some([[1.0, 2.0, 3.0], [4.0, 5.0, 6.5]]),
        cave: true,
    };
    layout::write_group(&mut w, &p, stimuli, [None, Some(&cave)]);
    assert_eq!(w.len(), layout::GROUP_WORDS);
    let (goal, threat) = (
        layout::GROUP_REGIONS,
        layout::GROUP_REGIONS + layout::REGION_WORDS,
    );
    assert_eq!(w[goal..threat], [0; layout::REGION_WORDS]);
    assert_eq!(w[threat], layout::REGION_CAVE);
    assert_eq!(w[threat + 1], Fx::from_f32(1.0).to_bits() as u32);
    assert_eq!(w[threat + 6], Fx::from_f32(6.5).to_bits() as u32);
    assert_eq!(w[8], p.r_att.to_bits() as u32);
    assert_eq!(w[15], p.max_speed.to_bits() as u32);
    assert_eq!(w[layout::GROUP_GOAL], layout::NO_SOURCE);
    assert_eq!(w[layout::GROUP_THREAT], 3);
    assert_eq!(
        w[layout::GROUP_RANGE2],
        (p.r_att * p.r_att).to_bits() as u32
    );
}

#[test]
fn status_words_are_the_shaders() {
    StatusWords {
        wgsl: FLY_STEP.source,
        file: "fly_step.wgsl",
        prefix: "FLY",
        fields: &FIELDS,
        kinds: 3,
        indices: [None, Some(0), Some(15)],
        status_of,
        status_error,
    }
    .check();
}
