//! The rules of the agent groups: names, counts, the model fits the world, the objects a group
//! names (nest, goal, spawn object), the spawn region and the parameters.

use std::collections::HashMap;

use swarm_core::Fx;
use swarm_core::ant::AntParams;
use swarm_core::bee::BeeParams;
use swarm_core::model::ModelParams;

use super::{Problem, finite_all, inside, lookup, positive, show, world_text};
use crate::scenario::types::{Group, MAX_AGENTS, Model, ScalarType, Scenario, SpawnRegion};

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
        if g.model != s.world.model() {
            return Err(Problem::new(
                field("model"),
                format!(
                    "`{}` groups live in a {} world, but this world is {}D (`dim = {}`)",
                    g.model.as_str(),
                    if g.model == Model::Ant {
                        "2D (`dim = 2`)"
                    } else {
                        "3D (`dim = 3`)"
                    },
                    s.world.dim(),
                    s.world.dim()
                ),
            ));
        }
        validate_model_fields(s, objects, g, &path)?;
        validate_spawn(s, objects, g, &path)?;
    }
    Ok(())
}

/// The fields that depend on the group's model: the object it names (an ant group's nest, a
/// bee group's goal), none of the other model's fields, valid parameters.
fn validate_model_fields(
    s: &Scenario,
    objects: &HashMap<&str, usize>,
    g: &Group,
    path: &str,
) -> Result<(), Problem> {
    let field = |f: &str| format!("{path}.{f}");
    match g.model {
        Model::Ant => {
            let Some(nest) = &g.nest else {
                return Err(Problem::new(
                    field("nest"),
                    "missing field `nest`: an ant group needs the name of its home nest (an \
                     object of kind `nest`)",
                ));
            };
            object_of_kind(s, objects, nest, &field("nest"), "nest")?;
            not_given(
                g.goal.is_some(),
                field("goal"),
                "`goal` is for bee groups; ants forage between their `nest` and the food sources",
            )?;
            not_given(
                g.bee.is_some(),
                field("bee"),
                "bee parameters in an ant group; use `[groups.ant]` for ant parameters",
            )?;
            let fixed = |p: &AntParams<f32>| p.cast::<Fx>().validate();
            check_params(&g.ant_params(), fixed, g.scalar, path, "ant")
        }
        Model::Bee => {
            not_given(
                g.nest.is_some(),
                field("nest"),
                "`nest` is for ant groups; bees fly toward a `goal` (an object of kind `target`)",
            )?;
            if let Some(goal) = &g.goal {
                object_of_kind(s, objects, goal, &field("goal"), "target")?;
            }
            not_given(
                g.ant.is_some(),
                field("ant"),
                "ant parameters in a bee group; use `[groups.bee]` for bee parameters",
            )?;
            let fixed = |p: &BeeParams<f32>| p.cast::<Fx>().validate();
            check_params(&g.bee_params(), fixed, g.scalar, path, "bee")
        }
    }
}

/// The object `name` (named at `path`) exists and is of kind `kind`.
fn object_of_kind(
    s: &Scenario,
    objects: &HashMap<&str, usize>,
    name: &str,
    path: &str,
    kind: &str,
) -> Result<(), Problem> {
    let (_, o) = lookup(s, objects, name, path)?;
    if o.kind.tag() != kind {
        return Err(Problem::new(
            path,
            format!(
                "`{name}` is a `{}`, expected an object of kind `{kind}`",
                o.kind.tag()
            ),
        ));
    }
    Ok(())
}

/// A field of the other model's groups (`given`: it is there) is refused with `message`.
fn not_given(given: bool, path: String, message: &str) -> Result<(), Problem> {
    if given {
        return Err(Problem::new(path, message));
    }
    Ok(())
}

/// Checks a group's parameters, and for a fixed-point group also `in_fixed` of them (their
/// check once converted to `Fx`); the problem names the first bad one and what it takes (from
/// the model's parameter table in swarm-core).
fn check_params<P: ModelParams>(
    params: &P,
    in_fixed: impl FnOnce(&P) -> swarm_core::Result<()>,
    scalar: ScalarType,
    path: &str,
    model: &str,
) -> Result<(), Problem> {
    let checked = params.validate().and_then(|()| match scalar {
        ScalarType::Fixed => in_fixed(params),
        ScalarType::F32 => Ok(()),
    });
    let Err(e) = checked else {
        return Ok(());
    };
    let field = match e {
        swarm_core::Error::BadParam { field } => field,
        _ => "?",
    };
    let takes = match P::index_of(field) {
        Some(i) => P::SPECS[i].to_string(),
        None => format!("a value `{model}` parameters accept"),
    };
    Err(Problem::new(
        format!("{path}.{model}.{field}"),
        format!("invalid {model} parameter `{field}`: expected {takes}"),
    ))
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
