//! Visually-based roll-to-avoidance (chen §IV-B): field of view, the velocity tuning of eq. 5
//! and the body roll of eq. 6-7.

use super::frame::ObstacleSense;
use crate::{Scalar, Vec3};

/// cos 45°: the half-angle of the bee's 90° field of view (§IV-B, \[54\]).
const COS_HALF_FOV: f32 = core::f32::consts::FRAC_1_SQRT_2;

wire_type! {
    /// An obstacle the bee is avoiding: in its field of view and closer than d0 (§IV-B).
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct Sighting<S> {
        /// r_e = p_e − r: from the bee's mass point to the closest surface point (eq. 7).
        pub r_e: Vec3<S>,
        /// d = |r_e|.
        pub d: S,
        /// The surface's outward unit normal n at p_e.
        pub normal: Vec3<S>,
    }
}

/// Whether the direction `r_e` lies in the field of view around the unit forward axis `o`:
/// the angle α with cos α = o·r_e / (|o||r_e|) is at most 45° (§IV-B). A zero `r_e` (the bee
/// touches the surface) counts as seen.
pub fn in_fov<S: Scalar>(forward: Vec3<S>, r_e: Vec3<S>) -> bool {
    forward.dot(r_e) >= S::from_f32(COS_HALF_FOV) * r_e.length()
}

/// The obstacle as seen from `pos`, if it is closer than the threshold `d0` (§IV-B): r_e, d
/// and the unit normal. Eq. 5 tunes the velocity for it ([`tune_velocity`]) whether or not it
/// is in the field of view; whether it starts an avoidance is [`in_view`]'s call.
pub fn near<S: Scalar>(pos: Vec3<S>, obstacle: &ObstacleSense<S>, d0: S) -> Option<Sighting<S>> {
    let r_e = obstacle.point - pos;
    let d = r_e.length();
    (d < d0).then(|| Sighting {
        r_e,
        d,
        normal: obstacle.normal.normalized().unwrap_or(Vec3::up()),
    })
}

/// Whether a near obstacle (see [`near`]) makes the bee avoid it (§IV-B): it is in the field
/// of view around the unit forward axis, or the bee was already avoiding (`avoiding`) and the
/// obstacle is not behind it (o·r_e ≥ 0).
///
/// The paper starts an avoidance when the obstacle "enters the sensing area"; it does not say
/// when it ends, only that the bee "attempts to return to a horizontal posture once the
/// obstacle has been avoided". We end it when the obstacle is passed (behind the bee) or
/// farther than d0, so a bee sliding along a surface (o tangent to it, the obstacle at 90°)
/// keeps its avoidance roll until it is past.
pub fn in_view<S: Scalar>(forward: Vec3<S>, s: &Sighting<S>, avoiding: bool) -> bool {
    in_fov(forward, s.r_e) || (avoiding && forward.dot(s.r_e) >= S::ZERO)
}

/// [`near`] and [`in_view`] together: the obstacle the bee avoids, if any.
pub fn sense<S: Scalar>(
    pos: Vec3<S>,
    forward: Vec3<S>,
    obstacle: &ObstacleSense<S>,
    d0: S,
    avoiding: bool,
) -> Option<Sighting<S>> {
    near(pos, obstacle, d0).filter(|s| in_view(forward, s, avoiding))
}

/// Bridson's ramp of eq. 5: ramp(x) = 3/8 x⁵ − 10/8 x³ + 15/8 x for |x| < 1 and ±1 beyond
/// (odd; eq. 5 uses γ = |ramp(d/d0)| with x ≥ 0). Smooth, monotone, ramp(0) = 0, ramp(1) = 1.
///
/// Evaluated as 1 − (1 − x)³(1 + 9/8 x + 3/8 x²) on |x|, the same polynomial factored at its
/// triple root x = 1: exact at both ends and never above 1 in floating or fixed point.
pub fn ramp<S: Scalar>(x: S) -> S {
    let a = x.abs().min(S::ONE);
    let y = S::ONE - a;
    let poly = S::ONE + a * (S::from_f32(1.125) + a * S::from_f32(0.375));
    // Multiplying by y last keeps the fixed-point rounding error of y³·poly near ½ ulp.
    let r = S::ONE - y * (y * (y * poly));
    if x < S::ZERO { -r } else { r }
}

