//! Warnings: a scenario that runs, but probably not as its author meant.

use std::fmt;

use super::diagnostic::Diagnostic;
use super::types::Scenario;

/// What a [`ScenarioWarning`] is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum WarningKind {
    /// A nest lies inside an obstacle, or overlaps one: ants start in the obstacle, and part
    /// (or all) of the nest cannot be reached.
    NestInObstacle,
    /// A food source or way point overlaps an obstacle (it is not wholly inside one: that is
    /// an error), so part of it cannot be reached.
    FoodOverlapsObstacle,
    /// Part of a group's spawn region lies inside obstacles: agents start inside them.
    SpawnInObstacle,
    /// A nest overlaps a food source: ants pick food up where they drop it.
    NestCoversFood,
    /// An event puts an obstacle over a food source, way point or target, which cannot be
    /// reached until the obstacle is moved or removed.
    EventCoversFood,
}

/// A warning about a scenario: where (file, line, column, field) and why, like an error's
/// [`Diagnostic`] (whose kind is [`Warning`](super::DiagnosticKind::Warning)).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ScenarioWarning {
    /// What it is about.
    pub kind: WarningKind,
    /// Where, and the message.
    pub diagnostic: Diagnostic,
}

impl ScenarioWarning {
    /// Whether the warning still concerns `sc`: a warning about `events[k]` does not once
    /// `--steps` has dropped that event (see [`Scenario::set_steps`]).
    pub fn applies_to(&self, sc: &Scenario) -> bool {
        let Some(rest) = self.diagnostic.field.strip_prefix("events[") else {
            return true;
        };
        rest.split(']')
            .next()
            .and_then(|k| k.parse::<usize>().ok())
            .is_none_or(|k| k < sc.events.len())
    }
}

impl fmt::Display for ScenarioWarning {
    /// `file:line:column: warning in `field`: message`, then the source line with a caret.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.diagnostic.fmt(f)
    }
}
