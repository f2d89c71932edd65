//! The bee controller on the GPU (`shaders/bee_*.wgsl`, lavapipe where there is no GPU) against
//! `swarm_core::bee::step_checked`:
//!
//! * over `Fx`, bit for bit (every output word: the status, the decision and the next state):
//!   every step exchange of real fixed-point simulations of the built-in bee scenarios, and
//!   randomised and edge inputs (empty and full frames, zero and vertical vectors, hovering
//!   bees, obstacles on the bee and at the edge of its field of view, bees at the edge of the
//!   world, invalid inputs that must be refused with the same error); Perlin noise, the curl
//!   potentials and force, the SPH density and repulsion function by function;
//! * over `f32`, measured: the same scenarios simulated in `f32` (and random inputs, NaN and
//!   infinities among them), the share of bit-identical decisions, of decisions with the same
//!   status and avoidance, and the largest difference of the next position, with floors;
//! * the word layout: both sides' constants, and values through the GPU's unpacking and
//!   packing unchanged.
//!
//! `cargo test -p swarm-sim --lib gpu::bee -- --nocapture` prints the figures.

use std::fmt::Debug;
use std::time::Instant;

use rayon::prelude::*;
use swarm_core::bee::{
    self, BeeDecision, BeeNeighbor, BeeParams, BeeState, BeeStepReply, BeeStepRequest,
    ObstacleSense, curl, oscillation, perlin, sph,
};
use swarm_core::{Checked, Error, Fx, Scalar, Vec3};

use super::layout::*;
use super::*;
use crate::bees::{BeeSim, BeeSimFrame, N, P};
use crate::engine::{Engine, apply_due_events};
use crate::gpu::kernel::map_words;
use crate::gpu::shaders::{self, BEE_FRAME, SCALAR_FX};
use crate::gpu::test_gpu;
use crate::gpu::tests::Rng;
use crate::gpu::tests::harness::{
    self, BeeGroups, Measure, PerScalar, StatusWords, TestScalar, assert_constants,
    assert_valid_wgsl, decode_exchange, params_by_id, share, shortened,
};
use crate::scenario::builtin_names;

/// The inputs of one `step_checked`.
#[derive(Clone, Debug)]
struct StepCase<S> {
    state: BeeState<S>,
    frame: BeeSimFrame<S>,
    params: Checked<BeeParams<S>>,
}

impl<S: Word> StepCase<S> {
    fn rust(&self) -> StepResult<S> {
        bee::step_checked(&self.state, &self.frame, &self.params)
    }
}

// ---- comparing ----

/// Where the next position lies in a step's output words (after the status and the decision).
const NEXT_POS: usize = 1 + DECISION_WORDS;
/// Where `avoiding` lies in a step's output words.
const AVOIDING: usize = 1 + 8;

/// How far apart the next positions of two Ok answers are, at most.
#[derive(Debug, Default)]
struct PosDiff {
    /// The largest distance between the next positions of two Ok answers.
    max_pos_diff: f64,
    /// The largest such distance relative to the position's magnitude (at least 1).
    max_pos_rel: f64,
}

impl Measure for PosDiff {
    fn add(&mut self, o: PosDiff) {
        if worse(o.max_pos_diff, self.max_pos_diff) {
            self.max_pos_diff = o.max_pos_diff;
        }
        if worse(o.max_pos_rel, self.max_pos_rel) {
            self.max_pos_rel = o.max_pos_rel;
        }
    }
}

/// How the GPU's answers compare with Rust's (with the same status and, if Ok, the same
/// avoidance as the discrete fields).
type Compared = harness::Compared<PosDiff>;

/// `got` (the GPU's output) against `want` (Rust's), a step's output words each.
fn compared<S: Word>(got: &[u32], want: &[u32]) -> Compared {
    Compared::of(
        got,
        want,
        STEP_OUTPUT_WORDS,
        |g, w| g[AVOIDING] == w[AVOIDING],
        |c, g, w| {
            if g[0] == 0 && w[0] == 0 {
                let pos = |x: &[u32]| {
                    let p = Vec3::<S>::new(
                        S::from_word(x[NEXT_POS]),
                        S::from_word(x[NEXT_POS + 1]),
                        S::from_word(x[NEXT_POS + 2]),
                    );
                    [p.x, p.y, p.z].map(|c| f64::from(c.to_f32()))
                };
                let (a, b) = (pos(g), pos(w));
                let d =
                    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt();
                if worse(d, c.max_pos_diff) {
                    c.max_pos_diff = d;
                }
                let rel = d / b.iter().fold(1.0, |m: f64, x| m.max(x.abs()));
                if worse(rel, c.max_pos_rel) {
                    c.max_pos_rel = rel;
                }
            }
        },
    )
}

/// Whether the distance `d` is larger than `max` (NaN counts as the largest).
fn worse(d: f64, max: f64) -> bool {
    d.is_nan() || d > max
}

/// The step kernel on `cases` against `step_checked`; and Rust's answers.
fn compare<S: TestScalar>(
    gpu: &Gpu,
    k: &BeeKernels,
    cases: &[StepCase<S>],
) -> (Compared, Vec<StepResult<S>>) {
    let mut input = Vec::with_capacity(cases.len() * STEP_INPUT_WORDS);
    let mut want = Vec::with_capacity(cases.len() * STEP_OUTPUT_WORDS);
    let rust: Vec<StepResult<S>> = cases.par_iter().map(StepCase::rust).collect();
    for (c, r) in cases.iter().zip(&rust) {
        write_step_input(&mut input, &c.state, &c.frame, &c.params);
        write_step_result(&mut want, r);
    }
    let got = k.step(gpu, &input).expect("step kernel");
    (compared::<S>(&got, &want), rust)
}

/// Panics unless every decision of `c` is bit for bit Rust's, with the first that is not.
fn assert_identical<S: Word, C: Debug>(what: &str, c: &Compared, cases: &[C]) {
    c.assert_identical(what, cases, |w| format!("{:?}", read_step_result::<S>(w)));
}

