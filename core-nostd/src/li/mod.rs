//! The mesoscopic and macroscopic levels of Li, Wolinski, Pettré and Lin 2015,
//! *Biologically-Inspired Visual Simulation of Insect Swarms* (li2015 §4.2-4.3): an insect
//! flies to a waypoint; on arrival it samples the next one from the data's distributions of
//! segment length and turning angle (Algorithm 1) and screens it with the Metropolis-Hastings
//! ratio of the data's visiting-frequency density (§4.3). The microscopic level, collision
//! avoidance on the way, is [`orca3d`](crate::orca3d).
//!
//! * [`sampler::Table`]: an empirical distribution as an inverse-CDF table of `M` bins (spec
//!   §2.1, ours);
//! * [`waypoint::direction`]: `direction(d, θ)` of Algorithm 1 in 3D (spec §2.2, ours: the
//!   previous direction turned by |θ| at a uniform azimuth);
//! * [`density::Density`]: the visiting-frequency grid `w_c`, one byte a cell (a device keeps
//!   16³ cells in 4 KiB; obstacles and the outside are 0);
//! * [`waypoint::next_waypoint`]: Algorithm 1 with the screening of §4.3;
//! * [`LiParams`], [`LiState`], [`LiFrame`] and [`step()`]: the whole insect of spec §1.6 as a
//!   model (the waypoint, the preferred velocity toward it, ORCA, the move), its learned data
//!   in its parameters.
//!
//! `no_std`, no allocation, no panics; generic over [`Scalar`](crate::Scalar). Randomness is
//! counter-based: streams [`LI_LENGTH`](crate::rand::stream::LI_LENGTH) and the four after
//! it, one set per proposal.
//!
//! ## Example
//!
//! ```
//! use swarm_core::li::density::Density;
//! use swarm_core::li::sampler::Table;
//! use swarm_core::li::waypoint::{Screening, Waypoint, next_waypoint};
//! use swarm_core::{StepCtx, Vec3};
//!
//! // Segment lengths 0.01-0.03 m, turns 0-0.5 rad, uniform within their ranges.
//! let lengths = Table::<f32, 4>::from_counts(0.01, 0.03, &[1, 1, 1, 1]).unwrap();
//! let turns = Table::<f32, 4>::from_counts(0.0, 0.5, &[1, 1, 1, 1]).unwrap();
//! // A 2 × 2 × 2 grid of 0.5 m cells, every cell visited as often.
//! let weights = [10u8; 8];
//! let density = Density::new(Vec3::new(0.0, 0.0, 0.0), 0.5, [2, 2, 2], &weights).unwrap();
//! let params = Screening::<f32>::default();
//! let here = Vec3::new(0.5, 0.5, 0.5);
//! // Arrived (the waypoint is where the insect is): a new one is proposed and accepted.
//! let at = Waypoint { waypoint: here, seg_start: here };
//! let ctx = StepCtx { seed: 1, agent: 0, step: 0 };
//! let next = next_waypoint(here, &at, &lengths, &turns, &density, &params, ctx).unwrap();
//! assert!(next.accepted);
//! let l = (next.waypoint.waypoint - here).length();
//! assert!((0.01..=0.03).contains(&l), "{l}");
//! ```

pub mod density;
pub mod frame;
pub mod params;
pub mod sampler;
pub mod step;
pub mod waypoint;
mod wire;

pub use frame::{LiFrame, LiState};
pub use params::{BINS, LiParams, LiTable};
pub use step::{LiDecision, preferred, step, step_checked};
#[cfg(feature = "serde")]
pub use wire::{LiDevice, MAX_LI_FRAME, MAX_LI_PAYLOAD, MAX_LI_REPLY_FRAME, MAX_LI_REPLY_PAYLOAD};
pub use wire::{
    LiNeighbour, LiStep, LiStepReply, LiStepRequest, WIRE_LI_NEIGHBOURS, WIRE_LI_SURFACES,
    WireLiFrame,
};

#[cfg(test)]
mod tests;
