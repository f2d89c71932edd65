//! From the raw serde shapes (`raw.rs`) to the typed, checked scenario (`types.rs`), and back.
//!
//! [`build`] is the one step from a file's shape to a [`Scenario`]: the conversion of each raw
//! value checks the fields that must fit its form (the fields of an object's `kind`, one of the
//! two spawn forms, one action per event; a problem's path is relative to the converted value
//! and prefixed by its parent), then the rules (`rules/`) check the whole typed scenario. The
//! typed values serialize through their raw shapes, and deserialize through the same
//! conversion (for a whole scenario, through [`build`]).

use serde::de::Error as _;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use super::diagnostic::DiagnosticKind;
use super::problem::Problem;
use super::raw::{
    GROUP_FIELDS, KindTag, RawEvent, RawGroup, RawMove, RawObject, RawScenario, RawSpawn, RawWorld,
};
use super::rules;
use super::sanity::Finding;
use super::types::{
    Action, Event, Group, Model, Object, ObjectKind, Scenario, Spawn, SpawnRegion, World,
};

/// The typed scenario of `raw` (named `default_name` when the file has no `name`, read from
/// the file `source` if any: the rules resolve the files it names from there), checked by
/// every rule, with its warnings; or the first problem and the stage that found it
/// ([`Shape`](DiagnosticKind::Shape): a field that does not fit its form;
/// [`Rule`](DiagnosticKind::Rule): a rule of the scenario).
pub(crate) fn build(
    raw: RawScenario,
    default_name: &str,
    source: Option<&std::path::Path>,
) -> Result<(Scenario, Vec<Finding>), (DiagnosticKind, Problem)> {
    let mut scenario = raw
        .convert(default_name)
        .map_err(|p| (DiagnosticKind::Shape, p))?;
    scenario.source = source.map(std::path::Path::to_path_buf);
    let findings = rules::validate(&scenario).map_err(|p| (DiagnosticKind::Rule, p))?;
    Ok((scenario, findings))
}

/// Serde for the typed values through their raw shapes: reading converts with `$convert`,
/// writing converts back (`From`).
macro_rules! serde_via_raw {
    ($($ty:ident => $raw:ident . $convert:ident,)*) => {$(
        impl Serialize for $ty {
            fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
                $raw::from(self.clone()).serialize(serializer)
            }
        }

        impl<'de> Deserialize<'de> for $ty {
            fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
                $raw::deserialize(deserializer)?
                    .$convert()
                    .map_err(D::Error::custom)
            }
        }
    )*};
}

serde_via_raw! {
    Scenario => RawScenario.checked,
    World => RawWorld.convert,
    Group => RawGroup.convert,
    Spawn => RawSpawn.convert,
    Object => RawObject.convert,
    Event => RawEvent.convert,
}

impl RawScenario {
    /// The typed scenario (not yet validated); `default_name` when the file has no `name`.
    fn convert(self, default_name: &str) -> Result<Scenario, Problem> {
        let world = self.world.convert().map_err(|p| p.under("world"))?;
        let groups = convert_each("groups", self.groups, RawGroup::convert)?;
        let objects = convert_each("objects", self.objects, RawObject::convert)?;
        let events = convert_each("events", self.events, RawEvent::convert)?;
        Ok(Scenario {
            name: self.name.unwrap_or_else(|| default_name.to_owned()),
            description: self.description,
            seed: self.seed,
            steps: self.steps,
            world,
            groups,
            objects,
            events,
            outputs: self.outputs,
            backend: self.backend,
            source: None,
        })
    }

    /// Converted and checked (the serde path: a scenario without a file, named `scenario`
    /// unless it says otherwise; file loading goes through `load.rs`, which adds the lines).
    fn checked(self) -> Result<Scenario, Problem> {
        build(self, "scenario", None)
            .map(|(s, _)| s)
            .map_err(|(_, p)| p)
    }
}