/// The test GPU and the bee kernel over `S`, made once for every test.
fn kernels<S: TestScalar>() -> &'static (Gpu, BeeKernels) {
    static KERNELS: PerScalar<(Gpu, BeeKernels)> = PerScalar::new();
    KERNELS.get::<S>(|| {
        let gpu = test_gpu();
        let k = BeeKernels::new::<S>(&gpu).expect("the bee kernel compiles");
        (gpu, k)
    })
}

// ---- real exchanges ----

/// The exchanges of a simulation: every step request of the recorded steps, and the engine's
/// replies.
struct Real<S> {
    cases: Vec<StepCase<S>>,
    replies: Vec<BeeStepReply<S>>,
}

/// The built-in scenario `name` simulated in `S` for `ticks` steps (its events, if any, at the
/// same fraction of the shortened run), every bee's step exchange (`Engine::exchanges`, decoded
/// from postcard) recorded every `every` steps.
fn real<S: TestScalar>(name: &str, ticks: u32, every: u32) -> Real<S> {
    let sc = shortened::<S>(name, ticks);
    let mut sim = BeeSim::from_scenario(&sc, sc.seed).expect("the scenario builds");
    let ids: Vec<u32> = (0..sim.agents() as u32).collect();
    let params: Vec<Checked<BeeParams<S>>> =
        params_by_id::<S, BeeGroups, _>(ids.len(), &sim.groups, |g| (&g.ids, g.params));
    let mut out = Real {
        cases: Vec::new(),
        replies: Vec::new(),
    };
    for t in 0..ticks {
        apply_due_events(&mut sim, &sc);
        Engine::decide(&mut sim, 0).expect("step");
        if t % every == every - 1 {
            for ex in Engine::exchanges(&sim, 0, &ids).expect("step exchanges") {
                let (req, reply): (BeeStepRequest<S>, BeeStepReply<S>) = decode_exchange(&ex);
                out.cases.push(StepCase {
                    state: req.state,
                    frame: req.frame,
                    params: params[ex.agent as usize],
                });
                out.replies.push(reply);
            }
        }
        Engine::publish(&mut sim, 0).expect("publish");
    }
    out
}

/// The bee scenarios of the real exchanges: steps simulated and every how many the exchanges
/// are recorded (about 105,000 decisions; long enough for the swarms to reach the shafts, the
/// nest and the gathering point).
const SCENARIOS: &[(&str, u32, u32)] = &[
    ("bees-fig11-grassland", 45, 1),
    ("bees-fig14-shafts", 400, 2),
    ("bees-fig15-nest", 240, 2),
];

/// What the decisions of `cases` cover, for the report.
fn coverage<S: Word>(cases: &[&StepCase<S>], replies: &[&BeeStepReply<S>]) -> String {
    let frames = |f: &dyn Fn(&BeeSimFrame<S>) -> bool| cases.iter().filter(|c| f(&c.frame)).count();
    let decided =
        |f: &dyn Fn(&BeeDecision<S>) -> bool| replies.iter().filter(|r| f(&r.decision)).count();
    let max = S::from_f32(3.999);
    format!(
        "avoiding {}, obstacle sensed {}, tuned by eq. 5 {}; full neighbour lists {}, with \
         neighbours {}, with target particles {} (full {}), with a goal {}; at the speed limit {}",
        decided(&|d| d.avoiding),
        frames(&|f| f.obstacle.is_some()),
        replies
            .iter()
            .filter(|r| r.state.u0 != Vec3::zero())
            .count(),
        frames(&|f| f.neighbours.len() == N),
        frames(&|f| !f.neighbours.is_empty()),
        frames(&|f| !f.targets.is_empty()),
        frames(&|f| f.targets.len() == P),
        frames(&|f| f.goal.is_some()),
        decided(&|d| d.velocity.length() > max),
    )
}

/// Every scenario of [`SCENARIOS`] simulated in `S`, its exchanges on the GPU against Rust
/// (whose answers must be the engine's replies); the comparisons and, for the report, what the
/// decisions cover.
fn real_runs<S: TestScalar>(check: impl Fn(&str, &Compared, &Real<S>)) -> (Compared, String) {
    let (gpu, k) = kernels::<S>();
    let runs: Vec<Real<S>> = SCENARIOS
        .par_iter()
        .map(|&(name, ticks, every)| real::<S>(name, ticks, every))
        .collect();
    let mut all = Compared::default();
    for (&(name, _, _), run) in SCENARIOS.iter().zip(&runs) {
        let (c, rust) = compare(gpu, k, &run.cases);
        for (rust, reply) in rust.iter().zip(&run.replies) {
            assert_eq!(
                rust.as_ref(),
                Ok(&(reply.decision, reply.state)),
                "{name}: Rust's step is the engine's"
            );
        }
        check(name, &c, run);
        all.add(c);
    }
    let cases: Vec<&StepCase<S>> = runs.iter().flat_map(|r| &r.cases).collect();
    let replies: Vec<&BeeStepReply<S>> = runs.iter().flat_map(|r| &r.replies).collect();
    (all, coverage(&cases, &replies))
}

/// The real exchanges cover every built-in bee scenario.
#[test]
fn every_bee_scenario_is_simulated() {
    let bees: Vec<&str> = builtin_names()
        .iter()
        .copied()
        .filter(|n| n.starts_with("bees-"))
        .collect();
    assert!(!bees.is_empty());
    for name in bees {
        assert!(
            SCENARIOS.iter().any(|s| s.0 == name),
            "{name} is not in SCENARIOS"
        );
    }
}

/// Fixed point: every step exchange of real simulations, bit for bit.
#[test]
fn fx_real_exchanges_are_bit_for_bit() {
    let t0 = Instant::now();
    let (c, covered) = real_runs::<Fx>(|name, c, run| {
        assert_identical::<Fx, _>(name, c, &run.cases);
    });
    println!(
        "fixed point, real exchanges of {} scenarios: {} step decisions identical on the GPU \
         ({:.1} s)\n  {covered}",
        SCENARIOS.len(),
        c.identical,
        t0.elapsed().as_secs_f64(),
    );
    assert!(c.total >= 100_000, "{}", c.total);
    assert_eq!(c.identical, c.total);
}

