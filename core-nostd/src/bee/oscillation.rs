//! Body oscillation (chen §IV-A): the maneuvering functions of eq. 3-4, the lift coefficient of
//! Fig. 4 and the oscillation force F_o of eq. 2, plus the body frame it is expressed in.

use super::params::BeeParams;
use crate::scalar::deg;
use crate::{Scalar, Vec3};

/// Speeds at or below this count as hovering: the forward axis then falls back to the stored
/// one.
const HOVER_SPEED: f32 = 1e-3;

/// Pitch maneuvering function, eq. 3: θ_pitch = 16.429 + 3.5 sin(π (t + 2.986) / 35.972), in
/// degrees, `t` in seconds.
pub fn pitch_deg<S: Scalar>(t: S) -> S {
    S::from_f32(16.429) + S::from_f32(3.5) * sin_pi_over(t + S::from_f32(2.986), 35.972)
}

/// Roll maneuvering function, eq. 4: θ_roll = −0.765 + 18.914 sin(π (t + 38.298) / 91.775), in
/// degrees, `t` in seconds.
pub fn roll_deg<S: Scalar>(t: S) -> S {
    S::from_f32(-0.765) + S::from_f32(18.914) * sin_pi_over(t + S::from_f32(38.298), 91.775)
}

/// sin(π·x/T), with x reduced modulo the period 2T first so that the phase stays exact for large
/// times in both scalar types (a rounded π/T would drift linearly with t).
fn sin_pi_over<S: Scalar>(x: S, t_half: f32) -> S {
    let cycles = x / S::from_f32(2.0 * t_half);
    let frac = cycles - S::from_i32(cycles.floor_i32());
    (frac * S::from_f32(core::f32::consts::TAU)).sin()
}

/// The period mean of eq. 4, in degrees: the constant term −0.765°.
///
/// The sway of eq. 2 uses the roll's deviation from this mean (see [`sway_deg`]).
pub const MEAN_ROLL_DEG: f32 = -0.765;

/// The roll angle (degrees) that drives the sway of eq. 2 when the roll comes from eq. 4: the
/// roll's deviation from its period mean, θ_roll − θ̄_roll, θ̄_roll = [`MEAN_ROLL_DEG`].
///
/// §IV-A describes the oscillation as a shift "around its mean position" (the same reading we
/// give the lift, see [`oscillation_force`]); taken literally, eq. 4's constant −0.765° would
/// push every bee to its left for ever, a steady sideways drift of
/// κ1·m·g·0.765°/(m·c) ≈ 0.12 units/s in the default column. The roll set-point itself
/// (the decision) stays eq. 4's θ_roll; eq. 6's avoidance roll drives the sway in full.
pub fn sway_deg<S: Scalar>(roll_deg: S) -> S {
    roll_deg - S::from_f32(MEAN_ROLL_DEG)
}

/// The period of eq. 4, 2 × 91.775 s.
pub const ROLL_PERIOD: f64 = 183.55;

/// The period of eq. 3, 2 × 35.972 s.
pub const PITCH_PERIOD: f64 = 71.944;

