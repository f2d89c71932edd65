//! Obstacles (xiang2018 §4.2.2, "obstacles > external disturbance > food = nest"): the avoiding
//! turn of Fig. 5b, going round an obstacle that blocks the way to the goal, and the hard
//! constraint that keeps the move of eq. 5 out of every obstacle the ant senses.

use super::frame::{AntObject, Surface};
use super::params::AntParams;
use super::state::{AntState, Follow, Turn, WINDING_LIMIT};
use crate::rand::{self, stream};
use crate::{Scalar, StepCtx, Vec2};

/// How far in front of an obstacle surface a move ends at the least (units): room for the
/// rounding of positions to `f32` or [`Fx`](crate::Fx) and of the sensed surfaces.
pub const SURFACE_MARGIN: f32 = 1.0 / 64.0;

/// The nearest surface to go round: an obstacle, or with `disturbances` also the rim of a
/// disturbance's dangerous circle the ant is outside of (an ant inside escapes instead); the
/// flag tells a rim.
fn nearest_surface<S: Scalar>(
    pos: Vec2<S>,
    objects: &[AntObject<S>],
    disturbances: bool,
) -> Option<(S, Surface<S>, bool)> {
    let mut best: Option<(S, Surface<S>, bool)> = None;
    for o in objects {
        let found = match *o {
            AntObject::Obstacle(surface) => {
                // Inside (the normal points from the ant to the surface): distance 0.
                let away = pos - surface.closest;
                let dist = if away.dot(surface.normal) < S::ZERO {
                    S::ZERO
                } else {
                    away.length()
                };
                Some((dist, surface, false))
            }
            AntObject::Disturbance { center, radius } if disturbances => {
                let away = pos - center;
                let len = away.length();
                away.normalized().filter(|_| len >= radius).map(|u| {
                    let surface = Surface {
                        closest: center + u * radius,
                        normal: u,
                    };
                    (len - radius, surface, true)
                })
            }
            _ => None,
        };
        if let Some((dist, surface, rim)) = found
            && best.is_none_or(|(d, _, _)| dist < d)
        {
            best = Some((dist, surface, rim));
        }
    }
    best
}

/// The direction along the surface with normal `n`, the way `turn` goes round.
pub fn tangent<S: Scalar>(n: Vec2<S>, turn: Turn) -> Vec2<S> {
    match turn {
        Turn::Ccw => n.perp(),
        Turn::Cw => -n.perp(),
    }
}

