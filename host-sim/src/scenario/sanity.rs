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

use crate::ants::{AntObjectDef, AntObjectKind, Shape2};

use super::problem::Problem;
use super::types::{Action, Object, ObjectKind, Scenario, SpawnRegion};
use super::warning::WarningKind;

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

/// An obstacle's solid.
enum Solid {
    Disc([f32; 2], f32),
    /// A polygon, as the engine's object (for its inside test).
    Polygon(AntObjectDef),
    Ball([f32; 3], f32),
    Cuboid([f32; 3], [f32; 3]),
    /// A vertical cylinder: axis `[x, z]`, radius, y range.
    Cylinder([f32; 2], f32, f32, f32),
}

fn dist(a: &[f32], b: &[f32]) -> f32 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f32>()
        .sqrt()
}

impl Solid {
    fn of(kind: &ObjectKind) -> Option<Solid> {
        Some(match kind {
            ObjectKind::Rock { center, radius } => Solid::Disc(*center, *radius),
            ObjectKind::Polygon { points } => Solid::Polygon(AntObjectDef {
                id: 0,
                name: String::new(),
                kind: AntObjectKind::Obstacle,
                shape: Shape2::Polygon {
                    points: points.clone(),
                },
                active: true,
            }),
            ObjectKind::Sphere { center, radius } => Solid::Ball(*center, *radius),
            ObjectKind::Box { min, max } => Solid::Cuboid(*min, *max),
            ObjectKind::Shaft {
                center,
                radius,
                y_min,
                y_max,
            } => Solid::Cylinder(*center, *radius, *y_min, *y_max),
            _ => return None,
        })
    }

    /// (inside, distance from `p` to the boundary) for the 2D solids.
    fn polygon_probe(def: &AntObjectDef, p: &[f32]) -> (bool, f32) {
        let p = [p[0], p.get(1).copied().unwrap_or(0.0)];
        let (q, inside) = def.closest(p);
        (inside, dist(&p, &q))
    }

    /// Whether the point `p` (`dim` numbers) lies inside (borders included).
    fn contains_point(&self, p: &[f32]) -> bool {
        self.contains_round(p, 0.0)
    }

    /// Whether the disc or ball (`c`, `r`) lies wholly inside (borders included).
    fn contains_round(&self, c: &[f32], r: f32) -> bool {
        match self {
            Solid::Disc(center, radius) => dist(c, center) + r <= *radius,
            Solid::Ball(center, radius) => dist(c, center) + r <= *radius,
            Solid::Polygon(def) => {
                let (inside, d) = Self::polygon_probe(def, c);
                inside && d >= r
            }
            Solid::Cuboid(lo, hi) => (0..3).all(|k| c[k] - r >= lo[k] && c[k] + r <= hi[k]),
            Solid::Cylinder(axis, radius, y0, y1) => {
                dist(&[c[0], c[2]], axis) + r <= *radius && c[1] - r >= *y0 && c[1] + r <= *y1
            }
        }
    }

