//! The ant scenario: eight ants of one colony in a 30 × 30 arena with a nest, a food source, a
//! round rock and a disturbance, run for [`STEPS`] two-phase ticks (`ant::plan` for every ant,
//! then `ant::resolve` with the neighbours' predictions), followed by a few deliberately bad
//! frames that must be refused with the same typed error on both sides.
//!
//! The starting positions are chosen so that the interesting branches of the controller run in
//! a handful of ticks: an ant that meets its nest without a label (S_nothing → S_nest), a laden
//! ant dropping food at the nest, an unladen ant collecting at the food source (stop timers
//! running out, labels changing, the turn back), an ant heading into the rock (avoidance), one
//! inside the disturbance (escape), an S_nothing ant next to a laden one (Table 1 transfer),
//! ants predicted within collision range of each other (eq. 2-4 repulsion), an ant at the wall
//! (boundary reflection), and casual stops (p_stop raised to 0.05).
//!
//! Words per ant and tick (in ant order, ticks in order):
//! `plan.predicted.{x,y}`, `plan.state.heading.{x,y}`, `discrete(plan.state)`,
//! `next.pos.{x,y}`, `next.heading.{x,y}`, `discrete(next)`, `next.arrival.{x,y}`
//! — 12 words; then the probes (see `probes` below).
//!
//! [`cost`] is the other use of this world: a larger colony, timed call by call (the
//! `ant-node-cycles` images).

use crate::{Meter, Sink, Stats, Word, uniform};
use swarm_core::ant::{
    self, AntNeighbor, AntObject, AntParams, AntPlan, AntState, Label, PlanFrame, ResolveFrame,
    Surface,
};
use swarm_core::{Checked, Rect, Scalar, StepCtx, Vec2};

/// Ants in the scenario.
pub const AGENTS: usize = 8;
/// Ticks simulated.
pub const STEPS: u32 = 6;
/// Neighbour capacity of the frames (an MCU-sized choice).
pub const N: usize = 8;
/// Object capacity of the frames.
pub const O: usize = 4;
/// Words per ant and tick.
pub const WORDS_PER_ANT_TICK: usize = 12;
/// The run's seed.
pub const SEED: u32 = 2018;

const NEST_ID: u16 = 0;
const FOOD_ID: u16 = 1;
/// Objects are sensed within this distance of their nearest point.
const SENSE: f32 = 8.0;
/// Neighbours are reported within this distance (beyond the controller's contact range, so
/// its own range filter runs too).
const HEAR: f32 = 3.0;
/// Obstacle surfaces are heard in the resolve phase within this distance (a step, and some).
const STEP_REACH: f32 = 1.1;

/// The static world, in scalar `S`.
struct World<S> {
    bounds: Rect<S>,
    nest: (Vec2<S>, S),
    food: (Vec2<S>, S),
    rock: (Vec2<S>, S),
    danger: (Vec2<S>, S),
}

impl<S: Scalar> World<S> {
    fn new() -> Self {
        let v = Vec2::<S>::from_f32;
        let s = S::from_f32;
        World {
            bounds: Rect::new(v(0.0, 0.0), v(30.0, 30.0)),
            nest: (v(5.0, 5.0), s(2.5)),
            food: (v(24.0, 20.0), s(2.5)),
            rock: (v(15.0, 10.0), s(2.0)),
            danger: (v(8.0, 22.0), s(3.0)),
        }
    }

