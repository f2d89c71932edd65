//! Sanity checks of a scenario's layout, after the rules of `rules/` have passed: what cannot
//! work is refused (a food source, way point or target wholly inside an obstacle, at the start
//! or moved or added there by an event), what probably is a mistake is a warning (a nest in or
//! on an obstacle, a food source partly in one, a spawn region partly inside obstacles, a nest
//! covering a food source, an event dropping an obstacle over a food source).
//!
//! Geometry is exact for every pair of shapes (circles, simple polygons convex or concave with
//! the engine's own inside test, spheres, boxes, shafts); only the share of a spawn region
//! inside obstacles is measured on a grid of points (a few thousand). Containment is checked
//! against one obstacle at a time: a food source covered by two touching rocks is not refused.

mod solid;

use super::problem::Problem;
use super::types::{Action, Object, ObjectKind, Scenario, SpawnRegion};
use super::warning::WarningKind;
use solid::{Solid, dist};

/// A warning found by [`check`]: its kind and where (field path) and why.
pub(crate) struct Finding {
    pub kind: WarningKind,
    pub problem: Problem,
}

/// Share of a spawn region inside obstacles from which a warning is given.
const SPAWN_SHARE_WARN: f64 = 0.01;

/// Grid points per axis when sampling a spawn region (2D, 3D).
const SAMPLES_2D: usize = 48;
const SAMPLES_3D: usize = 16;

/// What an object is, for these checks.
enum Role<'a> {
    /// Agents must not enter it.
    Obstacle(Solid),
    /// Agents must reach it: a food source, way point or target (centre, radius).
    Destination(&'a [f32], f32),
    /// An ant nest (centre, radius).
    Nest(&'a [f32], f32),
    /// Nothing checked (disturbances).
    Other,
}

fn role(kind: &ObjectKind) -> Role<'_> {
    match kind {
        ObjectKind::Nest { center, radius } => Role::Nest(center, *radius),
        ObjectKind::Food { center, radius, .. } | ObjectKind::Waypoint { center, radius, .. } => {
            Role::Destination(center, *radius)
        }
        ObjectKind::Target { center, radius, .. } | ObjectKind::Zone { center, radius } => {
            Role::Destination(center, *radius)
        }
        ObjectKind::Disturbance { .. } | ObjectKind::Region { .. } => Role::Other,
        _ => Solid::of(kind).map_or(Role::Other, Role::Obstacle),
    }
}

/// `food `name` (centre [x, y], radius r)`.
fn describe(o: &Object) -> String {
    let kind = match o.kind {
        ObjectKind::Food { .. } => "food source",
        ObjectKind::Waypoint { .. } => "way point",
        ObjectKind::Target { .. } => "target",
        _ => o.kind.tag(),
    };
    match (o.kind.center(), o.kind.radius()) {
        (Some(c), Some(r)) => {
            let c: Vec<String> = c.iter().map(|v| v.to_string()).collect();
            format!(
                "{kind} `{}` (centre [{}], radius {r})",
                o.name,
                c.join(", ")
            )
        }
        _ => format!("{kind} `{}`", o.name),
    }
}

/// Why nobody reaches a destination inside an obstacle.
fn unreachable(o: &Object) -> &'static str {
    match o.kind {
        ObjectKind::Waypoint { .. } => "the colony's route cannot pass through it",
        ObjectKind::Target { .. } => "no bee can reach it",
        ObjectKind::Zone { .. } => "no insect can reach it",
        _ => "no ant can ever collect from it",
    }
}

/// The state of the world's objects at some step: each object as it is then, and whether it
/// is present.
struct State<'s> {
    s: &'s Scenario,
    objects: Vec<(Object, bool)>,
}

