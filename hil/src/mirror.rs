//! The mirror: run a scenario on the host and, for the chosen agents, send each step's sensor
//! frames to the device and compare its decisions with the host's, bit for bit (the postcard
//! bytes of both decisions). A mismatch is recorded with its step, agent, sensor frame and both
//! decisions, and the run goes on so every mismatch is counted.

use std::time::Instant;

use indicatif::{ProgressBar, ProgressStyle};
use serde::Serialize;
use serde::de::DeserializeOwned;
use swarm_core::ant::{self, AntParams, AntPlan};
use swarm_core::bee::{self, BeeParams, BeeState};
use swarm_core::wire::{
    AntPlanReply, AntPlanRequest, AntResolveReply, AntResolveRequest, BeeStepReply, BeeStepRequest,
    Controller, DeviceStats, ErrorReply, Identity, MAX_ANT_FRAME, MAX_BEE_FRAME, Message,
    params_hash,
};
use swarm_core::{Checked, StepCtx};
use swarm_sim::ants::{AntSim, plan_frame, resolve_frame};
use swarm_sim::bees::{BeeSim, bee_frame, bee_frame_time};
use swarm_sim::scalar::{ByScalar, SimScalar};
use swarm_sim::scenario::{Scenario, World};

use crate::client::{Client, Partial};
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
    /// Which request: `plan`, `resolve` (ants) or `step` (bees).
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
    /// `ants` or `bees`.
    pub model: String,
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
            "{:.0} decisions/s, latency p50 {} µs, p99 {} µs, max {} µs; {:.1} bytes per round trip\n",
            self.decisions_per_s,
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
    /// [`Tally::check`] for every chosen agent of one phase of `step` that was answered, in
    /// order.
    fn check_all<Q: Serialize, D: Serialize>(
        &mut self,
        (step, phase): (u32, &'static str),
        chosen: &[u32],
        requests: &[Q],
        host: &[D],
        device: &[Option<std::result::Result<D, ErrorReply>>],
    ) {
        for ((&id, req), (h, d)) in chosen.iter().zip(requests).zip(host.iter().zip(device)) {
            if let Some(d) = d {
                self.check((step, id, phase), req, h, d);
            }
        }
    }

    /// Compares `device` with `host` bit for bit (their postcard bytes).
    fn check<Q: Serialize, D: Serialize>(
        &mut self,
        (step, agent, phase): (u32, u32, &'static str),
        request: &Q,
        host: &D,
        device: &std::result::Result<D, ErrorReply>,
    ) {
        self.decisions += 1;
        let same = match device {
            Ok(d) => postcard::to_allocvec(d).ok() == postcard::to_allocvec(host).ok(),
            Err(_) => false,
        };
        if same {
            return;
        }
        self.mismatches += 1;
        self.at.push(MismatchAt { step, agent, phase });
        if self.first.is_none() {
            let json = |v: &dyn erased::Json| v.json();
            self.first = Some(Mismatch {
                step,
                agent,
                phase,
                request: json(request),
                host: json(host),
                device: match device {
                    Ok(d) => json(d),
                    Err(e) => serde_json::json!({ "error": e.name(), "code": e.code }),
                },
            });
        }
    }
}

/// `serde_json::to_value` behind a trait object (the mismatch keeps any decision type).
mod erased {
    pub trait Json {
        fn json(&self) -> serde_json::Value;
    }
    impl<T: serde::Serialize> Json for T {
        fn json(&self) -> serde_json::Value {
            serde_json::to_value(self).unwrap_or(serde_json::Value::Null)
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

fn core_err(e: swarm_core::Error) -> HilError {
    HilError::Invalid(e.to_string())
}

/// Mirrors scenario `sc` (ants or bees, every group already in scalar type `S`) on the device
/// behind `client`, calling `before_step` before each step.
pub fn mirror_scenario<S, T>(
    sc: &Scenario,
    client: &mut Client<T>,
    opts: &MirrorOptions,
    before_step: &mut dyn FnMut(u32) -> Result<()>,
) -> Result<MirrorReport>
where
    S: SimScalar + Serialize + DeserializeOwned,
    T: Transport,
    AntSim: GroupsOf<S>,
    BeeSim: BeeGroupsOf<S>,
{
    let bad = |e: swarm_sim::SimError| HilError::Invalid(format!("scenario `{}`: {e}", sc.name));
    match sc.world {
        World::Ants2D { .. } => {
            let sim = AntSim::from_scenario(sc, sc.seed).map_err(bad)?;
            mirror_ants_with::<S, T>(&sc.name, sim, client, opts, before_step)
        }
        World::Bees3D { .. } => {
            let sim = BeeSim::from_scenario(sc, sc.seed).map_err(bad)?;
            mirror_bees_with::<S, T>(&sc.name, sim, client, opts, before_step)
        }
    }
}

/// The parameters a device must run to mirror scenario `sc` in scalar type `S`.
pub enum DeviceParams<S> {
    /// An ant device.
    Ant(AntParams<S>),
    /// A bee device.
    Bee(BeeParams<S>),
}

/// [`DeviceParams`] of scenario `sc` (every group already in scalar type `S`).
pub fn device_params<S>(sc: &Scenario) -> Result<DeviceParams<S>>
where
    S: SimScalar,
    AntSim: GroupsOf<S>,
    BeeSim: BeeGroupsOf<S>,
{
    let bad = |e: swarm_sim::SimError| HilError::Invalid(format!("scenario `{}`: {e}", sc.name));
    Ok(match sc.world {
        World::Ants2D { .. } => DeviceParams::Ant(*GroupsOf::<S>::single_params(
            &AntSim::from_scenario(sc, sc.seed).map_err(bad)?,
        )?),
        World::Bees3D { .. } => DeviceParams::Bee(*BeeGroupsOf::<S>::single_params(
            &BeeSim::from_scenario(sc, sc.seed).map_err(bad)?,
        )?),
    })
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

/// The postcard bytes of a decision: what "bit for bit" compares.
fn bytes<D: Serialize>(d: &D) -> Option<Vec<u8>> {
    postcard::to_allocvec(d).ok()
}

impl Session {
    /// Sends `requests` and returns the device's decisions (`decision` of each reply). A
    /// decision that differs from the host's (`host`) is asked for again, up to twice: a
    /// device's real divergence repeats. An answer that then equals the host's replaces the
    /// first (counted in `reasked`: a flaky device, or line damage that passed the CRC);
    /// otherwise the first stands as the device's decision. When the link fails, the decisions
    /// that came so far (`None` for the others) come back with the error: a mismatch found
    /// must be counted before the run stops.
    fn ask<T, Q, A, D>(
        &mut self,
        client: &mut Client<T>,
        requests: &[Q],
        host: &[D],
        decision: impl Fn(&A) -> D,
    ) -> (Decisions<D>, Option<HilError>)
    where
        T: Transport,
        Q: Message + Serialize + Clone,
        A: Message + DeserializeOwned,
        D: Serialize,
    {
        let Partial { replies, error } = self.call_all::<T, Q, A>(client, requests);
        let mut out: Decisions<D> = replies
            .into_iter()
            .map(|r| r.map(|r| r.map(|a| decision(&a))))
            .collect();
        if error.is_some() {
            return (out, error);
        }
        for _ in 0..2 {
            let differ: Vec<usize> = (0..out.len())
                .filter(|&i| {
                    out[i]
                        .as_ref()
                        .is_some_and(|d| d.as_ref().ok().and_then(bytes) != bytes(&host[i]))
                })
                .collect();
            if differ.is_empty() {
                break;
            }
            let again: Vec<Q> = differ.iter().map(|&i| requests[i].clone()).collect();
            let answers = self.call_all::<T, Q, A>(client, &again);
            for (i, a) in differ.into_iter().zip(answers.replies) {
                if let Some(Ok(a)) = a {
                    let d = decision(&a);
                    if bytes(&d) == bytes(&host[i]) {
                        out[i] = Some(Ok(d));
                        self.reasked += 1;
                    }
                }
            }
            if answers.error.is_some() {
                return (out, answers.error);
            }
        }
        (out, None)
    }

    /// Handshake and configure.
    fn open<T: Transport>(
        client: &mut Client<T>,
        expected: Identity,
        params_hash: u64,
        id: u32,
    ) -> Result<(Self, Identity)> {
        let device = client.handshake(&expected)?;
        client.configure(id, params_hash)?;
        let s = Session {
            expected,
            params_hash,
            id,
            resets: 0,
            reasked: 0,
        };
        Ok((s, device))
    }

    /// [`Client::call_all_partial`], re-handshaking and sending again the requests a reset
    /// device refused for want of a session.
    fn call_all<T: Transport, Q: Message + Serialize + Clone, A: Message + DeserializeOwned>(
        &mut self,
        client: &mut Client<T>,
        requests: &[Q],
    ) -> Partial<A> {
        let mut p = client.call_all_partial::<Q, A>(requests);
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
            let again: Vec<Q> = lost.iter().map(|&i| requests[i].clone()).collect();
            let answers = client.call_all_partial::<Q, A>(&again);
            for (i, a) in lost.into_iter().zip(answers.replies) {
                p.replies[i] = a;
            }
            p.error = answers.error;
        }
        p
    }
}

/// The device's decisions, in request order; `None` where no answer came.
type Decisions<D> = Vec<Option<std::result::Result<D, ErrorReply>>>;

/// The error for a frame the host's own controller refused (the harness built it wrong).
fn host_refused(
    model: &'static str,
    id: u32,
    step: u32,
) -> impl FnOnce(swarm_core::Error) -> HilError {
    move |e| HilError::Invalid(format!("the host refused {model} {id} at step {step}: {e}"))
}

/// Mirrors the ants of `sim` (every group in scalar type `S`) on the device behind `client`:
/// handshake, configure, then every step a plan request and a resolve request per chosen ant.
pub fn mirror_ants<S, T>(
    name: &str,
    sim: AntSim,
    client: &mut Client<T>,
    opts: &MirrorOptions,
) -> Result<MirrorReport>
where
    S: SimScalar + Serialize + DeserializeOwned,
    T: Transport,
    AntSim: GroupsOf<S>,
{
    mirror_ants_with::<S, T>(name, sim, client, opts, &mut |_| Ok(()))
}

/// [`mirror_ants`], calling `before_step(step)` before each step (e.g. to reset the board
/// mid-run in a test).
pub fn mirror_ants_with<S, T>(
    name: &str,
    mut sim: AntSim,
    client: &mut Client<T>,
    opts: &MirrorOptions,
    before_step: &mut dyn FnMut(u32) -> Result<()>,
) -> Result<MirrorReport>
where
    S: SimScalar + Serialize + DeserializeOwned,
    T: Transport,
    AntSim: GroupsOf<S>,
{
    let params: Checked<AntParams<S>> = sim.single_params()?;
    let agents = sim.agents();
    let run = Run::open(client, &*params, MAX_ANT_FRAME, agents, opts)?;
    run.finish(
        name,
        "ants",
        client,
        opts,
        |session, client, tally, chosen| {
            let step = sim.step;
            before_step(step)?;
            sim.plan_phase().map_err(sim_err)?;
            let slots = slots_by_id(&sim.world.sensed.id);
            let mut plans = Vec::with_capacity(chosen.len());
            let mut host_plans = Vec::with_capacity(chosen.len());
            for &id in chosen {
                let slot = slots[id as usize];
                let state = sim.state_of(slot)?;
                let frame = plan_frame::<S>(&sim.world, slot);
                let ctx = StepCtx {
                    seed: sim.seed,
                    agent: id,
                    step,
                };
                host_plans.push(ant::plan_checked(&state, &frame, &params, ctx));
                plans.push(AntPlanRequest { state, frame, ctx });
            }
            let host_plans = host_plans
                .into_iter()
                .zip(chosen)
                .map(|(h, &id)| h.map_err(host_refused("ant", id, step)))
                .collect::<Result<Vec<AntPlan<S>>>>()?;
            let (device, failed) =
                session.ask(client, &plans, &host_plans, |r: &AntPlanReply<S>| r.plan);
            tally.check_all((step, "plan"), chosen, &plans, &host_plans, &device);
            failed.map_or(Ok(()), Err)?;
            let mut resolves = Vec::with_capacity(chosen.len());
            let mut host_next = Vec::with_capacity(chosen.len());
            for (&id, host) in chosen.iter().zip(&host_plans) {
                let frame = resolve_frame::<S>(&sim.world, slots[id as usize]);
                let next = ant::resolve_checked(host, &frame, &params)
                    .map_err(host_refused("ant", id, step))?;
                host_next.push(next);
                resolves.push(AntResolveRequest { plan: *host, frame });
            }
            let (device, failed) =
                session.ask(client, &resolves, &host_next, |r: &AntResolveReply<S>| {
                    r.state
                });
            tally.check_all((step, "resolve"), chosen, &resolves, &host_next, &device);
            failed.map_or(Ok(()), Err)?;
            sim.resolve_phase().map_err(sim_err)?;
            Ok(())
        },
    )
}

/// Mirrors the bees of `sim` (every group in scalar type `S`) on the device behind `client`:
/// handshake, configure, then every step a step request per chosen bee.
pub fn mirror_bees<S, T>(
    name: &str,
    sim: BeeSim,
    client: &mut Client<T>,
    opts: &MirrorOptions,
) -> Result<MirrorReport>
where
    S: SimScalar + Serialize + DeserializeOwned,
    T: Transport,
    BeeSim: BeeGroupsOf<S>,
{
    mirror_bees_with::<S, T>(name, sim, client, opts, &mut |_| Ok(()))
}

/// [`mirror_bees`], calling `before_step(step)` before each step.
pub fn mirror_bees_with<S, T>(
    name: &str,
    mut sim: BeeSim,
    client: &mut Client<T>,
    opts: &MirrorOptions,
    before_step: &mut dyn FnMut(u32) -> Result<()>,
) -> Result<MirrorReport>
where
    S: SimScalar + Serialize + DeserializeOwned,
    T: Transport,
    BeeSim: BeeGroupsOf<S>,
{
    let params: Checked<BeeParams<S>> = sim.single_params()?;
    let agents = sim.agents();
    let run = Run::open(client, &*params, MAX_BEE_FRAME, agents, opts)?;
    run.finish(
        name,
        "bees",
        client,
        opts,
        |session, client, tally, chosen| {
            let step = sim.step;
            before_step(step)?;
            // The frames of this step, from the world as the step will see it.
            sim.world.index_positions();
            let slots = slots_by_id(&sim.world.sensed.id);
            let dt = params.dt.to_f64();
            let mut requests = Vec::with_capacity(chosen.len());
            let mut host = Vec::with_capacity(chosen.len());
            for &id in chosen {
                let slot = slots[id as usize];
                let (state, goal) = sim.bee_of(slot)?;
                let goal = goal.and_then(|g| sim.world.target_center(g));
                // The bee's own clock, as the engine gives it.
                let t = S::from_f64(bee_frame_time(sim.seed, id, step, dt));
                let frame = bee_frame::<S>(&sim.world, slot, goal, t);
                host.push(
                    bee::step_checked(&state, &frame, &params)
                        .map_err(host_refused("bee", id, step))?,
                );
                requests.push(BeeStepRequest { state, frame });
            }
            let (device, failed) = session.ask(client, &requests, &host, |r: &BeeStepReply<S>| {
                (r.decision, r.state)
            });
            tally.check_all((step, "step"), chosen, &requests, &host, &device);
            failed.map_or(Ok(()), Err)?;
            sim.step().map_err(sim_err)?;
            Ok(())
        },
    )
}

/// Access to the bee groups of one scalar type.
pub trait BeeGroupsOf<S> {
    /// The parameters shared by every group (an error if a group differs or has another
    /// scalar type).
    fn single_params(&self) -> Result<Checked<BeeParams<S>>>;
    /// The state and the goal (target object id) of the bee in world slot `slot`.
    fn bee_of(&self, slot: usize) -> Result<(BeeState<S>, Option<u16>)>;
}

macro_rules! bee_groups_of {
    ($s:ty, $variant:ident) => {
        impl BeeGroupsOf<$s> for BeeSim {
            fn single_params(&self) -> Result<Checked<BeeParams<$s>>> {
                one_params(self.groups.iter().map(|g| match g {
                    ByScalar::$variant(g) => Some((g.name.as_str(), &g.params)),
                    _ => None,
                }))
            }
            fn bee_of(&self, slot: usize) -> Result<(BeeState<$s>, Option<u16>)> {
                self.groups
                    .iter()
                    .find_map(|g| match g {
                        ByScalar::$variant(g)
                            if (g.first..g.first + g.states.len()).contains(&slot) =>
                        {
                            Some((g.states[slot - g.first], g.goal))
                        }
                        _ => None,
                    })
                    .ok_or_else(|| {
                        HilError::Invalid(format!("no bee of this scalar type in slot {slot}"))
                    })
            }
        }
    };
}
bee_groups_of!(f32, F32);
bee_groups_of!(swarm_core::Fx, Fixed);

/// The one parameter set of groups given as `(name, params)`, `None` for a group of another
/// scalar type.
fn one_params<'a, P: PartialEq + Clone + 'a>(
    groups: impl Iterator<Item = Option<(&'a str, &'a Checked<P>)>>,
) -> Result<Checked<P>> {
    let mut first: Option<(&str, &Checked<P>)> = None;
    for g in groups {
        let (name, params) = g.ok_or_else(|| {
            HilError::Invalid("every group must have the device's scalar type".into())
        })?;
        if let Some((f, fp)) = first
            && **fp != **params
        {
            return Err(HilError::Invalid(format!(
                "groups `{f}` and `{name}` have different parameters; a device runs one \
                 parameter set"
            )));
        }
        first.get_or_insert((name, params));
    }
    first
        .map(|(_, p)| p.clone())
        .ok_or_else(|| HilError::Invalid("the scenario has no agents".into()))
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

fn sim_err(e: swarm_sim::SimError) -> HilError {
    HilError::Invalid(format!("simulation: {e}"))
}

/// The scaffolding both mirrors share: the session, the chosen agents, the tally, the progress
/// bar, the clock and the report.
struct Run {
    session: Session,
    device: Identity,
    chosen: Vec<u32>,
}

impl Run {
    /// Handshake and configure for a device running `params` (frames up to `max_frame`), and
    /// the agents to mirror out of `agents`.
    fn open<T: Transport, P: Controller>(
        client: &mut Client<T>,
        params: &P,
        max_frame: usize,
        agents: usize,
        opts: &MirrorOptions,
    ) -> Result<Run> {
        let expected = Identity::of(params, max_frame, "host").map_err(core_err)?;
        let hash = params_hash(params).map_err(core_err)?;
        let (session, device) = Session::open(client, expected, hash, opts.session)?;
        Ok(Run {
            session,
            device,
            chosen: pick_agents(agents, opts.agents),
        })
    }

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

/// Slot of every agent id, this step (slots move when the simulator reorders them).
fn slots_by_id(ids: &[u32]) -> Vec<usize> {
    let mut out = vec![0; ids.len()];
    for (slot, &id) in ids.iter().enumerate() {
        out[id as usize] = slot;
    }
    out
}

/// Access to the ant groups of one scalar type.
pub trait GroupsOf<S> {
    /// The parameters shared by every group (an error if a group differs or has another
    /// scalar type).
    fn single_params(&self) -> Result<Checked<AntParams<S>>>;
    /// The slot and state of the ant in world slot `slot`.
    fn state_of(&self, slot: usize) -> Result<swarm_core::ant::AntState<S>>;
}

macro_rules! groups_of {
    ($s:ty, $variant:ident) => {
        impl GroupsOf<$s> for AntSim {
            fn single_params(&self) -> Result<Checked<AntParams<$s>>> {
                one_params(self.groups.iter().map(|g| match g {
                    ByScalar::$variant(g) => Some((g.name.as_str(), &g.params)),
                    _ => None,
                }))
            }
            fn state_of(&self, slot: usize) -> Result<swarm_core::ant::AntState<$s>> {
                self.groups
                    .iter()
                    .find_map(|g| match g {
                        ByScalar::$variant(g)
                            if (g.first..g.first + g.states.len()).contains(&slot) =>
                        {
                            Some(g.states[slot - g.first])
                        }
                        _ => None,
                    })
                    .ok_or_else(|| {
                        HilError::Invalid(format!("no ant of this scalar type in slot {slot}"))
                    })
            }
        }
    };
}
groups_of!(f32, F32);
groups_of!(swarm_core::Fx, Fixed);
