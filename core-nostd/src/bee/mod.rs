//! The bee controller of Chen et al., *A Bio-inspired Model for Bee Simulations* (chen):
//! sections III-V, eq. 1-11, Table I.
//!
//! Each step a bee sums three forces (eq. 1, §III):
//!
//! * [`oscillation`]: body oscillation F_o, thrust/lift/sway from the pitch and roll
//!   maneuvering functions (eq. 2-4, Fig. 4, §IV-A);
//! * [`curl`]: the curl-noise force F_curl = ∇ × ψ of a Perlin potential ([`perlin`],
//!   eq. 8-9, §V-A);
//! * [`sph`]: SPH pressure repulsion F_repul from neighbours and target particles (eq. 10-11,
//!   §V-B);
//!
//! plus a linear drag −m·c·u (ours), and, when an obstacle is in view and close, [`vision`]
//! rolls the body away (eq. 6-7); near any obstacle it tunes the velocity to slip along the
//! surface (eq. 5, §IV-B). [`step()`] runs one step:
//! `(&BeeState, &BeeFrame, &BeeParams) -> Result<(BeeDecision, BeeState)>`; [`step_with`] is
//! the same with the per-time constants ([`StepConsts`]) computed once for a whole swarm.
//!
//! World axes: y is up. Angles in states and decisions are radians; eq. 3, 4 and 6 are
//! evaluated in degrees as printed. Deviations from the printed paper (each documented where
//! it applies, and listed in `docs/models.md`): the weight is carried by the mean lift, eq. 2
//! applies the lift's deviation from its period mean
//! ([`oscillation::oscillation_force`]); a linear drag is added ([`BeeParams::damping`]); o is
//! the direction of flight and the thrust points to the goal ([`oscillation::forward_axis`]);
//! an avoidance lasts until the obstacle is passed ([`vision::in_view`]); u_t of eq. 5 is the
//! tangential part, and u_0 the current velocity, for every obstacle within d0
//! ([`vision::tune_velocity`]); eq. 11 uses the symmetric (p_i + p_j) pressure of its reference
//! \[61\] and target particles the density of an isolated particle ([`sph::repulsion`]); eq. 8
//! is read as noise on a lattice of edge L ([`curl::potential`]); frame times wrap below the
//! input limit ([`oscillation::wrap_time`]).
//!
//! ## Example
//!
//! ```
//! use swarm_core::bee::{self, BeeFrame, BeeNeighbor, BeeParams, BeeState};
//! use swarm_core::Vec3;
//!
//! let params = BeeParams::<f32>::default();
//! let state = BeeState::new(Vec3::new(0.0, 1.0, 0.0), Vec3::new(1.0, 0.0, 0.0));
//! let mut frame: BeeFrame<f32, 8, 16> = BeeFrame::new(0.0);
//! frame.neighbours.push(BeeNeighbor {
//!     pos: Vec3::new(1.0, 1.0, 0.0),
//!     vel: Vec3::new(0.0, 0.0, 1.0),
//!     density: 0.05,
//! }).unwrap();
//! frame.goal = Some(Vec3::new(10.0, 1.0, 0.0));
//!
//! let (decision, next) = bee::step(&state, &frame, &params).unwrap();
//! assert!(decision.velocity.length() <= params.max_speed);
//! assert_eq!(next.pos, state.pos + decision.velocity * params.dt);
//! assert!(decision.density > 0.0); // broadcast to the neighbours next step
//! ```

pub mod curl;
pub mod frame;
pub mod oscillation;
pub mod params;
pub mod perlin;
pub mod sph;
pub mod step;
pub mod vision;
mod wire;

pub use frame::{BeeDecision, BeeFrame, BeeNeighbor, BeeState, ObstacleSense};
pub use params::BeeParams;
pub use step::{StepConsts, step, step_checked, step_with};
#[cfg(feature = "serde")]
pub use wire::{
    BeeDevice, MAX_BEE_FRAME, MAX_BEE_PAYLOAD, MAX_BEE_REPLY_FRAME, MAX_BEE_REPLY_PAYLOAD,
};
pub use wire::{
    BeeStepReply, BeeStepRequest, Step, WIRE_BEE_NEIGHBOURS, WIRE_BEE_TARGETS, WireBeeFrame,
};