/// The least share of `f32` decisions (real exchanges) that must be bit-identical.
const F32_IDENTICAL_FLOOR: f64 = 0.2;
/// The least share of `f32` decisions with the same status and avoidance.
const F32_DISCRETE_FLOOR: f64 = 0.999;
/// The largest distance between the GPU's and Rust's next positions in `f32` (units), in the
/// scenarios (a world of tens of units).
const F32_MAX_POS_DIFF: f64 = 1e-4;
/// The largest such distance relative to the position's magnitude (random inputs reach the
/// input limit, where an f32 is 1/1024 apart).
const F32_MAX_POS_REL: f64 = 1e-6;

/// `f32`: the same scenarios simulated in `f32`, measured (docs/gpu.md: not promised).
#[test]
fn f32_real_exchanges_are_measured() {
    let t0 = Instant::now();
    let (c, _) = real_runs::<f32>(|_, _, _| {});
    let pct = |n, c: &Compared| 100.0 * share(n, c.total);
    println!(
        "f32 on {}: {} step decisions, {:.2} % bit-identical, {:.3} % the same status and \
         avoidance, next positions at most {:.2e} apart ({:.1} s)",
        kernels::<f32>().0.info().name,
        c.total,
        pct(c.identical, &c),
        pct(c.discrete, &c),
        c.measured.max_pos_diff,
        t0.elapsed().as_secs_f64(),
    );
    assert!(c.total >= 100_000);
    // Random and edge inputs (NaN and infinities among the invalid ones): the same refusals.
    let mut g = Gen(Rng::new(0xf32));
    let cases: Vec<StepCase<f32>> = (0..10_000).map(|_| g.case()).collect();
    let (gpu, k) = kernels::<f32>();
    let (r, _) = compare(gpu, k, &cases);
    println!(
        "f32, random and edge inputs: {} decisions, {:.2} % bit-identical, {:.3} % the same \
         status and avoidance ({} refused), next positions at most {:.2e} apart ({:.2e} of \
         their magnitude)",
        r.total,
        pct(r.identical, &r),
        pct(r.discrete, &r),
        r.refused,
        r.measured.max_pos_diff,
        r.measured.max_pos_rel,
    );
    assert!(share(c.identical, c.total) >= F32_IDENTICAL_FLOOR, "{c:?}");
    assert!(c.measured.max_pos_diff <= F32_MAX_POS_DIFF, "{c:?}");
    for (what, c) in [("real", &c), ("random", &r)] {
        assert!(
            share(c.discrete, c.total) >= F32_DISCRETE_FLOOR,
            "{what}: {c:?}"
        );
        assert!(c.measured.max_pos_rel <= F32_MAX_POS_REL, "{what}: {c:?}");
    }
}

// ---- randomised and edge inputs ----

