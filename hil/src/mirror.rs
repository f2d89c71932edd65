//! The mirror: run a scenario on the host and, for the chosen agents, send each step's sensor
//! frames to the device and compare its decisions with the host's, bit for bit (the postcard
//! bytes of both decisions). A mismatch is recorded with its step, agent, sensor frame and both
//! decisions, and the run goes on so every mismatch is counted.

use std::time::Instant;

use indicatif::{ProgressBar, ProgressStyle};
use serde::Serialize;
use swarm_core::wire::{DeviceStats, ErrorReply, Identity};
use swarm_sim::engine::{Engine, Exchange, apply_due_events};
use swarm_sim::scenario::Scenario;

use crate::client::{Client, Expect, Partial, RawRequest};
use crate::transport::{FaultCounts, Transport};
use crate::verdict::{MismatchAt, Verdict};
use crate::{HilError, Result};

/// What to mirror.
#[derive(Clone, Debug)]
pub struct MirrorOptions {
    /// How many agents to mirror (spread evenly over the ids), `None`: all.
    pub agents: Option<usize>,
    /// Steps to run.
    pub steps: u32,
    /// Session id sent with `Configure`.
    pub session: u32,
    /// Show a progress bar.
    pub progress: bool,
}

/// Latency percentiles of the answered requests, in microseconds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Latency {
    /// Median.
    pub p50: u32,
    /// 99th percentile.
    pub p99: u32,
    /// Largest.
    pub max: u32,
}

impl Latency {
    fn of(us: &[u32]) -> Latency {
        let mut v = us.to_vec();
        v.sort_unstable();
        let at = |q: f64| {
            v.get(((v.len() as f64 * q).ceil() as usize).saturating_sub(1))
                .copied()
                .unwrap_or(0)
        };
        Latency {
            p50: at(0.5),
            p99: at(0.99),
            max: v.last().copied().unwrap_or(0),
        }
    }
}

/// A decision of the device that differs from the host's.
#[derive(Clone, Debug, Serialize)]
pub struct Mismatch {
    /// Simulation step.
    pub step: u32,
    /// Agent id.
    pub agent: u32,
    /// Which phase of the model's tick: `plan`, `resolve` (ants), `step` (bees), ...
    pub phase: &'static str,
    /// The request sent (state and sensor frame).
    pub request: serde_json::Value,
    /// The host's decision.
    pub host: serde_json::Value,
    /// The device's decision (or its error reply).
    pub device: serde_json::Value,
}

/// Flash and static RAM of a firmware image, from its ELF sections.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct ImageSize {
    /// `.vector_table + .text + .rodata + .data` (the initial values of `.data` live in flash).
    pub flash: u64,
    /// `.data + .bss + .uninit` (the stack not included).
    pub ram: u64,
}

/// The outcome of a mirror run.
#[derive(Clone, Debug, Serialize)]
pub struct MirrorReport {
    /// Scenario name.
    pub scenario: String,
    /// The model (`ant`, `bee`, ...: [`Engine::model`]).
    pub model: String,
    /// Who made the host's decisions: `cpu` or `gpu` ([`Engine::backend`]).
    pub backend: String,
    /// The GPU adapter of the `gpu` backend.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub adapter: Option<String>,
    /// The device's identity.
    pub device: String,
    /// The link.
    pub transport: String,
    /// Agents mirrored.
    pub agents: usize,
    /// Steps asked for.
    pub steps: u32,
    /// Steps completed (fewer than `steps` when the run stopped part way).
    pub completed_steps: u32,
    /// What the run concluded (see [`Verdict`]).
    pub verdict: Verdict,
    /// Why the run stopped part way, if it did.
    pub failure: Option<String>,
    /// Decisions compared.
    pub decisions: u64,
    /// Decisions that differed.
    pub mismatches: u64,
    /// The first of them.
    pub first_mismatch: Option<Mismatch>,
    /// Where each of them was found.
    pub mismatch_at: Vec<MismatchAt>,
    /// Reply frames dropped for a bad CRC (host side).
    pub crc_errors: u64,
    /// Times the host's receiver resynchronised.
    pub resyncs: u64,
    /// Requests that timed out.
    pub timeouts: u64,
    /// Requests sent again.
    pub retries: u64,
    /// Ping probes sent at the end of batches (to detect losses early).
    pub probes: u64,
    /// Times the device was found reset mid-run (it had lost the session) and re-handshaken.
    pub resets: u32,
    /// Decisions that differed but equalled the host's when asked again: a flaky device
    /// (verdict `flaky`, unless the line's damage explains them: see
    /// [`crate::verdict::flaky`]).
    pub reasked: u64,
    /// CRC-valid answers that did not decode (damage past the CRC), asked again.
    pub undecodable: u64,
    /// Smoothed round trip at the end, in microseconds.
    pub srtt_us: u64,
    /// Retransmission timeout at the end, in microseconds.
    pub rto_us: u64,
    /// Requests in flight at most: `--window`, cut to what the device buffers
    /// (`rx_buffer`) unless the line has flow control.
    pub window: u64,
    /// What the device says it buffers while computing (`Identity.rx_buffer`, bytes).
    pub rx_buffer: u32,
    /// Round-trip latency.
    pub latency_us: Latency,
    /// Decisions per second of wall time.
    pub decisions_per_s: f64,
    /// Bytes sent.
    pub bytes_tx: u64,
    /// Bytes received.
    pub bytes_rx: u64,
    /// Bytes both ways per request and reply, on average.
    pub bytes_per_round_trip: f64,
    /// Wall time.
    pub seconds: f64,
    /// The device's own counters at the end.
    pub device_stats: Option<DeviceStats>,
    /// Faults injected on the link, if any.
    pub faults: Option<FaultCounts>,
    /// The firmware image's size, when the device is a known image (QEMU runs).
    pub image: Option<ImageSize>,
}