impl State<'_> {
    fn present(&self) -> impl Iterator<Item = (usize, &Object)> {
        self.objects
            .iter()
            .enumerate()
            .filter(|(_, (_, on))| *on)
            .map(|(j, (o, _))| (j, o))
    }

    /// The first present obstacle (other than `i`) that holds the disc/ball wholly.
    fn covering(&self, i: usize, c: &[f32], r: f32) -> Option<(usize, &Object)> {
        self.present().filter(|(j, _)| *j != i).find(
            |(_, o)| matches!(role(&o.kind), Role::Obstacle(solid) if solid.contains_round(c, r)),
        )
    }

    /// The present obstacles (other than `i`) that overlap the disc/ball.
    fn overlapping(&self, i: usize, c: &[f32], r: f32) -> Vec<(usize, &Object)> {
        self.present()
            .filter(|(j, _)| *j != i)
            .filter(|(_, o)| {
                matches!(role(&o.kind), Role::Obstacle(solid) if solid.overlaps_round(c, r))
            })
            .collect()
    }

    /// Checks present object `i` against every other present object; `at` is the field the
    /// findings point at and `when` says when ("" at the start, "after this event (step N), "
    /// for an event). `moved` is true when `i` is what the event changed (a destination moved
    /// or added into an obstacle is refused; an obstacle dropped over one is a warning).
    fn check_object(
        &self,
        i: usize,
        at: &str,
        when: &str,
        event: bool,
        out: &mut Vec<Finding>,
    ) -> Result<(), Problem> {
        let o = &self.objects[i].0;
        let warn = |out: &mut Vec<Finding>, kind, message: String| {
            out.push(Finding {
                kind,
                problem: Problem::new(at, message),
            })
        };
        match role(&o.kind) {
            Role::Destination(c, r) => {
                if let Some((j, ob)) = self.covering(i, c, r) {
                    return Err(Problem::new(
                        at,
                        format!(
                            "{when}the {} lies entirely inside the {} `{}` (objects[{j}]): {}; \
                             move it out of the obstacle",
                            describe(o),
                            ob.kind.tag(),
                            ob.name,
                            unreachable(o)
                        ),
                    ));
                }
                let over = self.overlapping(i, c, r);
                if matches!(
                    o.kind,
                    ObjectKind::Food { .. } | ObjectKind::Waypoint { .. }
                ) && let Some((j, ob)) = over.first()
                {
                    warn(
                        out,
                        WarningKind::FoodOverlapsObstacle,
                        format!(
                            "{when}the {} overlaps the {} `{}` (objects[{j}]): ants reach only \
                             the part outside it",
                            describe(o),
                            ob.kind.tag(),
                            ob.name
                        ),
                    );
                }
                if let Some((j, nest)) = self.nest_overlapping(i, c, r) {
                    warn(
                        out,
                        WarningKind::NestCoversFood,
                        format!(
                            "{when}the {} overlaps the nest `{}` (objects[{j}]): ants pick food \
                             up where they deliver it",
                            describe(o),
                            nest.name
                        ),
                    );
                }
            }
            Role::Nest(c, r) => {
                if let Some((j, ob)) = self.covering(i, c, r) {
                    warn(
                        out,
                        WarningKind::NestInObstacle,
                        format!(
                            "{when}the {} lies entirely inside the {} `{}` (objects[{j}]): ants \
                             cannot deliver food to it",
                            describe(o),
                            ob.kind.tag(),
                            ob.name
                        ),
                    );
                } else if let Some((j, ob)) = self.overlapping(i, c, r).first() {
                    warn(
                        out,
                        WarningKind::NestInObstacle,
                        format!(
                            "{when}the {} overlaps the {} `{}` (objects[{j}]): part of the nest \
                             cannot be reached",
                            describe(o),
                            ob.kind.tag(),
                            ob.name
                        ),
                    );
                }
                if event {
                    for (j, food) in self.present().filter(|(j, _)| *j != i) {
                        if let Role::Destination(fc, fr) = role(&food.kind)
                            && matches!(food.kind, ObjectKind::Food { .. })
                            && Solid::Disc([c[0], c[1]], r).overlaps_round(fc, fr)
                        {
                            warn(
                                out,
                                WarningKind::NestCoversFood,
                                format!(
                                    "{when}the {} overlaps the {} (objects[{j}]): ants pick \
                                     food up where they deliver it",
                                    describe(o),
                                    describe(food)
                                ),
                            );
                        }
                    }
                }
            }
            Role::Obstacle(solid) if event => {
                for (j, d) in self.present().filter(|(j, _)| *j != i) {
                    if let Role::Destination(c, r) = role(&d.kind)
                        && solid.contains_round(c, r)
                    {
                        warn(
                            out,
                            WarningKind::EventCoversFood,
                            format!(
                                "{when}the {} `{}` covers the {} (objects[{j}]) entirely: {} \
                                 until the obstacle is moved or removed",
                                o.kind.tag(),
                                o.name,
                                describe(d),
                                unreachable(d)
                            ),
                        );
                    }
                }
            }
            Role::Obstacle(_) | Role::Other => {}
        }
        Ok(())
    }

    /// A present nest (other than `i`) overlapping the disc (`c`, `r`).
    fn nest_overlapping(&self, i: usize, c: &[f32], r: f32) -> Option<(usize, &Object)> {
        self.present().filter(|(j, _)| *j != i).find(|(_, o)| {
            matches!(role(&o.kind), Role::Nest(nc, nr) if Solid::Disc([nc[0], nc[1]], nr).overlaps_round(c, r))
        })
    }
}