/// Random inputs: mostly valid (so every branch of the controller runs), with edge geometry
/// (zero and vertical vectors, coincident positions, obstacles on the bee, at the edge of the
/// field of view and behind it, bees at the edge of the world) and, now and then, one invalid
/// field.
struct Gen(Rng);

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
    fn v<S: Scalar>(&mut self, r: f32) -> Vec3<S> {
        Vec3::from_f32(self.f(-r, r), self.f(-r, r), self.f(-r, r))
    }
    /// Within `r` of `at` on each axis; on a quarter grid a third of the time (exact ties).
    fn near<S: Scalar>(&mut self, at: Vec3<S>, r: f32) -> Vec3<S> {
        let mut d = [self.f(-r, r), self.f(-r, r), self.f(-r, r)];
        if self.one_in(3) {
            d = d.map(|x| (x * 4.0).round() / 4.0);
        }
        at + Vec3::from_f32(d[0], d[1], d[2])
    }
    /// A unit vector: along an axis, diagonal, or at random.
    fn unit<S: Scalar>(&mut self) -> Vec3<S> {
        let sign = |g: &mut Gen| if g.one_in(2) { -1.0 } else { 1.0 };
        match self.below(5) {
            0 => {
                let s = sign(self);
                match self.below(3) {
                    0 => Vec3::from_f32(s, 0.0, 0.0),
                    1 => Vec3::from_f32(0.0, s, 0.0),
                    _ => Vec3::from_f32(0.0, 0.0, s),
                }
            }
            1 => {
                let d = core::f32::consts::FRAC_1_SQRT_2;
                let (a, b) = (sign(self), sign(self));
                Vec3::from_f32(a * d, 0.0, b * d)
            }
            _ => loop {
                let v: Vec3<f32> = self.v(1.0);
                let l = v.length();
                if l > 0.1 {
                    break Vec3::from_f32(v.x / l, v.y / l, v.z / l);
                }
            },
        }
    }
    /// A value no valid input has, or one at the edge of the input limit.
    fn weird<S: Word>(&mut self) -> S {
        let sign = if self.one_in(2) { -1.0 } else { 1.0 };
        match self.below(7) {
            0 => S::from_word(self.0.next()),
            1 => S::from_f32(sign * 20_000.0),
            2 => S::from_f32(sign * 16_000.0),
            3 => S::from_f32(sign * 16_000.01),
            4 => S::from_word(f32::NAN.to_bits()),
            5 => S::from_word(f32::INFINITY.to_bits() | ((sign < 0.0) as u32) << 31),
            _ => S::from_word(if self.one_in(2) {
                0x7fff_ffff
            } else {
                0x8000_0000
            }),
        }
    }
    fn weird_vec<S: Word>(&mut self, v: Vec3<S>) -> Vec3<S> {
        match self.below(4) {
            0 => Vec3::new(self.weird(), v.y, v.z),
            1 => Vec3::new(v.x, self.weird(), v.z),
            2 => Vec3::new(v.x, v.y, self.weird()),
            _ => Vec3::new(self.weird(), self.weird(), self.weird()),
        }
    }
    fn params<S: Word>(&mut self) -> Checked<BeeParams<S>> {
        let preset = match self.below(3) {
            0 => BeeParams::<S>::default(),
            1 => BeeParams::grassland(),
            _ => BeeParams::around_nest(),
        };
        if self.below(4) != 0 {
            return preset.checked().unwrap();
        }
        let dt = self.s(0.01, 0.2);
        let p = BeeParams {
            h: self.s(0.5, 6.0),
            grid_edge: self.s(0.5, 6.0),
            kappa1: self.s(0.0, 3.0),
            kappa2: self.s(0.0, 6.0),
            kappa3: self.s(0.0, 3.0),
            epsilon: self.s(0.0, 3.0),
            mass: self.s(0.2, 3.0),
            gravity: self.s(0.0, 12.0),
            air_density: self.s(0.0, 2.0),
            wing_area: self.s(0.0, 0.2),
            radius: self.s(0.0, 0.6),
            d0: self.s(0.5, 4.0),
            dt,
            stiffness: self.s(0.0, 300.0),
            rest_density: self.s(0.0, 0.05),
            max_speed: self.s(0.5, 8.0),
            damping: self.s::<S>(0.0, 1.0) / dt,
        };
        p.checked().unwrap_or_else(|_| preset.checked().unwrap())
    }

    /// A state: a bee in the world (now and then at its edge), flying, hovering or still, now
    /// and then straight up; one field in twelve states invalid.
    fn state<S: Word>(&mut self) -> BeeState<S> {
        let mut pos: Vec3<S> =
            Vec3::from_f32(self.f(-5.0, 65.0), self.f(0.0, 30.0), self.f(-5.0, 65.0));
        if self.one_in(30) {
            // At the edge of the representable world, maybe flying out of it.
            let l = 16_000.0 - self.f(0.0, 0.2);
            pos.x = S::from_f32(if self.one_in(2) { l } else { -l });
        }
        let vel = match self.below(10) {
            0 => Vec3::zero(),
            1 => self.v(0.0009),
            2 => Vec3::from_f32(0.0, self.f(-3.0, 3.0), 0.0),
            3 => self.v(9.0),
            _ => self.v(3.0),
        };
        let forward = match self.below(6) {
            0 => Vec3::zero(),
            1 => self.v(2.0),
            2 => Vec3::from_f32(0.0, 1.0, 0.0),
            _ => self.unit(),
        };
        let u0 = if self.one_in(2) {
            Vec3::zero()
        } else {
            self.v(4.0)
        };
        let mut s = BeeState {
            pos,
            vel,
            forward,
            density: self.s(0.0, 1.0),
            avoiding: self.one_in(3),
            u0,
            roll: self.s(-0.8, 0.8),
            pitch: self.s(0.0, 0.4),
        };
        if self.one_in(12) {
            self.spoil_state(&mut s);
        }
        s
    }

    /// One invalid (or just valid) field of `s`.
    fn spoil_state<S: Word>(&mut self, s: &mut BeeState<S>) {
        match self.below(8) {
            0 => s.pos = self.weird_vec(s.pos),
            1 => s.vel = self.weird_vec(s.vel),
            2 => s.forward = self.weird_vec(s.forward),
            3 => {
                s.density = if self.one_in(2) {
                    self.weird()
                } else {
                    -S::EPS
                }
            }
            4 => s.u0 = self.weird_vec(s.u0),
            5 => s.roll = self.weird(),
            6 => s.pitch = self.weird(),
            _ => s.density = S::from_f32(16_000.0),
        }
    }

    /// A frame around `s`: empty, full or in between; neighbours and particles near the bee
    /// (some on it), a goal or none, an obstacle or none; one in twelve with an invalid field.
    fn frame<S: Word>(&mut self, s: &BeeState<S>) -> BeeSimFrame<S> {
        let t = match self.below(8) {
            0 => 0.0,
            1 => 16_000.0,
            2 => self.f(15_990.0, 16_000.0),
            3 => (self.below(300) as f32) * 71.944 / 4.0,
            _ => self.f(0.0, 16_000.0),
        };
        let mut f = BeeSimFrame::new(S::from_f32(t));
        let count = |g: &mut Gen, cap: usize| match g.below(4) {
            0 => 0,
            1 => cap,
            _ => g.below(cap as u32 + 1) as usize,
        };
        for _ in 0..count(self, N) {
            let pos = if self.one_in(12) {
                s.pos
            } else {
                self.near(s.pos, 3.5)
            };
            let _ = f.neighbours.push(BeeNeighbor {
                pos,
                vel: self.v(3.0),
                density: if self.one_in(6) {
                    S::ZERO
                } else {
                    self.s(0.0, 0.6)
                },
            });
        }
        for _ in 0..count(self, P) {
            let p = if self.one_in(12) {
                s.pos
            } else {
                self.near(s.pos, 3.5)
            };
            let _ = f.targets.push(p);
        }
        f.goal = match self.below(6) {
            0 | 1 => None,
            2 => Some(s.pos),
            3 => Some(s.pos + Vec3::from_f32(0.0, self.f(-9.0, 9.0), 0.0)),
            _ => Some(self.near(s.pos, 40.0)),
        };
        f.obstacle = match self.below(3) {
            0 => None,
            _ => Some(self.obstacle(s)),
        };
        if self.one_in(12) {
            self.spoil_frame(&mut f);
        }
        f
    }

    /// An obstacle point and normal around `s`: closer or farther than d0, in front, beside or
    /// behind, on the edge of the field of view, on the bee; a unit normal (±1 %).
    fn obstacle<S: Word>(&mut self, s: &BeeState<S>) -> ObstacleSense<S> {
        let dir: Vec3<S> = match self.below(5) {
            0 => {
                // On the edge of a ±45° field of view around the velocity (or +x).
                let o = s.vel.normalized().unwrap_or(Vec3::from_f32(1.0, 0.0, 0.0));
                let side = Vec3::<S>::up().cross(o).normalized().unwrap_or(Vec3::up());
                let k = S::from_f32(core::f32::consts::FRAC_1_SQRT_2);
                o * k + side * k
            }
            1 => s.vel.normalized().unwrap_or(Vec3::from_f32(1.0, 0.0, 0.0)),
            _ => self.unit(),
        };
        let d = match self.below(6) {
            0 => 0.0,
            1 => 2.0,
            _ => self.f(0.0, 4.5),
        };
        let point = s.pos + dir * S::from_f32(d);
        let normal = match self.below(6) {
            0 => -dir,
            1 => self.unit(),
            2 => -dir * S::from_f32([0.99, 1.01, 0.995, 1.005][self.below(4) as usize]),
            _ => {
                let n: Vec3<S> = self.unit();
                if n.dot(dir) > S::ZERO { -n } else { n }
            }
        };
        let normal = if normal.length() < S::from_f32(0.5) {
            Vec3::up()
        } else {
            normal
        };
        ObstacleSense { point, normal }
    }

    /// One invalid (or just valid) field of a frame.
    fn spoil_frame<S: Word>(&mut self, f: &mut BeeSimFrame<S>) {
        match self.below(6) {
            0 => {
                f.t = if self.one_in(2) {
                    self.weird()
                } else {
                    -S::EPS
                }
            }
            1 if !f.neighbours.is_empty() => {
                let i = self.below(f.neighbours.len() as u32) as usize;
                let n = &mut f.neighbours[i];
                match self.below(4) {
                    0 => n.pos = Gen::weird_vec(self, n.pos),
                    1 => n.vel = Gen::weird_vec(self, n.vel),
                    2 => n.density = -S::EPS,
                    _ => n.density = self.weird(),
                }
            }
            2 if !f.targets.is_empty() => {
                let i = self.below(f.targets.len() as u32) as usize;
                f.targets[i] = self.weird_vec(f.targets[i]);
            }
            3 => f.goal = Some(self.weird_vec(f.goal.unwrap_or(Vec3::zero()))),
            4 if f.obstacle.is_some() => {
                let mut o = f.obstacle.unwrap();
                match self.below(3) {
                    0 => o.point = self.weird_vec(o.point),
                    1 => o.normal = self.weird_vec(o.normal),
                    _ => {
                        let k = [0.989, 1.011, 0.0, 2.0][self.below(4) as usize];
                        o.normal = o.normal * S::from_f32(k);
                    }
                }
                f.obstacle = Some(o);
            }
            _ => f.t = S::from_f32(-1.0),
        }
    }

    fn case<S: Word>(&mut self) -> StepCase<S> {
        let state = self.state();
        StepCase {
            frame: self.frame(&state),
            state,
            params: self.params(),
        }
    }
}

