//! The forces of Eq. 2-5: the zone interaction F_int (Eq. 5), friction and the stimulus
//! response (F_pro, Eq. 3), and the inherent noise F_ξ (Eq. 4 and the Fig. 10 candidates).

use super::frame::{FlyState, Neighbour, Stimulus};
use super::params::{FlyParams, NOISE_CURL, NOISE_GAUSSIAN, NOISE_PERLIN, NOISE_WHITE};
use crate::bee::curl::{curl_force, potential};
use crate::rand::{self, stream};
use crate::scalar::pi;
use crate::{Scalar, StepCtx, Vec3};

/// The zone of a neighbour at distance `r` (g of Eq. 5): repulsion on [0, r_rep), alignment
/// on [r_rep, r_ali), attraction on [r_ali, r_att], none beyond.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Zone {
    /// g = −1: −r̂_ji, away from j.
    Repulsion,
    /// g = 0: v̂_ji, along the relative velocity.
    Alignment,
    /// g = 1: +r̂_ji, towards j.
    Attraction,
}

/// The zone of distance `r` under `p`'s radii (R-T1), `None` beyond r_att.
pub fn zone<S: Scalar>(r: S, p: &FlyParams<S>) -> Option<Zone> {
    if r < p.r_rep {
        Some(Zone::Repulsion)
    } else if r < p.r_ali {
        Some(Zone::Alignment)
    } else if r <= p.r_att {
        Some(Zone::Attraction)
    } else {
        None
    }
}

/// F_int of Eq. 5: per zone k, (χ_k/N_k)·Σ_j (g r̂_ji + (1 − |g|) v̂_ji) over the neighbours
/// within r_att in that zone (a zone with N_k = 0 adds nothing), r̂_ji = (r_j − r_i)/r_ji,
/// v̂_ji = (v_j − v_i)/‖v_j − v_i‖. Ours (spec §2.1): a coincident neighbour (r̂ undefined)
/// and the insect's own id are skipped; v̂_ji = 0 where the relative velocity cannot be
/// normalised. Each zone's sum runs in the frame's order.
pub fn zone_force<S: Scalar>(
    me: &FlyState<S>,
    id: u32,
    neighbours: &[Neighbour<S>],
    p: &FlyParams<S>,
) -> Vec3<S> {
    // (sum, count) per zone: repulsion, alignment, attraction.
    let mut sums = [(Vec3::<S>::zero(), 0u16); 3];
    for n in neighbours.iter().filter(|n| n.id != id) {
        let d = n.pos - me.pos;
        let Some(r_hat) = d.normalized() else {
            continue;
        };
        let (k, term) = match zone(d.length(), p) {
            Some(Zone::Repulsion) => (0, -r_hat),
            Some(Zone::Alignment) => (1, (n.vel - me.vel).normalized().unwrap_or(Vec3::zero())),
            Some(Zone::Attraction) => (2, r_hat),
            None => continue,
        };
        sums[k].0 += term;
        sums[k].1 += 1;
    }
    let weights = [p.chi_rep, p.chi_ali, p.chi_att];
    let mut f = Vec3::zero();
    for ((sum, count), chi) in sums.into_iter().zip(weights) {
        if count > 0 {
            f += sum * (chi / S::from_i32(i32::from(count)));
        }
    }
    f
}

/// F_fric = −γ‖v‖v (Materials and Methods, "Self-propulsion"): quadratic drag.
pub fn friction<S: Scalar>(vel: Vec3<S>, gamma: S) -> Vec3<S> {
    vel * -(gamma * vel.length())
}

