// The ren2016 insect (host-sim/src/gpu/shaders.rs, FLY_STEP): `swarm_core::fly`
// (core-nostd/src/fly/: `frame.rs`'s validation, `force.rs`, `step.rs`) and the 3D ORCA it
// hands its preferred velocity to (core-nostd/src/orca3d/: `plane.rs`, `lp.rs`, `solve`),
// function by function over the scalar `S`. The noise reuses the bee model's Perlin potential
// and curl (bee_curl.wgsl), the number checks the bee frame's (bee_frame.wgsl: `bee_check_vec`,
// the status words) and the unit check wang's (wang_step.wgsl: `wang_check_unit`, `check_unit`
// of check.rs). In fixed point every result is the Rust's bit for bit (the GPU engine's tests
// compare them).
//
// Loops (lavapipe stops an invocation after 65,535 loop iterations, nested loops and called
// functions counted together): LP3 over at most 16 planes, each violated plane an LP2 over the
// planes before it, each violated one an LP1 over those before it; LP4 an LP3 of its projected
// planes per plane violated by more than the current penetration. A program of 16 planes each
// violating every earlier one would cost about 50,000 iterations; real frames cost far fewer.

// ---- the values (frame.rs, params.rs) ----

// WIRE_FLY_NEIGHBOURS, WIRE_FLY_SURFACES (core-nostd/src/fly/wire.rs): the frame's capacities,
// and so the ORCA program's (`solve::<S, N>`: at most N planes).
const FLY_NEIGHBOURS: u32 = 16u;
const FLY_SURFACES: u32 = 4u;

// STIMULUS_TARGET, STIMULUS_PREDATOR (frame.rs).
const FLY_STIMULUS_TARGET: u32 = 0u;
const FLY_STIMULUS_PREDATOR: u32 = 1u;

// NOISE_CURL, NOISE_PERLIN, NOISE_WHITE, NOISE_GAUSSIAN (params.rs); NOISE_NONE (4) and
// anything else is no noise.
const FLY_NOISE_CURL: u32 = 0u;
const FLY_NOISE_PERLIN: u32 = 1u;
const FLY_NOISE_WHITE: u32 = 2u;
const FLY_NOISE_GAUSSIAN: u32 = 3u;
// FALLBACK_LP4 (params.rs); anything else is FALLBACK_STOP, zero velocity.
const FLY_FALLBACK_LP4: u32 = 1u;

// The random streams of the model (core-nostd/src/rand.rs, stream::FLY_*).
const RAND_FLY_ESCAPE: u32 = 0x40u;
const RAND_FLY_NOISE_X: u32 = 0x41u;
const RAND_FLY_NOISE_Y: u32 = 0x42u;
const RAND_FLY_NOISE_Z: u32 = 0x43u;

// FlyState::validate's bound on escape_theta: `FRAC_PI_2 + 1e-3` in f32.
const FLY_THETA_LIMIT: f32 = 1.5717964f;
// RVO_EPSILON (lp.rs): the threshold of the parallelism tests.
const FLY_RVO_EPSILON: f32 = 0.00001f;
// The Irwin–Hall sum's scale √(3/4) (force.rs, `noise_force`).
const FLY_GAUSS_NORM: f32 = 0.8660254f;

// FlyState: what an insect carries from one step to the next.
struct FlyState {
    pos: vec3<S>,
    vel: vec3<S>,
    escape_theta: S,
    escaping: bool,
}

// Neighbour: a neighbour within r_att as the insect senses it.
struct FlyNeighbour {
    id: u32,
    pos: vec3<S>,
    vel: vec3<S>,
}

// Surface (orca3d): a surface's closest point and outward unit normal.
struct FlySurface {
    point: vec3<S>,
    normal: vec3<S>,
}

// FlyFrame<S, 16, 4>: a heapless Vec is an array and its length, the Option a flag.
struct FlyFrame {
    neighbours: array<FlyNeighbour, 16>,
    neighbours_len: u32,
    has_stimulus: bool,
    stimulus_pos: vec3<S>,
    stimulus_kind: u32,
    surfaces: array<FlySurface, 4>,
    surfaces_len: u32,
}

// FlyParams (validated on the host: `Checked`).
struct FlyParams {
    gamma: S,
    scale: S,
    gain: S,
    chi_rep: S,
    r_rep: S,
    chi_ali: S,
    r_ali: S,
    chi_att: S,
    r_att: S,
    chi_res: S,
    r_res: S,
    dt: S,
    radius: S,
    margin: S,
    tau: S,
    max_speed: S,
    orca_neighbours: u32,
    noise: u32,
    fallback: u32,
    escape_sides: u32,
}

