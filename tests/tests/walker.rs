//! The test-only walker model (`swarm_tests::walker`) plugs into everything generic by
//! implementing the traits, with no edit to a generic file: the device endpoint serves it, the
//! run loop writes its outputs, the soft device and the HIL mirror check it, 0 mismatches.

use swarm_core::model::{ModelParams, Phase};
use swarm_core::wire::{
    self, Accumulator, Configure, Controller, DeviceEndpoint, Event, Hello, Identity, params_hash,
};
use swarm_core::{Fx, Scalar, StepCtx, Vec2};
use swarm_hil::HilError;
use swarm_hil::client::{Client, ClientOptions};
use swarm_hil::loopback::{Line, LinkKind, loopback_engine};
use swarm_hil::mirror::{MirrorOptions, mirror};
use swarm_hil::soft::{SoftDevice, serve};
use swarm_hil::transport::memory_pair;
use swarm_sim::engine::Engine;
use swarm_sim::run::{RunOptions, run_with};
use swarm_sim::scalar::SimScalar;
use swarm_sim::scenario::Scenario;
use swarm_tests::walker::{Walk, WalkParams, WalkReply, WalkRequest, WalkSim, WalkState};

fn sim<S: SimScalar>(n: usize, seed: u32) -> WalkSim<S> {
    WalkSim::new(WalkParams::default().checked().unwrap(), n, seed)
}

#[test]
fn walkers_stay_between_the_walls_and_bounce_off_them() {
    let mut s = sim::<Fx>(40, 3);
    for _ in 0..2000 {
        s.tick().unwrap();
    }
    let w = WalkParams::<Fx>::default().half_width;
    assert!(
        s.states()
            .iter()
            .all(|st| st.pos.x.abs() <= w && st.pos.y.abs() <= w)
    );
    assert!(s.states().iter().map(|st| st.bounces).sum::<u32>() > 10);
}

#[test]
fn the_device_endpoint_serves_the_walker_without_knowing_it() {
    let params = WalkParams::<f32>::default();
    let mut device = DeviceEndpoint::<WalkParams<f32>, 128, 128>::new(params, "walker").unwrap();
    let request = WalkRequest {
        state: WalkState {
            pos: Vec2::new(19.9, 0.0),
            heading: Vec2::new(1.0, 0.0),
            bounces: 0,
        },
        ctx: StepCtx {
            seed: 1,
            agent: 2,
            step: 3,
        },
    };
    let configure = Configure {
        session: 1,
        params_hash: params_hash(&params).unwrap(),
        reset_stats: false,
    };
    let mut line = [0u8; 256];
    let mut n = wire::encode_message(1, &Hello, &mut line).unwrap();
    n += wire::encode_message(2, &configure, &mut line[n..]).unwrap();
    n += wire::encode_message(3, &request, &mut line[n..]).unwrap();
    let mut rx = Accumulator::<256>::new();
    let mut replies = Vec::new();
    device
        .serve(&line[..n], |r| {
            let mut input = r;
            while let Some((Event::Frame(f), rest)) = rx.feed(input) {
                replies.push((f.header.kind, f.payload.to_vec()));
                input = rest;
            }
            Ok::<_, ()>(())
        })
        .unwrap();
    assert_eq!(replies.len(), 3);
    let identity: Identity = wire::decode_payload(&replies[0].1).unwrap();
    assert_eq!(identity.controller, <WalkParams<f32> as Controller>::KIND);
    let expected = Walk::run(&params.checked().unwrap(), &request).unwrap();
    assert_eq!(replies[2].0, 0x81);
    let got: WalkReply<f32> = wire::decode_payload(&replies[2].1).unwrap();
    assert_eq!(got, expected);
}

/// The scenario of the walkers' run: a built-in one, whose world, steps, events and outputs are
/// what the run loop reads; the walkers are built from its agent count by the test.
fn scenario() -> Scenario {
    let mut sc = swarm_sim::scenario::builtin("ants-fig7a-single-colony").unwrap();
    sc.set_steps(300);
    sc.outputs.render = false;
    sc.outputs.gif = false;
    sc
}

#[test]
fn the_run_loop_writes_the_walkers_outputs() {
    let dir = tempfile::tempdir().unwrap();
    let opts = RunOptions {
        out: dir.path().join("run"),
        steps: None,
        seed: None,
        threads: Some(1),
        backend: None,
        progress: false,
        warnings: Vec::new(),
    };
    let sc = scenario();
    let report = run_with(&sc, &opts, |sc, seed| {
        Ok(Box::new(sim::<f32>(sc.agent_count() as usize, seed)) as Box<dyn Engine>)
    })
    .unwrap();
    assert_eq!(report.summary.agents, sc.agent_count() as u32);
    assert_eq!(report.summary.groups[0].model, "walker");
    assert!(report.summary.extra.contains_key("walker_bounces"));
    for f in [
        "positions.npy",
        "summary.json",
        "trajectories.csv",
        "run.log",
    ] {
        assert!(opts.out.join(f).is_file(), "{f}");
    }
}

/// `agents` walkers mirrored for `steps` steps, quietly.
fn mirror_options(agents: usize, steps: u32) -> MirrorOptions {
    MirrorOptions {
        agents: Some(agents),
        steps,
        session: 5,
        progress: false,
    }
}