/// What the nearest obstacle makes an ant heading `heading` do this tick (§4.2.2), if anything:
/// the new heading, and the [`Follow`] the ant keeps (ours) when it has a goal.
///
/// * **Avoiding** (Fig. 5b, the paper's rule): an obstacle ahead (the heading points into its
///   surface) within `avoid_range` turns the ant perpendicular to the ant-obstacle line, on the
///   side of its heading (the smaller turn; a random side when exactly head-on).
/// * **Going round** (ours): an ant with a goal that meets an obstacle ahead within twice the
///   avoiding range (or the rim of a disturbance's dangerous circle, which it would otherwise
///   walk back into as soon as it escaped, §4.2.2 Fig. 5c) turns along the surface on the
///   shorter side and keeps to it, between half and the whole avoiding range from the surface
///   (a rim: one to two avoiding ranges), until the way toward the goal is free: the goal lies in
///   front of the surface and the angle from the goal direction to the way along the surface,
///   followed continuously from tick to tick (`winding`, Pledge's counter, in quarter turns; it
///   changes with the surface, not with the neighbours' pushes), is at most a quarter turn.
///   Round a wall the ant lets go at the far corner; in a cup whose mouth faces away from the
///   goal the winding is half a turn, so the ant follows the wall out over the lip and round
///   the outside. It lets go of a surface more than twice the avoiding range away (the
///   obstacle was removed, or the ant was pushed off).
pub fn obstacle_heading<S: Scalar>(
    s: &AntState<S>,
    heading: Vec2<S>,
    objects: &[AntObject<S>],
    params: &AntParams<S>,
    ctx: StepCtx,
) -> Option<(Vec2<S>, Option<Follow<S>>)> {
    let goal = s.goal.and_then(|g| (g - s.pos).normalized());
    let (dist, surface, rim) = nearest_surface(s.pos, objects, goal.is_some())?;
    let n = surface.normal;
    // Round a danger the ants keep farther off (ours): escaping ants leave its circle before
    // they meet the ones going round.
    let near = if rim {
        params.avoid_range
    } else {
        params.avoid_range / S::from_i32(2)
    };
    if let (Some(f), Some(g)) = (s.follow, goal)
        && dist <= params.avoid_range + near + near
    {
        let winding = unwrap(turn_angle(g, tangent(n, f.turn)), f.winding);
        // A quarter turn, and a little for the rounding.
        let free = g.dot(n) > S::ZERO && winding.abs() <= S::from_f32(1.03);
        if !free {
            let h = follow_heading(n, dist, f.turn, near, near + near);
            return Some((h, Some(Follow { winding, ..f })));
        }
    }
    // Fig. 5b: only an obstacle ahead, within the avoiding range; an ant with a goal starts
    // going round from twice that (ours: it joins the ants already going round at the surface
    // instead of pressing into them).
    let range = if goal.is_some() {
        params.avoid_range + near + near
    } else {
        params.avoid_range
    };
    if !(heading.dot(n) < S::ZERO && dist <= range) {
        return None;
    }
    let turn = match goal {
        // Going round toward a goal: the shorter way, judged from the goal's direction; nearly
        // head-on (within about 15°), the ant's own preferred side, the same every time (a
        // crowd at the middle of a wall splits instead of dithering).
        Some(g) => {
            let side = n.perp().dot(g);
            if side.abs() >= S::from_f32(0.25) {
                side_of(side)
            } else if rand::rand(ctx.seed, ctx.agent, 0, stream::ANT_SIDE) & 1 == 1 {
                Turn::Ccw
            } else {
                Turn::Cw
            }
        }
        // Fig. 5b: the smaller turn; exactly head-on, a random side.
        None => {
            let side = n.perp().dot(heading);
            if side != S::ZERO {
                side_of(side)
            } else if rand::rand(ctx.seed, ctx.agent, ctx.step, stream::ANT_FALLBACK) & 1 == 1 {
                Turn::Ccw
            } else {
                Turn::Cw
            }
        }
    };
    let h = tangent(n, turn);
    let follow = goal.map(|g| Follow {
        turn,
        winding: turn_angle(g, h),
    });
    Some((h, follow))
}

/// The way round whose direction along the surface has the positive component `side` of a
/// heading on `normal.perp()`.
fn side_of<S: Scalar>(side: S) -> Turn {
    if side > S::ZERO { Turn::Ccw } else { Turn::Cw }
}

/// Along the surface on the `turn` side; turned toward it when farther than `far` (round a
/// corner the surface falls away), away from it when nearer than `near` (room for the ants
/// that follow the same surface).
fn follow_heading<S: Scalar>(n: Vec2<S>, dist: S, turn: Turn, near: S, far: S) -> Vec2<S> {
    let pull = if dist > far {
        (far - dist) / far
    } else if dist < near {
        (near - dist) / near
    } else {
        S::ZERO
    };
    let t = tangent(n, turn);
    (t + n * pull.clamp_to(-S::ONE, S::ONE))
        .normalized()
        .unwrap_or(t)
}

/// The signed turn from `a` to `b` (counter-clockwise positive) as a *diamond angle* in quarter
/// turns, in (−2, 2]: monotonic in the angle, exact at every multiple of a quarter turn, and
/// free of trigonometry (one division: a few hundred bytes less on a microcontroller).
fn turn_angle<S: Scalar>(a: Vec2<S>, b: Vec2<S>) -> S {
    let (x, y) = (a.dot(b), a.cross(b));
    let d = x.abs() + y.abs();
    if d == S::ZERO {
        return S::ZERO;
    }
    let t = y / d;
    let two = S::from_i32(2);
    if x >= S::ZERO {
        t
    } else if y >= S::ZERO {
        two - t
    } else {
        -two - t
    }
}

/// The turn equal to `angle` modulo a full turn (4 quarter turns) nearest to `previous` (a
/// winding followed through its full turns), limited to ±[`WINDING_LIMIT`].
fn unwrap<S: Scalar>(angle: S, previous: S) -> S {
    let full = S::from_i32(4);
    let turns = ((previous - angle) / full + S::from_f32(0.5)).floor_i32();
    let lim = S::from_f32(WINDING_LIMIT);
    (angle + full * S::from_i32(turns)).clamp_to(-lim, lim)
}