// What a step gives: the status word (0: Ok), the next state, the decision (pref, infeasible).
struct FlyResult {
    status: u32,
    next: FlyState,
    pref: vec3<S>,
    infeasible: bool,
}

// FlyParams::orca_radius: radius·(1 + margin).
fn fly_orca_radius(p: FlyParams) -> S {
    return s_mul(p.radius, s_add(S_ONE, p.margin));
}

// reach (host-sim/src/fly/world.rs): radius + τ·max_speed, where an obstacle plane stops
// binding.
fn fly_reach(p: FlyParams) -> S {
    return s_add(fly_orca_radius(p), s_mul(p.tau, p.max_speed));
}

// ---- status words (the encoding of bee_frame.wgsl; the field table FIELDS of
// host-sim/src/gpu/fly/layout.rs decodes them) ----

// Error::Inconsistent.
const FLY_ERROR_INCONSISTENT: u32 = 3u;

const FLY_FIELD_STATE_POS: u32 = 1u; // "state.pos"
const FLY_FIELD_STATE_VEL: u32 = 2u; // "state.vel"
const FLY_FIELD_STATE_ESCAPE_THETA: u32 = 3u; // "state.escape_theta"
const FLY_FIELD_FRAME_NEIGHBOURS_POS: u32 = 4u; // "frame.neighbours.pos"
const FLY_FIELD_FRAME_NEIGHBOURS_VEL: u32 = 5u; // "frame.neighbours.vel"
const FLY_FIELD_FRAME_NEIGHBOURS_ID: u32 = 6u; // "frame.neighbours.id"
const FLY_FIELD_FRAME_STIMULUS_POS: u32 = 7u; // "frame.stimulus.pos"
const FLY_FIELD_FRAME_STIMULUS_KIND: u32 = 8u; // "frame.stimulus.kind"
const FLY_FIELD_FRAME_SURFACES_POINT: u32 = 9u; // "frame.surfaces.point"
const FLY_FIELD_FRAME_SURFACES_NORMAL: u32 = 10u; // "frame.surfaces.normal"
const FLY_FIELD_PREF: u32 = 11u; // "pref"
const FLY_FIELD_NEXT_POS: u32 = 12u; // "next.pos"

// ---- validation (frame.rs) ----

// FlyState::validate: pos and vel within the limit, escape_theta within ±(π/2 + 1e-3).
fn fly_state_validate(s: FlyState) -> u32 {
    var e = bee_check_vec(s.pos, FLY_FIELD_STATE_POS);
    if (e == BEE_OK) {
        e = bee_check_vec(s.vel, FLY_FIELD_STATE_VEL);
    }
    if (e == BEE_OK && !bee_within(s.escape_theta, s_from_f32(FLY_THETA_LIMIT))) {
        if (!s_is_finite(s.escape_theta)) {
            e = bee_error(BEE_ERROR_NON_FINITE, FLY_FIELD_STATE_ESCAPE_THETA);
        } else {
            e = bee_error(BEE_ERROR_OUT_OF_RANGE, FLY_FIELD_STATE_ESCAPE_THETA);
        }
    }
    return e;
}

// FlyFrame::validate: every neighbour's numbers and no id twice, the stimulus, the surfaces'
// points and unit normals (list errors at the entry).
fn fly_frame_validate(f: ptr<function, FlyFrame>) -> u32 {
    for (var i = 0u; i < (*f).neighbours_len; i = i + 1u) {
        let n = (*f).neighbours[i];
        var e = bee_check_vec(n.pos, FLY_FIELD_FRAME_NEIGHBOURS_POS);
        if (e == BEE_OK) {
            e = bee_check_vec(n.vel, FLY_FIELD_FRAME_NEIGHBOURS_VEL);
        }
        if (e != BEE_OK) {
            return bee_error_at(e, i);
        }
        for (var j = 0u; j < i; j = j + 1u) {
            if ((*f).neighbours[j].id == n.id) {
                return bee_error_at(
                    bee_error(FLY_ERROR_INCONSISTENT, FLY_FIELD_FRAME_NEIGHBOURS_ID), i);
            }
        }
    }
    if ((*f).has_stimulus) {
        let e = bee_check_vec((*f).stimulus_pos, FLY_FIELD_FRAME_STIMULUS_POS);
        if (e != BEE_OK) {
            return e;
        }
        if ((*f).stimulus_kind > FLY_STIMULUS_PREDATOR) {
            return bee_error(BEE_ERROR_OUT_OF_RANGE, FLY_FIELD_FRAME_STIMULUS_KIND);
        }
    }
    for (var i = 0u; i < (*f).surfaces_len; i = i + 1u) {
        let s = (*f).surfaces[i];
        var e = bee_check_vec(s.point, FLY_FIELD_FRAME_SURFACES_POINT);
        if (e == BEE_OK) {
            e = wang_check_unit(s.normal, FLY_FIELD_FRAME_SURFACES_NORMAL);
        }
        if (e != BEE_OK) {
            return bee_error_at(e, i);
        }
    }
    return BEE_OK;
}

