// The li2015 insect (host-sim/src/gpu/shaders.rs, LI_STEP): `swarm_core::li`
// (core-nostd/src/li/: `sampler.rs`'s inverse-CDF draw, `density.rs`'s grid, `waypoint.rs`'s
// Algorithm 1 with the Metropolis-Hastings screening, `step.rs`), function by function over the
// scalar `S`, on the 3D ORCA of fly_step.wgsl (`fly_orca_frame`, orca3d::solve_frame) and its
// frame: a li frame is a FlyFrame without a stimulus, validated by `fly_frame_validate`, whose
// field codes the LI_FIELD_* of the frame repeat. In fixed point every result is the Rust's bit
// for bit (the GPU engine's tests compare them).
//
// A group's learned data (the two tables, the density grid) is read where it lies, in the
// groups' words (binding 11, host-sim/src/gpu/li/layout.rs).

@group(0) @binding(11) var<storage, read> li_groups: array<u32>;

// ---- the values (frame.rs, params.rs, waypoint.rs) ----

// SAMPLING_MH, SAMPLING_MESO, SAMPLING_RANDOM (waypoint.rs).
const LI_SAMPLING_MH: u32 = 0u;
const LI_SAMPLING_RANDOM: u32 = 2u;

// BINS (params.rs): the most bins of a learned table; 7 halvings find a bin among 64.
const LI_BINS: u32 = 64u;
const LI_SEARCH_STEPS: u32 = 7u;

// The random streams of the model (core-nostd/src/rand.rs, stream::LI_*).
const RAND_LI_LENGTH: u32 = 0x50u;
const RAND_LI_TURN: u32 = 0x51u;
const RAND_LI_AZIMUTH: u32 = 0x52u;
const RAND_LI_HEIGHT: u32 = 0x53u;
const RAND_LI_ACCEPT: u32 = 0x54u;

// A group's words (layout.rs, GROUP_*): the seven parameters in S in LiParams' order (dt,
// speed, eps, radius, margin, tau, range), then patience, orca_neighbours, proposals, sampling,
// fallback; the range squared in S (the selection's limit); the tables (lo, hi in S, the number
// of bins, the cdf in S, LI_TABLE_WORDS each); the density (origin, cell in S, dims) and its
// weights, four bytes a word, the first the lowest.
const LI_GROUP_WORDS: u32 = 1184u;
const LI_GROUP_PATIENCE: u32 = 7u;
const LI_GROUP_RANGE2: u32 = 12u;
const LI_GROUP_LENGTHS: u32 = 16u;
const LI_GROUP_TURNS: u32 = 83u;
const LI_TABLE_WORDS: u32 = 67u;
const LI_GROUP_DENSITY: u32 = 150u;
const LI_GROUP_WEIGHTS: u32 = 160u;

// LiState: what an insect carries from one step to the next.
struct LiState {
    pos: vec3<S>,
    vel: vec3<S>,
    waypoint: vec3<S>,
    seg_start: vec3<S>,
    age: u32,
}

// LiParams but the data (validated on the host: `Checked`).
struct LiParams {
    dt: S,
    speed: S,
    eps: S,
    radius: S,
    margin: S,
    tau: S,
    range: S,
    patience: u32,
    orca_neighbours: u32,
    proposals: u32,
    sampling: u32,
    fallback: u32,
}

// What a step gives: the status word (0: Ok), the next state, the decision.
struct LiResult {
    status: u32,
    next: LiState,
    pref: vec3<S>,
    proposals: u32,
    accepted: bool,
    infeasible: bool,
}

// ---- status words (the encoding of bee_frame.wgsl; the field table FIELDS of
// host-sim/src/gpu/li/layout.rs decodes them). The frame's codes are fly_step.wgsl's
// (fly_frame_validate writes them); code 8 is none (a li frame has no stimulus). ----

const LI_FIELD_STATE_POS: u32 = 1u; // "state.pos"
const LI_FIELD_STATE_VEL: u32 = 2u; // "state.vel"
const LI_FIELD_STATE_WAYPOINT: u32 = 3u; // "state.waypoint"
const LI_FIELD_FRAME_NEIGHBOURS_POS: u32 = 4u; // "frame.neighbours.pos"
const LI_FIELD_FRAME_NEIGHBOURS_VEL: u32 = 5u; // "frame.neighbours.vel"
const LI_FIELD_FRAME_NEIGHBOURS_ID: u32 = 6u; // "frame.neighbours.id"
const LI_FIELD_STATE_SEG_START: u32 = 7u; // "state.seg_start"
const LI_FIELD_FRAME_SURFACES_POINT: u32 = 9u; // "frame.surfaces.point"
const LI_FIELD_FRAME_SURFACES_NORMAL: u32 = 10u; // "frame.surfaces.normal"
const LI_FIELD_PREF: u32 = 11u; // "pref"
const LI_FIELD_NEXT_POS: u32 = 12u; // "next.pos"

