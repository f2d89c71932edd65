//! What every swarm model shares, whatever its equations: the [`Model`] trait (its parameter
//! table, its per-agent state and the [`Phase`]s of its tick) and the parameter table itself
//! ([`ModelParams`]: names, ranges, units, validation), from which the host derives its scenario
//! overrides and their messages and the device its checks.
//!
//! A model is named by its parameter set in one scalar type (`AntParams<f32>`,
//! `BeeParams<Fx>`): that value is what a device runs and what the session's parameter hash
//! covers. Everything generic (the device endpoint, the host's engine, outputs and mirror)
//! reaches a model through these traits only.
//!
//! ```
//! use swarm_core::model::{Model, ModelParams, Phase, Phases};
//! use swarm_core::ant::{AntParams, Plan};
//!
//! type Ant = AntParams<f32>;
//! assert_eq!(Ant::NAME, "ant");
//! assert_eq!(<<Ant as Model>::Phases as Phases<Ant>>::NAMES, ["plan", "resolve"]);
//! assert_eq!(<Plan as Phase<Ant>>::NAME, "plan");
//! let params = Ant::default().checked().unwrap();
//! assert_eq!(params.speed, 1.0);
//! ```

mod params;
mod phase;

pub use params::{ModelParams, ParamSpec, ParamValue, Range};
pub use phase::{Phase, Phases};

/// A swarm model in one scalar type, named by its parameter set: the parameter table
/// ([`ModelParams`], validated once into [`Checked`](crate::Checked)), the state each agent
/// carries from tick to tick, and the phases of a tick.
///
/// The sensor frames and decisions are the phases' requests and replies: for the ants a plan
/// phase (state and plan frame → plan) then a resolve phase (plan and the neighbours'
/// predictions → next state), for the bees one step (state and frame → decision and next
/// state), for the wang insects an advect phase (state and fields → tentative position) then
/// a separate phase (tentative position and the neighbours' → next state). With the `serde` feature, [`Controller`](crate::wire::Controller) adds the
/// wire description (controller kind, frame capacities, largest messages).
pub trait Model: ModelParams + Clone + PartialEq {
    /// The model's short name (`ant`, `bee`): scenario files, reports, run logs.
    const NAME: &'static str;
    /// What an agent carries from one tick to the next.
    type State: Copy + PartialEq + core::fmt::Debug;
    /// The phases of a tick, in order: a tuple of [`Phase`]s.
    type Phases: Phases<Self>;
}
