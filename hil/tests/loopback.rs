//! The mirror against the soft device, end to end: in memory and over a pseudo-terminal, in
//! both scalar types, through injected faults; and devices that must be caught.

use std::time::Duration;

use swarm_core::ant::AntParams;
use swarm_core::wire::{self, Accumulator, AntDevice, AntPlanReply, Event, kind};
use swarm_hil::client::machine::RawPayload;
use swarm_hil::client::{Client, ClientOptions, RtoOptions};
use swarm_hil::loopback::{Line, LinkKind, loopback, with_scalar};
use swarm_hil::mirror::{MirrorOptions, MirrorReport, mirror, pick_agents};
use swarm_hil::soft::{SoftDevice, serve};
use swarm_hil::transport::{FaultSpec, Transport, memory_pair};
use swarm_hil::{HilError, Result};
use swarm_sim::ants::AntSim;
use swarm_sim::scenario::{self, ScalarType, Scenario};

fn fig7a() -> Scenario {
    scenario::builtin("ants-fig7a-single-colony").unwrap()
}

fn opts(agents: usize, steps: u32) -> MirrorOptions {
    MirrorOptions {
        agents: Some(agents),
        steps,
        session: 42,
        progress: false,
    }
}

/// Mirrors `agents` ants of `sc` for `steps` steps on the device behind `client`.
fn mirror_ants<T: Transport>(
    sc: &Scenario,
    client: &mut Client<T>,
    agents: usize,
    steps: u32,
) -> Result<MirrorReport> {
    let sim = AntSim::from_scenario(sc, sc.seed).unwrap();
    let opts = opts(agents, steps);
    mirror(&sc.name, Box::new(sim), client, &opts, &mut |_| Ok(()))
}

#[test]
fn ten_thousand_decisions_of_ants_and_of_bees_match_in_memory_and_over_a_pty_in_both_scalars() {
    // Ants: 50 ants × 100 steps × (plan + resolve); bees: 100 bees × 100 steps.
    let cases = [
        (fig7a(), 50),
        (scenario::builtin("bees-fig15-nest").unwrap(), 100),
    ];
    let clean_line = clean_line();
    for (sc, agents) in &cases {
        for link in [LinkKind::Memory, LinkKind::Pty] {
            for scalar in [ScalarType::F32, ScalarType::Fixed] {
                let what = format!("{} {link:?} {scalar:?}", sc.name);
                let line = Line {
                    client: clean_line,
                    ..Line::clean(link)
                };
                let r = loopback(sc, scalar, line, &opts(*agents, 100)).unwrap();
                assert_eq!(r.decisions, 10_000, "{what}");
                assert_eq!(r.mismatches, 0, "{what}: {}", r.human());
                // The timeout follows the measured round trips (tens of µs here, floor 50 ms):
                // a thread descheduled longer than that on a busy machine costs a harmless
                // retransmission, answered twice.
                assert_eq!(r.crc_errors, 0, "{what}");
                assert!(r.retries <= 100, "{what}: {}", r.human());
                let dev = r.device_stats.unwrap();
                // Every request intact (the probes of the session setup and of the final stats
                // request fall outside the device's counting).
                let ok = dev.link.frames_ok as u64;
                assert!(
                    (10_000..=10_000 + r.probes + r.retries + 1).contains(&ok),
                    "{what}: {ok}"
                );
                assert_eq!(dev.link.resyncs(), 0, "{what}");
            }
        }
    }
}

#[test]
fn faults_on_the_line_are_survived_and_reported() {
    // 1 % of the bytes damaged each way (a third dropped, a third flipped, a third inserted),
    // plus bursts of garbage.
    let spec: FaultSpec = "drop=0.0034,flip=0.0033,insert=0.0033,garbage=0.0005"
        .parse()
        .unwrap();
    let client = ClientOptions::default();
    for (link, scalar) in [
        (LinkKind::Memory, ScalarType::Fixed),
        (LinkKind::Pty, ScalarType::F32),
    ] {
        let line = Line {
            link,
            faults: spec,
            fault_seed: 3,
            client,
        };
        let r = loopback(&fig7a(), scalar, line, &opts(20, 50)).unwrap();
        assert_eq!(r.decisions, 2_000, "every decision accounted for");
        assert_eq!(r.mismatches, 0, "{}", r.human());
        let f = r.faults.expect("fault counts");
        assert!(
            f.dropped > 100 && f.flipped > 100 && f.inserted > 100 && f.bursts > 5,
            "{f:?}"
        );
        assert!(
            r.crc_errors + r.resyncs > 0 && r.retries > 0,
            "{}",
            r.human()
        );
    }
}

