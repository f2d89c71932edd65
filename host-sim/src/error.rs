//! The crate's error type: one flat enum for the engines, the scenario files and the run
//! outputs.

use std::path::PathBuf;

use crate::scenario::Diagnostic;

/// `Result` with [`SimError`].
pub type Result<T> = std::result::Result<T, SimError>;

/// Everything that can go wrong in the simulator.
///
/// Every message can be shown to a user as it is: it names the step and agent, the scenario
/// file, line and field, or the output file (and line) and what was wrong. The variants come in
/// four groups: the engines and runs; scenarios (a bad scenario file is one
/// [`InvalidScenario`](SimError::InvalidScenario), its [`Diagnostic`] naming file, line, column
/// and field); the data handed to an output writer (`cannot write <file>: ...`); and files of a
/// run folder that cannot be read back (`<file>[:line]: ...`).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SimError {
    // ---- engines and runs ----
    /// A controller refused its input (a bug in the world or in frame building: the report
    /// names the step, the agent and the field).
    #[error("{phase} of agent {agent} at step {step}: {source}")]
    Controller {
        /// Which call.
        phase: &'static str,
        /// Step.
        step: u32,
        /// Agent id.
        agent: u32,
        /// The controller's error.
        source: swarm_core::Error,
    },
    /// The groups of a simulation mirrored on one device compute in different scalar types.
    #[error("groups `{first}` and `{other}` have different scalar types; a device runs one")]
    MixedScalars {
        /// The first group.
        first: String,
        /// A group of another scalar type.
        other: String,
    },
    /// The groups of a simulation mirrored on one device have different parameters.
    #[error(
        "groups `{first}` and `{other}` have different parameters; a device runs one parameter set"
    )]
    DifferentParams {
        /// The first group.
        first: String,
        /// A group with other parameters.
        other: String,
    },
    /// The simulation has no agents.
    #[error("the simulation has no agents")]
    NoAgents,
    /// An agent id the simulation does not have.
    #[error("no agent {id} (the simulation has {agents})")]
    NoAgent {
        /// The id asked for.
        id: u32,
        /// How many agents there are.
        agents: usize,
    },
    /// A device for the simulation's parameters could not be made.
    #[error("device: {0}")]
    Device(swarm_core::Error),
    /// A scenario given to a model that does not live in its world (an ant simulation of a
    /// 3D world, ...).
    #[error("scenario `{scenario}` is not a {dim}D world: the {model} model cannot run it")]
    WrongWorld {
        /// The scenario.
        scenario: String,
        /// The model.
        model: &'static str,
        /// The dimension the model needs.
        dim: usize,
    },
    /// A group names an object the scenario does not have (or of the wrong kind).
    #[error("group `{group}`: no {what} `{name}`")]
    NoObject {
        /// The group.
        group: String,
        /// What it names (`nest`, `goal`).
        what: &'static str,
        /// The name (empty if none was given).
        name: String,
    },
    /// A group's parameters, converted to its scalar type, fail the controller's validation.
    #[error("group `{group}`: {source}")]
    GroupParams {
        /// The group.
        group: String,
        /// The controller's complaint (which parameter).
        source: swarm_core::Error,
    },
    /// A worker-thread count of zero.
    #[error("threads: must be at least 1")]
    NoThreads,
    /// The pool of worker threads could not be started.
    #[error("threads: cannot start {threads} threads: {source}")]
    ThreadPool {
        /// The count asked for.
        threads: usize,
        /// The pool's error.
        source: rayon::ThreadPoolBuildError,
    },
    /// A benchmark with nothing to time.
    #[error("bench: needs at least one agent and one step (got {agents} agents, {steps} steps)")]
    EmptyBench {
        /// Agents asked for.
        agents: usize,
        /// Steps asked for.
        steps: u32,
    },
    /// A run failed after it started writing: its output folder was left as it was, and the
    /// run's log (ending with the error) kept beside it, when it could be.
    #[error(
        "{error}\n{} was left untouched{}",
        target.display(),
        log.as_ref().map_or_else(String::new, |l| format!("; the failed run's log is {}", l.display()))
    )]
    RunFailed {
        /// The output folder the run was to replace.
        target: PathBuf,
        /// The failed run's log, if it could be kept.
        log: Option<PathBuf>,
        /// What went wrong.
        error: Box<SimError>,
    },

    // ---- scenarios ----
    /// A scenario file could not be read.
    #[error("cannot read scenario file `{}`: {source}", path.display())]
    ScenarioRead {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        #[source]
        source: std::io::Error,
    },
    /// A scenario is not valid TOML, does not have the scenario's shape (unknown field, wrong
    /// type, missing field) or breaks a rule of the scenario (a spawn region outside the world,
    /// an event naming a missing object, a bad controller parameter, ...). Loading stops at the
    /// first problem; the diagnostic names the file, line, column and field path.
    #[error("{0}")]
    InvalidScenario(Box<Diagnostic>),
    /// Neither a built-in scenario nor a file of that name (`resolve`).
    #[error(
        "no built-in scenario and no file named `{name}` (built-in scenarios: {})",
        builtins.join(", ")
    )]
    ScenarioNotFound {
        /// The name or path asked for.
        name: String,
        /// The names of the built-in scenarios.
        builtins: &'static [&'static str],
    },

    /// An output could not be written or read (the path in the message).
    #[error(transparent)]
    Output(#[from] crate::output::OutputError),
}

impl SimError {
    /// A controller's refusal of agent `agent`'s frame in `phase` at `step`.
    pub fn controller(phase: &'static str, step: u32, agent: u32, e: swarm_core::Error) -> Self {
        SimError::Controller {
            phase,
            step,
            agent,
            source: e,
        }
    }

    /// The diagnostic of an [`InvalidScenario`](SimError::InvalidScenario) error.
    pub fn diagnostic(&self) -> Option<&Diagnostic> {
        match self {
            SimError::InvalidScenario(d) => Some(d),
            _ => None,
        }
    }
}