#[test]
fn the_mirror_checks_the_walkers_on_their_soft_device_with_no_mismatch() {
    for link in [LinkKind::Memory, LinkKind::Pty] {
        let r = loopback_engine(
            "walkers",
            Box::new(sim::<Fx>(50, 9)),
            Line::clean(link),
            &mirror_options(12, 40),
        )
        .unwrap();
        assert_eq!(r.decisions, 12 * 40, "{link:?}");
        assert_eq!(r.mismatches, 0, "{}", r.human());
        assert_eq!(r.model, "walker");
        assert!(r.passed(), "{}", r.human());
    }
}

#[test]
fn the_mirror_refuses_a_device_with_other_walls() {
    let other = WalkSim::<f32>::new(
        WalkParams {
            half_width: 10.0,
            ..WalkParams::default()
        }
        .checked()
        .unwrap(),
        8,
        1,
    );
    let device = other.device().unwrap().soft;
    let (dev_end, host_end) = memory_pair();
    let soft = SoftDevice::spawn(move |stop| serve(device, dev_end, stop).map(|_| ()));
    let mut client = Client::new(host_end, ClientOptions::default());
    let err = mirror(
        "walkers",
        Box::new(sim::<f32>(8, 1)),
        &mut client,
        &mirror_options(4, 5),
        &mut |_| Ok(()),
    )
    .unwrap_err();
    assert!(matches!(err, HilError::Handshake(_)), "{err}");
    assert!(err.to_string().contains("params hash"), "{err}");
    soft.stop().unwrap();
}

/// The walker's scenario file (`model = "walker"`, `walker = { .. }`).
const WALKER_BOX: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/data/walker-box.toml");

/// Runs one of the binaries that register the walker; its output, after checking it exited 0.
fn registered(bin: &str, args: &[&str]) -> String {
    let out = std::process::Command::new(bin).args(args).output().unwrap();
    let (stdout, stderr) = (
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr),
    );
    assert!(
        out.status.success(),
        "{bin} {args:?}: {}\n{stdout}\n{stderr}",
        out.status
    );
    stdout.into_owned()
}

#[test]
fn swarm_run_serves_a_registered_model_from_its_scenario_file() {
    let swarm = env!("CARGO_BIN_EXE_walker-swarm");
    assert!(registered(swarm, &["models"]).contains("walker"));
    // Its parameter table, as the model declares it.
    let table = registered(swarm, &["models", "walker"]);
    assert!(
        table.contains("speed") && table.contains("a number in"),
        "{table}"
    );
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("run");
    let out_str = out.to_str().unwrap();
    registered(swarm, &["run", WALKER_BOX, "--out", out_str, "--quiet"]);
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["groups"][0]["model"], "walker");
    assert_eq!(summary["agents"], 40);
    assert!(summary["extra"]["walker_bounces"].as_u64().unwrap() > 0);
    for f in [
        "positions.npy",
        "trajectories.csv",
        "snapshot.png",
        "run.gif",
    ] {
        assert!(out.join(f).is_file(), "{f}");
    }
    // Same seed, same bits: the file's walkers again.
    let again = dir.path().join("again");
    registered(
        swarm,
        &[
            "run",
            WALKER_BOX,
            "--out",
            again.to_str().unwrap(),
            "--quiet",
        ],
    );
    assert_eq!(
        std::fs::read(out.join("positions.npy")).unwrap(),
        std::fs::read(again.join("positions.npy")).unwrap()
    );
    let bench = registered(
        swarm,
        &[
            "bench", "--model", "walker", "--agents", "100", "--steps", "3",
        ],
    );
    assert!(bench.contains("\"model\": \"walker\""), "{bench}");
}

#[test]
fn swarm_hil_loopback_mirrors_a_registered_model_with_no_mismatch() {
    let hil = env!("CARGO_BIN_EXE_walker-swarm-hil");
    let dir = tempfile::tempdir().unwrap();
    for transport in ["memory", "pty"] {
        let json = dir.path().join(format!("{transport}.json"));
        registered(
            hil,
            &[
                "loopback",
                "--scenario",
                WALKER_BOX,
                "--transport",
                transport,
                "--agents",
                "10",
                "--steps",
                "60",
                "--scalar",
                "fixed",
                "--quiet",
                "--json",
                json.to_str().unwrap(),
            ],
        );
        let r: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
        assert_eq!(r["decisions"], 600, "{transport}: {r}");
        assert_eq!(r["mismatches"], 0, "{transport}: {r}");
    }
}

#[test]
fn the_walker_rules_refuse_what_cannot_work() {
    swarm_sim::models::register(&swarm_tests::walker::ENTRY).unwrap();
    let text = std::fs::read_to_string(WALKER_BOX).unwrap();
    assert!(Scenario::from_str(&text, "walker-box.toml").is_ok());
    for (from, to, field, says) in [
        (
            "half_width = 20",
            "half_width = 30",
            "groups[0].walker.half_width",
            "outside the world",
        ),
        (
            "speed = 0.8",
            "speed = 30",
            "groups[0].walker.speed",
            "invalid walker parameter",
        ),
        (
            "speed = 0.8",
            "sped = 0.8",
            "groups[0].walker.sped",
            "unknown field `sped`",
        ),
        (
            "max = [10, 10]",
            "max = [22, 10]",
            "groups[0].spawn",
            "between the walls",
        ),
        (
            "model = \"walker\"",
            "model = \"wlaker\"",
            "groups[0].model",
            "unknown model `wlaker`",
        ),
    ] {
        let broken = text.replace(from, to);
        assert_ne!(broken, text, "{from}");
        let err = Scenario::from_str(&broken, "walker-box.toml").unwrap_err();
        let d = err.diagnostic().expect("a diagnostic");
        assert_eq!(d.field, field, "{err}");
        assert!(d.message.contains(says), "{err}");
    }
}