#[test]
fn a_device_with_other_parameters_is_refused_at_the_handshake() {
    let sc = fig7a();
    let other = AntParams::<f32> {
        w0: 0.5,
        ..AntParams::default()
    };
    let device = AntDevice::<f32>::new(other, "other-ant").unwrap();
    let (dev_end, host_end) = memory_pair();
    let soft = SoftDevice::spawn(move |stop| serve(Box::new(device), dev_end, stop).map(|_| ()));
    let mut client = Client::new(host_end, ClientOptions::default());
    let err = mirror_ants(&sc, &mut client, 5, 5).unwrap_err();
    let msg = err.to_string();
    assert!(matches!(err, HilError::Handshake(_)), "{msg}");
    assert!(
        msg.contains("other-ant") && msg.contains("params hash 0x"),
        "{msg}"
    );
    soft.stop().unwrap();
}

#[test]
fn a_planted_wrong_decision_is_reported_with_its_step_and_agent() {
    let sc = with_scalar(&fig7a(), ScalarType::F32);
    let sim = AntSim::from_scenario(&sc, sc.seed).unwrap();
    let agents = 10;
    let chosen = pick_agents(sim.agents(), Some(agents));
    // The plan of the 8th chosen ant at step 3.
    let target = {
        let mut probe = AntSim::from_scenario(&sc, sc.seed).unwrap();
        for _ in 0..3 {
            probe.step().unwrap();
        }
        probe.plan_phase().unwrap();
        let slot = probe
            .world
            .sensed
            .id
            .iter()
            .position(|&i| i == chosen[7])
            .unwrap();
        let [x, y] = probe.world.predicted[slot];
        swarm_core::Vec2::new(x as f32, y as f32)
    };
    // A device divergence repeats every time the plan is asked for (unlike line damage).
    let r = scripted(
        move |_, reply| {
            if reply.plan.predicted == target {
                Act::Wrong
            } else {
                Act::Pass
            }
        },
        ClientOptions::default(),
    )
    .unwrap();
    assert_eq!(r.decisions, 120);
    assert_eq!(r.mismatches, 1, "{}", r.human());
    assert_eq!(
        r.reasked, 0,
        "asked again, the device repeats its divergence"
    );
    let m = r.first_mismatch.unwrap();
    assert_eq!((m.step, m.agent, m.phase), (3, chosen[7], "plan"));
    let host: AntPlanReply<f32> = serde_json::from_value(m.host).unwrap();
    let dev: AntPlanReply<f32> = serde_json::from_value(m.device).unwrap();
    assert_eq!(
        dev.plan.predicted.x.to_bits(),
        host.plan.predicted.x.to_bits() + 1
    );
    assert!(
        m.request.get("frame").is_some(),
        "the sensor frame is in the report"
    );
}

#[test]
fn a_device_reset_mid_run_is_re_handshaken_and_reported() {
    let sc = with_scalar(&fig7a(), ScalarType::Fixed);
    // The scenario's parameters are f32 numbers, cast to fixed point.
    let params = AntParams::<f32>::default().cast::<swarm_core::Fx>();
    let mut device = AntDevice::<swarm_core::Fx>::new(params, "resetting-ant").unwrap();
    let (mut dev_end, host_end) = memory_pair();
    // The device loses its session (a reset) after its 250th reply.
    let soft = SoftDevice::spawn(move |stop| {
        let mut buf = [0u8; 4096];
        let mut replies = 0;
        while !stop.load(std::sync::atomic::Ordering::Relaxed) {
            let n = match dev_end.recv(&mut buf, Duration::from_millis(10)) {
                Ok(n) => n,
                Err(_) => break,
            };
            let mut out = Vec::new();
            let mut input = &buf[..n];
            while let Some((reply, rest)) = device.feed(input) {
                out.extend_from_slice(reply);
                input = rest;
                replies += 1;
                if replies == 250 {
                    device.reset();
                }
            }
            if dev_end.send(&out).is_err() {
                break;
            }
        }
        Ok(())
    });
    let mut client = Client::new(host_end, ClientOptions::default());
    let r = mirror_ants(&sc, &mut client, 20, 10).unwrap();
    soft.stop().unwrap();
    assert_eq!(r.decisions, 400);
    assert_eq!(r.mismatches, 0, "{}", r.human());
    assert_eq!(r.resets, 1, "{}", r.human());
}

