//! Phase 2 of a tick: collision avoidance (xiang2018 eq. 2-4) and the move (eq. 5).

use super::frame::ResolveFrame;
use super::obstacle::constrain;
use super::params::AntParams;
use super::plan::AntPlan;
use super::state::{AntState, check_point};
use crate::{Checked, Result, Scalar, Vec2};

/// The repulsion sum R_d(t+1) of eq. 3 for an ant predicted at `me`, from the predicted
/// positions `others` of its neighbours:
///
/// R_d = Σ_d w_d·R_d*,  w_d = C / ‖p_d* − p*‖^k,  R_d* the unit vector between the two
/// predictions (eq. 4), over the n_c ants closer than `collision_range`.
///
/// Eq. 4 as printed, (p_d* − p*)/‖p_d* − p*‖, points from the current ant *to* the d-th one,
/// while the text defines R_d* as "the unit vector pointing from the d-th colliding ant to the
/// current ant" — a repulsion. We follow the text: R_d* = (p* − p_d*)/‖p* − p_d*‖. A neighbour
/// predicted exactly at p* gives no direction and is skipped. Terms are summed in frame order.
///
/// w_d is limited to [`W_MAX`] (ours): as ‖p_d* − p*‖ → 0 the printed weight diverges, which
/// overflows `f32` and saturates fixed point differently; past the limit R_d is dominated by the
/// nearest ant either way, so the direction of O(t+1) is unaffected.
pub fn repulsion<S: Scalar>(me: Vec2<S>, others: &[Vec2<S>], params: &AntParams<S>) -> Vec2<S> {
    let mut sum = Vec2::zero();
    for &p in others {
        let away = me - p;
        let dist = away.length();
        if dist >= params.collision_range {
            continue;
        }
        if let Some(unit) = away.normalized() {
            let w = (params.c / dist.powi(params.k)).min(S::from_f32(W_MAX));
            sum += unit * w;
        }
    }
    sum
}

/// The largest repulsion weight w_d of eq. 3 (8 neighbours at the limit stay below 2^15).
pub const W_MAX: f32 = 1000.0;

/// Phase 2 of the ant tick (xiang2018 §4.3, Algorithm 1 lines 4-5):
///
/// * eq. 2: O(t+1) = w0·O*(t+1) + (1 − w0)·R_d(t+1) (see [`repulsion`] for eq. 3-4), with R_d
///   limited to unit length (ours: the printed sum is unbounded, and a crowd's pushes then
///   outweigh O* entirely), normalised to a unit orientation (O* if the sum vanishes);
/// * eq. 5: p(t+1) = p(t) + v·O(t+1)·Δt, kept inside the arena and out of every obstacle
///   surface of the frame ([`constrain`]: the move slides along a surface it would cross, or
///   the ant stays; ours; a move that would leave the arena is clamped to it first, then
///   constrained), O(t+1) then being the direction of the move.
///
/// A stopped ant does not move. Returns the ant's state for the next tick.
pub fn resolve<S: Scalar, const N: usize>(
    plan: &AntPlan<S>,
    frame: &ResolveFrame<S, N>,
    params: &AntParams<S>,
) -> Result<AntState<S>> {
    resolve_checked(plan, frame, &params.checked()?)
}

/// [`resolve`] with parameters validated beforehand (the plan and frame are still checked).
#[inline]
pub fn resolve_checked<S: Scalar, const N: usize>(
    plan: &AntPlan<S>,
    frame: &ResolveFrame<S, N>,
    params: &Checked<AntParams<S>>,
) -> Result<AntState<S>> {
    let params: &AntParams<S> = params;
    plan.state.validate()?;
    check_point(plan.predicted, "plan.predicted")?;
    frame.validate()?;
    let mut s = plan.state;
    if s.is_stopped() {
        return Ok(s);
    }
    let r = repulsion(plan.predicted, &frame.neighbours, params);
    // R_d enters eq. 2 as an orientation, blended with the unit O* by w0 and 1 − w0: a sum
    // longer than one is limited to unit length (ours; docs/models.md).
    let r = if r.length_sq() > S::ONE {
        r.normalized().unwrap_or(r)
    } else {
        r
    };
    let o = s.heading * params.w0 + r * (S::ONE - params.w0);
    let o = o.normalized().unwrap_or(s.heading);
    // A move that would leave the arena is clamped to it first, then kept out of the
    // obstacles: clamping afterwards could push the ant into an obstacle on the border.
    let mut step = o * (params.speed * params.dt);
    if !frame.bounds.contains(s.pos + step) {
        step = frame.bounds.clamp(s.pos + step) - s.pos;
    }
    let mut m = constrain(s.pos, step, &frame.obstacles);
    if !frame.bounds.contains(s.pos + m) {
        // Sliding along a surface left the arena: stay (an ant that starts outside, as a
        // state from outside may, is clamped).
        m = if frame.bounds.contains(s.pos) {
            Vec2::zero()
        } else {
            frame.bounds.clamp(s.pos + m) - s.pos
        };
    }
    // The orientation is the way the ant actually moved (unchanged if it stayed).
    s.heading = m.normalized().unwrap_or(o);
    s.pos += m;
    Ok(s)
}
