//! The ant controller on the GPU (`shaders/ant_*.wgsl`, lavapipe where there is no GPU) against
//! `swarm_core::ant::plan_checked` and `resolve_checked`:
//!
//! * over `Fx`, bit for bit (every output word: the status, and the whole plan or state): every
//!   plan and resolve exchange of real fixed-point simulations of built-in ant scenarios, and
//!   randomised and edge inputs (empty and full frames, ants inside obstacles and on disturbance
//!   centres, stopped ants, every label, motion and stop, invalid inputs that must be refused
//!   with the same error);
//! * over `f32`, measured: the same scenarios simulated in `f32` (and random inputs, NaN and
//!   infinities among them), the share of decisions whose words are identical and of those
//!   whose discrete fields (status, label, ids, flags, motion, stop) are, with a floor under the
//!   latter;
//! * the word layout: both sides' constants, and values through the GPU's unpacking and
//!   packing unchanged.
//!
//! `cargo test -p swarm-sim --lib gpu::ant -- --nocapture` prints the figures.

use std::fmt::Debug;
use std::result::Result;
use std::time::Instant;

use rayon::prelude::*;
use swarm_core::ant::{
    self, AntNeighbor, AntObject, AntParams, AntPlan, AntPlanReply, AntPlanRequest,
    AntResolveReply, AntResolveRequest, AntState, Follow, Label, MotionState, SURFACES, StopReason,
    StopTimer, Surface, Turn,
};
use swarm_core::{Checked, Error, Fx, Rect, Scalar, StepCtx, Vec2};

use super::layout::*;
use super::*;
use crate::ants::{AntPlanFrame, AntResolveFrame, AntSim, N, O};
use crate::engine::{Engine, apply_due_events};
use crate::gpu::kernel::map_words;
use crate::gpu::shaders::{self, ANT_FRAME};
use crate::gpu::test_gpu;
use crate::gpu::tests::Rng;
use crate::gpu::tests::harness::{
    AntGroups, Compared, PerScalar, StatusWords, TestScalar, assert_constants, assert_valid_wgsl,
    decode_exchange, params_by_id, share, shortened,
};

/// The inputs of one `plan_checked`.
#[derive(Clone, Debug)]
struct PlanCase<S> {
    state: AntState<S>,
    frame: AntPlanFrame<S>,
    params: Checked<AntParams<S>>,
    ctx: StepCtx,
}

impl<S: Word> PlanCase<S> {
    fn rust(&self) -> Result<AntPlan<S>, Error> {
        ant::plan_checked(&self.state, &self.frame, &self.params, self.ctx)
    }
}

/// The inputs of one `resolve_checked`.
#[derive(Clone, Debug)]
struct ResolveCase<S> {
    plan: AntPlan<S>,
    frame: AntResolveFrame<S>,
    params: Checked<AntParams<S>>,
}

impl<S: Word> ResolveCase<S> {
    fn rust(&self) -> Result<AntState<S>, Error> {
        ant::resolve_checked(&self.plan, &self.frame, &self.params)
    }
}

// ---- comparing ----

/// Where the discrete fields of a state lie in its words: label, nest, origin, the goal's and
/// the follow's flags, the turn, motion, the stop (flag, reason, remaining, place).
const DISCRETE: [usize; 11] = [4, 5, 6, 9, 12, 13, 15, 16, 17, 18, 19];

/// The plan or resolve kernel's output words (`got`) against Rust's (`want`), `words` per
/// decision: a status, then a state (or a plan, whose state comes first).
fn compared(got: &[u32], want: &[u32], words: usize) -> Compared {
    Compared::of(
        got,
        want,
        words,
        |g, w| DISCRETE.iter().all(|&k| g[1 + k] == w[1 + k]),
        |(), _, _| {},
    )
}

/// Rust's answers to plan cases.
type Plans<S> = Vec<Result<AntPlan<S>, Error>>;
/// Rust's answers to resolve cases.
type States<S> = Vec<Result<AntState<S>, Error>>;

/// The plan kernel on `cases` against `plan_checked`; and Rust's answers.
fn compare_plans<S: TestScalar>(
    gpu: &Gpu,
    k: &AntKernels,
    cases: &[PlanCase<S>],
) -> (Compared, Plans<S>) {
    let mut input = Vec::with_capacity(cases.len() * PLAN_INPUT_WORDS);
    let mut want = Vec::with_capacity(cases.len() * PLAN_OUTPUT_WORDS);
    let rust: Plans<S> = cases.par_iter().map(PlanCase::rust).collect();
    for (c, r) in cases.iter().zip(&rust) {
        write_plan_input(&mut input, &c.state, &c.frame, &c.params, c.ctx);
        write_plan_result(&mut want, r);
    }
    let got = k.plan(gpu, &input).expect("plan kernel");
    (compared(&got, &want, PLAN_OUTPUT_WORDS), rust)
}

/// The resolve kernel on `cases` against `resolve_checked`; and Rust's answers.
fn compare_resolves<S: TestScalar>(
    gpu: &Gpu,
    k: &AntKernels,
    cases: &[ResolveCase<S>],
) -> (Compared, States<S>) {
    let mut input = Vec::with_capacity(cases.len() * RESOLVE_INPUT_WORDS);
    let mut want = Vec::with_capacity(cases.len() * RESOLVE_OUTPUT_WORDS);
    let rust: States<S> = cases.par_iter().map(ResolveCase::rust).collect();
    for (c, r) in cases.iter().zip(&rust) {
        write_resolve_input(&mut input, &c.plan, &c.frame, &c.params);
        write_resolve_result(&mut want, r);
    }
    let got = k.resolve(gpu, &input).expect("resolve kernel");
    (compared(&got, &want, RESOLVE_OUTPUT_WORDS), rust)
}

/// A status and the value after it, decoded, for a failure's report.
fn decoded<V: Debug>(words: &[u32], read: fn(&[u32]) -> crate::Result<V>) -> String {
    match status_error(words[0]) {
        Ok(Ok(())) => format!("{:?}", read(&words[1..])),
        Ok(Err(e)) => format!("Err({e:?})"),
        Err(e) => format!("{e}"),
    }
}

/// Panics unless every decision of `c` is bit for bit Rust's, with the first that is not.
fn assert_identical<C: Debug, V: Debug>(
    what: &str,
    c: &Compared,
    cases: &[C],
    read: fn(&[u32]) -> crate::Result<V>,
) {
    c.assert_identical(what, cases, |w| decoded(w, read));
}