// ---- the forces (force.rs, Eq. 2-5) ----

// zone_force: F_int of Eq. 5, per zone k (χ_k/N_k)·Σ_j (g r̂_ji + (1 − |g|) v̂_ji): repulsion
// −r̂ on [0, r_rep), alignment v̂ on [r_rep, r_ali), attraction +r̂ on [r_ali, r_att]; a
// coincident neighbour and the insect's own id skipped, each zone summed in the frame's order.
fn fly_zone_force(me: FlyState, id: u32, f: ptr<function, FlyFrame>, p: FlyParams) -> vec3<S> {
    var sums = array<vec3<S>, 3>(vec3<S>(), vec3<S>(), vec3<S>());
    var counts = array<i32, 3>(0, 0, 0);
    for (var i = 0u; i < (*f).neighbours_len; i = i + 1u) {
        let n = (*f).neighbours[i];
        if (n.id == id) {
            continue;
        }
        let d = geom_vec3_sub(n.pos, me.pos);
        let r_hat = geom_vec3_normalized(d);
        if (!r_hat.is_some) {
            continue;
        }
        let r = geom_vec3_length(d);
        var k = 0u;
        var term = geom_vec3_neg(r_hat.value);
        if (r < p.r_rep) {
            k = 0u;
        } else if (r < p.r_ali) {
            k = 1u;
            let v = geom_vec3_normalized(geom_vec3_sub(n.vel, me.vel));
            term = select(vec3<S>(), v.value, v.is_some);
        } else if (r <= p.r_att) {
            k = 2u;
            term = r_hat.value;
        } else {
            continue;
        }
        sums[k] = geom_vec3_add(sums[k], term);
        counts[k] = counts[k] + 1;
    }
    var weights = array<S, 3>(p.chi_rep, p.chi_ali, p.chi_att);
    var force = vec3<S>();
    for (var k = 0u; k < 3u; k = k + 1u) {
        if (counts[k] > 0) {
            force = geom_vec3_add(force,
                geom_vec3_mul(sums[k], s_div(weights[k], s_from_i32(counts[k]))));
        }
    }
    return force;
}

// friction: F_fric = −γ‖v‖v (quadratic drag).
fn fly_friction(vel: vec3<S>, gamma: S) -> vec3<S> {
    return geom_vec3_mul(vel, s_neg(s_mul(gamma, geom_vec3_length(vel))));
}

// response's result: F_res and the insect's next (θ, escaping).
struct FlyResponse {
    force: vec3<S>,
    theta: S,
    escaping: bool,
}

// response: F_res = χ_res·H(r_res − r_ie)·(s_e r̂_ie R(n, θ) − (1 − s_e) r̂_ie) (Eq. 3), r̂_ie
// away from the stimulus, R the rotation about +y by θ; θ drawn when a predator enters r_res
// (stream FLY_ESCAPE, U[−π/2, 0] or U[−π/2, π/2]) and kept while it stays in range.
fn fly_response(me: FlyState, f: ptr<function, FlyFrame>, p: FlyParams, c: StepCtx)
    -> FlyResponse {
    let none = FlyResponse(vec3<S>(), me.escape_theta, false);
    if (!(*f).has_stimulus) {
        return none;
    }
    let d = geom_vec3_sub(me.pos, (*f).stimulus_pos);
    if (!(geom_vec3_length(d) <= p.r_res)) {
        return none;
    }
    let u = geom_vec3_normalized(d);
    let r_hat = select(vec3<S>(), u.value, u.is_some);
    if ((*f).stimulus_kind != FLY_STIMULUS_PREDATOR) {
        return FlyResponse(geom_vec3_mul(geom_vec3_neg(r_hat), p.chi_res), me.escape_theta,
                           false);
    }
    var theta = me.escape_theta;
    if (!me.escaping) {
        let x = rand_unit(c.seed, c.agent, c.step, RAND_FLY_ESCAPE);
        let half_pi = s_mul(S_PI, s_from_f32(0.5f));
        if (p.escape_sides == 0u) {
            theta = s_neg(s_mul(x, half_pi));
        } else {
            theta = s_mul(s_sub(s_add(x, x), S_ONE), half_pi);
        }
    }
    let sc = s_sin_cos(theta);
    let turned = vec3<S>(
        s_add(s_mul(r_hat.x, sc.y), s_mul(r_hat.z, sc.x)),
        r_hat.y,
        s_sub(s_mul(r_hat.z, sc.y), s_mul(r_hat.x, sc.x)),
    );
    return FlyResponse(geom_vec3_mul(turned, p.chi_res), theta, true);
}