/// Sets one field of a state or frame to a value.
type Breaker<S> = fn(&mut BeeState<S>, &mut BeeSimFrame<S>, S);

/// Hand-made inputs: a still bee with nothing around, a full frame on the bee itself, a hovering
/// bee facing its goal or with none, a bee flying straight up, obstacles on the bee, dead ahead
/// and exactly beside it, a bee at the edge of the world flying out, times 0 and the limit;
/// then every field refused (each kind of error the field can have).
fn edge_cases<S: Word>(g: &mut Gen) -> Vec<StepCase<S>> {
    let p = || BeeParams::<S>::default().checked().unwrap();
    let at: Vec3<S> = Vec3::from_f32(30.0, 12.0, 30.0);
    let still = BeeState::new(at, Vec3::zero());
    let mut out = Vec::new();
    let mut push = |state: BeeState<S>, frame: BeeSimFrame<S>| {
        out.push(StepCase {
            state,
            frame,
            params: p(),
        })
    };
    let empty = |t: f32| BeeSimFrame::<S>::new(S::from_f32(t));
    push(still, empty(0.0));
    push(BeeState::new(Vec3::zero(), Vec3::zero()), empty(16_000.0));
    let mut zero = still;
    zero.forward = Vec3::zero();
    push(zero, empty(3.0));
    let mut f = empty(3.0);
    f.goal = Some(at + Vec3::from_f32(0.0, 0.0, -5.0));
    push(zero, f.clone());
    f.goal = Some(at);
    push(zero, f.clone());
    f.goal = Some(at + Vec3::from_f32(0.0, 5.0, 0.0));
    push(zero, f.clone());
    let up = BeeState::new(at, Vec3::from_f32(0.0, 2.0, 0.0));
    push(up, f.clone());
    // Full lists, every entry on the bee.
    let mut full = empty(7.5);
    for _ in 0..N {
        let _ = full.neighbours.push(BeeNeighbor {
            pos: at,
            vel: Vec3::zero(),
            density: S::ZERO,
        });
    }
    for _ in 0..P {
        let _ = full.targets.push(at);
    }
    push(still, full.clone());
    // Full lists around the bee, capsules just touching.
    let mut ring = empty(7.5);
    for k in 0..N {
        let a = k as f32 * core::f32::consts::TAU / N as f32;
        let _ = ring.neighbours.push(BeeNeighbor {
            pos: at + Vec3::from_f32(0.5 * a.cos(), 0.0, 0.5 * a.sin()),
            vel: Vec3::from_f32(1.0, 0.0, 0.0),
            density: S::from_f32(0.1),
        });
        let _ = ring
            .targets
            .push(at + Vec3::from_f32(0.0, 1.0 * a.cos(), 1.0 * a.sin()));
    }
    push(still, ring);
    // Obstacles: on the bee, dead ahead, beside (90°), at 45°, at d0.
    let flying = BeeState::new(at, Vec3::from_f32(1.0, 0.0, 0.0));
    for (dx, dz, nx, nz) in [
        (0.0, 0.0, -1.0, 0.0),
        (1.0, 0.0, -1.0, 0.0),
        (0.0, -1.0, 0.0, 1.0),
        (0.0, 1.0, 0.0, -1.0),
        (1.0, 1.0, 0.0, -1.0),
        (1.0, -1.0, 0.0, 1.0),
        (2.0, 0.0, -1.0, 0.0),
        (-1.0, 0.0, 1.0, 0.0),
    ] {
        for avoiding in [false, true] {
            let mut f = empty(1.0);
            f.obstacle = Some(ObstacleSense {
                point: at + Vec3::from_f32(dx, 0.0, dz),
                normal: Vec3::from_f32(nx, 0.0, nz),
            });
            push(BeeState { avoiding, ..flying }, f);
        }
    }
    // At the edge of the world, flying out.
    let edge = BeeState::new(
        Vec3::from_f32(16_000.0, -16_000.0, 15_999.99),
        Vec3::from_f32(4.0, -4.0, 4.0),
    );
    push(edge, empty(2.0));
    // Every field refused.
    let nan = S::from_word(f32::NAN.to_bits());
    let big = S::from_f32(16_000.5);
    let negative = -S::EPS;
    let mut base = full.clone();
    base.goal = Some(at);
    base.obstacle = Some(ObstacleSense {
        point: at,
        normal: Vec3::up(),
    });
    let breakers: Vec<Breaker<S>> = vec![
        |s, _, v| s.pos.y = v,
        |s, _, v| s.vel.z = v,
        |s, _, v| s.forward.x = v,
        |s, _, v| s.density = v,
        |s, _, v| s.u0.y = v,
        |s, _, v| s.roll = v,
        |s, _, v| s.pitch = v,
        |_, f, v| f.t = v,
        |_, f, v| f.neighbours[N - 1].pos.x = v,
        |_, f, v| f.neighbours[3].vel.y = v,
        |_, f, v| f.neighbours[5].density = v,
        |_, f, v| f.targets[P - 1].z = v,
        |_, f, v| f.goal.as_mut().unwrap().x = v,
        |_, f, v| f.obstacle.as_mut().unwrap().point.z = v,
        |_, f, v| f.obstacle.as_mut().unwrap().normal.x = v,
    ];
    for b in breakers {
        for v in [nan, big, -big, negative, g.weird()] {
            let (mut s, mut f) = (still, base.clone());
            b(&mut s, &mut f, v);
            push(s, f);
        }
    }
    for k in [0.98, 0.989, 0.99, 1.01, 1.011, 0.0] {
        let mut f = base.clone();
        f.obstacle.as_mut().unwrap().normal = Vec3::from_f32(0.0, k, 0.0);
        push(still, f);
    }
    out
}