/// A bee's own clock offset (seconds, in [0, [`TIME_WRAP`])): its phase of the maneuvering
/// functions of eq. 3-4, a pure function of the seed and the agent id computed with the
/// counter-based random numbers ([`rand`](crate::rand::rand)).
///
/// Eq. 3-4 are functions of the time alone, so with one shared clock every bee of a swarm
/// would pitch and roll in step and the whole swarm would sway as one. Real bees are not
/// synchronised: each bee runs the maneuvering functions on its own clock,
/// t_bee = t + offset (see [`bee_time`]), with
///
/// offset = (k + x)·[`ROLL_PERIOD`], x = frac(b + id·φ⁻¹), k ∈ {0, …, 77}:
///
/// * x, the bee's phase of eq. 4 (the sway), is a golden-ratio (Weyl) sequence over the ids
///   from a base b drawn once per seed (`stream::BEE_PHASE_BASE`), in 32-bit integer arithmetic:
///   the roll phases of any run of consecutive ids are spread evenly over the period, so the
///   sways of a swarm cancel whatever its size (independent draws leave a common sway of
///   order 1/√N: 0.1 units/s for 100 bees);
/// * k, which of the 78 periods of eq. 4 in [`TIME_WRAP`] the offset falls in, is drawn per bee
///   (`stream::BEE_PHASE`), which makes its phase of eq. 3 (the pitch, hence the thrust)
///   random: 183.55 s is 2.55 periods of eq. 3.
///
/// A device computes the same bits (integer hashing, then `f64`) and, as before, receives its
/// clock as the frame time t: no input is added.
pub fn clock_offset(seed: u32, agent: u32) -> f64 {
    use crate::rand::{rand, stream};
    let base = rand(seed, 0, 0, stream::BEE_PHASE_BASE);
    // 2^32/φ, odd: consecutive ids step the phase by 0.618 of a period.
    let x = base.wrapping_add(agent.wrapping_mul(0x9e37_79b9));
    let k = rand(seed, agent, 0, stream::BEE_PHASE) % 78;
    (f64::from(k) + (f64::from(x) + 0.5) / 4_294_967_296.0) * ROLL_PERIOD
}

/// The frame time t (seconds) of bee `agent` at step `step`: its own clock
/// `step·dt + clock_offset(seed, agent)`, wrapped below the input limit by [`wrap_time`]
/// (which keeps the phases of eq. 3-4).
pub fn bee_time(seed: u32, agent: u32, step: u32, dt: f64) -> f64 {
    wrap_time(f64::from(step) * dt + clock_offset(seed, agent))
}

/// Lift coefficient of Fig. 4: l(α) = −0.00095953 α² + 0.090635 α − 0.34182, α in degrees (the
/// body attack angle, α = θ_pitch, §IV-A).
///
/// Evaluated in Horner form on α/10 (coefficients −0.095953, 0.90635, −0.34182) so that the
/// small α² coefficient keeps its precision in fixed point.
pub fn lift_coefficient<S: Scalar>(alpha_deg: S) -> S {
    let a = alpha_deg / S::from_i32(10);
    (S::from_f32(-0.095953) * a + S::from_f32(0.90635)) * a - S::from_f32(0.34182)
}

/// The mean of the lift coefficient over one period of eq. 3: with θ_pitch = c + A·sin(·),
/// c = 16.429°, A = 3.5°, the mean of l(θ) = a θ² + b θ + d (Fig. 4) is
/// l(c) + a·A²/2 = 0.882357 (sin² averages ½).
pub const MEAN_LIFT_COEFFICIENT: f32 = 0.882_356_6;

/// The body's forward axis o (§IV-B: "a vector o from the mass point of a bee in the forward
/// direction along the body longitudinal axis"), a unit vector, which the ±45° field of view
/// and the roll side of eq. 7 are measured from.
///
/// The body points where the bee flies: o is the direction of the velocity. When the bee
/// hovers (speed at most 1e-3) it keeps the stored forward vector, turns to the goal if it
/// has no stored one (a fresh state stores +x), and faces +x as the last resort.
pub fn forward_axis<S: Scalar>(vel: Vec3<S>, stored: Vec3<S>, heading: Option<Vec3<S>>) -> Vec3<S> {
    let hover = S::from_f32(HOVER_SPEED);
    unit(vel, hover)
        .or_else(|| unit(stored, S::ZERO))
        .or(heading)
        .unwrap_or(Vec3::new(S::ONE, S::ZERO, S::ZERO))
}

/// The direction of flight toward the goal: the unit vector from `pos` to `goal`, if there is
/// a goal and the bee is not on it.
///
/// The bee "repeatedly flies toward a target based on visual cues" (§I, §V-B): its thrust
/// (body X of eq. 2) points this way. The paper gives no other attraction to the target.
pub fn goal_heading<S: Scalar>(pos: Vec3<S>, goal: Option<Vec3<S>>) -> Option<Vec3<S>> {
    goal.and_then(|g| unit(g - pos, S::ZERO))
}

/// The unit vector along the horizontal part of `v`, if that part is above zero.
pub fn horizontal<S: Scalar>(v: Vec3<S>) -> Option<Vec3<S>> {
    unit(Vec3::new(v.x, S::ZERO, v.z), S::ZERO)
}

