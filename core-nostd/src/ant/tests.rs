//! Unit tests of the ant controller, one or more per rule of xiang2018 §4.

use super::*;
use crate::rand::{self, stream};
use crate::{Error, Fx, Rect, Scalar, StepCtx, Vec2};

type F = f32;
type Frame = PlanFrame<F, 8, 4>;

fn v(x: f32, y: f32) -> Vec2<F> {
    Vec2::new(x, y)
}
fn arena() -> Rect<F> {
    Rect::new(v(0.0, 0.0), v(100.0, 100.0))
}
fn ctx(step: u32) -> StepCtx {
    StepCtx {
        seed: 11,
        agent: 1,
        step,
    }
}
/// A step at which neither a casual stop nor anything random interferes.
fn active_ctx(params: &AntParams<F>) -> StepCtx {
    (0..)
        .map(ctx)
        .find(|c| !rand::chance(*c, stream::ANT_STOP, params.p_stop))
        .unwrap()
}
fn no_turn() -> AntParams<F> {
    AntParams {
        theta: 1e-6,
        ..AntParams::default()
    }
}
fn ant(label: Label) -> AntState<F> {
    let mut a = AntState::at_nest(0, v(50.0, 50.0), v(1.0, 0.0));
    a.label = label;
    a.origin = if label == Label::Food { 7 } else { 0 };
    a
}
fn neighbour(id: u32, label: Label, nest: u16, at: Vec2<F>, arrival: Vec2<F>) -> AntNeighbor<F> {
    AntNeighbor {
        id,
        pos: at,
        label,
        nest,
        origin: if label == Label::Nest { nest } else { 7 },
        arrival,
    }
}
/// A frame of the test arena with `neighbours` and `objects`.
fn frame_with(
    neighbours: impl IntoIterator<Item = AntNeighbor<F>>,
    objects: impl IntoIterator<Item = AntObject<F>>,
) -> Frame {
    let mut f = Frame::new(arena());
    for n in neighbours {
        f.neighbours.push(n).unwrap();
    }
    for o in objects {
        f.objects.push(o).unwrap();
    }
    f
}

/// The food source `id`, a disc of `radius` around `center`.
fn food(id: u16, center: Vec2<F>, radius: F) -> AntObject<F> {
    AntObject::Food { id, center, radius }
}

/// The nest `id`, a disc of `radius` around `center`.
fn nest(id: u16, center: Vec2<F>, radius: F) -> AntObject<F> {
    AntObject::Nest { id, center, radius }
}

fn plan_with(a: &AntState<F>, f: &Frame, p: &AntParams<F>) -> AntPlan<F> {
    plan(a, f, p, active_ctx(p)).unwrap()
}
/// An obstacle sensed by an ant at `at` (outside it), its closest point `closest`.
fn rock(at: Vec2<F>, closest: Vec2<F>) -> AntObject<F> {
    AntObject::Obstacle(Surface {
        closest,
        normal: (at - closest).normalized().unwrap(),
    })
}
fn angle_between(a: Vec2<F>, b: Vec2<F>) -> f32 {
    a.cross(b).atan2(a.dot(b)).abs()
}

// ---- Table 1: information transfer -------------------------------------------------------

fn transfer_case(i: Label, j: Label, j_nest: u16) -> bool {
    let p = no_turn();
    let a = ant(i);
    let target = v(50.0, 90.0); // straight "north" of the ant
    let f = frame_with([neighbour(2, j, j_nest, v(51.0, 50.0), target)], []);
    let out = plan_with(&a, &f, &p);
    let turned = angle_between(out.state.heading, v(0.0, 1.0)) < 1e-3;
    assert_eq!(turned, out.state.motion == MotionState::InteractNeighbors);
    turned
}

#[test]
fn table1_situation1_nothing_learns_food() {
    assert!(transfer_case(Label::Nothing, Label::Food, 3));
}

#[test]
fn table1_situation2_nest_learns_food_from_any_colony() {
    assert!(transfer_case(Label::Nest, Label::Food, 0));
    assert!(transfer_case(Label::Nest, Label::Food, 3));
}

#[test]
fn table1_situation3_food_learns_own_nest_only() {
    assert!(transfer_case(Label::Food, Label::Nest, 0));
    assert!(
        !transfer_case(Label::Food, Label::Nest, 3),
        "another colony's nest"
    );
}

