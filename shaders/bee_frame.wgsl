// The bee's state, its sensor frame and its decision, with input validation
// (host-sim/src/gpu/shaders.rs, BEE_FRAME): `swarm_core::bee::frame` (core-nostd/src/bee/frame.rs),
// over the scalar `S`, with the simulator's capacities (host_sim::bees::sense::{N, P}, the
// wire's), and the status words with which the bee kernels report the `swarm_core::Error` a Rust
// function returns. World axes: y is up (chen eq. 7).
//
// A heapless `Vec` is a fixed array and its length (`neighbours_len`, ...; the entries past the
// length mean nothing); an `Option` a flag and a value (`has_goal`, `goal`; the value means
// nothing when the flag is false).

// WIRE_BEE_NEIGHBOURS (host_sim::bees::N): neighbours in a frame.
const BEE_NEIGHBOURS: u32 = 16u;
// WIRE_BEE_TARGETS (host_sim::bees::P): target particles in a frame.
const BEE_TARGETS: u32 = 16u;

// BeeState<S>: what a bee carries from one step to the next.
struct BeeState {
    // Position r of the mass point.
    pos: vec3<S>,
    // Velocity u.
    vel: vec3<S>,
    // Last forward vector o (need not be normalized).
    forward: vec3<S>,
    // Density ρ_i of eq. 10 from the last step.
    density: S,
    // Whether the bee was avoiding an obstacle at the last step (§IV-B).
    avoiding: bool,
    // u_0 of eq. 5: the velocity eq. 5 tuned at the last step.
    u0: vec3<S>,
    // Last roll and pitch set-points (rad).
    roll: S,
    pitch: S,
}

// BeeNeighbor<S>: a neighbour as it broadcast itself.
struct BeeNeighbor {
    pos: vec3<S>,
    vel: vec3<S>,
    density: S,
}

// ObstacleSense<S>: what the bee sees of the nearest obstacle (§IV-B, Fig. 3b): the closest
// surface point p_e and the outward unit normal there.
struct BeeObstacleSense {
    point: vec3<S>,
    normal: vec3<S>,
}

// BeeFrame<S, N, P>: one step's sensor input.
struct BeeFrame {
    // Time t in seconds (eq. 3-4): the bee's own clock.
    t: S,
    neighbours_len: u32,
    neighbours: array<BeeNeighbor, BEE_NEIGHBOURS>,
    // Virtual static particles sampled on a target (§V-B).
    targets_len: u32,
    targets: array<vec3<S>, BEE_TARGETS>,
    // The target the bee flies toward (§V-B), if any.
    has_goal: bool,
    goal: vec3<S>,
    // The nearest obstacle, if one is sensed.
    has_obstacle: bool,
    obstacle: BeeObstacleSense,
}

// BeeDecision<S>: the outcome of one step.
struct BeeDecision {
    // Acceleration a = F/m (eq. 1, with the drag).
    accel: vec3<S>,
    // Velocity set-point u*.
    velocity: vec3<S>,
    // Roll and pitch set-points (rad).
    roll: S,
    pitch: S,
    // Whether the bee is avoiding an obstacle (§IV-B).
    avoiding: bool,
    // The new density ρ_i (eq. 10), to broadcast.
    density: S,
}

// ---- status words: the `swarm_core::Error` of a refused input ----
//
// 0 is Ok; else `kind | field << 8 | (index + 1) << 16`: the Error variant (`BEE_ERROR_*`), the
// field it names (`BEE_FIELD_*`, the table `FIELDS` of host-sim/src/gpu/bee/layout.rs, which
// decodes a status word into the `Error`), and its list index if it has one (0: none).

const BEE_OK: u32 = 0u;
// Error::NonFinite, Error::OutOfRange.
const BEE_ERROR_NON_FINITE: u32 = 1u;
const BEE_ERROR_OUT_OF_RANGE: u32 = 2u;