    /// Whether the disc or ball (`c`, `r`) and the solid share more than a boundary point.
    fn overlaps_round(&self, c: &[f32], r: f32) -> bool {
        match self {
            Solid::Disc(center, radius) => dist(c, center) < r + radius,
            Solid::Ball(center, radius) => dist(c, center) < r + radius,
            Solid::Polygon(def) => {
                let (inside, d) = Self::polygon_probe(def, c);
                inside || d < r
            }
            Solid::Cuboid(lo, hi) => {
                let q: Vec<f32> = (0..3).map(|k| c[k].clamp(lo[k], hi[k])).collect();
                dist(c, &q) < r
            }
            Solid::Cylinder(axis, radius, y0, y1) => {
                let out_h = (dist(&[c[0], c[2]], axis) - radius).max(0.0);
                let out_y = (y0 - c[1]).max(c[1] - y1).max(0.0);
                out_h.hypot(out_y) < r
            }
        }
    }
}

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
        ObjectKind::Target { center, radius, .. } => Role::Destination(center, *radius),
        ObjectKind::Disturbance { .. } => Role::Other,
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shapes_contain_and_overlap_exactly() {
        let disc = Solid::Disc([0.0, 0.0], 10.0);
        assert!(disc.contains_round(&[5.0, 0.0], 5.0));
        assert!(!disc.contains_round(&[5.0, 0.0], 5.5));
        assert!(disc.overlaps_round(&[14.0, 0.0], 5.0));
        assert!(
            !disc.overlaps_round(&[15.0, 0.0], 5.0),
            "touching is not overlapping"
        );
        // A concave polygon (a U): the notch is outside.
        let u = Solid::of(&ObjectKind::Polygon {
            points: vec![
                [0.0, 0.0],
                [30.0, 0.0],
                [30.0, 30.0],
                [20.0, 30.0],
                [20.0, 10.0],
                [10.0, 10.0],
                [10.0, 30.0],
                [0.0, 30.0],
            ],
        })
        .unwrap();
        assert!(u.contains_round(&[5.0, 15.0], 4.0));
        assert!(!u.contains_round(&[5.0, 15.0], 6.0));
        assert!(!u.contains_point(&[15.0, 20.0]), "the notch");
        assert!(!u.overlaps_round(&[15.0, 20.0], 4.0));
        assert!(u.overlaps_round(&[15.0, 20.0], 6.0));
        let cube = Solid::Cuboid([0.0; 3], [10.0; 3]);
        assert!(cube.contains_round(&[5.0; 3], 5.0));
        assert!(!cube.contains_round(&[5.0, 5.0, 6.0], 5.0));
        assert!(cube.overlaps_round(&[5.0, 12.0, 5.0], 2.5));
        assert!(
            !cube.overlaps_round(&[12.0, 12.0, 5.0], 2.5),
            "corner distance is 2.83"
        );
        let shaft = Solid::Cylinder([0.0, 0.0], 3.0, 0.0, 20.0);
        assert!(shaft.contains_round(&[1.0, 10.0, 0.0], 2.0));
        assert!(!shaft.contains_round(&[1.0, 19.0, 0.0], 2.0));
        assert!(shaft.overlaps_round(&[0.0, 21.0, 0.0], 2.0));
        assert!(!shaft.overlaps_round(&[5.0, 10.0, 0.0], 1.5));
        let ball = Solid::Ball([0.0; 3], 4.0);
        assert!(ball.contains_point(&[0.0, 4.0, 0.0]));
        assert!(!ball.contains_point(&[0.0, 4.1, 0.0]));
    }

    use crate::scenario::{
        BUILTINS, DiagnosticKind, ScenarioError, WarningKind, resolve_with_warnings,
    };

    /// An ant world: a nest, a food source, a rock and a concave polygon (a U open upwards,
    /// its notch x 110..120, y 10..30) well apart; the tests move things into each other.
    const ANTS: &str = r#"
steps = 100
world = { dim = 2, min = [0, 0], max = [200, 100] }

[[groups]]
name = "colony"
model = "ant"
count = 10
nest = "nest"
spawn = { at = "nest", radius = 4 }

[[objects]]
name = "nest"
kind = "nest"
center = [20, 50]
radius = 3

[[objects]]
name = "food"
kind = "food"
center = [180, 50]
radius = 3

[[objects]]
name = "boulder"
kind = "rock"
center = [60, 50]
radius = 10

[[objects]]
name = "u"
kind = "polygon"
points = [[100, 0], [130, 0], [130, 30], [120, 30], [120, 10], [110, 10], [110, 30], [100, 30]]
"#;

    const BEES: &str = r#"
steps = 50
world = { dim = 3, min = [0, 0, 0], max = [60, 30, 60] }

[[groups]]
name = "swarm"
model = "bee"
count = 10
goal = "flower"
spawn = { min = [2, 5, 2], max = [10, 15, 10] }

[[objects]]
name = "flower"
kind = "target"
center = [40, 15, 40]
radius = 2
particles = 20

[[objects]]
name = "ground"
kind = "box"
min = [0, 0, 0]
max = [60, 1, 60]

