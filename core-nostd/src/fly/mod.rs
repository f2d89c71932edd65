//! The force-based flying insect of Ren, Wang, Jin and Manocha, *Simulating Flying Insects
//! Using Dynamics and Data-Driven Noise Modeling to Generate Diverse Collective Behaviors*,
//! PLoS ONE 11(5), 2016 (ren2016): a second-order agent model. Each insect (unit mass)
//! integrates the zone interaction of Eq. 5 (repulsion, alignment, attraction), quadratic
//! friction and a stimulus response (Eq. 3) and the curl-noise force (Eq. 4) into a preferred
//! velocity (Eq. 2, Algorithm 1); ORCA turns it into a collision-free velocity.
//!
//! Departures from the printed paper (documented where they apply, and listed in
//! `docs/models.md`): neighbours are the frame's nearest `N` (the paper is all-pairs), the
//! escape angle is drawn once per episode, the Gaussian noise candidate is an Irwin–Hall sum
//! (no logarithm on a device), and the ORCA constants (radius, τ, speed limit) are ours.

pub mod force;
pub mod frame;
pub mod params;
pub mod step;
pub mod temperature;
mod wire;

#[cfg(test)]
mod tests;

pub use crate::orca3d::Surface;
pub use frame::{FlyFrame, FlyState, Neighbour, STIMULUS_PREDATOR, STIMULUS_TARGET, Stimulus};
pub use params::{
    FALLBACK_LP4, FALLBACK_STOP, FlyParams, NOISE_CURL, NOISE_GAUSSIAN, NOISE_NONE, NOISE_PERLIN,
    NOISE_WHITE,
};
pub use step::{FlyDecision, step, step_checked};
#[cfg(feature = "serde")]
pub use wire::{
    FlyDevice, MAX_FLY_FRAME, MAX_FLY_PAYLOAD, MAX_FLY_REPLY_FRAME, MAX_FLY_REPLY_PAYLOAD,
};
pub use wire::{
    FlyStep, FlyStepReply, FlyStepRequest, WIRE_FLY_NEIGHBOURS, WIRE_FLY_SURFACES, WireFlyFrame,
};
