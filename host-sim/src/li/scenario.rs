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

use super::data::{GridShape, fixture_tables, gaussian_weights, sketch_points, sketch_sigma};
use super::model::LiModel;
#[cfg(doc)]
use super::model::ModelGrid;
use crate::scenario::{Group, GroupCheck, ParamsOverride, Problem, Scenario, read_table};
use crate::space::{BeeObstacle, Shape3};
use crate::{Result, SimError};

/// The visiting-frequency grid of a group (§4.3): cells over the world's box, weighted by
/// Gaussian bumps at `points` and along the `sketch` (spec §2.6), obstacle cells 0; neither
/// given, every free cell alike.
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
                let overrides = read_table(map, &["density", "model"], |key, map: &mut A| {
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
            let sigma = d.sigma().unwrap_or(1.0);
            let mut points = d.points.clone();
            points.extend(sketch_points(&d.sketch, 0.5 * sigma));
            let weights = gaussian_weights(&shape, &points, sigma, &obstacles(scenario));
            shape.with(&weights)?
        }
    };
    let (lengths, turns) = match &model {
        Some((m, _)) => (m.lengths.table()?, m.turns.table()?),
        None => fixture_tables(),
    };
    Ok(table.overrides.apply(LiParams {
        lengths,
        turns,
        density,
        ..LiParams::default()
    }))
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
        let err = toml::from_str::<LiTable>("model = 3").unwrap_err();
        assert!(err.message().contains("invalid type"), "{err}");
    }
}