// ---- real exchanges ----

/// The exchanges of a simulation: every plan and resolve request of the recorded ticks, and the
/// engine's replies.
struct Real<S> {
    plans: Vec<PlanCase<S>>,
    plan_replies: Vec<AntPlan<S>>,
    resolves: Vec<ResolveCase<S>>,
    resolve_replies: Vec<AntState<S>>,
}

/// The built-in scenario `name` simulated in `S` for `ticks` ticks (its events at the same
/// fraction of the shortened run), every ant's plan and resolve exchange (`Engine::exchanges`,
/// decoded from postcard) recorded every `every` ticks.
fn real<S: TestScalar>(name: &str, ticks: u32, every: u32) -> Real<S> {
    let sc = shortened::<S>(name, ticks);
    let mut sim = AntSim::from_scenario(&sc, sc.seed).expect("the scenario builds");
    let ids: Vec<u32> = (0..sim.agents() as u32).collect();
    let params: Vec<Checked<AntParams<S>>> =
        params_by_id::<S, AntGroups, _>(ids.len(), &sim.groups, |g| (&g.ids, g.params));
    let mut out = Real {
        plans: Vec::new(),
        plan_replies: Vec::new(),
        resolves: Vec::new(),
        resolve_replies: Vec::new(),
    };
    for t in 0..ticks {
        apply_due_events(&mut sim, &sc);
        let record = t % every == 0;
        sim.decide(0).expect("plan");
        if record {
            for ex in sim.exchanges(0, &ids).expect("plan exchanges") {
                let (req, reply): (AntPlanRequest<S>, AntPlanReply<S>) = decode_exchange(&ex);
                out.plans.push(PlanCase {
                    state: req.state,
                    frame: req.frame,
                    params: params[ex.agent as usize],
                    ctx: req.ctx,
                });
                out.plan_replies.push(reply.plan);
            }
        }
        sim.publish(0).expect("publish plans");
        sim.decide(1).expect("resolve");
        if record {
            for ex in sim.exchanges(1, &ids).expect("resolve exchanges") {
                let (req, reply): (AntResolveRequest<S>, AntResolveReply<S>) = decode_exchange(&ex);
                out.resolves.push(ResolveCase {
                    plan: req.plan,
                    frame: req.frame,
                    params: params[ex.agent as usize],
                });
                out.resolve_replies.push(reply.state);
            }
        }
        sim.publish(1).expect("publish states");
    }
    out
}

/// The scenarios of the real exchanges, and ticks simulated (recording every `EVERY`th).
const SCENARIOS: &[(&str, u32)] = &[
    ("ants-fig7a-single-colony", 300),
    ("ants-fig7b-obstacles", 300),
    ("ants-fig8a-hybrid", 300),
    ("ants-fig1c-heart", 300),
    ("ants-fig11-dynamic-obstacles", 300),
    ("ants-fig13-disturbance", 300),
];
const EVERY: u32 = 8;

/// What the decisions of `plans` and `resolves` cover (labels, motions, stops, frames), for the
/// report.
fn coverage<S: Word>(
    plans: &[&PlanCase<S>],
    planned: &[AntPlan<S>],
    resolves: &[&ResolveCase<S>],
) -> String {
    let ok = planned;
    let count = |f: &dyn Fn(&AntPlan<S>) -> bool| ok.iter().filter(|p| f(p)).count();
    let frames = |f: &dyn Fn(&PlanCase<S>) -> bool| plans.iter().filter(|c| f(c)).count();
    format!(
        "plans: label food {} nest {} nothing {}; motion stop {} basic {} neighbours {} \
         environment {}; collecting {} dropping {} casual {}; following {}; full neighbour \
         lists {}, obstacles sensed {}, disturbances {}; resolves with obstacle surfaces {}, \
         with neighbours {}",
        count(&|p| p.state.label == Label::Food),
        count(&|p| p.state.label == Label::Nest),
        count(&|p| p.state.label == Label::Nothing),
        count(&|p| p.state.motion == MotionState::Stop),
        count(&|p| p.state.motion == MotionState::BasicMovement),
        count(&|p| p.state.motion == MotionState::InteractNeighbors),
        count(&|p| p.state.motion == MotionState::InteractEnvironment),
        count(&|p| p
            .state
            .stop
            .is_some_and(|t| t.reason == StopReason::CollectingFood)),
        count(&|p| p
            .state
            .stop
            .is_some_and(|t| t.reason == StopReason::DroppingFood)),
        count(&|p| p.state.stop.is_some_and(|t| t.reason == StopReason::Casual)),
        count(&|p| p.state.follow.is_some()),
        frames(&|c| c.frame.neighbours.len() == N),
        frames(&|c| c
            .frame
            .objects
            .iter()
            .any(|o| matches!(o, AntObject::Obstacle(_)))),
        frames(&|c| {
            c.frame
                .objects
                .iter()
                .any(|o| matches!(o, AntObject::Disturbance { .. }))
        }),
        resolves
            .iter()
            .filter(|c| !c.frame.obstacles.is_empty())
            .count(),
        resolves
            .iter()
            .filter(|c| !c.frame.neighbours.is_empty())
            .count(),
    )
}

/// The test GPU and the ant kernels over `S`, made once for every test.
fn kernels<S: TestScalar>() -> &'static (Gpu, AntKernels) {
    static KERNELS: PerScalar<(Gpu, AntKernels)> = PerScalar::new();
    KERNELS.get::<S>(|| {
        let gpu = test_gpu();
        let k = AntKernels::new::<S>(&gpu).expect("the ant kernels compile");
        (gpu, k)
    })
}

