//! What a ren2016 group of a scenario is: its parameter table (`fly = { preset = "mating",
//! chi_res = 12 }`, a column of ren2016's Table 1 and overrides) and the rules of the model (an
//! optional `goal` it pursues and `threat` it escapes, each an object with a centre; no ant
//! fields; parameters the controller accepts).

use serde::{Deserialize, Serialize};
use swarm_core::Fx;
use swarm_core::fly::FlyParams;

use crate::Result;
use crate::scenario::{Group, GroupCheck, Preset, PresetOverride, Problem};

/// `[groups.fly]`: a Table 1 preset, and any of the `FlyParams` parameters on top of it.
pub type FlyParamsOverride = PresetOverride<FlyParams<f32>, FlyPreset>;

/// A column of ren2016's Table 1 (spec §3.1, with our constants for what the paper leaves out:
/// Δt, the ORCA radius, τ and speed limit).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FlyPreset {
    /// `"midge"`: fitted to dataset 1 (γ 11.16, χ_rep 5.61, r_rep 0.17, χ_att 14.29).
    #[default]
    Midge,
    /// `"aggregation"`: the midge set with alignment (χ_ali 5, r_ali* 1).
    Aggregation,
    /// `"fruitfly"`: fitted to datasets 2-4 (γ 8.76, χ_rep 1.74, r_rep 1.48, χ_att 10.39).
    Fruitfly,
    /// `"mating"`: the fruit-fly set with alignment and pursuit (χ_res 10, r_res 2).
    Mating,
    /// `"escape"`: the fruit-fly set with alignment and escape (χ_res 20, r_res 8).
    Escape,
    /// `"bats"`: γ 10.21, χ_rep 8, r_rep 2, χ_ali 20, χ_att 25, χ_res 10, r_res 10.
    Bats,
    /// `"locust"`: γ 1.4, gain 0.36, pursuit of the crop (χ_res 60, r_res 25).
    Locust,
    /// `"phase"`: after the phase transition (gain 0.1, χ_ali 10).
    Phase,
    /// `"phototaxis"`: pursuit of the lamp holder (χ_res 1, r_res 5).
    Phototaxis,
}

impl Preset<FlyParams<f32>> for FlyPreset {
    fn params(&self) -> FlyParams<f32> {
        match self {
            FlyPreset::Midge => FlyParams::midge(),
            FlyPreset::Aggregation => FlyParams::aggregation(),
            FlyPreset::Fruitfly => FlyParams::fruitfly(),
            FlyPreset::Mating => FlyParams::mating(),
            FlyPreset::Escape => FlyParams::escape(),
            FlyPreset::Bats => FlyParams::bats(),
            FlyPreset::Locust => FlyParams::locust(),
            FlyPreset::Phase => FlyParams::phase(),
            FlyPreset::Phototaxis => FlyParams::phototaxis(),
        }
    }
}

/// The ren2016 parameters of group `g`: the preset (default `midge`) with its overrides
/// applied.
///
/// # Errors
///
/// [`SimError::ParamsTable`](crate::SimError::ParamsTable) for a table that is not ren2016
/// parameters (never for a loaded scenario).
pub fn fly_params(g: &Group) -> Result<FlyParams<f32>> {
    Ok(g.params_as::<FlyParamsOverride>()?.params())
}

/// The kinds a goal or threat may be: objects with a centre `[x, y, z]` (a solid sphere is
/// also an obstacle, as the predator of Fig. 8 and the lamp of Fig. 7), or a `region` (a
/// threat's walls sensed ahead; a goal's nearest point, the locusts' crop field of Fig. 4), or
/// a `cave` (a goal's walls or the air ahead, pursued: the bats' echolocation of Fig. 9).
pub(crate) const SOURCE_KINDS: [&str; 5] = ["zone", "target", "sphere", "region", "cave"];

/// The rules of a ren2016 group: no ant `nest`; a `goal` (the target it pursues) and a
/// `threat` (the predator it escapes), each optional, objects with a centre; parameters the controller accepts (in fixed point too for a fixed
/// group), with the neighbour range r_att within fixed point's reach.
pub(crate) fn check(c: &GroupCheck<'_>) -> std::result::Result<(), Problem> {
    let g = c.group;
    c.not_given(
        "nest",
        g.nest.is_some(),
        "`nest` is for ant groups; ren2016 insects pursue a `goal` (an object of kind `zone`, \
         `target` or `sphere`)",
    )?;
    for (field, name) in [("goal", &g.goal), ("threat", &g.threat)] {
        if let Some(name) = name {
            stimulus_object(c, field, name)?;
        }
    }
    let params = c.params::<FlyParamsOverride>()?.params();
    c.check_params(&params, |p| p.cast::<Fx>().validate())?;
    c.fixed_range("r_att", "the neighbour range r_att", params.r_att)
}

/// `name` (field `field` of the group) must be an object of a [`SOURCE_KINDS`] kind.
fn stimulus_object(
    c: &GroupCheck<'_>,
    field: &str,
    name: &str,
) -> std::result::Result<(), Problem> {
    let kind = c
        .scenario
        .object(name)
        .map(|o| o.kind.tag())
        .unwrap_or("zone");
    if !SOURCE_KINDS.contains(&kind) {
        return Err(c.problem(
            field,
            format!(
                "`{name}` is a `{kind}`, expected an object with a centre `[x, y, z]` (`zone`, \
                 `target` or `sphere`), a `region` or a `cave`"
            ),
        ));
    }
    c.object_of_kind(field, name, kind)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_fly_preset_is_an_extra_key() {
        let f: FlyParamsOverride = toml::from_str("chi_res = 12\npreset = \"mating\"").unwrap();
        assert_eq!(f.preset, Some(FlyPreset::Mating));
        assert_eq!(f.params().chi_res, 12.0);
        assert_eq!(f.params().r_res, 2.0);
        let err = toml::from_str::<FlyParamsOverride>("gama = 4").unwrap_err();
        assert!(err.message().starts_with("unknown field `gama`"), "{err}");
    }
}