    /// What ant `i` senses in the plan phase: ants within [`HEAR`] in id order, and the objects
    /// within [`SENSE`] (at most [`O`]: nest, food, rock, disturbance).
    fn plan_frame(&self, ants: &[AntState<S>], i: usize) -> PlanFrame<S, N, O> {
        let me = ants[i].pos;
        let mut f = PlanFrame::new(self.bounds);
        let hear = S::from_f32(HEAR);
        for (j, a) in ants.iter().enumerate() {
            if j != i && (a.pos - me).length() <= hear {
                let _ = f.neighbours.push(neighbour(j, a));
            }
        }
        let sense = S::from_f32(SENSE);
        let near = |c: Vec2<S>, r: S| (c - me).length() <= sense + r;
        if near(self.nest.0, self.nest.1) {
            let _ = f.objects.push(AntObject::Nest {
                id: NEST_ID,
                center: self.nest.0,
                radius: self.nest.1,
            });
        }
        if near(self.food.0, self.food.1) {
            let _ = f.objects.push(AntObject::Food {
                id: FOOD_ID,
                center: self.food.0,
                radius: self.food.1,
            });
        }
        if let Some(surface) = self.rock_seen_from(me)
            && (surface.closest - me).length() <= sense
        {
            let _ = f.objects.push(AntObject::Obstacle(surface));
        }
        if near(self.danger.0, self.danger.1) {
            let _ = f.objects.push(AntObject::Disturbance {
                center: self.danger.0,
                radius: self.danger.1,
            });
        }
        f
    }

    /// The rock's surface as an ant at `me` (outside it) senses it.
    fn rock_seen_from(&self, me: Vec2<S>) -> Option<Surface<S>> {
        let u = (me - self.rock.0).normalized()?;
        Surface::seen_from(me, self.rock.0 + u * self.rock.1)
    }

    /// What ant `i` hears in the resolve phase: the predictions of the others within [`HEAR`]
    /// of its own prediction, in id order; and the rock's surface if it is within a step.
    fn resolve_frame(&self, plans: &[Option<AntPlan<S>>], i: usize) -> ResolveFrame<S, N> {
        let mut f = ResolveFrame::new(self.bounds);
        let Some(me) = plans[i] else { return f };
        let pos = me.state.pos;
        if let Some(surface) = self.rock_seen_from(pos)
            && (surface.closest - pos).length() <= S::from_f32(STEP_REACH)
        {
            let _ = f.obstacles.push(surface);
        }
        let hear = S::from_f32(HEAR);
        for (j, p) in plans.iter().enumerate() {
            if let Some(p) = p
                && j != i
                && (p.predicted - me.predicted).length() <= hear
            {
                let _ = f.neighbours.push(p.predicted);
            }
        }
        f
    }
}

/// What an ant hears of ant `id` (its state `a`): its entry in a plan frame's neighbours.
#[inline]
pub fn neighbour<S: Scalar>(id: usize, a: &AntState<S>) -> AntNeighbor<S> {
    let AntState {
        pos,
        label,
        nest,
        origin,
        arrival,
        ..
    } = *a;
    AntNeighbor {
        id: id as u32,
        pos,
        label,
        nest,
        origin,
        arrival,
    }
}

/// The scenario's parameters: the defaults with short stops and frequent casual stops, so that
/// every stop kind starts and ends within [`STEPS`] ticks.
pub fn params<S: Scalar>() -> AntParams<S> {
    AntParams {
        p_stop: S::from_f32(0.05),
        casual_stop_ticks: 2,
        collect_ticks: 2,
        drop_ticks: 2,
        ..AntParams::default()
    }
}

