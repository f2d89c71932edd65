//! One li2015 step for one insect (spec §1.6): the waypoint (Algorithm 1 with the
//! Metropolis-Hastings screening of §4.3), the preferred velocity toward it, ORCA (§4.1), the
//! move.

use super::frame::{LiFrame, LiState};
use super::params::LiParams;
use super::waypoint::{Waypoint, next_waypoint};
use crate::orca3d::{self, Fallback, OrcaParams};
use crate::{Checked, Result, Scalar, StepCtx, Vec3};

wire_type! {
    /// What the step decided besides the next state.
    #[derive(Clone, Copy, Debug, Default, PartialEq)]
    pub struct LiDecision<S> {
        /// The preferred velocity toward the waypoint.
        pub pref: Vec3<S>,
        /// How many waypoints were proposed (0: not arrived).
        pub proposals: u8,
        /// Whether a proposal was accepted.
        pub accepted: bool,
        /// Whether ORCA's program was infeasible (the fallback acted).
        pub infeasible: bool,
    }
}

/// The preferred velocity toward `g` from `x` (spec §1.6, ours: RVO2's convention): v0 along
/// g − x, or (g − x)/Δt when that is shorter than one step at v0 (no overshoot).
pub fn preferred<S: Scalar>(x: Vec3<S>, g: Vec3<S>, speed: S, dt: S) -> Vec3<S> {
    let d = g - x;
    let reach = speed * dt;
    if d.length_sq() <= reach * reach {
        d * (S::ONE / dt)
    } else {
        d.normalized().map_or(Vec3::zero(), |u| u * speed)
    }
}

/// One step of the insect (spec §1.6):
///
/// 1. the waypoint: [`next_waypoint`] (Algorithm 1, screened as [`LiParams::sampling`]
///    says); a waypoint held for [`LiParams::patience`] steps counts as reached;
/// 2. v_pref = [`preferred`] toward it;
/// 3. ORCA ([`orca3d::solve_frame`]) with the frame's surfaces, then its first
///    min(`orca_neighbours`, `N` − surfaces) neighbours, every insect of radius
///    [`LiParams::orca_radius`], τ, Δt, the speed limit v0 and the fallback of the
///    parameters;
/// 4. x ← x + v_new·Δt, v ← v_new.
///
/// # Errors
///
/// The first bad parameter, state field or frame field ([`LiState::validate`],
/// [`LiFrame::validate`]); `NonFinite` (`next.pos`) if the result overflows in `f32`.
pub fn step<S: Scalar, const N: usize, const O: usize>(
    state: &LiState<S>,
    frame: &LiFrame<S, N, O>,
    params: &LiParams<S>,
    ctx: StepCtx,
) -> Result<(LiState<S>, LiDecision<S>)> {
    step_checked(state, frame, &params.clone().checked()?, ctx)
}

/// [`step`] with parameters validated beforehand (the state and frame are still checked).
pub fn step_checked<S: Scalar, const N: usize, const O: usize>(
    state: &LiState<S>,
    frame: &LiFrame<S, N, O>,
    params: &Checked<LiParams<S>>,
    ctx: StepCtx,
) -> Result<(LiState<S>, LiDecision<S>)> {
    let p: &LiParams<S> = params;
    state.validate()?;
    frame.validate()?;
    let current = Waypoint {
        // Out of patience: arrived wherever it is.
        waypoint: if state.age >= p.patience {
            state.pos
        } else {
            state.waypoint
        },
        seg_start: state.seg_start,
    };
    let next = next_waypoint(
        state.pos,
        &current,
        &p.lengths,
        &p.turns,
        &p.density.view()?,
        &p.screening(),
        ctx,
    )?;
    let g = next.waypoint.waypoint;
    let pref = preferred(state.pos, g, p.speed, p.dt);
    let orca = OrcaParams {
        time_horizon: p.tau,
        dt: p.dt,
        max_speed: p.speed,
        max_neighbors: u16::from(p.orca_neighbours),
        fallback: Fallback::of_code(p.fallback),
    };
    let solution = orca3d::solve_frame::<S, N>(
        ctx.agent,
        state.pos,
        state.vel,
        p.orca_radius(),
        &frame.neighbours,
        &frame.surfaces,
        pref,
        &orca,
    )?;
    let vel = solution.velocity;
    let next_state = LiState {
        pos: state.pos + vel * p.dt,
        vel,
        waypoint: g,
        seg_start: next.waypoint.seg_start,
        age: if next.proposals > 0 {
            0
        } else {
            state.age.saturating_add(1)
        },
    };
    next_state.pos.check("next.pos")?;
    Ok((
        next_state,
        LiDecision {
            pref,
            proposals: next.proposals,
            accepted: next.accepted,
            infeasible: solution.infeasible,
        },
    ))
}
