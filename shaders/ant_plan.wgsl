// Phase 1 of an ant tick (host-sim/src/gpu/shaders.rs, ANT_PLAN): `swarm_core::ant::plan`
// (core-nostd/src/ant/plan.rs): steps (1)-(3) of xiang2018 §4 and the predicted position of
// eq. 1, over the scalar `S`.

// AntPlan<S>: the state after the local exploration (heading = O*(t+1)) and the predicted
// position p*(t+1) (eq. 1).
struct AntPlan {
    state: AntState,
    predicted: vec2<S>,
}

// Result<AntPlan<S>>: `status` 0 and the plan, or the status word of the error (the plan then
// means nothing).
struct AntPlanResult {
    status: u32,
    plan: AntPlan,
}

// The result of predict: (heading, predicted).
struct AntPredict {
    heading: vec2<S>,
    predicted: vec2<S>,
}

// plan_checked: phase 1 of the ant tick (xiang2018 §4, Algorithm 1 lines 2-3 and Algorithm 2)
// with parameters validated beforehand (the state and frame are checked):
// 1. Stop (§4.1): a stopped ant counts down its timer and stays (finish_stop when it runs
//    out); an active ant stops casually with probability p_stop.
// 2. Basic movement (§4.1): a random turn in (-θ, θ) from the current orientation, or from the
//    direction to the goal (ours).
// 3. Interactions (§4.2): an informing neighbour (Table 1) gives the goal (Fig. 6); then the
//    environment, which takes priority over neighbours.
// 4. Prediction (eq. 1) and boundary check (§4.3).
fn ant_plan_checked(
    state: AntState,
    frame: ptr<function, AntPlanFrame>,
    params: AntParams,
    ctx: StepCtx,
) -> AntPlanResult {
    var e = ant_state_validate(state);
    if (e != ANT_OK) {
        return AntPlanResult(e, AntPlan());
    }
    e = ant_plan_frame_validate(frame, ctx.agent);
    if (e != ANT_OK) {
        return AntPlanResult(e, AntPlan());
    }
    if (!geom_rect_contains((*frame).bounds, state.pos)) {
        return AntPlanResult(ant_error(ANT_ERROR_OUT_OF_RANGE, ANT_FIELD_STATE_POS), AntPlan());
    }
    var s = state;

    // (1) The stop state.
    if (s.has_stop) {
        var timer = s.stop;
        timer.remaining = timer.remaining - 1u; // validated ≥ 1
        if (timer.remaining > 0u) {
            s.stop = timer;
            return AntPlanResult(ANT_OK, ant_stay(s));
        }
        s.has_stop = false;
        s = ant_finish_stop(s, timer);
    } else if (rand_chance(ctx.seed, ctx.agent, ctx.step, RAND_ANT_STOP, params.p_stop)) {
        return AntPlanResult(ANT_OK, ant_stop(s, ANT_STOP_CASUAL, params.casual_stop_ticks, 0u));
    }

    // (3a) Information from neighbours (Table 1): the informer's latest arrival position
    // becomes the ant's goal (§4.2.1, Fig. 6) ...
    s.motion = ANT_MOTION_BASIC_MOVEMENT;
    let informed = ant_informer(s, frame, params);
    if (informed.is_some) {
        s.has_goal = true;
        s.goal = informed.value;
        s.motion = ANT_MOTION_INTERACT_NEIGHBORS;
    }
    // ... which it forgets once there without having found its destination (ours).
    let step = s_mul(params.speed, params.dt);
    if (s.has_goal && geom_length(geom_sub(s.goal, s.pos)) <= step) {
        s.has_goal = false;
    }

    // (2) Basic movement: a random turn in (-θ, θ) (§4.1) from the current orientation, or,
    // with a goal, from the direction to it (ours).
    let turn = rand_angle(ctx.seed, ctx.agent, ctx.step, RAND_ANT_TURN, params.theta);
    var reference = s.heading;
    if (s.has_goal) {
        let g = geom_normalized(geom_sub(s.goal, s.pos));
        if (g.is_some) {
            reference = g.value;
        }
    }
    s.heading = geom_normalized_or(geom_rotated(reference, turn), reference);

    // (3b) The environment, which the ant prefers to its neighbours (§4, Fig. 4a).
    let sensing = s;
    s.has_follow = false;
    let env = ant_environment(sensing, frame, params, ctx);
    if (env.kind == ANT_ENV_AVOID) {
        s.heading = env.heading;
        s.has_follow = env.has_follow;
        s.follow = env.follow;
        s.motion = ANT_MOTION_INTERACT_ENVIRONMENT;
    } else if (env.kind == ANT_ENV_ESCAPE) {
        s.heading = env.heading;
        s.motion = ANT_MOTION_INTERACT_ENVIRONMENT;
    } else if (env.kind == ANT_ENV_COLLECT) {
        // A stopped ant holds its orientation (§4.1): undo this tick's turns.
        s.heading = state.heading;
        return AntPlanResult(
            ANT_OK,
            ant_stop(s, ANT_STOP_COLLECTING_FOOD, params.collect_ticks, env.place),
        );
    } else if (env.kind == ANT_ENV_DROP) {
        s.heading = state.heading;
        return AntPlanResult(
            ANT_OK,
            ant_stop(s, ANT_STOP_DROPPING_FOOD, params.drop_ticks, env.place),
        );
    } else if (env.kind == ANT_ENV_AT_NEST) {
        s.label = ANT_LABEL_NEST;
        s.origin = s.nest;
        s.arrival = s.pos;
        s.motion = ANT_MOTION_INTERACT_ENVIRONMENT;
    }

    // (4) Eq. 1 with the boundary check.
    let p = ant_predict(s.pos, s.heading, (*frame).bounds, params);
    s.heading = p.heading;
    return AntPlanResult(ANT_OK, AntPlan(s, p.predicted));
}