impl MirrorReport {
    /// Whether the run completed and the device decided exactly what the host decided, at
    /// the first asking.
    pub fn passed(&self) -> bool {
        self.verdict.passed()
    }

    /// A few lines for people.
    pub fn human(&self) -> String {
        let mut s = format!(
            "{} on {} over {}: {} decisions of {} agents in {} of {} steps, {} mismatches; \
             verdict {}\n",
            self.scenario,
            self.device,
            self.transport,
            self.decisions,
            self.agents,
            self.completed_steps,
            self.steps,
            self.mismatches,
            self.verdict
        );
        if let Some(a) = &self.adapter {
            s += &format!("host decisions made on the GPU: {a}\n");
        }
        if let Some(f) = &self.failure {
            s += &format!("stopped: {f}\n");
        }
        if let Some(m) = &self.first_mismatch {
            s += &format!(
                "first mismatch: step {}, agent {}, {}\n  host   {}\n  device {}\n",
                m.step, m.agent, m.phase, m.host, m.device
            );
        }
        s += &format!(
            "{:.0} decisions/s (window {}), latency p50 {} µs, p99 {} µs, max {} µs; {:.1} bytes \
             per round trip\n",
            self.decisions_per_s,
            self.window,
            self.latency_us.p50,
            self.latency_us.p99,
            self.latency_us.max,
            self.bytes_per_round_trip
        );
        s += &format!(
            "link: {} CRC errors, {} resyncs, {} timeouts, {} retries, {} device resets, {} \
             answers wrong then right when asked again, {} undecodable answers",
            self.crc_errors,
            self.resyncs,
            self.timeouts,
            self.retries,
            self.resets,
            self.reasked,
            self.undecodable
        );
        if let Some(f) = &self.faults {
            s += &format!(
                "; injected: {} dropped, {} flipped, {} inserted bytes, {} garbage bursts",
                f.dropped, f.flipped, f.inserted, f.bursts
            );
        }
        s
    }
}

/// Tallies decisions and keeps the first mismatch.
#[derive(Default)]
struct Tally {
    decisions: u64,
    mismatches: u64,
    first: Option<Mismatch>,
    at: Vec<MismatchAt>,
}

impl Tally {
    /// Compares the device's answer to each exchange that was answered with the engine's
    /// reply, bit for bit (their postcard bytes).
    fn check_all(&mut self, step: u32, exchanges: &[Exchange], device: &Decisions) {
        for (ex, answer) in exchanges.iter().zip(device) {
            let Some(answer) = answer else { continue };
            self.decisions += 1;
            if answer.as_ref().is_ok_and(|d| *d == ex.reply.bytes) {
                continue;
            }
            self.mismatches += 1;
            let (agent, phase) = (ex.agent, ex.phase);
            self.at.push(MismatchAt { step, agent, phase });
            if self.first.is_none() {
                self.first = Some(Mismatch {
                    step,
                    agent,
                    phase,
                    request: ex.request.to_json(),
                    host: ex.reply.to_json(),
                    device: match answer {
                        Ok(d) => (ex.reply.json)(d),
                        Err(e) => serde_json::json!({ "error": e.name(), "code": e.code }),
                    },
                });
            }
        }
    }
}