/// Every sanity check of `s` (whose rules have passed): `Err` for what cannot work, the
/// warnings otherwise.
pub(crate) fn check(s: &Scenario) -> Result<Vec<Finding>, Problem> {
    let mut out = Vec::new();
    let mut state = State {
        s,
        objects: s.objects.iter().map(|o| (o.clone(), o.active)).collect(),
    };
    for i in 0..state.objects.len() {
        if state.objects[i].1 {
            state.check_object(i, &format!("objects[{i}].center"), "", false, &mut out)?;
        }
    }
    for (g, group) in s.groups.iter().enumerate() {
        spawn_check(&state, g, &group.spawn.region, &mut out);
    }
    for (k, e) in s.events.iter().enumerate() {
        let Some(i) = state
            .s
            .objects
            .iter()
            .position(|o| o.name == e.action.object())
        else {
            continue;
        };
        let at = match &e.action {
            Action::Move { to, .. } => {
                state.objects[i].0.kind.set_center(to);
                format!("events[{k}].move.to")
            }
            Action::Add(_) | Action::Start(_) => {
                state.objects[i].1 = true;
                format!("events[{k}].{}", e.action.verb())
            }
            Action::Remove(_) | Action::Stop(_) => {
                state.objects[i].1 = false;
                continue;
            }
        };
        if state.objects[i].1 {
            let when = format!("after this event (step {}), ", e.step);
            state.check_object(i, &at, &when, true, &mut out)?;
        }
    }
    Ok(out)
}

/// Warns when part of group `g`'s spawn region lies inside obstacles present at the start.
fn spawn_check(state: &State<'_>, g: usize, region: &SpawnRegion, out: &mut Vec<Finding>) {
    let (lo, hi, center, radius) = match region {
        SpawnRegion::Around { at, radius } => {
            let Some(c) = state.s.object(at).and_then(|o| o.kind.point()) else {
                return;
            };
            let lo: Vec<f32> = c.iter().map(|v| v - radius).collect();
            let hi: Vec<f32> = c.iter().map(|v| v + radius).collect();
            (lo, hi, Some(c.to_vec()), *radius)
        }
        SpawnRegion::Box { min, max } => (min.clone(), max.clone(), None, 0.0),
    };
    let solids: Vec<(&Object, Solid)> = state
        .present()
        .filter_map(|(_, o)| Solid::of(&o.kind).map(|s| (o, s)))
        .collect();
    if solids.is_empty() {
        return;
    }
    let n = if lo.len() == 2 {
        SAMPLES_2D
    } else {
        SAMPLES_3D
    };
    let (mut total, mut inside) = (0usize, 0usize);
    let mut hit = vec![false; solids.len()];
    let mut p = vec![0.0f32; lo.len()];
    let cells = n.pow(lo.len() as u32);
    for cell in 0..cells {
        let mut rest = cell;
        for (k, v) in p.iter_mut().enumerate() {
            let t = ((rest % n) as f32 + 0.5) / n as f32;
            rest /= n;
            *v = lo[k] + t * (hi[k] - lo[k]);
        }
        if center.as_ref().is_some_and(|c| dist(&p, c) > radius) {
            continue;
        }
        total += 1;
        let mut any = false;
        for (h, (_, solid)) in hit.iter_mut().zip(&solids) {
            if solid.contains_point(&p) {
                *h = true;
                any = true;
            }
        }
        inside += usize::from(any);
    }
    let share = inside as f64 / total.max(1) as f64;
    if share < SPAWN_SHARE_WARN {
        return;
    }
    let names: Vec<String> = solids
        .iter()
        .zip(&hit)
        .filter(|(_, h)| **h)
        .map(|((o, _), _)| format!("`{}`", o.name))
        .collect();
    let how_much = if inside == total {
        "the whole spawn region lies".to_owned()
    } else {
        format!("about {:.0} % of the spawn region lies", share * 100.0)
    };
    out.push(Finding {
        kind: WarningKind::SpawnInObstacle,
        problem: Problem::new(
            format!("groups[{g}].spawn"),
            format!(
                "{how_much} inside the obstacle{} {}: agents that start there begin inside an \
                 obstacle",
                if names.len() == 1 { "" } else { "s" },
                names.join(", ")
            ),
        ),
    });
}
