//! What an ant group of a scenario is: its parameter table (`ant = { w0 = 0.6 }`) and the
//! rules of the ant model (a home nest, no bee fields, parameters the controller accepts).

use swarm_core::Fx;
use swarm_core::ant::AntParams;

use crate::Result;
use crate::scenario::{Group, GroupCheck, ParamsOverride, Problem};

/// `[groups.ant]`: any of the `AntParams` parameters (xiang2018), on top of the defaults.
pub type AntParamsOverride = ParamsOverride<AntParams<f32>>;

/// The ant parameters of group `g`: `AntParams::default()` with its overrides applied.
///
/// # Errors
///
/// [`SimError::ParamsTable`](crate::SimError::ParamsTable) for a table that is not ant
/// parameters (never for a loaded scenario).
pub fn ant_params(g: &Group) -> Result<AntParams<f32>> {
    Ok(g.params_as::<AntParamsOverride>()?
        .apply(AntParams::default()))
}

/// The rules of an ant group: it names its home nest (an object of kind `nest`), no bee
/// `goal`, and parameters the controller accepts (in fixed point too for a fixed group).
pub(crate) fn check(c: &GroupCheck<'_>) -> std::result::Result<(), Problem> {
    let g = c.group;
    let Some(nest) = &g.nest else {
        return Err(c.problem(
            "nest",
            "missing field `nest`: an ant group needs the name of its home nest (an object of \
             kind `nest`)",
        ));
    };
    c.object_of_kind("nest", nest, "nest")?;
    c.no_threat()?;
    c.not_given(
        "goal",
        g.goal.is_some(),
        "`goal` is for bee groups; ants forage between their `nest` and the food sources",
    )?;
    let params = c.params::<AntParamsOverride>()?.apply(AntParams::default());
    c.check_params(&params, |p| p.cast::<Fx>().validate())?;
    c.fixed_range("contact_range", "contact_range", params.contact_range)?;
    c.fixed_range("collision_range", "collision_range", params.collision_range)
}
