//! The GPU engine against the CPU engine: the same scenario, tick by tick, every bee's state,
//! decision and correction, the correction counts and every exchange the mirror would send,
//! over `Fx` bit for bit.
//!
//! `cargo test -p swarm-sim --lib gpu::bee::engine -- --nocapture` prints what each run covered.

use swarm_core::{Fx, Scalar};

use super::engine::{CHECK_EVERY, GpuBeeSim};
use super::layout;
use crate::bees::{BeeGroup, BeeSim, Contacts};
use crate::engine::{Engine, apply_due_events};
use crate::error::SimError;
use crate::gpu::test_gpu;
use crate::scalar::ByScalar;
use crate::scenario::{Action, Event, Object, ObjectKind, ScalarType, Scenario, World, builtin};

/// Scenario `name` in fixed point, its events moved into its first `ticks` ticks.
fn fixed(name: &str, ticks: u32) -> Scenario {
    let mut sc = builtin(name).unwrap_or_else(|| panic!("no built-in scenario {name}"));
    for g in &mut sc.groups {
        g.scalar = ScalarType::Fixed;
    }
    for e in &mut sc.events {
        e.step = (u64::from(e.step) * u64::from(ticks) / u64::from(sc.steps)) as u32;
    }
    sc.steps = ticks;
    sc
}

