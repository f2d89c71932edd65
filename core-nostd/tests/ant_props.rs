//! Property tests: any ant input, garbage floats included, gives `Ok` or a typed `Err`, never a
//! panic, for both scalar types; an `Ok` plan keeps the ant inside the arena.

use proptest::prelude::*;
use swarm_core::ant::{
    self, AntNeighbor, AntObject, AntParams, AntState, Label, MotionState, PlanFrame, ResolveFrame,
    StopReason, StopTimer, Surface,
};
use swarm_core::{Fx, Rect, Scalar, StepCtx, Vec2};

fn float() -> impl Strategy<Value = f32> {
    prop_oneof![
        4 => -120.0f32..120.0,
        1 => any::<f32>(),
        1 => Just(f32::NAN),
        1 => Just(f32::INFINITY),
        1 => Just(0.0f32),
        1 => -40_000.0f32..40_000.0,
    ]
}
fn vec2() -> impl Strategy<Value = [f32; 2]> {
    [float(), float()]
}
fn label() -> impl Strategy<Value = Label> {
    prop_oneof![Just(Label::Nothing), Just(Label::Food), Just(Label::Nest)]
}
fn motion() -> impl Strategy<Value = MotionState> {
    prop_oneof![
        Just(MotionState::Stop),
        Just(MotionState::BasicMovement),
        Just(MotionState::InteractNeighbors),
        Just(MotionState::InteractEnvironment)
    ]
}
fn stop() -> impl Strategy<Value = Option<StopTimer>> {
    proptest::option::of(
        (
            prop_oneof![
                Just(StopReason::Casual),
                Just(StopReason::CollectingFood),
                Just(StopReason::DroppingFood)
            ],
            0u16..4,
            0u16..3,
        )
            .prop_map(|(reason, remaining, place)| StopTimer {
                reason,
                remaining,
                place,
            }),
    )
}

/// A neighbour: id, position, label, nest, origin, latest arrival.
type RawNeighbour = (u32, [f32; 2], Label, u16, u16, [f32; 2]);

#[derive(Debug, Clone)]
struct Input {
    pos: [f32; 2],
    heading: [f32; 2],
    arrival: [f32; 2],
    label: Label,
    nest: u16,
    origin: u16,
    motion: MotionState,
    stop: Option<StopTimer>,
    bounds: [f32; 4],
    neighbours: Vec<RawNeighbour>,
    objects: Vec<(u8, [f32; 2], f32, u16)>,
    predictions: Vec<[f32; 2]>,
    ctx: (u32, u32, u32),
    speed: f32,
}

fn input() -> impl Strategy<Value = Input> {
    (
        (vec2(), prop_oneof![3 => Just([0.6f32, 0.8]), 1 => vec2()], vec2(), label()),
        (0u16..3, 0u16..3, motion(), stop()),
        prop_oneof![3 => Just([0.0f32, 0.0, 100.0, 100.0]), 1 => [float(), float(), float(), float()]],
        proptest::collection::vec((0u32..6, vec2(), label(), 0u16..3, 0u16..3, vec2()), 0..8),
        proptest::collection::vec((0u8..4, vec2(), float(), 0u16..3), 0..4),
        proptest::collection::vec(vec2(), 0..8),
        (any::<u32>(), 0u32..6, any::<u32>()),
        prop_oneof![3 => Just(1.0f32), 1 => float()],
    )
        .prop_map(
            |((pos, heading, arrival, label), (nest, origin, motion, stop), bounds, neighbours, objects, predictions, ctx, speed)| {
                Input {
                    pos,
                    heading,
                    arrival,
                    label,
                    nest,
                    origin,
                    motion,
                    stop,
                    bounds,
                    neighbours,
                    objects,
                    predictions,
                    ctx,
                    speed,
                }
            },
        )
}

fn run<S: Scalar>(i: &Input) {
    let v = |a: [f32; 2]| Vec2::<S>::from_f32(a[0], a[1]);
    let state = AntState {
        pos: v(i.pos),
        heading: v(i.heading),
        arrival: v(i.arrival),
        label: i.label,
        nest: i.nest,
        origin: i.origin,
        goal: None,
        follow: None,
        motion: i.motion,
        stop: i.stop,
    };
    let bounds = Rect::new(v([i.bounds[0], i.bounds[1]]), v([i.bounds[2], i.bounds[3]]));
    let mut frame = PlanFrame::<S, 8, 4>::new(bounds);
    for &(id, pos, label, nest, origin, arrival) in &i.neighbours {
        let _ = frame.neighbours.push(AntNeighbor {
            id,
            pos: v(pos),
            label,
            nest,
            origin,
            arrival: v(arrival),
        });
    }
    for &(kind, p, r, id) in &i.objects {
        let (center, radius) = (v(p), S::from_f32(r));
        let _ = frame.objects.push(match kind {
            0 => match Surface::seen_from(state.pos, center) {
                Some(surface) => AntObject::Obstacle(surface),
                None => continue,
            },
            1 => AntObject::Disturbance { center, radius },
            2 => AntObject::Food { id, center, radius },
            _ => AntObject::Nest { id, center, radius },
        });
    }
    let params = AntParams::<S> {
        speed: S::from_f32(i.speed),
        ..AntParams::default()
    };
    let ctx = StepCtx {
        seed: i.ctx.0,
        agent: i.ctx.1,
        step: i.ctx.2,
    };
    let Ok(plan) = ant::plan(&state, &frame, &params, ctx) else {
        return;
    };
    assert!(bounds.contains(plan.predicted) || !bounds.contains(state.pos));
    let mut rf = ResolveFrame::<S, 8>::new(bounds);
    for &p in &i.predictions {
        let _ = rf.neighbours.push(v(p));
    }
    if let Ok(next) = ant::resolve(&plan, &rf, &params) {
        assert!(bounds.contains(next.pos) || !bounds.contains(state.pos));
        assert!(
            next.validate().is_ok(),
            "resolve produced an invalid state: {next:?}"
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(3000))]

    #[test]
    fn any_input_gives_ok_or_typed_error_f32(i in input()) {
        run::<f32>(&i);
    }

    #[test]
    fn any_input_gives_ok_or_typed_error_fixed(i in input()) {
        run::<Fx>(&i);
    }
}
