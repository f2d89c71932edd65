// Visually-based roll-to-avoidance (host-sim/src/gpu/shaders.rs, BEE_VISION):
// `swarm_core::bee::vision` (core-nostd/src/bee/vision.rs, chen §IV-B): the field of view, the
// velocity tuning of eq. 5 and the body roll of eq. 6-7, over the scalar `S`.

// COS_HALF_FOV: cos 45°, the half-angle of the bee's 90° field of view (§IV-B, [54]):
// core::f32::consts::FRAC_1_SQRT_2.
const BEE_COS_HALF_FOV: f32 = 0.70710677f;

// Sighting<S>: an obstacle closer than d0 (§IV-B): r_e = p_e − r, d = |r_e|, the unit normal.
struct BeeSighting {
    r_e: vec3<S>,
    d: S,
    normal: vec3<S>,
}

// Option<Sighting<S>>: `value` means nothing when `is_some` is false.
struct BeeOptionSighting {
    is_some: bool,
    value: BeeSighting,
}

// in_fov: whether `r_e` lies within 45° of the unit forward axis: o·r_e ≥ cos 45°·|r_e| (a zero
// r_e counts as seen).
fn bee_in_fov(forward: vec3<S>, r_e: vec3<S>) -> bool {
    return geom_vec3_dot(forward, r_e)
        >= s_mul(s_from_f32(BEE_COS_HALF_FOV), geom_vec3_length(r_e));
}

// near: the obstacle as seen from `pos`, if it is closer than `d0`: r_e, d and the unit normal
// (up if the normal is zero).
fn bee_near(pos: vec3<S>, obstacle: BeeObstacleSense, d0: S) -> BeeOptionSighting {
    let r_e = geom_vec3_sub(obstacle.point, pos);
    let d = geom_vec3_length(r_e);
    if (!(d < d0)) {
        return BeeOptionSighting(false, BeeSighting());
    }
    let n = geom_vec3_normalized(obstacle.normal);
    return BeeOptionSighting(true, BeeSighting(r_e, d, select(geom_vec3_up(), n.value, n.is_some)));
}

// in_view: whether a near obstacle makes the bee avoid it: in the field of view, or the bee was
// already avoiding and the obstacle is not behind it (o·r_e ≥ 0).
fn bee_in_view(forward: vec3<S>, s: BeeSighting, avoiding: bool) -> bool {
    return bee_in_fov(forward, s.r_e) || (avoiding && geom_vec3_dot(forward, s.r_e) >= S_ZERO);
}

// sense: near and in_view together: the obstacle the bee avoids, if any.
fn bee_sense(
    pos: vec3<S>,
    forward: vec3<S>,
    obstacle: BeeObstacleSense,
    d0: S,
    avoiding: bool,
) -> BeeOptionSighting {
    let s = bee_near(pos, obstacle, d0);
    if (s.is_some && bee_in_view(forward, s.value, avoiding)) {
        return s;
    }
    return BeeOptionSighting(false, BeeSighting());
}

// ramp: Bridson's ramp of eq. 5 evaluated as 1 − (1 − x)³(1 + 9/8 x + 3/8 x²) on |x| ≤ 1, odd.
fn bee_ramp(x: S) -> S {
    let a = s_min(s_abs(x), S_ONE);
    let y = s_sub(S_ONE, a);
    let poly = s_add(S_ONE, s_mul(a, s_add(s_from_f32(1.125f), s_mul(a, s_from_f32(0.375f)))));
    let r = s_sub(S_ONE, s_mul(y, s_mul(y, s_mul(y, poly))));
    if (x < S_ZERO) {
        return s_neg(r);
    }
    return r;
}

// tune_velocity: the tuned velocity of eq. 5, u* = u − (1 − γ)·n·min(n·u, 0), γ = |ramp(d/d0)|
// (the tangential u_t and u_0 = u of our reading).
fn bee_tune_velocity(u: vec3<S>, normal: vec3<S>, d: S, d0: S) -> vec3<S> {
    let gamma = s_abs(bee_ramp(s_div(d, d0)));
    let approach = s_min(geom_vec3_dot(normal, u), S_ZERO);
    return geom_vec3_sub(u, geom_vec3_mul(normal, s_mul(approach, s_sub(S_ONE, gamma))));
}

// side_value: the side value of eq. 7, y = [0, 1, 0]·(o × r_e) (> 0: the obstacle is on the
// left).
fn bee_side_value(forward: vec3<S>, r_e: vec3<S>) -> S {
    return geom_vec3_cross(forward, r_e).y;
}

// avoidance_roll_deg: the avoidance roll of eq. 6 in degrees,
// sign(y)·exp(−|d0 − d|²/2)·45° (sign(0) = +1).
fn bee_avoidance_roll_deg(forward: vec3<S>, r_e: vec3<S>, d: S, d0: S) -> S {
    var sgn = S_ONE;
    if (bee_side_value(forward, r_e) < S_ZERO) {
        sgn = s_neg(S_ONE);
    }
    let gap = s_sub(d0, d);
    return s_mul(s_mul(sgn, s_exp(s_div(s_neg(s_mul(gap, gap)), s_from_i32(2)))), s_from_i32(45));
}