/// `k` agent ids spread evenly over `0..n` (all of them for `None` or `k ≥ n`).
pub fn pick_agents(n: usize, k: Option<usize>) -> Vec<u32> {
    match k {
        Some(k) if k < n => (0..k).map(|i| (i * n / k) as u32).collect(),
        _ => (0..n as u32).collect(),
    }
}

fn bar(show: bool, steps: u32) -> ProgressBar {
    if !show {
        return ProgressBar::hidden();
    }
    let b = ProgressBar::new(steps.into());
    b.set_style(
        ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {pos}/{len} steps {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    b
}

/// Mirrors scenario `sc` on the device behind `client`: the scenario's engine
/// ([`swarm_sim::models::engine`]) runs on the host with the scenario's timed events (see
/// [`mirror_with_events`]), and every step each chosen agent's requests go to the device,
/// calling `before_step` before each step.
pub fn mirror_scenario<T: Transport>(
    sc: &Scenario,
    client: &mut Client<T>,
    opts: &MirrorOptions,
    before_step: &mut dyn FnMut(u32) -> Result<()>,
) -> Result<MirrorReport> {
    let mut engine = swarm_sim::models::engine(sc, sc.seed)?;
    mirror_with_events(sc, &mut *engine, client, opts, before_step)
}

/// Mirrors the simulation `engine` (of any model; its groups must share one parameter set in
/// one scalar type) on the device behind `client`: handshake, configure, then every step, for
/// each phase of the model's tick, the chosen agents' requests, whose answers are compared
/// with the decisions the engine made. `before_step(step)` runs before each step (e.g. to
/// reset the board mid-run in a test). No scenario events are applied: for an engine built
/// from a scenario with events, use [`mirror_with_events`].
pub fn mirror<T: Transport>(
    name: &str,
    mut engine: Box<dyn Engine>,
    client: &mut Client<T>,
    opts: &MirrorOptions,
    before_step: &mut dyn FnMut(u32) -> Result<()>,
) -> Result<MirrorReport> {
    mirror_steps(name, &mut *engine, None, client, opts, before_step)
}

/// [`mirror`] of `engine`, built from scenario `sc`, applying the scenario's timed events
/// before the steps they are scheduled for, as `swarm run` does
/// ([`apply_due_events`]): a mirrored scenario whose objects are added, removed or moved, or
/// whose disturbances start, decides what its run decides. The engine is borrowed: after the
/// run it is at the step the mirror reached.
pub fn mirror_with_events<T: Transport>(
    sc: &Scenario,
    engine: &mut dyn Engine,
    client: &mut Client<T>,
    opts: &MirrorOptions,
    before_step: &mut dyn FnMut(u32) -> Result<()>,
) -> Result<MirrorReport> {
    mirror_steps(&sc.name, engine, Some(sc), client, opts, before_step)
}

/// The mirror run of `engine`, with the timed events of `events` if given.
fn mirror_steps<T: Transport>(
    name: &str,
    engine: &mut dyn Engine,
    events: Option<&Scenario>,
    client: &mut Client<T>,
    opts: &MirrorOptions,
    before_step: &mut dyn FnMut(u32) -> Result<()>,
) -> Result<MirrorReport> {
    let device = engine.device()?;
    let (session, identity) = Session::open(client, device.expected, device.params_hash, opts)?;
    let run = Run {
        session,
        device: identity,
        chosen: pick_agents(engine.agents(), opts.agents),
    };
    let model = engine.model();
    let (backend, adapter) = (engine.backend(), engine.adapter());
    let host = |r: &mut MirrorReport| {
        r.backend = backend.into();
        r.adapter = adapter.clone();
    };
    let result = run.finish(
        name,
        model,
        client,
        opts,
        |session, client, tally, chosen| {
            let step = engine.next_step();
            before_step(step)?;
            if let Some(sc) = events {
                apply_due_events(engine, sc);
            }
            for phase in 0..engine.phases().len() {
                engine.decide(phase)?;
                let exchanges = engine.exchanges(phase, chosen)?;
                let (device, failed) = session.ask(client, &exchanges);
                tally.check_all(step, &exchanges, &device);
                failed.map_or(Ok(()), Err)?;
                engine.publish(phase)?;
            }
            Ok(())
        },
    );
    match result {
        Ok(mut r) => {
            host(&mut r);
            Ok(r)
        }
        Err(e) => Err(e.with_report(host)),
    }
}

/// An open session with the device, re-opened when the device loses it (a reset).
struct Session {
    expected: Identity,
    params_hash: u64,
    id: u32,
    /// Times the device was found reset (it answered `NoSession`) and re-handshaken.
    resets: u32,
    /// Decisions that differed, and equalled the host's when asked again (a flaky device, or
    /// damage on the line that passed the CRC).
    reasked: u64,
}

/// The device's answers (reply payloads), in request order; `None` where no answer came.
type Decisions = Vec<Option<std::result::Result<Vec<u8>, ErrorReply>>>;

/// The requests of `exchanges`, to send.
fn requests<'a>(exchanges: impl IntoIterator<Item = &'a Exchange>) -> Vec<RawRequest> {
    exchanges
        .into_iter()
        .map(|ex| RawRequest {
            kind: ex.request.kind,
            payload: ex.request.bytes.clone(),
            expect: Expect {
                kind: ex.reply.kind,
                decodes: ex.reply.decodes,
            },
        })
        .collect()
}

impl Session {
    /// Handshake and configure (session `opts.session`) with a device expected to be
    /// `expected`.
    fn open<T: Transport>(
        client: &mut Client<T>,
        expected: Identity,
        params_hash: u64,
        opts: &MirrorOptions,
    ) -> Result<(Self, Identity)> {
        let device = client.handshake(&expected)?;
        client.configure(opts.session, params_hash)?;
        let s = Session {
            expected,
            params_hash,
            id: opts.session,
            resets: 0,
            reasked: 0,
        };
        Ok((s, device))
    }

    /// Sends the requests of `exchanges` and returns the device's answers. An answer that
    /// differs from the engine's is asked for again, up to twice: a device's real divergence
    /// repeats. An answer that then equals the engine's replaces the first (counted in
    /// `reasked`: a flaky device, or line damage that passed the CRC); otherwise the first
    /// stands. When the link fails, the answers that came so far (`None` for the others) come
    /// back with the error: a mismatch found must be counted before the run stops.
    fn ask<T: Transport>(
        &mut self,
        client: &mut Client<T>,
        exchanges: &[Exchange],
    ) -> (Decisions, Option<HilError>) {
        let Partial {
            replies: mut out,
            error,
        } = self.call_all(client, &requests(exchanges));
        if error.is_some() {
            return (out, error);
        }
        for _ in 0..2 {
            let differ: Vec<usize> = (0..out.len())
                .filter(|&i| {
                    out[i]
                        .as_ref()
                        .is_some_and(|d| d.as_ref().ok() != Some(&exchanges[i].reply.bytes))
                })
                .collect();
            if differ.is_empty() {
                break;
            }
            let again = self.call_all(client, &requests(differ.iter().map(|&i| &exchanges[i])));
            for (i, a) in differ.into_iter().zip(again.replies) {
                if let Some(Ok(d)) = a
                    && d == exchanges[i].reply.bytes
                {
                    out[i] = Some(Ok(d));
                    self.reasked += 1;
                }
            }
            if again.error.is_some() {
                return (out, again.error);
            }
        }
        (out, None)
    }

    /// [`Client::call_raw`], re-handshaking and sending again the requests a reset device
    /// refused for want of a session.
    fn call_all<T: Transport>(
        &mut self,
        client: &mut Client<T>,
        requests: &[RawRequest],
    ) -> Partial<Vec<u8>> {
        let mut p = client.call_raw(requests);
        for _ in 0..3 {
            if p.error.is_some() {
                break;
            }
            let lost: Vec<usize> = (0..p.replies.len())
                .filter(
                    |&i| matches!(&p.replies[i], Some(Err(e)) if e.code == ErrorReply::NO_SESSION),
                )
                .collect();
            if lost.is_empty() {
                break;
            }
            self.resets += 1;
            let reopened = client
                .handshake(&self.expected)
                .and_then(|_| client.configure(self.id, self.params_hash));
            if let Err(e) = reopened {
                for &i in &lost {
                    p.replies[i] = None;
                }
                p.error = Some(e);
                break;
            }
            let again: Vec<RawRequest> = lost.iter().map(|&i| requests[i].clone()).collect();
            let answers = client.call_raw(&again);
            for (i, a) in lost.into_iter().zip(answers.replies) {
                p.replies[i] = a;
            }
            p.error = answers.error;
        }
        p
    }
}

#[allow(clippy::too_many_arguments)]
fn report<T: Transport>(
    scenario: &str,
    model: &str,
    device: &Identity,
    client: &Client<T>,
    agents: usize,
    steps: u32,
    tally: Tally,
    seconds: f64,
    device_stats: Option<DeviceStats>,
) -> MirrorReport {
    let link = client.report();
    let lat = client.latencies_us();
    let trips = lat.len().max(1) as f64;
    MirrorReport {
        scenario: scenario.to_string(),
        model: model.to_string(),
        backend: String::new(),
        adapter: None,
        device: device.name.to_string(),
        transport: String::new(),
        agents,
        steps,
        completed_steps: steps,
        verdict: Verdict::default(),
        failure: None,
        decisions: tally.decisions,
        mismatches: tally.mismatches,
        first_mismatch: tally.first,
        mismatch_at: tally.at,
        crc_errors: link.crc_errors,
        resyncs: link.resyncs,
        timeouts: link.timeouts,
        retries: link.retries,
        probes: link.probes,
        resets: 0,
        reasked: 0,
        undecodable: link.undecodable,
        srtt_us: link.srtt_us,
        rto_us: link.rto_us,
        window: link.window,
        rx_buffer: device.rx_buffer,
        latency_us: Latency::of(lat),
        decisions_per_s: tally.decisions as f64 / seconds.max(1e-9),
        bytes_tx: link.bytes_tx,
        bytes_rx: link.bytes_rx,
        bytes_per_round_trip: (link.bytes_tx + link.bytes_rx) as f64 / trips,
        seconds,
        device_stats,
        faults: None,
        image: None,
    }
}

/// Whether `reasked` wrong-then-right answers are more than the damage seen on the line (frames
/// dropped by either receiver) explains.
fn flaky_beyond_line_damage(reasked: u64, host_drops: u64, device: Option<&DeviceStats>) -> bool {
    let device_drops = device.map_or(0, |d| u64::from(d.link.resyncs()));
    crate::verdict::flaky(reasked, host_drops + device_drops)
}

/// The scaffolding of a mirror run: the session, the chosen agents, the tally, the progress
/// bar, the clock and the report.
struct Run {
    session: Session,
    device: Identity,
    chosen: Vec<u32>,
}

impl Run {
    /// Runs `tick` (one simulation step: ask, compare, advance) `opts.steps` times, then asks
    /// for the device's counters and writes the report. When a step fails, the report of what
    /// was compared until then comes back inside [`HilError::Aborted`].
    fn finish<T: Transport>(
        mut self,
        name: &str,
        model: &str,
        client: &mut Client<T>,
        opts: &MirrorOptions,
        mut tick: impl FnMut(&mut Session, &mut Client<T>, &mut Tally, &[u32]) -> Result<()>,
    ) -> Result<MirrorReport> {
        let bar = bar(opts.progress, opts.steps);
        let mut tally = Tally::default();
        let t0 = Instant::now();
        let mut failure = None;
        let mut completed = 0;
        for _ in 0..opts.steps {
            if let Err(e) = tick(&mut self.session, client, &mut tally, &self.chosen) {
                failure = Some(e);
                break;
            }
            completed += 1;
            bar.inc(1);
            bar.set_message(format!(
                "{} decisions, {} mismatches",
                tally.decisions, tally.mismatches
            ));
        }
        bar.finish_and_clear();
        let seconds = t0.elapsed().as_secs_f64();
        // After a failure the link may be dead: no waiting for the device's counters then.
        let device_stats = match failure {
            None => client.device_stats().ok(),
            Some(_) => None,
        };
        let mut r = report(
            name,
            model,
            &self.device,
            client,
            self.chosen.len(),
            opts.steps,
            tally,
            seconds,
            device_stats,
        );
        r.resets = self.session.resets;
        r.reasked = self.session.reasked;
        r.transport = client.link_mut().name();
        r.completed_steps = completed;
        r.failure = failure.as_ref().map(ToString::to_string);
        r.verdict = Verdict {
            mismatch: r.mismatches > 0,
            flaky: flaky_beyond_line_damage(r.reasked, r.resyncs, r.device_stats.as_ref()),
            link_failure: failure.is_some(),
        };
        match failure {
            None => Ok(r),
            Some(source) => Err(HilError::Aborted {
                report: Box::new(r),
                source: Box::new(source),
            }),
        }
    }
}