/// `v / |v|`, if `|v|` is above `min` (and above zero).
fn unit<S: Scalar>(v: Vec3<S>, min: S) -> Option<Vec3<S>> {
    let len = v.length();
    if len > min && len > S::ZERO {
        Some(Vec3::new(v.x / len, v.y / len, v.z / len))
    } else {
        None
    }
}

/// The body's side (Z, sway) axis of eq. 2: o × up, normalized (horizontal; +z when o is
/// vertical).
///
/// With y up this is right-handed: facing +x, the side axis is +z, the bee's right. A positive
/// roll (right wing down) therefore sways the bee to its right.
pub fn side_axis<S: Scalar>(forward: Vec3<S>) -> Vec3<S> {
    unit(forward.cross(Vec3::up()), S::ZERO).unwrap_or(Vec3::new(S::ZERO, S::ZERO, S::ONE))
}

/// The oscillation force F_o of eq. 2 in world coordinates:
///
/// * thrust f_t = m·g·θ_pitch along `thrust_dir` (body X: toward the goal, see
///   [`goal_heading`]; level along o without a goal or while avoiding),
/// * lift f_l = ½·ρ·A·|u|²·(l(θ_pitch) − l̄) along world up (body Y; we keep the lift
///   vertical whatever the heading), l̄ = [`MEAN_LIFT_COEFFICIENT`],
/// * sway f_s = m·g·θ_roll along the horizontal side axis o × up of the body axis o (body Z,
///   [`side_axis`]: the roll is about the longitudinal axis),
///
/// with the angles in radians in f_t and f_s and θ_pitch in degrees in l (Fig. 4). `pitch_deg`
/// comes from eq. 3; `roll_deg` is the sway angle: eq. 4's roll as its deviation from the
/// period mean ([`sway_deg`]), or eq. 6's roll while avoiding an obstacle.
///
/// Lift and weight: eq. 1 has no gravity, and the printed lift is always positive
/// (l ∈ [0.65, 1.09] over the pitch range of eq. 3), so taken literally every bee climbs
/// without end. §IV-A defines the oscillation as "a vertical body shift around its mean
/// position": we take the weight m·g as carried by the mean lift (hovering bees, \[45\]-\[46\])
/// and apply only the lift's deviation from its mean over the period of eq. 3 at the current
/// speed, ½ρA|u|²(l(θ_pitch) − l̄). At a steady speed the vertical force then averages to zero
/// over a period: the bee rises and sinks around its mean altitude.
pub fn oscillation_force<S: Scalar>(
    p: &BeeParams<S>,
    forward: Vec3<S>,
    thrust_dir: Vec3<S>,
    speed: S,
    pitch_deg: S,
    roll_deg: S,
) -> Vec3<S> {
    let mg = p.mass * p.gravity;
    let thrust = mg * deg(pitch_deg);
    let sway = mg * deg(roll_deg);
    let half_rho_a = p.air_density * p.wing_area / S::from_i32(2);
    let dl = lift_coefficient(pitch_deg) - S::from_f32(MEAN_LIFT_COEFFICIENT);
    let lift = half_rho_a * dl * speed * speed;
    thrust_dir * thrust + Vec3::up() * lift + side_axis(forward) * sway
}

/// The period after which the host's frame time wraps: 78 periods of eq. 4 (2 × 91.775 s) =
/// 14316.9 s, which is also 199 periods of eq. 3 (2 × 35.972 s = 14316.856 s) to within
/// 0.044 s. Frame times must stay below [`LIMIT`](super::params::LIMIT) (16000 s: the
/// fixed-point range), which a run at Δt = 0.05 s reaches after 320,000 steps.
pub const TIME_WRAP: f64 = 78.0 * 183.55;