/// The fields a set of results refuses, deduplicated.
fn refused_fields<S>(results: &[StepResult<S>]) -> Vec<&'static str> {
    let mut fields: Vec<&'static str> = results
        .iter()
        .filter_map(|r| r.as_ref().err())
        .filter_map(|e| match *e {
            Error::NonFinite { field, .. } | Error::OutOfRange { field, .. } => Some(field),
            _ => None,
        })
        .collect();
    fields.sort_unstable();
    fields.dedup();
    fields
}

/// Fixed point: randomised and edge inputs, bit for bit, errors included.
#[test]
fn fx_random_and_edge_inputs_are_bit_for_bit() {
    let t0 = Instant::now();
    let mut g = Gen(Rng::new(0x00be_e5ed));
    let mut cases: Vec<StepCase<Fx>> = (0..20_000).map(|_| g.case()).collect();
    cases.extend(edge_cases(&mut g));
    let (gpu, k) = kernels::<Fx>();
    let (c, rust) = compare(gpu, k, &cases);
    assert_identical::<Fx, _>("random step", &c, &cases);
    let fields = refused_fields(&rust);
    let avoiding = rust
        .iter()
        .filter(|r| r.as_ref().is_ok_and(|(d, _)| d.avoiding))
        .count();
    println!(
        "fixed point, random and edge inputs: {} steps ({} refused, {} fields named, {} \
         avoiding) identical on the GPU ({:.1} s)",
        c.total,
        c.refused,
        fields.len(),
        avoiding,
        t0.elapsed().as_secs_f64()
    );
    // Every input field is refused somewhere (the output checks never fire in fixed point).
    assert_eq!(fields.len(), 15, "{fields:?}");
    assert!(avoiding > 1_000, "{avoiding}");
}

// ---- Perlin noise, curl, SPH: function by function ----

/// `bee_perlin`, `bee_potential` and `bee_curl_force` over `Fx` against `perlin::perlin`,
/// `curl::potential` and `curl::curl_force`: points across cells, on lattice corners and
/// edges, negative, and far out (saturating `r/L`), with the edge lengths and magnitudes of
/// Table I and others.
#[test]
fn noise_and_curl_are_bit_for_bit() {
    let mut g = Gen(Rng::new(0x0c0f));
    let mut input = Vec::new();
    let mut want = Vec::new();
    let mut points: Vec<(Vec3<Fx>, Fx, Fx, u8)> = Vec::new();
    for i in 0..8_000u32 {
        let p: Vec3<Fx> = match i % 5 {
            0 => g.near(Vec3::zero(), 8.0),
            1 => Vec3::from_f32(
                g.below(17) as f32 - 8.0,
                g.below(17) as f32 / 2.0,
                -(g.below(9) as f32),
            ),
            2 => g.v(16_000.0),
            _ => g.v(70.0),
        };
        let (l, e) = match g.below(4) {
            0 => (Fx::from_f32(2.7), Fx::from_f32(1.7)),
            1 => (Fx::from_f32(2.2), Fx::from_f32(2.0)),
            2 => (g.s(0.01, 0.2), g.s(0.0, 3.0)),
            _ => (g.s(0.2, 8.0), g.s(0.0, 5.0)),
        };
        points.push((p, l, e, g.below(256) as u8));
    }
    for &(p, l, e, seed) in &points {
        input.extend([p.x, p.y, p.z, l, e].map(Word::to_word));
        input.push(u32::from(seed));
        let n = perlin::perlin(p, seed);
        want.extend([n.value, n.grad.x, n.grad.y, n.grad.z].map(Word::to_word));
        for n in curl::potential(p, l, e) {
            want.extend([n.value, n.grad.x, n.grad.y, n.grad.z].map(Word::to_word));
        }
        let c = curl::curl_force(p, l, e);
        want.extend([c.x, c.y, c.z].map(Word::to_word));
    }
    let kernel = "
@group(0) @binding(0) var<storage, read> input: array<u32>;
@group(0) @binding(1) var<storage, read_write> output: array<u32>;
fn put(o: u32, n: BeeNoise) {
    output[o] = s_to_word(n.value);
    output[o + 1u] = s_to_word(n.grad.x);
    output[o + 2u] = s_to_word(n.grad.y);
    output[o + 3u] = s_to_word(n.grad.z);
}
@compute @workgroup_size(WORKGROUP)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(id, groups);
    if (i >= arrayLength(&input) / 6u) { return; }
    let b = i * 6u;
    let p = vec3<S>(s_from_word(input[b]), s_from_word(input[b + 1u]), s_from_word(input[b + 2u]));
    let l = s_from_word(input[b + 3u]);
    let e = s_from_word(input[b + 4u]);
    let o = i * 19u;
    put(o, bee_perlin(p, input[b + 5u]));
    let psi = bee_potential(p, l, e);
    put(o + 4u, psi.x);
    put(o + 8u, psi.y);
    put(o + 12u, psi.z);
    let c = bee_curl_force(p, l, e);
    output[o + 16u] = s_to_word(c.x);
    output[o + 17u] = s_to_word(c.y);
    output[o + 18u] = s_to_word(c.z);
}";
    let uses = [&SCALAR_FX, &shaders::BEE_CURL];
    let got = map_words(&test_gpu(), &uses, kernel, "main", &input, 6, 19).unwrap();
    for (i, (g, w)) in got.chunks(19).zip(want.chunks(19)).enumerate() {
        assert_eq!(g, w, "point #{i}: {:?}", points[i]);
    }
}

