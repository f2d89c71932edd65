// The ant's own state (host-sim/src/gpu/shaders.rs, ANT_STATE): `swarm_core::ant::state`
// (core-nostd/src/ant/state.rs, xiang2018 §4), over the scalar `S`, and the status words with
// which the ant kernels report the `swarm_core::Error` a Rust function returns.
//
// An `Option` field is a flag and a value (`has_goal`, `goal`); the value means nothing when the
// flag is false (ant_layout.wgsl writes it as zero words). The enums are their Rust
// discriminants (`Label::Food as u32`, ...).

// Label (the status label S_c, §4).
const ANT_LABEL_NOTHING: u32 = 0u;
const ANT_LABEL_FOOD: u32 = 1u;
const ANT_LABEL_NEST: u32 = 2u;

// MotionState (§4, Fig. 4a).
const ANT_MOTION_STOP: u32 = 0u;
const ANT_MOTION_BASIC_MOVEMENT: u32 = 1u;
const ANT_MOTION_INTERACT_NEIGHBORS: u32 = 2u;
const ANT_MOTION_INTERACT_ENVIRONMENT: u32 = 3u;

// StopReason (§4.1).
const ANT_STOP_CASUAL: u32 = 0u;
const ANT_STOP_COLLECTING_FOOD: u32 = 1u;
const ANT_STOP_DROPPING_FOOD: u32 = 2u;

// Turn (which way round an obstacle).
const ANT_TURN_CCW: u32 = 0u;
const ANT_TURN_CW: u32 = 1u;

// WINDING_LIMIT: the largest winding of a Follow (quarter turns).
const ANT_WINDING_LIMIT: f32 = 16.0f;
// COORD_LIMIT: the largest absolute coordinate accepted from outside.
const ANT_COORD_LIMIT: f32 = 16384.0f;

// StopTimer: a running stop (§4.1); `remaining` and `place` are u16 in Rust.
struct AntStopTimer {
    reason: u32,
    remaining: u32,
    place: u32,
}

// Follow<S>: an ant going round an obstacle (its way round, and its winding in quarter turns).
struct AntFollow {
    turn: u32,
    winding: S,
}

// AntState<S>: everything an ant carries from one tick to the next (`nest`, `origin` are u16).
struct AntState {
    pos: vec2<S>,
    heading: vec2<S>,
    label: u32,
    nest: u32,
    origin: u32,
    arrival: vec2<S>,
    has_goal: bool,
    goal: vec2<S>,
    has_follow: bool,
    follow: AntFollow,
    motion: u32,
    has_stop: bool,
    stop: AntStopTimer,
}

// ---- status words: the `swarm_core::Error` of a refused input ----
//
// 0 is Ok; else `kind | field << 8 | (index + 1) << 16`: the Error variant (`ANT_ERROR_*`), the
// field it names (`ANT_FIELD_*`, the table `FIELDS` of host-sim/src/gpu/ant/layout.rs, which
// decodes a status word into the `Error`), and its list index if it has one (0: none).

const ANT_OK: u32 = 0u;
// Error::NonFinite, Error::OutOfRange, Error::Inconsistent.
const ANT_ERROR_NON_FINITE: u32 = 1u;
const ANT_ERROR_OUT_OF_RANGE: u32 = 2u;
const ANT_ERROR_INCONSISTENT: u32 = 3u;

// The fields an ant controller names in its errors.
const ANT_FIELD_STATE_POS: u32 = 1u; // "state.pos"
const ANT_FIELD_STATE_ARRIVAL: u32 = 2u; // "state.arrival"
const ANT_FIELD_STATE_HEADING: u32 = 3u; // "state.heading"
const ANT_FIELD_STATE_ORIGIN: u32 = 4u; // "state.origin"
const ANT_FIELD_STATE_GOAL: u32 = 5u; // "state.goal"
const ANT_FIELD_STATE_FOLLOW: u32 = 6u; // "state.follow"
const ANT_FIELD_STATE_FOLLOW_WINDING: u32 = 7u; // "state.follow.winding"
const ANT_FIELD_STATE_STOP_REMAINING: u32 = 8u; // "state.stop.remaining"
const ANT_FIELD_STATE_STOP_REASON: u32 = 9u; // "state.stop.reason"
const ANT_FIELD_STATE_STOP: u32 = 10u; // "state.stop"
const ANT_FIELD_BOUNDS: u32 = 11u; // "bounds"
const ANT_FIELD_NEIGHBOURS_POS: u32 = 12u; // "neighbours.pos"
const ANT_FIELD_NEIGHBOURS_ARRIVAL: u32 = 13u; // "neighbours.arrival"
const ANT_FIELD_NEIGHBOURS_ID: u32 = 14u; // "neighbours.id"
const ANT_FIELD_NEIGHBOURS_ORIGIN: u32 = 15u; // "neighbours.origin"
const ANT_FIELD_OBJECTS_CLOSEST: u32 = 16u; // "objects.closest"
const ANT_FIELD_OBJECTS_NORMAL: u32 = 17u; // "objects.normal"
const ANT_FIELD_OBJECTS_CENTER: u32 = 18u; // "objects.center"
const ANT_FIELD_OBJECTS_RADIUS: u32 = 19u; // "objects.radius"
const ANT_FIELD_NEIGHBOURS: u32 = 20u; // "neighbours"
const ANT_FIELD_OBSTACLES_CLOSEST: u32 = 21u; // "obstacles.closest"
const ANT_FIELD_OBSTACLES_NORMAL: u32 = 22u; // "obstacles.normal"
const ANT_FIELD_PLAN_PREDICTED: u32 = 23u; // "plan.predicted"