/// A frame time for an unbounded clock `t` (seconds, ≥ 0): `t` itself below
/// [`LIMIT`](super::params::LIMIT) (the same bits), else `t` minus the whole number of
/// [`TIME_WRAP`] periods that brings it into [LIMIT − TIME_WRAP, LIMIT).
///
/// Eq. 4 is exactly periodic in `TIME_WRAP`; eq. 3 shifts by 0.044 s of its 71.944 s period per
/// wrap (θ_pitch off by at most 0.014° after one wrap, i.e. after 4.4 h of flight; the phase
/// error grows by that much per further 4 h). A negative, NaN, infinite or absurd (above
/// 1e15 s) `t` is returned as is (the controller refuses it).
pub fn wrap_time(t: f64) -> f64 {
    let limit = f64::from(super::params::LIMIT);
    if t.is_nan() || t < limit || t > 1e15 {
        return t;
    }
    // `as` truncates: the floor of a non-negative value.
    let wraps = ((t - limit) / TIME_WRAP) as u64 + 1;
    let r = t - wraps as f64 * TIME_WRAP;
    // Rounding for huge t.
    if r >= limit { r - TIME_WRAP } else { r }
}

#[cfg(test)]
mod tests {
    #[test]
    fn maneuvering_functions_keep_their_phase_for_long_runs() {
        use crate::Fx;
        for t in [0.0f32, 1000.0, 5_000.5, 15_999.0] {
            let exact = |c: f64, a: f64, off: f64, half: f64| {
                c + a * (core::f64::consts::PI * (t as f64 + off) / half).sin()
            };
            let roll = exact(-0.765, 18.914, 38.298, 91.775);
            let pitch = exact(16.429, 3.5, 2.986, 35.972);
            for (got, want) in [
                (roll_deg(Fx::from_f32(t)).to_f32() as f64, roll),
                (pitch_deg(Fx::from_f32(t)).to_f32() as f64, pitch),
                (roll_deg(t) as f64, roll),
                (pitch_deg(t) as f64, pitch),
            ] {
                // 5e-4 rad = 0.029°.
                assert!((got - want).abs() < 0.029, "t = {t}: {got} vs {want}");
            }
        }
    }

    use super::*;
    use crate::Fx;

    fn near(a: f32, b: f32, tol: f32) -> bool {
        (a - b).abs() <= tol
    }

    #[test]
    fn eq3_eq4_at_t0() {
        let pitch = 16.429 + 3.5 * (core::f64::consts::PI * 2.986 / 35.972).sin();
        let roll = -0.765 + 18.914 * (core::f64::consts::PI * 38.298 / 91.775).sin();
        assert!(near(pitch_deg(0.0f32), pitch as f32, 1e-4));
        assert!(near(roll_deg(0.0f32), roll as f32, 1e-4));
        assert!(near(pitch_deg(Fx::ZERO).to_f32(), pitch as f32, 2e-3));
        assert!(near(roll_deg(Fx::ZERO).to_f32(), roll as f32, 2e-3));
        // Bounds of the sinusoids: pitch ≤ 20° (§IV-A), roll within ±19.7°.
        for i in 0..400 {
            let t = i as f32 * 0.5;
            assert!((12.9..=19.93).contains(&pitch_deg(t)));
            assert!((-19.68..=18.15).contains(&roll_deg(t)));
        }
    }