/// Every scenario of [`SCENARIOS`] simulated in `S`, its exchanges on the GPU against Rust
/// (whose answers must be the engine's replies); the comparisons and, for the report, what the
/// decisions cover.
fn real_runs<S: TestScalar>(
    check: impl Fn(&str, &Compared, &Compared, &Real<S>),
) -> (Compared, Compared, String) {
    let (gpu, k) = kernels::<S>();
    let (mut plans, mut resolves) = (Compared::default(), Compared::default());
    let runs: Vec<Real<S>> = SCENARIOS
        .par_iter()
        .map(|&(name, ticks)| real::<S>(name, ticks, EVERY))
        .collect();
    for (&(name, _), run) in SCENARIOS.iter().zip(&runs) {
        let (p, planned) = compare_plans(gpu, k, &run.plans);
        let (r, resolved) = compare_resolves(gpu, k, &run.resolves);
        for (rust, reply) in planned.iter().zip(&run.plan_replies) {
            assert_eq!(
                rust.as_ref(),
                Ok(reply),
                "{name}: Rust's plan is the engine's"
            );
        }
        for (rust, reply) in resolved.iter().zip(&run.resolve_replies) {
            assert_eq!(
                rust.as_ref(),
                Ok(reply),
                "{name}: Rust's state is the engine's"
            );
        }
        check(name, &p, &r, run);
        plans.add(p);
        resolves.add(r);
    }
    let cases: Vec<&PlanCase<S>> = runs.iter().flat_map(|r| &r.plans).collect();
    let planned: Vec<AntPlan<S>> = runs.iter().flat_map(|r| r.plan_replies.clone()).collect();
    let resolve_cases: Vec<&ResolveCase<S>> = runs.iter().flat_map(|r| &r.resolves).collect();
    let covered = coverage(&cases, &planned, &resolve_cases);
    (plans, resolves, covered)
}

/// Fixed point: every plan and resolve exchange of real simulations, bit for bit.
#[test]
fn fx_real_exchanges_are_bit_for_bit() {
    let t0 = Instant::now();
    let (plans, resolves, covered) = real_runs::<Fx>(|name, p, r, run| {
        assert_identical(&format!("{name}: plan"), p, &run.plans, read_plan::<Fx>);
        assert_identical(
            &format!("{name}: resolve"),
            r,
            &run.resolves,
            read_state::<Fx>,
        );
    });
    println!(
        "fixed point, real exchanges of {} scenarios: {} plan and {} resolve decisions \
         identical on the GPU ({:.1} s)\n  {covered}",
        SCENARIOS.len(),
        plans.identical,
        resolves.identical,
        t0.elapsed().as_secs_f64(),
    );
    assert!(plans.total >= 100_000 && resolves.total >= 100_000);
    assert_eq!(
        (plans.identical, resolves.identical),
        (plans.total, resolves.total)
    );
}

/// `f32`: the same scenarios simulated in `f32`, measured (docs/gpu.md: not promised).
#[test]
fn f32_real_exchanges_are_measured() {
    let t0 = Instant::now();
    let (plans, resolves, _) = real_runs::<f32>(|_, _, _, _| {});
    let pct = |n, c: &Compared| 100.0 * share(n, c.total);
    println!(
        "f32 on {}: plan {} decisions, {:.2} % bit-identical, {:.3} % identical discrete fields \
         (status, label, ids, goal/follow flags, turn, motion, stop); resolve {} decisions, \
         {:.2} % bit-identical, {:.3} % identical discrete fields ({:.1} s)",
        kernels::<f32>().0.info().name,
        plans.total,
        pct(plans.identical, &plans),
        pct(plans.discrete, &plans),
        resolves.total,
        pct(resolves.identical, &resolves),
        pct(resolves.discrete, &resolves),
        t0.elapsed().as_secs_f64(),
    );
    assert!(plans.total >= 100_000 && resolves.total >= 100_000);
    // Random and edge inputs (NaN and infinities among the invalid ones): the same refusals.
    let mut g = Gen(Rng::new(0xf32));
    let cases: Vec<PlanCase<f32>> = (0..20_000).map(|_| g.plan_case()).collect();
    let resolve_cases: Vec<ResolveCase<f32>> = cases.iter().map(|c| g.resolve_case(c)).collect();
    let (gpu, k) = kernels::<f32>();
    let (rp, _) = compare_plans(gpu, k, &cases);
    let (rr, _) = compare_resolves(gpu, k, &resolve_cases);
    println!(
        "f32, random and edge inputs: plan {:.2} % bit-identical, {:.3} % identical discrete \
         fields ({} refused); resolve {:.2} % bit-identical, {:.3} % identical discrete fields \
         ({} refused)",
        pct(rp.identical, &rp),
        pct(rp.discrete, &rp),
        rp.refused,
        pct(rr.identical, &rr),
        pct(rr.discrete, &rr),
        rr.refused,
    );
    // The floor: a few discrete decisions in a thousand may flip where a distance or a
    // product lands on the other side of a threshold.
    assert!(
        share(plans.discrete, plans.total) >= F32_DISCRETE_FLOOR,
        "plan: {plans:?}"
    );
    assert!(
        share(resolves.discrete, resolves.total) >= F32_DISCRETE_FLOOR,
        "resolve: {resolves:?}"
    );
    for (what, c) in [("random plan", &rp), ("random resolve", &rr)] {
        assert!(
            share(c.discrete, c.total) >= F32_DISCRETE_FLOOR,
            "{what}: {c:?}"
        );
    }
}

/// The least share of `f32` decisions whose discrete fields the GPU must reproduce.
const F32_DISCRETE_FLOOR: f64 = 0.99;

// ---- randomised and edge inputs ----

/// Random inputs: mostly valid (so every branch of the controllers runs), with edge geometry
/// (exact ties on a quarter grid, ants on borders, inside obstacles, on disturbance centres,
/// head-on to surfaces) and, now and then, one invalid field.
struct Gen(Rng);

/// The arena of most generated frames.
const ARENA: [f32; 4] = [0.0, 0.0, 200.0, 120.0];

