//! ORCA half-spaces of velocity space: the plane a neighbour induces (van den Berg, Guy, Lin
//! and Manocha, *Reciprocal n-body collision avoidance*, ISRR 2009, §5: ORCA^τ_{A|B} =
//! {v | (v − (v_A^opt + ½u))·n ≥ 0}, in 3D as RVO2-3D's `Agent::computeNewVelocity`) and the
//! plane a static obstacle surface induces (ours, ren2016 spec §2.5).

use super::{Body, Surface};
use crate::{Scalar, Vec3};

wire_type! {
    /// A half-space of velocity space: the valid side is `(v − point)·normal ≥ 0` (RVO2-3D's
    /// `Plane`). `normal` has unit length.
    #[derive(Clone, Copy, Debug, Default, PartialEq)]
    pub struct Plane<S> {
        /// A point on the boundary plane.
        pub point: Vec3<S>,
        /// The unit normal, pointing into the valid side.
        pub normal: Vec3<S>,
    }
}

impl<S: Scalar> Plane<S> {
    /// The plane through `point` with unit normal `normal`.
    #[inline]
    pub const fn new(point: Vec3<S>, normal: Vec3<S>) -> Self {
        Plane { point, normal }
    }

    /// How far `v` lies outside the half-space, `normal·(point − v)`: positive when `v`
    /// violates it (RVO2-3D's violation test `planes[i].normal * (planes[i].point - result) >
    /// 0`).
    #[inline]
    pub fn violation(&self, v: Vec3<S>) -> S {
        self.normal.dot(self.point - v)
    }
}

/// `v / s` as RVO2-3D's `Vector3::operator/` computes it: `v · (1/s)` (bit-identical to the
/// reference in `f32`).
#[inline]
pub(crate) fn div<S: Scalar>(v: Vec3<S>, s: S) -> Vec3<S> {
    v * (S::ONE / s)
}

/// The unit vector along `v` as RVO2-3D's `normalize` computes it (`v / abs(v)`) for `f32`;
/// [`Vec3::normalized`] (scaled, no overflow) for fixed point. `None` for a zero vector.
#[inline]
pub(crate) fn unit<S: Scalar>(v: Vec3<S>) -> Option<Vec3<S>> {
    if S::DIRECT_LENGTH {
        let l = v.length();
        (l > S::ZERO && l.is_finite()).then(|| div(v, l))
    } else {
        v.normalized()
    }
}

/// The ORCA plane agent `i` (`agent`) takes from neighbour `j` (`other`), taking half the
/// responsibility
/// (ORCA, van den Berg et al. 2009, §5, eq. (6): `point = v_i + ½u`, `normal = n`).
///
/// As RVO2-3D's `computeNewVelocity`, with `p = r_j − r_i`, `u_rel = v_i − v_j`,
/// `R = radius_i + radius_j`:
///
/// * no collision (`|p|² > R²`): `w = u_rel − p/τ`; if `w·p < 0` and `(w·p)² > R²|w|²` the
///   closest boundary point of the truncated velocity obstacle is on the cut-off sphere:
///   `n = ŵ`, `u = (R/τ − |w|)ŵ`; else on the cone: `a = |p|²`, `b = p·u_rel`,
///   `c = |u_rel|² − |p × u_rel|²/(|p|² − R²)`, `t = (b + √(b² − ac))/a`, `w = u_rel − t·p`,
///   `n = ŵ`, `u = (R·t − |w|)ŵ`;
/// * collision (`|p|² ≤ R²`): the cut-off sphere of one time step: `w = u_rel − p/Δt`,
///   `n = ŵ`, `u = (R/Δt − |w|)ŵ`.
///
/// `inv_tau` is 1/τ (time horizon), `inv_dt` is 1/Δt. Where RVO2-3D would divide by a zero
/// `|w|` (an exactly degenerate relative velocity) the normal falls back to `−p̂` (move away
/// from the neighbour, `u = (R/τ or R/Δt)·n` less the current approach); `None` when the two
/// agents also coincide (no direction to separate along: the plane is left out).
pub fn neighbour_plane<S: Scalar>(
    agent: &Body<S>,
    other: &Body<S>,
    inv_tau: S,
    inv_dt: S,
) -> Option<Plane<S>> {
    let half = S::from_f32(0.5);
    let rel_pos = other.pos - agent.pos;
    let rel_vel = agent.vel - other.vel;
    let dist_sq = rel_pos.length_sq();
    let r = agent.radius + other.radius;
    let r_sq = r * r;

    let (normal, u) = if dist_sq > r_sq {
        // No collision.
        let w = rel_vel - rel_pos * inv_tau;
        let w_len_sq = w.length_sq();
        let dot = w.dot(rel_pos);
        if dot < S::ZERO && dot * dot > r_sq * w_len_sq {
            // Project on the cut-off sphere.
            let w_len = w_len_sq.sqrt();
            let n = div(w, w_len);
            (n, n * (r * inv_tau - w_len))
        } else {
            // Project on the cone.
            let a = dist_sq;
            let b = rel_pos.dot(rel_vel);
            let c = rel_vel.length_sq() - rel_pos.cross(rel_vel).length_sq() / (dist_sq - r_sq);
            let t = (b + (b * b - a * c).sqrt()) / a;
            let ww = rel_vel - rel_pos * t;
            match unit(ww) {
                Some(n) => (n, n * (r * t - ww.length())),
                None => away(rel_pos, rel_vel, r * inv_tau)?,
            }
        }
    } else {
        // Collision: the cut-off sphere of one time step.
        let w = rel_vel - rel_pos * inv_dt;
        match unit(w) {
            Some(n) => (n, n * (r * inv_dt - w.length())),
            None => away(rel_pos, rel_vel, r * inv_dt)?,
        }
    };
    Some(Plane::new(agent.vel + u * half, normal))
}

/// The degenerate-`w` fallback of [`neighbour_plane`]: normal `−p̂`, and a `u` that makes the
/// relative velocity along it at least `speed` (away from the neighbour).
fn away<S: Scalar>(rel_pos: Vec3<S>, rel_vel: Vec3<S>, speed: S) -> Option<(Vec3<S>, Vec3<S>)> {
    let n = unit(-rel_pos)?;
    Some((n, n * (speed - rel_vel.dot(n))))
}

/// The hard plane a static obstacle surface induces (ours, ren2016 spec §2.5): with the
/// surface's closest point `surface.point`, its outward normal `n = surface.normal` (unit
/// length: [`solve`](super::solve) normalises it) and the agent's signed distance
/// `d = n·(pos − point)`,
///
/// * `n·v ≥ −(d − radius)/τ` when `d > radius` (the agent may approach the surface but not
///   reach it within the time horizon τ);
/// * `n·v ≥ (radius − d)/Δt` otherwise (leave the penetration within one step).
///
/// Full responsibility (no ½: the obstacle does not move). `inv_tau` is 1/τ, `inv_dt` 1/Δt.
pub fn obstacle_plane<S: Scalar>(
    agent: &Body<S>,
    surface: &Surface<S>,
    inv_tau: S,
    inv_dt: S,
) -> Plane<S> {
    let n = surface.normal;
    let d = n.dot(agent.pos - surface.point);
    let bound = if d > agent.radius {
        -(d - agent.radius) * inv_tau
    } else {
        (agent.radius - d) * inv_dt
    };
    Plane::new(n * bound, n)
}