// noise_force's uniform draw: 2·U(0, 1) − 1 of stream `s`.
fn fly_uniform(c: StepCtx, s: u32) -> S {
    let u = rand_unit(c.seed, c.agent, c.step, s);
    return s_sub(s_add(u, u), S_ONE);
}

// noise_force: F_ξ (Eq. 4, Fig. 10): the curl noise ∇ × P (bee_curl_force), the Perlin vector
// P, white noise gain·U(−1, 1)³, Gaussian noise gain·(three Irwin–Hall sums of four draws,
// streams + (k << 8), times √(3/4)), or none.
fn fly_noise_force(pos: vec3<S>, p: FlyParams, c: StepCtx) -> vec3<S> {
    var axes = array<u32, 3>(RAND_FLY_NOISE_X, RAND_FLY_NOISE_Y, RAND_FLY_NOISE_Z);
    if (p.noise == FLY_NOISE_CURL) {
        return bee_curl_force(pos, p.scale, p.gain);
    }
    if (p.noise == FLY_NOISE_PERLIN) {
        let pot = bee_potential(pos, p.scale, p.gain);
        return vec3<S>(pot.x.value, pot.y.value, pot.z.value);
    }
    if (p.noise == FLY_NOISE_WHITE) {
        let v = vec3<S>(fly_uniform(c, axes[0]), fly_uniform(c, axes[1]), fly_uniform(c, axes[2]));
        return geom_vec3_mul(v, p.gain);
    }
    if (p.noise == FLY_NOISE_GAUSSIAN) {
        let norm = s_from_f32(FLY_GAUSS_NORM);
        var v = vec3<S>();
        for (var a = 0u; a < 3u; a = a + 1u) {
            var sum = S_ZERO;
            for (var k = 0u; k < 4u; k = k + 1u) {
                sum = s_add(sum, fly_uniform(c, axes[a] + (k << 8u)));
            }
            v[a] = s_mul(sum, norm);
        }
        return geom_vec3_mul(v, p.gain);
    }
    return vec3<S>();
}

// ---- ORCA's planes (orca3d/plane.rs) ----

// Plane: the valid side is (v − point)·normal ≥ 0.
struct FlyPlane {
    point: vec3<S>,
    normal: vec3<S>,
}

// An Option of a plane, of a normal and `u`, of a velocity.
struct FlyOptionPlane {
    is_some: bool,
    value: FlyPlane,
}

// Plane::violation: normal·(point − v), positive when v violates the plane.
fn fly_violation(p: FlyPlane, v: vec3<S>) -> S {
    return geom_vec3_dot(p.normal, geom_vec3_sub(p.point, v));
}

// div: v·(1/s), as RVO2-3D's `operator/`.
fn fly_div(v: vec3<S>, s: S) -> vec3<S> {
    return geom_vec3_mul(v, s_div(S_ONE, s));
}

// unit: v/|v| by `div` in f32 (S_DIRECT_LENGTH), `Vec3::normalized` in fixed point; none for a
// zero vector (or, in f32, an infinite length).
fn fly_unit(v: vec3<S>) -> GeomOptionVec3 {
    if (S_DIRECT_LENGTH) {
        let l = geom_vec3_length(v);
        if (l > S_ZERO && s_is_finite(l)) {
            return GeomOptionVec3(true, fly_div(v, l));
        }
        return GeomOptionVec3(false, vec3<S>());
    }
    return geom_vec3_normalized(v);
}

// away: the degenerate-w fallback of neighbour_plane, normal −p̂ and u making the relative
// velocity along it at least `speed`; none when the agents coincide.
fn fly_away(rel_pos: vec3<S>, rel_vel: vec3<S>, speed: S, agent_vel: vec3<S>) -> FlyOptionPlane {
    let n = fly_unit(geom_vec3_neg(rel_pos));
    if (!n.is_some) {
        return FlyOptionPlane(false, FlyPlane(vec3<S>(), vec3<S>()));
    }
    let u = geom_vec3_mul(n.value, s_sub(speed, geom_vec3_dot(rel_vel, n.value)));
    return fly_plane_of(agent_vel, n.value, u);
}

