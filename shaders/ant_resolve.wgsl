// Phase 2 of an ant tick (host-sim/src/gpu/shaders.rs, ANT_RESOLVE): `swarm_core::ant::resolve`
// (core-nostd/src/ant/resolve.rs): collision avoidance (xiang2018 eq. 2-4) and the move
// (eq. 5), over the scalar `S`.

// W_MAX: the largest repulsion weight w_d of eq. 3 (ours).
const ANT_W_MAX: f32 = 1000.0f;

// Result<AntState<S>>: `status` 0 and the state, or the status word of the error.
struct AntResolveResult {
    status: u32,
    state: AntState,
}

// repulsion: the repulsion sum R_d(t+1) of eq. 3 for an ant predicted at `me`, from the
// frame's predicted positions of its neighbours: R_d = Σ_d w_d·R_d*, w_d = C / ‖p_d* − p*‖^k
// (limited to W_MAX), R_d* the unit vector from the d-th ant to this one (eq. 4 as the text
// defines it), over the ants closer than `collision_range`, in frame order; a neighbour
// predicted exactly at p* gives no direction and is skipped.
fn ant_repulsion(me: vec2<S>, frame: ptr<function, AntResolveFrame>, params: AntParams) -> vec2<S> {
    var sum = vec2<S>();
    for (var i = 0u; i < (*frame).neighbours_len; i = i + 1u) {
        let away = geom_sub(me, (*frame).neighbours[i]);
        let dist = geom_length(away);
        if (dist >= params.collision_range) {
            continue;
        }
        let unit = geom_normalized(away);
        if (unit.is_some) {
            let w = s_min(s_div(params.c, s_powi(dist, params.k)), s_from_f32(ANT_W_MAX));
            sum = geom_add(sum, geom_mul(unit.value, w));
        }
    }
    return sum;
}

// resolve_checked: phase 2 of the ant tick (xiang2018 §4.3, Algorithm 1 lines 4-5) with
// parameters validated beforehand (the plan and frame are checked):
// * eq. 2: O(t+1) = w0·O*(t+1) + (1 − w0)·R_d(t+1) (ant_repulsion for eq. 3-4), R_d limited to
//   unit length (ours), normalised (O* if the sum vanishes);
// * eq. 5: p(t+1) = p(t) + v·O(t+1)·Δt, clamped to the arena, then kept out of every
//   obstacle surface of the frame (ant_constrain; ours), O(t+1) then the direction of the move.
// A stopped ant does not move.
fn ant_resolve_checked(
    plan: AntPlan,
    frame: ptr<function, AntResolveFrame>,
    params: AntParams,
) -> AntResolveResult {
    var e = ant_state_validate(plan.state);
    if (e != ANT_OK) {
        return AntResolveResult(e, AntState());
    }
    e = ant_check_point(plan.predicted, ANT_FIELD_PLAN_PREDICTED);
    if (e != ANT_OK) {
        return AntResolveResult(e, AntState());
    }
    e = ant_resolve_frame_validate(frame);
    if (e != ANT_OK) {
        return AntResolveResult(e, AntState());
    }
    var s = plan.state;
    if (ant_state_is_stopped(s)) {
        return AntResolveResult(ANT_OK, s);
    }
    var r = ant_repulsion(plan.predicted, frame, params);
    // R_d enters eq. 2 as an orientation: a sum longer than one is limited to unit length.
    if (geom_length_sq(r) > S_ONE) {
        r = geom_normalized_or(r, r);
    }
    let blend = geom_add(geom_mul(s.heading, params.w0), geom_mul(r, s_sub(S_ONE, params.w0)));
    let o = geom_normalized_or(blend, s.heading);
    // A move that would leave the arena is clamped to it first, then kept out of the
    // obstacles.
    let bounds = (*frame).bounds;
    var step = geom_mul(o, s_mul(params.speed, params.dt));
    if (!geom_rect_contains(bounds, geom_add(s.pos, step))) {
        step = geom_sub(geom_rect_clamp(bounds, geom_add(s.pos, step)), s.pos);
    }
    var m = ant_constrain(s.pos, step, frame);
    if (!geom_rect_contains(bounds, geom_add(s.pos, m))) {
        // Sliding along a surface left the arena: stay (an ant that starts outside is
        // clamped).
        if (geom_rect_contains(bounds, s.pos)) {
            m = vec2<S>();
        } else {
            m = geom_sub(geom_rect_clamp(bounds, geom_add(s.pos, m)), s.pos);
        }
    }
    // The orientation is the way the ant actually moved (unchanged if it stayed).
    s.heading = geom_normalized_or(m, o);
    s.pos = geom_add(s.pos, m);
    return AntResolveResult(ANT_OK, s);
}