/// Every bee's words, in id order: its state, its last decision, what the world corrected.
fn words(sim: &BeeSim) -> Vec<(u32, Vec<u32>)> {
    fn of(g: &BeeGroup<Fx>, out: &mut Vec<(u32, Vec<u32>)>) {
        for k in 0..g.states.len() {
            let mut w = Vec::new();
            layout::write_state(&mut w, &g.states[k]);
            layout::write_decision(&mut w, &g.decisions[k]);
            w.push(u32::from(g.corrected[k]));
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
    /// Ticks compared, and exchanges compared.
    ticks: u32,
    exchanges: usize,
    /// Bee-ticks avoiding an obstacle (of the ticks compared).
    avoiding: usize,
    /// The corrections on the CPU at the end.
    contacts: Contacts,
}

/// Runs `sc` on both engines and compares them after every `every`-th tick (and the last): every
/// word of every bee, the correction counts, and the exchanges of every bee in that tick.
fn same_as_cpu(sc: &Scenario, every: u32) -> Covered {
    let name = &sc.name;
    let mut cpu = BeeSim::from_scenario(sc, sc.seed).unwrap();
    let mut gpu = GpuBeeSim::new(BeeSim::from_scenario(sc, sc.seed).unwrap(), test_gpu()).unwrap();
    let ids: Vec<u32> = (0..cpu.agents() as u32).collect();
    let mut covered = Covered::default();
    for t in 0..sc.steps {
        apply_due_events(&mut cpu, sc);
        apply_due_events(&mut gpu, sc);
        let look = (t + 1) % every == 0 || t + 1 == sc.steps;
        Engine::decide(&mut cpu, 0).unwrap();
        gpu.decide(0).unwrap();
        if look {
            let (a, b) = (
                Engine::exchanges(&cpu, 0, &ids).unwrap(),
                gpu.exchanges(0, &ids).unwrap(),
            );
            assert_eq!(a.len(), b.len());
            for (x, y) in a.iter().zip(&b) {
                let what = format!("{name}: exchange of bee {} in tick {t}", x.agent);
                assert_eq!((x.agent, x.phase), (y.agent, y.phase), "{what}");
                assert!(
                    x.request.bytes == y.request.bytes,
                    "{what}: request differs"
                );
                assert!(x.reply.bytes == y.reply.bytes, "{what}: reply differs");
            }
            covered.exchanges += a.len();
        }
        Engine::publish(&mut cpu, 0).unwrap();
        gpu.publish(0).unwrap();
        if look {
            gpu.sync().unwrap();
            let g = gpu.sim();
            let (a, b) = (words(&cpu), words(g));
            assert_eq!(a.len(), b.len());
            for (x, y) in a.iter().zip(&b) {
                assert_eq!(x, y, "{name}: bee {} after tick {}", x.0, t + 1);
            }
            assert_eq!(
                cpu.contacts,
                g.contacts,
                "{name}: contacts after tick {}",
                t + 1
            );
            assert_eq!(
                cpu.last_contacts,
                g.last_contacts,
                "{name}: the contacts of tick {}",
                t + 1
            );
            assert_eq!(cpu.step, g.step);
            assert_eq!(Engine::frame(&cpu), gpu.frame(), "{name}: recorded frame");
            covered.ticks += 1;
            covered.avoiding += a.iter().filter(|(_, w)| w[10] != 0).count();
        }
    }
    covered.contacts = cpu.contacts;
    println!("{name}: {} ticks: {covered:?}", sc.steps);
    covered
}

#[test]
fn fig11_is_the_cpus() {
    same_as_cpu(&fixed("bees-fig11-grassland", 60), 6);
}

#[test]
fn fig14_is_the_cpus() {
    let c = same_as_cpu(&fixed("bees-fig14-shafts", 400), 20);
    assert!(
        c.avoiding > 0,
        "the shafts must be avoided for this test to test it"
    );
}

#[test]
fn fig15_is_the_cpus() {
    same_as_cpu(&fixed("bees-fig15-nest", 240), 20);
}

/// `bees-fig14-shafts` with a world that changes under the swarm: a ceiling below some of the
/// bees (clamped into the bounds), a rock added onto them and moved, a shaft moved onto them
/// (put back on its surface), a second target added (its particles: more world than the GPU's
/// buffer held), the goal removed, added again and moved.
fn changing_world(ticks: u32) -> Scenario {
    let mut sc = fixed("bees-fig14-shafts", ticks);
    sc.world = World::Space {
        min: [0.0, 0.0, -10.0],
        max: [72.0, 17.0, 70.0],
    };
    sc.objects.push(Object {
        name: "rock".into(),
        active: false,
        kind: ObjectKind::Sphere {
            center: [8.0, 13.0, 30.0],
            radius: 3.0,
        },
    });
    sc.objects.push(Object {
        name: "flower".into(),
        active: false,
        kind: ObjectKind::Target {
            center: [40.0, 10.0, 30.0],
            radius: 2.0,
            particles: 150,
        },
    });
    let at = |k: u32| k * ticks / 160;
    let mv = |object: &str, to: &[f32]| Action::Move {
        object: object.into(),
        to: to.to_vec(),
    };
    sc.events = vec![
        Event {
            step: at(10),
            action: Action::Add("rock".into()),
        },
        Event {
            step: at(30),
            action: mv("rock", &[11.0, 12.0, 28.0]),
        },
        Event {
            step: at(45),
            action: mv("shaft-1", &[14.0, 30.0]),
        },
        Event {
            step: at(60),
            action: Action::Add("flower".into()),
        },
        Event {
            step: at(70),
            action: Action::Remove("goal".into()),
        },
        Event {
            step: at(90),
            action: Action::Add("goal".into()),
        },
        Event {
            step: at(100),
            action: mv("goal", &[45.0, 12.0, 25.0]),
        },
        Event {
            step: at(120),
            action: Action::Remove("rock".into()),
        },
    ];
    sc
}

#[test]
fn a_changing_world_is_the_cpus() {
    let c = same_as_cpu(&changing_world(160), 10);
    assert!(
        c.contacts.obstacle > 0 && c.contacts.bounds > 0,
        "the world must correct bees for this test to test it: {c:?}"
    );
}

/// The bees of slot `slots` with a negative density (refused: `state.density`).
fn broken(sc: &Scenario, slots: &[usize]) -> BeeSim {
    let mut sim = BeeSim::from_scenario(sc, sc.seed).unwrap();
    let ByScalar::Fixed(g) = &mut sim.groups[0] else {
        panic!("fixed point");
    };
    for &k in slots {
        g.states[k].density = -Fx::ONE;
    }
    sim
}

/// A controller's refusal on the GPU is the CPU's error: the same step, bee (the lowest slot
/// refused) and field, reported at the next sync, or by a tick after at most `CHECK_EVERY`.
#[test]
fn a_refusal_is_the_cpus_error() {
    let sc = fixed("bees-fig14-shafts", 10);
    let mut cpu = broken(&sc, &[30, 7]);
    let cpu_error = Engine::tick(&mut cpu).unwrap_err().to_string();
    assert!(cpu_error.contains("state.density"), "{cpu_error}");
    let mut gpu = GpuBeeSim::new(broken(&sc, &[30, 7]), test_gpu()).unwrap();
    gpu.tick().unwrap();
    assert_eq!(gpu.sync().unwrap_err().to_string(), cpu_error);

    let mut gpu = GpuBeeSim::new(broken(&sc, &[30, 7]), test_gpu()).unwrap();
    for t in 1..CHECK_EVERY {
        gpu.tick().unwrap_or_else(|e| panic!("tick {t}: {e}"));
    }
    assert_eq!(gpu.tick().unwrap_err().to_string(), cpu_error);
}

/// One GPU engine runs one scalar type.
#[test]
fn mixed_scalars_are_refused() {
    let mut sc = fixed("bees-fig14-shafts", 1);
    let mut other = sc.groups[0].clone();
    other.name = "in-f32".into();
    other.scalar = ScalarType::F32;
    other.count = 3;
    sc.groups.push(other);
    let e = GpuBeeSim::new(BeeSim::from_scenario(&sc, 1).unwrap(), test_gpu()).err();
    assert!(
        matches!(&e, Some(SimError::GpuMixedScalars { first, other }) if first == "swarm" && other == "in-f32"),
        "{e:?}"
    );
}
