//! The local velocity V_l (wang2014 §4, eq. 1-3): the curl of the boundary-modulated Perlin
//! potential, and the two baselines of §7.1.

use super::frame::Boundary;
use super::params::{NOISE_PERLIN, NOISE_RANDOM, WangParams};
use crate::bee::curl::{curl_force, potential};
use crate::bee::vision::ramp;
use crate::rand::{self, stream};
use crate::{Scalar, StepCtx, Vec3};

/// α'(r) of eq. 3 for r in [0, 1]: 15/8·(r² − 1)² (α'(0) = 15/8, α'(1) = 0).
#[inline]
pub fn ramp_slope<S: Scalar>(r: S) -> S {
    let u = r * r - S::ONE;
    S::from_f32(1.875) * u * u
}

/// The bounded curl noise V_l = ∇ × N of eq. 1 with N the boundary-modulated potential of
/// eq. 2, N = α P + (1 − α)(n·P) n, P = gain·(P1, P2, P3)(x/scale) (§4; the Perlin vector of
/// [`bee::curl::potential`](crate::bee::curl::potential), three seeds, analytic gradients).
///
/// Evaluated in closed form (ours, spec §2.1), with a = α(d/d0) (eq. 3,
/// [`bee::vision::ramp`](crate::bee::vision::ramp)), ∇a = α'(d/d0)/d0·n, J_P the Jacobian of P
/// (rows ∇P_k) and H_d the Hessian of the distance (∇n = H_d, ∇ × n = 0):
///
/// V_l = a (∇ × P) + ∇a × P + (1 − a)(J_Pᵀ n + H_d P) × n
///
/// (the term −(n·P)(∇a × n) of the product rule vanishes, ∇a ∥ n). d = (x − point)·n,
/// clamped to ≥ 0; H_d = curvature·(I − n nᵀ − axis axisᵀ) from the [`Boundary`]. The normal
/// component of every term but the first is zero, and a = 0 on the surface: no flux through
/// it (Fig. 3). With H_d exact the field is exactly divergence-free; with curvature 0 near a
/// curved surface its divergence is O(gain/(scale·ρ)) (spec W-T5).
///
/// With no boundary, or d ≥ d0, this is exactly
/// [`bee::curl::curl_force`](crate::bee::curl::curl_force) (α = 1).
pub fn curl_noise<S: Scalar>(
    pos: Vec3<S>,
    scale: S,
    gain: S,
    d0: S,
    boundary: Option<&Boundary<S>>,
) -> Vec3<S> {
    let Some(b) = boundary else {
        return curl_force(pos, scale, gain);
    };
    let n = b.normal.normalized().unwrap_or(b.normal);
    let d = (pos - b.point).dot(n).max(S::ZERO);
    if d >= d0 {
        return curl_force(pos, scale, gain);
    }
    let r = d / d0;
    let a = ramp(r);
    let grad_a = n * (ramp_slope(r) / d0);
    let [p1, p2, p3] = potential(pos, scale, gain);
    let p = Vec3::new(p1.value, p2.value, p3.value);
    let curl = Vec3::new(
        p3.grad.y - p2.grad.z,
        p1.grad.z - p3.grad.x,
        p2.grad.x - p1.grad.y,
    );
    // J_Pᵀ n = Σ_k n_k ∇P_k.
    let jtn = p1.grad * n.x + p2.grad * n.y + p3.grad * n.z;
    // H_d P = κ (P − n (n·P) − a (a·P)).
    let hp = (p - n * n.dot(p) - b.axis * b.axis.dot(p)) * b.curvature;
    curl * a + grad_a.cross(p) + (jtn + hp).cross(n) * (S::ONE - a)
}

/// The Perlin vector P(x) = gain·(P1, P2, P3)(x/scale) itself (§4): the compressible
/// baseline of §7.1 ("Perlin noise", ours as a V_l source).
pub fn perlin_velocity<S: Scalar>(pos: Vec3<S>, scale: S, gain: S) -> Vec3<S> {
    let [p1, p2, p3] = potential(pos, scale, gain);
    Vec3::new(p1.value, p2.value, p3.value)
}

/// A uniform vector in [−gain, gain]³, drawn afresh for each insect and step from the streams
/// [`WANG_NOISE_X`](stream::WANG_NOISE_X), `_Y`, `_Z`: the "random noise" baseline of §7.1
/// (ours as a V_l source).
pub fn random_velocity<S: Scalar>(gain: S, ctx: StepCtx) -> Vec3<S> {
    let draw = |s: u32| {
        let u: S = rand::unit(ctx, s);
        (u + u - S::ONE) * gain
    };
    Vec3::new(
        draw(stream::WANG_NOISE_X),
        draw(stream::WANG_NOISE_Y),
        draw(stream::WANG_NOISE_Z),
    )
}

/// V_l from the source [`WangParams::noise`] selects: the bounded curl noise
/// ([`curl_noise`], the model), the Perlin vector ([`perlin_velocity`]) or uniform random
/// noise ([`random_velocity`]). The baselines ignore the boundary.
pub fn noise_velocity<S: Scalar>(
    pos: Vec3<S>,
    boundary: Option<&Boundary<S>>,
    params: &WangParams<S>,
    ctx: StepCtx,
) -> Vec3<S> {
    match params.noise {
        NOISE_PERLIN => perlin_velocity(pos, params.scale, params.gain),
        NOISE_RANDOM => random_velocity(params.gain, ctx),
        _ => curl_noise(pos, params.scale, params.gain, params.d0, boundary),
    }
}