#[test]
fn steps_zero_on_the_command_line_is_refused_like_steps_zero_in_a_file() {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_swarm-hil"))
        .args([
            "loopback",
            "--scenario",
            "ants-fig7a-single-colony",
            "--steps",
            "0",
        ])
        .output()
        .expect("runs swarm-hil");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "accepted --steps 0: {err}");
    assert!(
        err.contains("--steps") && err.contains("expected at least 1 step, found 0"),
        "{err}"
    );
}

/// What a [`Scripted`] device link does with the `n`-th plan reply (counted from 0, retries
/// included), given that reply.
#[derive(Clone, Copy)]
enum Act {
    /// Sends it as it is.
    Pass,
    /// Moves its predicted x up by one ulp (a wrong decision, valid CRC).
    Wrong,
    /// Replaces its payload by a byte that does not decode (valid CRC).
    Garbled,
    /// Sends nothing, now or ever again.
    Silence,
}

/// A device link that follows a script for the plan replies.
struct Scripted<F> {
    inner: swarm_hil::transport::MemoryTransport,
    rx: Accumulator<2048>,
    plans: u32,
    silent: bool,
    script: F,
}

impl<F: FnMut(u32, &AntPlanReply<f32>) -> Act + Send> Transport for Scripted<F> {
    fn send(&mut self, bytes: &[u8]) -> Result<()> {
        let mut out = Vec::new();
        let mut input = bytes;
        while let Some((event, rest)) = self.rx.feed(input) {
            input = rest;
            let Event::Frame(frame) = event else { continue };
            let mut buf = [0u8; 512];
            let seq = frame.header.seq;
            let raw = |buf: &mut [u8]| {
                wire::encode_frame(frame.header.kind, seq, &RawPayload(frame.payload), buf)
            };
            let n = if frame.header.kind == kind::ANT_PLAN_REPLY && !self.silent {
                let n = self.plans;
                self.plans += 1;
                let mut reply: AntPlanReply<f32> = frame.message().unwrap();
                match (self.script)(n, &reply) {
                    Act::Pass => raw(&mut buf).unwrap(),
                    Act::Wrong => {
                        let x = reply.plan.predicted.x;
                        reply.plan.predicted.x = f32::from_bits(x.to_bits() + 1);
                        wire::encode_message(seq, &reply, &mut buf).unwrap()
                    }
                    Act::Garbled => {
                        wire::encode_frame(kind::ANT_PLAN_REPLY, seq, &(0xffu8,), &mut buf).unwrap()
                    }
                    Act::Silence => {
                        self.silent = true;
                        0
                    }
                }
            } else if self.silent {
                0
            } else {
                raw(&mut buf).unwrap()
            };
            out.extend_from_slice(&buf[..n]);
        }
        if out.is_empty() {
            return Ok(());
        }
        self.inner.send(&out)
    }
    fn recv(&mut self, buf: &mut [u8], timeout: Duration) -> Result<usize> {
        self.inner.recv(buf, timeout)
    }
    fn name(&self) -> String {
        "scripted".into()
    }
}

/// Mirrors 10 ants for 6 steps of fig. 7a against a soft device behind `script`.
fn scripted(
    script: impl FnMut(u32, &AntPlanReply<f32>) -> Act + Send + 'static,
    client: ClientOptions,
) -> Result<MirrorReport> {
    let sc = with_scalar(&fig7a(), ScalarType::F32);
    let device = AntDevice::<f32>::new(AntParams::default(), "soft-ant").unwrap();
    let (dev_end, host_end) = memory_pair();
    let link = Scripted {
        inner: dev_end,
        rx: Accumulator::new(),
        plans: 0,
        silent: false,
        script,
    };
    let soft = SoftDevice::spawn(move |stop| serve(Box::new(device), link, stop).map(|_| ()));
    let mut client = Client::new(host_end, client);
    let r = mirror_ants(&sc, &mut client, 10, 6);
    soft.stop().unwrap();
    r
}

/// The client of a clean line: the timeout's floor well above a descheduled thread (the
/// default 2 ms is for damaged lines, where a fast retry matters; here the tests run in
/// parallel, and a retransmission would make the scripted replies' count ambiguous).
fn clean_line() -> ClientOptions {
    ClientOptions {
        rto: RtoOptions {
            min: Duration::from_millis(50),
            ..RtoOptions::default()
        },
        ..ClientOptions::default()
    }
}

/// [`scripted`] on a clean line's client, a script that does `act` to the `n`-th plan reply
/// and passes the others, and a run that completes.
fn scripted_once(n: u32, act: Act) -> MirrorReport {
    scripted(
        move |i, _| if i == n { act } else { Act::Pass },
        clean_line(),
    )
    .unwrap()
}