/// The colony at tick 0.
fn initial<S: Scalar>(w: &World<S>) -> [AntState<S>; AGENTS] {
    let v = Vec2::<S>::from_f32;
    let laden = |pos: Vec2<S>, heading: Vec2<S>| AntState {
        label: Label::Food,
        origin: FOOD_ID,
        arrival: w.food.0,
        ..AntState::at_nest(NEST_ID, pos, heading)
    };
    [
        // 0: leaving the nest (S_nest), refreshing its arrival point while inside.
        AntState::at_nest(NEST_ID, v(5.0, 5.0), v(1.0, 1.0)),
        // 1: S_nothing, inside its nest: becomes S_nest.
        AntState::exploring(NEST_ID, v(5.5, 4.0), v(-1.0, 0.0)),
        // 2: laden, at the nest: drops the food, becomes S_nest, turns back.
        laden(v(6.0, 6.5), v(-1.0, -1.0)),
        // 3: S_nest at the food source: collects, becomes S_food, turns back.
        AntState::at_nest(NEST_ID, v(23.0, 19.5), v(1.0, 0.0)),
        // 4: heading into the rock: avoids it.
        AntState::at_nest(NEST_ID, v(11.5, 10.2), v(1.0, 0.0)),
        // 5: inside the disturbance: escapes.
        AntState::exploring(NEST_ID, v(9.0, 21.0), v(0.0, 1.0)),
        // 6: S_nothing beside the laden ant 7: told about the food (Table 1), and both
        //    predicted within collision range (eq. 2-4).
        AntState::exploring(NEST_ID, v(27.6, 26.2), v(1.0, 0.2)),
        // 7: laden, at the east wall, heading out: reflected.
        laden(v(29.4, 25.5), v(1.0, 0.0)),
    ]
}

/// Runs the scenario, emitting every decision word.
pub fn run<S: Word>(out: &mut impl Sink) {
    let w = World::<S>::new();
    let params = params::<S>();
    let mut ants = initial(&w);
    for step in 0..STEPS {
        // Phase 1: every ant plans on the previous tick's states.
        let mut plans: [Option<AntPlan<S>>; AGENTS] = [None; AGENTS];
        for (i, plan) in plans.iter_mut().enumerate() {
            let ctx = StepCtx {
                seed: SEED,
                agent: i as u32,
                step,
            };
            match ant::plan(&ants[i], &w.plan_frame(&ants, i), &params, ctx) {
                Ok(p) => {
                    out.vec2(p.predicted);
                    out.vec2(p.state.heading);
                    out.put(discrete(&p.state));
                    *plan = Some(p);
                }
                Err(e) => out.error(&e),
            }
        }
        // Phase 2: every ant resolves with its neighbours' predictions.
        for i in 0..AGENTS {
            let Some(plan) = plans[i] else { continue };
            match ant::resolve(&plan, &w.resolve_frame(&plans, i), &params) {
                Ok(next) => {
                    out.vec2(next.pos);
                    out.vec2(next.heading);
                    out.put(discrete(&next));
                    out.vec2(next.arrival);
                    ants[i] = next;
                }
                Err(e) => out.error(&e),
            }
        }
    }
    probes(&w, &ants, &params, out);
}

/// Ants in the colony of [`cost`].
pub const COST_AGENTS: usize = 24;
/// Ticks of [`cost`]: `COST_AGENTS * COST_TICKS` ant-steps are timed.
pub const COST_TICKS: u32 = 16;

/// What [`cost`] measured, in the meter's ticks.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct AntCost {
    /// One `ant::plan_checked` call (phase 1).
    pub plan: Stats,
    /// One `ant::resolve_checked` call (phase 2).
    pub resolve: Stats,
    /// One ant-step: the plan and the resolve of one ant in one tick.
    pub step: Stats,
    /// The ant-steps of ants that were not stopped after their plan (a stopped ant's plan
    /// returns early and its resolve does nothing).
    pub moving: Stats,
    /// Neighbours in the plan frames, summed (the mean is `neighbours / plan.n`).
    pub neighbours: u32,
    /// Plan frames holding [`N`] neighbours, the capacity.
    pub full_frames: u32,
    /// Controller calls that returned an error (0 expected: only decisions are timed).
    pub errors: u32,
}

