//! # swarm-sim
//!
//! The std host simulator: whole ant colonies and bee swarms, every agent driven through the
//! same [`swarm_core`] controllers a microcontroller runs. The simulator is the reference a
//! device is checked against, so its sensor frames are built by public functions the HIL
//! harness calls too.
//!
//! * [`scenario`]: scenario files (TOML) and the built-in scenarios, checked before a run;
//! * [`engine`]: the [`Engine`](engine::Engine) trait through which everything generic drives
//!   any model, one phase at a time (and what a mirror asks of it: requests, replies, the
//!   device); [`models`]: the one place naming the built-in models;
//! * [`ants`], [`bees`]: each model's world, sensing and deterministic parallel CPU engine;
//! * [`fields`]: global fields on a grid of cells (signed distance, a fast-marching cost field
//!   and its descent direction) for the field-based models;
//! * [`orca`]: crowds avoiding each other with 3D ORCA, stepped in parallel (RVO2-3D's
//!   `doStep` on a grid), and the random-cube benchmark scenario;
//! * [`run`]: `swarm run`, a scenario from its first tick to its last into one output folder
//!   ([`output`]: CSV, `.npy`, JSON, PNG, GIF); [`mod@bench`]: `swarm bench`.
//!
//! `docs/architecture.md` says how a new model plugs in. The GPU backend is not built yet
//! (issue 14).
//!
//! ```
//! use swarm_sim::{engine::Engine, models, scenario};
//!
//! let sc = scenario::builtin("ants-fig7a-single-colony").unwrap();
//! let mut engine = models::engine(&sc, sc.seed).unwrap();
//! assert_eq!((engine.model(), engine.phases()), ("ant", &["plan", "resolve"][..]));
//! engine.tick().unwrap();
//! assert_eq!(engine.next_step(), 1);
//! assert_eq!(engine.frame().agents.len(), engine.agents());
//! ```

pub use swarm_core;

pub mod ants;
pub mod bees;
pub mod bench;
pub mod cli;
pub mod engine;
mod error;
pub mod eval;
pub mod fields;
pub mod fit;
pub mod fly;
pub mod gpu;
pub mod grid;
pub mod huge;
pub mod li;
pub mod models;
pub(crate) mod nearest;
pub mod obstacle_index;
pub mod orca;
pub mod output;
mod par;
pub mod run;
pub mod scalar;
pub mod scenario;
pub mod space;
pub mod spawn;
pub mod swarm3d;
pub mod wang;

pub use error::{Result, SimError};