#[test]
fn table1_non_situations_transfer_nothing() {
    for (i, j) in [
        (Label::Nothing, Label::Nothing),
        (Label::Nothing, Label::Nest),
        (Label::Nest, Label::Nothing),
        (Label::Nest, Label::Nest),
        (Label::Food, Label::Nothing),
        (Label::Food, Label::Food),
    ] {
        assert!(!transfer_case(i, j, 0), "{i:?} <- {j:?} must not transfer");
    }
}

#[test]
fn nearest_informer_wins_and_range_is_respected() {
    let p = no_turn();
    let a = ant(Label::Nest);
    // Far informer (beyond contact range) points south, near one north-east, middle one west.
    let mut f = frame_with(
        [
            neighbour(5, Label::Food, 0, v(50.0, 53.0), v(50.0, 0.0)),
            neighbour(6, Label::Food, 0, v(50.5, 50.5), v(90.0, 90.0)),
            neighbour(7, Label::Food, 0, v(48.5, 50.0), v(0.0, 50.0)),
        ],
        [],
    );
    let out = plan_with(&a, &f, &p);
    assert!(angle_between(out.state.heading, v(1.0, 1.0)) < 1e-3);
    // Only the out-of-range one left: nothing happens.
    f.neighbours.retain(|n| n.id == 5);
    let out = plan_with(&a, &f, &p);
    assert_eq!(out.state.motion, MotionState::BasicMovement);
}

// ---- §4.1: stop state and basic movement ------------------------------------------------

fn casual_stop_count<S: Scalar>() -> u32 {
    let p = AntParams::<S>::default();
    (0..100_000u32)
        .filter(|&step| {
            let c = StepCtx {
                seed: 3,
                agent: step % 17,
                step,
            };
            rand::chance(c, stream::ANT_STOP, p.p_stop)
        })
        .count() as u32
}

#[test]
fn casual_stop_frequency_is_0_005() {
    // Binomial(1e5, 0.005): mean 500, σ = 22.3. We accept ±5σ = [388, 612]; a correct
    // generator fails this with probability < 1e-6.
    for n in [casual_stop_count::<f32>(), casual_stop_count::<Fx>()] {
        assert!((388..=612).contains(&n), "{n} stops in 1e5 draws");
    }
}

#[test]
fn casual_stop_holds_position_and_heading_for_its_duration() {
    let p = AntParams::<F>::default();
    let step = (0..)
        .find(|&s| rand::chance(ctx(s), stream::ANT_STOP, p.p_stop))
        .unwrap();
    let a = ant(Label::Nest);
    let f = Frame::new(arena());
    let out = plan(&a, &f, &p, ctx(step)).unwrap();
    assert_eq!(out.state.motion, MotionState::Stop);
    assert_eq!(out.predicted, a.pos);
    let mut s = resolve(&out, &ResolveFrame::<F, 8>::new(arena()), &p).unwrap();
    let mut stopped = 1;
    for t in 1..20 {
        let o = plan(&s, &f, &p, ctx(step + t)).unwrap();
        s = resolve(&o, &ResolveFrame::<F, 8>::new(arena()), &p).unwrap();
        if o.state.motion != MotionState::Stop {
            break;
        }
        assert_eq!((s.pos, s.heading), (a.pos, a.heading));
        stopped += 1;
    }
    assert_eq!(stopped, p.casual_stop_ticks);
}

#[test]
fn turns_stay_inside_theta() {
    let p = AntParams::<F>::default();
    let pf = AntParams::<Fx>::default();
    let a = ant(Label::Nest);
    let af = AntState::<Fx>::at_nest(0, Vec2::from_f32(50.0, 50.0), Vec2::from_f32(0.6, 0.8));
    let f = Frame::new(arena());
    let ff = PlanFrame::<Fx, 8, 4>::new(Rect::new(Vec2::zero(), Vec2::from_f32(100.0, 100.0)));
    let (mut lo, mut hi) = (0.0f32, 0.0f32);
    for step in 0..20_000 {
        let c = ctx(step);
        let turn: f32 = rand::angle(c, stream::ANT_TURN, p.theta);
        assert!(turn.abs() < p.theta, "drawn turn {turn}");
        let turn_fx: Fx = rand::angle(c, stream::ANT_TURN, pf.theta);
        assert!(turn_fx.abs() < pf.theta, "drawn fixed turn {turn_fx}");
        lo = lo.min(turn);
        hi = hi.max(turn);
        let out = plan(&a, &f, &p, c).unwrap();
        if out.state.motion == MotionState::BasicMovement {
            let d = out
                .state
                .heading
                .cross(a.heading)
                .atan2(out.state.heading.dot(a.heading));
            assert!(d.abs() < p.theta + 1e-5, "realised turn {d}");
        }
        let out = plan(&af, &ff, &pf, c).unwrap();
        if out.state.motion == MotionState::BasicMovement {
            let (h, h0) = (out.state.heading.to_f32(), af.heading.to_f32());
            let d = h.cross(h0).atan2(h.dot(h0));
            assert!(d.abs() < p.theta + 2e-4, "realised fixed turn {d}");
        }
    }
    // The whole interval is used.
    assert!(lo < -0.99 * p.theta && hi > 0.99 * p.theta);
}

