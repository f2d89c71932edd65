//! A group's parameter overrides (`ant = { w0 = 0.6 }`, `bee = { preset = "grassland",
//! kappa2 = 4 }`): any parameter of the model's parameter table ([`ModelParams::SPECS`] in
//! swarm-core), by name, on top of a base. Nothing here names a parameter: a model's table is
//! the list, so a new model's parameters need no edit here.

use std::collections::BTreeMap;
use std::fmt;
use std::marker::PhantomData;

use serde::de::DeserializeOwned;
use serde::de::{self, DeserializeSeed, MapAccess, Visitor};
use serde::ser::SerializeMap;
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use swarm_core::model::{ModelParams, ParamSpec, ParamValue, Range};

/// Overrides of some of the parameters `P` (a model's parameter struct), by their names in
/// `P`'s table ([`ModelParams::SPECS`]); in a file, a table such as `ant = { w0 = 0.6, k = 3 }`.
///
/// Reading one refuses a name that is not in the table (listing the names there are), a real
/// number for an integer parameter and an integer too large for its field, with serde's
/// messages for a struct field of that type (`expected u8`, ...); an integer is read as a real
/// number where a real is expected. The values' ranges are checked with the scenario's rules
/// ([`ModelParams::validate`] of the parameters with the overrides applied).
pub struct ParamsOverride<P: ModelParams> {
    /// Index in `P::SPECS` → value; only values `P::set` accepts.
    values: BTreeMap<usize, ParamValue<P::Scalar>>,
}

impl<P: ModelParams> ParamsOverride<P> {
    /// No parameter overridden.
    pub fn new() -> Self {
        ParamsOverride {
            values: BTreeMap::new(),
        }
    }

    /// The names of the parameters an override may set (as in the file): `P`'s table.
    pub fn names() -> impl Iterator<Item = &'static str> {
        P::SPECS.iter().map(|s| s.name)
    }

    /// Whether no parameter is overridden.
    pub fn is_empty(&self) -> bool {
        self.values.is_empty()
    }

    /// The value given for parameter `name`, if any.
    pub fn get(&self, name: &str) -> Option<ParamValue<P::Scalar>> {
        P::index_of(name).and_then(|i| self.values.get(&i).copied())
    }

    /// The parameters given, in the order of `P`'s table.
    pub fn iter(&self) -> impl Iterator<Item = (&'static ParamSpec, ParamValue<P::Scalar>)> + '_ {
        self.values.iter().map(|(&i, &v)| (&P::SPECS[i], v))
    }

    /// Drops the value given for parameter `name`, returning it.
    pub fn remove(&mut self, name: &str) -> Option<ParamValue<P::Scalar>> {
        P::index_of(name).and_then(|i| self.values.remove(&i))
    }

    /// `base` with every parameter given here replaced.
    pub fn apply(&self, base: P) -> P {
        let mut p = base;
        for (&i, &v) in &self.values {
            // Accepted by `set` when it was stored (see `ParamsOverride::set`).
            let stored = p.set(i, v);
            debug_assert!(stored, "parameter {}", P::SPECS[i].name);
        }
        p
    }
}

impl<P: ModelParams + Default> ParamsOverride<P> {
    /// Sets parameter `name` to `value`. False, and nothing changed, for a name not in `P`'s
    /// table, a value of the other kind or an integer too large for the field (what
    /// [`ModelParams::set`] refuses).
    pub fn set(&mut self, name: &str, value: ParamValue<P::Scalar>) -> bool {
        let Some(i) = P::index_of(name) else {
            return false;
        };
        if !P::default().set(i, value) {
            return false;
        }
        self.values.insert(i, value);
        true
    }
}

impl<P: ModelParams> Default for ParamsOverride<P> {
    fn default() -> Self {
        Self::new()
    }
}

impl<P: ModelParams> Clone for ParamsOverride<P> {
    fn clone(&self) -> Self {
        ParamsOverride {
            values: self.values.clone(),
        }
    }
}

impl<P: ModelParams> PartialEq for ParamsOverride<P> {
    fn eq(&self, other: &Self) -> bool {
        self.values == other.values
    }
}