impl Gen {
    fn below(&mut self, n: u32) -> u32 {
        self.0.below(n)
    }
    fn one_in(&mut self, n: u32) -> bool {
        self.0.below(n) == 0
    }
    /// Uniform in `[lo, hi)`.
    fn f(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * ((self.0.next() >> 8) as f32 / 16_777_216.0)
    }
    fn s<S: Scalar>(&mut self, lo: f32, hi: f32) -> S {
        S::from_f32(self.f(lo, hi))
    }
    /// Within `r` of `at` on each axis; on a quarter grid a third of the time (exact ties).
    fn near<S: Scalar>(&mut self, at: Vec2<S>, r: f32) -> Vec2<S> {
        let (mut dx, mut dy) = (self.f(-r, r), self.f(-r, r));
        if self.one_in(3) {
            dx = (dx * 4.0).round() / 4.0;
            dy = (dy * 4.0).round() / 4.0;
        }
        at + Vec2::from_f32(dx, dy)
    }
    /// A unit vector: along an axis, diagonal, or at a random angle.
    fn unit<S: Scalar>(&mut self) -> Vec2<S> {
        let sign = |g: &mut Gen| if g.one_in(2) { -1.0 } else { 1.0 };
        match self.below(6) {
            0 => {
                let s = sign(self);
                if self.one_in(2) {
                    Vec2::from_f32(s, 0.0)
                } else {
                    Vec2::from_f32(0.0, s)
                }
            }
            1 => {
                let d = core::f32::consts::FRAC_1_SQRT_2;
                let (a, b) = (sign(self), sign(self));
                Vec2::from_f32(a * d, b * d)
            }
            _ => Vec2::from_angle(self.s(-4.0, 4.0)),
        }
    }
    /// A value no valid input has, or one at the edge of the coordinate limit.
    fn weird<S: Word>(&mut self) -> S {
        let sign = if self.one_in(2) { -1.0 } else { 1.0 };
        match self.below(5) {
            0 => S::from_word(self.0.next()),
            1 => S::from_f32(sign * 20_000.0),
            2 => S::from_f32(sign * 16_384.0),
            3 => S::from_f32(sign * 16_384.01),
            _ => S::from_word(if self.one_in(2) {
                0x7fff_ffff
            } else {
                0x8000_0000
            }),
        }
    }
    fn weird_point<S: Word>(&mut self, p: Vec2<S>) -> Vec2<S> {
        match self.below(3) {
            0 => Vec2::new(self.weird(), p.y),
            1 => Vec2::new(p.x, self.weird()),
            _ => Vec2::new(self.weird(), self.weird()),
        }
    }
    fn label(&mut self) -> Label {
        [Label::Nothing, Label::Food, Label::Nest][self.below(3) as usize]
    }
    fn bounds<S: Word>(&mut self) -> Rect<S> {
        let [a, b, c, d] = ARENA;
        let r = Rect::new(Vec2::from_f32(a, b), Vec2::from_f32(c, d));
        match self.below(40) {
            0 => Rect::new(r.min, Vec2::new(r.min.x, r.max.y)),
            1 => Rect::new(self.weird_point(r.min), r.max),
            2 => Rect::new(
                Vec2::from_f32(-16_384.0, -3.5),
                Vec2::from_f32(16_384.0, 7.25),
            ),
            _ => r,
        }
    }
    fn params<S: Word>(&mut self) -> Checked<AntParams<S>> {
        let default = || AntParams::<S>::default().checked().unwrap();
        if self.below(3) != 0 {
            return default();
        }
        let p_stop = match self.below(5) {
            0 => 0.0,
            1 => 1.0,
            2 => 0.3,
            _ => self.f(0.0, 1.0),
        };
        let p = AntParams {
            speed: self.s(0.05, 4.0),
            dt: self.s(0.25, 2.0),
            theta: self.s(0.01, core::f32::consts::PI),
            p_stop: S::from_f32(p_stop),
            casual_stop_ticks: 1 + self.below(8) as u16,
            collect_ticks: 1 + self.below(20) as u16,
            drop_ticks: 1 + self.below(20) as u16,
            contact_range: self.s(0.2, 6.0),
            avoid_range: self.s(0.2, 6.0),
            collision_range: self.s(0.2, 4.0),
            w0: self.s(0.0, 1.0),
            c: self.s(0.0, 5.0),
            k: self.below(9) as u8,
        };
        p.checked().unwrap_or_else(|_| default())
    }

    /// A state in `bounds`' usual arena, stopped a quarter of the time; one field in twelve
    /// states invalid.
    fn state<S: Word>(&mut self) -> AntState<S> {
        let [a, b, c, d] = ARENA;
        let mut pos: Vec2<S> = Vec2::from_f32(self.f(a + 1.0, c - 1.0), self.f(b + 1.0, d - 1.0));
        if self.one_in(20) {
            // On a border or a corner.
            pos = Vec2::from_f32(
                if self.one_in(2) { a } else { pos.x.to_f32() },
                if self.one_in(2) { d } else { pos.y.to_f32() },
            );
        }
        let label = self.label();
        let nest = self.below(3) as u16;
        let goal = match self.below(6) {
            0..=2 => None,
            3 => Some(self.near(pos, 30.0)),
            4 => Some(self.near(pos, 1.2)),
            _ => Some(pos),
        };
        let follow = if goal.is_some() && self.one_in(2) {
            let winding = match self.below(4) {
                0 => S::from_i32(self.below(9) as i32 - 4),
                _ => self.s(-16.0, 16.0),
            };
            Some(Follow {
                turn: if self.one_in(2) { Turn::Ccw } else { Turn::Cw },
                winding,
            })
        } else {
            None
        };
        let (motion, stop) = if self.one_in(4) {
            let reason = match (label, self.below(2)) {
                (_, 0) => StopReason::Casual,
                (Label::Food, _) => StopReason::DroppingFood,
                _ => StopReason::CollectingFood,
            };
            let place = if reason == StopReason::DroppingFood {
                nest
            } else {
                self.below(4) as u16
            };
            let remaining = [1, 1, 2, 7][self.below(4) as usize];
            let t = StopTimer {
                reason,
                remaining,
                place,
            };
            (MotionState::Stop, Some(t))
        } else {
            let m = [
                MotionState::BasicMovement,
                MotionState::InteractNeighbors,
                MotionState::InteractEnvironment,
            ];
            (m[self.below(3) as usize], None)
        };
        let mut s = AntState {
            pos,
            heading: self.unit(),
            label,
            nest,
            origin: if label == Label::Nest {
                nest
            } else {
                self.below(4) as u16
            },
            arrival: self.near(pos, 40.0),
            goal,
            follow,
            motion,
            stop,
        };
        if self.one_in(12) {
            self.spoil_state(&mut s);
        }
        s
    }

