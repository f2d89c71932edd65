//! What a li2015 group of a scenario is: its parameter table (`li = { sampling = 1, density =
//! { points = [[0.455, 0.455, 0.455]], sigma = 0.12 } }`: any [`LiParams`] parameter, the
//! visiting-frequency grid over the world, and a model file), and the rules of the model (no
//! `nest`, `goal` or `threat`: the density is where the swarm goes).
//!
//! The segment-length and turning-angle tables come from the group's model file (`li = {
//! model = "data/li-synthetic/model.toml" }`, written by `swarm li fit`: [`LiModel`]), else
//! they are the synthetic process's (spec §2.1, [`fixture_tables`]). The density is the
//! group's `density` when it gives one; else the model file's grid, used as it is (same
//! origin, cells and weights, a free cell at least 1: [`ModelGrid::placed`]) when it lies
//! inside the world, refused before the run when it does not ([`SimError::LiModelOutside`]);
//! without either, every free cell alike. Obstacle cells are 0 in every case.
//!
//! A model path is relative to the folder of the scenario file that names it (to the current
//! folder for a scenario without a file).

use std::fmt;
use std::marker::PhantomData;

use std::path::{Path, PathBuf};

use serde::de::{self, Deserializer, MapAccess, Visitor};
use serde::ser::{SerializeMap, Serializer};
use serde::{Deserialize, Serialize};
use swarm_core::Fx;
use swarm_core::li::LiParams;

use super::data::{
    GridShape, fixture_tables, gaussian_weights, light_weights, sketch_points, sketch_sigma,
};
use super::model::LiModel;
#[cfg(doc)]
use super::model::ModelGrid;
use crate::scenario::{Group, GroupCheck, ParamsOverride, Problem, Scenario, read_table};
use crate::space::{BeeObstacle, Shape3};
use crate::{Result, SimError};

/// The visiting-frequency grid of a group (§4.3): cells over the world's box, weighted by
/// Gaussian bumps at `points` and along the `sketch` (spec §2.6), or drawn to the lights of a
/// `route` in turn (Fig. 6), obstacle cells 0; none given, every free cell alike.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DensitySpec {
    /// Cells along the world's longest side (16: 16³ = 4 KiB in a cube).
    #[serde(default = "default_cells")]
    pub cells: u16,
    /// Centres of Gaussian bumps `[x, y, z]`.
    #[serde(default)]
    pub points: Vec<[f32; 3]>,
    /// A polyline `[[x, y, z], ...]` whose Gaussian the swarm follows (Fig. 5's sketches),
    /// sampled every σ/2.
    #[serde(default)]
    pub sketch: Vec<[f32; 3]>,
    /// The bumps' σ (units); default 0.1 × the sketch's bounding-box diagonal; required for
    /// points without a sketch.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sigma: Option<f32>,
    /// Lights the swarm visits in turn (Fig. 6), in place of points and a sketch.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub route: Option<Route>,
}

/// `route = { lights = [[x, y, z], ...] }`: the swarm is drawn to each light in turn (li2015
/// Fig. 6, spec §2.6, ours): the density is w_c = exp(−C_j(c)/λ) for the current light j
/// ([`light_weights`]), and the group moves on to the next light once the share of its
/// insects within `reach` of light j is `share` × the share of the density there (ours: the
/// density, one byte a cell with every free cell at least 1, holds only 40-70 % of itself
/// within 3 m of a light, so the spec's 80 % of the swarm could never be met).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Route {
    /// The lights, in the order they are visited.
    pub lights: Vec<[f32; 3]>,
    /// λ: the length over which the density falls by e along the path (units; the spec's 2).
    /// Beyond λ·ln 255 of the light (11 m at 2) the density is its floor of 1 and
    /// Metropolis-Hastings no longer drifts toward the light.
    #[serde(default = "default_lambda")]
    pub lambda: f32,
    /// The distance from a light within which an insect has reached it (units; 3).
    #[serde(default = "default_reach")]
    pub reach: f32,
    /// The share of the density's own share within `reach` that the group must have there
    /// before the next light is lit (0.8).
    #[serde(default = "default_share")]
    pub share: f32,
}

fn default_lambda() -> f32 {
    2.0
}
fn default_reach() -> f32 {
    3.0
}
fn default_share() -> f32 {
    0.8
}

fn default_cells() -> u16 {
    16
}

impl Default for DensitySpec {
    fn default() -> Self {
        DensitySpec {
            cells: default_cells(),
            points: Vec::new(),
            sketch: Vec::new(),
            sigma: None,
            route: None,
        }
    }
}