// LiState::validate: every vector within the limit.
fn li_state_validate(s: LiState) -> u32 {
    var e = bee_check_vec(s.pos, LI_FIELD_STATE_POS);
    if (e == BEE_OK) {
        e = bee_check_vec(s.vel, LI_FIELD_STATE_VEL);
    }
    if (e == BEE_OK) {
        e = bee_check_vec(s.waypoint, LI_FIELD_STATE_WAYPOINT);
    }
    if (e == BEE_OK) {
        e = bee_check_vec(s.seg_start, LI_FIELD_STATE_SEG_START);
    }
    return e;
}

// ---- the group's data ----

fn li_group_u(g: u32, k: u32) -> u32 {
    return li_groups[g * LI_GROUP_WORDS + k];
}

fn li_group_s(g: u32, k: u32) -> S {
    return s_from_word(li_group_u(g, k));
}

fn li_group_vec3(g: u32, k: u32) -> vec3<S> {
    return vec3<S>(li_group_s(g, k), li_group_s(g, k + 1u), li_group_s(g, k + 2u));
}

// The parameters of group g.
fn li_group_params(g: u32) -> LiParams {
    let o = LI_GROUP_PATIENCE;
    return LiParams(li_group_s(g, 0u), li_group_s(g, 1u), li_group_s(g, 2u), li_group_s(g, 3u),
                    li_group_s(g, 4u), li_group_s(g, 5u), li_group_s(g, 6u), li_group_u(g, o),
                    li_group_u(g, o + 1u), li_group_u(g, o + 2u), li_group_u(g, o + 3u),
                    li_group_u(g, o + 4u));
}

// LiParams::orca_radius: radius·(1 + margin).
fn li_orca_radius(p: LiParams) -> S {
    return s_mul(p.radius, s_add(S_ONE, p.margin));
}

// ---- the learned distributions (sampler.rs) ----

// Table::sample of the table at word `t` of group g: the value at cumulative share u, the first
// bin whose share exceeds u (partition_point: a binary search over the non-decreasing shares)
// interpolated linearly; hi at or beyond the last share, lo for u ≤ 0.
fn li_sample(g: u32, t: u32, u: S) -> S {
    let lo = li_group_s(g, t);
    let hi = li_group_s(g, t + 1u);
    if (!(u > S_ZERO)) {
        return lo;
    }
    let m = li_group_u(g, t + 2u);
    let cdf = t + 3u;
    var a = 0u;
    var b = m;
    for (var step = 0u; step < LI_SEARCH_STEPS && a < b; step = step + 1u) {
        let mid = (a + b) / 2u;
        if (li_group_s(g, cdf + mid) <= u) {
            a = mid + 1u;
        } else {
            b = mid;
        }
    }
    let k = a;
    if (k >= m) {
        return hi;
    }
    var below = S_ZERO;
    if (k > 0u) {
        below = li_group_s(g, cdf + k - 1u);
    }
    let within = s_div(s_sub(u, below), s_sub(li_group_s(g, cdf + k), below));
    let width = s_div(s_sub(hi, lo), s_from_i32(i32(m)));
    return s_add(lo, s_mul(s_add(s_from_i32(i32(k)), within), width));
}

// ---- the density (density.rs) ----

// Density::cell_of for group g: the flat index (x fastest) of the cell holding p, −1 outside
// the grid.
fn li_density_cell(g: u32, p: vec3<S>) -> i32 {
    let d = LI_GROUP_DENSITY;
    let origin = li_group_vec3(g, d);
    let cell = li_group_s(g, d + 3u);
    var index = 0u;
    var stride = 1u;
    for (var k = 0u; k < 3u; k = k + 1u) {
        let dim = li_group_u(g, d + 4u + k);
        let q = s_div(s_sub(p[k], origin[k]), cell);
        if (!s_is_finite(q) || q < S_ZERO) {
            return -1;
        }
        let i = s_floor_i32(q);
        if (i < 0 || i >= i32(dim)) {
            return -1;
        }
        index = index + u32(i) * stride;
        stride = stride * dim;
    }
    return i32(index);
}

