//! The mirror applies a scenario's timed events before the steps they are scheduled for, as
//! `swarm run` does: a mirrored scenario whose objects are added and moved and whose
//! disturbance starts and stops, mirrored in memory against its soft device over the steps of
//! its events, finds no mismatch and ends where a plain run of the same steps ends.

use std::path::{Path, PathBuf};
use std::time::Duration;

use swarm_hil::client::{Client, ClientOptions, RtoOptions};
use swarm_hil::loopback::with_scalar;
use swarm_hil::mirror::{MirrorOptions, MirrorReport, mirror_with_events};
use swarm_hil::soft::{SoftDevice, serve};
use swarm_hil::transport::memory_pair;
use swarm_sim::output::{self, Frame, read_csv, write_csv};
use swarm_sim::run::{RunOptions, run};
use swarm_sim::scenario::{self, Action, Backend, Event, ScalarType, Scenario};

/// Steps mirrored: every event below falls inside them.
const STEPS: u32 = 10;

fn event(step: u32, action: Action) -> Event {
    Event { step, action }
}

/// At `step`, `object` moves to `to`.
fn move_to(step: u32, object: &str, to: [f32; 2]) -> Event {
    event(
        step,
        Action::Move {
            object: object.into(),
            to: to.to_vec(),
        },
    )
}

/// Fig. 13 with its disturbance moved onto the nest (where the ants start), started at step 3
/// and stopped at step 7, and the food moved at step 5.
fn disturbance() -> Scenario {
    let mut sc = scenario::builtin("ants-fig13-disturbance").unwrap();
    sc.events = vec![
        move_to(2, "danger", [50.0, 60.0]),
        event(3, Action::Start("danger".into())),
        move_to(5, "food", [60.0, 70.0]),
        event(7, Action::Stop("danger".into())),
    ];
    short(sc)
}

/// Fig. 11 with a rock moved onto the nest and added at step 4 (the ants under it are moved
/// out), and removed at step 8.
fn rock_on_the_nest() -> Scenario {
    let mut sc = scenario::builtin("ants-fig11-dynamic-obstacles").unwrap();
    sc.events = vec![
        move_to(1, "rock-1", [50.0, 60.0]),
        event(4, Action::Add("rock-1".into())),
        event(8, Action::Remove("rock-1".into())),
    ];
    short(sc)
}

/// wang2014 Fig. 8 with the chased ball moved next to the swarm at step 4: the cost field is
/// solved again and every insect turns (issue 15).
fn chase() -> Scenario {
    let mut sc = scenario::builtin("wang-fig8-chasing").unwrap();
    sc.events = vec![Event {
        step: 4,
        action: Action::Move {
            object: "ball".into(),
            to: vec![40.0, 20.0, 4.0],
        },
    }];
    short(sc)
}

/// ren2016 Fig. 8 with the predator added at step 2 beside the swarm and moved into it at
/// step 5: the flies that see it escape (issue 16).
fn escape() -> Scenario {
    let mut sc = scenario::builtin("fly-fig8-escape").unwrap();
    sc.events = vec![
        event(2, Action::Add("predator".into())),
        Event {
            step: 2,
            action: Action::Move {
                object: "predator".into(),
                to: vec![22.0, 20.0, 20.0],
            },
        },
        Event {
            step: 5,
            action: Action::Move {
                object: "predator".into(),
                to: vec![28.0, 20.0, 20.0],
            },
        },
    ];
    short(sc)
}

/// `sc` run for [`STEPS`] steps, recording only the trajectories.
fn short(mut sc: Scenario) -> Scenario {
    sc.set_steps(STEPS);
    sc.outputs.render = false;
    sc.outputs.gif = false;
    sc.outputs.npy = false;
    sc.outputs.trajectories = true;
    sc.validate().unwrap();
    sc
}

/// A fresh folder for this test's outputs.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("mirror-events-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Mirrors `sc` with its events on its soft device in memory; returns the report and the
/// engine's last frame.
fn mirrored(sc: &Scenario) -> (MirrorReport, Frame) {
    let mut engine = swarm_sim::models::engine(sc, sc.seed).unwrap();
    let device = engine.device().unwrap().soft;
    let (dev_end, host_end) = memory_pair();
    let soft = SoftDevice::spawn(move |stop| serve(device, dev_end, stop).map(|_| ()));
    // A clean line: the timeout's floor well above a descheduled thread (tests run in
    // parallel).
    let client = ClientOptions {
        rto: RtoOptions {
            min: Duration::from_millis(50),
            ..RtoOptions::default()
        },
        ..ClientOptions::default()
    };
    let mut client = Client::new(host_end, client);
    let opts = MirrorOptions {
        agents: Some(25),
        steps: STEPS,
        session: 13,
        progress: false,
    };
    let r = mirror_with_events(sc, &mut *engine, &mut client, &opts, &mut |_| Ok(())).unwrap();
    soft.stop().unwrap();
    assert_eq!(engine.next_step(), STEPS);
    engine.sync().unwrap();
    (r, engine.frame())
}