// The fields the bee controller names in its errors.
const BEE_FIELD_STATE_POS: u32 = 1u; // "state.pos"
const BEE_FIELD_STATE_VEL: u32 = 2u; // "state.vel"
const BEE_FIELD_STATE_FORWARD: u32 = 3u; // "state.forward"
const BEE_FIELD_STATE_DENSITY: u32 = 4u; // "state.density"
const BEE_FIELD_STATE_U0: u32 = 5u; // "state.u0"
const BEE_FIELD_STATE_ROLL: u32 = 6u; // "state.roll"
const BEE_FIELD_STATE_PITCH: u32 = 7u; // "state.pitch"
const BEE_FIELD_FRAME_T: u32 = 8u; // "frame.t"
const BEE_FIELD_FRAME_NEIGHBOURS_POS: u32 = 9u; // "frame.neighbours.pos"
const BEE_FIELD_FRAME_NEIGHBOURS_VEL: u32 = 10u; // "frame.neighbours.vel"
const BEE_FIELD_FRAME_NEIGHBOURS_DENSITY: u32 = 11u; // "frame.neighbours.density"
const BEE_FIELD_FRAME_TARGETS: u32 = 12u; // "frame.targets"
const BEE_FIELD_FRAME_GOAL: u32 = 13u; // "frame.goal"
const BEE_FIELD_FRAME_OBSTACLE_POINT: u32 = 14u; // "frame.obstacle.point"
const BEE_FIELD_FRAME_OBSTACLE_NORMAL: u32 = 15u; // "frame.obstacle.normal"
const BEE_FIELD_DECISION_ACCEL: u32 = 16u; // "decision.accel"
const BEE_FIELD_DECISION_VELOCITY: u32 = 17u; // "decision.velocity"
const BEE_FIELD_DECISION_POS: u32 = 18u; // "decision.pos"
const BEE_FIELD_DECISION_DENSITY: u32 = 19u; // "decision.density"

// Error::non_finite(field), out_of_range(field), as a status word.
fn bee_error(kind: u32, field: u32) -> u32 {
    return kind | (field << 8u);
}

// Error::at: the same error pinned to entry `i` of a list field (Ok stays Ok).
fn bee_error_at(status: u32, i: u32) -> u32 {
    if (status == BEE_OK) {
        return BEE_OK;
    }
    return (status & 0xffffu) | ((min(i, 0xfffeu) + 1u) << 16u);
}

// ---- validation (frame.rs) ----

// within: |v| ≤ l (false for NaN); for f32 through the sign-clearing `f32::abs`, as `s_abs`.
fn bee_within(v: S, l: S) -> bool {
    return s_abs(v) <= l;
}

// check_num: Err unless `v` is finite and |v| ≤ LIMIT.
fn bee_check_num(v: S, field: u32) -> u32 {
    // Fast path: NaN fails the comparisons, and an infinity exceeds the limit.
    if (bee_within(v, s_from_f32(BEE_LIMIT))) {
        return BEE_OK;
    }
    if (!s_is_finite(v)) {
        return bee_error(BEE_ERROR_NON_FINITE, field);
    }
    return bee_error(BEE_ERROR_OUT_OF_RANGE, field);
}

// check_vec: check_num on every component (a non-finite component is reported before an
// out-of-range one: `v.check(field)?` first, after which every component is finite).
fn bee_check_vec(v: vec3<S>, field: u32) -> u32 {
    let l = s_from_f32(BEE_LIMIT);
    if (bee_within(v.x, l) && bee_within(v.y, l) && bee_within(v.z, l)) {
        return BEE_OK;
    }
    if (!geom_vec3_check(v)) {
        return bee_error(BEE_ERROR_NON_FINITE, field);
    }
    return bee_error(BEE_ERROR_OUT_OF_RANGE, field);
}

// check_density: check_num and v ≥ 0.
fn bee_check_density(v: S, field: u32) -> u32 {
    let e = bee_check_num(v, field);
    if (e != BEE_OK) {
        return e;
    }
    if (v < S_ZERO) {
        return bee_error(BEE_ERROR_OUT_OF_RANGE, field);
    }
    return BEE_OK;
}