// Density::at for group g: w_c of the cell holding p, 0 outside the grid.
fn li_density_at(g: u32, p: vec3<S>) -> u32 {
    let c = li_density_cell(g, p);
    if (c < 0) {
        return 0u;
    }
    let index = u32(c);
    let w = li_group_u(g, LI_GROUP_WEIGHTS + index / 4u);
    return (w >> ((index % 4u) * 8u)) & 0xffu;
}

// ---- Algorithm 1 and its screening (waypoint.rs) ----

// direction(d, θ, φ, z): the unit vector at |θ| from d̂ at azimuth φ about it (from d̂ × a, a the
// world axis least aligned with d̂); for a d that does not normalise, the uniform direction of
// height z and azimuth φ.
fn li_direction(d: vec3<S>, theta: S, phi: S, z: S) -> vec3<S> {
    let sc_phi = s_sin_cos(phi);
    let s_phi = sc_phi.x;
    let c_phi = sc_phi.y;
    let nd = geom_vec3_normalized(d);
    if (!nd.is_some) {
        let r = s_sqrt(s_max(s_sub(S_ONE, s_mul(z, z)), S_ZERO));
        return vec3<S>(s_mul(r, c_phi), z, s_mul(r, s_phi));
    }
    let n = nd.value;
    let ax = s_abs(n.x);
    let ay = s_abs(n.y);
    let az = s_abs(n.z);
    // Each component chosen (a vector of constants could lose a zero's sign, bee_world.wgsl).
    let x_axis = ax <= ay && ax <= az;
    let y_axis = !x_axis && ay <= az;
    let z_axis = !x_axis && !y_axis;
    let a = vec3<S>(select(S_ZERO, S_ONE, x_axis), select(S_ZERO, S_ONE, y_axis),
                    select(S_ZERO, S_ONE, z_axis));
    let e1o = geom_vec3_normalized(geom_vec3_cross(n, a));
    let e1 = select(a, e1o.value, e1o.is_some);
    let e2 = geom_vec3_cross(n, e1);
    let sc_t = s_sin_cos(s_abs(theta));
    return geom_vec3_add(geom_vec3_mul(n, sc_t.y),
                         geom_vec3_mul(geom_vec3_add(geom_vec3_mul(e1, c_phi),
                                                     geom_vec3_mul(e2, s_phi)), sc_t.x));
}

// accept: never into a zero cell; from a zero cell any w_g > 0; else with probability
// min(1, w_g/w_x) (u·w_x < w_g).
fn li_accept(w_x: u32, w_g: u32, u: S) -> bool {
    return w_g > 0u && (w_x <= w_g || s_mul(u, s_from_i32(i32(w_x))) < s_from_i32(i32(w_g)));
}

// What next_waypoint decided: the waypoint, the segment's start, the proposals, the acceptance.
struct LiNext {
    waypoint: vec3<S>,
    seg_start: vec3<S>,
    proposals: u32,
    accepted: bool,
}

