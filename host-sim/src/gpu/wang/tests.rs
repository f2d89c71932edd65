//! The wang2014 GPU engine against the CPU engine: the same simulation tick by tick, every
//! insect's state, replies, corrections and pushes, the counts, and every exchange the mirror
//! would send, over `Fx` bit for bit; and the layout's two sides.
//!
//! `cargo test -p swarm-sim --lib gpu::wang -- --nocapture` prints what each run covered.

use swarm_core::wang::WangParams;
use swarm_core::{Fx, Scalar};

use super::engine::{GpuWangSim, modules};
use super::layout::{self, FIELDS, WGSL_CONSTANTS, status_error, status_of};
use crate::engine::{Engine, apply_due_events};
use crate::gpu::shaders::{WANG_STEP, WANG_TICK};
use crate::gpu::tests::harness::{StatusWords, assert_constants, assert_valid_wgsl, fixed};
use crate::gpu::{break_two_inverted, same_refusal, test_gpu};
use crate::scalar::ByScalar;
use crate::scenario::{ScalarType, Scenario};
use crate::wang::{WangGroup, WangSim, bench_wang_world};

/// Every insect's words, in id order: its state, the corrections and the pushes of the last
/// tick. (Its replies are compared in the exchanges: after a tick the CPU's buffers of them
/// hold other values, the states before, or, after a re-sort of the slots, the states.)
fn words(sim: &WangSim) -> Vec<(u32, Vec<u32>)> {
    fn of(g: &WangGroup<Fx>, out: &mut Vec<(u32, Vec<u32>)>) {
        for k in 0..g.states.len() {
            let mut w = Vec::new();
            layout::write_state(&mut w, &g.states[k]);
            w.extend([u32::from(g.corrected[k]), u32::from(g.pushes[k])]);
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

/// What a run covered.
#[derive(Debug, Default)]
struct Covered {
    ticks: u32,
    exchanges: usize,
    /// Insect-ticks MDE pushed, and world corrections, on the CPU.
    pushed: u64,
    corrected: u64,
}

/// Runs the simulation `make` builds for `ticks` ticks on both engines (with the events of
/// `events`) and compares them after every `every`-th tick (and the last): every word of every
/// insect, the counts, the recorded frame, and the exchanges of both phases of every insect.
fn same_run(
    name: &str,
    make: impl Fn() -> WangSim,
    ticks: u32,
    every: u32,
    events: Option<&Scenario>,
) -> Covered {
    let mut cpu = make();
    let mut gpu = GpuWangSim::new(make(), test_gpu()).unwrap();
    let ids: Vec<u32> = (0..cpu.agents() as u32).collect();
    let mut covered = Covered::default();
    for t in 0..ticks {
        if let Some(sc) = events {
            apply_due_events(&mut cpu, sc);
            apply_due_events(&mut gpu, sc);
        }
        let look = (t + 1) % every == 0 || t + 1 == ticks;
        for phase in 0..2 {
            Engine::decide(&mut cpu, phase).unwrap();
            gpu.decide(phase).unwrap();
            if look {
                let (a, b) = (
                    Engine::exchanges(&cpu, phase, &ids).unwrap(),
                    gpu.exchanges(phase, &ids).unwrap(),
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
            Engine::publish(&mut cpu, phase).unwrap();
            gpu.publish(phase).unwrap();
        }
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
    covered.pushed = cpu.total.pushed;
    covered.corrected = cpu.total.obstacle + cpu.total.bounds;
    println!("{name}: {ticks} ticks: {covered:?}");
    covered
}

/// Built-in scenario `name` in fixed point over `ticks` ticks, compared every `every`.
fn same_as_cpu(name: &str, ticks: u32, every: u32) -> Covered {
    let sc = fixed(name, ticks);
    let make = || WangSim::from_scenario(&sc, sc.seed).unwrap();
    same_run(name, make, ticks, every, Some(&sc))
}

/// The synthetic bench world: spheres, a shaft, a ground box, boundaries everywhere, MDE.
#[test]
fn the_bench_world_is_the_cpus() {
    let make = || {
        let mut sim = bench_wang_world(3000, 7, ScalarType::Fixed);
        let top = sim.world.max[1];
        if let ByScalar::Fixed(g) = &mut sim.groups[0] {
            // Some insects inside the ground box, some above the ceiling: corrected.
            for (k, s) in g.states.iter_mut().enumerate().step_by(50) {
                s.pos.y = Fx::from_f32(if k % 100 == 0 { 0.5 } else { top + 0.3 });
            }
        }
        sim
    };
    let c = same_run("bench", make, 40, 8, None);
    assert!(c.pushed > 0, "MDE must push for this test to test it");
    assert!(
        c.corrected > 0,
        "the world must correct for this test to test it"
    );
}

/// Fig. 8: the chased ball moves (the field solved again on the host, uploaded).
#[test]
fn the_chase_is_the_cpus() {
    same_as_cpu("wang-fig8-chasing", 120, 20);
}

/// Fig. 13: curl, Perlin and random noise side by side (three groups).
#[test]
fn the_noise_comparison_is_the_cpus() {
    same_as_cpu("wang-fig13-noise-compare", 60, 15);
}

/// Fig. 10: phototaxis (the lamp, its draws).
#[test]
fn phototaxis_is_the_cpus() {
    same_as_cpu("wang-fig10-phototaxis", 60, 20);
}

/// A refusal on the GPU is the CPU's error: the same phase, step, insect and field.
#[test]
fn a_refusal_is_the_cpus() {
    let make = || {
        let mut sim = bench_wang_world(200, 3, ScalarType::Fixed);
        if let ByScalar::Fixed(g) = &mut sim.groups[0] {
            // An insect far outside every limit: its state is refused.
            let k = g.states.len() / 2;
            g.states[k].pos.x = Fx::from_f32(20_000.0);
        }
        sim
    };
    let mut gpu = GpuWangSim::new(make(), test_gpu()).unwrap();
    let e = same_refusal(&mut make(), &mut gpu);
    assert!(e.contains("state.pos"), "{e}");
}

/// Two insects refused in one tick: both engines name the lower id, whatever slots they hold.
#[test]
fn two_refusals_name_the_lower_id() {
    let make = || {
        let mut sim = bench_wang_world(200, 3, ScalarType::Fixed);
        let ByScalar::Fixed(g) = &mut sim.groups[0] else {
            panic!("fixed point");
        };
        let lower = break_two_inverted(&g.ids, &mut g.states, |s| s.pos.x = Fx::from_f32(20_000.0));
        (sim, lower)
    };
    let (mut cpu, lower) = make();
    let mut gpu = GpuWangSim::new(make().0, test_gpu()).unwrap();
    let e = same_refusal(&mut cpu, &mut gpu);
    assert!(e.contains(&format!("agent {lower} ")), "{e}");
}

/// `f32` on the GPU is measured, not promised: after 50 ticks of the bench world the
/// positions stay within a few millimetres of the CPU's.
#[test]
fn f32_stays_near_the_cpu() {
    let make = || bench_wang_world(1000, 9, ScalarType::F32);
    let mut cpu = make();
    let mut gpu = GpuWangSim::new(make(), test_gpu()).unwrap();
    for _ in 0..50 {
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
    println!("f32: largest difference after 50 ticks {worst:e} m");
    assert!(worst < 5e-3, "{worst}");
}

#[test]
fn the_kernels_are_valid_wgsl() {
    assert_valid_wgsl("wang tick", modules, "");
}

#[test]
fn the_layout_constants_are_the_shaders() {
    let wgsl = format!("{}{}", WANG_TICK.source, WANG_STEP.source);
    assert_constants(&wgsl, WGSL_CONSTANTS, true);
    // The parameters' words follow the struct's fields, nine of them.
    let p = WangParams::<Fx>::aggregation();
    let mut w = Vec::new();
    layout::write_group(
        &mut w,
        &p,
        layout::GroupInputs {
            field: 7,
            lamp: None,
        },
    );
    assert_eq!(w.len(), layout::GROUP_WORDS);
    assert_eq!(w[layout::GROUP_FIELD], 7);
}

#[test]
fn status_words_are_the_shaders() {
    StatusWords {
        wgsl: WANG_STEP.source,
        file: "wang_step.wgsl",
        prefix: "WANG",
        fields: &FIELDS,
        kinds: 3,
        indices: [None, Some(0), Some(7)],
        status_of,
        status_error,
    }
    .check();
}
