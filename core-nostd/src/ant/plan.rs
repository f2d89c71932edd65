//! Phase 1 of a tick: steps (1)-(3) of xiang2018 §4 and the predicted position of eq. 1.

use super::frame::PlanFrame;
use super::interact::{EnvAction, environment, informer};
use super::params::AntParams;
use super::state::{AntState, Label, MotionState, StopReason, StopTimer};
use crate::rand::{self, stream};
use crate::{Checked, Error, Rect, Result, Scalar, StepCtx, Vec2};

wire_type! {
    /// The outcome of [`plan`]: the ant's state after the local exploration, with its preferred
    /// orientation O*(t+1) as `state.heading`, and its predicted position p*(t+1) (eq. 1), which
    /// the ant broadcasts to its neighbours before [`resolve`](super::resolve).
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct AntPlan<S> {
        /// State after steps (1)-(3): label, timers and motion updated, heading = O*(t+1),
        /// position still p(t).
        pub state: AntState<S>,
        /// p*(t+1) = p(t) + v·O*(t+1)·Δt, boundary-checked (eq. 1, §4.3).
        pub predicted: Vec2<S>,
    }
}

/// Phase 1 of the ant tick (xiang2018 §4, Algorithm 1 lines 2-3 and Algorithm 2):
///
/// 1. **Stop** (§4.1): a stopped ant counts down its timer and stays; when a collecting
///    (dropping) stop runs out, S_c becomes S_food (S_nest), the latest arrival position is
///    recorded, the ant turns back the way it came and takes the place it came from (its nest,
///    its food) as its goal. An active ant stops casually with probability `p_stop`.
/// 2. **Basic movement** (§4.1): turn by a uniform random angle in (−θ, θ) from the current
///    orientation, or from the direction to the goal when the ant has one (ours).
/// 3. **Interactions** (§4.2): a neighbour that can inform the ant (Table 1, nearest first)
///    makes that neighbour's latest arrival position the ant's goal (Fig. 6; a goal reached
///    without arriving is forgotten); then the environment, which takes priority over
///    neighbours: stops at food or its nest, obstacles (avoiding, going round toward the goal,
///    [`obstacle_heading`](super::obstacle_heading)) > disturbance > relabelling at the nest.
/// 4. **Prediction** (eq. 1) and boundary check (§4.3): p* = p + v·O*·Δt; a prediction that
///    leaves the arena reflects O* off the wall(s) it crosses.
///
/// Pure: the same inputs give the same bits. Bad input returns an error and nothing else.
pub fn plan<S: Scalar, const N: usize, const O: usize>(
    state: &AntState<S>,
    frame: &PlanFrame<S, N, O>,
    params: &AntParams<S>,
    ctx: StepCtx,
) -> Result<AntPlan<S>> {
    plan_checked(state, frame, &params.checked()?, ctx)
}