/// The hard constraint on the move of eq. 5 (ours: the paper avoids obstacles by the heading
/// alone, which lets the blend of eq. 2 with the neighbours' repulsion carry an ant into an
/// obstacle). `step` is the move p(t+1) − p(t); the result ends at least [`SURFACE_MARGIN`] in
/// front of every surface in `surfaces`, so the straight move crosses none of them:
///
/// 1. a move that would end behind a surface loses the part of it that goes into the surface
///    (it slides along the surface); this is repeated for the next surface it would cross (a
///    corner), up to three times;
/// 2. a move that still crosses a surface is dropped: the ant stays (the start is in front of
///    every surface, so staying is allowed);
/// 3. an ant that starts behind a surface (inside an obstacle, or within the margin) moves out
///    along that surface's normal, at most `step`'s length.
pub fn constrain<S: Scalar>(pos: Vec2<S>, step: Vec2<S>, surfaces: &[Surface<S>]) -> Vec2<S> {
    let margin = S::from_f32(SURFACE_MARGIN);
    // How far the move ends in front of surface `s` (≥ 0 required), and its start.
    let clearance = |m: Vec2<S>, s: &Surface<S>| {
        let start = (pos - s.closest).dot(s.normal) - margin;
        (start + m.dot(s.normal), start)
    };
    let worst = |m: Vec2<S>| {
        let mut w: Option<(S, S, Vec2<S>)> = None;
        for s in surfaces {
            let (c, start) = clearance(m, s);
            if c < S::ZERO && w.is_none_or(|(wc, _, _)| c < wc) {
                w = Some((c, start, s.normal));
            }
        }
        w
    };
    let mut m = step;
    for _ in 0..3 {
        match worst(m) {
            None => return m,
            Some((_, start, n)) if start < S::ZERO => return n * (-start).min(step.length()),
            // Slide: remove the part of the move that goes into the surface.
            Some((c, _, n)) => m -= n * c,
        }
    }
    match worst(m) {
        None => m,
        Some(_) => Vec2::zero(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wall_at_x(x: f32) -> Surface<f32> {
        Surface {
            closest: Vec2::new(x, 0.0),
            normal: Vec2::new(-1.0, 0.0),
        }
    }

    #[test]
    fn a_move_into_a_wall_slides_along_it() {
        let pos = Vec2::new(9.5, 0.0);
        let m = constrain(pos, Vec2::new(0.6, 0.8), &[wall_at_x(10.0)]);
        assert!((pos.x + m.x) <= 10.0 - SURFACE_MARGIN + 1e-6);
        assert_eq!(m.y, 0.8);
    }

    #[test]
    fn a_move_away_or_along_is_untouched() {
        let pos = Vec2::new(9.0, 0.0);
        let m = Vec2::new(-0.6, 0.8);
        assert_eq!(constrain(pos, m, &[wall_at_x(10.0)]), m);
    }

    #[test]
    fn a_corner_stops_or_slides_out_of_it() {
        // A concave corner: walls x = 10 and y = 10, ant at (9.5, 9.5) heading into both.
        let floor = Surface {
            closest: Vec2::new(9.5, 10.0),
            normal: Vec2::new(0.0, -1.0),
        };
        let pos = Vec2::new(9.5, 9.5);
        let m = constrain(
            pos,
            Vec2::new(
                core::f32::consts::FRAC_1_SQRT_2,
                core::f32::consts::FRAC_1_SQRT_2,
            ),
            &[wall_at_x(10.0), floor],
        );
        let q = pos + m;
        assert!(q.x <= 10.0 - SURFACE_MARGIN + 1e-5 && q.y <= 10.0 - SURFACE_MARGIN + 1e-5);
    }

    #[test]
    fn an_ant_inside_moves_out_along_the_normal() {
        // Inside a wall x ≥ 10 at x = 10.3: the surface point is (10, 0), the way out is −x.
        let pos = Vec2::new(10.3, 0.0);
        let m = constrain(pos, Vec2::new(1.0, 0.0), &[wall_at_x(10.0)]);
        assert!(m.x < 0.0 && (pos.x + m.x) <= 10.0);
    }
}