/// The tuned velocity of eq. 5: u* = u + (1 − γ)(u_t − u_0), γ = |ramp(d/d0)|, with u_0 the
/// velocity being tuned (this step's u) and u_t its tangential part; only an approach toward
/// the surface is tuned (a bee moving away keeps its velocity):
///
/// u* = u − (1 − γ)·n·min(n·u, 0).
///
/// Two departures from the printed equation, both to meet the bypass condition u·n = 0 that
/// the same paragraph states ("tune the magnitude of the bee's velocity to zero on the obstacle
/// while preserving the velocity vector for the slipping purpose"):
///
/// * u_t. The paper prints u_t = n(n·u_0), the *normal* part of u_0. With that, at the surface
///   (γ = 0, u = u_0) u* = n(n·u_0): the bee would fly straight along the normal, into or away
///   from the obstacle. We use the tangential part u_t = u_0 − n(n·u_0) (the curl-noise boundary
///   treatment of Bridson \[16\]).
/// * u_0. The paper's u_0 is the velocity where the bee first perceived the obstacle. Tuning
///   by that fixed vector leaves whatever the bee gained since (thrust, curl noise, neighbours
///   pushing) untouched, and in the Fig. 14 shaft field that carried bees into the shafts
///   (104 world corrections in 600 steps). Taking u_0 = u makes eq. 5 Bridson's ramp on the
///   current velocity: the normal approach speed is scaled by γ ≈ 15/8·d/d0 near the surface,
///   so a bee with |u|·Δt < d0 never reaches it.
///
/// The controller applies it for every obstacle closer than d0 ([`near`]), in the field of
/// view or not: in Bridson's curl noise, which eq. 5 is taken from, the ramp holds all around
/// a boundary, and a bee curving into a shaft at a glancing angle (more than 45° off its
/// forward axis) would otherwise fly into it.
pub fn tune_velocity<S: Scalar>(u: Vec3<S>, normal: Vec3<S>, d: S, d0: S) -> Vec3<S> {
    let gamma = ramp(d / d0).abs();
    let approach = normal.dot(u).min(S::ZERO);
    u - normal * (approach * (S::ONE - gamma))
}

/// The side value of eq. 7: y = [0, 1, 0]·(o × r_e) = o_z·r_e,x − o_x·r_e,z.
///
/// With y up and right-handed axes, y > 0 when the obstacle is on the bee's left.
pub fn side_value<S: Scalar>(forward: Vec3<S>, r_e: Vec3<S>) -> S {
    forward.cross(r_e).y
}