/// The colony of [`cost`] at tick 0: three crowds (half the colony around the nest, a quarter
/// on the way past the rock, a quarter at the food source), the labels mixed (S_nothing, S_nest, laden), headings spread.
fn cost_colony<S: Scalar>(w: &World<S>) -> [AntState<S>; COST_AGENTS] {
    core::array::from_fn(|i| {
        let k = i as u32;
        // (x range, y range) of the crowd.
        let ((x0, x1), (y0, y1)) = match i % 4 {
            0 | 2 => ((4.0, 9.0), (3.0, 8.0)),
            1 => ((11.0, 16.0), (7.0, 12.0)),
            _ => ((20.0, 25.0), (17.0, 22.0)),
        };
        let pos = Vec2::new(uniform(k, 1, x0, x1), uniform(k, 2, y0, y1));
        let heading = Vec2::new(uniform(k, 3, -1.0, 1.0), uniform(k, 4, -1.0, 1.0));
        match (i / 3) % 3 {
            0 => AntState::exploring(NEST_ID, pos, heading),
            1 => AntState::at_nest(NEST_ID, pos, heading),
            _ => AntState {
                label: Label::Food,
                origin: FOOD_ID,
                arrival: w.food.0,
                ..AntState::at_nest(NEST_ID, pos, heading)
            },
        }
    })
}

/// Times the ant controller as a serial node runs it, call by call: [`COST_AGENTS`] ants of
/// one colony in this module's world for [`COST_TICKS`] two-phase ticks, every ant's
/// `ant::plan_checked` on its plan frame, then every ant's `ant::resolve_checked` with its
/// neighbours' predictions (the calls `AntDevice` makes for `AntPlanRequest` and
/// `AntResolveRequest`, parameters validated once). The frames are built outside the timed
/// blocks; only the controller call (its input validation included) is timed.
pub fn cost<S: Scalar>(params: &Checked<AntParams<S>>, meter: &mut impl Meter) -> AntCost {
    let w = World::<S>::new();
    let mut ants = cost_colony(&w);
    let mut c = AntCost::default();
    for step in 0..COST_TICKS {
        let mut plans: [Option<AntPlan<S>>; COST_AGENTS] = [None; COST_AGENTS];
        let mut plan_ticks = [0u32; COST_AGENTS];
        for i in 0..COST_AGENTS {
            let ctx = StepCtx {
                seed: SEED,
                agent: i as u32,
                step,
            };
            let frame = w.plan_frame(&ants, i);
            c.neighbours += frame.neighbours.len() as u32;
            c.full_frames += u32::from(frame.neighbours.len() == N);
            let (r, t) = meter.measure((&ants[i], &frame), |(s, f)| {
                ant::plan_checked(s, f, params, ctx)
            });
            c.plan.add(t);
            plan_ticks[i] = t;
            match r {
                Ok(p) => plans[i] = Some(p),
                Err(_) => c.errors += 1,
            }
        }
        for i in 0..COST_AGENTS {
            let Some(plan) = plans[i] else { continue };
            let frame = w.resolve_frame(&plans, i);
            let (r, t) =
                meter.measure((&plan, &frame), |(p, f)| ant::resolve_checked(p, f, params));
            c.resolve.add(t);
            c.step.add(plan_ticks[i].saturating_add(t));
            if !plan.state.is_stopped() {
                c.moving.add(plan_ticks[i].saturating_add(t));
            }
            match r {
                Ok(next) => ants[i] = next,
                Err(_) => c.errors += 1,
            }
        }
    }
    c
}

/// A probe's outcome: the error's marker and code, or (wrongly accepted) the plan.
fn emit<S: Word>(r: swarm_core::Result<AntPlan<S>>, out: &mut impl Sink) {
    if let Some(p) = out.decided(r) {
        out.vec2(p.predicted);
        out.put(discrete(&p.state));
    }
}

