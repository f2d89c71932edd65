//! One ren2016 step for one insect (Algorithm 1, spec §1.5 step 2): the forces into a
//! preferred velocity, ORCA into the actual velocity, the move.

use super::force::{friction, noise_force, response, zone_force};
use super::frame::{FlyFrame, FlyState};
use super::params::FlyParams;
use crate::orca3d::{self, Fallback, OrcaParams};
use crate::{Checked, Result, Scalar, StepCtx, Vec3};

wire_type! {
    /// What the step decided besides the next state.
    #[derive(Clone, Copy, Debug, Default, PartialEq)]
    pub struct FlyDecision<S> {
        /// The preferred velocity v_pref = v + (F_int + F_pro + F_ξ)·Δt (Algorithm 1).
        pub pref: Vec3<S>,
        /// Whether ORCA's program was infeasible (the fallback of
        /// [`FlyParams::fallback`] acted).
        pub infeasible: bool,
    }
}

/// One step of the insect (Algorithm 1, Eq. 2-5):
///
/// 1. F_int of Eq. 5 over the frame's neighbours ([`zone_force`]);
/// 2. F_fric = −γ‖v‖v ([`friction`]);
/// 3. F_res, the response to the frame's stimulus ([`response`]; updates the escape episode);
/// 4. F_ξ, the noise ([`noise_force`]: the curl noise of Eq. 4 by default);
/// 5. v_pref = v + (F_int + F_fric + F_res + F_ξ)·Δt;
/// 6. ORCA ([`orca3d::solve`]) with the obstacle surfaces first, then the first
///    min(`orca_neighbours`, `N` − surfaces) neighbours of the frame (nearest first; an
///    entry with the insect's own id is skipped), every insect of radius
///    [`FlyParams::radius`]·(1 + [`FlyParams::margin`]), τ, Δt and the speed limit of the parameters; an infeasible
///    program gives zero velocity (the paper) or RVO2-3D's least-penetration velocity;
/// 7. r ← r + v_new·Δt, v ← v_new.
///
/// # Errors
///
/// The first bad parameter, state field or frame field ([`FlyState::validate`],
/// [`FlyFrame::validate`]); `NonFinite` (`next.pos`) if the result overflows in `f32`.
pub fn step<S: Scalar, const N: usize, const O: usize>(
    state: &FlyState<S>,
    frame: &FlyFrame<S, N, O>,
    params: &FlyParams<S>,
    ctx: StepCtx,
) -> Result<(FlyState<S>, FlyDecision<S>)> {
    step_checked(state, frame, &params.checked()?, ctx)
}

/// [`step`] with parameters validated beforehand (the state and frame are still checked).
pub fn step_checked<S: Scalar, const N: usize, const O: usize>(
    state: &FlyState<S>,
    frame: &FlyFrame<S, N, O>,
    params: &Checked<FlyParams<S>>,
    ctx: StepCtx,
) -> Result<(FlyState<S>, FlyDecision<S>)> {
    let p: &FlyParams<S> = params;
    state.validate()?;
    frame.validate()?;
    let f_int = zone_force(state, ctx.agent, &frame.neighbours, p);
    let f_fric = friction(state.vel, p.gamma);
    let (f_res, escape_theta, escaping) = response(state, frame.stimulus.as_ref(), p, ctx);
    let f_xi = noise_force(state.pos, p, ctx);
    let pref = state.vel + (f_int + f_fric + f_res + f_xi) * p.dt;

    let orca = OrcaParams {
        time_horizon: p.tau,
        dt: p.dt,
        max_speed: p.max_speed,
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
    let next = FlyState {
        pos: state.pos + vel * p.dt,
        vel,
        escape_theta,
        escaping,
    };
    next.pos.check("next.pos")?;
    Ok((
        next,
        FlyDecision {
            pref,
            infeasible: solution.infeasible,
        },
    ))
}
