//! The crate's error type.

/// `Result` with [`SimError`].
pub type Result<T> = std::result::Result<T, SimError>;

/// Everything that can go wrong in the simulator.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SimError {
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
    /// The scenario cannot run (its message says why).
    #[error("{0}")]
    Invalid(String),
    /// A scenario file could not be read or is invalid (file, line, field in the message).
    #[error(transparent)]
    Scenario(#[from] crate::scenario::ScenarioError),
    /// An output could not be written or read (the path in the message).
    #[error(transparent)]
    Output(#[from] crate::output::OutputError),
    /// A run failed after it started writing: its output folder was left as it was, and the
    /// run's log (ending with the error) kept beside it, when it could be.
    #[error(
        "{error}\n{} was left untouched{}",
        target.display(),
        log.as_ref().map_or_else(String::new, |l| format!("; the failed run's log is {}", l.display()))
    )]
    RunFailed {
        /// The output folder the run was to replace.
        target: std::path::PathBuf,
        /// The failed run's log, if it could be kept.
        log: Option<std::path::PathBuf>,
        /// What went wrong.
        error: Box<SimError>,
    },
}

impl SimError {
    pub(crate) fn controller(
        phase: &'static str,
        step: u32,
        agent: u32,
        e: swarm_core::Error,
    ) -> Self {
        SimError::Controller {
            phase,
            step,
            agent,
            source: e,
        }
    }
}
