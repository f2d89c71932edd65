//! # swarm-core
//!
//! The on-device decision logic of the swarm toolkit: `#![no_std]`, no `alloc`, no panics on
//! any input. It holds
//!
//! * [`ant`]: the ant foraging state machine of Xiang et al. 2018, *Biologically inspired ant
//!   colony simulation* (sections 3-4, Table 1, eq. 1-5), as a two-phase `plan` → `resolve` tick;
//! * [`bee`]: the bee controller of Chen et al., *A Bio-inspired Model for Bee Simulations*
//!   (sections III-V, eq. 1-11, Table I): body oscillation, visual roll-to-avoid, curl noise and
//!   SPH repulsion;
//! * [`wang`]: the noise-aware insect swarm of Wang et al. 2014, *Inherent Noise-Aware Insect
//!   Swarm Simulation* (§4-7, eq. 1-9): bounded curl noise plus a navigation direction, as a
//!   two-phase `advect` → `separate` (minimum distance enforcement) step;
//! * [`fly`]: the force-based flying insect of Ren et al. 2016, *Simulating Flying Insects
//!   Using Dynamics and Data-Driven Noise Modeling* (Eq. 2-5, Algorithm 1): zone forces,
//!   friction, stimulus response and curl noise into a preferred velocity;
//! * [`li`]: the waypoint levels of Li et al. 2015, *Biologically-Inspired Visual Simulation
//!   of Insect Swarms* (§4.2-4.3, Algorithm 1): data-driven waypoints screened by
//!   Metropolis-Hastings against a visiting-frequency density;
//! * [`orca3d`]: 3D ORCA with RVO2-3D semantics and hard obstacle planes (ren2016 spec §2.5);
//! * [`wire`] (feature `serde`): the message types, the frame codec
//!   `COBS(header ‖ postcard payload ‖ CRC) ‖ 0x00`, the session protocol (handshake,
//!   configure, ping, statistics) and the device endpoint
//!   ([`DeviceEndpoint`](wire::DeviceEndpoint)), shared by firmware and host.
//!
//! Everything is generic over a [`Scalar`]: `f32` (math through `libm` by default, or
//! `micromath`) and, with feature `fixed`, [`Fx`], an I16F16 fixed-point number whose
//! arithmetic, trigonometry, square root and exponential are computed in integers so that
//! results are bit-identical on every machine. Randomness is counter-based
//! ([`rand::rand`]): a decision depends only on its inputs.
//!
//! ## Example: one ant tick
//!
//! ```
//! use swarm_core::ant::{self, AntParams, AntState, Label, PlanFrame, ResolveFrame};
//! use swarm_core::{Rect, StepCtx, Vec2};
//!
//! let params = AntParams::<f32>::default();
//! let state = AntState::at_nest(0, Vec2::new(10.0, 10.0), Vec2::new(1.0, 0.0));
//! let bounds = Rect::new(Vec2::new(0.0, 0.0), Vec2::new(100.0, 100.0));
//! let frame: PlanFrame<f32, 8, 4> = PlanFrame::new(bounds);
//! let ctx = StepCtx { seed: 7, agent: 0, step: 0 };
//!
//! // Phase 1: the preferred heading O* and predicted position p* (eq. 1).
//! let plan = ant::plan(&state, &frame, &params, ctx).unwrap();
//! // (A robot broadcasts `plan.predicted` here; its neighbours' plans come back.)
//! let neighbours: ResolveFrame<f32, 8> = ResolveFrame::new(bounds);
//! // Phase 2: collision avoidance (eq. 2-4) and the move (eq. 5).
//! let next = ant::resolve(&plan, &neighbours, &params).unwrap();
//! assert_eq!(next.label, Label::Nest);
//! assert!((next.pos - state.pos).length() <= params.speed * params.dt * 1.0001);
//! ```
#![cfg_attr(not(test), no_std)]
#![forbid(unsafe_code)]
#![warn(missing_docs)]

#[cfg(all(feature = "libm", feature = "micromath"))]
compile_error!(
    "features `libm` and `micromath` are exclusive: pick one f32 math backend (use `default-features = false, features = [\"micromath\"]`)"
);
#[cfg(not(any(feature = "libm", feature = "micromath")))]
compile_error!(
    "swarm-core needs an f32 math backend: enable feature `libm` (default) or `micromath`"
);

/// Adds the wire derives (`serde`, `defmt`) that every public data type of the crate carries.
macro_rules! wire_type {
    ($($item:item)*) => {$(
        #[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
        #[cfg_attr(feature = "defmt", derive(defmt::Format))]
        $item
    )*};
}

pub mod ant;
pub mod bee;
mod check;
mod error;
pub mod fly;
pub mod geom;
pub mod li;
pub mod model;
pub mod orca3d;
pub mod rand;
pub mod scalar;
pub mod wang;
#[cfg(feature = "serde")]
pub mod wire;

pub use error::{Error, Result};
pub use geom::{Rect, Vec2, Vec3};
#[cfg(feature = "fixed")]
pub use scalar::Fx;
pub use scalar::{Constant, MathBackend, Scalar, ScalarKind};

/// Parameters that passed their `validate()`: a controller given `Checked` parameters does not
/// check them again (a simulator validates once, then runs millions of ticks). Obtained from
/// [`AntParams::checked`](ant::AntParams::checked),
/// [`BeeParams::checked`](bee::BeeParams::checked) or
/// [`WangParams::checked`](wang::WangParams::checked); read-only afterwards.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Checked<P>(P);

impl<P> core::ops::Deref for Checked<P> {
    type Target = P;
    fn deref(&self) -> &P {
        &self.0
    }
}

impl<P> Checked<P> {
    /// Wraps parameters whose validation the caller has just run.
    pub(crate) fn assume_valid(p: P) -> Self {
        Checked(p)
    }
}

/// Where a decision sits in the run: the inputs of the counter-based random numbers
/// ([`rand::rand`]). Time is always an argument, never read from a clock.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct StepCtx {
    /// The run's seed.
    pub seed: u32,
    /// The agent's id (stable for the whole run).
    pub agent: u32,
    /// The step number.
    pub step: u32,
}
