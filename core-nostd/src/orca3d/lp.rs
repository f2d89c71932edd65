//! The incremental linear programs of ORCA (van den Berg, Guy, Lin and Manocha, *Reciprocal
//! n-body collision avoidance*, ISRR 2009, §5.2: Seidel-style randomised-incremental LP, here
//! in the caller's deterministic order), ported from RVO2-3D's `Agent.cc`
//! (`linearProgram1..4`): minimise `‖v − v_opt‖` (or maximise `v·v_opt` for a unit `v_opt`
//! when optimising a direction) subject to half-spaces [`Plane`] and the speed sphere
//! `‖v‖ ≤ radius`.
//!
//! No recursion, no allocation: LP3 calls LP2 calls LP1, and LP4 builds its projected planes in
//! a [`heapless::Vec`] of const capacity `N`. Arithmetic follows RVO2-3D operation by
//! operation, so `f32` results match the reference library's `float` ones.

use heapless::Vec as HVec;

use super::plane::{Plane, unit};
use crate::{Scalar, Vec3};

/// RVO2-3D's `RVO3D_EPSILON`: the threshold of its parallelism tests (squared sines).
pub const RVO_EPSILON: f32 = 1e-5;

/// A directed line `point + t·direction` (`direction` of unit length).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Line<S> {
    /// The direction (unit length).
    pub direction: Vec3<S>,
    /// A point on the line.
    pub point: Vec3<S>,
}

/// `RVO_EPSILON` in `S`.
#[inline]
fn eps<S: Scalar>() -> S {
    S::from_f32(RVO_EPSILON)
}

/// The 1D LP on `line` (RVO2-3D `linearProgram1`) subject to the half-spaces `planes` (the
/// planes before the one the line lies on) and `‖v‖ ≤ radius`. With `direction_opt` the
/// extreme point along `opt` is returned, else the point closest to `opt`. `None` if the
/// constraints leave nothing of the line.
pub fn linear_program1<S: Scalar>(
    planes: &[Plane<S>],
    line: &Line<S>,
    radius: S,
    opt: Vec3<S>,
    direction_opt: bool,
) -> Option<Vec3<S>> {
    let dot = line.point.dot(line.direction);
    let discriminant = dot * dot + radius * radius - line.point.length_sq();
    if discriminant < S::ZERO {
        // The max-speed sphere fully invalidates the line.
        return None;
    }
    let sqrt_d = discriminant.sqrt();
    let mut t_left = -dot - sqrt_d;
    let mut t_right = -dot + sqrt_d;

    for p in planes {
        let numerator = (p.point - line.point).dot(p.normal);
        let denominator = line.direction.dot(p.normal);
        if denominator * denominator <= eps() {
            // The line is (almost) parallel to plane p.
            if numerator > S::ZERO {
                return None;
            }
            continue;
        }
        let t = numerator / denominator;
        if denominator >= S::ZERO {
            // Plane p bounds the line on the left.
            t_left = t_left.max(t);
        } else {
            // Plane p bounds the line on the right.
            t_right = t_right.min(t);
        }
        if t_left > t_right {
            return None;
        }
    }

    let at = |t: S| line.point + line.direction * t;
    Some(if direction_opt {
        if opt.dot(line.direction) > S::ZERO {
            at(t_right)
        } else {
            at(t_left)
        }
    } else {
        let t = line.direction.dot(opt - line.point);
        if t < t_left {
            at(t_left)
        } else if t > t_right {
            at(t_right)
        } else {
            at(t)
        }
    })
}

/// The 2D LP on `plane` (RVO2-3D `linearProgram2`) subject to the half-spaces `planes` (those
/// before it) and `‖v‖ ≤ radius`. `None` if infeasible.
pub fn linear_program2<S: Scalar>(
    planes: &[Plane<S>],
    plane: &Plane<S>,
    radius: S,
    opt: Vec3<S>,
    direction_opt: bool,
) -> Option<Vec3<S>> {
    let plane_dist = plane.point.dot(plane.normal);
    let plane_dist_sq = plane_dist * plane_dist;
    let radius_sq = radius * radius;
    if plane_dist_sq > radius_sq {
        // The max-speed sphere fully invalidates the plane.
        return None;
    }
    let plane_radius_sq = radius_sq - plane_dist_sq;
    let plane_center = plane.normal * plane_dist;

    let mut result = if direction_opt {
        // Project the direction opt on the plane.
        let plane_opt = opt - plane.normal * opt.dot(plane.normal);
        let len_sq = plane_opt.length_sq();
        if len_sq <= eps() {
            plane_center
        } else {
            plane_center + plane_opt * (plane_radius_sq / len_sq).sqrt()
        }
    } else {
        // Project the point opt on the plane.
        let r = opt + plane.normal * (plane.point - opt).dot(plane.normal);
        // If outside the plane's circle, project on the circle.
        if r.length_sq() > radius_sq {
            let pr = r - plane_center;
            let pr_len_sq = pr.length_sq();
            if pr_len_sq > S::ZERO {
                plane_center + pr * (plane_radius_sq / pr_len_sq).sqrt()
            } else {
                // Only reachable through rounding (RVO2-3D would give NaN here).
                plane_center
            }
        } else {
            r
        }
    };

    for (i, p) in planes.iter().enumerate() {
        if p.violation(result) > S::ZERO {
            // The result violates plane i: solve on the intersection line of plane i and this
            // plane.
            let cross = p.normal.cross(plane.normal);
            if cross.length_sq() <= eps() {
                // (Almost) parallel: plane i fully invalidates this plane.
                return None;
            }
            let direction = unit(cross)?;
            let line_normal = direction.cross(plane.normal);
            let point = plane.point
                + line_normal * ((p.point - plane.point).dot(p.normal) / line_normal.dot(p.normal));
            let line = Line { direction, point };
            result = linear_program1(planes.get(..i)?, &line, radius, opt, direction_opt)?;
        }
    }
    Some(result)
}

