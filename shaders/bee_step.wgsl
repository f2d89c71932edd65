// The bee controller's entry point (host-sim/src/gpu/shaders.rs, BEE_STEP):
// `swarm_core::bee::step` (core-nostd/src/bee/step.rs): one step of chen eq. 1, over the
// scalar `S`.

// Result<(BeeDecision<S>, BeeState<S>)>: `status` 0 and the decision and next state, or the
// status word of the error (the values then mean nothing).
struct BeeStepResult {
    status: u32,
    decision: BeeDecision,
    state: BeeState,
}

// StepConsts<S>: what a step needs that depends only on the parameters and the frame time t:
// the SPH kernels (eq. 10-11) and θ_pitch(t), θ_roll(t) (eq. 3-4, degrees).
struct BeeStepConsts {
    t: S,
    h: S,
    kernels: BeeKernels,
    pitch: S,
    roll: S,
}

// StepConsts::new: the constants of `params` at time `t`.
fn bee_step_consts_new(params: BeeParams, t: S) -> BeeStepConsts {
    return BeeStepConsts(t, params.h, bee_kernels_new(params.h), bee_pitch_deg(t), bee_roll_deg(t));
}

// step_checked: one step of the bee controller with parameters validated beforehand (the
// state and frame are checked):
// 1. every input field validated (the status word names the field, and the index for list
//    entries);
// 2. body frame: forward axis o along the velocity, heading to the goal; vision (§IV-B);
// 3. angles: θ_pitch from eq. 3; θ_roll from eq. 6 when avoiding, else eq. 4;
// 4. forces: F_o (eq. 2), F_curl (eq. 8-9), ρ_i (eq. 10) and F_repul (eq. 11);
// 5. eq. 1 plus the linear drag, a = F/m, u = u_p + aΔt (§III);
// 6. eq. 5 with an obstacle closer than d0, the speed limit: u*; the new position r + u*Δt.
fn bee_step_checked(
    state: BeeState,
    frame: ptr<function, BeeFrame>,
    params: BeeParams,
) -> BeeStepResult {
    var e = bee_state_validate(state);
    if (e == BEE_OK) {
        e = bee_frame_validate(frame);
    }
    if (e != BEE_OK) {
        return BeeStepResult(e, BeeDecision(), BeeState());
    }
    return bee_run(state, frame, params, bee_step_consts_new(params, (*frame).t));
}

// step_with: step_checked with the constants of the step computed beforehand, the same bits;
// constants made for another time or kernel radius are not used (computed afresh).
fn bee_step_with(
    state: BeeState,
    frame: ptr<function, BeeFrame>,
    params: BeeParams,
    consts: BeeStepConsts,
) -> BeeStepResult {
    var e = bee_state_validate(state);
    if (e == BEE_OK) {
        e = bee_frame_validate(frame);
    }
    if (e != BEE_OK) {
        return BeeStepResult(e, BeeDecision(), BeeState());
    }
    if (consts.t == (*frame).t && consts.h == params.h) {
        return bee_run(state, frame, params, consts);
    }
    return bee_run(state, frame, params, bee_step_consts_new(params, (*frame).t));
}