/// Bad input must be refused with the same typed error on the MCU and the host: a neighbour
/// beyond the coordinate limit, a duplicate neighbour id, a non-unit heading, and a bad
/// parameter. Each emits the error's marker and code (or, wrongly accepted, its plan).
fn probes<S: Word>(
    w: &World<S>,
    ants: &[AntState<S>; AGENTS],
    params: &AntParams<S>,
    out: &mut impl Sink,
) {
    let ctx = StepCtx {
        seed: SEED,
        agent: 0,
        step: STEPS,
    };
    let far = AntNeighbor {
        id: 5,
        pos: Vec2::from_f32(20_000.0, 3.0),
        label: Label::Food,
        nest: NEST_ID,
        origin: FOOD_ID,
        arrival: w.food.0,
    };
    let mut f = w.plan_frame(ants, 0);
    f.neighbours.clear();
    let _ = f.neighbours.push(AntNeighbor {
        id: 3,
        pos: ants[0].pos,
        ..far
    });
    let _ = f.neighbours.push(far);
    emit(ant::plan(&ants[0], &f, params, ctx), out);

    let mut f = w.plan_frame(ants, 0);
    f.neighbours.clear();
    let twin = AntNeighbor {
        id: 4,
        pos: ants[0].pos,
        ..far
    };
    let _ = f.neighbours.push(twin);
    let _ = f.neighbours.push(twin);
    emit(ant::plan(&ants[0], &f, params, ctx), out);

    let mut bent = ants[0];
    bent.heading = Vec2::from_f32(0.5, 0.5);
    emit(ant::plan(&bent, &w.plan_frame(ants, 0), params, ctx), out);

    let bad = AntParams {
        speed: -S::ONE,
        ..*params
    };
    emit(ant::plan(&ants[0], &w.plan_frame(ants, 0), &bad, ctx), out);
}

/// The discrete part of a state in one word:
/// `label | motion << 2 | stopped << 4 | reason << 5 | place << 8 | remaining << 16 | origin << 24`
/// (place, remaining and origin truncated to 8 bits; the scenario keeps them small).
pub fn discrete<S>(s: &AntState<S>) -> u32 {
    let (stopped, reason, place, remaining) = match s.stop {
        Some(t) => (
            1,
            t.reason as u32,
            u32::from(t.place),
            u32::from(t.remaining),
        ),
        None => (0, 0, 0, 0),
    };
    s.label as u32
        | (s.motion as u32) << 2
        | stopped << 4
        | reason << 5
        | (place & 0xff) << 8
        | (remaining & 0xff) << 16
        | (u32::from(s.origin) & 0xff) << 24
}

#[cfg(all(test, feature = "std"))]
mod tests {
    use super::*;
    use crate::host::{Calls, collect};
    use swarm_core::ant::{EnvAction, StopReason};

    /// Decoded per tick: (plan discrete words, resolved discrete words), per ant.
    /// Per tick: the plan-phase and the resolved discrete words, per ant.
    type Tick = ([u32; AGENTS], [u32; AGENTS]);

    fn ticks<S: Word>() -> (Vec<Tick>, Vec<u32>) {
        let words = collect(run::<S>);
        let mut t = Vec::new();
        let mut at = 0;
        for _ in 0..STEPS {
            let mut p = [0; AGENTS];
            let mut r = [0; AGENTS];
            for d in p.iter_mut() {
                *d = words[at + 4];
                at += 5;
            }
            for d in r.iter_mut() {
                *d = words[at + 4];
                at += 7;
            }
            t.push((p, r));
        }
        (t, words[at..].to_vec())
    }