/// `bee_density` and `bee_repulsion` over `Fx` against `sph::density` and `sph::repulsion`
/// (the step uses `interact_with`, the same bits; these are the module's other entry points).
#[test]
fn sph_density_and_repulsion_are_bit_for_bit() {
    let mut g = Gen(Rng::new(0x5b4));
    let cases: Vec<StepCase<Fx>> = (0..4_000).map(|_| g.case()).collect();
    let mut input = Vec::new();
    let mut want = Vec::new();
    for c in &cases {
        // The density to repel with: the state's (any valid value).
        write_step_input(&mut input, &c.state, &c.frame, &c.params);
        let rho = sph::density(
            c.state.pos,
            &c.frame.neighbours,
            &c.frame.targets,
            &c.params,
        );
        let f = sph::repulsion(
            c.state.pos,
            c.state.density,
            &c.frame.neighbours,
            &c.frame.targets,
            &c.params,
        );
        let (rho_i, force) = sph::interact(
            c.state.pos,
            &c.frame.neighbours,
            &c.frame.targets,
            &c.params,
        );
        want.extend([rho, f.x, f.y, f.z, rho_i, force.x, force.y, force.z].map(Word::to_word));
    }
    let kernel = "
@group(0) @binding(0) var<storage, read> input: array<u32>;
@group(0) @binding(1) var<storage, read_write> output: array<u32>;
const IN_WORDS: u32 = BEE_STATE_WORDS + BEE_FRAME_WORDS + BEE_PARAMS_WORDS;
@compute @workgroup_size(WORKGROUP)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(id, groups);
    if (i >= arrayLength(&input) / IN_WORDS) { return; }
    let b = i * IN_WORDS;
    var sw: array<u32, BEE_STATE_WORDS>;
    for (var k = 0u; k < BEE_STATE_WORDS; k++) { sw[k] = input[b + k]; }
    var fw: array<u32, BEE_FRAME_WORDS>;
    for (var k = 0u; k < BEE_FRAME_WORDS; k++) { fw[k] = input[b + BEE_STATE_WORDS + k]; }
    var pw: array<u32, BEE_PARAMS_WORDS>;
    for (var k = 0u; k < BEE_PARAMS_WORDS; k++) {
        pw[k] = input[b + BEE_STATE_WORDS + BEE_FRAME_WORDS + k];
    }
    let s = bee_state_from_words(sw);
    var f = bee_frame_from_words(&fw);
    let p = bee_params_from_words(pw);
    let rho = bee_density(s.pos, &f, p);
    let r = bee_repulsion(s.pos, s.density, &f, p);
    let both = bee_interact(s.pos, &f, p);
    let o = i * 8u;
    output[o] = s_to_word(rho);
    output[o + 1u] = s_to_word(r.x);
    output[o + 2u] = s_to_word(r.y);
    output[o + 3u] = s_to_word(r.z);
    output[o + 4u] = s_to_word(both.rho);
    output[o + 5u] = s_to_word(both.force.x);
    output[o + 6u] = s_to_word(both.force.y);
    output[o + 7u] = s_to_word(both.force.z);
}";
    let uses = modules(&SCALAR_FX);
    let got = map_words(
        &test_gpu(),
        &uses,
        kernel,
        "main",
        &input,
        STEP_INPUT_WORDS,
        8,
    )
    .unwrap();
    for (i, (g, w)) in got.chunks(8).zip(want.chunks(8)).enumerate() {
        assert_eq!(g, w, "case #{i}: {:?}", cases[i]);
    }
}

// ---- the layout ----

/// The kernel compiles (naga, as wgpu would) over both scalars.
#[test]
fn the_kernel_is_valid_wgsl() {
    assert_valid_wgsl("bee step", modules, STEP_KERNEL);
}

/// Both sides of the layout have the same word counts and capacities.
#[test]
fn the_layout_constants_are_the_shaders() {
    let wgsl = format!("{}{}", BEE_LAYOUT.source, BEE_FRAME.source);
    assert_constants(&wgsl, WGSL_CONSTANTS, false);
}

/// The status words name every field of `FIELDS` as `shaders/bee_frame.wgsl` does, and decode
/// to the error they encode.
#[test]
fn status_words_are_the_shaders() {
    StatusWords {
        wgsl: BEE_FRAME.source,
        file: "bee_frame.wgsl",
        prefix: "BEE",
        fields: &FIELDS,
        kinds: 2,
        indices: [None, Some(0), Some(15)],
        status_of,
        status_error,
    }
    .check();
    assert_eq!(
        status_of(&Error::Inconsistent {
            field: "state.pos",
            index: None
        }),
        u32::MAX
    );
}