/// The avoidance roll of eq. 6, in degrees: θ_roll = sign(y)·exp(−|d0 − d|²/2)·45°, y from
/// eq. 7 ([`side_value`]).
///
/// Sign: sign(0) is taken as +1 (an obstacle dead ahead; the paper's sign function returns only
/// ±1). A positive roll sways the bee to its right ([`side_axis`](super::oscillation::side_axis)),
/// so an obstacle on the left (y > 0) makes the bee roll and sway right, away from it, and
/// vice versa.
///
/// Magnitude: §IV-B says the roll "gradually increases as the bee approaches the obstacle", but
/// eq. 6 as printed peaks (45°) at d = d0 and decreases toward exp(−d0²/2)·45° at contact. We
/// follow the equation.
pub fn avoidance_roll_deg<S: Scalar>(forward: Vec3<S>, r_e: Vec3<S>, d: S, d0: S) -> S {
    let sign = if side_value(forward, r_e) < S::ZERO {
        -S::ONE
    } else {
        S::ONE
    };
    let gap = d0 - d;
    sign * (-(gap * gap) / S::from_i32(2)).exp() * S::from_i32(45)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Fx;

    fn v<S: Scalar>(x: f32, y: f32, z: f32) -> Vec3<S> {
        Vec3::from_f32(x, y, z)
    }

    #[test]
    fn ramp_ends_and_monotone() {
        assert_eq!(ramp(0.0f32), 0.0);
        assert_eq!(ramp(Fx::ZERO), Fx::ZERO);
        for x in [1.0f32, 1.5, 100.0] {
            assert_eq!(ramp(x), 1.0);
            assert_eq!(ramp(Fx::from_f32(x)), Fx::ONE);
        }
        assert!((ramp(0.999_999f32) - 1.0).abs() < 1e-5);
        let (mut prev, mut prev_fx) = (0.0f32, Fx::ZERO);
        for i in 1..=1000 {
            let x = i as f32 / 1000.0;
            let (r, r_fx) = (ramp(x), ramp(Fx::from_f32(x)));
            assert!(r >= prev && r_fx >= prev_fx, "ramp not monotone at {x}");
            assert!(r <= 1.0 && r_fx <= Fx::ONE);
            assert!((r - r_fx.to_f32()).abs() < 1e-4);
            let poly = 3.0 / 8.0 * x.powi(5) - 10.0 / 8.0 * x.powi(3) + 15.0 / 8.0 * x;
            assert!(
                (r - poly).abs() < 1e-6,
                "ramp({x}) = {r}, eq. 5 gives {poly}"
            );
            (prev, prev_fx) = (r, r_fx);
        }
        assert_eq!(ramp(-2.0f32), -1.0);
        // Every fixed-point value in [0, 1]: monotone, exactly.
        let mut prev = Fx::ZERO;
        for bits in 0..=65_536 {
            let r = ramp(Fx::from_bits(bits));
            assert!(
                r >= prev && r <= Fx::ONE,
                "Fx ramp not monotone at {bits} ulp"
            );
            prev = r;
        }
    }

    fn fov_case<S: Scalar>() {
        let o = v::<S>(1.0, 0.0, 0.0);
        assert!(in_fov(o, v(1.0, 0.0, 0.0)));
        assert!(in_fov(o, v(1.0, 0.0, 0.99))); // 44.7°
        assert!(in_fov(o, v(1.0, 0.9, 0.0)));
        assert!(!in_fov(o, v(1.0, 0.0, 1.02))); // 45.6°
        assert!(!in_fov(o, v(0.0, 0.0, -1.0)));
        assert!(!in_fov(o, v(-1.0, 0.0, 0.0)));
        let obstacle = |x, z| ObstacleSense {
            point: v::<S>(x, 0.0, z),
            normal: v(-1.0, 0.0, 0.0),
        };
        let d0 = S::from_f32(2.0);
        for avoiding in [false, true] {
            assert!(sense(Vec3::zero(), o, &obstacle(1.0, 0.5), d0, avoiding).is_some());
            // Close but behind: ignored.
            assert!(sense(Vec3::zero(), o, &obstacle(-0.5, 0.0), d0, avoiding).is_none());
            // In view but beyond d0: ignored.
            assert!(sense(Vec3::zero(), o, &obstacle(2.5, 0.0), d0, avoiding).is_none());
        }
        // Close beside: ignored unless an avoidance goes on.
        assert!(sense(Vec3::zero(), o, &obstacle(0.5, 0.6), d0, false).is_none());
        assert!(sense(Vec3::zero(), o, &obstacle(0.0, 0.6), d0, true).is_some());
        assert!(sense(Vec3::zero(), o, &obstacle(-0.1, 0.6), d0, true).is_none());
    }

    #[test]
    fn obstacle_outside_45_degrees_is_ignored() {
        fov_case::<f32>();
        fov_case::<Fx>();
    }

    fn tangent_case<S: Scalar>(tol: f32) {
        let n = v::<S>(-0.6, 0.0, -0.8);
        let u0 = v::<S>(1.0, 0.3, 2.0);
        let d0 = S::from_f32(2.0);
        let u = tune_velocity(u0, n, S::ZERO, d0);
        assert!(u.dot(n).to_f32().abs() < tol, "u*·n = {:?}", u.dot(n));
        // The tangential part is kept.
        let t = u0 - n * n.dot(u0);
        assert!((u - t).to_f32().length() < tol);
        // Far from the surface (d ≥ d0) nothing changes.
        assert_eq!(tune_velocity(u0, n, d0, d0), u0);
        // In between the normal component is partly removed.
        let mid = tune_velocity(u0, n, S::ONE, d0).dot(n).to_f32();
        assert!(mid.abs() < u0.dot(n).to_f32().abs() && mid * u0.dot(n).to_f32() > 0.0);
        // Moving away from the surface: untouched.
        assert_eq!(tune_velocity(-u0, n, S::ZERO, d0), -u0);
    }

    /// A bee flying straight at a wall with every step tuned by eq. 5 slows down and never
    /// reaches it (at the speed limit, 4 units/s, Δt = 0.05 s, d0 = 2).
    fn approach_case<S: Scalar>() {
        let n = v::<S>(-1.0, 0.0, 0.0);
        let (d0, dt) = (S::from_f32(2.0), S::from_f32(0.05));
        let mut d = S::from_f32(1.99);
        for _ in 0..400 {
            let u = tune_velocity(v::<S>(4.0, 0.0, 1.0), n, d, d0);
            assert!(u.z == S::ONE, "the tangential velocity is kept");
            d -= u.x * dt;
            assert!(d > S::ZERO, "reached the wall");
        }
    }

    #[test]
    fn tuned_velocity_is_tangent_at_contact() {
        tangent_case::<f32>(1e-6);
        tangent_case::<Fx>(1e-3);
    }

    #[test]
    fn eq5_alone_keeps_a_bee_off_the_surface() {
        approach_case::<f32>();
        approach_case::<Fx>();
    }

    fn roll_case<S: Scalar>(tol: f32) {
        let o = v::<S>(1.0, 0.0, 0.0);
        let d0 = 2.0f32;
        // Facing +x with y up, the bee's left is −z.
        let left = v::<S>(1.0, 0.0, -0.5);
        let right = v::<S>(1.0, 0.0, 0.5);
        assert!(side_value(o, left) > S::ZERO);
        assert!(side_value(o, right) < S::ZERO);
        for d in [0.0f32, 0.5, 1.0, 1.5, 1.99] {
            let want = (-(d0 - d) * (d0 - d) / 2.0).exp() * 45.0;
            let (ds, d0s) = (S::from_f32(d), S::from_f32(d0));
            let l = avoidance_roll_deg(o, left, ds, d0s).to_f32();
            let r = avoidance_roll_deg(o, right, ds, d0s).to_f32();
            assert!(
                (l - want).abs() < tol,
                "roll({d}) = {l}, eq. 6 gives {want}"
            );
            assert!(
                (r + want).abs() < tol,
                "roll({d}) = {r}, eq. 6 gives {}",
                -want
            );
        }
        // Dead ahead: sign(0) = +1.
        assert!(avoidance_roll_deg(o, v(1.0, 0.0, 0.0), S::ONE, S::from_f32(d0)) > S::ZERO);
    }

    #[test]
    fn roll_sign_flips_left_right_and_magnitude_matches_eq6() {
        roll_case::<f32>(1e-4);
        roll_case::<Fx>(1e-2);
    }
}