    /// One invalid (or just valid) field of `s`.
    fn spoil_state<S: Word>(&mut self, s: &mut AntState<S>) {
        match self.below(14) {
            0 => s.pos = self.weird_point(s.pos),
            1 => s.arrival = self.weird_point(s.arrival),
            2 => {
                // |heading| around the ±1 % bounds, zero, or weird.
                let k = [1.0099, 1.0101, 0.9901, 0.9899, 0.0][self.below(5) as usize];
                s.heading = s.heading * S::from_f32(k);
            }
            3 => s.heading = self.weird_point(s.heading),
            4 => {
                s.label = Label::Nest;
                s.origin = s.nest + 1;
            }
            5 => s.goal = Some(self.weird_point(s.pos)),
            6 => {
                s.goal = None;
                s.follow = Some(Follow {
                    turn: Turn::Cw,
                    winding: S::ZERO,
                });
            }
            7 => {
                s.goal = Some(s.pos);
                let w = [16.0, -16.0, 16.01, -16.5][self.below(4) as usize];
                s.follow = Some(Follow {
                    turn: Turn::Ccw,
                    winding: S::from_f32(w),
                });
            }
            8 => {
                s.motion = MotionState::Stop;
                s.stop = Some(StopTimer {
                    reason: StopReason::Casual,
                    remaining: 0,
                    place: 0,
                });
            }
            9 => {
                s.label = Label::Food;
                s.motion = MotionState::Stop;
                s.stop = Some(StopTimer {
                    reason: StopReason::CollectingFood,
                    remaining: 3,
                    place: 1,
                });
            }
            10 => {
                s.motion = MotionState::Stop;
                s.stop = Some(StopTimer {
                    reason: StopReason::DroppingFood,
                    remaining: 3,
                    place: s.nest + u16::from(s.label == Label::Food),
                });
            }
            11 => {
                s.motion = MotionState::Stop;
                s.stop = None;
            }
            12 => {
                s.motion = MotionState::BasicMovement;
                s.stop = Some(StopTimer {
                    reason: StopReason::Casual,
                    remaining: 2,
                    place: 0,
                });
            }
            _ => s.pos = Vec2::from_f32(-0.5, 60.0),
        }
    }

    /// A surface `d` in front of `at` (behind it, the ant inside, for `d` < 0).
    fn surface<S: Word>(&mut self, at: Vec2<S>, d: f32) -> Surface<S> {
        let normal: Vec2<S> = self.unit();
        let mut closest = at - normal * S::from_f32(d);
        if self.one_in(4) {
            closest = self.near(closest, 0.5);
        }
        Surface { closest, normal }
    }

    /// One invalid (or just valid) field of a surface.
    fn spoil_surface<S: Word>(&mut self, s: &mut Surface<S>) {
        match self.below(3) {
            0 => s.closest = self.weird_point(s.closest),
            1 => {
                let k = [1.019, 1.021, 0.979, 0.981, 0.0][self.below(5) as usize];
                s.normal = s.normal * S::from_f32(k);
            }
            _ => s.normal = self.weird_point(s.normal),
        }
    }

    /// A plan frame around `s` for ant `agent`: empty, full or in between, neighbours within
    /// about the contact range, objects near; one in twelve with an invalid field.
    fn plan_frame<S: Word>(&mut self, s: &AntState<S>, agent: u32) -> AntPlanFrame<S> {
        let mut f = AntPlanFrame::new(self.bounds());
        let n = match self.below(4) {
            0 => 0,
            1 => N,
            _ => self.below(N as u32 + 1) as usize,
        };
        let mut ids: Vec<u32> = Vec::new();
        while ids.len() < n {
            let id = self.below(1000);
            if id != agent && !ids.contains(&id) {
                ids.push(id);
            }
        }
        for id in ids {
            let label = self.label();
            let nest = if self.one_in(2) {
                s.nest
            } else {
                self.below(3) as u16
            };
            let _ = f.neighbours.push(AntNeighbor {
                id,
                pos: self.near(s.pos, 2.5),
                label,
                nest,
                origin: if label == Label::Nest {
                    nest
                } else {
                    self.below(4) as u16
                },
                arrival: self.near(s.pos, 40.0),
            });
        }
        let m = match self.below(3) {
            0 => 0,
            1 => O,
            _ => self.below(O as u32 + 1) as usize,
        };
        for _ in 0..m {
            let o = match self.below(5) {
                0 | 1 => {
                    let d = self.f(-1.0, 5.0);
                    AntObject::Obstacle(self.surface(s.pos, d))
                }
                2 => AntObject::Disturbance {
                    center: if self.one_in(8) {
                        s.pos
                    } else {
                        self.near(s.pos, 9.0)
                    },
                    radius: self.s(0.5, 10.0),
                },
                3 => AntObject::Food {
                    id: self.below(4) as u16,
                    center: self.near(s.pos, 6.0),
                    radius: self.s(0.5, 5.0),
                },
                _ => AntObject::Nest {
                    id: if self.below(3) == 0 {
                        self.below(3) as u16
                    } else {
                        s.nest
                    },
                    center: self.near(s.pos, 6.0),
                    radius: self.s(0.5, 5.0),
                },
            };
            let _ = f.objects.push(o);
        }
        if self.one_in(12) {
            self.spoil_plan_frame(&mut f, agent);
        }
        f
    }

    fn spoil_plan_frame<S: Word>(&mut self, f: &mut AntPlanFrame<S>, agent: u32) {
        let nn = f.neighbours.len();
        let no = f.objects.len();
        if nn > 0 && self.one_in(2) {
            let i = self.below(nn as u32) as usize;
            let first = f.neighbours[0].id;
            let n = &mut f.neighbours[i];
            match self.below(5) {
                0 => n.pos = self.weird_point(n.pos),
                1 => n.arrival = self.weird_point(n.arrival),
                2 => n.id = agent,
                3 => n.id = first,
                _ => {
                    n.label = Label::Nest;
                    n.origin = n.nest + 1;
                }
            }
        } else if no > 0 {
            let i = self.below(no as u32) as usize;
            let bad: S = match self.below(4) {
                0 => S::ZERO,
                1 => -S::ONE,
                2 => S::from_f32(16_384.5),
                _ => S::EPS,
            };
            match &mut f.objects[i] {
                AntObject::Obstacle(s) => self.spoil_surface(s),
                AntObject::Disturbance { center, radius }
                | AntObject::Food { center, radius, .. }
                | AntObject::Nest { center, radius, .. } => {
                    if self.one_in(2) {
                        *center = self.weird_point(*center);
                    } else {
                        *radius = bad;
                    }
                }
            }
        }
    }

    fn plan_case<S: Word>(&mut self) -> PlanCase<S> {
        let state = self.state();
        let ctx = StepCtx {
            seed: self.0.next(),
            agent: self.below(1000),
            step: self.below(100_000),
        };
        PlanCase {
            frame: self.plan_frame(&state, ctx.agent),
            state,
            params: self.params(),
            ctx,
        }
    }

