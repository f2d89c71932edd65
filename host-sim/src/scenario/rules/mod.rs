//! The rules of a scenario: what a valid scenario is, checked on the typed [`Scenario`] (a
//! loaded file's or one built in code). Each check returns the first [`Problem`], at the path of
//! the field in the file; the sanity checks of the layout ([`sanity::check`]) come last and
//! also give the warnings.

mod events;
mod groups;
mod objects;

use std::collections::HashMap;

use super::problem::Problem;
use super::sanity::{self, Finding};
use super::types::{MAX_COORD, Object, Scenario, World};

/// Every rule of a scenario, then its sanity checks ([`sanity::check`]): the first problem,
/// or the warnings; a problem's path is the field's path in the file.
pub(crate) fn validate(s: &Scenario) -> Result<Vec<Finding>, Problem> {
    steps_rule(s.steps, "steps")?;
    validate_world(&s.world)?;
    if s.outputs.every == 0 {
        return Err(Problem::new(
            "outputs.every",
            "expected at least 1 (record every N steps), found 0",
        ));
    }
    let objects = objects::validate_objects(s)?;
    groups::validate_groups(s, &objects)?;
    events::validate_events(s, &objects)?;
    sanity::check(s)
}

/// A run has at least one step.
pub(crate) fn steps_rule(steps: u32, field: &str) -> Result<(), Problem> {
    if steps == 0 {
        return Err(Problem::new(field, "expected at least 1 step, found 0"));
    }
    Ok(())
}

fn validate_world(world: &World) -> Result<(), Problem> {
    for (field, p) in [("world.min", world.min()), ("world.max", world.max())] {
        finite_all(p, field)?;
        if p.iter().any(|v| v.abs() > MAX_COORD) {
            return Err(Problem::new(
                field,
                format!(
                    "coordinates must lie within ±{MAX_COORD} (the controllers' range), found {}",
                    show(p)
                ),
            ));
        }
    }
    let axes = ["x", "y", "z"];
    for (i, (lo, hi)) in world.min().iter().zip(world.max()).enumerate() {
        if lo >= hi {
            return Err(Problem::new(
                "world.max",
                format!(
                    "expected `max` greater than `min` on every axis, but on {} max {hi} <= min {lo}",
                    axes[i]
                ),
            ));
        }
    }
    Ok(())
}

/// The object `name` refers to, or a problem at `path` listing the names there are.
pub(crate) fn lookup<'s>(
    s: &'s Scenario,
    objects: &HashMap<&str, usize>,
    name: &str,
    path: &str,
) -> Result<(usize, &'s Object), Problem> {
    match objects.get(name) {
        Some(&i) => Ok((i, &s.objects[i])),
        None => {
            let mut known: Vec<&str> = s.objects.iter().map(|o| o.name.as_str()).collect();
            known.sort_unstable();
            Err(Problem::new(
                path,
                if known.is_empty() {
                    format!("no object named `{name}`: the scenario has no objects")
                } else {
                    format!("no object named `{name}` (objects: {})", known.join(", "))
                },
            ))
        }
    }
}

/// `[a, b]` with the shortest exact float formatting.
pub(super) fn show(p: &[f32]) -> String {
    let items: Vec<String> = p.iter().map(|v| v.to_string()).collect();
    format!("[{}]", items.join(", "))
}

pub(super) fn world_text(world: &World) -> String {
    format!("{}..{}", show(world.min()), show(world.max()))
}

pub(super) fn finite_all(p: &[f32], path: &str) -> Result<(), Problem> {
    if p.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(Problem::new(
            path,
            format!("expected finite numbers, found {}", show(p)),
        ))
    }
}

/// `p` has `dim` finite numbers inside the world.
pub(super) fn inside(world: &World, p: &[f32], path: &str, what: &str) -> Result<(), Problem> {
    if p.len() != world.dim() {
        return Err(Problem::new(
            path,
            format!(
                "expected {} numbers {}, found {}",
                world.dim(),
                if world.dim() == 2 {
                    "[x, y]"
                } else {
                    "[x, y, z]"
                },
                p.len()
            ),
        ));
    }
    finite_all(p, path)?;
    if world.contains(p) {
        Ok(())
    } else {
        Err(Problem::new(
            path,
            format!(
                "{what} {} lies outside the world {}",
                show(p),
                world_text(world)
            ),
        ))
    }
}

/// A strictly positive, finite length no larger than the coordinate range.
pub(super) fn positive(v: f32, path: &str) -> Result<(), Problem> {
    if v.is_finite() && v > 0.0 && v <= MAX_COORD {
        Ok(())
    } else {
        Err(Problem::new(
            path,
            format!("expected a positive number (at most {MAX_COORD}), found {v}"),
        ))
    }
}
