//! The two phases of a wang2014 step (spec §1.6): [`advect`] (eq. 9 and the phototaxis bias,
//! one explicit Euler step to the tentative position x*), then, once every insect has
//! broadcast x*, [`separate`] (minimum distance enforcement, §6).

use super::curl::noise_velocity;
use super::frame::{AdvectFrame, SeparateFrame, WangState};
use super::params::WangParams;
use crate::check::within;
use crate::rand::{self, stream};
use crate::scalar::pi;
use crate::{Checked, Result, Scalar, StepCtx, Vec3};

/// Phase 1: the insect's velocity and tentative position.
///
/// V = V_l + V_g (eq. 9): V_l from [`noise_velocity`] (the bounded curl noise of eq. 1-3 by
/// default), V_g = s0·guide (eq. 8; the host samples −∇C/‖∇C‖ of the cost field). Phototaxis
/// (§7, "probabilistically added a small magnitude of speed towards the lamp holder"): with
/// probability p_photo ([`rand::chance`], stream [`WANG_PHOTO`](stream::WANG_PHOTO)) and a
/// lamp in the frame, V += u_photo·(lamp − x)/‖lamp − x‖ (ours: p and u). Then one explicit
/// Euler step (ours; the paper gives no integrator): x* = x + V·Δt. The reply carries x* and
/// V.
///
/// # Errors
///
/// The first bad parameter, state field or frame field (see [`WangState::validate`],
/// [`AdvectFrame::validate`]); in `f32`, `NonFinite` (`moved.pos`) if the result overflows.
pub fn advect<S: Scalar>(
    state: &WangState<S>,
    frame: &AdvectFrame<S>,
    params: &WangParams<S>,
    ctx: StepCtx,
) -> Result<WangState<S>> {
    advect_checked(state, frame, &params.checked()?, ctx)
}

/// [`advect`] with parameters validated beforehand (the state and frame are still checked).
pub fn advect_checked<S: Scalar>(
    state: &WangState<S>,
    frame: &AdvectFrame<S>,
    params: &Checked<WangParams<S>>,
    ctx: StepCtx,
) -> Result<WangState<S>> {
    let p: &WangParams<S> = params;
    state.validate()?;
    frame.validate()?;
    let mut v = noise_velocity(state.pos, frame.boundary.as_ref(), p, ctx) + frame.guide * p.s0;
    if let Some(lamp) = frame.lamp
        && rand::chance(ctx, stream::WANG_PHOTO, p.p_photo)
        && let Some(toward) = (lamp - state.pos).normalized()
    {
        v += toward * p.u_photo;
    }
    let moved = WangState {
        pos: state.pos + v * p.dt,
        vel: v,
    };
    moved.pos.check("moved.pos")?;
    moved.vel.check("moved.vel")?;
    Ok(moved)
}

/// The direction that separates a coincident pair: a uniform random unit vector from
/// `(seed, lower id, step)` (streams [`WANG_MDE`](stream::WANG_MDE) and
/// [`WANG_MDE_AZIMUTH`](stream::WANG_MDE_AZIMUTH)), the same for both insects of the pair.
pub fn pair_direction<S: Scalar>(seed: u32, lower: u32, step: u32) -> Vec3<S> {
    let ctx = StepCtx {
        seed,
        agent: lower,
        step,
    };
    let h: S = rand::unit(ctx, stream::WANG_MDE);
    let z = h + h - S::ONE;
    let phi = rand::angle(ctx, stream::WANG_MDE_AZIMUTH, pi::<S>());
    let r = (S::ONE - z * z).max(S::ZERO).sqrt();
    let (s, c) = phi.sin_cos();
    Vec3::new(r * c, z, r * s)
}

/// Phase 2: minimum distance enforcement (§6) on the tentative positions.
///
/// For every neighbour j (other than the insect itself) with d_ij = ‖x*_i − x*_j‖ < d_min,
/// x_i += ½(d_min − d_ij)·ê_ij, ê_ij = (x*_i − x*_j)/d_ij (ours: Treuille et al.'s
/// half-deficit rule, the paper only says "push them apart"). Jacobi form (ours): every push
/// is computed from the tentative positions and the pushes are summed in increasing neighbour
/// id, so the result is bit for bit independent of the neighbours' order, and pair (i, j)
/// moves both by opposite amounts. A coincident pair (d_ij·1024 < d_min, or a difference too
/// small to normalise) is split along [`pair_direction`] of the lower id: + for the lower
/// id, − for the higher. One pass (§6: MDE "cannot absolutely avoid collisions"). d_min = 0
/// disables MDE. The velocity passes through unchanged.
///
/// Returns x_{k+1} and how many neighbours pushed (0: MDE not applied).
///
/// # Errors
///
/// The first bad parameter, `moved` field (`moved.pos`, `moved.vel`) or frame field
/// ([`SeparateFrame::validate`]).
pub fn separate<S: Scalar, const K: usize>(
    moved: &WangState<S>,
    frame: &SeparateFrame<S, K>,
    params: &WangParams<S>,
    ctx: StepCtx,
) -> Result<(WangState<S>, u8)> {
    separate_checked(moved, frame, &params.checked()?, ctx)
}

/// [`separate`] with parameters validated beforehand (the state and frame are still checked).
pub fn separate_checked<S: Scalar, const K: usize>(
    moved: &WangState<S>,
    frame: &SeparateFrame<S, K>,
    params: &Checked<WangParams<S>>,
    ctx: StepCtx,
) -> Result<(WangState<S>, u8)> {
    moved.validate_as("moved.pos", "moved.vel")?;
    frame.validate()?;
    let d_min = params.d_min;
    if d_min <= S::ZERO {
        return Ok((*moved, 0));
    }
    // The pushes, kept sorted by id (ids are distinct: validated).
    let mut pushes = [(0u32, Vec3::<S>::zero()); K];
    let mut n = 0;
    for c in &frame.neighbours {
        if c.id == ctx.agent {
            continue;
        }
        let diff = moved.pos - c.pos;
        // Cheap reject first (also keeps `length` away from far, large differences).
        if !(within(diff.x, d_min) & within(diff.y, d_min) & within(diff.z, d_min)) {
            continue;
        }
        let d = diff.length();
        if d >= d_min {
            continue;
        }
        let apart = if d * S::from_i32(1024) < d_min {
            None
        } else {
            diff.normalized()
        };
        let e = apart.unwrap_or_else(|| {
            let u = pair_direction::<S>(ctx.seed, ctx.agent.min(c.id), ctx.step);
            if ctx.agent < c.id { u } else { -u }
        });
        let push = e * ((d_min - d) * S::from_f32(0.5));
        let mut at = n;
        while at > 0 && pushes[at - 1].0 > c.id {
            pushes[at] = pushes[at - 1];
            at -= 1;
        }
        pushes[at] = (c.id, push);
        n += 1;
    }
    let mut pos = moved.pos;
    for (_, push) in &pushes[..n] {
        pos += *push;
    }
    let state = WangState {
        pos,
        vel: moved.vel,
    };
    Ok((state, u8::try_from(n).unwrap_or(u8::MAX)))
}