#[test]
fn a_mismatch_before_the_line_goes_silent_is_in_the_report_with_the_link_failure() {
    // The 25th plan reply (step 2) is wrong, then the line goes silent: asking again fails.
    let client = ClientOptions {
        dead_after: Duration::from_millis(300),
        ..clean_line()
    };
    let err = scripted(
        |n, _| match n {
            24 => Act::Wrong,
            25.. => Act::Silence,
            _ => Act::Pass,
        },
        client,
    )
    .unwrap_err();
    let HilError::Aborted { report, source } = err else {
        panic!("{err}")
    };
    assert!(matches!(*source, HilError::LinkDead { .. }), "{source}");
    assert_eq!(report.completed_steps, 2);
    assert_eq!(
        report.decisions,
        2 * 20 + 5,
        "the answered plans of step 2 count"
    );
    assert_eq!(report.mismatches, 1, "{}", report.human());
    let m = report.first_mismatch.as_ref().expect("the mismatch");
    assert_eq!((m.step, m.phase), (2, "plan"));
    assert_eq!(report.mismatch_at.len(), 1);
    assert!(report.verdict.mismatch && report.verdict.link_failure);
    assert_eq!(report.verdict.exit_code(), 3);
    assert!(
        report
            .failure
            .as_deref()
            .is_some_and(|f| f.contains("nothing intact")),
        "{:?}",
        report.failure
    );
    let json = serde_json::to_value(&*report).unwrap();
    assert_eq!(json["verdict"], "mismatch+link-failure");
}

#[test]
fn a_crc_valid_reply_that_does_not_decode_is_asked_again() {
    let r = scripted_once(7, Act::Garbled);
    assert_eq!((r.decisions, r.mismatches), (120, 0), "{}", r.human());
    assert_eq!(r.undecodable, 1);
    assert!(r.passed(), "line damage is not the device's fault");
}

#[test]
fn a_device_wrong_then_right_when_asked_again_is_flaky_not_passed() {
    let r = scripted_once(13, Act::Wrong);
    assert_eq!(
        (r.decisions, r.mismatches, r.reasked),
        (120, 0, 1),
        "{}",
        r.human()
    );
    assert!(!r.passed());
    assert_eq!(r.verdict.name(), "flaky");
    assert_eq!(r.verdict.exit_code(), 4);
}

fn swarm_hil_cli(args: &[&str]) -> (Option<i32>, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_swarm-hil"))
        .args(args)
        .output()
        .expect("runs swarm-hil");
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn usage_errors_exit_64_and_say_what_is_wrong() {
    let base = ["--scenario", "ants-fig7a-single-colony", "--quiet"];
    for (args, says) in [
        (&["loopback", "--agents", "0"][..], "--agents 0"),
        (&["loopback", "--agents", "501"][..], "has only 500 agents"),
        (
            &["loopback", "--steps", "0"][..],
            "expected at least 1 step",
        ),
        (&["loopback", "--inject", "drop=2"][..], "rate in [0, 1]"),
        (&["loopback", "--dead-after", "inf"][..], "--dead-after"),
        (&["loopback", "--bogus"][..], "--bogus"),
        (
            &[
                "qemu",
                "--firmware",
                "ant-node",
                "--steps",
                "5",
                "--reset-at-step",
                "5",
            ][..],
            "--reset-at-step 5 is beyond the run",
        ),
        (
            &["mirror", "--tcp", "127.0.0.1:1", "--agents", "0"][..],
            "--agents 0",
        ),
    ] {
        let all: Vec<&str> = args.iter().chain(&base).copied().collect();
        let (code, err) = swarm_hil_cli(&all);
        assert_eq!(code, Some(64), "{all:?}: {err}");
        assert!(err.contains(says), "{all:?}: {err}");
    }
    let (code, _) = swarm_hil_cli(&["--help"]);
    assert_eq!(code, Some(0));
}

#[test]
fn the_json_report_is_written_when_the_link_fails() {
    // A device that never answers: no report of decisions, but a JSON that says why.
    let dir = tempfile::tempdir().unwrap();
    let json = dir.path().join("r.json");
    let (code, err) = swarm_hil_cli(&[
        "loopback",
        "--scenario",
        "ants-fig7a-single-colony",
        "--agents",
        "4",
        "--steps",
        "3",
        "--quiet",
        "--inject",
        "drop=1",
        "--dead-after",
        "0.3",
        "--json",
        json.to_str().unwrap(),
    ]);
    assert_eq!(code, Some(1), "{err}");
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(v["verdict"], "link-failure", "{v}");
    assert!(
        v["failure"].as_str().unwrap().contains("nothing intact"),
        "{v}"
    );
}
