// Body oscillation (host-sim/src/gpu/shaders.rs, BEE_OSCILLATION):
// `swarm_core::bee::oscillation` (core-nostd/src/bee/oscillation.rs, chen §IV-A): the
// maneuvering functions of eq. 3-4, the lift coefficient of Fig. 4 and the oscillation force
// F_o of eq. 2, and the body frame it is expressed in, over the scalar `S`.
//
// Not ported: `clock_offset`, `bee_time` and `wrap_time`, the host's frame times, computed in
// f64 (WGSL has none); a bee's frame time t reaches the kernels as an input, as it reaches a
// device.

// HOVER_SPEED: speeds at or below this count as hovering (the forward axis then falls back to
// the stored one).
const BEE_HOVER_SPEED: f32 = 0.001f;
// MEAN_ROLL_DEG: the period mean of eq. 4, in degrees.
const BEE_MEAN_ROLL_DEG: f32 = -0.765f;
// MEAN_LIFT_COEFFICIENT: the mean of the lift coefficient over one period of eq. 3.
const BEE_MEAN_LIFT_COEFFICIENT: f32 = 0.8823566f;
// The periods 2T of the sines of eq. 3 and 4 (`S::from_f32(2.0 * t_half)` in sin_pi_over, with
// t_half 35.972 and 91.775: doubling is exact in f32, these are the same f32s).
const BEE_PITCH_PERIOD: f32 = 71.944f;
const BEE_ROLL_PERIOD: f32 = 183.55f;
// core::f32::consts::TAU.
const BEE_TAU: f32 = 6.2831855f;

// sin_pi_over: sin(π·x/T) with x reduced modulo the period 2T first (`period`: Rust's
// `S::from_f32(2.0 * t_half)`), so that the phase stays exact for large times.
fn bee_sin_pi_over(x: S, period: S) -> S {
    let cycles = s_div(x, period);
    let frac = s_sub(cycles, s_from_i32(s_floor_i32(cycles)));
    return s_sin(s_mul(frac, s_from_f32(BEE_TAU)));
}

// pitch_deg: the pitch maneuvering function, eq. 3:
// θ_pitch = 16.429 + 3.5 sin(π (t + 2.986) / 35.972), in degrees, t in seconds.
fn bee_pitch_deg(t: S) -> S {
    let phase = bee_sin_pi_over(s_add(t, s_from_f32(2.986f)), s_from_f32(BEE_PITCH_PERIOD));
    return s_add(s_from_f32(16.429f), s_mul(s_from_f32(3.5f), phase));
}

// roll_deg: the roll maneuvering function, eq. 4:
// θ_roll = −0.765 + 18.914 sin(π (t + 38.298) / 91.775), in degrees, t in seconds.
fn bee_roll_deg(t: S) -> S {
    let phase = bee_sin_pi_over(s_add(t, s_from_f32(38.298f)), s_from_f32(BEE_ROLL_PERIOD));
    return s_add(s_from_f32(-0.765f), s_mul(s_from_f32(18.914f), phase));
}

// sway_deg: the roll angle (degrees) that drives the sway of eq. 2 when the roll comes from
// eq. 4: its deviation from the period mean.
fn bee_sway_deg(roll_deg: S) -> S {
    return s_sub(roll_deg, s_from_f32(BEE_MEAN_ROLL_DEG));
}

// lift_coefficient: Fig. 4, l(α) = −0.00095953 α² + 0.090635 α − 0.34182 (α in degrees), in
// Horner form on α/10.
fn bee_lift_coefficient(alpha_deg: S) -> S {
    let a = s_div(alpha_deg, s_from_i32(10));
    return s_sub(
        s_mul(s_add(s_mul(s_from_f32(-0.095953f), a), s_from_f32(0.90635f)), a),
        s_from_f32(0.34182f),
    );
}

// unit: `v / |v|`, if |v| is above `lowest` (and above zero).
fn bee_unit(v: vec3<S>, lowest: S) -> GeomOptionVec3 {
    let len = geom_vec3_length(v);
    if (len > lowest && len > S_ZERO) {
        return GeomOptionVec3(true, vec3<S>(s_div(v.x, len), s_div(v.y, len), s_div(v.z, len)));
    }
    return GeomOptionVec3(false, vec3<S>(S_ZERO, S_ZERO, S_ZERO));
}

// forward_axis: the body's unit forward axis o (§IV-B): the direction of the velocity; when the
// bee hovers (speed at most HOVER_SPEED) the stored forward vector, else the heading to the
// goal, else +x.
fn bee_forward_axis(vel: vec3<S>, stored: vec3<S>, heading: GeomOptionVec3) -> vec3<S> {
    let v = bee_unit(vel, s_from_f32(BEE_HOVER_SPEED));
    if (v.is_some) {
        return v.value;
    }
    let s = bee_unit(stored, S_ZERO);
    if (s.is_some) {
        return s.value;
    }
    if (heading.is_some) {
        return heading.value;
    }
    return vec3<S>(S_ONE, S_ZERO, S_ZERO);
}

// goal_heading: the unit vector from `pos` to the goal, if there is a goal and the bee is not
// on it.
fn bee_goal_heading(pos: vec3<S>, goal: GeomOptionVec3) -> GeomOptionVec3 {
    if (!goal.is_some) {
        return GeomOptionVec3(false, vec3<S>(S_ZERO, S_ZERO, S_ZERO));
    }
    return bee_unit(geom_vec3_sub(goal.value, pos), S_ZERO);
}

// horizontal: the unit vector along the horizontal part of `v`, if that part is above zero.
fn bee_horizontal(v: vec3<S>) -> GeomOptionVec3 {
    return bee_unit(vec3<S>(v.x, S_ZERO, v.z), S_ZERO);
}

// side_axis: the body's side (sway) axis of eq. 2, o × up normalized (+z when o is vertical).
fn bee_side_axis(forward: vec3<S>) -> vec3<S> {
    let s = bee_unit(geom_vec3_cross(forward, geom_vec3_up()), S_ZERO);
    if (s.is_some) {
        return s.value;
    }
    return vec3<S>(S_ZERO, S_ZERO, S_ONE);
}

// oscillation_force: F_o of eq. 2 in world coordinates: the thrust m·g·θ_pitch along
// `thrust_dir`, the lift ½ρA|u|²(l(θ_pitch) − l̄) along world up (the weight carried by the
// mean lift), the sway m·g·θ_roll along the side axis of `forward` (angles in radians in the
// thrust and sway, θ_pitch in degrees in l).
fn bee_oscillation_force(
    p: BeeParams,
    forward: vec3<S>,
    thrust_dir: vec3<S>,
    speed: S,
    pitch_deg: S,
    roll_deg: S,
) -> vec3<S> {
    let mg = s_mul(p.mass, p.gravity);
    let thrust = s_mul(mg, s_deg(pitch_deg));
    let sway = s_mul(mg, s_deg(roll_deg));
    let half_rho_a = s_div(s_mul(p.air_density, p.wing_area), s_from_i32(2));
    let dl = s_sub(bee_lift_coefficient(pitch_deg), s_from_f32(BEE_MEAN_LIFT_COEFFICIENT));
    let lift = s_mul(s_mul(s_mul(half_rho_a, dl), speed), speed);
    return geom_vec3_add(
        geom_vec3_add(geom_vec3_mul(thrust_dir, thrust), geom_vec3_mul(geom_vec3_up(), lift)),
        geom_vec3_mul(bee_side_axis(forward), sway),
    );
}
