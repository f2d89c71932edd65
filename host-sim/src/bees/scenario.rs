//! What a bee group of a scenario is: its parameter table (`bee = { preset = "grassland",
//! kappa2 = 4 }`, a column of chen's Table I and overrides) and the rules of the bee model (an
//! optional goal target, no ant fields, parameters the controller accepts).

use serde::{Deserialize, Serialize};
use swarm_core::Fx;
use swarm_core::bee::BeeParams;

use crate::Result;
use crate::scenario::{Group, GroupCheck, Preset, PresetOverride, Problem};

/// `[groups.bee]`: a Table I preset, and any of the `BeeParams` parameters (chen) on top of
/// it.
pub type BeeParamsOverride = PresetOverride<BeeParams<f32>, BeePreset>;

/// A column of chen's Table I.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BeePreset {
    /// `"optimized"`: `BeeParams::default()` (h 3, L 2.7, κ 1.4/2.3/1.2, ε 1.7).
    #[default]
    Optimized,
    /// `"grassland"`: `BeeParams::grassland()` (L 2.2, κ 1.5/5/0.9, ε 2).
    Grassland,
    /// `"around_nest"`: `BeeParams::around_nest()` (L 2.2, κ 1/2.5/1.7, ε 2).
    AroundNest,
}

impl Preset<BeeParams<f32>> for BeePreset {
    fn params(&self) -> BeeParams<f32> {
        match self {
            BeePreset::Optimized => BeeParams::default(),
            BeePreset::Grassland => BeeParams::grassland(),
            BeePreset::AroundNest => BeeParams::around_nest(),
        }
    }
}

/// The bee parameters of group `g`: the preset (default `optimized`) with its overrides
/// applied.
///
/// # Errors
///
/// [`SimError::ParamsTable`](crate::SimError::ParamsTable) for a table that is not bee
/// parameters (never for a loaded scenario).
pub fn bee_params(g: &Group) -> Result<BeeParams<f32>> {
    Ok(g.params_as::<BeeParamsOverride>()?.params())
}

/// The rules of a bee group: no ant `nest`, a `goal` (if any) that is a `target`, and
/// parameters the controller accepts (in fixed point too for a fixed group).
pub(crate) fn check(c: &GroupCheck<'_>) -> std::result::Result<(), Problem> {
    let g = c.group;
    c.no_threat()?;
    c.not_given(
        "nest",
        g.nest.is_some(),
        "`nest` is for ant groups; bees fly toward a `goal` (an object of kind `target`)",
    )?;
    if let Some(goal) = &g.goal {
        c.object_of_kind("goal", goal, "target")?;
    }
    let params = c.params::<BeeParamsOverride>()?.params();
    c.check_params(&params, |p| p.cast::<Fx>().validate())?;
    // The neighbour range is h + 2r (the capsule gap below h).
    c.fixed_range(
        "h",
        "the neighbour range h + 2·radius",
        params.h + 2.0 * params.radius,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_bee_preset_is_an_extra_key() {
        let b: BeeParamsOverride = toml::from_str("kappa2 = 4\npreset = \"grassland\"").unwrap();
        assert_eq!(b.preset, Some(BeePreset::Grassland));
        assert_eq!(b.params().kappa2, 4.0);
        assert_eq!(
            toml::to_string(&b).unwrap(),
            "preset = \"grassland\"\nkappa2 = 4.0\n"
        );
        let err = toml::from_str::<BeeParamsOverride>("kapa2 = 4").unwrap_err();
        assert!(
            err.message()
                .starts_with("unknown field `kapa2`, expected one of `preset`, `h`, "),
            "{err}"
        );
    }
}
