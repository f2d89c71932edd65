//! What a wang2014 group of a scenario is: its parameter table (`wang = { preset =
//! "aggregation", gain = 0.5 }`, a column of wang2014's Table 1 and overrides) and the rules of
//! the model (a `goal` it flies to, no ant fields, parameters the controller accepts).

use serde::{Deserialize, Serialize};
use swarm_core::Fx;
use swarm_core::wang::WangParams;

use crate::Result;
use crate::scenario::{Group, GroupCheck, Preset, PresetOverride, Problem};

/// `[groups.wang]`: a Table 1 preset, and any of the `WangParams` parameters on top of it.
pub type WangParamsOverride = PresetOverride<WangParams<f32>, WangPreset>;

/// A column of wang2014's Table 1 (with the spec's choices for what the table leaves out).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum WangPreset {
    /// `"two_blocks"` (also Chasing): scale 0.4, gain 0.25, s0 1.5, Δt 0.01.
    #[default]
    TwoBlocks,
    /// `"aggregation"`: scale 0.2, gain 0.7, s0 2.5, Δt 0.005.
    Aggregation,
    /// `"phototaxis"`: scale 0.6, gain 1.0, s0 2.5, the bias toward the lamp (p 0.05,
    /// 0.2·s0).
    Phototaxis,
    /// `"locusts"`: scale 0.6, gain 1.0 (the table's missing cells, spec W1), s0 8.
    Locusts,
}

impl Preset<WangParams<f32>> for WangPreset {
    fn params(&self) -> WangParams<f32> {
        match self {
            WangPreset::TwoBlocks => WangParams::two_blocks(),
            WangPreset::Aggregation => WangParams::aggregation(),
            WangPreset::Phototaxis => WangParams::phototaxis(),
            WangPreset::Locusts => WangParams::locusts(),
        }
    }
}

/// The wang2014 parameters of group `g`: the preset (default `two_blocks`) with its
/// overrides applied.
///
/// # Errors
///
/// [`SimError::ParamsTable`](crate::SimError::ParamsTable) for a table that is not wang2014
/// parameters (never for a loaded scenario).
pub fn wang_params(g: &Group) -> Result<WangParams<f32>> {
    Ok(g.params_as::<WangParamsOverride>()?.params())
}

/// The kinds a wang2014 group's `goal` may name: a goal area (`zone`, `region`), or an
/// obstacle whose surroundings are the goal (the chased ball of Fig. 8).
pub(crate) const GOAL_KINDS: [&str; 5] = ["zone", "region", "sphere", "box", "shaft"];

/// The rules of a wang2014 group: no ant `nest`; a `goal` (required: the navigation field
/// leads there) that is a goal area or an obstacle; parameters the controller accepts (in
/// fixed point too for a fixed group).
pub(crate) fn check(c: &GroupCheck<'_>) -> std::result::Result<(), Problem> {
    let g = c.group;
    c.no_threat()?;
    c.not_given(
        "nest",
        g.nest.is_some(),
        "`nest` is for ant groups; wang2014 insects fly toward a `goal`",
    )?;
    let Some(goal) = &g.goal else {
        return Err(c.problem(
            "goal",
            "missing field `goal`: a wang2014 group flies along the minimum-cost field to its \
             goal (an object of kind `zone` or `region`, or an obstacle to gather around)",
        ));
    };
    let kind = c
        .scenario
        .object(goal)
        .map(|o| o.kind.tag())
        .unwrap_or("zone");
    if !GOAL_KINDS.contains(&kind) {
        return Err(c.problem(
            "goal",
            format!(
                "`{goal}` is a `{kind}`, expected a goal area (`zone`, `region`) or an obstacle \
                 (`sphere`, `box`, `shaft`)"
            ),
        ));
    }
    c.object_of_kind("goal", goal, kind)?;
    let params = c.params::<WangParamsOverride>()?.params();
    c.check_params(&params, |p| p.cast::<Fx>().validate())?;
    c.fixed_range("d_min", "the separation distance d_min", params.d_min)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_wang_preset_is_an_extra_key() {
        let w: WangParamsOverride = toml::from_str("gain = 0.5\npreset = \"locusts\"").unwrap();
        assert_eq!(w.preset, Some(WangPreset::Locusts));
        assert_eq!(w.params().gain, 0.5);
        assert_eq!(w.params().s0, 8.0);
        let err = toml::from_str::<WangParamsOverride>("gian = 4").unwrap_err();
        assert!(err.message().starts_with("unknown field `gian`"), "{err}");
    }
}
