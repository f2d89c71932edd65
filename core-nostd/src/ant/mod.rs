//! The ant foraging controller of Xiang et al. 2018, *Biologically inspired ant colony
//! simulation* (sections 3-4).
//!
//! A tick is two calls, because the collision avoidance of eq. 2-4 needs every neighbour's
//! *predicted* position:
//!
//! 1. [`plan`]: stop / basic movement / interactions (§4.1-4.2) → preferred orientation O* and
//!    predicted position p* (eq. 1). A robot broadcasts p* to its neighbours.
//! 2. [`resolve`]: with the neighbours' predictions, the final orientation (eq. 2-4) and
//!    position (eq. 5).
//!
//! Both are pure functions of their arguments; randomness comes from [`crate::rand`] keyed by
//! the [`StepCtx`](crate::StepCtx).

mod frame;
mod interact;
mod obstacle;
mod params;
mod plan;
mod resolve;
mod state;
#[cfg(test)]
mod tests;
mod wire;

pub use frame::{AntNeighbor, AntObject, PlanFrame, ResolveFrame, SURFACES, Surface};
pub use interact::{EnvAction, environment, informer, transfers};
pub use obstacle::{SURFACE_MARGIN, constrain, obstacle_heading, tangent};
pub use params::AntParams;
pub use plan::{AntPlan, plan, plan_checked, predict};
pub use resolve::{W_MAX, repulsion, resolve, resolve_checked};
pub use state::{
    AntState, COORD_LIMIT, Follow, Label, MotionState, StopReason, StopTimer, Turn, WINDING_LIMIT,
};
#[cfg(feature = "serde")]
pub use wire::{
    AntDevice, MAX_ANT_FRAME, MAX_ANT_PAYLOAD, MAX_ANT_REPLY_FRAME, MAX_ANT_REPLY_PAYLOAD,
};
pub use wire::{
    AntPlanReply, AntPlanRequest, AntResolveReply, AntResolveRequest, Plan, Resolve,
    WIRE_ANT_NEIGHBOURS, WIRE_ANT_OBJECTS, WirePlanFrame, WireResolveFrame,
};