impl DensitySpec {
    /// The σ of the bumps: given, or the sketch's default; `None` when points need one.
    pub fn sigma(&self) -> Option<f32> {
        self.sigma
            .or_else(|| (self.sketch.len() >= 2).then(|| sketch_sigma(&self.sketch)))
    }
}

/// `li = { .. }`: [`LiParams`] overrides, the group's [`DensitySpec`] and model file.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LiTable {
    /// The parameters set on top of the defaults.
    pub overrides: ParamsOverride<LiParams<f32>>,
    /// The density (default: uniform, 16 cells along the longest side).
    pub density: DensitySpec,
    /// Whether the table gives `density` (with a `model`, the model's grid is the density
    /// unless it does).
    pub density_given: bool,
    /// The model file (`swarm li fit`) whose tables (and grid) the group uses.
    pub model: Option<String>,
    /// The segment lengths of the tables × this (default 1): insects larger than the data's
    /// (butterflies flying the midges' paths, Fig. 5) fly the same shapes at their own scale.
    pub length_scale: Option<f32>,
}

impl Serialize for LiTable {
    fn serialize<S: Serializer>(&self, serializer: S) -> std::result::Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(None)?;
        self.overrides.write_entries(&mut map)?;
        if self.density_given || self.model.is_none() {
            map.serialize_entry("density", &self.density)?;
        }
        if let Some(m) = &self.model {
            map.serialize_entry("model", m)?;
        }
        if let Some(k) = self.length_scale {
            map.serialize_entry("length_scale", &k)?;
        }
        map.end()
    }
}

impl<'de> Deserialize<'de> for LiTable {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> std::result::Result<Self, D::Error> {
        struct Table(PhantomData<LiTable>);
        impl<'de> Visitor<'de> for Table {
            type Value = LiTable;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("struct LiParamsOverride")
            }
            fn visit_map<A: MapAccess<'de>>(
                self,
                map: A,
            ) -> std::result::Result<LiTable, A::Error> {
                let mut density = None;
                let mut model = None;
                let mut length_scale = None;
                let extras = &["density", "model", "length_scale"];
                let overrides = read_table(map, extras, |key, map: &mut A| {
                    if key == "length_scale" {
                        if length_scale.is_some() {
                            return Err(de::Error::duplicate_field("length_scale"));
                        }
                        length_scale = Some(map.next_value()?);
                        return Ok(());
                    }
                    if key == "model" {
                        if model.is_some() {
                            return Err(de::Error::duplicate_field("model"));
                        }
                        model = Some(map.next_value()?);
                        return Ok(());
                    }
                    if density.is_some() {
                        return Err(de::Error::duplicate_field("density"));
                    }
                    density = Some(map.next_value()?);
                    Ok(())
                })?;
                Ok(LiTable {
                    overrides,
                    density_given: density.is_some(),
                    density: density.unwrap_or_default(),
                    model,
                    length_scale,
                })
            }
        }
        deserializer.deserialize_map(Table(PhantomData))
    }
}

/// The active obstacles of `scenario` (what the density leaves empty).
fn obstacles(scenario: &Scenario) -> Vec<BeeObstacle> {
    scenario
        .objects
        .iter()
        .enumerate()
        .filter_map(|(id, o)| {
            Shape3::of(&o.kind).map(|s| BeeObstacle::new(id as u16, &o.name, s, o.active))
        })
        .collect()
}

/// The file `model` names in `scenario`: relative to the scenario file's folder (to the
/// current folder for a scenario without a file), or absolute.
pub fn model_path(scenario: &Scenario, model: &str) -> PathBuf {
    let model = Path::new(model);
    match scenario.source.as_deref().and_then(Path::parent) {
        Some(dir) if model.is_relative() => dir.join(model),
        _ => model.to_path_buf(),
    }
}

