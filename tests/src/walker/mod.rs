//! A test-only swarm model, written the way a team would add one: a random walker between
//! four walls. Its controller ([`core`]) implements the `swarm-core` model traits; its
//! simulation ([`sim`]) implements the `swarm-sim` [`Engine`](swarm_sim::engine::Engine), and
//! its [`entry`] in the model table lets scenario files name it.
//! Nothing generic in the workspace names it, yet the run loop, the outputs, the soft device
//! and the HIL mirror serve it (`tests/tests/walker.rs`).

pub mod core;
pub mod entry;
pub mod sim;

pub use self::core::{Walk, WalkParams, WalkReply, WalkRequest, WalkState};
pub use self::entry::{ENTRY, WalkParamsOverride};
pub use self::sim::WalkSim;
