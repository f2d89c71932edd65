//! What a model's rules see of one of its groups, with the checks the models share: a model's
//! entry ([`ModelEntry::check`](crate::models::ModelEntry::check)) receives a [`GroupCheck`]
//! for every group of its model, after the rules every group follows (name, count, the model's
//! world, the spawn region).

use std::collections::HashMap;

use serde::de::DeserializeOwned;
use swarm_core::model::ModelParams;
use toml::de::DeTable;

use super::locate::path_at;
use super::problem::{Problem, join};
use super::rules::lookup;
use super::types::{Group, ScalarType, Scenario};

/// One group of a scenario, as its model's rules see it.
pub struct GroupCheck<'a> {
    /// The scenario.
    pub scenario: &'a Scenario,
    /// The group.
    pub group: &'a Group,
    /// Its index in [`Scenario::groups`].
    pub index: usize,
    objects: &'a HashMap<&'a str, usize>,
}

impl<'a> GroupCheck<'a> {
    pub(crate) fn new(
        scenario: &'a Scenario,
        index: usize,
        objects: &'a HashMap<&'a str, usize>,
    ) -> Self {
        GroupCheck {
            scenario,
            group: &scenario.groups[index],
            index,
            objects,
        }
    }

    /// The path of the group's field `field` in the file (`groups[1].nest`).
    pub fn field(&self, field: &str) -> String {
        join(&format!("groups[{}]", self.index), field)
    }

    /// A problem at the group's field `field`.
    pub fn problem(&self, field: &str, message: impl Into<String>) -> Problem {
        Problem::new(self.field(field), message)
    }

    /// The object `name`, named by the group's field `field`, exists and is of kind `kind`
    /// (`nest`, `target`, ...).
    ///
    /// # Errors
    ///
    /// A problem at `field` naming the objects there are, or the kind found.
    pub fn object_of_kind(&self, field: &str, name: &str, kind: &str) -> Result<(), Problem> {
        let (_, o) = lookup(self.scenario, self.objects, name, &self.field(field))?;
        if o.kind.tag() != kind {
            return Err(self.problem(
                field,
                format!(
                    "`{name}` is a `{}`, expected an object of kind `{kind}`",
                    o.kind.tag()
                ),
            ));
        }
        Ok(())
    }

    /// Refuses the group's field `field` when it is `given`: a field of other models' groups
    /// (`message` says what it is for).
    ///
    /// # Errors
    ///
    /// A problem at `field` with `message`.
    pub fn not_given(&self, field: &str, given: bool, message: &str) -> Result<(), Problem> {
        if given {
            return Err(self.problem(field, message));
        }
        Ok(())
    }

    /// Refuses a `threat` (an object the agents flee) in a group of a model that has none.
    ///
    /// # Errors
    ///
    /// A problem at `threat` naming the model.
    pub fn no_threat(&self) -> Result<(), Problem> {
        let model = self.group.model.as_str();
        self.not_given(
            "threat",
            self.group.threat.is_some(),
            &format!("`threat` (an object the agents flee) is not part of the {model} model"),
        )
    }

    /// The group's parameter table (under the model's name) read as `T`, the model's override
    /// type; `T::default()` when there is none.
    ///
    /// # Errors
    ///
    /// A problem at the parameter that does not read (`groups[0].ant.sped`), with serde's
    /// message (an unknown name lists the names there are).
    pub fn params<T: DeserializeOwned + Default>(&self) -> Result<T, Problem> {
        let at = self.field(self.group.model.as_str());
        let Some(table) = &self.group.params else {
            return Ok(T::default());
        };
        // Written out and read back with spans, to find the parameter a problem is at.
        let text = toml::to_string(table).map_err(|e| Problem::new(&at, e.to_string()))?;
        let tree = DeTable::parse(&text).map_err(|e| Problem::new(&at, e.message()))?;
        T::deserialize(toml::de::Deserializer::from(tree.clone())).map_err(|e| {
            let inner = e
                .span()
                .map(|s| path_at(&tree, s.start))
                .unwrap_or_default();
            Problem::new(join(&at, &inner), e.message())
        })
    }

    /// For a fixed-point group, refuses a sensing range `value` (`range`: the parameter `field`
    /// of the model's table, or an expression of its parameters) whose square does not fit
    /// I16F16 (below
    /// 32768, so below 181.02): the neighbours of a fixed-point agent are selected by squared
    /// distance in fixed point, and a saturated square would take in every agent the grid
    /// query returns.
    ///
    /// # Errors
    ///
    /// A problem at `<model>.<field>` saying so.
    pub fn fixed_range(&self, field: &str, range: &str, value: f32) -> Result<(), Problem> {
        if self.group.scalar != ScalarType::Fixed || value * value < 32_768.0 {
            return Ok(());
        }
        let model = self.group.model.as_str();
        Err(self.problem(
            &format!("{model}.{field}"),
            format!(
                "{range} = {value} is too large for a fixed-point group: ranges are squared in \
                 I16F16, so they must stay below 181 (or use scalar = \"f32\")"
            ),
        ))
    }

    /// Checks the group's parameters `params`, and for a fixed-point group also `in_fixed` of
    /// them (their check once converted to the fixed-point type).
    ///
    /// # Errors
    ///
    /// A problem at the first bad parameter (`groups[0].ant.theta`), saying what it takes
    /// (from the model's parameter table, [`ModelParams::SPECS`]).
    pub fn check_params<P: ModelParams>(
        &self,
        params: &P,
        in_fixed: impl FnOnce(&P) -> swarm_core::Result<()>,
    ) -> Result<(), Problem> {
        let checked = params.validate().and_then(|()| match self.group.scalar {
            ScalarType::Fixed => in_fixed(params),
            ScalarType::F32 => Ok(()),
        });
        let Err(e) = checked else {
            return Ok(());
        };
        let field = match e {
            swarm_core::Error::BadParam { field } => field,
            _ => "?",
        };
        let model = self.group.model.as_str();
        let takes = match P::index_of(field) {
            Some(i) => P::SPECS[i].to_string(),
            None => format!("a value `{model}` parameters accept"),
        };
        Err(self.problem(
            &format!("{model}.{field}"),
            format!("invalid {model} parameter `{field}`: expected {takes}"),
        ))
    }
}