/// The li2015 parameters of group `g` of `scenario`: the defaults with its overrides, the
/// tables of its model file (else the fixture's), and its density over the world (its own
/// `density`, else the model file's grid, else uniform).
///
/// # Errors
///
/// [`SimError::ParamsTable`] for a table that is not li parameters, [`SimError::WrongWorld`]
/// for a 2D world, [`SimError::LiGrid`] for a grid a device cannot hold (never for a loaded
/// scenario); what [`LiModel::read`] refuses, and [`SimError::LiModelOutside`] for a model
/// grid outside the world.
pub fn li_params(scenario: &Scenario, g: &Group) -> Result<LiParams<f32>> {
    let table = g.params_as::<LiTable>()?;
    let (min, max) = scenario.bounds::<3>("li")?;
    let model = match &table.model {
        Some(m) => {
            let path = model_path(scenario, m);
            Some((LiModel::read(&path)?, path))
        }
        None => None,
    };
    let density = match &model {
        Some((m, path)) if !table.density_given => m
            .density
            .placed((min, max), &obstacles(scenario))
            .map_err(|(grid_min, grid_max)| SimError::LiModelOutside {
                path: path.clone(),
                grid_min,
                grid_max,
                world_min: min,
                world_max: max,
            })?,
        _ => {
            let d = &table.density;
            let shape = GridShape::over(min, max, d.cells)?;
            let weights = match d.route.as_ref().and_then(|r| Some((r, r.lights.first()?))) {
                Some((route, &first)) => {
                    light_weights(&shape, first, route.lambda, &obstacles(scenario))?
                }
                None => {
                    let sigma = d.sigma().unwrap_or(1.0);
                    let mut points = d.points.clone();
                    points.extend(sketch_points(&d.sketch, 0.5 * sigma));
                    gaussian_weights(&shape, &points, sigma, &obstacles(scenario))
                }
            };
            shape.with(&weights)?
        }
    };
    let (mut lengths, turns) = match &model {
        Some((m, _)) => (m.lengths.table()?, m.turns.table()?),
        None => fixture_tables(),
    };
    if let Some(k) = table.length_scale {
        lengths.lo *= k;
        lengths.hi *= k;
    }
    Ok(table.overrides.apply(LiParams {
        lengths,
        turns,
        density,
        ..LiParams::default()
    }))
}

/// A route, its group's density grid and the weights of each light, in order.
pub type RouteDensities = (Route, GridShape, Vec<Vec<u8>>);

/// The route of group `g`, its density grid's cells and the weights of each light, in order,
/// when it has one.
///
/// # Errors
///
/// As [`li_params`].
pub fn route_of(scenario: &Scenario, g: &Group) -> Result<Option<RouteDensities>> {
    let table = g.params_as::<LiTable>()?;
    let Some(route) = table.density.route else {
        return Ok(None);
    };
    let (min, max) = scenario.bounds::<3>("li")?;
    let shape = GridShape::over(min, max, table.density.cells)?;
    let walls = obstacles(scenario);
    let weights = route
        .lights
        .iter()
        .map(|&l| light_weights(&shape, l, route.lambda, &walls))
        .collect::<Result<Vec<_>>>()?;
    Ok(Some((route, shape, weights)))
}

/// The rules of a li2015 group: no `nest`, `goal` or `threat`; a density grid a device holds,
/// with a σ when it has points and some cell to go to; parameters the controller accepts (in
/// fixed point too for a fixed group).
pub(crate) fn check(c: &GroupCheck<'_>) -> std::result::Result<(), Problem> {
    let g = c.group;
    c.no_threat()?;
    for (field, given) in [("nest", g.nest.is_some()), ("goal", g.goal.is_some())] {
        c.not_given(
            field,
            given,
            "li2015 insects go where their density grid sends them (`li = { density = { .. } }`), \
             not to a goal or nest",
        )?;
    }
    let table = c.params::<LiTable>()?;
    let d = &table.density;
    let at = |f: &str| format!("li.density.{f}");
    if !d.points.is_empty() && d.sigma().is_none() {
        return Err(c.problem(
            &at("sigma"),
            "missing: Gaussian points need their width σ (units)",
        ));
    }
    if let Some(s) = d.sigma
        && !(s.is_finite() && s > 0.0)
    {
        return Err(c.problem(&at("sigma"), format!("{s} is not a positive width")));
    }
    if d.sketch.len() == 1 {
        return Err(c.problem(&at("sketch"), "a sketch needs at least two points"));
    }
    if let Some(r) = &d.route {
        route_rules(c, d, r)?;
    }
    if let Some(k) = table.length_scale
        && !(k.is_finite() && k > 0.0)
    {
        return Err(c.problem(
            "li.length_scale",
            format!("{k} is not a positive factor of the segment lengths"),
        ));
    }
    if let Some(m) = &table.model {
        if m.trim().is_empty() {
            return Err(c.problem(
                "li.model",
                "an empty path: name a model file (`swarm li fit`)",
            ));
        }
        LiModel::read(&model_path(c.scenario, m))
            .map_err(|e| c.problem("li.model", e.to_string()))?;
    }
    let params = li_params(c.scenario, g).map_err(|e| match e {
        SimError::LiModelOutside { .. } => c.problem("li.model", e.to_string()),
        _ => c.problem(&at("cells"), e.to_string()),
    })?;
    if params.density.weights.iter().all(|&w| w == 0) {
        return Err(c.problem(
            "li.density",
            "every cell is inside an obstacle: \
             the insects would have nowhere to go",
        ));
    }
    c.check_params(&params, |p| p.cast::<Fx>().validate())
}