/// [`plan`] with parameters validated beforehand (the state and frame are still checked).
#[inline]
pub fn plan_checked<S: Scalar, const N: usize, const O: usize>(
    state: &AntState<S>,
    frame: &PlanFrame<S, N, O>,
    params: &Checked<AntParams<S>>,
    ctx: StepCtx,
) -> Result<AntPlan<S>> {
    let params: &AntParams<S> = params;
    state.validate()?;
    frame.validate(ctx.agent)?;
    if !frame.bounds.contains(state.pos) {
        return Err(Error::out_of_range("state.pos"));
    }
    let mut s = *state;

    // (1) The stop state.
    if let Some(mut timer) = s.stop {
        timer.remaining -= 1; // validated ≥ 1
        if timer.remaining > 0 {
            s.stop = Some(timer);
            return Ok(stay(s));
        }
        s.stop = None;
        finish_stop(&mut s, timer);
    } else if rand::chance(ctx, stream::ANT_STOP, params.p_stop) {
        return Ok(stop(s, StopReason::Casual, params.casual_stop_ticks, 0));
    }

    // (3a) Information from neighbours (Table 1): the informer's latest arrival position
    // becomes the ant's goal (§4.2.1, Fig. 6) ...
    s.motion = MotionState::BasicMovement;
    if let Some(target) = informer(&s, &frame.neighbours, params) {
        s.goal = Some(target);
        s.motion = MotionState::InteractNeighbors;
    }
    // ... which it forgets once there without having found its destination (ours).
    let step = params.speed * params.dt;
    if s.goal.is_some_and(|g| (g - s.pos).length() <= step) {
        s.goal = None;
    }

    // (2) Basic movement: a random turn in (−θ, θ) (§4.1) from the current orientation, or,
    // with a goal, from the direction to it (ours: the informed ant "moves closer to the
    // destination", §4.2.1, on every tick rather than only at the contact).
    let turn = rand::angle(ctx, stream::ANT_TURN, params.theta);
    let reference = s
        .goal
        .and_then(|g| (g - s.pos).normalized())
        .unwrap_or(s.heading);
    s.heading = reference.rotated(turn).normalized().unwrap_or(reference);

    // (3b) The environment, which the ant prefers to its neighbours (§4, Fig. 4a).
    let sensing = s;
    s.follow = None;
    match environment(&sensing, &frame.objects, params, ctx) {
        EnvAction::None => {}
        EnvAction::Avoid(h, follow) => {
            s.heading = h;
            s.follow = follow;
            s.motion = MotionState::InteractEnvironment;
        }
        EnvAction::Escape(h) => {
            s.heading = h;
            s.motion = MotionState::InteractEnvironment;
        }
        // A stopped ant holds its orientation (§4.1): undo this tick's turns.
        EnvAction::Collect(food) => {
            s.heading = state.heading;
            return Ok(stop(
                s,
                StopReason::CollectingFood,
                params.collect_ticks,
                food,
            ));
        }
        EnvAction::Drop(nest) => {
            s.heading = state.heading;
            return Ok(stop(s, StopReason::DroppingFood, params.drop_ticks, nest));
        }
        EnvAction::AtNest => {
            s.label = Label::Nest;
            s.origin = s.nest;
            s.arrival = s.pos;
            s.motion = MotionState::InteractEnvironment;
        }
    }

    // (4) Eq. 1 with the boundary check.
    let (heading, predicted) = predict(s.pos, s.heading, frame.bounds, params);
    s.heading = heading;
    Ok(AntPlan {
        state: s,
        predicted,
    })
}

/// Eq. 1, p* = p + v·O*·Δt, with the boundary check of §4.3: a component of O* that would take
/// p* across a wall is reflected, and p* is kept inside the arena.
pub fn predict<S: Scalar>(
    pos: Vec2<S>,
    heading: Vec2<S>,
    bounds: Rect<S>,
    params: &AntParams<S>,
) -> (Vec2<S>, Vec2<S>) {
    let step = params.speed * params.dt;
    let mut h = heading;
    let p = pos + h * step;
    // Non-short-circuit `&` and `|`: one rarely taken branch per axis, not one on the sign of
    // the heading (a coin toss for the branch predictor).
    let zero = S::ZERO;
    if (p.x < bounds.min.x) & (h.x < zero) | (p.x > bounds.max.x) & (h.x > zero) {
        h.x = -h.x;
    }
    if (p.y < bounds.min.y) & (h.y < zero) | (p.y > bounds.max.y) & (h.y > zero) {
        h.y = -h.y;
    }
    (h, bounds.clamp(pos + h * step))
}

/// The ant stays where it is this tick (p* = p).
fn stay<S: Scalar>(mut s: AntState<S>) -> AntPlan<S> {
    s.motion = MotionState::Stop;
    AntPlan {
        predicted: s.pos,
        state: s,
    }
}

fn stop<S: Scalar>(mut s: AntState<S>, reason: StopReason, ticks: u16, place: u16) -> AntPlan<S> {
    s.stop = Some(StopTimer {
        reason,
        remaining: ticks,
        place,
    });
    stay(s)
}

/// The end of a stop (§4.1): collecting makes S_c = S_food, dropping makes S_c = S_nest; the
/// ant records where it arrived, turns back the way it came and takes as its goal the place it
/// came from: the paper says it "starts to move toward the nest" after collecting and "back to
/// the food" after dropping; ours: toward its latest arrival at the nest (if it has one) and
/// at the food source, the one memory an ant has of each place.
fn finish_stop<S: Scalar>(s: &mut AntState<S>, timer: StopTimer) {
    let (label, goal) = match timer.reason {
        StopReason::Casual => return,
        // Back to the nest it last left, if it has been at its nest.
        StopReason::CollectingFood => (Label::Food, (s.label == Label::Nest).then_some(s.arrival)),
        // Back to the food it collected (a laden ant's arrival is where it collected).
        StopReason::DroppingFood => (Label::Nest, Some(s.arrival)),
    };
    s.label = label;
    s.origin = timer.place;
    s.arrival = s.pos;
    s.goal = goal;
    s.follow = None;
    s.heading = -s.heading;
}
