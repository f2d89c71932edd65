//! The rules of the agent groups: names, counts, a known model that fits the world, the spawn
//! region; then the rules of the group's model (the objects it names, its parameters: the
//! model's entry, [`ModelEntry::check`](crate::models::ModelEntry::check)).

use std::collections::HashMap;

use super::{Problem, finite_all, inside, lookup, positive, show, world_text};
use crate::scenario::check::GroupCheck;
use crate::scenario::types::{Group, MAX_AGENTS, Scenario, SpawnRegion};

pub(super) fn validate_groups(s: &Scenario, objects: &HashMap<&str, usize>) -> Result<(), Problem> {
    if s.groups.is_empty() {
        return Err(Problem::new(
            "groups",
            "a scenario needs at least one group of agents (a [[groups]] table)",
        ));
    }
    let mut names: HashMap<&str, usize> = HashMap::new();
    let mut total: u64 = 0;
    for (i, g) in s.groups.iter().enumerate() {
        let path = format!("groups[{i}]");
        let field = |f: &str| format!("{path}.{f}");
        if g.name.is_empty() {
            return Err(Problem::new(field("name"), "expected a non-empty name"));
        }
        if let Some(j) = names.insert(&g.name, i) {
            return Err(Problem::new(
                field("name"),
                format!(
                    "duplicate group name `{}` (also groups[{j}]); names must be unique",
                    g.name
                ),
            ));
        }
        if g.count == 0 || g.count > MAX_AGENTS {
            return Err(Problem::new(
                field("count"),
                format!("expected 1 to {MAX_AGENTS} agents, found {}", g.count),
            ));
        }
        total += u64::from(g.count);
        if total > u64::from(MAX_AGENTS) {
            return Err(Problem::new(
                field("count"),
                format!(
                    "the groups hold {total} agents in all, more than the {MAX_AGENTS} a \
                     scenario may have"
                ),
            ));
        }
        if g.model != s.groups[0].model {
            return Err(Problem::new(
                field("model"),
                format!(
                    "every group of a scenario runs the same model, and groups[0] is `{}`, not \
                     `{}`",
                    s.groups[0].model, g.model
                ),
            ));
        }
        let Some(model) = crate::models::find(g.model.as_str()) else {
            return Err(Problem::new(
                field("model"),
                format!(
                    "unknown model `{}`, expected one of {}",
                    g.model,
                    crate::models::names()
                        .iter()
                        .map(|n| format!("`{n}`"))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            ));
        };
        if model.dim != s.world.dim() {
            return Err(Problem::new(
                field("model"),
                format!(
                    "`{}` groups live in a {d}D world (`dim = {d}`), but this world is {w}D \
                     (`dim = {w}`)",
                    g.model,
                    d = model.dim,
                    w = s.world.dim(),
                ),
            ));
        }
        (model.check)(&GroupCheck::new(s, i, objects))?;
        validate_spawn(s, objects, g, &path)?;
    }
    Ok(())
}

fn validate_spawn(
    s: &Scenario,
    objects: &HashMap<&str, usize>,
    g: &Group,
    path: &str,
) -> Result<(), Problem> {
    let field = |f: &str| format!("{path}.spawn.{f}");
    let world = &s.world;
    match &g.spawn.region {
        SpawnRegion::Around { at, radius } => {
            let (_, o) = lookup(s, objects, at, &field("at"))?;
            let Some(center) = o.kind.point() else {
                return Err(Problem::new(
                    field("at"),
                    format!(
                        "cannot spawn around `{at}`: a `{}` has no centre point (spawn around a \
                         nest, food source, target, ... or in a box with `min` + `max`)",
                        o.kind.tag()
                    ),
                ));
            };
            positive(*radius, &field("radius"))?;
            let fits = center
                .iter()
                .zip(world.min().iter().zip(world.max()))
                .all(|(c, (lo, hi))| c - radius >= *lo && c + radius <= *hi);
            if !fits {
                return Err(Problem::new(
                    field("radius"),
                    format!(
                        "the {} of radius {radius} around `{at}` (centre {}) reaches outside the \
                         world {}",
                        if world.dim() == 2 { "disc" } else { "ball" },
                        show(center),
                        world_text(world)
                    ),
                ));
            }
        }
        SpawnRegion::Box { min, max } => {
            inside(world, min, &field("min"), "the corner")?;
            inside(world, max, &field("max"), "the corner")?;
            if min.iter().zip(max).any(|(lo, hi)| lo > hi) {
                return Err(Problem::new(
                    field("max"),
                    format!(
                        "expected `max` >= `min` on every axis, found min {} max {}",
                        show(min),
                        show(max)
                    ),
                ));
            }
        }
    }
    if let Some(h) = &g.spawn.heading {
        let path = field("heading");
        if h.len() != world.dim() {
            return Err(Problem::new(
                path,
                format!(
                    "expected a direction of {} numbers, found {}",
                    world.dim(),
                    h.len()
                ),
            ));
        }
        finite_all(h, &path)?;
        if h.iter().all(|v| *v == 0.0) {
            return Err(Problem::new(
                path,
                "expected a non-zero direction (leave `heading` out for random headings)",
            ));
        }
    }
    Ok(())
}