// ---- §4.2.2: environment --------------------------------------------------------------

#[test]
fn obstacle_ahead_turns_perpendicular_to_the_ant_obstacle_line() {
    let p = AntParams::<F>::default();
    let a = ant(Label::Nest);
    for closest in [v(51.5, 50.2), v(51.0, 49.0), v(51.9, 50.0)] {
        let mut f = Frame::new(arena());
        f.objects.push(rock(a.pos, closest)).unwrap();
        let out = plan_with(&a, &f, &p);
        assert_eq!(out.state.motion, MotionState::InteractEnvironment);
        let line = (closest - a.pos).normalized().unwrap();
        assert!(out.state.heading.dot(line).abs() < 1e-5, "{closest:?}");
    }
    // Behind the ant, or too far: ignored.
    for closest in [v(48.5, 50.0), v(60.0, 50.0)] {
        let mut f = Frame::new(arena());
        f.objects.push(rock(a.pos, closest)).unwrap();
        assert_ne!(
            plan_with(&a, &f, &p).state.motion,
            MotionState::InteractEnvironment
        );
    }
}

#[test]
fn escape_increases_distance_to_the_disturbance() {
    let p = AntParams::<F>::default();
    for center in [v(49.0, 50.0), v(52.0, 53.0), v(50.0, 47.5), v(55.0, 50.0)] {
        let a = ant(Label::Food);
        let mut f = Frame::new(arena());
        f.objects
            .push(AntObject::Disturbance {
                center,
                radius: 10.0,
            })
            .unwrap();
        let out = plan_with(&a, &f, &p);
        assert_eq!(out.state.motion, MotionState::InteractEnvironment);
        let next = resolve(&out, &ResolveFrame::<F, 8>::new(arena()), &p).unwrap();
        assert!((next.pos - center).length() > (a.pos - center).length() + 0.99 * p.speed);
    }
}

#[test]
fn environment_priority_food_stop_then_obstacle_then_disturbance() {
    let p = no_turn();
    let a = ant(Label::Nest);
    let obstacle = rock(a.pos, v(51.0, 50.0));
    let disturbance = AntObject::Disturbance {
        center: v(45.0, 45.0),
        radius: 20.0,
    };
    let food = food(7, v(50.0, 50.0), 3.0);
    // Inside the food, the ant stops to collect whatever else is around (a stop runs into
    // nothing).
    let mut f = Frame::new(arena());
    f.objects.extend([food, disturbance, obstacle]);
    let out = plan_with(&a, &f, &p);
    assert_eq!(out.state.stop.unwrap().reason, StopReason::CollectingFood);
    f.objects.remove(0);
    let out = plan_with(&a, &f, &p);
    assert!(out.state.heading.x.abs() < 1e-5, "avoidance wins");
    f.objects.pop();
    let out = plan_with(&a, &f, &p);
    assert!(
        angle_between(out.state.heading, v(1.0, 1.0)) < 1e-4,
        "escape wins"
    );
}