/// The named `f32` constants of the bee modules are the Rust ones (their conversion by
/// `s_from_f32` is checked for every module by the ant tests' `the_shaders_constants_are_rusts`).
#[test]
fn the_shaders_named_constants_are_rusts() {
    let sources: String = shaders::ALL
        .iter()
        .filter(|m| m.name.starts_with("bee_"))
        .map(|m| m.source)
        .collect();
    let named = |name: &str| -> f32 {
        let decl = format!("const {name}: f32 = ");
        let (_, rest) = sources
            .split_once(&decl)
            .unwrap_or_else(|| panic!("no {decl}"));
        let lit = &rest[..rest.find(';').unwrap()];
        lit.strip_suffix('f').unwrap().parse().unwrap()
    };
    let u32s = |name: &str| -> u32 {
        let decl = format!("const {name}: u32 = ");
        let (_, rest) = sources
            .split_once(&decl)
            .unwrap_or_else(|| panic!("no {decl}"));
        let lit = &rest[..rest.find(';').unwrap()];
        lit.strip_suffix('u').unwrap().parse().unwrap()
    };
    assert_eq!(named("BEE_LIMIT"), bee::params::LIMIT);
    assert_eq!(named("BEE_MIN_POSITIVE"), bee::params::MIN_POSITIVE);
    assert_eq!(
        named("BEE_MEAN_LIFT_COEFFICIENT"),
        oscillation::MEAN_LIFT_COEFFICIENT
    );
    assert_eq!(named("BEE_MEAN_ROLL_DEG"), oscillation::MEAN_ROLL_DEG);
    // sin_pi_over's `S::from_f32(2.0 * t_half)` for eq. 3 and 4, and TAU.
    assert_eq!(
        named("BEE_PITCH_PERIOD").to_bits(),
        (2.0f32 * 35.972).to_bits()
    );
    assert_eq!(
        named("BEE_ROLL_PERIOD").to_bits(),
        (2.0f32 * 91.775).to_bits()
    );
    assert_eq!(named("BEE_TAU"), core::f32::consts::TAU);
    // vision.rs's COS_HALF_FOV and oscillation.rs's HOVER_SPEED (private there).
    assert_eq!(named("BEE_COS_HALF_FOV"), core::f32::consts::FRAC_1_SQRT_2);
    assert_eq!(named("BEE_HOVER_SPEED"), 1e-3);
    let seeds = [u32s("BEE_SEED_1"), u32s("BEE_SEED_2"), u32s("BEE_SEED_3")];
    assert_eq!(seeds, curl::SEEDS.map(u32::from));
}

/// Values through the words and back: in Rust, and through the GPU's unpacking and packing
/// (`bee_*_from_words`, `bee_*_to_words`) over both scalars.
#[test]
fn values_survive_the_layout() {
    fn check<S: TestScalar>(gpu: &Gpu) {
        let mut g = Gen(Rng::new(78));
        let cases: Vec<StepCase<S>> = (0..1_500).map(|_| g.case()).collect();
        let mut input = Vec::new();
        let mut results = Vec::new();
        for c in &cases {
            let at = input.len();
            write_step_input(&mut input, &c.state, &c.frame, &c.params);
            let w = &input[at..];
            assert_eq!(w.len(), STEP_INPUT_WORDS);
            let mut again = Vec::new();
            write_step_input(
                &mut again,
                &read_state::<S>(w).unwrap(),
                &read_frame::<S>(&w[STATE_WORDS..]).unwrap(),
                &read_params::<S>(&w[STATE_WORDS + FRAME_WORDS..]),
            );
            assert_eq!(again, w);
            // A result: the state as the next state, a decision of its numbers.
            let s = c.state;
            let d = BeeDecision {
                accel: s.u0,
                velocity: s.vel,
                roll: s.roll,
                pitch: s.pitch,
                avoiding: !s.avoiding,
                density: s.density,
            };
            let r: StepResult<S> = Ok((d, s));
            let at = results.len();
            write_step_result(&mut results, &r);
            let w = &results[at..];
            assert_eq!(w.len(), STEP_OUTPUT_WORDS);
            let mut again = Vec::new();
            write_step_result(&mut again, &read_step_result::<S>(w).unwrap());
            assert_eq!(again, w);
        }
        // On the GPU: the state and frame of an input unpacked and packed again.
        let kernel = "
@group(0) @binding(0) var<storage, read> input: array<u32>;
@group(0) @binding(1) var<storage, read_write> output: array<u32>;
const IN_WORDS: u32 = BEE_STATE_WORDS + BEE_FRAME_WORDS + BEE_PARAMS_WORDS;
@compute @workgroup_size(WORKGROUP)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(id, groups);
    if (i >= arrayLength(&input) / IN_WORDS) { return; }
    let b = i * IN_WORDS;
    var sw: array<u32, BEE_STATE_WORDS>;
    for (var k = 0u; k < BEE_STATE_WORDS; k++) { sw[k] = input[b + k]; }
    var fw: array<u32, BEE_FRAME_WORDS>;
    for (var k = 0u; k < BEE_FRAME_WORDS; k++) { fw[k] = input[b + BEE_STATE_WORDS + k]; }
    var s = bee_state_to_words(bee_state_from_words(sw));
    var frame = bee_frame_from_words(&fw);
    var f = bee_frame_to_words(&frame);
    let o = i * (BEE_STATE_WORDS + BEE_FRAME_WORDS);
    for (var k = 0u; k < BEE_STATE_WORDS; k++) { output[o + k] = s[k]; }
    for (var k = 0u; k < BEE_FRAME_WORDS; k++) { output[o + BEE_STATE_WORDS + k] = f[k]; }
}";
        let kept = STATE_WORDS + FRAME_WORDS;
        let uses = modules(scalar_module::<S>());
        let got = map_words(gpu, &uses, kernel, "main", &input, STEP_INPUT_WORDS, kept).unwrap();
        for (i, (g, w)) in got
            .chunks(kept)
            .zip(input.chunks(STEP_INPUT_WORDS))
            .enumerate()
        {
            assert_eq!(g, &w[..kept], "input #{i} over {:?}", S::KIND);
        }
    }
    let gpu = test_gpu();
    check::<Fx>(&gpu);
    check::<f32>(&gpu);
}
