//! The rules of the timed events: in step order before the end of the run, naming an object
//! present (or absent) at that step, moving an object to a place inside the world.

use std::collections::HashMap;

use super::objects::validate_geometry;
use super::{Problem, finite_all, lookup};
use crate::scenario::types::{Action, ObjectKind, Scenario};

pub(super) fn validate_events(s: &Scenario, objects: &HashMap<&str, usize>) -> Result<(), Problem> {
    let mut active: Vec<bool> = s.objects.iter().map(|o| o.active).collect();
    let mut previous: Option<(u32, usize)> = None;
    for (i, e) in s.events.iter().enumerate() {
        let path = format!("events[{i}]");
        let field = |f: &str| format!("{path}.{f}");
        if e.step >= s.steps {
            return Err(Problem::new(
                field("step"),
                format!(
                    "expected a step before the end of the run (`steps` = {}), found {}",
                    s.steps, e.step
                ),
            ));
        }
        if let Some((step, j)) = previous
            && e.step < step
        {
            return Err(Problem::new(
                field("step"),
                format!(
                    "events must be listed in step order, but step {} comes after step {step} \
                     (events[{j}])",
                    e.step
                ),
            ));
        }
        previous = Some((e.step, i));
        let verb = e.action.verb();
        let name = e.action.object();
        let name_path = if verb == "move" {
            field("move.object")
        } else {
            field(verb)
        };
        let (k, o) = lookup(s, objects, name, &name_path)?;
        let step = e.step;
        match &e.action {
            Action::Add(_) if active[k] => {
                return Err(Problem::new(
                    name_path,
                    format!(
                        "`{name}` is already present at step {step} (objects are present from \
                         the start unless `active = false`)"
                    ),
                ));
            }
            Action::Remove(_) if !active[k] => {
                return Err(Problem::new(
                    name_path,
                    format!("`{name}` is not present at step {step}, so it cannot be removed"),
                ));
            }
            Action::Add(_) | Action::Remove(_) => active[k] = !active[k],
            Action::Start(_) | Action::Stop(_) => {
                if !matches!(o.kind, ObjectKind::Disturbance { .. }) {
                    return Err(Problem::new(
                        name_path,
                        format!(
                            "`{verb}` applies to disturbances, but `{name}` is a `{}` (use \
                             `add` / `remove`)",
                            o.kind.tag()
                        ),
                    ));
                }
                let start = matches!(e.action, Action::Start(_));
                if active[k] == start {
                    return Err(Problem::new(
                        name_path,
                        if start {
                            format!(
                                "`{name}` is already acting at step {step} (a disturbance acts \
                                 from the start unless `active = false`)"
                            )
                        } else {
                            format!("`{name}` is not acting at step {step}, so it cannot stop")
                        },
                    ));
                }
                active[k] = start;
            }
            Action::Move { to, .. } => {
                let Some(center) = o.kind.center() else {
                    return Err(Problem::new(
                        name_path,
                        format!(
                            "`{name}` is a `{}`, which has no centre to move",
                            o.kind.tag()
                        ),
                    ));
                };
                let to_path = field("move.to");
                if to.len() != center.len() {
                    return Err(Problem::new(
                        to_path,
                        format!(
                            "expected {} numbers (like the `center` of the `{}` `{name}`), \
                             found {}",
                            center.len(),
                            o.kind.tag(),
                            to.len()
                        ),
                    ));
                }
                finite_all(to, &to_path)?;
                let mut moved = o.clone();
                moved.kind.set_center(to);
                validate_geometry(&s.world, &moved, "")
                    .map_err(|p| Problem::new(to_path, format!("after the move: {}", p.message)))?;
            }
        }
    }
    Ok(())
}