// next_waypoint (its checks made by the step's): unchanged until arrived (‖x − g‖ ≤ ε); then up
// to K proposals x + l·direction(±(x − s), θ) (or uniform in the grid's box, SAMPLING_RANDOM),
// each screened by `li_accept` (or inside the grid), the first accepted one the waypoint with
// s = x; if none is, held at x with the heading the K rejections reversed.
fn li_next_waypoint(g: u32, pos: vec3<S>, waypoint: vec3<S>, seg_start: vec3<S>, p: LiParams,
                    c: StepCtx) -> LiNext {
    let off = geom_vec3_sub(pos, waypoint);
    if (geom_vec3_length_sq(off) > s_mul(p.eps, p.eps)) {
        return LiNext(waypoint, seg_start, 0u, false);
    }
    let w_x = li_density_at(g, pos);
    let came = geom_vec3_sub(pos, seg_start);
    let two = s_from_i32(2);
    // The grid's box (Density::bounds).
    let d = LI_GROUP_DENSITY;
    let lo = li_group_vec3(g, d);
    let cell = li_group_s(g, d + 3u);
    let far = vec3<S>(s_mul(cell, s_from_i32(i32(li_group_u(g, d + 4u)))),
                      s_mul(cell, s_from_i32(i32(li_group_u(g, d + 5u)))),
                      s_mul(cell, s_from_i32(i32(li_group_u(g, d + 6u)))));
    let hi = geom_vec3_add(lo, far);
    for (var a = 0u; a < p.proposals; a = a + 1u) {
        let shift = a << 8u;
        let u1 = rand_unit(c.seed, c.agent, c.step, RAND_LI_LENGTH + shift);
        let u2 = rand_unit(c.seed, c.agent, c.step, RAND_LI_TURN + shift);
        let u3 = rand_unit(c.seed, c.agent, c.step, RAND_LI_AZIMUTH + shift);
        var q: vec3<S>;
        if (p.sampling == LI_SAMPLING_RANDOM) {
            q = geom_vec3_add(lo, vec3<S>(s_mul(s_sub(hi.x, lo.x), u1),
                                          s_mul(s_sub(hi.y, lo.y), u2),
                                          s_mul(s_sub(hi.z, lo.z), u3)));
        } else {
            let l = li_sample(g, LI_GROUP_LENGTHS, u1);
            let theta = li_sample(g, LI_GROUP_TURNS, u2);
            let phi = s_mul(s_sub(s_mul(u3, two), S_ONE), S_PI);
            let z = s_sub(s_mul(rand_unit(c.seed, c.agent, c.step, RAND_LI_HEIGHT + shift), two),
                          S_ONE);
            let heading = select(geom_vec3_neg(came), came, (a % 2u) == 0u);
            q = geom_vec3_add(pos, geom_vec3_mul(li_direction(heading, theta, phi, z), l));
        }
        var accepted: bool;
        if (p.sampling == LI_SAMPLING_MH) {
            let u = rand_unit(c.seed, c.agent, c.step, RAND_LI_ACCEPT + shift);
            accepted = li_accept(w_x, li_density_at(g, q), u);
        } else {
            accepted = li_density_cell(g, q) >= 0;
        }
        if (accepted) {
            return LiNext(q, pos, a + 1u, true);
        }
    }
    // Held: the heading as the K rejections reversed it.
    var held_start = seg_start;
    if ((p.proposals % 2u) == 1u) {
        let s = geom_vec3_add(pos, came);
        // check_vec: finite and within the coordinate limit.
        held_start = select(pos, s, bee_check_vec(s, 0u) == BEE_OK);
    }
    return LiNext(pos, held_start, p.proposals, false);
}

// ---- the step (step.rs) ----

// preferred: v0 along g − x, or (g − x)/Δt when that is shorter than one step at v0.
fn li_preferred(x: vec3<S>, g: vec3<S>, speed: S, dt: S) -> vec3<S> {
    let d = geom_vec3_sub(g, x);
    let reach = s_mul(speed, dt);
    if (geom_vec3_length_sq(d) <= s_mul(reach, reach)) {
        return geom_vec3_mul(d, s_div(S_ONE, dt));
    }
    let u = geom_vec3_normalized(d);
    return select(vec3<S>(), geom_vec3_mul(u.value, speed), u.is_some);
}

// step_checked for the insect of group g: the state and frame validated; the waypoint (held
// past `patience` steps: arrived where it is), v_pref toward it, ORCA, x ← x + v·Δt.
fn li_step_checked(g: u32, s: LiState, f: ptr<function, FlyFrame>, p: LiParams, c: StepCtx)
    -> LiResult {
    var out = LiResult(BEE_OK, s, vec3<S>(), 0u, false, false);
    out.status = li_state_validate(s);
    if (out.status == BEE_OK) {
        out.status = fly_frame_validate(f);
    }
    if (out.status != BEE_OK) {
        return out;
    }
    let current = select(s.waypoint, s.pos, s.age >= p.patience);
    let next = li_next_waypoint(g, s.pos, current, s.seg_start, p, c);
    out.proposals = next.proposals;
    out.accepted = next.accepted;
    let pref = li_preferred(s.pos, next.waypoint, p.speed, p.dt);
    out.pref = pref;
    // solve's checks: what the state and frame checks have not checked already.
    out.status = bee_check_vec(pref, LI_FIELD_PREF);
    if (out.status != BEE_OK) {
        return out;
    }
    let orca = fly_orca_frame(s.pos, s.vel, f, li_orca_radius(p), p.tau, p.dt, p.speed,
                              p.orca_neighbours, p.fallback, pref, c.agent);
    out.infeasible = orca.infeasible;
    let vel = orca.velocity;
    var age = min(s.age + 1u, 0xffffu);
    if (next.proposals > 0u) {
        age = 0u;
    }
    let moved = LiState(geom_vec3_add(s.pos, geom_vec3_mul(vel, p.dt)), vel, next.waypoint,
                        next.seg_start, age);
    if (!geom_vec3_check(moved.pos)) {
        out.status = bee_error(BEE_ERROR_NON_FINITE, LI_FIELD_NEXT_POS);
        return out;
    }
    out.next = moved;
    return out;
}