/// The stimulus response F_res = χ_res·H(r_res − r_ie)·(s_e r̂_ie R(n, θ) − (1 − s_e) r̂_ie)
/// with r̂_ie = (r_i − r_e)/r_ie pointing away from the stimulus (spec R10) and R(n, θ) the
/// right-hand rotation about n = +y by θ. Pursuit (s_e = 0) heads straight at the target;
/// escape (s_e = 1) heads away from the predator turned by θ, so the angle to the threat is
/// 90-180° (Fig. 20a).
///
/// θ is drawn when a predator enters r_res ([`rand::unit`], stream
/// [`FLY_ESCAPE`](stream::FLY_ESCAPE); θ ~ U[−π/2, 0], or U[−π/2, π/2] with
/// `escape_sides` 1) and kept while it stays in range (ours, spec §2.3). Returns the force
/// and the insect's next (θ, escaping). Nothing in range, or the insect on the stimulus:
/// no force.
pub fn response<S: Scalar>(
    me: &FlyState<S>,
    stimulus: Option<&Stimulus<S>>,
    p: &FlyParams<S>,
    ctx: StepCtx,
) -> (Vec3<S>, S, bool) {
    let away = stimulus.and_then(|s| {
        let d = me.pos - s.pos;
        (d.length() <= p.r_res).then_some((s, d))
    });
    let Some((s, d)) = away else {
        return (Vec3::zero(), me.escape_theta, false);
    };
    let r_hat = d.normalized().unwrap_or(Vec3::zero());
    if !s.is_predator() {
        return (-r_hat * p.chi_res, me.escape_theta, false);
    }
    let theta = if me.escaping {
        me.escape_theta
    } else {
        let u: S = rand::unit(ctx, stream::FLY_ESCAPE);
        let half_pi = pi::<S>() * S::from_f32(0.5);
        if p.escape_sides == 0 {
            -(u * half_pi)
        } else {
            (u + u - S::ONE) * half_pi
        }
    };
    let (sin, cos) = theta.sin_cos();
    let turned = Vec3::new(
        r_hat.x * cos + r_hat.z * sin,
        r_hat.y,
        r_hat.z * cos - r_hat.x * sin,
    );
    (turned * p.chi_res, theta, true)
}

/// F_ξ (Eq. 4 and Fig. 10), by [`FlyParams::noise`]:
///
/// * curl: [`bee::curl::curl_force`](crate::bee::curl::curl_force)(r, scale, gain), ∇ × P
///   with P = gain·Per(r/scale) (the model);
/// * Perlin: P(r) itself ([`bee::curl::potential`](crate::bee::curl::potential) values);
/// * white: gain·U(−1, 1)³, drawn per insect and step (streams
///   [`FLY_NOISE_X`](stream::FLY_NOISE_X), `_Y`, `_Z`);
/// * Gaussian: gain times three standard normals, each the sum of four U(−1, 1) draws scaled
///   to unit variance (ours: the Scalar trait has no logarithm for Box–Muller's √(−2 ln W),
///   and a fixed-point device has none either; the Irwin–Hall sum matches the first four
///   moments closely; streams `FLY_NOISE_X` … with offsets);
/// * none: zero ("dynamics only", Fig. 13).
pub fn noise_force<S: Scalar>(pos: Vec3<S>, p: &FlyParams<S>, ctx: StepCtx) -> Vec3<S> {
    let uniform = |s: u32| {
        let u: S = rand::unit(ctx, s);
        u + u - S::ONE
    };
    let axes = [
        stream::FLY_NOISE_X,
        stream::FLY_NOISE_Y,
        stream::FLY_NOISE_Z,
    ];
    match p.noise {
        NOISE_CURL => curl_force(pos, p.scale, p.gain),
        NOISE_PERLIN => {
            let [a, b, c] = potential(pos, p.scale, p.gain);
            Vec3::new(a.value, b.value, c.value)
        }
        NOISE_WHITE => {
            let [x, y, z] = axes.map(uniform);
            Vec3::new(x, y, z) * p.gain
        }
        NOISE_GAUSSIAN => {
            // Var(U(−1, 1)) = 1/3: four of them sum to variance 4/3; × √(3/4) → 1.
            let norm = S::from_f32(0.866_025_4);
            let [x, y, z] = axes.map(|s| {
                let sum = (0..4u32).fold(S::ZERO, |acc, k| acc + uniform(s + (k << 8)));
                sum * norm
            });
            Vec3::new(x, y, z) * p.gain
        }
        // NOISE_NONE (validated parameters hold nothing else).
        _ => Vec3::zero(),
    }
}