#[test]
fn collecting_then_dropping_food_relabels_after_the_stop() {
    let p = AntParams::<F>::default();
    let mut a = ant(Label::Nest);
    a.arrival = v(1.0, 1.0);
    let f = frame_with([], [food(9, v(50.5, 50.0), 2.0)]);
    let rf = ResolveFrame::<F, 8>::new(arena());
    let mut s = resolve(&plan_with(&a, &f, &p), &rf, &p).unwrap();
    assert_eq!(s.stop.unwrap().reason, StopReason::CollectingFood);
    assert_eq!((s.label, s.pos), (Label::Nest, a.pos));
    // The arrival tick is the first stopped tick; the ant moves again on the tick after the
    // last one.
    let mut stopped_ticks = 1;
    for t in 1.. {
        s = resolve(&plan(&s, &f, &p, ctx(1000 + t)).unwrap(), &rf, &p).unwrap();
        if !s.is_stopped() {
            break;
        }
        stopped_ticks += 1;
    }
    assert_eq!(stopped_ticks, p.collect_ticks);
    assert_eq!((s.label, s.origin, s.arrival), (Label::Food, 9, a.pos));
    assert!(s.heading.x < 0.0, "turned back");

    // Laden, at another colony's nest: nothing; at its own nest: drop, then S_nest.
    let mut laden = ant(Label::Food);
    laden.pos = v(20.0, 20.0);
    let mut f = frame_with([], [nest(4, v(20.0, 21.0), 2.0)]);
    assert!(!plan_with(&laden, &f, &p).state.is_stopped());
    f.objects[0] = nest(0, v(20.0, 21.0), 2.0);
    let mut s = resolve(&plan_with(&laden, &f, &p), &rf, &p).unwrap();
    assert_eq!(s.stop.unwrap().reason, StopReason::DroppingFood);
    let mut t = 0;
    while s.is_stopped() {
        s = resolve(&plan(&s, &f, &p, ctx(2000 + t)).unwrap(), &rf, &p).unwrap();
        t += 1;
    }
    assert_eq!((s.label, s.origin), (Label::Nest, 0));
}

#[test]
fn nothing_ant_at_its_nest_becomes_nest_without_stopping() {
    let p = AntParams::<F>::default();
    let mut a = ant(Label::Nothing);
    a.origin = 0;
    let mut f = frame_with([], [nest(0, v(50.0, 51.0), 2.0)]);
    let out = plan_with(&a, &f, &p);
    assert_eq!(out.state.label, Label::Nest);
    assert_eq!(out.state.motion, MotionState::InteractEnvironment);
    assert!(!out.state.is_stopped());
    assert!((out.predicted - a.pos).length() > 0.99);
    // Another colony's nest does nothing.
    f.objects[0] = nest(1, v(50.0, 51.0), 2.0);
    assert_eq!(plan_with(&a, &f, &p).state.label, Label::Nothing);
}

// ---- §4.3: boundary, eq. 1-5 -------------------------------------------------------------

#[test]
fn boundary_reflects_the_heading_and_keeps_the_ant_inside() {
    let p = no_turn();
    let mut a = ant(Label::Nest);
    a.pos = v(99.5, 50.0);
    let out = plan_with(&a, &Frame::new(arena()), &p);
    assert!(out.state.heading.x < 0.0);
    assert!(arena().contains(out.predicted));
    assert!((out.predicted.x - 98.5).abs() < 1e-4);
}

#[test]
fn eq2_to_4_against_hand_computed_values() {
    // Ant predicted at (10, 10) heading +x; neighbours predicted at (10, 11) and (9, 10) (both
    // within collision range 1.5), one at (12, 10) beyond it. C = 1, k = 2, w0 = 0.6, v = 1.
    // R_1* = (0, -1), w_1 = 1/1^2 = 1; R_2* = (1, 0), w_2 = 1/1 = 1 ⇒ R_d = (1, -1), longer
    // than one: limited to (0.707107, -0.707107).
    // O = 0.6·(1, 0) + 0.4·(0.707107, -0.707107) = (0.882843, -0.282843)
    //   → unit (0.952320, -0.305102).
    let p = AntParams::<F>::default();
    let mut s = ant(Label::Nest);
    s.pos = v(9.0, 10.0);
    let plan = AntPlan {
        state: s,
        predicted: v(10.0, 10.0),
    };
    let r = repulsion(
        v(10.0, 10.0),
        &[v(10.0, 11.0), v(9.0, 10.0), v(12.0, 10.0)],
        &p,
    );
    assert!((r - v(1.0, -1.0)).length() < 1e-6);
    let mut rf = ResolveFrame::<F, 8>::new(arena());
    rf.neighbours
        .extend([v(10.0, 11.0), v(9.0, 10.0), v(12.0, 10.0)]);
    let next = resolve(&plan, &rf, &p).unwrap();
    assert!((next.heading - v(0.952_32, -0.305_102)).length() < 1e-5);
    assert!((next.pos - v(9.952_32, 9.694_898)).length() < 1e-5);
    // A single neighbour at distance 1.25 (w = 0.64) is not limited: O = (0.6, 0) + 0.4·(0,
    // -0.64) = (0.6, -0.256) → unit (0.919778, -0.392438).
    let mut rf = ResolveFrame::<F, 8>::new(arena());
    rf.neighbours.push(v(10.0, 11.25)).unwrap();
    let next = resolve(&plan, &rf, &p).unwrap();
    assert!((next.heading - v(0.919_778, -0.392_438)).length() < 1e-5);
    // k = 1 and C = 2: w_d = 2/0.5 = 4 for a neighbour at distance 0.5 straight ahead.
    let p2 = AntParams { c: 2.0, k: 1, ..p };
    let r = repulsion(v(0.0, 0.0), &[v(0.5, 0.0)], &p2);
    assert!((r - v(-4.0, 0.0)).length() < 1e-6);
}

