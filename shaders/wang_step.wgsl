// The wang2014 controller (host-sim/src/gpu/shaders.rs, WANG_STEP): `swarm_core::wang`
// (core-nostd/src/wang/: `curl.rs`, `step.rs`, the validation of `frame.rs`), function by
// function over the scalar `S`, on the bee model's Perlin potential and Bridson ramp
// (bee_curl.wgsl, bee_vision.wgsl) as the Rust is, and the bee frame's number checks
// (bee_frame.wgsl: `bee_within`, `bee_check_vec`, the status words). In fixed point every result
// is the Rust's bit for bit (the GPU engine's tests compare them).

// ---- the values (frame.rs, params.rs) ----

// WangState: the position and the velocity of the last step.
struct WangState {
    pos: vec3<S>,
    vel: vec3<S>,
}

// Boundary: the nearest boundary surface of eq. 2 and the curvature of its distance field.
struct WangBoundary {
    point: vec3<S>,
    normal: vec3<S>,
    curvature: S,
    axis: vec3<S>,
}

// WangParams (validated on the host: `Checked`).
struct WangParams {
    scale: S,
    gain: S,
    s0: S,
    dt: S,
    d0: S,
    d_min: S,
    p_photo: S,
    u_photo: S,
    noise: u32,
}

// The advect frame: the navigation direction, the boundary if any, the lamp if any.
struct WangAdvectFrame {
    guide: vec3<S>,
    has_boundary: bool,
    boundary: WangBoundary,
    has_lamp: bool,
    lamp: vec3<S>,
}

// WIRE_WANG_NEIGHBOURS: the separate frame's capacity.
const WANG_NEIGHBOURS: u32 = 8u;

// The separate frame: up to WANG_NEIGHBOURS neighbours' ids and tentative positions.
struct WangSeparateFrame {
    ids: array<u32, 8>,
    pos: array<vec3<S>, 8>,
    len: u32,
}

// NOISE_PERLIN, NOISE_RANDOM (params.rs); anything else is the bounded curl noise.
const WANG_NOISE_PERLIN: u32 = 1u;
const WANG_NOISE_RANDOM: u32 = 2u;

// MAX_CURVATURE, MAX_GUIDE (frame.rs).
const WANG_MAX_CURVATURE: f32 = 100.0f;
const WANG_MAX_GUIDE: f32 = 1.01f;

// The random streams of the model (core-nostd/src/rand.rs, stream::WANG_*).
const RAND_WANG_PHOTO: u32 = 0x30u;
const RAND_WANG_NOISE_X: u32 = 0x31u;
const RAND_WANG_NOISE_Y: u32 = 0x32u;
const RAND_WANG_NOISE_Z: u32 = 0x33u;
const RAND_WANG_MDE: u32 = 0x34u;
const RAND_WANG_MDE_AZIMUTH: u32 = 0x35u;

// ---- status words (the encoding of bee_frame.wgsl; the field table FIELDS of
// host-sim/src/gpu/wang/layout.rs decodes them) ----

// Error::Inconsistent.
const WANG_ERROR_INCONSISTENT: u32 = 3u;

const WANG_FIELD_STATE_POS: u32 = 1u; // "state.pos"
const WANG_FIELD_STATE_VEL: u32 = 2u; // "state.vel"
const WANG_FIELD_FRAME_GUIDE: u32 = 3u; // "frame.guide"
const WANG_FIELD_FRAME_BOUNDARY_POINT: u32 = 4u; // "frame.boundary.point"
const WANG_FIELD_FRAME_BOUNDARY_NORMAL: u32 = 5u; // "frame.boundary.normal"
const WANG_FIELD_FRAME_BOUNDARY_CURVATURE: u32 = 6u; // "frame.boundary.curvature"
const WANG_FIELD_FRAME_BOUNDARY_AXIS: u32 = 7u; // "frame.boundary.axis"
const WANG_FIELD_FRAME_LAMP: u32 = 8u; // "frame.lamp"
const WANG_FIELD_MOVED_POS: u32 = 9u; // "moved.pos"
const WANG_FIELD_MOVED_VEL: u32 = 10u; // "moved.vel"
const WANG_FIELD_FRAME_NEIGHBOURS_POS: u32 = 11u; // "frame.neighbours.pos"
const WANG_FIELD_FRAME_NEIGHBOURS_ID: u32 = 12u; // "frame.neighbours.id"