// Plane::new(v_i + ½u, n): agent i takes half the responsibility (ORCA eq. 6).
fn fly_plane_of(agent_vel: vec3<S>, n: vec3<S>, u: vec3<S>) -> FlyOptionPlane {
    let half = s_from_f32(0.5f);
    return FlyOptionPlane(true, FlyPlane(geom_vec3_add(agent_vel, geom_vec3_mul(u, half)), n));
}

// neighbour_plane: the ORCA plane of agent i from neighbour j (van den Berg et al. 2009, §5,
// RVO2-3D's computeNewVelocity): the truncated cone's cut-off sphere or side when apart, the
// cut-off sphere of one time step in collision.
fn fly_neighbour_plane(pos: vec3<S>, vel: vec3<S>, o_pos: vec3<S>, o_vel: vec3<S>, r: S,
                       inv_tau: S, inv_dt: S) -> FlyOptionPlane {
    let rel_pos = geom_vec3_sub(o_pos, pos);
    let rel_vel = geom_vec3_sub(vel, o_vel);
    let dist_sq = geom_vec3_length_sq(rel_pos);
    let r_sq = s_mul(r, r);
    if (dist_sq > r_sq) {
        // No collision.
        let w = geom_vec3_sub(rel_vel, geom_vec3_mul(rel_pos, inv_tau));
        let w_len_sq = geom_vec3_length_sq(w);
        let dot = geom_vec3_dot(w, rel_pos);
        if (dot < S_ZERO && s_mul(dot, dot) > s_mul(r_sq, w_len_sq)) {
            // Project on the cut-off sphere.
            let w_len = s_sqrt(w_len_sq);
            let n = fly_div(w, w_len);
            return fly_plane_of(vel, n, geom_vec3_mul(n, s_sub(s_mul(r, inv_tau), w_len)));
        }
        // Project on the cone.
        let a = dist_sq;
        let b = geom_vec3_dot(rel_pos, rel_vel);
        let c = s_sub(geom_vec3_length_sq(rel_vel),
                      s_div(geom_vec3_length_sq(geom_vec3_cross(rel_pos, rel_vel)),
                            s_sub(dist_sq, r_sq)));
        let t = s_div(s_add(b, s_sqrt(s_sub(s_mul(b, b), s_mul(a, c)))), a);
        let ww = geom_vec3_sub(rel_vel, geom_vec3_mul(rel_pos, t));
        let n = fly_unit(ww);
        if (n.is_some) {
            return fly_plane_of(vel, n.value,
                                geom_vec3_mul(n.value, s_sub(s_mul(r, t), geom_vec3_length(ww))));
        }
        return fly_away(rel_pos, rel_vel, s_mul(r, inv_tau), vel);
    }
    // Collision: the cut-off sphere of one time step.
    let w = geom_vec3_sub(rel_vel, geom_vec3_mul(rel_pos, inv_dt));
    let n = fly_unit(w);
    if (n.is_some) {
        return fly_plane_of(vel, n.value,
                            geom_vec3_mul(n.value, s_sub(s_mul(r, inv_dt), geom_vec3_length(w))));
    }
    return fly_away(rel_pos, rel_vel, s_mul(r, inv_dt), vel);
}

// obstacle_plane: the hard plane of a surface (ours, ren2016 spec §2.5), d = n·(pos − point):
// n·v ≥ −(d − radius)/τ while d > radius, else n·v ≥ (radius − d)/Δt.
fn fly_obstacle_plane(pos: vec3<S>, radius: S, s: FlySurface, inv_tau: S, inv_dt: S)
    -> FlyPlane {
    let n = s.normal;
    let d = geom_vec3_dot(n, geom_vec3_sub(pos, s.point));
    var bound = s_mul(s_sub(radius, d), inv_dt);
    if (d > radius) {
        bound = s_mul(s_neg(s_sub(d, radius)), inv_tau);
    }
    return FlyPlane(geom_vec3_mul(n, bound), n);
}

// ---- the linear programs (orca3d/lp.rs, RVO2-3D's linearProgram1..4) ----

// A program's planes: at most FLY_NEIGHBOURS (`solve::<S, N>`, N the frame's capacity).
struct FlyPlanes {
    planes: array<FlyPlane, 16>,
    len: u32,
}

// LP3's result: the velocity and the plane it failed on (`len` on success).
struct FlyLp {
    result: vec3<S>,
    fail: u32,
}

fn fly_eps() -> S {
    return s_from_f32(FLY_RVO_EPSILON);
}

