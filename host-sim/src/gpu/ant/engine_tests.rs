//! The GPU engine against the CPU engine: the same scenario, tick by tick, every ant's state
//! and every count, over `Fx` bit for bit.

use swarm_core::Fx;

use super::engine::GpuAntSim;
use crate::ants::{AntGroup, AntObjectKind, AntSim};
use crate::engine::{Engine, apply_due_events};
use crate::gpu::tests::harness::fixed;
use crate::gpu::{break_two_inverted, same_refusal, test_gpu};
use crate::scalar::ByScalar;
use crate::scenario::ObjectKind;

/// Every ant's state words, in id order.
fn states(sim: &AntSim) -> Vec<(u32, Vec<u32>)> {
    fn of(g: &AntGroup<Fx>, out: &mut Vec<(u32, Vec<u32>)>) {
        for (id, s) in g.states_by_id() {
            let mut w = Vec::new();
            super::layout::write_state(&mut w, &s);
            out.push((id, w));
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

/// Runs scenario `name` for `ticks` ticks on both engines and compares them every `every`.
fn same_as_cpu(name: &str, ticks: u32, every: u32) {
    same_as_cpu_in_chunks(name, ticks, every, None);
}

/// [`same_as_cpu`] with the GPU's states bound `chunk` ants at a time (default: as many as a
/// binding holds).
fn same_as_cpu_in_chunks(name: &str, ticks: u32, every: u32, chunk: Option<usize>) {
    let sc = fixed(name, ticks);
    let mut cpu = AntSim::from_scenario(&sc, sc.seed).unwrap();
    let host = AntSim::from_scenario(&sc, sc.seed).unwrap();
    let mut gpu = match chunk {
        Some(c) => GpuAntSim::chunked(host, test_gpu(), c),
        None => GpuAntSim::new(host, test_gpu()),
    }
    .unwrap();
    for t in 0..ticks {
        apply_due_events(&mut cpu, &sc);
        apply_due_events(&mut gpu, &sc);
        Engine::tick(&mut cpu).unwrap();
        gpu.tick().unwrap();
        if (t + 1) % every == 0 || t + 1 == ticks {
            gpu.sync().unwrap();
            let (a, b) = (states(&cpu), states(gpu.sim()));
            for (x, y) in a.iter().zip(&b) {
                assert_eq!(x, y, "{name}: ant {} after tick {}", x.0, t + 1);
            }
            assert_eq!(cpu.delivered, gpu.sim().delivered, "{name} tick {}", t + 1);
            let active = |s: &AntSim| {
                s.world
                    .objects
                    .iter()
                    .map(|o| (o.active, o.kind.clone()))
                    .collect::<Vec<_>>()
            };
            assert_eq!(active(&cpu), active(gpu.sim()), "{name} tick {}", t + 1);
        }
    }
}

/// The built-in ant scenarios, each tested for 300 ticks with its events moved into them,
/// compared every 25.
macro_rules! same_as_cpu {
    ($($test:ident: $name:literal,)*) => {$(
        #[test]
        fn $test() {
            same_as_cpu($name, 300, 25);
        }
    )*};
}

same_as_cpu! {
    fig7a_is_the_cpus: "ants-fig7a-single-colony",
    fig7b_is_the_cpus: "ants-fig7b-obstacles",
    fig8a_is_the_cpus: "ants-fig8a-hybrid",
    fig8b_is_the_cpus: "ants-fig8b-hybrid-obstacles",
    fig11_is_the_cpus: "ants-fig11-dynamic-obstacles",
    fig12_is_the_cpus: "ants-fig12-moved-food",
    fig13_is_the_cpus: "ants-fig13-disturbance",
    fig14_is_the_cpus: "ants-fig14-waypoints",
    fig1c_is_the_cpus: "ants-fig1c-heart",
}

/// The states bound in chunks of 128 ants (four dispatches a kernel; the largest swarms are
/// bound so), with a route and events: the same bits.
#[test]
fn chunks_of_ants_are_the_cpus() {
    same_as_cpu_in_chunks("ants-fig14-waypoints", 200, 50, Some(128));
    same_as_cpu_in_chunks("ants-fig11-dynamic-obstacles", 200, 50, Some(192));
}

/// Food with an amount is taken on the GPU as on the CPU, and disappears when empty.
#[test]
fn food_runs_out_as_on_the_cpu() {
    let mut sc = fixed("ants-fig7a-single-colony", 700);
    let mut limited = 0;
    for o in &mut sc.objects {
        if let ObjectKind::Food { amount, .. } = &mut o.kind {
            *amount = Some(4);
            limited += 1;
        }
    }
    assert!(limited > 0);
    let mut cpu = AntSim::from_scenario(&sc, sc.seed).unwrap();
    let mut gpu = GpuAntSim::new(AntSim::from_scenario(&sc, sc.seed).unwrap(), test_gpu()).unwrap();
    for _ in 0..sc.steps {
        Engine::tick(&mut cpu).unwrap();
        gpu.tick().unwrap();
    }
    gpu.sync().unwrap();
    let food = |s: &AntSim| {
        s.world
            .objects
            .iter()
            .filter_map(|o| match o.kind {
                AntObjectKind::Food { amount } => Some((o.active, amount)),
                _ => None,
            })
            .collect::<Vec<_>>()
    };
    assert_eq!(food(&cpu), food(gpu.sim()));
    assert!(
        food(&cpu)
            .iter()
            .all(|&(active, amount)| !active && amount == Some(0)),
        "the food must run out for this test to test it: {:?}",
        food(&cpu)
    );
    assert_eq!(states(&cpu), states(gpu.sim()));
}

/// A controller's refusal on the GPU is the CPU's error: the same phase, step, agent (the
/// lowest id refused, wherever its slot lies) and field, reported at the next check.
#[test]
fn a_refusal_is_the_cpus_error() {
    let sc = fixed("ants-fig7a-single-colony", 10);
    let broken = || {
        let mut sim = AntSim::from_scenario(&sc, sc.seed).unwrap();
        let ByScalar::Fixed(g) = &mut sim.groups[0] else {
            panic!("fixed point");
        };
        // Two ants, their slots and ids the other way round, have lost their heading.
        let lower = break_two_inverted(&g.ids, &mut g.states, |s| {
            s.heading = swarm_core::Vec2::zero()
        });
        (sim, lower)
    };
    let (mut cpu, lower) = broken();
    let mut gpu = GpuAntSim::new(broken().0, test_gpu()).unwrap();
    let cpu_error = same_refusal(&mut cpu, &mut gpu);
    assert!(cpu_error.contains("heading"), "{cpu_error}");
    assert!(
        cpu_error.contains(&format!("agent {lower} ")),
        "{cpu_error}"
    );
}