    /// A resolve frame around a plan: neighbours' predictions near its own (some on it),
    /// obstacle surfaces within about a step (some with the ant behind them); one in twelve
    /// with an invalid field.
    fn resolve_frame<S: Word>(&mut self, plan: &AntPlan<S>) -> AntResolveFrame<S> {
        let mut f = AntResolveFrame::new(self.bounds());
        let n = match self.below(4) {
            0 => 0,
            1 => N,
            _ => self.below(N as u32 + 1) as usize,
        };
        for _ in 0..n {
            let p = if self.one_in(10) {
                plan.predicted
            } else {
                self.near(plan.predicted, 2.0)
            };
            let _ = f.neighbours.push(p);
        }
        let m = match self.below(4) {
            0 => 0,
            1 => SURFACES,
            _ => self.below(SURFACES as u32 + 1) as usize,
        };
        for _ in 0..m {
            let d = if self.one_in(6) {
                self.f(-0.6, 0.05)
            } else {
                self.f(0.0, 1.6)
            };
            let _ = f.obstacles.push(self.surface(plan.state.pos, d));
        }
        if self.one_in(12) {
            if !f.neighbours.is_empty() && self.one_in(2) {
                let i = self.below(f.neighbours.len() as u32) as usize;
                f.neighbours[i] = self.weird_point(f.neighbours[i]);
            } else if !f.obstacles.is_empty() {
                let i = self.below(f.obstacles.len() as u32) as usize;
                let mut s = f.obstacles[i];
                self.spoil_surface(&mut s);
                f.obstacles[i] = s;
            }
        }
        f
    }

    /// A resolve case: the plan of `from` (Rust's, when it plans) or a random state with a
    /// prediction about a step away.
    fn resolve_case<S: Word>(&mut self, from: &PlanCase<S>) -> ResolveCase<S> {
        let mut plan = match from.rust() {
            Ok(p) if self.below(3) != 0 => p,
            _ => {
                let state = self.state();
                AntPlan {
                    predicted: self.near(state.pos, 1.5),
                    state,
                }
            }
        };
        if self.one_in(40) {
            plan.predicted = self.weird_point(plan.predicted);
        }
        ResolveCase {
            frame: self.resolve_frame(&plan),
            plan,
            params: from.params,
        }
    }
}

/// Every label, motion state and stop (every reason, 0 to 2 ticks left, at the ant's nest or
/// elsewhere), with an empty and a full frame each.
fn every_state_kind<S: Word>(g: &mut Gen) -> Vec<PlanCase<S>> {
    let mut out = Vec::new();
    let stops = [
        StopReason::Casual,
        StopReason::CollectingFood,
        StopReason::DroppingFood,
    ];
    for label in [Label::Nothing, Label::Food, Label::Nest] {
        for motion in [
            MotionState::Stop,
            MotionState::BasicMovement,
            MotionState::InteractNeighbors,
            MotionState::InteractEnvironment,
        ] {
            let mut timers = vec![None];
            for reason in stops {
                for remaining in 0..3 {
                    for place in [1, 2] {
                        timers.push(Some(StopTimer {
                            reason,
                            remaining,
                            place,
                        }));
                    }
                }
            }
            for stop in timers {
                for full in [false, true] {
                    let mut c = g.plan_case::<S>();
                    c.state.label = label;
                    c.state.nest = 1;
                    c.state.origin = 1;
                    c.state.motion = motion;
                    c.state.stop = stop;
                    c.state.pos = Vec2::from_f32(100.0, 60.0);
                    c.state.heading = Vec2::from_f32(1.0, 0.0);
                    if !full {
                        c.frame.neighbours.clear();
                        c.frame.objects.clear();
                    }
                    c.frame.bounds = Rect::new(Vec2::zero(), Vec2::from_f32(200.0, 120.0));
                    out.push(c);
                }
            }
        }
    }
    out
}

/// Hand-made geometry: exactly head-on to a wall (a random side), exactly on a disturbance
/// centre (a random direction), on a nest's or food's border, a goal exactly one step away,
/// neighbours tied in distance (the lower id informs).
fn edge_geometry<S: Word>(g: &mut Gen) -> Vec<PlanCase<S>> {
    let mut out = Vec::new();
    for i in 0..64u32 {
        let mut c = g.plan_case::<S>();
        c.state = AntState::at_nest(1, Vec2::from_f32(100.0, 60.0), Vec2::from_f32(1.0, 0.0));
        c.state.label = [Label::Nothing, Label::Food, Label::Nest][(i % 3) as usize];
        c.state.origin = 1;
        c.frame = AntPlanFrame::new(Rect::new(Vec2::zero(), Vec2::from_f32(200.0, 120.0)));
        c.ctx.agent = 7;
        c.ctx.step = i;
        let p = c.state.pos;
        let wall = Surface {
            closest: p + Vec2::from_f32(1.0, 0.0),
            normal: Vec2::from_f32(-1.0, 0.0),
        };
        match i % 8 {
            0 => {
                let _ = c.frame.objects.push(AntObject::Obstacle(wall));
            }
            1 => {
                let _ = c.frame.objects.push(AntObject::Disturbance {
                    center: p,
                    radius: S::from_i32(3),
                });
            }
            2 => {
                let _ = c.frame.objects.push(AntObject::Nest {
                    id: 1,
                    center: p + Vec2::from_f32(2.0, 0.0),
                    radius: S::from_i32(2),
                });
                let _ = c.frame.objects.push(AntObject::Food {
                    id: 3,
                    center: p - Vec2::from_f32(0.0, 1.5),
                    radius: S::from_f32(1.5),
                });
            }
            3 => c.state.goal = Some(p + Vec2::from_f32(0.0, 1.0)),
            4 | 5 => {
                for (k, id) in [9u32, 4, 12, 5].into_iter().enumerate() {
                    let d = if k % 2 == 0 { 1.0 } else { -1.0 };
                    let _ = c.frame.neighbours.push(AntNeighbor {
                        id,
                        pos: p + Vec2::from_f32(d, 0.0),
                        label: Label::Food,
                        nest: 1,
                        origin: id as u16,
                        arrival: Vec2::from_f32(10.0 * k as f32, 5.0),
                    });
                }
            }
            6 => {
                // Going round the wall toward a goal behind it.
                c.state.goal = Some(p + Vec2::from_f32(20.0, 0.5));
                c.state.follow = Some(Follow {
                    turn: if i % 16 < 8 { Turn::Ccw } else { Turn::Cw },
                    winding: S::from_f32(0.5),
                });
                let _ = c.frame.objects.push(AntObject::Obstacle(wall));
            }
            _ => {
                // A goal behind a disturbance's rim.
                c.state.goal = Some(p + Vec2::from_f32(30.0, 0.0));
                let _ = c.frame.objects.push(AntObject::Disturbance {
                    center: p + Vec2::from_f32(4.0, 0.0),
                    radius: S::from_i32(2),
                });
            }
        }
        out.push(c);
    }
    out
}

