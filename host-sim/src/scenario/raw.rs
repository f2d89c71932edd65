//! The serde shapes of the scenario file, and their conversion into the typed model.
//!
//! The file's tagged forms (`dim`, `kind`, the two spawn forms, the event verbs) are read into
//! flat structs of options first, so that serde reports unknown fields and wrong types at the
//! exact key, and the conversion here reports a field that does not fit its form by name (a
//! path relative to the converted value, prefixed by the caller).

use serde::{Deserialize, Serialize};

use super::problem::Problem;
use super::types::{
    Action, AntParamsOverride, BeeParamsOverride, Event, Group, Model, Object, ObjectKind, Outputs,
    ScalarType, Scenario, Spawn, SpawnRegion, World,
};

/// The whole file.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawScenario {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    #[serde(default)]
    pub description: String,
    #[serde(default)]
    pub seed: u32,
    pub steps: u32,
    pub world: RawWorld,
    #[serde(default)]
    pub groups: Vec<RawGroup>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub objects: Vec<RawObject>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub events: Vec<RawEvent>,
    #[serde(default)]
    pub outputs: Outputs,
}

impl RawScenario {
    /// The typed scenario (not yet validated); `default_name` when the file has no `name`.
    pub(crate) fn convert(self, default_name: &str) -> Result<Scenario, Problem> {
        let world = self.world.convert().map_err(|p| p.under("world"))?;
        let groups = self
            .groups
            .into_iter()
            .enumerate()
            .map(|(i, g)| g.convert().map_err(|p| p.under(&format!("groups[{i}]"))))
            .collect::<Result<_, _>>()?;
        let objects = self
            .objects
            .into_iter()
            .enumerate()
            .map(|(i, o)| o.convert().map_err(|p| p.under(&format!("objects[{i}]"))))
            .collect::<Result<_, _>>()?;
        let events = self
            .events
            .into_iter()
            .enumerate()
            .map(|(i, e)| e.convert().map_err(|p| p.under(&format!("events[{i}]"))))
            .collect::<Result<_, _>>()?;
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
            source: None,
        })
    }
}

impl TryFrom<RawScenario> for Scenario {
    type Error = Problem;

    /// Converts and validates (the serde path; file loading goes through `load.rs`, which
    /// adds the line numbers).
    fn try_from(raw: RawScenario) -> Result<Self, Problem> {
        let scenario = raw.convert("scenario")?;
        super::rules::validate(&scenario)?;
        Ok(scenario)
    }
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
        }
    }
}

/// `[world]`.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawWorld {
    pub dim: u8,
    pub min: Vec<f32>,
    pub max: Vec<f32>,
}

impl RawWorld {
    fn convert(self) -> Result<World, Problem> {
        match self.dim {
            2 => Ok(World::Ants2D {
                min: array(&self.min, "min", "[x, y] (a 2D world)")?,
                max: array(&self.max, "max", "[x, y] (a 2D world)")?,
            }),
            3 => Ok(World::Bees3D {
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

impl TryFrom<RawWorld> for World {
    type Error = Problem;
    fn try_from(raw: RawWorld) -> Result<Self, Problem> {
        raw.convert()
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

/// `[[groups]]`.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawGroup {
    pub name: String,
    pub model: Model,
    pub count: u32,
    #[serde(default)]
    pub scalar: ScalarType,
    pub spawn: RawSpawn,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub nest: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub goal: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ant: Option<AntParamsOverride>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bee: Option<BeeParamsOverride>,
}

impl RawGroup {
    fn convert(self) -> Result<Group, Problem> {
        Ok(Group {
            name: self.name,
            model: self.model,
            count: self.count,
            scalar: self.scalar,
            spawn: self.spawn.convert().map_err(|p| p.under("spawn"))?,
            nest: self.nest,
            goal: self.goal,
            ant: self.ant,
            bee: self.bee,
        })
    }
}

impl TryFrom<RawGroup> for Group {
    type Error = Problem;
    fn try_from(raw: RawGroup) -> Result<Self, Problem> {
        raw.convert()
    }
}

impl From<Group> for RawGroup {
    fn from(g: Group) -> Self {
        RawGroup {
            name: g.name,
            model: g.model,
            count: g.count,
            scalar: g.scalar,
            spawn: g.spawn.into(),
            nest: g.nest,
            goal: g.goal,
            ant: g.ant,
            bee: g.bee,
        }
    }
}

/// `spawn = { at = "nest", radius = 10 }` or `spawn = { min = [..], max = [..] }`, either with
/// an optional `heading`.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawSpawn {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub at: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius: Option<f32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min: Option<Vec<f32>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max: Option<Vec<f32>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub heading: Option<Vec<f32>>,
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

impl TryFrom<RawSpawn> for Spawn {
    type Error = Problem;
    fn try_from(raw: RawSpawn) -> Result<Self, Problem> {
        raw.convert()
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

/// The `kind` of an object.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub(crate) enum KindTag {
    Nest,
    Food,
    Rock,
    Polygon,
    Disturbance,
    Waypoint,
    Sphere,
    Box,
    Shaft,
    Target,
}

/// `[[objects]]`: every geometry field of every kind, optional; the conversion checks that
/// exactly the fields of the object's `kind` are there.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawObject {
    pub name: String,
    pub kind: KindTag,
    #[serde(default = "yes", skip_serializing_if = "is_true")]
    pub active: bool,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub center: Option<Vec<f32>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius: Option<f32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub amount: Option<u32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub order: Option<u32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub particles: Option<u32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min: Option<Vec<f32>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max: Option<Vec<f32>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub y_min: Option<f32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub y_max: Option<f32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub points: Option<Vec<[f32; 2]>>,
}

fn yes() -> bool {
    true
}

fn is_true(b: &bool) -> bool {
    *b
}

impl RawObject {
    fn convert(self) -> Result<Object, Problem> {
        use KindTag as K;
        let tag = self.kind;
        let (fields, required): (&[&str], &[&str]) = match tag {
            K::Nest | K::Rock | K::Disturbance | K::Sphere => {
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
            K::Box => (&["min", "max"], &["min", "max"]),
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
    }
}

impl TryFrom<RawObject> for Object {
    type Error = Problem;
    fn try_from(raw: RawObject) -> Result<Self, Problem> {
        raw.convert()
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
        };
        raw
    }
}

/// `[[events]]`: a step and exactly one action.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawEvent {
    pub step: u32,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub add: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub remove: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub start: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stop: Option<String>,
    #[serde(default, rename = "move", skip_serializing_if = "Option::is_none")]
    pub move_: Option<RawMove>,
}

/// `move = { object = "name", to = [..] }`.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawMove {
    pub object: String,
    pub to: Vec<f32>,
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

impl TryFrom<RawEvent> for Event {
    type Error = Problem;
    fn try_from(raw: RawEvent) -> Result<Self, Problem> {
        raw.convert()
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