    fn coverage<S: Word>() {
        let (t, probes) = ticks::<S>();
        let motion = |d: u32| (d >> 2) & 3;
        let seen_motion: Vec<u32> = (0..4)
            .filter(|m| t.iter().any(|(p, _)| p.iter().any(|&d| motion(d) == *m)))
            .collect();
        assert_eq!(seen_motion, [0, 1, 2, 3], "every motion state occurs");
        for reason in [
            StopReason::Casual,
            StopReason::CollectingFood,
            StopReason::DroppingFood,
        ] {
            let r = reason as u32;
            assert!(
                t.iter()
                    .any(|(p, _)| p.iter().any(|&d| d & 0x10 != 0 && (d >> 5) & 3 == r)),
                "stop {reason:?} occurs"
            );
        }
        let label = |d: u32| d & 3;
        let changed = |i: usize, from: Label, to: Label| {
            t.windows(2)
                .any(|w| label(w[0].1[i]) == from as u32 && label(w[1].1[i]) == to as u32)
                || (label(t[0].1[i]) == to as u32 && from == initial(&World::<S>::new())[i].label)
        };
        assert!(
            changed(1, Label::Nothing, Label::Nest),
            "ant 1 becomes S_nest at its nest"
        );
        assert!(changed(2, Label::Food, Label::Nest), "ant 2 drops its food");
        assert!(changed(3, Label::Nest, Label::Food), "ant 3 collects food");
        // The probes: far neighbour, twin id, bent heading, bad parameter.
        let m = crate::ERROR_MARKER;
        assert_eq!(
            probes,
            [
                m,
                2 << 16 | 1,
                m,
                3 << 16 | 1,
                m,
                2 << 16 | 0xffff,
                m,
                4 << 16 | 0xffff
            ]
        );

        // Tick 0, branch by branch.
        let w = World::<S>::new();
        let ants = initial(&w);
        let p = params::<S>();
        let ctx = |i| StepCtx {
            seed: SEED,
            agent: i as u32,
            step: 0,
        };
        let env =
            |i: usize| ant::environment(&ants[i], &w.plan_frame(&ants, i).objects, &p, ctx(i));
        assert!(
            matches!(env(4), EnvAction::Avoid(..)),
            "ant 4 avoids the rock: {:?}",
            env(4)
        );
        assert!(
            matches!(env(5), EnvAction::Escape(_)),
            "ant 5 escapes: {:?}",
            env(5)
        );
        assert!(matches!(env(1), EnvAction::AtNest));
        assert!(matches!(env(2), EnvAction::Drop(NEST_ID)));
        assert!(matches!(env(3), EnvAction::Collect(FOOD_ID)));
        assert!(
            ant::informer(&ants[6], &w.plan_frame(&ants, 6).neighbours, &p).is_some(),
            "ant 6 is informed"
        );
        let plans: [Option<AntPlan<S>>; AGENTS] =
            core::array::from_fn(|i| ant::plan(&ants[i], &w.plan_frame(&ants, i), &p, ctx(i)).ok());
        let r = ant::repulsion(
            plans[6].unwrap().predicted,
            &w.resolve_frame(&plans, 6).neighbours,
            &p,
        );
        assert!(r.length() > S::ZERO, "ants 6 and 7 repel (eq. 2-4)");
        assert!(
            plans[7].unwrap().state.heading.x < S::ZERO,
            "ant 7 reflected off the east wall"
        );
    }

    scalar_tests!(
        coverage,
        f32_scenario_exercises_every_branch,
        fixed_scenario_exercises_every_branch
    );

    fn cost_covers<S: Scalar>() {
        let params = params_of_node::<S>().checked().unwrap();
        let c = cost(&params, &mut Calls);
        let steps = COST_AGENTS as u32 * COST_TICKS;
        assert_eq!(c.errors, 0, "only decisions are timed");
        assert_eq!((c.plan.n, c.resolve.n, c.step.n), (steps, steps, steps));
        assert_eq!((c.step.min, c.step.max), (2, 2));
        assert!(c.moving.n > steps / 2 && c.moving.n < steps, "{c:?}");
        let mean = c.neighbours as f32 / steps as f32;
        assert!((2.0..7.0).contains(&mean), "mean neighbours {mean}");
        assert!(c.full_frames > 0, "some frames are full");
    }

    /// The serial nodes' ant parameters (`fw_node::ant_params`: the defaults).
    fn params_of_node<S: Scalar>() -> AntParams<S> {
        AntParams::<f32>::default().cast()
    }

    scalar_tests!(
        cost_covers,
        f32_cost_run_times_decisions_in_crowds,
        fixed_cost_run_times_decisions_in_crowds
    );

    #[test]
    fn word_count() {
        let n = collect(run::<f32>).len();
        assert_eq!(n, STEPS as usize * AGENTS * WORDS_PER_ANT_TICK + 8);
    }
}