/// Fixed point: randomised and edge inputs, bit for bit, errors included.
#[test]
fn fx_random_and_edge_inputs_are_bit_for_bit() {
    let t0 = Instant::now();
    let mut g = Gen(Rng::new(0x05ee_da17));
    let mut plans: Vec<PlanCase<Fx>> = (0..30_000).map(|_| g.plan_case()).collect();
    plans.extend(every_state_kind(&mut g));
    plans.extend(edge_geometry(&mut g));
    let mut resolves: Vec<ResolveCase<Fx>> = plans.iter().map(|c| g.resolve_case(c)).collect();
    // Stopped ants of the state kinds, and the same plans with their frames emptied.
    let extra: Vec<ResolveCase<Fx>> = resolves
        .iter()
        .take(5_000)
        .map(|c| ResolveCase {
            frame: AntResolveFrame::new(c.frame.bounds),
            ..c.clone()
        })
        .collect();
    resolves.extend(extra);
    let (gpu, k) = kernels::<Fx>();
    let (p, planned) = compare_plans(gpu, k, &plans);
    assert_identical("random plan", &p, &plans, read_plan::<Fx>);
    let (r, resolved) = compare_resolves(gpu, k, &resolves);
    assert_identical("random resolve", &r, &resolves, read_state::<Fx>);
    let refusals = |cs: &[Result<(), Error>]| {
        let mut kinds: Vec<String> = cs
            .iter()
            .filter_map(|r| r.err())
            .map(|e| match e {
                Error::NonFinite { field, .. }
                | Error::OutOfRange { field, .. }
                | Error::Inconsistent { field, .. } => field.to_string(),
                e => format!("{e:?}"),
            })
            .collect();
        kinds.sort();
        kinds.dedup();
        kinds.len()
    };
    let plan_errs: Vec<Result<(), Error>> = planned.iter().map(|r| r.map(|_| ())).collect();
    let resolve_errs: Vec<Result<(), Error>> = resolved.iter().map(|r| r.map(|_| ())).collect();
    println!(
        "fixed point, random and edge inputs: {} plans ({} refused, {} fields named) and {} \
         resolves ({} refused, {} fields named) identical on the GPU ({:.1} s)",
        p.total,
        p.refused,
        refusals(&plan_errs),
        r.total,
        r.refused,
        refusals(&resolve_errs),
        t0.elapsed().as_secs_f64()
    );
    // Every field a controller names in its errors is refused somewhere.
    assert!(refusals(&plan_errs) >= 19, "{}", refusals(&plan_errs));
    assert!(refusals(&resolve_errs) >= 14, "{}", refusals(&resolve_errs));
}

// ---- the layout ----

/// The kernels compile (naga, as wgpu would) over both scalars.
#[test]
fn the_kernels_are_valid_wgsl() {
    assert_valid_wgsl("plan", modules, PLAN_KERNEL);
    assert_valid_wgsl("resolve", modules, RESOLVE_KERNEL);
}

/// Both sides of the layout have the same word counts and capacities.
#[test]
fn the_layout_constants_are_the_shaders() {
    let wgsl = format!("{}{}", ANT_LAYOUT.source, ANT_FRAME.source);
    assert_constants(&wgsl, WGSL_CONSTANTS, false);
}

/// The status words name every field of `FIELDS` as `shaders/ant_state.wgsl` does, and decode
/// to the error they encode.
#[test]
fn status_words_are_the_shaders() {
    StatusWords {
        wgsl: shaders::ANT_STATE.source,
        file: "ant_state.wgsl",
        prefix: "ANT",
        fields: &FIELDS,
        kinds: 3,
        indices: [None, Some(0), Some(7)],
        status_of,
        status_error,
    }
    .check();
}

/// Every constant the generic modules convert (`s_from_f32(0.25f)`, `s_from_f32(ANT_W_MAX)`):
/// naga reads the literal as Rust does (the same f32 bits), `scalar_fx` converts it as
/// `Fx::from_f32` does, and the named ones are the Rust constants.
#[test]
fn the_shaders_constants_are_rusts() {
    let sources: Vec<&str> = shaders::ALL
        .iter()
        .filter(|m| m.over_scalar)
        .map(|m| m.source)
        .collect();
    let named = |name: &str| -> f32 {
        let decl = format!("const {name}: f32 = ");
        let text = sources
            .iter()
            .find_map(|s| s.split_once(&decl).map(|(_, rest)| rest))
            .unwrap_or_else(|| panic!("no {decl}"));
        let lit = &text[..text.find(';').unwrap()];
        lit.strip_suffix('f').unwrap().parse().unwrap()
    };
    assert_eq!(named("ANT_COORD_LIMIT"), ant::COORD_LIMIT);
    assert_eq!(named("ANT_WINDING_LIMIT"), ant::WINDING_LIMIT);
    assert_eq!(named("ANT_SURFACE_MARGIN"), ant::SURFACE_MARGIN);
    assert_eq!(named("ANT_W_MAX"), ant::W_MAX);
    assert_eq!(named("WANG_MAX_GUIDE"), swarm_core::wang::frame::MAX_GUIDE);
    assert_eq!(
        named("WANG_MAX_CURVATURE"),
        swarm_core::wang::frame::MAX_CURVATURE
    );
    let mut args: Vec<&str> = sources
        .iter()
        .flat_map(|s| s.split("s_from_f32(").skip(1))
        .map(|rest| &rest[..rest.find(')').unwrap()])
        .filter(|a| !a.starts_with("bitcast") && *a != "v")
        .collect();
    args.sort_unstable();
    args.dedup();
    assert!(args.len() >= 13, "{args:?}");
    let value = |a: &str| match a.strip_suffix('f') {
        Some(lit) => lit.parse::<f32>().unwrap(),
        None => named(a),
    };
    let body: String = args
        .iter()
        .enumerate()
        .map(|(k, a)| {
            format!(
                "output[{}u] = bitcast<u32>({a}); output[{}u] = bitcast<u32>(s_from_f32({a}));\n",
                2 * k,
                2 * k + 1
            )
        })
        .collect();
    let kernel = format!(
        "@group(0) @binding(0) var<storage, read> input: array<u32>;
@group(0) @binding(1) var<storage, read_write> output: array<u32>;
@compute @workgroup_size(WORKGROUP)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {{
    if (id.x >= arrayLength(&input)) {{ return; }}
    {body}
}}"
    );
    // Every module over the scalar (the constants are anyone's), with `scalar_fx`.
    let mut uses = vec![&shaders::SCALAR_FX];
    uses.extend(shaders::ALL.iter().filter(|m| m.over_scalar));
    let got = map_words(&test_gpu(), &uses, &kernel, "main", &[0], 1, 2 * args.len()).unwrap();
    for (k, a) in args.iter().enumerate() {
        let v = value(a);
        assert_eq!(got[2 * k], v.to_bits(), "{a}: naga reads another f32");
        assert_eq!(got[2 * k + 1], Fx::from_f32(v).to_word(), "{a}: converted");
    }
}

