//! Body oscillation (chen §IV-A): the maneuvering functions of eq. 3-4, the lift coefficient of
//! Fig. 4 and the oscillation force F_o of eq. 2, plus the body frame it is expressed in.

use super::params::BeeParams;
use crate::scalar::deg;
use crate::{Scalar, Vec3};

/// Horizontal speeds at or below this count as hovering: the forward axis then falls back to
/// the stored one.
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

/// Lift coefficient of Fig. 4: l(α) = −0.00095953 α² + 0.090635 α − 0.34182, α in degrees (the
/// body attack angle, α = θ_pitch, §IV-A).
///
/// Evaluated in Horner form on α/10 (coefficients −0.095953, 0.90635, −0.34182) so that the
/// small α² coefficient keeps its precision in fixed point.
pub fn lift_coefficient<S: Scalar>(alpha_deg: S) -> S {
    let a = alpha_deg / S::from_i32(10);
    (S::from_f32(-0.095953) * a + S::from_f32(0.90635)) * a - S::from_f32(0.34182)
}

/// The body's horizontal forward axis o (§IV-B: "a vector o from the mass point of a bee in the
/// forward direction along the body longitudinal axis").
///
/// The bee "repeatedly flies toward a target based on visual cues" (§I, §V-B), so o points
/// horizontally toward `goal` when there is one; otherwise along the horizontal velocity;
/// when the bee hovers, along the stored forward vector; and +x as the last resort.
pub fn forward_axis<S: Scalar>(
    pos: Vec3<S>,
    vel: Vec3<S>,
    stored: Vec3<S>,
    goal: Option<Vec3<S>>,
) -> Vec3<S> {
    let hover = S::from_f32(HOVER_SPEED);
    goal.and_then(|g| horizontal_dir(g - pos, S::ZERO))
        .or_else(|| horizontal_dir(vel, hover))
        .or_else(|| horizontal_dir(stored, S::ZERO))
        .unwrap_or(Vec3::new(S::ONE, S::ZERO, S::ZERO))
}

/// The unit vector along the horizontal part of `v`, if that part is longer than `min`.
fn horizontal_dir<S: Scalar>(v: Vec3<S>, min: S) -> Option<Vec3<S>> {
    let flat = Vec3::new(v.x, S::ZERO, v.z);
    let len = flat.length();
    if len > min && len > S::ZERO {
        Some(Vec3::new(flat.x / len, S::ZERO, flat.z / len))
    } else {
        None
    }
}

/// The body's side (Z, sway) axis of eq. 2: o × up.
///
/// With y up this is right-handed: facing +x, the side axis is +z, the bee's right. A positive
/// roll (right wing down) therefore sways the bee to its right.
pub fn side_axis<S: Scalar>(forward: Vec3<S>) -> Vec3<S> {
    forward.cross(Vec3::up())
}

/// The oscillation force F_o of eq. 2 in world coordinates:
///
/// * thrust f_t = m·g·θ_pitch along the forward axis o (body X),
/// * lift f_l = ½·ρ·A·|u|²·l(θ_pitch) along world up (body Y; the body frame is kept level,
///   only its heading turns),
/// * sway f_s = m·g·θ_roll along the side axis o × up (body Z, [`side_axis`]),
///
/// with the angles in radians in f_t and f_s and θ_pitch in degrees in l (Fig. 4). `pitch_deg`
/// comes from eq. 3; `roll_deg` from eq. 4, or from eq. 6 while avoiding an obstacle.
pub fn oscillation_force<S: Scalar>(
    p: &BeeParams<S>,
    forward: Vec3<S>,
    speed: S,
    pitch_deg: S,
    roll_deg: S,
) -> Vec3<S> {
    let mg = p.mass * p.gravity;
    let thrust = mg * deg(pitch_deg);
    let sway = mg * deg(roll_deg);
    let half_rho_a = p.air_density * p.wing_area / S::from_i32(2);
    let lift = half_rho_a * lift_coefficient(pitch_deg) * speed * speed;
    forward * thrust + Vec3::up() * lift + side_axis(forward) * sway
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
        let pos = v(1.0, 5.0, 1.0);
        // Toward the goal, horizontal even when the goal is above.
        assert_eq!(
            forward_axis(
                pos,
                v(1.0, 0.0, 0.0),
                v(1.0, 0.0, 0.0),
                Some(v(1.0, 9.0, 4.0))
            ),
            v(0.0, 0.0, 1.0)
        );
        // Goal straight above: no horizontal direction, fall back to the velocity.
        assert_eq!(
            forward_axis(
                pos,
                v(0.0, 1.0, -2.0),
                v(1.0, 0.0, 0.0),
                Some(v(1.0, 9.0, 1.0))
            ),
            v(0.0, 0.0, -1.0)
        );
        // Hovering: the stored forward vector, normalized.
        assert_eq!(
            forward_axis(pos, v(0.0, 0.0, 0.0), v(0.0, 0.0, -3.0), None),
            v(0.0, 0.0, -1.0)
        );
        assert_eq!(
            forward_axis(pos, Vec3::zero(), Vec3::zero(), None),
            v(1.0, 0.0, 0.0)
        );
    }

    #[test]
    fn force_components_and_handedness() {
        let p = BeeParams::<f32>::default();
        let o = Vec3::new(1.0, 0.0, 0.0);
        assert_eq!(side_axis(o), Vec3::new(0.0, 0.0, 1.0));
        let f = oscillation_force(&p, o, 2.0, 16.0, 10.0);
        let rad = core::f32::consts::PI / 180.0;
        assert!(near(f.x, 9.81 * 16.0 * rad, 1e-5));
        assert!(near(
            f.y,
            0.5 * 1.225 * 0.05 * 4.0 * lift_coefficient(16.0),
            1e-6
        ));
        assert!(near(f.z, 9.81 * 10.0 * rad, 1e-5));
        let g = oscillation_force(
            &p.cast::<Fx>(),
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