/// Every item of the array `list` converted; a problem's path starts with `list[i]`.
fn convert_each<R, T>(
    list: &str,
    items: Vec<R>,
    convert: impl Fn(R) -> Result<T, Problem>,
) -> Result<Vec<T>, Problem> {
    items
        .into_iter()
        .enumerate()
        .map(|(i, raw)| convert(raw).map_err(|p| p.under(&format!("{list}[{i}]"))))
        .collect()
}

impl From<Scenario> for RawScenario {
    fn from(s: Scenario) -> Self {
        RawScenario {
            name: Some(s.name),
            description: s.description,
            seed: s.seed,
            steps: s.steps,
            world: s.world.into(),
            groups: s.groups.into_iter().map(Into::into).collect(),
            objects: s.objects.into_iter().map(Into::into).collect(),
            events: s.events.into_iter().map(Into::into).collect(),
            outputs: s.outputs,
            backend: s.backend,
        }
    }
}

impl RawWorld {
    fn convert(self) -> Result<World, Problem> {
        match self.dim {
            2 => Ok(World::Plane {
                min: array(&self.min, "min", "[x, y] (a 2D world)")?,
                max: array(&self.max, "max", "[x, y] (a 2D world)")?,
            }),
            3 => Ok(World::Space {
                min: array(&self.min, "min", "[x, y, z] (a 3D world, y up)")?,
                max: array(&self.max, "max", "[x, y, z] (a 3D world, y up)")?,
            }),
            d => Err(Problem::new(
                "dim",
                format!("expected 2 (ants, [x, y]) or 3 (bees, [x, y, z]), found {d}"),
            )),
        }
    }
}

impl From<World> for RawWorld {
    fn from(w: World) -> Self {
        RawWorld {
            dim: if w.dim() == 2 { 2 } else { 3 },
            min: w.min().to_vec(),
            max: w.max().to_vec(),
        }
    }
}

/// `N` numbers from `v`, or a problem at `field` saying what `shape` was expected.
fn array<const N: usize>(v: &[f32], field: &str, shape: &str) -> Result<[f32; N], Problem> {
    <[f32; N]>::try_from(v).map_err(|_| {
        Problem::new(
            field,
            format!("expected {N} numbers {shape}, found {}", v.len()),
        )
    })
}

impl RawGroup {
    fn convert(self) -> Result<Group, Problem> {
        let mut params = None;
        // A model the rules will not know: they say so at `model`, before anything else.
        let known = crate::models::find(self.model.as_str()).is_some();
        for (key, value) in self.other {
            if known && key != self.model.as_str() {
                return Err(not_a_group_field(&key, &self.model));
            }
            match value {
                toml::Value::Table(t) => params = Some(t),
                v => {
                    return Err(Problem::new(
                        key,
                        format!(
                            "expected a table of `{}` parameters, e.g. `{} = {{ .. }}`, found {}",
                            self.model,
                            self.model,
                            v.type_str()
                        ),
                    ));
                }
            }
        }
        Ok(Group {
            name: self.name,
            model: self.model,
            count: self.count,
            scalar: self.scalar,
            spawn: self.spawn.convert().map_err(|p| p.under("spawn"))?,
            nest: self.nest,
            goal: self.goal,
            threat: self.threat,
            params,
        })
    }
}

/// The problem of key `key` in a group of `model`: another model's parameter table, or a key
/// groups do not have.
fn not_a_group_field(key: &str, model: &Model) -> Problem {
    let message = if crate::models::find(key).is_some() {
        format!(
            "{key} parameters in {} {model} group; this group's parameters go in \
             `[groups.{model}]`",
            article(model.as_str())
        )
    } else {
        let fields: Vec<String> = GROUP_FIELDS.iter().map(|f| format!("`{f}`")).collect();
        format!(
            "unknown field `{key}`, expected one of {}, or `{model}` (the model's parameters)",
            fields.join(", ")
        )
    };
    Problem::new(key, message)
}