    /// Every bee's clock offset lies in [0, TIME_WRAP); the roll phases of any run of
    /// consecutive ids are evenly spread (the mean sway of eq. 4 over them is near zero, for
    /// small and large swarms); the pitch phases are as spread as independent draws (measured:
    /// mean phasor 0.03-0.04 for 1,000 bees against the bound 0.096; with one draw of the
    /// period for all bees 0.12, and 1 for bees in step); the offset is a pure function of
    /// (seed, id); and a bee's frame time stays below the input limit for any step.
    #[test]
    fn bee_clocks_are_spread_in_range_and_pure() {
        use core::f64::consts::TAU;
        for seed in [0u32, 1, 14, 0xdead_beef] {
            for (first, n) in [
                (0u32, 10u32),
                (0, 100),
                (0, 1000),
                (500, 37),
                (u32::MAX - 20, 20),
            ] {
                let (mut roll, mut pitch) = (0.0f64, (0.0f64, 0.0f64));
                for id in first..first + n {
                    let o = clock_offset(seed, id);
                    assert!((0.0..TIME_WRAP).contains(&o), "{o}");
                    assert_eq!(o.to_bits(), clock_offset(seed, id).to_bits());
                    roll += (TAU * o / ROLL_PERIOD).sin();
                    let phase = TAU * o / PITCH_PERIOD;
                    pitch = (pitch.0 + phase.cos(), pitch.1 + phase.sin());
                }
                let n = f64::from(n);
                let roll = roll / n;
                assert!(roll.abs() < 0.1, "seed {seed}, {n} bees: mean sway {roll}");
                // The pitch phases are independent draws: the length of their mean phasor
                // exceeds sqrt(ln(10⁴)/n) once in 10⁴ swarms of independent uniform phases
                // (Rayleigh); bees pitching in step (one clock) give 1.
                let resultant = pitch.0.hypot(pitch.1) / n;
                assert!(
                    resultant < (10_000f64.ln() / n).sqrt(),
                    "seed {seed}, {n} bees: pitch phases in step ({resultant})"
                );
            }
            assert_ne!(clock_offset(seed, 3), clock_offset(seed.wrapping_add(1), 3));
        }
        for step in [0u32, 1, 33_000, 320_000, 1_000_000, u32::MAX] {
            for id in 0..20 {
                let t = bee_time(7, id, step, 0.05);
                assert!(
                    (0.0..f64::from(super::super::params::LIMIT)).contains(&t),
                    "{t}"
                );
            }
        }
        // The sway about its mean averages to zero over a period of eq. 4.
        let n = 10_000;
        let mean: f64 = (0..n)
            .map(|i| f64::from(sway_deg(roll_deg(183.55 * i as f32 / n as f32))))
            .sum::<f64>()
            / f64::from(n);
        assert!(mean.abs() < 1e-3, "{mean}");
    }

    #[test]
    fn lift_polynomial_of_fig4() {
        let l = |a: f64| -0.00095953 * a * a + 0.090635 * a - 0.34182;
        for a in [0.0f32, 10.0, 16.429, 20.0, 45.0] {
            assert!(
                near(lift_coefficient(a), l(a as f64) as f32, 1e-5),
                "l({a})"
            );
            let fx = lift_coefficient(Fx::from_f32(a)).to_f32();
            assert!(near(fx, l(a as f64) as f32, 2e-4), "Fx l({a}) = {fx}");
        }
        assert!(near(lift_coefficient(0.0f32), -0.34182, 1e-6));
        assert!(near(lift_coefficient(20.0f32), 1.0871, 1e-4));
    }

    #[test]
    fn forward_axis_priorities() {
        let v = Vec3::<f32>::from_f32;
        let to_goal = goal_heading(v(1.0, 5.0, 1.0), Some(v(1.0, 8.0, 5.0)));
        assert_eq!(to_goal, Some(v(0.0, 0.6, 0.8)));
        assert_eq!(goal_heading(v(1.0, 5.0, 1.0), Some(v(1.0, 5.0, 1.0))), None);
        assert_eq!(goal_heading(v(1.0, 5.0, 1.0), None), None);
        // Along the velocity, whatever the goal.
        assert_eq!(
            forward_axis(v(0.0, 3.0, -4.0), v(1.0, 0.0, 0.0), to_goal),
            v(0.0, 0.6, -0.8)
        );
        // Hovering: the stored forward vector, normalized; without one, the goal; else +x.
        assert_eq!(
            forward_axis(v(0.0, 0.0, 0.0), v(0.0, 0.0, -3.0), to_goal),
            v(0.0, 0.0, -1.0)
        );
        assert_eq!(
            forward_axis(v(0.0, 1e-4, 0.0), Vec3::zero(), to_goal),
            v(0.0, 0.6, 0.8)
        );
        assert_eq!(
            forward_axis(Vec3::zero(), Vec3::zero(), None),
            v(1.0, 0.0, 0.0)
        );
        // The side axis is horizontal and unit, also for a pitched o; +z for a vertical one.
        assert_eq!(side_axis(v(0.0, 0.6, -0.8)), v(1.0, 0.0, 0.0));
        assert_eq!(side_axis(v(0.0, 1.0, 0.0)), v(0.0, 0.0, 1.0));
    }

