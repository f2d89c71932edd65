//! Scenario files: TOML descriptions of a world, its agents, objects and timed events.
//!
//! A scenario is loaded with [`Scenario::from_path`], [`Scenario::from_str`], [`builtin`] or
//! [`resolve`] (a built-in name first, then a file). Loading checks everything before anything
//! runs; an error names the file, the line and column, the field path (`groups[1].spawn.radius`)
//! and what was expected. A layout that cannot work is refused too (a food source, way point or
//! target wholly inside an obstacle); one that probably is a mistake loads with warnings of the
//! same form ([`ScenarioWarning`]: a nest in an obstacle, a spawn region partly inside
//! obstacles, a nest covering a food source, ...), which the `*_with_warnings` loaders return
//! and `swarm run` prints and records in `run.log`.
//!
//! ```toml
//! name = "ants-fig7a-single-colony"   # optional, defaults to the file stem
//! description = "..."
//! seed = 7                            # default 0
//! steps = 4000
//! world = { dim = 2, min = [0, 0], max = [200, 120] }   # dim = 3 and [x, y, z] for bees
//!
//! [[groups]]
//! name = "colony"
//! model = "ant"                       # "ant" (2D), "bee" (3D), or a registered model (`swarm models`)
//! count = 500
//! scalar = "f32"                      # or "fixed"; default "f32"
//! nest = "nest"                       # ants: the home nest (required)
//! spawn = { at = "nest", radius = 12 }   # or { min = [..], max = [..] }; optional heading = [..]
//! ant = { w0 = 0.6 }                  # the model's parameters, under its name: any AntParams field;
//!                                     # bees: bee = { preset = "grassland", kappa2 = 4 }
//!
//! [[objects]]
//! name = "nest"
//! kind = "nest"                       # nest food rock polygon disturbance waypoint | sphere box shaft target
//! center = [40, 60]
//! radius = 5
//!
//! [[events]]
//! step = 2000
//! move = { object = "food", to = [120, 100] }   # or add/remove/start/stop = "name"
//!
//! [outputs]
//! every = 10                          # and trajectories, npy, render, gif (all default true)
//! ```

// The way a file goes: `load` (entry points) parses it into a `locate::Document`, serde reads
// the `raw` shapes (plain data), `build` converts them into the `types` and runs the `rules`
// (then the `sanity` checks); every check reports a `problem::Problem` at a field path, which
// `locate` places in the text. `params` are the parameter overrides, read by name from each
// model's parameter table. The rules every group follows are here; a group's model adds its
// own through its entry in `crate::models` (`check::GroupCheck` is what it sees). `types`
// imports none of `raw`, `build` or `load`.
mod build;
mod builtin;
mod check;
mod diagnostic;
mod load;
mod locate;
mod params;
mod problem;
mod raw;
mod rules;
mod sanity;
mod types;
mod warning;

#[cfg(test)]
mod tests;

pub use builtin::{BUILTINS, Builtin, builtin, builtin_names, resolve, resolve_with_warnings};
pub use check::GroupCheck;
pub use diagnostic::{Diagnostic, DiagnosticKind};
pub use load::check_steps;
pub(crate) use params::read_table;
pub use params::{ParamsOverride, Preset, PresetOverride};
pub use problem::Problem;
pub use types::{
    Action, Backend, Event, Group, MAX_AGENTS, MAX_COORD, MAX_TARGET_PARTICLES, Model, Object,
    ObjectKind, Outputs, ScalarType, Scenario, Spawn, SpawnRegion, World,
};
pub use warning::{ScenarioWarning, WarningKind};