#[test]
fn a_move_out_of_the_arena_is_not_clamped_into_an_obstacle_on_its_border() {
    // An obstacle reaching past the top border with a shallow face: the half-plane below the
    // line through (40, 100) and (80, 96) (a disc's tangent looks like this). An ant just
    // above the face that walks into it slides along the face, up and out of the arena;
    // clamping that end back onto the border moves it behind the face.
    let p = AntParams::<F>::default();
    let normal = v(0.1, 1.0).normalized().unwrap();
    let face = |x: f32| v(x, 100.0 - 0.1 * (x - 40.0));
    let mut checked = 0;
    for i in 0..80 {
        for d in [0.02, 0.05, 0.1, 0.2] {
            let pos = face(40.5 + 0.5 * i as f32) + normal * d;
            if !arena().contains(pos) {
                continue;
            }
            for j in 0..72 {
                let a = (j as f32) * core::f32::consts::TAU / 72.0;
                let mut s = ant(Label::Nest);
                s.pos = pos;
                s.heading = v(a.cos(), a.sin());
                let plan = AntPlan {
                    state: s,
                    predicted: pos + s.heading,
                };
                let mut rf = ResolveFrame::<F, 8>::new(arena());
                rf.obstacles
                    .push(Surface {
                        closest: face(60.0),
                        normal,
                    })
                    .unwrap();
                let next = resolve(&plan, &rf, &p).unwrap();
                assert!(
                    arena().contains(next.pos),
                    "{pos:?}, heading {a}: left the arena"
                );
                let clearance = (next.pos - face(60.0)).dot(normal);
                assert!(
                    clearance >= 0.0,
                    "{pos:?}, heading {a}: ends {clearance} behind the face"
                );
                checked += 1;
            }
        }
    }
    assert!(checked > 10_000, "{checked}");
}

// ---- Bad input ---------------------------------------------------------------------------

#[test]
fn bad_input_is_a_typed_error_naming_the_field() {
    let p = AntParams::<F>::default();
    let a = ant(Label::Nest);
    let c = ctx(0);
    let mut s = a;
    s.pos.x = f32::NAN;
    let e = plan(&s, &Frame::new(arena()), &p, c).unwrap_err();
    assert_eq!(
        e,
        Error::NonFinite {
            field: "state.pos",
            index: None
        }
    );
    let mut s = a;
    s.heading = v(0.0, 0.0);
    assert!(matches!(
        plan(&s, &Frame::new(arena()), &p, c),
        Err(Error::OutOfRange {
            field: "state.heading",
            ..
        })
    ));
    let mut s = a;
    s.origin = 3; // a Nest label must name its own nest
    assert!(matches!(
        plan(&s, &Frame::new(arena()), &p, c),
        Err(Error::Inconsistent { .. })
    ));

    let mut f = frame_with(
        [
            neighbour(4, Label::Food, 0, v(50.0, 51.0), v(0.0, 0.0)),
            neighbour(4, Label::Food, 0, v(50.0, 52.0), v(0.0, 0.0)),
        ],
        [],
    );
    assert_eq!(
        plan(&a, &f, &p, c).unwrap_err(),
        Error::Inconsistent {
            field: "neighbours.id",
            index: Some(1)
        }
    );
    f.neighbours[1].id = c.agent;
    assert!(
        plan(&a, &f, &p, c).is_err(),
        "the ant itself among its neighbours"
    );
    let f = frame_with(
        [],
        [
            rock(a.pos, v(1.0, 1.0)),
            food(0, v(1.0, f32::INFINITY), 1.0),
        ],
    );
    assert_eq!(
        plan(&a, &f, &p, c).unwrap_err(),
        Error::NonFinite {
            field: "objects.center",
            index: Some(1)
        }
    );
    let bad_bounds = Frame::new(Rect::new(v(10.0, 0.0), v(0.0, 10.0)));
    assert!(matches!(
        plan(&a, &bad_bounds, &p, c),
        Err(Error::OutOfRange {
            field: "bounds",
            ..
        })
    ));
    let bad_params = AntParams { speed: -1.0, ..p };
    assert_eq!(
        plan(&a, &Frame::new(arena()), &bad_params, c).unwrap_err(),
        Error::BadParam { field: "speed" }
    );
    let mut rf = ResolveFrame::<F, 8>::new(arena());
    rf.neighbours.push(v(f32::NAN, 0.0)).unwrap();
    let pl = plan(&a, &Frame::new(arena()), &p, c).unwrap();
    assert_eq!(
        resolve(&pl, &rf, &p).unwrap_err(),
        Error::NonFinite {
            field: "neighbours",
            index: Some(0)
        }
    );
}