/// `a` or `an` before `word`.
fn article(word: &str) -> &'static str {
    if word.starts_with(['a', 'e', 'i', 'o', 'u']) {
        "an"
    } else {
        "a"
    }
}

impl From<Group> for RawGroup {
    fn from(g: Group) -> Self {
        let other = g
            .params
            .map(|t| (g.model.to_string(), toml::Value::Table(t)))
            .into_iter()
            .collect();
        RawGroup {
            name: g.name,
            model: g.model,
            count: g.count,
            scalar: g.scalar,
            spawn: g.spawn.into(),
            nest: g.nest,
            goal: g.goal,
            threat: g.threat,
            other,
        }
    }
}

const SPAWN_FORMS: &str = "either `at` + `radius` (uniform around an object's centre) or `min` + \
                           `max` (uniform in a box)";

impl RawSpawn {
    fn convert(self) -> Result<Spawn, Problem> {
        let around = self.at.is_some() || self.radius.is_some();
        let boxed = self.min.is_some() || self.max.is_some();
        let region = match (around, boxed) {
            (true, true) => {
                let (field, other) = if self.min.is_some() {
                    ("min", if self.at.is_some() { "at" } else { "radius" })
                } else {
                    ("max", if self.at.is_some() { "at" } else { "radius" })
                };
                return Err(Problem::new(
                    field,
                    format!("`{field}` cannot be combined with `{other}`: give {SPAWN_FORMS}"),
                ));
            }
            (false, false) => {
                return Err(Problem::new(
                    "",
                    format!("no spawn region: expected {SPAWN_FORMS}"),
                ));
            }
            (true, false) => match (self.at, self.radius) {
                (Some(at), Some(radius)) => SpawnRegion::Around { at, radius },
                (None, _) => {
                    return Err(Problem::new(
                        "",
                        "missing field `at`: name the object to spawn around (or give `min` + \
                         `max` for a box)",
                    ));
                }
                (_, None) => {
                    return Err(Problem::new(
                        "",
                        "missing field `radius`: the radius of the disc (2D) or ball (3D) \
                         around `at`",
                    ));
                }
            },
            (false, true) => match (self.min, self.max) {
                (Some(min), Some(max)) => SpawnRegion::Box { min, max },
                (None, _) => {
                    return Err(Problem::new(
                        "",
                        "missing field `min`: a spawn box needs `min` and `max`",
                    ));
                }
                (_, None) => {
                    return Err(Problem::new(
                        "",
                        "missing field `max`: a spawn box needs `min` and `max`",
                    ));
                }
            },
        };
        Ok(Spawn {
            region,
            heading: self.heading,
        })
    }
}

impl From<Spawn> for RawSpawn {
    fn from(s: Spawn) -> Self {
        let (at, radius, min, max) = match s.region {
            SpawnRegion::Around { at, radius } => (Some(at), Some(radius), None, None),
            SpawnRegion::Box { min, max } => (None, None, Some(min), Some(max)),
        };
        RawSpawn {
            at,
            radius,
            min,
            max,
            heading: s.heading,
        }
    }
}