/// A route's rules: no points or sketch beside it, at least one light, each inside the world
/// and outside the obstacles, positive λ and reach, a share in (0, 1].
fn route_rules(c: &GroupCheck<'_>, d: &DensitySpec, r: &Route) -> std::result::Result<(), Problem> {
    let at = |f: &str| format!("li.density.route.{f}");
    if !d.points.is_empty() || !d.sketch.is_empty() || d.sigma.is_some() {
        return Err(c.problem(
            "li.density.route",
            "a route is the density: give it without `points`, a `sketch` or `sigma`",
        ));
    }
    if r.lights.is_empty() {
        return Err(c.problem(&at("lights"), "a route needs at least one light"));
    }
    let (min, max) = c
        .scenario
        .bounds::<3>("li")
        .map_err(|e| c.problem(&at("lights"), e.to_string()))?;
    let walls = obstacles(c.scenario);
    for (i, l) in r.lights.iter().enumerate() {
        let inside = (0..3).all(|k| l[k].is_finite() && l[k] >= min[k] && l[k] <= max[k]);
        if !inside {
            return Err(c.problem(
                &format!("li.density.route.lights[{i}]"),
                format!("{l:?} is outside the world {min:?}-{max:?}"),
            ));
        }
        if let Some(o) = walls.iter().find(|o| o.active && o.shape.meets_box(*l, *l)) {
            return Err(c.problem(
                &format!("li.density.route.lights[{i}]"),
                format!("{l:?} is inside the obstacle `{}`", o.name),
            ));
        }
    }
    for (field, v) in [("lambda", r.lambda), ("reach", r.reach)] {
        if !(v.is_finite() && v > 0.0) {
            return Err(c.problem(&at(field), format!("{v} is not a positive length")));
        }
    }
    // A light's own cell must count as within reach (its centre is at most half a cell
    // diagonal away), or no share of the density would be there to reach.
    if let Ok(shape) = GridShape::over(min, max, d.cells) {
        let half_diagonal = 0.5 * 3f32.sqrt() * shape.cell;
        if r.reach < half_diagonal {
            return Err(c.problem(
                &at("reach"),
                format!(
                    "{} is less than half a density cell's diagonal ({half_diagonal}): \
                     use fewer cells or a longer reach",
                    r.reach
                ),
            ));
        }
    }
    if !(r.share > 0.0 && r.share <= 1.0) {
        return Err(c.problem(
            &at("share"),
            format!("{} is not a share in (0, 1]", r.share),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_li_table_reads_parameters_and_a_density() {
        let t: LiTable = toml::from_str(
            "sampling = 1\ndensity = { cells = 8, points = [[0.5, 0.5, 0.5]], sigma = 0.1 }",
        )
        .unwrap();
        assert_eq!(t.overrides.apply(LiParams::default()).sampling, 1);
        assert_eq!((t.density.cells, t.density.sigma()), (8, Some(0.1)));
        let err = toml::from_str::<LiTable>("samplin = 1").unwrap_err();
        assert!(
            err.message().starts_with("unknown field `samplin`"),
            "{err}"
        );
        let err = toml::from_str::<LiTable>("density = { cell = 8 }").unwrap_err();
        assert!(err.message().contains("unknown field `cell`"), "{err}");
        assert_eq!(LiTable::default().density.cells, 16);
        assert!(t.density_given && t.model.is_none());
        // Written and read back: the same table.
        let text = toml::to_string(&t).unwrap();
        assert_eq!(toml::from_str::<LiTable>(&text).unwrap(), t);
        // A model without a density, and with one: both written back as they were.
        for text in [
            "model = \"m.toml\"",
            "model = \"m.toml\"\ndensity = { cells = 4 }",
        ] {
            let t: LiTable = toml::from_str(text).unwrap();
            assert_eq!(t.model.as_deref(), Some("m.toml"));
            assert_eq!(t.density_given, text.contains("density"));
            let again = toml::to_string(&t).unwrap();
            assert_eq!(toml::from_str::<LiTable>(&again).unwrap(), t);
        }
        let t: LiTable = toml::from_str("length_scale = 40.0").unwrap();
        assert_eq!(t.length_scale, Some(40.0));
        let again: LiTable = toml::from_str(&toml::to_string(&t).unwrap()).unwrap();
        assert_eq!(again.length_scale, Some(40.0));
        let err = toml::from_str::<LiTable>("model = 3").unwrap_err();
        assert!(err.message().contains("invalid type"), "{err}");
    }
}