// linear_program1: the 1D program on the line `point + t·direction` under the first `count`
// planes and ‖v‖ ≤ radius; none if they leave nothing of the line.
fn fly_lp1(ps: ptr<function, FlyPlanes>, count: u32, direction: vec3<S>, point: vec3<S>,
           radius: S, opt: vec3<S>, direction_opt: bool) -> GeomOptionVec3 {
    let no = GeomOptionVec3(false, vec3<S>());
    let dot = geom_vec3_dot(point, direction);
    let discriminant = s_sub(s_add(s_mul(dot, dot), s_mul(radius, radius)),
                             geom_vec3_length_sq(point));
    if (discriminant < S_ZERO) {
        // The max-speed sphere fully invalidates the line.
        return no;
    }
    let sqrt_d = s_sqrt(discriminant);
    var t_left = s_sub(s_neg(dot), sqrt_d);
    var t_right = s_add(s_neg(dot), sqrt_d);
    for (var i = 0u; i < count; i = i + 1u) {
        let p = (*ps).planes[i];
        let numerator = geom_vec3_dot(geom_vec3_sub(p.point, point), p.normal);
        let denominator = geom_vec3_dot(direction, p.normal);
        if (s_mul(denominator, denominator) <= fly_eps()) {
            // The line is (almost) parallel to plane p.
            if (numerator > S_ZERO) {
                return no;
            }
            continue;
        }
        let t = s_div(numerator, denominator);
        if (denominator >= S_ZERO) {
            t_left = s_max(t_left, t);
        } else {
            t_right = s_min(t_right, t);
        }
        if (t_left > t_right) {
            return no;
        }
    }
    var t = t_left;
    if (direction_opt) {
        if (geom_vec3_dot(opt, direction) > S_ZERO) {
            t = t_right;
        }
    } else {
        let t_opt = geom_vec3_dot(direction, geom_vec3_sub(opt, point));
        if (t_opt < t_left) {
            t = t_left;
        } else if (t_opt > t_right) {
            t = t_right;
        } else {
            t = t_opt;
        }
    }
    return GeomOptionVec3(true, geom_vec3_add(point, geom_vec3_mul(direction, t)));
}

// linear_program2: the 2D program on `plane` under the first `count` planes and ‖v‖ ≤ radius;
// none if infeasible.
fn fly_lp2(ps: ptr<function, FlyPlanes>, count: u32, plane: FlyPlane, radius: S, opt: vec3<S>,
           direction_opt: bool) -> GeomOptionVec3 {
    let no = GeomOptionVec3(false, vec3<S>());
    let plane_dist = geom_vec3_dot(plane.point, plane.normal);
    let plane_dist_sq = s_mul(plane_dist, plane_dist);
    let radius_sq = s_mul(radius, radius);
    if (plane_dist_sq > radius_sq) {
        // The max-speed sphere fully invalidates the plane.
        return no;
    }
    let plane_radius_sq = s_sub(radius_sq, plane_dist_sq);
    let plane_center = geom_vec3_mul(plane.normal, plane_dist);
    var result: vec3<S>;
    if (direction_opt) {
        // Project the direction opt on the plane.
        let plane_opt = geom_vec3_sub(opt,
                                      geom_vec3_mul(plane.normal, geom_vec3_dot(opt, plane.normal)));
        let len_sq = geom_vec3_length_sq(plane_opt);
        if (len_sq <= fly_eps()) {
            result = plane_center;
        } else {
            result = geom_vec3_add(plane_center,
                                   geom_vec3_mul(plane_opt, s_sqrt(s_div(plane_radius_sq, len_sq))));
        }
    } else {
        // Project the point opt on the plane.
        let r = geom_vec3_add(opt, geom_vec3_mul(plane.normal,
                                                 geom_vec3_dot(geom_vec3_sub(plane.point, opt),
                                                               plane.normal)));
        result = r;
        // If outside the plane's circle, project on the circle.
        if (geom_vec3_length_sq(r) > radius_sq) {
            let pr = geom_vec3_sub(r, plane_center);
            let pr_len_sq = geom_vec3_length_sq(pr);
            result = plane_center;
            if (pr_len_sq > S_ZERO) {
                result = geom_vec3_add(plane_center,
                                       geom_vec3_mul(pr, s_sqrt(s_div(plane_radius_sq, pr_len_sq))));
            }
        }
    }
    for (var i = 0u; i < count; i = i + 1u) {
        let p = (*ps).planes[i];
        if (fly_violation(p, result) > S_ZERO) {
            // Solve on the intersection line of plane i and this plane.
            let cross = geom_vec3_cross(p.normal, plane.normal);
            if (geom_vec3_length_sq(cross) <= fly_eps()) {
                // (Almost) parallel: plane i fully invalidates this plane.
                return no;
            }
            let direction = fly_unit(cross);
            if (!direction.is_some) {
                return no;
            }
            let line_normal = geom_vec3_cross(direction.value, plane.normal);
            let point = geom_vec3_add(plane.point, geom_vec3_mul(line_normal,
                s_div(geom_vec3_dot(geom_vec3_sub(p.point, plane.point), p.normal),
                      geom_vec3_dot(line_normal, p.normal))));
            let r = fly_lp1(ps, i, direction.value, point, radius, opt, direction_opt);
            if (!r.is_some) {
                return no;
            }
            result = r.value;
        }
    }
    return GeomOptionVec3(true, result);
}