/// The 3D LP (RVO2-3D `linearProgram3`): the velocity within `‖v‖ ≤ radius` closest to `opt`
/// (or, with `direction_opt`, extreme along the unit vector `opt`) satisfying every plane,
/// adding the planes in order. Returns the result and the index of the plane it failed on
/// (`planes.len()` on success); on failure the result is the optimum of the planes before it.
pub fn linear_program3<S: Scalar>(
    planes: &[Plane<S>],
    radius: S,
    opt: Vec3<S>,
    direction_opt: bool,
) -> (Vec3<S>, usize) {
    let mut result = if direction_opt {
        // Optimise a direction: opt has unit length.
        opt * radius
    } else if opt.length_sq() > radius * radius {
        // Closest point, opt outside the sphere.
        unit(opt).map_or(Vec3::zero(), |u| u * radius)
    } else {
        // Closest point, opt inside the sphere.
        opt
    };

    for (i, p) in planes.iter().enumerate() {
        if p.violation(result) > S::ZERO {
            let prefix = planes.get(..i).unwrap_or(&[]);
            match linear_program2(prefix, p, radius, opt, direction_opt) {
                Some(r) => result = r,
                None => return (result, i),
            }
        }
    }
    (result, planes.len())
}

/// The 4D LP (RVO2-3D `linearProgram4`), for when [`linear_program3`] failed at plane
/// `begin`: the velocity minimising the largest penetration of the planes `begin..`, found
/// plane by plane by a direction-optimising LP3 over the planes projected onto the bisectors
/// with the current plane. The first `hard` planes (static obstacles, ours, as RVO2's 2D
/// library keeps its obstacle lines) are kept as they are, never relaxed.
///
/// `result` is LP3's partial result. The projected planes are built in a fixed-capacity
/// vector of `N` planes: planes beyond it are left out of the projection (callers pass
/// `planes.len() ≤ N`, as [`solve`](super::solve) does).
pub fn linear_program4<S: Scalar, const N: usize>(
    planes: &[Plane<S>],
    begin: usize,
    hard: usize,
    radius: S,
    mut result: Vec3<S>,
) -> Vec3<S> {
    let half = S::from_f32(0.5);
    let mut distance = S::ZERO;
    let hard = hard.min(planes.len());

    for (i, pi) in planes.iter().enumerate().skip(begin) {
        if pi.violation(result) > distance {
            // The result violates plane i by more than the current penetration.
            // The hard planes as they are (RVO2 2D's `projLines(lines.begin(),
            // lines.begin() + numObstLines)`), then the soft planes before i, projected.
            let mut proj: HVec<Plane<S>, N> = HVec::new();
            for pj in planes.get(..hard).unwrap_or(&[]) {
                let _ = proj.push(*pj);
            }
            for pj in planes.get(hard..i).unwrap_or(&[]) {
                let cross = pj.normal.cross(pi.normal);
                let point = if cross.length_sq() <= eps() {
                    // Planes i and j are (almost) parallel.
                    if pi.normal.dot(pj.normal) > S::ZERO {
                        // Same direction: j adds nothing.
                        continue;
                    }
                    // Opposite directions.
                    (pi.point + pj.point) * half
                } else {
                    // A point on the intersection line of planes i and j.
                    let line_normal = cross.cross(pi.normal);
                    pi.point
                        + line_normal
                            * ((pj.point - pi.point).dot(pj.normal) / line_normal.dot(pj.normal))
                };
                let Some(normal) = unit(pj.normal - pi.normal) else {
                    continue;
                };
                let _ = proj.push(Plane::new(point, normal));
            }

            let (r, fail) = linear_program3(&proj, radius, pi.normal, true);
            // On failure (floating-point error only: the current result is feasible for the
            // projected planes) the current result is kept.
            if fail >= proj.len() {
                result = r;
            }
            distance = pi.violation(result);
        }
    }
    result
}