impl<P: ModelParams> fmt::Debug for ParamsOverride<P> {
    /// `{"w0": Real(0.6), "k": Int(3)}`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_map()
            .entries(self.iter().map(|(spec, v)| (spec.name, v)))
            .finish()
    }
}

impl<P: ModelParams<Scalar = f32>> ParamsOverride<P> {
    /// Writes the parameters given as entries of a map, in the order of `P`'s table.
    pub(crate) fn write_entries<M: SerializeMap>(&self, map: &mut M) -> Result<(), M::Error> {
        for (spec, value) in self.iter() {
            match value {
                ParamValue::Real(v) => map.serialize_entry(spec.name, &decimal(v))?,
                ParamValue::Int(v) => map.serialize_entry(spec.name, &v)?,
            }
        }
        Ok(())
    }
}

/// `v` as the shortest decimal that reads back as `v` (`0.68`, not `0.6800000071525574`).
fn decimal(v: f32) -> f64 {
    match v.to_string().parse::<f64>() {
        Ok(d) if d as f32 == v => d,
        _ => f64::from(v),
    }
}

impl<P: ModelParams<Scalar = f32>> Serialize for ParamsOverride<P> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(self.values.len()))?;
        self.write_entries(&mut map)?;
        map.end()
    }
}

impl<'de, P: ModelParams<Scalar = f32> + Default> Deserialize<'de> for ParamsOverride<P> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Table<P>(PhantomData<P>);

        impl<'de, P: ModelParams<Scalar = f32> + Default> Visitor<'de> for Table<P> {
            type Value = ParamsOverride<P>;

            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "struct {}Override", struct_name::<P>())
            }

            fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<Self::Value, A::Error> {
                // No extra keys, so `extra` is never called.
                read_table(map, &[], |_, _| Ok(()))
            }
        }

        deserializer.deserialize_map(Table(PhantomData))
    }
}

/// `AntParams` for `swarm_core::ant::params::AntParams<f32>`: the parameter struct's name, for
/// the message of a value that is not a table (`expected struct AntParamsOverride`).
fn struct_name<P>() -> &'static str {
    let full = std::any::type_name::<P>();
    let path = full.split('<').next().unwrap_or(full);
    path.rsplit("::").next().unwrap_or(path)
}

/// Reads a table whose keys are parameters of `P` or one of `extras`, which `extra` reads
/// (given the key and the map to take the value from).
pub(crate) fn read_table<'de, A, P>(
    mut map: A,
    extras: &'static [&'static str],
    mut extra: impl FnMut(&'static str, &mut A) -> Result<(), A::Error>,
) -> Result<ParamsOverride<P>, A::Error>
where
    A: MapAccess<'de>,
    P: ModelParams<Scalar = f32> + Default,
{
    let mut out = ParamsOverride::new();
    let keys = Key::<P> {
        extras,
        params: PhantomData,
    };
    while let Some(key) = map.next_key_seed(keys)? {
        let i = match key {
            Found::Extra(name) => {
                extra(name, &mut map)?;
                continue;
            }
            Found::Param(i) => i,
        };
        let spec = &P::SPECS[i];
        if out.values.contains_key(&i) {
            return Err(de::Error::duplicate_field(spec.name));
        }
        let value = match spec.range {
            Range::Real { .. } => ParamValue::Real(map.next_value::<f32>()?),
            Range::Int { .. } => ParamValue::Int(match IntField::of::<P>(i) {
                IntField::U8 => u32::from(map.next_value::<u8>()?),
                IntField::U16 => u32::from(map.next_value::<u16>()?),
                IntField::U32 => map.next_value::<u32>()?,
            }),
        };
        out.values.insert(i, value);
    }
    Ok(out)
}

/// The integer type of a parameter's field, found from what its `set` accepts; serde reads
/// the value as that type, so a value too large for the field is refused as for a struct field
/// of that type.
enum IntField {
    U8,
    U16,
    U32,
}

impl IntField {
    fn of<P: ModelParams + Default>(index: usize) -> IntField {
        let fits = |v: u32| P::default().set(index, ParamValue::Int(v));
        if !fits(u32::from(u8::MAX) + 1) {
            IntField::U8
        } else if !fits(u32::from(u16::MAX) + 1) {
            IntField::U16
        } else {
            IntField::U32
        }
    }
}

