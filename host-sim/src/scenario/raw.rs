//! The serde shapes of the scenario file: plain data, read and written by serde, checked by
//! nothing here (`build.rs` converts them into the typed scenario).
//!
//! The file's tagged forms (`dim`, `kind`, the two spawn forms, the event verbs) are read into
//! flat structs of options, so that serde reports unknown fields and wrong types at the exact
//! key; the conversion reports a field that does not fit its form by name.

use std::fmt;

use serde::de::{self, MapAccess, Visitor};
use serde::ser::SerializeMap;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use super::types::{Backend, Model, Outputs, ScalarType};

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
    #[serde(default, skip_serializing_if = "Backend::is_default")]
    pub backend: Backend,
}

/// `[world]`.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawWorld {
    pub dim: u8,
    pub min: Vec<f32>,
    pub max: Vec<f32>,
}

/// `[[groups]]`: the fixed fields, and every other key with its value in `other` (a group's
/// parameter table is under its model's name, which serde cannot know: the conversion keeps
/// the model's and refuses the rest by name).
#[derive(Clone, Debug)]
pub(crate) struct RawGroup {
    pub name: String,
    pub model: Model,
    pub count: u32,
    pub scalar: ScalarType,
    pub spawn: RawSpawn,
    pub nest: Option<String>,
    pub goal: Option<String>,
    pub threat: Option<String>,
    pub other: Vec<(String, toml::Value)>,
}

/// The fixed keys of a group, in the order they are written.
pub(crate) const GROUP_FIELDS: &[&str] = &[
    "name", "model", "count", "scalar", "spawn", "nest", "goal", "threat",
];

impl Serialize for RawGroup {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(None)?;
        map.serialize_entry("name", &self.name)?;
        map.serialize_entry("model", &self.model)?;
        map.serialize_entry("count", &self.count)?;
        map.serialize_entry("scalar", &self.scalar)?;
        map.serialize_entry("spawn", &self.spawn)?;
        for (key, value) in [
            ("nest", &self.nest),
            ("goal", &self.goal),
            ("threat", &self.threat),
        ] {
            if let Some(v) = value {
                map.serialize_entry(key, v)?;
            }
        }
        for (key, value) in &self.other {
            map.serialize_entry(key, value)?;
        }
        map.end()
    }
}

impl<'de> Deserialize<'de> for RawGroup {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Fields;

        impl<'de> Visitor<'de> for Fields {
            type Value = RawGroup;

            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("struct RawGroup")
            }

            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<RawGroup, A::Error> {
                let (mut name, mut model, mut count, mut scalar, mut spawn) =
                    (None, None, None, None, None);
                let (mut nest, mut goal, mut threat, mut other) = (None, None, None, Vec::new());
                while let Some(key) = map.next_key::<String>()? {
                    match key.as_str() {
                        "name" => name = Some(map.next_value()?),
                        "model" => model = Some(map.next_value()?),
                        "count" => count = Some(map.next_value()?),
                        "scalar" => scalar = Some(map.next_value()?),
                        "spawn" => spawn = Some(map.next_value()?),
                        "nest" => nest = Some(map.next_value()?),
                        "goal" => goal = Some(map.next_value()?),
                        "threat" => threat = Some(map.next_value()?),
                        _ => {
                            let value = map.next_value()?;
                            other.push((key, value));
                        }
                    }
                }
                Ok(RawGroup {
                    name: name.ok_or_else(|| de::Error::missing_field("name"))?,
                    model: model.ok_or_else(|| de::Error::missing_field("model"))?,
                    count: count.ok_or_else(|| de::Error::missing_field("count"))?,
                    scalar: scalar.unwrap_or_default(),
                    spawn: spawn.ok_or_else(|| de::Error::missing_field("spawn"))?,
                    nest,
                    goal,
                    threat,
                    other,
                })
            }
        }

        deserializer.deserialize_map(Fields)
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
    Zone,
    Region,
    Cave,
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
