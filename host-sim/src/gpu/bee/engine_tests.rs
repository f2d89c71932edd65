//! The GPU engine against the CPU engine: the same scenario, tick by tick, every bee's state,
//! decision and correction, the correction counts and every exchange the mirror would send,
//! over `Fx` bit for bit.
//!
//! `cargo test -p swarm-sim --lib gpu::bee::engine -- --nocapture` prints what each run covered.

use swarm_core::bee::{BeeParams, BeeState};
use swarm_core::{Fx, Scalar, Vec3};

use super::engine::{CHECK_EVERY, GpuBeeSim};
use super::layout;
use super::world::{GridShape3, world_words};
use crate::bees::{BeeGroup, BeeObstacle, BeeSim, BeeTarget, BeeWorld, Contacts, Shape3};
use crate::engine::{Engine, apply_due_events};
use crate::error::SimError;
use crate::gpu::tests::harness::fixed;
use crate::gpu::{inverted_slots, test_gpu};
use crate::scalar::ByScalar;
use crate::scenario::{Action, Event, Object, ObjectKind, ScalarType, Scenario, World};

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
    let make = || BeeSim::from_scenario(sc, sc.seed).unwrap();
    same_run(&sc.name, make, sc.steps, every, Some(sc))
}

/// Runs the simulation `make` builds for `ticks` ticks on both engines (with the events of
/// `events`, if any) and compares them after every `every`-th tick (and the last): every word
/// of every bee, the correction counts, the recorded frame, and the exchanges of every bee in
/// that tick.
fn same_run(
    name: &str,
    make: impl Fn() -> BeeSim,
    ticks: u32,
    every: u32,
    events: Option<&Scenario>,
) -> Covered {
    let mut cpu = make();
    let mut gpu = GpuBeeSim::new(make(), test_gpu()).unwrap();
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
    println!("{name}: {ticks} ticks: {covered:?}");
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
    let sc = changing_world(160);
    // The added target's particles make the world's words outgrow the GPU's buffer (which the
    // engine then makes again and binds anew).
    let mut sim = BeeSim::from_scenario(&sc, sc.seed).unwrap();
    let len = |sim: &BeeSim| world_words::<Fx>(&sim.world, &GridShape3::of(&sim.world, 100)).len();
    let before = len(&sim);
    let flower = sc.object_id("flower").unwrap();
    sim.apply(flower, &Action::Add("flower".into()));
    assert!(len(&sim) > before, "{} words, then {}", before, len(&sim));
    let c = same_as_cpu(&sc, 10);
    assert!(
        c.contacts.obstacle > 0 && c.contacts.bounds > 0,
        "the world must correct bees for this test to test it: {c:?}"
    );
}

/// 600 bees in a small volume crowded with obstacles, many of them inside one or outside the
/// bounds, flying every way: two overlapping spheres (a bee put back on one's surface lands in
/// the other: several rounds of corrections), a sphere through the volume's +x face, a box on
/// the ground (its bottom face on the bounds: closed), a shaft from floor to ceiling (both caps
/// closed), a box in a corner (three faces closed), an inactive sphere.
fn crowded() -> BeeSim {
    let params = BeeParams::<f32>::around_nest();
    let mut w = BeeWorld::new(
        [0.0; 3],
        [20.0, 10.0, 20.0],
        params.h + 2.0 * params.radius,
        2.0 * params.d0,
    );
    let shapes = [
        Shape3::Sphere {
            center: [5.0, 5.0, 5.0],
            radius: 3.0,
        },
        Shape3::Sphere {
            center: [8.0, 5.0, 5.5],
            radius: 3.0,
        },
        Shape3::Sphere {
            center: [19.0, 5.0, 10.0],
            radius: 2.5,
        },
        Shape3::Box {
            min: [10.0, 0.0, 12.0],
            max: [16.0, 4.0, 18.0],
        },
        Shape3::Shaft {
            center: [4.0, 15.0],
            radius: 1.5,
            y_min: 0.0,
            y_max: 10.0,
        },
        Shape3::Box {
            min: [0.0, 7.0, 0.0],
            max: [3.0, 10.0, 3.0],
        },
        Shape3::Sphere {
            center: [12.0, 6.0, 6.0],
            radius: 2.0,
        },
    ];
    for (k, s) in shapes.into_iter().enumerate() {
        w.obstacles
            .push(BeeObstacle::new(k as u16, format!("o{k}"), s, k != 6));
    }
    w.targets = vec![BeeTarget::new(7, "nest", [10.0, 5.0, 10.0], 1.5, 100)];
    let r = |i: u32, k: u32| swarm_core::rand::rand(5, i, 0, k) as f32 / 4_294_967_296.0;
    let states = (0..600u32)
        .map(|i| {
            let p = [
                -1.0 + 22.0 * r(i, 0),
                -1.0 + 12.0 * r(i, 1),
                -1.0 + 22.0 * r(i, 2),
            ];
            let v = [
                4.0 * r(i, 3) - 2.0,
                4.0 * r(i, 4) - 2.0,
                4.0 * r(i, 5) - 2.0,
            ];
            BeeState::new(
                Vec3::from_f32(p[0], p[1], p[2]),
                Vec3::from_f32(v[0], v[1], v[2]),
            )
        })
        .collect();
    let g = BeeGroup::new(
        "crowd".into(),
        0,
        params.cast::<Fx>().checked().unwrap(),
        Some(7),
        states,
    );
    BeeSim::new(w, vec![g.into()], 5)
}

#[test]
fn a_crowded_world_is_the_cpus() {
    let c = same_run("crowded", crowded, 40, 1, None);
    assert!(
        c.contacts.obstacle > 100 && c.contacts.bounds > 100,
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

/// A controller's refusal on the GPU is the CPU's error: the same step, bee (the lowest id
/// refused, wherever its slot lies) and field, reported at the next sync, or by a tick after
/// at most `CHECK_EVERY`.
#[test]
fn a_refusal_is_the_cpus_error() {
    let sc = fixed("bees-fig14-shafts", 10);
    let ids = match &broken(&sc, &[]).groups[0] {
        ByScalar::Fixed(g) => g.ids.clone(),
        ByScalar::F32(_) => panic!("fixed point"),
    };
    let (a, b) = inverted_slots(&ids);
    let mut cpu = broken(&sc, &[a, b]);
    let cpu_error = Engine::tick(&mut cpu).unwrap_err().to_string();
    assert!(cpu_error.contains("state.density"), "{cpu_error}");
    assert!(
        cpu_error.contains(&format!("agent {} ", ids[b])),
        "{cpu_error}"
    );
    let mut gpu = GpuBeeSim::new(broken(&sc, &[a, b]), test_gpu()).unwrap();
    gpu.tick().unwrap();
    assert_eq!(gpu.sync().unwrap_err().to_string(), cpu_error);

    let mut gpu = GpuBeeSim::new(broken(&sc, &[a, b]), test_gpu()).unwrap();
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