impl RawObject {
    fn convert(self) -> Result<Object, Problem> {
        use KindTag as K;
        let tag = self.kind;
        let (fields, required): (&[&str], &[&str]) = match tag {
            K::Nest | K::Rock | K::Disturbance | K::Sphere | K::Zone => {
                (&["center", "radius"], &["center", "radius"])
            }
            K::Food => (&["center", "radius", "amount"], &["center", "radius"]),
            K::Waypoint => (
                &["center", "radius", "order"],
                &["center", "radius", "order"],
            ),
            K::Target => (
                &["center", "radius", "particles"],
                &["center", "radius", "particles"],
            ),
            K::Polygon => (&["points"], &["points"]),
            K::Box | K::Region | K::Cave => (&["min", "max"], &["min", "max"]),
            K::Shaft => (
                &["center", "radius", "y_min", "y_max"],
                &["center", "radius", "y_min", "y_max"],
            ),
        };
        let kind_name = tag_name(tag);
        let present = [
            ("center", self.center.is_some()),
            ("radius", self.radius.is_some()),
            ("amount", self.amount.is_some()),
            ("order", self.order.is_some()),
            ("particles", self.particles.is_some()),
            ("min", self.min.is_some()),
            ("max", self.max.is_some()),
            ("y_min", self.y_min.is_some()),
            ("y_max", self.y_max.is_some()),
            ("points", self.points.is_some()),
        ];
        for (field, is_there) in present {
            if is_there && !fields.contains(&field) {
                return Err(Problem::new(
                    field,
                    format!(
                        "an object of kind `{kind_name}` has no field `{field}` (its fields: \
                         name, kind, active, {})",
                        fields.join(", ")
                    ),
                ));
            }
        }
        for field in required {
            if !present.iter().any(|(f, p)| f == field && *p) {
                return Err(Problem::new(
                    "",
                    format!(
                        "missing field `{field}`: an object of kind `{kind_name}` needs {}",
                        required.join(", ")
                    ),
                ));
            }
        }
        // Every required field is present from here on; the defaults below are never used.
        let center2 = || array::<2>(self.center.as_deref().unwrap_or(&[]), "center", "[x, y]");
        let center3 = || {
            array::<3>(
                self.center.as_deref().unwrap_or(&[]),
                "center",
                "[x, y, z] (y up)",
            )
        };
        let radius = self.radius.unwrap_or_default();
        let kind = match tag {
            K::Nest => ObjectKind::Nest {
                center: center2()?,
                radius,
            },
            K::Food => ObjectKind::Food {
                center: center2()?,
                radius,
                amount: self.amount,
            },
            K::Rock => ObjectKind::Rock {
                center: center2()?,
                radius,
            },
            K::Disturbance => ObjectKind::Disturbance {
                center: center2()?,
                radius,
            },
            K::Waypoint => ObjectKind::Waypoint {
                center: center2()?,
                radius,
                order: self.order.unwrap_or_default(),
            },
            K::Polygon => ObjectKind::Polygon {
                points: self.points.clone().unwrap_or_default(),
            },
            K::Sphere => ObjectKind::Sphere {
                center: center3()?,
                radius,
            },
            K::Target => ObjectKind::Target {
                center: center3()?,
                radius,
                particles: self.particles.unwrap_or_default(),
            },
            K::Box => ObjectKind::Box {
                min: array(self.min.as_deref().unwrap_or(&[]), "min", "[x, y, z]")?,
                max: array(self.max.as_deref().unwrap_or(&[]), "max", "[x, y, z]")?,
            },
            K::Zone => ObjectKind::Zone {
                center: center3()?,
                radius,
            },
            K::Region => ObjectKind::Region {
                min: array(self.min.as_deref().unwrap_or(&[]), "min", "[x, y, z]")?,
                max: array(self.max.as_deref().unwrap_or(&[]), "max", "[x, y, z]")?,
            },
            K::Cave => ObjectKind::Cave {
                min: array(self.min.as_deref().unwrap_or(&[]), "min", "[x, y, z]")?,
                max: array(self.max.as_deref().unwrap_or(&[]), "max", "[x, y, z]")?,
            },
            K::Shaft => ObjectKind::Shaft {
                center: array(
                    self.center.as_deref().unwrap_or(&[]),
                    "center",
                    "[x, z] (the position of the vertical axis; y is up)",
                )?,
                radius,
                y_min: self.y_min.unwrap_or_default(),
                y_max: self.y_max.unwrap_or_default(),
            },
        };
        Ok(Object {
            name: self.name,
            active: self.active,
            kind,
        })
    }
}

fn tag_name(tag: KindTag) -> &'static str {
    match tag {
        KindTag::Nest => "nest",
        KindTag::Food => "food",
        KindTag::Rock => "rock",
        KindTag::Polygon => "polygon",
        KindTag::Disturbance => "disturbance",
        KindTag::Waypoint => "waypoint",
        KindTag::Sphere => "sphere",
        KindTag::Box => "box",
        KindTag::Shaft => "shaft",
        KindTag::Target => "target",
        KindTag::Zone => "zone",
        KindTag::Region => "region",
        KindTag::Cave => "cave",
    }
}

