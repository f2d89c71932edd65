//! The serde shapes of the scenario file: plain data, read and written by serde, checked by
//! nothing here (`build.rs` converts them into the typed scenario).
//!
//! The file's tagged forms (`dim`, `kind`, the two spawn forms, the event verbs) are read into
//! flat structs of options, so that serde reports unknown fields and wrong types at the exact
//! key; the conversion reports a field that does not fit its form by name.

use serde::{Deserialize, Serialize};

use super::params::{AntParamsOverride, BeeParamsOverride};
use super::types::{Model, Outputs, ScalarType};

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

/// `[world]`.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawWorld {
    pub dim: u8,
    pub min: Vec<f32>,
    pub max: Vec<f32>,
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