// predict: eq. 1, p* = p + v·O*·Δt, with the boundary check of §4.3: a component of O* that
// would take p* across a wall is reflected, and p* is kept inside the arena.
fn ant_predict(pos: vec2<S>, heading: vec2<S>, bounds: GeomRect, params: AntParams) -> AntPredict {
    let step = s_mul(params.speed, params.dt);
    var h = heading;
    let p = geom_add(pos, geom_mul(h, step));
    let zero = S_ZERO;
    if ((p.x < bounds.min.x && h.x < zero) || (p.x > bounds.max.x && h.x > zero)) {
        h.x = s_neg(h.x);
    }
    if ((p.y < bounds.min.y && h.y < zero) || (p.y > bounds.max.y && h.y > zero)) {
        h.y = s_neg(h.y);
    }
    return AntPredict(h, geom_rect_clamp(bounds, geom_add(pos, geom_mul(h, step))));
}

// stay (plan.rs): the ant stays where it is this tick (p* = p).
fn ant_stay(state: AntState) -> AntPlan {
    var s = state;
    s.motion = ANT_MOTION_STOP;
    return AntPlan(s, s.pos);
}

// stop (plan.rs): the ant starts a stop of `ticks` ticks, and stays.
fn ant_stop(state: AntState, reason: u32, ticks: u32, place: u32) -> AntPlan {
    var s = state;
    s.has_stop = true;
    s.stop = AntStopTimer(reason, ticks, place);
    return ant_stay(s);
}

// finish_stop: the end of a stop (§4.1): collecting makes S_c = S_food, dropping S_c = S_nest;
// the ant records where it arrived, turns back the way it came and takes as its goal the place
// it came from (ours: its latest arrival there, if it has one).
fn ant_finish_stop(state: AntState, timer: AntStopTimer) -> AntState {
    var s = state;
    if (timer.reason == ANT_STOP_CASUAL) {
        return s;
    }
    var label = ANT_LABEL_NEST;
    // Back to the food it collected (a laden ant's arrival is where it collected).
    var has_goal = true;
    if (timer.reason == ANT_STOP_COLLECTING_FOOD) {
        // Back to the nest it last left, if it has been at its nest.
        label = ANT_LABEL_FOOD;
        has_goal = s.label == ANT_LABEL_NEST;
    }
    s.goal = s.arrival;
    s.has_goal = has_goal;
    s.label = label;
    s.origin = timer.place;
    s.arrival = s.pos;
    s.has_follow = false;
    s.heading = geom_neg(s.heading);
    return s;
}