/// A key of a parameter table: the index of a parameter of `P`, or one of the extra keys.
enum Found {
    Param(usize),
    Extra(&'static str),
}

/// Reads a key of a parameter table (the keys `P`'s table names, and `extras`). An unknown key
/// is refused where it stands, with the names there are.
struct Key<P> {
    extras: &'static [&'static str],
    params: PhantomData<P>,
}

impl<P> Clone for Key<P> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<P> Copy for Key<P> {}

impl<'de, P: ModelParams> DeserializeSeed<'de> for Key<P> {
    type Value = Found;

    fn deserialize<D: Deserializer<'de>>(self, deserializer: D) -> Result<Found, D::Error> {
        deserializer.deserialize_identifier(self)
    }
}

impl<'de, P: ModelParams> Visitor<'de> for Key<P> {
    type Value = Found;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("field identifier")
    }

    fn visit_str<E: de::Error>(self, key: &str) -> Result<Found, E> {
        if let Some(extra) = self.extras.iter().find(|x| **x == key) {
            return Ok(Found::Extra(extra));
        }
        P::index_of(key).map(Found::Param).ok_or_else(|| {
            let names: Vec<&str> = self
                .extras
                .iter()
                .copied()
                .chain(P::SPECS.iter().map(|s| s.name))
                .collect();
            E::custom(unknown_field(key, &names))
        })
    }
}

/// serde's message for an unknown field (what `de::Error::unknown_field` says; it takes the
/// names as a `'static` list, and these come from the table).
fn unknown_field(field: &str, expected: &[&str]) -> String {
    let names = match expected {
        [] => return format!("unknown field `{field}`, there are no fields"),
        [one] => format!("`{one}`"),
        [a, b] => format!("`{a}` or `{b}`"),
        all => {
            let quoted: Vec<String> = all.iter().map(|n| format!("`{n}`")).collect();
            format!("one of {}", quoted.join(", "))
        }
    };
    format!("unknown field `{field}`, expected {names}")
}

/// A named set of a model's parameters `P` (a column of its paper's table, e.g. chen's
/// Table I for bees), that a parameter table names with `preset = "..."`.
pub trait Preset<P>:
    Copy + Default + PartialEq + fmt::Debug + Serialize + DeserializeOwned
{
    /// The preset's parameters.
    fn params(&self) -> P;
}

/// A preset (`preset` in the file; default: `B::default()`) and overrides of some parameters
/// on top of it: a table such as `bee = { preset = "grassland", kappa2 = 4 }`.
#[derive(Clone, Debug, PartialEq)]
pub struct PresetOverride<P: ModelParams, B> {
    /// The base the parameters apply to.
    pub preset: Option<B>,
    /// The parameters set on top of the preset.
    pub overrides: ParamsOverride<P>,
}

impl<P: ModelParams, B> Default for PresetOverride<P, B> {
    fn default() -> Self {
        PresetOverride {
            preset: None,
            overrides: ParamsOverride::new(),
        }
    }
}

impl<P: ModelParams, B: Preset<P>> PresetOverride<P, B> {
    /// `base` with the parameters given here replaced (the preset is not used).
    pub fn apply(&self, base: P) -> P {
        self.overrides.apply(base)
    }

    /// The preset's parameters with the overrides applied.
    pub fn params(&self) -> P {
        self.apply(self.preset.unwrap_or_default().params())
    }
}

impl<P: ModelParams<Scalar = f32>, B: Serialize> Serialize for PresetOverride<P, B> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let len = usize::from(self.preset.is_some()) + self.overrides.values.len();
        let mut map = serializer.serialize_map(Some(len))?;
        if let Some(preset) = &self.preset {
            map.serialize_entry("preset", preset)?;
        }
        self.overrides.write_entries(&mut map)?;
        map.end()
    }
}

