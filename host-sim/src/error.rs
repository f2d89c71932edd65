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
    /// The scenario is invalid for the engine.
    #[error("scenario: {0}")]
    Invalid(String),
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