// BeeState::validate: every field finite, within ±LIMIT, density ≥ 0.
fn bee_state_validate(s: BeeState) -> u32 {
    var e = bee_check_vec(s.pos, BEE_FIELD_STATE_POS);
    if (e != BEE_OK) {
        return e;
    }
    e = bee_check_vec(s.vel, BEE_FIELD_STATE_VEL);
    if (e != BEE_OK) {
        return e;
    }
    e = bee_check_vec(s.forward, BEE_FIELD_STATE_FORWARD);
    if (e != BEE_OK) {
        return e;
    }
    e = bee_check_density(s.density, BEE_FIELD_STATE_DENSITY);
    if (e != BEE_OK) {
        return e;
    }
    e = bee_check_vec(s.u0, BEE_FIELD_STATE_U0);
    if (e != BEE_OK) {
        return e;
    }
    e = bee_check_num(s.roll, BEE_FIELD_STATE_ROLL);
    if (e != BEE_OK) {
        return e;
    }
    return bee_check_num(s.pitch, BEE_FIELD_STATE_PITCH);
}

// BeeFrame::validate: finite numbers within ±LIMIT, t ≥ 0, densities ≥ 0, a unit normal
// (±1 %); list errors carry the entry's index.
fn bee_frame_validate(frame: ptr<function, BeeFrame>) -> u32 {
    let t = (*frame).t;
    var e = bee_check_num(t, BEE_FIELD_FRAME_T);
    if (e != BEE_OK) {
        return e;
    }
    if (t < S_ZERO) {
        return bee_error(BEE_ERROR_OUT_OF_RANGE, BEE_FIELD_FRAME_T);
    }
    // The neighbours, then the target particles, in one loop (one copy of the checks in the
    // kernel).
    for (var j = 0u; j < BEE_NEIGHBOURS + BEE_TARGETS; j = j + 1u) {
        if (j < BEE_NEIGHBOURS) {
            if (j < (*frame).neighbours_len) {
                let nb = (*frame).neighbours[j];
                e = bee_check_vec(nb.pos, BEE_FIELD_FRAME_NEIGHBOURS_POS);
                if (e == BEE_OK) {
                    e = bee_check_vec(nb.vel, BEE_FIELD_FRAME_NEIGHBOURS_VEL);
                }
                if (e == BEE_OK) {
                    e = bee_check_density(nb.density, BEE_FIELD_FRAME_NEIGHBOURS_DENSITY);
                }
                e = bee_error_at(e, j);
            }
        } else if (j - BEE_NEIGHBOURS < (*frame).targets_len) {
            let i = j - BEE_NEIGHBOURS;
            e = bee_error_at(bee_check_vec((*frame).targets[i], BEE_FIELD_FRAME_TARGETS), i);
        }
        if (e != BEE_OK) {
            return e;
        }
    }
    if ((*frame).has_goal) {
        e = bee_check_vec((*frame).goal, BEE_FIELD_FRAME_GOAL);
        if (e != BEE_OK) {
            return e;
        }
    }
    if ((*frame).has_obstacle) {
        let ob = (*frame).obstacle;
        e = bee_check_vec(ob.point, BEE_FIELD_FRAME_OBSTACLE_POINT);
        if (e != BEE_OK) {
            return e;
        }
        e = bee_check_vec(ob.normal, BEE_FIELD_FRAME_OBSTACLE_NORMAL);
        if (e != BEE_OK) {
            return e;
        }
        let len = geom_vec3_length(ob.normal);
        if (!(len >= s_from_f32(0.99f) && len <= s_from_f32(1.01f))) {
            return bee_error(BEE_ERROR_OUT_OF_RANGE, BEE_FIELD_FRAME_OBSTACLE_NORMAL);
        }
    }
    return BEE_OK;
}