/// Values through the words and back: in Rust, and through the GPU's unpacking and packing
/// (`ant_*_from_words`, `ant_*_to_words`) over both scalars.
#[test]
fn values_survive_the_layout() {
    fn check<S: TestScalar>(gpu: &Gpu) {
        let mut g = Gen(Rng::new(77));
        let plans: Vec<PlanCase<S>> = (0..2_000).map(|_| g.plan_case()).collect();
        let resolves: Vec<ResolveCase<S>> = plans.iter().map(|c| g.resolve_case(c)).collect();
        let (mut pin, mut rin) = (Vec::new(), Vec::new());
        // In Rust: read, then written again, the same words (words: an f32 NaN is not equal
        // to itself).
        for (p, r) in plans.iter().zip(&resolves) {
            let at = pin.len();
            write_plan_input(&mut pin, &p.state, &p.frame, &p.params, p.ctx);
            let w = &pin[at..];
            assert_eq!(w.len(), PLAN_INPUT_WORDS);
            let mut again = Vec::new();
            write_plan_input(
                &mut again,
                &read_state::<S>(w).unwrap(),
                &read_plan_frame::<S>(&w[STATE_WORDS..]).unwrap(),
                &read_params::<S>(&w[STATE_WORDS + PLAN_FRAME_WORDS..]).unwrap(),
                read_ctx(&w[STATE_WORDS + PLAN_FRAME_WORDS + PARAMS_WORDS..]),
            );
            assert_eq!(again, w);
            let at = rin.len();
            write_resolve_input(&mut rin, &r.plan, &r.frame, &r.params);
            let w = &rin[at..];
            assert_eq!(w.len(), RESOLVE_INPUT_WORDS);
            let mut again = Vec::new();
            write_resolve_input(
                &mut again,
                &read_plan::<S>(w).unwrap(),
                &read_resolve_frame::<S>(&w[PLAN_WORDS..]).unwrap(),
                &read_params::<S>(&w[PLAN_WORDS + RESOLVE_FRAME_WORDS..]).unwrap(),
            );
            assert_eq!(again, w);
        }
        // On the GPU: the state and plan frame of a plan input, the plan and resolve frame of a
        // resolve input, unpacked and packed again.
        let kernel = |in_words: usize, body: &str| {
            format!(
                "@group(0) @binding(0) var<storage, read> input: array<u32>;
@group(0) @binding(1) var<storage, read_write> output: array<u32>;
@compute @workgroup_size(WORKGROUP)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {{
    let i = thread_index(id, groups);
    if (i >= arrayLength(&input) / {in_words}u) {{ return; }}
    let b = i * {in_words}u;
    {body}
}}"
            )
        };
        let plan_body = "var sw: array<u32, ANT_STATE_WORDS>;
    for (var k = 0u; k < ANT_STATE_WORDS; k++) { sw[k] = input[b + k]; }
    var fw: array<u32, ANT_PLAN_FRAME_WORDS>;
    for (var k = 0u; k < ANT_PLAN_FRAME_WORDS; k++) { fw[k] = input[b + ANT_STATE_WORDS + k]; }
    let s = ant_state_to_words(ant_state_from_words(sw));
    let f = ant_plan_frame_to_words(ant_plan_frame_from_words(fw));
    let o = i * (ANT_STATE_WORDS + ANT_PLAN_FRAME_WORDS);
    for (var k = 0u; k < ANT_STATE_WORDS; k++) { output[o + k] = s[k]; }
    for (var k = 0u; k < ANT_PLAN_FRAME_WORDS; k++) { output[o + ANT_STATE_WORDS + k] = f[k]; }";
        let resolve_body = "var pw: array<u32, ANT_PLAN_WORDS>;
    for (var k = 0u; k < ANT_PLAN_WORDS; k++) { pw[k] = input[b + k]; }
    var fw: array<u32, ANT_RESOLVE_FRAME_WORDS>;
    for (var k = 0u; k < ANT_RESOLVE_FRAME_WORDS; k++) { fw[k] = input[b + ANT_PLAN_WORDS + k]; }
    let p = ant_plan_to_words(ant_plan_from_words(pw));
    let f = ant_resolve_frame_to_words(ant_resolve_frame_from_words(fw));
    let o = i * (ANT_PLAN_WORDS + ANT_RESOLVE_FRAME_WORDS);
    for (var k = 0u; k < ANT_PLAN_WORDS; k++) { output[o + k] = p[k]; }
    for (var k = 0u; k < ANT_RESOLVE_FRAME_WORDS; k++) { output[o + ANT_PLAN_WORDS + k] = f[k]; }";
        let uses = modules(scalar_module::<S>());
        for (what, input, in_words, kept, body) in [
            (
                "plan input",
                &pin,
                PLAN_INPUT_WORDS,
                STATE_WORDS + PLAN_FRAME_WORDS,
                plan_body,
            ),
            (
                "resolve input",
                &rin,
                RESOLVE_INPUT_WORDS,
                PLAN_WORDS + RESOLVE_FRAME_WORDS,
                resolve_body,
            ),
        ] {
            let got = map_words(
                gpu,
                &uses,
                &kernel(in_words, body),
                "main",
                input,
                in_words,
                kept,
            )
            .unwrap_or_else(|e| panic!("{what}: {e}"));
            for (i, (g, w)) in got.chunks(kept).zip(input.chunks(in_words)).enumerate() {
                assert_eq!(g, &w[..kept], "{what} #{i} over {:?}", S::KIND);
            }
        }
    }
    let gpu = test_gpu();
    check::<Fx>(&gpu);
    check::<f32>(&gpu);
}