/// The last frame of a plain `swarm run` of `sc`, as read back from its trajectories.
fn plain_run(sc: &Scenario, dir: &Path) -> Frame {
    let out = dir.join("run");
    let opts = RunOptions {
        out: out.clone(),
        steps: None,
        seed: None,
        threads: Some(1),
        backend: None,
        progress: false,
        warnings: Vec::new(),
    };
    run(sc, &opts).unwrap();
    let frames = read_csv(out.join(output::TRAJECTORIES_CSV)).unwrap();
    frames.into_iter().last().unwrap()
}

/// `frame` as the trajectories file records it (written and read back).
fn as_recorded(frame: Frame, dir: &Path) -> Frame {
    let path = dir.join("mirrored.csv");
    write_csv(&path, &[frame]).unwrap();
    read_csv(&path).unwrap().pop().unwrap()
}

/// `sc`'s engine ticked [`STEPS`] times with no event applied.
fn without_events(sc: &Scenario) -> Frame {
    let mut engine = swarm_sim::models::engine(sc, sc.seed).unwrap();
    for _ in 0..STEPS {
        engine.tick().unwrap();
    }
    engine.sync().unwrap();
    engine.frame()
}

/// How many agents of `a` and `b` differ (all, if they do not hold the same agents).
fn differing(a: &Frame, b: &Frame) -> usize {
    if a.agents.len() != b.agents.len() {
        return a.agents.len().max(b.agents.len());
    }
    a.agents
        .iter()
        .zip(&b.agents)
        .filter(|(x, y)| x != y)
        .count()
}

#[test]
fn a_mirrored_scenario_applies_its_events_and_ends_where_its_run_ends() {
    let cases = [
        ("disturbance", disturbance(), ScalarType::F32, Backend::Cpu),
        (
            "disturbance-fixed",
            disturbance(),
            ScalarType::Fixed,
            Backend::Cpu,
        ),
        ("rock", rock_on_the_nest(), ScalarType::F32, Backend::Cpu),
        // The device against decisions made on the GPU (issue 14).
        (
            "disturbance-fixed-gpu",
            disturbance(),
            ScalarType::Fixed,
            Backend::Gpu,
        ),
        (
            "rock-fixed-gpu",
            rock_on_the_nest(),
            ScalarType::Fixed,
            Backend::Gpu,
        ),
        ("chase", chase(), ScalarType::F32, Backend::Cpu),
        ("chase-fixed", chase(), ScalarType::Fixed, Backend::Cpu),
        ("escape", escape(), ScalarType::F32, Backend::Cpu),
        ("escape-fixed", escape(), ScalarType::Fixed, Backend::Cpu),
    ];
    for (name, sc, scalar, backend) in cases {
        let model = sc.groups[0].model.to_string();
        let mut sc = with_scalar(&sc, scalar);
        sc.backend = backend;
        let dir = scratch(name);
        let phases = swarm_sim::models::engine(&sc, sc.seed)
            .unwrap()
            .phases()
            .len() as u64;
        let (r, frame) = mirrored(&sc);
        assert_eq!(r.decisions, 25 * phases * u64::from(STEPS), "{name}");
        assert_eq!(r.mismatches, 0, "{name}: {}", r.human());
        assert!(r.passed(), "{name}: {}", r.human());
        assert_eq!(r.model, model, "{name}");
        assert_eq!(r.backend, backend.name(), "{name}");
        assert_eq!(frame.step, STEPS, "{name}");
        // The events changed where the ants are ...
        let moved = differing(&frame, &without_events(&sc));
        assert!(moved > 0, "{name}: the events changed nothing");
        // ... and the mirror applied them as the run loop does.
        let run = plain_run(&sc, &dir);
        assert_eq!(run.step, STEPS, "{name}");
        let off = differing(&as_recorded(frame, &dir), &run);
        assert_eq!(
            off, 0,
            "{name}: agents not where the run has them ({moved} moved by the events)"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