// run (step.rs): the step proper, on validated input.
fn bee_run(
    state: BeeState,
    frame: ptr<function, BeeFrame>,
    params: BeeParams,
    consts: BeeStepConsts,
) -> BeeStepResult {
    let heading = bee_goal_heading(state.pos, GeomOptionVec3((*frame).has_goal, (*frame).goal));
    let o = bee_forward_axis(state.vel, state.forward, heading);
    var close = BeeOptionSighting(false, BeeSighting());
    if ((*frame).has_obstacle) {
        close = bee_near(state.pos, (*frame).obstacle, params.d0);
    }
    let sight = close.is_some && bee_in_view(o, close.value, state.avoiding);
    let pitch = consts.pitch;
    // Thrust toward the goal; without one, or while avoiding, level along the body axis.
    let h = bee_horizontal(o);
    let level = select(vec3<S>(S_ZERO, S_ZERO, S_ZERO), h.value, h.is_some);
    // The roll set-point, the angle that drives the sway, and the thrust direction.
    var roll: S;
    var sway: S;
    var thrust_dir: vec3<S>;
    if (sight) {
        roll = bee_avoidance_roll_deg(o, close.value.r_e, close.value.d, params.d0);
        sway = roll;
        thrust_dir = level;
    } else {
        roll = consts.roll;
        sway = bee_sway_deg(consts.roll);
        thrust_dir = select(level, heading.value, heading.is_some);
    }

    let sph = bee_interact_with(state.pos, frame, params, consts.kernels);
    let speed = geom_vec3_length(state.vel);
    let f_o = bee_oscillation_force(params, o, thrust_dir, speed, pitch, sway);
    let f_curl = bee_curl_force(state.pos, params.grid_edge, params.epsilon);
    let drag = geom_vec3_mul(state.vel, s_mul(params.mass, params.damping));
    let force = geom_vec3_sub(
        geom_vec3_add(
            geom_vec3_add(geom_vec3_mul(f_o, params.kappa1), geom_vec3_mul(f_curl, params.kappa2)),
            geom_vec3_mul(sph.force, params.kappa3),
        ),
        drag,
    );
    let accel = bee_div(force, params.mass);

    var u = geom_vec3_add(state.vel, geom_vec3_mul(accel, params.dt));
    var u0 = vec3<S>(S_ZERO, S_ZERO, S_ZERO);
    if (close.is_some) {
        u0 = u;
        u = bee_tune_velocity(u, close.value.normal, close.value.d, params.d0);
    }
    let velocity = bee_limit_speed(u, params.max_speed);

    let decision = BeeDecision(accel, velocity, s_deg(roll), s_deg(pitch), sight, sph.rho);
    let next = BeeState(
        bee_within_limit(geom_vec3_add(state.pos, geom_vec3_mul(velocity, params.dt))),
        velocity,
        o,
        sph.rho,
        decision.avoiding,
        u0,
        decision.roll,
        decision.pitch,
    );
    let e = bee_check_outputs(decision, next);
    if (e != BEE_OK) {
        return BeeStepResult(e, BeeDecision(), BeeState());
    }
    return BeeStepResult(BEE_OK, decision, next);
}

// within_limit: every coordinate limited to ±LIMIT, so the next state is a valid input.
fn bee_within_limit(p: vec3<S>) -> vec3<S> {
    let l = s_from_f32(BEE_LIMIT);
    let m = s_neg(l);
    return vec3<S>(s_clamp_to(p.x, m, l), s_clamp_to(p.y, m, l), s_clamp_to(p.z, m, l));
}

// div (step.rs): `v / k` component-wise.
fn bee_div(v: vec3<S>, k: S) -> vec3<S> {
    return vec3<S>(s_div(v.x, k), s_div(v.y, k), s_div(v.z, k));
}

// limit_speed: `u` scaled down to length `max_len` if longer.
fn bee_limit_speed(u: vec3<S>, max_len: S) -> vec3<S> {
    let len = geom_vec3_length(u);
    if (len > max_len) {
        return vec3<S>(
            s_mul(s_div(u.x, len), max_len),
            s_mul(s_div(u.y, len), max_len),
            s_mul(s_div(u.z, len), max_len),
        );
    }
    return u;
}

// check_outputs: every output finite (f32 overflow with extreme inputs; never for Fx).
fn bee_check_outputs(d: BeeDecision, next: BeeState) -> u32 {
    if (!geom_vec3_check(d.accel)) {
        return bee_error(BEE_ERROR_NON_FINITE, BEE_FIELD_DECISION_ACCEL);
    }
    if (!geom_vec3_check(d.velocity)) {
        return bee_error(BEE_ERROR_NON_FINITE, BEE_FIELD_DECISION_VELOCITY);
    }
    if (!geom_vec3_check(next.pos)) {
        return bee_error(BEE_ERROR_NON_FINITE, BEE_FIELD_DECISION_POS);
    }
    if (!s_is_finite(d.density)) {
        return bee_error(BEE_ERROR_NON_FINITE, BEE_FIELD_DECISION_DENSITY);
    }
    return BEE_OK;
}