// Error::non_finite(field), out_of_range(field), inconsistent(field), as a status word.
fn ant_error(kind: u32, field: u32) -> u32 {
    return kind | (field << 8u);
}

// Error::at: the same error pinned to entry `i` of a list field (Ok stays Ok).
fn ant_error_at(status: u32, i: u32) -> u32 {
    if (status == ANT_OK) {
        return ANT_OK;
    }
    return (status & 0xffffu) | ((min(i, 0xfffeu) + 1u) << 16u);
}

// ---- state.rs ----

// AntState::is_stopped: whether the ant stands still this tick.
fn ant_state_is_stopped(s: AntState) -> bool {
    return s.has_stop;
}

// check_point (state.rs): Err unless `p` is finite and inside ±COORD_LIMIT.
fn ant_check_point(p: vec2<S>, field: u32) -> u32 {
    let lim = s_from_f32(ANT_COORD_LIMIT);
    // NaN fails the comparison too; which error it is, is worked out off the hot path.
    if (s_abs(p.x) <= lim && s_abs(p.y) <= lim) {
        return ANT_OK;
    }
    if (!geom_check(p)) {
        return ant_error(ANT_ERROR_NON_FINITE, field);
    }
    return ant_error(ANT_ERROR_OUT_OF_RANGE, field);
}

// check_range (state.rs): Err unless `v` is finite and within [lo, hi].
fn ant_check_range(v: S, lo: S, hi: S, field: u32) -> u32 {
    if (!s_is_finite(v)) {
        return ant_error(ANT_ERROR_NON_FINITE, field);
    }
    if (v < lo || v > hi) {
        return ant_error(ANT_ERROR_OUT_OF_RANGE, field);
    }
    return ANT_OK;
}

// AntState::validate: finite coordinates inside COORD_LIMIT, a unit heading (±1 %),
// consistent label/origin and stop fields.
fn ant_state_validate(s: AntState) -> u32 {
    var e = ant_check_point(s.pos, ANT_FIELD_STATE_POS);
    if (e != ANT_OK) {
        return e;
    }
    e = ant_check_point(s.arrival, ANT_FIELD_STATE_ARRIVAL);
    if (e != ANT_OK) {
        return e;
    }
    // |heading| in (0.99, 1.01), compared squared; a NaN or infinite component fails too.
    let l2 = geom_length_sq(s.heading);
    if (!(l2 > s_from_f32(0.9801f) && l2 < s_from_f32(1.0201f))) {
        if (!geom_check(s.heading)) {
            return ant_error(ANT_ERROR_NON_FINITE, ANT_FIELD_STATE_HEADING);
        }
        return ant_error(ANT_ERROR_OUT_OF_RANGE, ANT_FIELD_STATE_HEADING);
    }
    if (s.label == ANT_LABEL_NEST && s.origin != s.nest) {
        return ant_error(ANT_ERROR_INCONSISTENT, ANT_FIELD_STATE_ORIGIN);
    }
    if (s.has_goal) {
        e = ant_check_point(s.goal, ANT_FIELD_STATE_GOAL);
        if (e != ANT_OK) {
            return e;
        }
    }
    if (s.has_follow) {
        if (!s.has_goal) {
            return ant_error(ANT_ERROR_INCONSISTENT, ANT_FIELD_STATE_FOLLOW);
        }
        let lim = s_from_f32(ANT_WINDING_LIMIT);
        e = ant_check_range(s.follow.winding, s_neg(lim), lim, ANT_FIELD_STATE_FOLLOW_WINDING);
        if (e != ANT_OK) {
            return e;
        }
    }
    if (s.motion == ANT_MOTION_STOP) {
        if (!s.has_stop) {
            return ant_error(ANT_ERROR_INCONSISTENT, ANT_FIELD_STATE_STOP);
        }
        if (s.stop.remaining == 0u) {
            return ant_error(ANT_ERROR_OUT_OF_RANGE, ANT_FIELD_STATE_STOP_REMAINING);
        }
        if (s.stop.reason == ANT_STOP_COLLECTING_FOOD && s.label == ANT_LABEL_FOOD) {
            return ant_error(ANT_ERROR_INCONSISTENT, ANT_FIELD_STATE_STOP_REASON);
        }
        if (s.stop.reason == ANT_STOP_DROPPING_FOOD
            && (s.label != ANT_LABEL_FOOD || s.stop.place != s.nest)) {
            return ant_error(ANT_ERROR_INCONSISTENT, ANT_FIELD_STATE_STOP_REASON);
        }
        return ANT_OK;
    }
    if (s.has_stop) {
        return ant_error(ANT_ERROR_INCONSISTENT, ANT_FIELD_STATE_STOP);
    }
    return ANT_OK;
}