impl<'de, P, B> Deserialize<'de> for PresetOverride<P, B>
where
    P: ModelParams<Scalar = f32> + Default,
    B: Preset<P>,
{
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Table<P, B>(PhantomData<(P, B)>);

        impl<'de, P, B> Visitor<'de> for Table<P, B>
        where
            P: ModelParams<Scalar = f32> + Default,
            B: Preset<P>,
        {
            type Value = PresetOverride<P, B>;

            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "struct {}Override", struct_name::<P>())
            }

            fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<Self::Value, A::Error> {
                let mut preset = None;
                let overrides = read_table(map, &["preset"], |_, map: &mut A| {
                    if preset.is_some() {
                        return Err(de::Error::duplicate_field("preset"));
                    }
                    preset = Some(map.next_value()?);
                    Ok(())
                })?;
                Ok(PresetOverride { preset, overrides })
            }
        }

        deserializer.deserialize_map(Table(PhantomData))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A model of two parameters, to show an override needs nothing but the table.
    #[derive(Clone, Debug, Default, PartialEq)]
    struct Toy {
        gain: f32,
        ticks: u16,
    }

    const fn spec(name: &'static str, range: Range) -> ParamSpec {
        ParamSpec {
            name,
            range,
            unit: "",
        }
    }

    impl ModelParams for Toy {
        type Scalar = f32;
        const SPECS: &'static [ParamSpec] = &[
            spec("gain", Range::closed(0.0, 2.0)),
            spec("ticks", Range::int(1, 100)),
        ];

        fn get(&self, index: usize) -> Option<ParamValue<f32>> {
            match index {
                0 => Some(ParamValue::Real(self.gain)),
                1 => Some(ParamValue::Int(u32::from(self.ticks))),
                _ => None,
            }
        }

        fn set(&mut self, index: usize, value: ParamValue<f32>) -> bool {
            match (index, value) {
                (0, ParamValue::Real(v)) => self.gain = v,
                (1, ParamValue::Int(v)) => match u16::try_from(v) {
                    Ok(v) => self.ticks = v,
                    Err(_) => return false,
                },
                _ => return false,
            }
            true
        }
    }

    fn read(text: &str) -> Result<ParamsOverride<Toy>, String> {
        toml::from_str(text).map_err(|e| e.message().to_owned())
    }

    #[test]
    fn any_table_of_parameters_reads_writes_and_applies() {
        let o = read("ticks = 7\ngain = 1").unwrap();
        assert_eq!(
            o.get("gain"),
            Some(ParamValue::Real(1.0)),
            "an integer for a real"
        );
        assert_eq!(
            o.apply(Toy::default()),
            Toy {
                gain: 1.0,
                ticks: 7
            }
        );
        // Written in the table's order; read back the same.
        let text = toml::to_string(&o).unwrap();
        assert_eq!(text, "gain = 1.0\nticks = 7\n");
        assert_eq!(read(&text).unwrap(), o);
        assert_eq!(format!("{o:?}"), r#"{"gain": Real(1.0), "ticks": Int(7)}"#);
        assert!(read("").unwrap().is_empty());
    }

    #[test]
    fn what_the_table_does_not_allow_is_refused() {
        for (text, message) in [
            (
                "gian = 1",
                "unknown field `gian`, expected `gain` or `ticks`",
            ),
            (
                "ticks = 1.5",
                "invalid type: floating point `1.5`, expected u16",
            ),
            (
                "ticks = 70000",
                "invalid value: integer `70000`, expected u16",
            ),
            ("gain = \"x\"", "invalid type: string \"x\", expected f32"),
        ] {
            assert_eq!(read(text).unwrap_err(), message);
        }
        assert!(
            toml::from_str::<BTreeMap<String, ParamsOverride<Toy>>>("t = 5")
                .unwrap_err()
                .message()
                .ends_with("expected struct ToyOverride")
        );
        // In code: the same limits.
        let mut o = ParamsOverride::<Toy>::new();
        assert!(!o.set("gian", ParamValue::Real(1.0)));
        assert!(!o.set("ticks", ParamValue::Real(1.0)));
        assert!(!o.set("ticks", ParamValue::Int(70_000)));
        assert!(o.is_empty());
        assert!(o.set("ticks", ParamValue::Int(3)));
        assert_eq!(o.remove("ticks"), Some(ParamValue::Int(3)));
        assert!(o.is_empty());
    }
}