// linear_program3: the velocity within ‖v‖ ≤ radius closest to opt (or extreme along the unit
// opt) satisfying every plane, adding them in order; on failure the optimum of the planes before
// the one it failed on.
fn fly_lp3(ps: ptr<function, FlyPlanes>, radius: S, opt: vec3<S>, direction_opt: bool) -> FlyLp {
    var result = opt;
    if (direction_opt) {
        result = geom_vec3_mul(opt, radius);
    } else if (geom_vec3_length_sq(opt) > s_mul(radius, radius)) {
        let u = fly_unit(opt);
        result = select(vec3<S>(), geom_vec3_mul(u.value, radius), u.is_some);
    }
    for (var i = 0u; i < (*ps).len; i = i + 1u) {
        let p = (*ps).planes[i];
        if (fly_violation(p, result) > S_ZERO) {
            let r = fly_lp2(ps, i, p, radius, opt, direction_opt);
            if (!r.is_some) {
                return FlyLp(result, i);
            }
            result = r.value;
        }
    }
    return FlyLp(result, (*ps).len);
}

// linear_program4: after LP3 failed at plane `begin`, the velocity minimising the largest
// penetration of the planes from `begin` on, the first `hard` (obstacle) planes kept as they are.
fn fly_lp4(ps: ptr<function, FlyPlanes>, begin: u32, hard_in: u32, radius: S, start: vec3<S>)
    -> vec3<S> {
    let half = s_from_f32(0.5f);
    var result = start;
    var distance = S_ZERO;
    let hard = min(hard_in, (*ps).len);
    for (var i = begin; i < (*ps).len; i = i + 1u) {
        let pi = (*ps).planes[i];
        if (fly_violation(pi, result) > distance) {
            var proj: FlyPlanes;
            for (var j = 0u; j < hard; j = j + 1u) {
                proj.planes[proj.len] = (*ps).planes[j];
                proj.len = proj.len + 1u;
            }
            for (var j = hard; j < i; j = j + 1u) {
                let pj = (*ps).planes[j];
                let cross = geom_vec3_cross(pj.normal, pi.normal);
                var point: vec3<S>;
                if (geom_vec3_length_sq(cross) <= fly_eps()) {
                    // Planes i and j are (almost) parallel.
                    if (geom_vec3_dot(pi.normal, pj.normal) > S_ZERO) {
                        // Same direction: j adds nothing.
                        continue;
                    }
                    // Opposite directions.
                    point = geom_vec3_mul(geom_vec3_add(pi.point, pj.point), half);
                } else {
                    // A point on the intersection line of planes i and j.
                    let line_normal = geom_vec3_cross(cross, pi.normal);
                    point = geom_vec3_add(pi.point, geom_vec3_mul(line_normal,
                        s_div(geom_vec3_dot(geom_vec3_sub(pj.point, pi.point), pj.normal),
                              geom_vec3_dot(line_normal, pj.normal))));
                }
                let normal = fly_unit(geom_vec3_sub(pj.normal, pi.normal));
                if (!normal.is_some) {
                    continue;
                }
                proj.planes[proj.len] = FlyPlane(point, normal.value);
                proj.len = proj.len + 1u;
            }
            let r = fly_lp3(&proj, radius, pi.normal, true);
            // On failure (floating-point error only) the current result is kept.
            if (r.fail >= proj.len) {
                result = r.result;
            }
            distance = fly_violation(pi, result);
        }
    }
    return result;
}

// ---- ORCA on a frame (orca3d::solve_frame, shared with li2015's li_step.wgsl) ----

// ORCA's answer: the new velocity and whether the program was infeasible (the fallback acted).
struct FlyOrca {
    velocity: vec3<S>,
    infeasible: bool,
}