[[objects]]
name = "pole"
kind = "shaft"
center = [30, 30]
radius = 3
y_min = 0
y_max = 30
"#;

    fn edit(text: &str, from: &str, to: &str) -> String {
        assert!(text.contains(from), "`{from}` not in the text");
        text.replacen(from, to, 1)
    }

    fn line_of(text: &str, needle: &str) -> usize {
        text[..text.find(needle).unwrap()].matches('\n').count() + 1
    }

    fn warnings(text: &str) -> Vec<crate::scenario::ScenarioWarning> {
        Scenario::from_str_with_warnings(text, "t.toml")
            .unwrap_or_else(|e| panic!("{e}"))
            .1
    }

    /// Loads `text`, expects it refused at `line` / `field`, with a message naming `names`.
    #[track_caller]
    fn refused(text: &str, line: usize, field: &str, names: &[&str]) {
        let err = Scenario::from_str(text, "t.toml").expect_err("should be refused");
        let shown = err.to_string();
        let Some(d) = err.diagnostic() else {
            panic!("not a diagnostic: {shown}")
        };
        assert_eq!(
            (d.kind, d.line, d.field.as_str()),
            (DiagnosticKind::Rule, Some(line), field),
            "{shown}"
        );
        for n in names {
            assert!(
                d.message.contains(&format!("`{n}`")),
                "should name `{n}`: {shown}"
            );
        }
        assert!(shown.contains(&format!("t.toml:{line}:")), "{shown}");
        // The serde path refuses it too.
        assert!(toml::from_str::<Scenario>(text).is_err());
    }

    #[test]
    fn the_base_scenarios_load_without_warnings() {
        assert!(warnings(ANTS).is_empty());
        assert!(warnings(BEES).is_empty());
    }

    #[test]
    fn every_builtin_loads_without_warnings() {
        for b in BUILTINS {
            let (_, w) = resolve_with_warnings(b.name).unwrap_or_else(|e| panic!("{e}"));
            assert!(w.is_empty(), "{}: {:?}", b.name, w);
        }
    }

    #[test]
    fn food_inside_an_obstacle_is_refused_naming_both() {
        // Inside the rock.
        let t = edit(ANTS, "center = [180, 50]", "center = [62, 52]");
        refused(
            &t,
            line_of(&t, "center = [62, 52]"),
            "objects[1].center",
            &["food", "boulder"],
        );
        // Inside a leg of the concave polygon.
        let t = edit(ANTS, "center = [180, 50]", "center = [105, 15]");
        refused(
            &t,
            line_of(&t, "center = [105, 15]"),
            "objects[1].center",
            &["food", "u"],
        );
        // In the notch of the U: outside the polygon, fine.
        let t = edit(ANTS, "center = [180, 50]", "center = [115, 20]");
        assert!(warnings(&t).is_empty());
        // Across the rock's rim: a warning, not an error.
        let t = edit(ANTS, "center = [180, 50]", "center = [70, 50]");
        let w = warnings(&t);
        assert_eq!(w.len(), 1, "{w:?}");
        assert_eq!(w[0].kind, WarningKind::FoodOverlapsObstacle);
        assert_eq!(w[0].diagnostic.field, "objects[1].center");
        assert_eq!(w[0].diagnostic.line, Some(line_of(&t, "center = [70, 50]")));
        assert!(
            w[0].to_string().contains("warning in `objects[1].center`"),
            "{}",
            w[0]
        );
    }

    #[test]
    fn a_way_point_inside_an_obstacle_is_refused() {
        let t = format!(
            "{ANTS}\n[[objects]]\nname = \"wp\"\nkind = \"waypoint\"\ncenter = [60, 48]\nradius = 2\norder = 1\n"
        );
        refused(
            &t,
            line_of(&t, "center = [60, 48]"),
            "objects[4].center",
            &["wp", "boulder"],
        );
    }

    #[test]
    fn a_nest_in_or_on_an_obstacle_is_a_warning() {
        let t = edit(ANTS, "center = [20, 50]", "center = [60, 50]");
        let w = warnings(&t);
        assert!(
            w.iter().any(|w| w.kind == WarningKind::NestInObstacle
                && w.diagnostic.message.contains("entirely inside")
                && w.diagnostic.message.contains("`boulder`")),
            "{w:?}"
        );
        // Its ants spawn inside the rock too.
        assert!(
            w.iter().any(|w| w.kind == WarningKind::SpawnInObstacle
                && w.diagnostic.field == "groups[0].spawn"
                && w.diagnostic.message.contains("the whole spawn region")),
            "{w:?}"
        );
        let t = edit(ANTS, "center = [20, 50]", "center = [48, 50]");
        let w = warnings(&t);
        assert!(
            w.iter().any(|w| w.kind == WarningKind::NestInObstacle
                && w.diagnostic.message.contains("overlaps")),
            "{w:?}"
        );
    }

    #[test]
    fn a_spawn_region_partly_inside_obstacles_is_a_warning() {
        let t = edit(
            ANTS,
            "spawn = { at = \"nest\", radius = 4 }",
            "spawn = { min = [40, 40], max = [60, 60] }",
        );
        let w = warnings(&t);
        assert_eq!(w.len(), 1, "{w:?}");
        let d = &w[0].diagnostic;
        assert_eq!(
            (w[0].kind, d.field.as_str()),
            (WarningKind::SpawnInObstacle, "groups[0].spawn")
        );
        // Half the rock's disc in a 20 x 20 box: π·100/2 / 400 ≈ 39 %.
        assert!(
            d.message.contains("about 39 %") && d.message.contains("`boulder`"),
            "{}",
            w[0]
        );
        assert_eq!(d.line, Some(line_of(&t, "spawn = { min")));
    }

    #[test]
    fn a_nest_covering_food_is_a_warning() {
        let t = edit(ANTS, "center = [180, 50]", "center = [22, 50]");
        let w = warnings(&t);
        assert_eq!(w.len(), 1, "{w:?}");
        assert_eq!(w[0].kind, WarningKind::NestCoversFood);
        assert!(w[0].diagnostic.message.contains("`nest`"), "{}", w[0]);
    }

    #[test]
    fn events_are_checked() {
        // Moving the food into the rock is refused at the event.
        let t = format!(
            "{ANTS}\n[[events]]\nstep = 50\nmove = {{ object = \"food\", to = [60, 50] }}\n"
        );
        refused(
            &t,
            line_of(&t, "to = [60, 50]"),
            "events[0].move.to",
            &["food", "boulder"],
        );
        // Moving the nest onto the food is a warning.
        let t = format!(
            "{ANTS}\n[[events]]\nstep = 50\nmove = {{ object = \"nest\", to = [180, 52] }}\n"
        );
        let w = warnings(&t);
        assert!(
            w.iter().any(|w| w.kind == WarningKind::NestCoversFood
                && w.diagnostic.field == "events[0].move.to"
                && w.diagnostic.message.contains("step 50")),
            "{w:?}"
        );
        // A rock dropped over the food later is a warning (a blocked source is an experiment);
        // an inactive rock over the food at the start is not checked until it appears.
        let t = format!(
            "{ANTS}\n[[objects]]\nname = \"lid\"\nkind = \"rock\"\ncenter = [180, 50]\nradius = 5\nactive = false\n\n[[events]]\nstep = 40\nadd = \"lid\"\n\n[[events]]\nstep = 60\nremove = \"lid\"\n"
        );
        let w = warnings(&t);
        assert_eq!(w.len(), 1, "{w:?}");
        assert_eq!(w[0].kind, WarningKind::EventCoversFood);
        assert_eq!(w[0].diagnostic.field, "events[0].add");
        assert_eq!(w[0].diagnostic.line, Some(line_of(&t, "add = \"lid\"")));
        // Food added into a rock that is present is refused.
        let t = format!(
            "{ANTS}\n[[objects]]\nname = \"late\"\nkind = \"food\"\ncenter = [58, 50]\nradius = 2\nactive = false\n\n[[events]]\nstep = 40\nadd = \"late\"\n"
        );
        refused(
            &t,
            line_of(&t, "add = \"late\""),
            "events[0].add",
            &["late", "boulder"],
        );
        // Once `--steps` drops an event, its warnings no longer apply.
        let mut sc = Scenario::from_str(&format!(
            "{ANTS}\n[[objects]]\nname = \"lid\"\nkind = \"rock\"\ncenter = [180, 50]\nradius = 5\nactive = false\n\n[[events]]\nstep = 40\nadd = \"lid\"\n"
        ), "t.toml").unwrap();
        let w = sc.warnings();
        assert_eq!(w.len(), 1);
        assert_eq!(
            (w[0].diagnostic.line, w[0].diagnostic.file.as_str()),
            (None, "t")
        );
        assert!(w[0].applies_to(&sc));
        sc.set_steps(30);
        assert!(!w[0].applies_to(&sc));
        assert!(sc.warnings().is_empty());
    }

    #[test]
    fn bee_targets_inside_obstacles_are_refused() {
        let t = edit(BEES, "center = [40, 15, 40]", "center = [30, 15, 30]");
        refused(
            &t,
            line_of(&t, "center = [30, 15, 30]"),
            "objects[0].center",
            &["flower", "pole"],
        );
        let t = edit(BEES, "center = [40, 15, 40]", "center = [40, 0.5, 40]\n#");
        // Half sunk in the ground: reachable from above, no error.
        assert!(Scenario::from_str(&t, "t.toml").is_ok());
        let t = edit(BEES, "radius = 2\n", "radius = 0.4\n");
        let t = edit(&t, "center = [40, 15, 40]", "center = [40, 0.5, 40]");
        refused(
            &t,
            line_of(&t, "center = [40, 0.5, 40]"),
            "objects[0].center",
            &["flower", "ground"],
        );
        let t = format!(
            "{BEES}\n[[events]]\nstep = 10\nmove = {{ object = \"flower\", to = [30, 20, 30] }}\n"
        );
        refused(
            &t,
            line_of(&t, "to = [30, 20, 30]"),
            "events[0].move.to",
            &["flower", "pole"],
        );
        // A spawn box in the ground.
        let t = edit(
            BEES,
            "spawn = { min = [2, 5, 2], max = [10, 15, 10] }",
            "spawn = { min = [2, 0, 2], max = [10, 2, 10] }",
        );
        let w = warnings(&t);
        assert_eq!(w.len(), 1, "{w:?}");
        assert_eq!(w[0].kind, WarningKind::SpawnInObstacle);
        assert!(w[0].diagnostic.message.contains("about 50 %"), "{}", w[0]);
    }

    #[test]
    fn validate_refuses_what_code_changed() {
        let mut sc = Scenario::from_str(ANTS, "t.toml").unwrap();
        sc.objects[1].kind.set_center(&[60.0, 50.0]);
        let err = sc.validate().unwrap_err();
        assert!(
            matches!(&err, ScenarioError::Invalid(d) if d.field == "objects[1].center"),
            "{err}"
        );
    }
}