// ---- validation (check.rs, frame.rs) ----

// check_length: check_vec, then a length within [lo, hi] (limits included; the callers convert
// them as the Rust does, `S::from_f32`).
fn wang_check_length(v: vec3<S>, lo: S, hi: S, field: u32) -> u32 {
    let e = bee_check_vec(v, field);
    if (e != BEE_OK) {
        return e;
    }
    let len = geom_vec3_length(v);
    if (len >= lo && len <= hi) {
        return BEE_OK;
    }
    return bee_error(BEE_ERROR_OUT_OF_RANGE, field);
}

// check_unit: a unit vector within 1 ± 1 %.
fn wang_check_unit(v: vec3<S>, field: u32) -> u32 {
    return wang_check_length(v, s_from_f32(0.99f), s_from_f32(1.01f), field);
}

// Vec3::check: NonFinite unless every component is finite.
fn wang_check_finite(v: vec3<S>, field: u32) -> u32 {
    if (geom_vec3_check(v)) {
        return BEE_OK;
    }
    return bee_error(BEE_ERROR_NON_FINITE, field);
}

// WangState::validate_as: both vectors finite and within the limit.
fn wang_state_validate(s: WangState, pos: u32, vel: u32) -> u32 {
    let e = bee_check_vec(s.pos, pos);
    if (e != BEE_OK) {
        return e;
    }
    return bee_check_vec(s.vel, vel);
}

// Boundary::validate.
fn wang_boundary_validate(b: WangBoundary) -> u32 {
    var e = bee_check_vec(b.point, WANG_FIELD_FRAME_BOUNDARY_POINT);
    if (e == BEE_OK) {
        e = wang_check_unit(b.normal, WANG_FIELD_FRAME_BOUNDARY_NORMAL);
    }
    if (e == BEE_OK) {
        // check_nonneg, then at most MAX_CURVATURE.
        e = bee_check_num(b.curvature, WANG_FIELD_FRAME_BOUNDARY_CURVATURE);
        if (e == BEE_OK && (b.curvature < S_ZERO
                            || b.curvature > s_from_f32(WANG_MAX_CURVATURE))) {
            e = bee_error(BEE_ERROR_OUT_OF_RANGE, WANG_FIELD_FRAME_BOUNDARY_CURVATURE);
        }
    }
    if (e == BEE_OK) {
        e = bee_check_vec(b.axis, WANG_FIELD_FRAME_BOUNDARY_AXIS);
    }
    if (e == BEE_OK && any(b.axis != vec3<S>())) {
        e = wang_check_unit(b.axis, WANG_FIELD_FRAME_BOUNDARY_AXIS);
    }
    return e;
}

// AdvectFrame::validate.
fn wang_advect_frame_validate(f: WangAdvectFrame) -> u32 {
    var e = wang_check_length(f.guide, s_from_f32(0.0f), s_from_f32(WANG_MAX_GUIDE),
                              WANG_FIELD_FRAME_GUIDE);
    if (e == BEE_OK && f.has_boundary) {
        e = wang_boundary_validate(f.boundary);
    }
    if (e == BEE_OK && f.has_lamp) {
        e = bee_check_vec(f.lamp, WANG_FIELD_FRAME_LAMP);
    }
    return e;
}

// SeparateFrame::validate: every position within the limit, no id twice (errors at the entry).
fn wang_separate_frame_validate(f: ptr<function, WangSeparateFrame>) -> u32 {
    for (var i = 0u; i < (*f).len; i = i + 1u) {
        let e = bee_check_vec((*f).pos[i], WANG_FIELD_FRAME_NEIGHBOURS_POS);
        if (e != BEE_OK) {
            return bee_error_at(e, i);
        }
        for (var j = 0u; j < i; j = j + 1u) {
            if ((*f).ids[j] == (*f).ids[i]) {
                return bee_error_at(bee_error(WANG_ERROR_INCONSISTENT, WANG_FIELD_FRAME_NEIGHBOURS_ID), i);
            }
        }
    }
    return BEE_OK;
}

// ---- the local velocity (curl.rs) ----

