//! The noise-aware insect swarm of Wang, Jin, Deng and Zhou, *Inherent Noise-Aware Insect
//! Swarm Simulation*, Computer Graphics Forum 33(6), 2014 (wang2014): a field-based,
//! first-order model where every insect is a massless point advected by
//! V = ∇ × N + V_g (eq. 9), the curl of a boundary-modulated Perlin potential (eq. 1-3) plus a
//! global navigation field (the unit descent direction of a minimum-cost field, eq. 4-8), then
//! pushed apart from neighbours that came too close (minimum distance enforcement, §6).
//!
//! The per-insect parts live here; the global fields (signed distance, repulsion, the
//! fast-marching cost field and its gradient) are the host's (`swarm-sim`), which hands an
//! insect the navigation direction in its sensor frame.
//!
//! A step has two phases, like the ant's plan → resolve:
//!
//! * [`advect`] ([`Advect`]): V = V_l + s0·guide (eq. 8-9) with V_l the bounded curl noise
//!   ([`curl::curl_noise`], eq. 1-3, closed form) or a baseline of §7.1
//!   ([`curl::noise_velocity`]), plus the phototaxis bias (§7); x* = x + V·Δt;
//! * the insect broadcasts x*;
//! * [`separate`] ([`Separate`]): minimum distance enforcement (§6) against the neighbours'
//!   x*.
//!
//! Eq. 3's ramp α is [`ramp`] (the bee's, chen eq. 5: the same Bridson ramp), eq. 6's bell is
//! [`bell()`]. Departures from the printed paper (each documented where it applies, and listed
//! in `docs/models.md`): the boundary's distance-field curvature travels in the frame
//! ([`Boundary`]), V_l may be one of the §7.1 baselines ([`WangParams::noise`]), the step is
//! explicit Euler with a bounded Δt ([`WangParams::dt`]), MDE is a Jacobi half-deficit push
//! with a random split of coincident pairs ([`separate`]), and phototaxis is a bias of
//! u_photo with probability p_photo per step ([`advect`]).
//!
//! ## Example
//!
//! ```
//! use swarm_core::wang::{self, AdvectFrame, Boundary, Close, SeparateFrame, WangParams, WangState};
//! use swarm_core::{StepCtx, Vec3};
//!
//! let params = WangParams::<f32>::default();
//! let ctx = StepCtx { seed: 1, agent: 0, step: 0 };
//! let state = WangState::new(Vec3::new(0.0, 0.5, 0.0));
//! let mut frame = AdvectFrame::new(Vec3::new(0.0, 0.0, 1.0)); // −∇C/‖∇C‖ from the host
//! frame.boundary = Some(Boundary::plane(Vec3::zero(), Vec3::up())); // the ground
//!
//! let moved = wang::advect(&state, &frame, &params, ctx).unwrap();
//! assert_eq!(moved.pos, state.pos + moved.vel * params.dt);
//!
//! // (The insect broadcasts `moved.pos`; a neighbour's comes back.)
//! let mut near: SeparateFrame<f32, 8> = SeparateFrame::new();
//! near.neighbours.push(Close { id: 1, pos: moved.pos + Vec3::new(0.05, 0.0, 0.0) }).unwrap();
//! let (next, pushes) = wang::separate(&moved, &near, &params, ctx).unwrap();
//! assert_eq!(pushes, 1);
//! assert!((next.pos.x - (moved.pos.x - 0.025)).abs() < 1e-6); // half the 0.05 m deficit
//! ```

pub mod bell;
pub mod curl;
pub mod frame;
pub mod params;
pub mod step;
mod wire;

#[cfg(test)]
mod tests;

pub use crate::bee::vision::ramp;
pub use bell::bell;
pub use curl::{curl_noise, noise_velocity};
pub use frame::{AdvectFrame, Boundary, Close, SeparateFrame, WangState};
pub use params::WangParams;
pub use step::{advect, advect_checked, separate, separate_checked};
pub use wire::{
    Advect, AdvectReply, AdvectRequest, Separate, SeparateReply, SeparateRequest,
    WIRE_WANG_NEIGHBOURS, WireSeparateFrame,
};
#[cfg(feature = "serde")]
pub use wire::{
    MAX_WANG_FRAME, MAX_WANG_PAYLOAD, MAX_WANG_REPLY_FRAME, MAX_WANG_REPLY_PAYLOAD, WangDevice,
};