impl From<Object> for RawObject {
    fn from(o: Object) -> Self {
        let mut raw = RawObject {
            name: o.name,
            kind: KindTag::Nest,
            active: o.active,
            center: o.kind.center().map(<[f32]>::to_vec),
            radius: o.kind.radius(),
            amount: None,
            order: None,
            particles: None,
            min: None,
            max: None,
            y_min: None,
            y_max: None,
            points: None,
        };
        raw.kind = match o.kind {
            ObjectKind::Nest { .. } => KindTag::Nest,
            ObjectKind::Food { amount, .. } => {
                raw.amount = amount;
                KindTag::Food
            }
            ObjectKind::Rock { .. } => KindTag::Rock,
            ObjectKind::Polygon { points } => {
                raw.points = Some(points);
                KindTag::Polygon
            }
            ObjectKind::Disturbance { .. } => KindTag::Disturbance,
            ObjectKind::Waypoint { order, .. } => {
                raw.order = Some(order);
                KindTag::Waypoint
            }
            ObjectKind::Sphere { .. } => KindTag::Sphere,
            ObjectKind::Box { min, max } => {
                raw.min = Some(min.to_vec());
                raw.max = Some(max.to_vec());
                KindTag::Box
            }
            ObjectKind::Shaft { y_min, y_max, .. } => {
                raw.y_min = Some(y_min);
                raw.y_max = Some(y_max);
                KindTag::Shaft
            }
            ObjectKind::Target { particles, .. } => {
                raw.particles = Some(particles);
                KindTag::Target
            }
            ObjectKind::Zone { .. } => KindTag::Zone,
            ObjectKind::Region { min, max } => {
                raw.min = Some(min.to_vec());
                raw.max = Some(max.to_vec());
                KindTag::Region
            }
            ObjectKind::Cave { min, max } => {
                raw.min = Some(min.to_vec());
                raw.max = Some(max.to_vec());
                KindTag::Cave
            }
        };
        raw
    }
}

impl RawEvent {
    fn convert(self) -> Result<Event, Problem> {
        let mut actions = Vec::new();
        if let Some(o) = self.add {
            actions.push(Action::Add(o));
        }
        if let Some(o) = self.remove {
            actions.push(Action::Remove(o));
        }
        if let Some(m) = self.move_ {
            actions.push(Action::Move {
                object: m.object,
                to: m.to,
            });
        }
        if let Some(o) = self.start {
            actions.push(Action::Start(o));
        }
        if let Some(o) = self.stop {
            actions.push(Action::Stop(o));
        }
        let mut actions = actions.into_iter();
        match (actions.next(), actions.next()) {
            (Some(action), None) => Ok(Event {
                step: self.step,
                action,
            }),
            (None, _) => Err(Problem::new(
                "",
                "an event needs one action: `add`, `remove`, `move`, `start` or `stop`",
            )),
            (Some(first), Some(second)) => Err(Problem::new(
                second.verb(),
                format!(
                    "an event has exactly one action, found both `{}` and `{}` (write one \
                     event for each)",
                    first.verb(),
                    second.verb()
                ),
            )),
        }
    }
}

impl From<Event> for RawEvent {
    fn from(e: Event) -> Self {
        let mut raw = RawEvent {
            step: e.step,
            add: None,
            remove: None,
            start: None,
            stop: None,
            move_: None,
        };
        match e.action {
            Action::Add(o) => raw.add = Some(o),
            Action::Remove(o) => raw.remove = Some(o),
            Action::Start(o) => raw.start = Some(o),
            Action::Stop(o) => raw.stop = Some(o),
            Action::Move { object, to } => raw.move_ = Some(RawMove { object, to }),
        }
        raw
    }
}