// ramp_slope: α'(r) = 15/8·(r² − 1)².
fn wang_ramp_slope(r: S) -> S {
    let u = s_sub(s_mul(r, r), S_ONE);
    return s_mul(s_mul(s_from_f32(1.875f), u), u);
}

// curl_noise: V_l = a (∇ × P) + ∇a × P + (1 − a)(J_Pᵀ n + H_d P) × n (eq. 1-3, closed form).
fn wang_curl_noise(pos: vec3<S>, scale: S, gain: S, d0: S, has_b: bool, b: WangBoundary)
    -> vec3<S> {
    if (!has_b) {
        return bee_curl_force(pos, scale, gain);
    }
    let nn = geom_vec3_normalized(b.normal);
    let n = select(b.normal, nn.value, nn.is_some);
    let d = s_max(geom_vec3_dot(geom_vec3_sub(pos, b.point), n), S_ZERO);
    if (d >= d0) {
        return bee_curl_force(pos, scale, gain);
    }
    let r = s_div(d, d0);
    let a = bee_ramp(r);
    let grad_a = geom_vec3_mul(n, s_div(wang_ramp_slope(r), d0));
    let pot = bee_potential(pos, scale, gain);
    let p = vec3<S>(pot.x.value, pot.y.value, pot.z.value);
    let curl = vec3<S>(
        s_sub(pot.z.grad.y, pot.y.grad.z),
        s_sub(pot.x.grad.z, pot.z.grad.x),
        s_sub(pot.y.grad.x, pot.x.grad.y),
    );
    let jtn = geom_vec3_add(
        geom_vec3_add(geom_vec3_mul(pot.x.grad, n.x), geom_vec3_mul(pot.y.grad, n.y)),
        geom_vec3_mul(pot.z.grad, n.z),
    );
    let hp = geom_vec3_mul(
        geom_vec3_sub(
            geom_vec3_sub(p, geom_vec3_mul(n, geom_vec3_dot(n, p))),
            geom_vec3_mul(b.axis, geom_vec3_dot(b.axis, p)),
        ),
        b.curvature,
    );
    return geom_vec3_add(
        geom_vec3_add(geom_vec3_mul(curl, a), geom_vec3_cross(grad_a, p)),
        geom_vec3_mul(geom_vec3_cross(geom_vec3_add(jtn, hp), n), s_sub(S_ONE, a)),
    );
}

// perlin_velocity: the Perlin vector P itself.
fn wang_perlin_velocity(pos: vec3<S>, scale: S, gain: S) -> vec3<S> {
    let pot = bee_potential(pos, scale, gain);
    return vec3<S>(pot.x.value, pot.y.value, pot.z.value);
}

// random_velocity: a uniform vector in [−gain, gain]³.
fn wang_random_draw(c: StepCtx, stream: u32, gain: S) -> S {
    let u = rand_unit(c.seed, c.agent, c.step, stream);
    return s_mul(s_sub(s_add(u, u), S_ONE), gain);
}

fn wang_random_velocity(gain: S, c: StepCtx) -> vec3<S> {
    return vec3<S>(
        wang_random_draw(c, RAND_WANG_NOISE_X, gain),
        wang_random_draw(c, RAND_WANG_NOISE_Y, gain),
        wang_random_draw(c, RAND_WANG_NOISE_Z, gain),
    );
}

// noise_velocity: V_l from the source the parameters select.
fn wang_noise_velocity(pos: vec3<S>, has_b: bool, b: WangBoundary, p: WangParams, c: StepCtx)
    -> vec3<S> {
    if (p.noise == WANG_NOISE_PERLIN) {
        return wang_perlin_velocity(pos, p.scale, p.gain);
    }
    if (p.noise == WANG_NOISE_RANDOM) {
        return wang_random_velocity(p.gain, c);
    }
    return wang_curl_noise(pos, p.scale, p.gain, p.d0, has_b, b);
}

// ---- the two phases (step.rs) ----

// A phase's result: the status word (0: Ok), the state, and how many neighbours pushed.
struct WangResult {
    status: u32,
    state: WangState,
    pushes: u32,
}