// solve_frame (orca3d/mod.rs) past its checks (the state's, the frame's and `pref`'s, made by the
// caller): the surfaces' planes, then those of the first min(orca_neighbours, 16 − surfaces)
// neighbours but the insect itself (`agent`), every insect of radius `radius`; LP3 toward `pref`
// within ‖v‖ ≤ max_speed, and when infeasible the fallback: LP4 (FLY_FALLBACK_LP4) or zero.
fn fly_orca_frame(pos: vec3<S>, vel: vec3<S>, f: ptr<function, FlyFrame>, radius: S, tau: S,
                  dt: S, max_speed: S, orca_neighbours: u32, fallback: u32, pref: vec3<S>,
                  agent: u32) -> FlyOrca {
    let inv_tau = s_div(S_ONE, tau);
    let inv_dt = s_div(S_ONE, dt);
    var ps: FlyPlanes;
    for (var i = 0u; i < (*f).surfaces_len; i = i + 1u) {
        var surface = (*f).surfaces[i];
        // Normalised by `solve` (a checked unit normal always normalises).
        surface.normal = geom_vec3_normalized(surface.normal).value;
        ps.planes[ps.len] = fly_obstacle_plane(pos, radius, surface, inv_tau, inv_dt);
        ps.len = ps.len + 1u;
    }
    let hard = ps.len;
    // The others: the frame's neighbours but the insect itself, at most `room`, of which ORCA
    // uses the first `orca_neighbours`.
    let room = FLY_NEIGHBOURS - (*f).surfaces_len;
    let used = min(room, orca_neighbours);
    var taken = 0u;
    for (var i = 0u; i < (*f).neighbours_len && taken < used; i = i + 1u) {
        let n = (*f).neighbours[i];
        if (n.id == agent) {
            continue;
        }
        taken = taken + 1u;
        let plane = fly_neighbour_plane(pos, vel, n.pos, n.vel, s_add(radius, radius),
                                        inv_tau, inv_dt);
        if (plane.is_some) {
            ps.planes[ps.len] = plane.value;
            ps.len = ps.len + 1u;
        }
    }
    let lp = fly_lp3(&ps, max_speed, pref, false);
    var out = FlyOrca(lp.result, false);
    if (lp.fail < ps.len) {
        out.infeasible = true;
        out.velocity = vec3<S>();
        if (fallback == FLY_FALLBACK_LP4) {
            out.velocity = fly_lp4(&ps, lp.fail, hard, max_speed, lp.result);
        }
    }
    return out;
}

// ---- the step (step.rs, Algorithm 1) ----

// step_checked: the state and frame validated; F_int, F_fric, F_res, F_ξ into
// v_pref = v + (F_int + F_fric + F_res + F_ξ)·Δt; ORCA (orca3d::solve: the surfaces' planes,
// then those of the first min(orca_neighbours, 16 − surfaces) neighbours, LP3 toward v_pref,
// the fallback when infeasible); r ← r + v·Δt.
fn fly_step_checked(s: FlyState, f: ptr<function, FlyFrame>, p: FlyParams, c: StepCtx)
    -> FlyResult {
    var out = FlyResult(BEE_OK, s, vec3<S>(), false);
    out.status = fly_state_validate(s);
    if (out.status == BEE_OK) {
        out.status = fly_frame_validate(f);
    }
    if (out.status != BEE_OK) {
        return out;
    }
    let f_int = fly_zone_force(s, c.agent, f, p);
    let f_fric = fly_friction(s.vel, p.gamma);
    let res = fly_response(s, f, p, c);
    let f_xi = fly_noise_force(s.pos, p, c);
    let pref = geom_vec3_add(s.vel, geom_vec3_mul(
        geom_vec3_add(geom_vec3_add(geom_vec3_add(f_int, f_fric), res.force), f_xi), p.dt));
    out.pref = pref;
    // solve's checks: what the state and frame checks have not checked already.
    out.status = bee_check_vec(pref, FLY_FIELD_PREF);
    if (out.status != BEE_OK) {
        return out;
    }

    let orca = fly_orca_frame(s.pos, s.vel, f, fly_orca_radius(p), p.tau, p.dt, p.max_speed,
                              p.orca_neighbours, p.fallback, pref, c.agent);
    out.infeasible = orca.infeasible;
    let vel = orca.velocity;
    let next = FlyState(geom_vec3_add(s.pos, geom_vec3_mul(vel, p.dt)), vel, res.theta,
                        res.escaping);
    if (!geom_vec3_check(next.pos)) {
        out.status = bee_error(BEE_ERROR_NON_FINITE, FLY_FIELD_NEXT_POS);
        return out;
    }
    out.next = next;
    return out;
}