// ---- Regressions from review -------------------------------------------------------------

#[test]
fn nearly_coincident_predictions_stay_finite_and_agree_across_scalars() {
    let p = AntParams::<F>::default();
    let pf = p.cast::<Fx>();
    for others in [
        [v(1.0, 1e-30), v(1.0, 0.5)],
        [v(1.01, 0.0), v(1.0, 0.02)],
        [v(1.0, 1e-6), v(1.0, -1e-6)],
    ] {
        let r = repulsion(v(1.0, 0.0), &others, &p);
        assert!(r.x.is_finite() && r.y.is_finite(), "{others:?} -> {r:?}");
        let others_fx = others.map(|o| o.cast::<Fx>());
        let rf = repulsion(Vec2::<Fx>::from_f32(1.0, 0.0), &others_fx, &pf).to_f32();
        if let (Some(a), Some(b)) = (r.normalized(), rf.normalized()) {
            assert!(
                angle_between(a, b) < 0.05,
                "{others:?}: f32 {a:?} vs fixed {b:?}"
            );
        }
    }
}

#[test]
fn contact_range_uses_true_distance_in_fixed_point() {
    let pf = AntParams::<Fx> {
        contact_range: Fx::from_f32(200.0),
        ..AntParams::default()
    };
    let mut a =
        AntState::<Fx>::at_nest(0, Vec2::from_f32(1000.0, 1000.0), Vec2::from_f32(1.0, 0.0));
    a.label = Label::Nest;
    let far = |id, dx: f32, arrival: Vec2<Fx>| AntNeighbor {
        id,
        pos: Vec2::from_f32(1000.0 + dx, 1000.0),
        label: Label::Food,
        nest: 0,
        origin: 7,
        arrival,
    };
    let near_target = Vec2::from_f32(0.0, 0.0);
    let ns = [
        far(1, 250.0, Vec2::from_f32(5.0, 5.0)),
        far(2, 190.0, near_target),
    ];
    assert_eq!(informer(&a, &ns, &pf), Some(near_target));
    assert_eq!(informer(&a, &ns[..1], &pf), None, "beyond contact range");
}

#[test]
fn an_ant_outside_the_arena_is_rejected() {
    let p = AntParams::<F>::default();
    let mut a = ant(Label::Nest);
    a.pos = v(150.0, 50.0);
    assert_eq!(
        plan(&a, &Frame::new(arena()), &p, ctx(0)).unwrap_err(),
        Error::OutOfRange {
            field: "state.pos",
            index: None
        }
    );
}

#[test]
fn arriving_at_food_holds_the_orientation() {
    let p = AntParams::<F>::default(); // full θ: the turn would change the heading
    let a = ant(Label::Nest);
    let f = frame_with([], [food(9, v(50.0, 50.0), 2.0)]);
    for step in 0..50 {
        let out = plan(&a, &f, &p, ctx(step)).unwrap();
        if out
            .state
            .stop
            .is_some_and(|t| t.reason == StopReason::CollectingFood)
        {
            assert_eq!(out.state.heading, a.heading);
        }
    }
}
