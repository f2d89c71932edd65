//! The recorded data: one [`Frame`] per recorded step, one [`AgentSample`] per agent.

use std::path::Path;

use crate::{Result, SimError};

/// One agent at one recorded step (40 bytes).
///
/// Coordinates are world coordinates: 2D ants use `z = 0` (and `hz = 0`); bees are 3D with `y`
/// up. `label` and `motion` are the model's small state codes, named by its engine
/// ([`Engine::state_names`](crate::engine::Engine::state_names)): for ants the `swarm-core`
/// label (0 nothing, 1 food, 2 nest, [`label_name`]) and motion state (0 stop, 1 basic
/// movement, 2 neighbours, 3 environment). `roll` and `pitch` are the body
/// attitude in degrees: for bees the set-points of the step's decision (chen eq. 3, and eq. 4
/// or eq. 6 while avoiding; a positive roll lowers the right wing, the right being
/// heading × up); ants are ground robots that stay level and record 0.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct AgentSample {
    /// Agent id (index in the swarm).
    pub id: u32,
    /// Position.
    pub pos: [f32; 3],
    /// Heading (unit vector; for bees the velocity direction).
    pub heading: [f32; 3],
    /// Index of the agent's group in the scenario.
    pub group: u16,
    /// State label code.
    pub label: u8,
    /// Motion state code.
    pub motion: u8,
    /// Roll angle in degrees (positive: right wing down); 0 for ants.
    pub roll: f32,
    /// Pitch angle in degrees (positive: nose up); 0 for ants.
    pub pitch: f32,
}

/// The whole swarm at one recorded step: agents in id order, the same agents in every frame.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Frame {
    /// The simulation step this frame was recorded at.
    pub step: u32,
    /// One sample per agent, in id order.
    pub agents: Vec<AgentSample>,
}

/// Name of an ant label code (`swarm_core::ant::Label` order); `"label<N>"` for other codes.
pub fn label_name(code: u8) -> std::borrow::Cow<'static, str> {
    match code {
        0 => "nothing".into(),
        1 => "food".into(),
        2 => "nest".into(),
        n => format!("label{n}").into(),
    }
}

/// Checks that every frame holds the same agents (same count and ids, in the same order) and that
/// steps increase strictly; returns the agent count. `path` only names the file in the error.
pub fn check_frames(frames: &[Frame], path: &Path) -> Result<usize> {
    let Some(first) = frames.first() else {
        return Ok(0);
    };
    let n = first.agents.len();
    for (fi, f) in frames.iter().enumerate() {
        if f.agents.len() != n {
            return Err(SimError::FrameAgentCount {
                path: path.to_path_buf(),
                frame: fi,
                step: f.step,
                agents: f.agents.len(),
                first: n,
            });
        }
        if fi > 0 && f.step <= frames[fi - 1].step {
            return Err(SimError::FrameStepOrder {
                path: path.to_path_buf(),
                frame: fi,
                step: f.step,
                previous: frames[fi - 1].step,
            });
        }
        if fi > 0
            && let Some(i) = (0..n).find(|&i| f.agents[i].id != first.agents[i].id)
        {
            return Err(SimError::FrameAgentId {
                path: path.to_path_buf(),
                frame: fi,
                step: f.step,
                index: i,
                id: f.agents[i].id,
                first: first.agents[i].id,
            });
        }
    }
    Ok(n)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sample_is_compact() {
        assert_eq!(std::mem::size_of::<AgentSample>(), 40);
    }

    #[test]
    fn names() {
        assert_eq!(label_name(1), "food");
        assert_eq!(label_name(9), "label9");
    }

    #[test]
    fn check_rejects_mismatch() {
        let a = |id| AgentSample {
            id,
            ..Default::default()
        };
        let ok = vec![
            Frame {
                step: 0,
                agents: vec![a(0), a(1)],
            },
            Frame {
                step: 5,
                agents: vec![a(0), a(1)],
            },
        ];
        assert_eq!(check_frames(&ok, Path::new("x")).unwrap(), 2);
        let mut bad = ok.clone();
        bad[1].agents.pop();
        assert!(check_frames(&bad, Path::new("x")).is_err());
        let mut bad = ok.clone();
        bad[1].agents[1].id = 7;
        assert!(check_frames(&bad, Path::new("x")).is_err());
        let mut bad = ok;
        bad[1].step = 0;
        assert!(check_frames(&bad, Path::new("x")).is_err());
    }
}