    #[test]
    fn mean_lift_coefficient_is_the_period_mean_of_fig4_over_eq3() {
        let n = 20_000;
        let mean = (0..n)
            .map(|i| {
                let t = PITCH_PERIOD * f64::from(i) / f64::from(n);
                let a = 16.429 + 3.5 * (core::f64::consts::PI * (t + 2.986) / 35.972).sin();
                -0.00095953 * a * a + 0.090635 * a - 0.34182
            })
            .sum::<f64>()
            / f64::from(n);
        assert!(
            (mean - f64::from(MEAN_LIFT_COEFFICIENT)).abs() < 1e-6,
            "{mean}"
        );
        // So the vertical force of eq. 2 averages to zero over a period at a steady speed.
        let p = BeeParams::<f32>::default();
        let o = Vec3::new(1.0, 0.0, 0.0);
        let lift: f64 = (0..n)
            .map(|i| {
                let t = PITCH_PERIOD as f32 * i as f32 / n as f32;
                f64::from(oscillation_force(&p, o, o, 3.0, pitch_deg(t), roll_deg(t)).y)
            })
            .sum::<f64>()
            / f64::from(n);
        assert!(lift.abs() < 1e-5, "mean lift {lift}");
    }

    #[test]
    fn time_wraps_below_the_input_limit_keeping_the_phase() {
        // Below the limit: the same bits.
        for t in [0.0, 0.05, 1234.5, 15_999.95] {
            assert_eq!(wrap_time(t).to_bits(), f64::to_bits(t));
        }
        for step in [320_000u64, 320_001, 400_000, 3_000_000, 4_294_967_295] {
            let t = step as f64 * 0.05;
            let w = wrap_time(t);
            assert!(
                (16_000.0 - TIME_WRAP..16_000.0).contains(&w),
                "step {step}: {w}"
            );
            let wraps = ((t - w) / TIME_WRAP).round();
            assert!(((t - w) - wraps * TIME_WRAP).abs() < 1e-6);
            // Eq. 4 exactly periodic; eq. 3 off by 0.044 s per wrap (in f64, the equations
            // themselves).
            let exact = |c: f64, a: f64, off: f64, half: f64, x: f64| {
                c + a * (core::f64::consts::PI * (x + off) / half).sin()
            };
            let droll =
                exact(-0.765, 18.914, 38.298, 91.775, t) - exact(-0.765, 18.914, 38.298, 91.775, w);
            let dpitch =
                exact(16.429, 3.5, 2.986, 35.972, t) - exact(16.429, 3.5, 2.986, 35.972, w);
            assert!(droll.abs() < 1e-6 * (1.0 + t / 1e4), "roll off by {droll}");
            assert!(dpitch.abs() < 0.015 * wraps, "pitch off by {dpitch}");
        }
        assert!(wrap_time(-1.0) < 0.0 && wrap_time(f64::NAN).is_nan());
    }

    #[test]
    fn force_components_and_handedness() {
        let p = BeeParams::<f32>::default();
        let o = Vec3::new(1.0, 0.0, 0.0);
        assert_eq!(side_axis(o), Vec3::new(0.0, 0.0, 1.0));
        let f = oscillation_force(&p, o, o, 2.0, 16.0, 10.0);
        let rad = core::f32::consts::PI / 180.0;
        assert!(near(f.x, 9.81 * 16.0 * rad, 1e-5));
        assert!(near(
            f.y,
            0.5 * 1.225 * 0.05 * 4.0 * (lift_coefficient(16.0) - MEAN_LIFT_COEFFICIENT),
            1e-6
        ));
        assert!(near(f.z, 9.81 * 10.0 * rad, 1e-5));
        let g = oscillation_force(
            &p.cast::<Fx>(),
            o.cast(),
            o.cast(),
            Fx::from_f32(2.0),
            Fx::from_f32(16.0),
            Fx::from_f32(10.0),
        );
        assert!(
            near(g.x.to_f32(), f.x, 1e-3)
                && near(g.y.to_f32(), f.y, 1e-3)
                && near(g.z.to_f32(), f.z, 1e-3)
        );
    }
}