// advect_checked: V = V_l + s0·guide (eq. 9), the phototaxis bias, x* = x + V·Δt.
fn wang_advect_checked(s: WangState, f: WangAdvectFrame, p: WangParams, c: StepCtx)
    -> WangResult {
    var e = wang_state_validate(s, WANG_FIELD_STATE_POS, WANG_FIELD_STATE_VEL);
    if (e == BEE_OK) {
        e = wang_advect_frame_validate(f);
    }
    if (e != BEE_OK) {
        return WangResult(e, s, 0u);
    }
    var v = geom_vec3_add(
        wang_noise_velocity(s.pos, f.has_boundary, f.boundary, p, c),
        geom_vec3_mul(f.guide, p.s0),
    );
    if (f.has_lamp && rand_chance(c.seed, c.agent, c.step, RAND_WANG_PHOTO, p.p_photo)) {
        let toward = geom_vec3_normalized(geom_vec3_sub(f.lamp, s.pos));
        if (toward.is_some) {
            v = geom_vec3_add(v, geom_vec3_mul(toward.value, p.u_photo));
        }
    }
    let moved = WangState(geom_vec3_add(s.pos, geom_vec3_mul(v, p.dt)), v);
    e = wang_check_finite(moved.pos, WANG_FIELD_MOVED_POS);
    if (e == BEE_OK) {
        e = wang_check_finite(moved.vel, WANG_FIELD_MOVED_VEL);
    }
    return WangResult(e, moved, 0u);
}

// pair_direction: the uniform unit vector that splits a coincident pair.
fn wang_pair_direction(seed: u32, lower: u32, step: u32) -> vec3<S> {
    let h = rand_unit(seed, lower, step, RAND_WANG_MDE);
    let z = s_sub(s_add(h, h), S_ONE);
    let phi = rand_angle(seed, lower, step, RAND_WANG_MDE_AZIMUTH, S_PI);
    let r = s_sqrt(s_max(s_sub(S_ONE, s_mul(z, z)), S_ZERO));
    let sc = s_sin_cos(phi);
    return vec3<S>(s_mul(r, sc.y), z, s_mul(r, sc.x));
}

// separate_checked: minimum distance enforcement (§6), Jacobi, pushes summed in id order.
fn wang_separate_checked(moved: WangState, f: ptr<function, WangSeparateFrame>, p: WangParams,
                         c: StepCtx) -> WangResult {
    var e = wang_state_validate(moved, WANG_FIELD_MOVED_POS, WANG_FIELD_MOVED_VEL);
    if (e == BEE_OK) {
        e = wang_separate_frame_validate(f);
    }
    if (e != BEE_OK) {
        return WangResult(e, moved, 0u);
    }
    let d_min = p.d_min;
    if (d_min <= S_ZERO) {
        return WangResult(BEE_OK, moved, 0u);
    }
    var ids: array<u32, 8>;
    var pushes: array<vec3<S>, 8>;
    var n = 0u;
    for (var i = 0u; i < (*f).len; i = i + 1u) {
        let id = (*f).ids[i];
        if (id == c.agent) {
            continue;
        }
        let diff = geom_vec3_sub(moved.pos, (*f).pos[i]);
        if (!(bee_within(diff.x, d_min) && bee_within(diff.y, d_min)
              && bee_within(diff.z, d_min))) {
            continue;
        }
        let d = geom_vec3_length(diff);
        if (d >= d_min) {
            continue;
        }
        var apart = GeomOptionVec3(false, vec3<S>());
        if (!(s_mul(d, s_from_i32(1024)) < d_min)) {
            apart = geom_vec3_normalized(diff);
        }
        var u = apart.value;
        if (!apart.is_some) {
            u = wang_pair_direction(c.seed, min(c.agent, id), c.step);
            if (c.agent > id) {
                u = geom_vec3_neg(u);
            }
        }
        let push = geom_vec3_mul(u, s_mul(s_sub(d_min, d), s_from_f32(0.5f)));
        var at = n;
        while (at > 0u && ids[at - 1u] > id) {
            ids[at] = ids[at - 1u];
            pushes[at] = pushes[at - 1u];
            at = at - 1u;
        }
        ids[at] = id;
        pushes[at] = push;
        n = n + 1u;
    }
    var pos = moved.pos;
    for (var k = 0u; k < n; k = k + 1u) {
        pos = geom_vec3_add(pos, pushes[k]);
    }
    return WangResult(BEE_OK, WangState(pos, moved.vel), n);
}
