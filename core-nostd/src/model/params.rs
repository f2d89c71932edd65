//! A model's parameters as a table: each one's name, the values it may take and its unit,
//! defined once next to the parameter struct and used by its validation, by the host's
//! scenario overrides and in their error messages.

use core::fmt;

use crate::scalar::Constant;
use crate::{Error, Result, Scalar};

/// The values a parameter may take.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Range {
    /// A real number in `[min, max]`, or `(min, max]` when `min_open`.
    Real {
        /// The lower end.
        min: Constant,
        /// The upper end (included).
        max: Constant,
        /// Whether `min` itself is excluded.
        min_open: bool,
    },
    /// An integer in `min..=max`.
    Int {
        /// The smallest value.
        min: u32,
        /// The largest value.
        max: u32,
    },
}

impl Range {
    /// A real number in `[min, max]`.
    pub const fn closed(min: f32, max: f32) -> Range {
        Range::Real {
            min: Constant::new(min),
            max: Constant::new(max),
            min_open: false,
        }
    }
    /// A real number in `(min, max]`.
    pub const fn above(min: f32, max: f32) -> Range {
        Range::Real {
            min: Constant::new(min),
            max: Constant::new(max),
            min_open: true,
        }
    }
    /// An integer in `min..=max`.
    pub const fn int(min: u32, max: u32) -> Range {
        Range::Int { min, max }
    }

    /// Whether `v` is in the range: a finite real number between the ends compared in `S`
    /// (the ends converted as [`Scalar::from_f32`] does), or an integer between them. A value
    /// of the other kind is not.
    #[inline]
    pub fn contains<S: Scalar>(&self, v: ParamValue<S>) -> bool {
        match (*self, v) {
            (Range::Real { min, max, min_open }, ParamValue::Real(v)) => {
                let (lo, hi) = (S::constant(min), S::constant(max));
                v.is_finite() && (if min_open { v > lo } else { v >= lo }) && v <= hi
            }
            (Range::Int { min, max }, ParamValue::Int(v)) => (min..=max).contains(&v),
            _ => false,
        }
    }
}

impl fmt::Display for Range {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Range::Real { min, max, min_open } => {
                let open = if min_open { '(' } else { '[' };
                write!(f, "a number in {open}{}, {}]", min.f32(), max.f32())
            }
            Range::Int { min, max } => write!(f, "an integer from {min} to {max}"),
        }
    }
}

/// One parameter of a model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParamSpec {
    /// Its field name (as in the struct, the scenario file and the error messages).
    pub name: &'static str,
    /// The values it may take.
    pub range: Range,
    /// Its unit, for messages (`""` if none).
    pub unit: &'static str,
}

impl fmt::Display for ParamSpec {
    /// What the parameter takes, e.g. "a number in (0, 100] (units/tick)".
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.range)?;
        if !self.unit.is_empty() {
            write!(f, " ({})", self.unit)?;
        }
        Ok(())
    }
}

/// The value of one parameter: a real number in the model's scalar, or an integer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ParamValue<S> {
    /// A real number.
    Real(S),
    /// A count or a small integer.
    Int(u32),
}

/// A model's parameter set, described by a table of [`ParamSpec`]s (implemented with
/// `model_params!`, which writes the table, `get` and `set` from one list).
pub trait ModelParams: Sized {
    /// The number type of its real parameters.
    type Scalar: Scalar;
    /// Every parameter, in the order [`ModelParams::validate`] checks them.
    const SPECS: &'static [ParamSpec];

    /// Parameter `index` of [`SPECS`](ModelParams::SPECS).
    fn get(&self, index: usize) -> Option<ParamValue<Self::Scalar>>;
    /// Sets parameter `index`; false (and nothing changed) for an index out of the table, a
    /// value of the other kind, or an integer too large for the field.
    fn set(&mut self, index: usize, value: ParamValue<Self::Scalar>) -> bool;
    /// Rules that tie parameters together, checked after each one's range.
    fn check_together(&self) -> Result<()> {
        Ok(())
    }

    /// The index of the parameter called `name`.
    fn index_of(name: &str) -> Option<usize> {
        Self::SPECS.iter().position(|s| s.name == name)
    }
    /// Checks every parameter against its range, then [`check_together`]; the error names the
    /// first bad one ([`Error::BadParam`]).
    ///
    /// [`check_together`]: ModelParams::check_together
    fn validate(&self) -> Result<()> {
        for (i, spec) in Self::SPECS.iter().enumerate() {
            match self.get(i) {
                Some(v) if spec.range.contains(v) => {}
                _ => return Err(Error::BadParam { field: spec.name }),
            }
        }
        self.check_together()
    }

    /// The parameters, validated once (see [`Checked`](crate::Checked)).
    ///
    /// # Errors
    ///
    /// The first bad parameter ([`ModelParams::validate`]).
    fn checked(self) -> Result<crate::Checked<Self>> {
        self.validate()?;
        Ok(crate::Checked::assume_valid(self))
    }
}

/// Implements [`ModelParams`] for a parameter struct generic over its scalar from one list of
/// `field: kind = range, "unit";` lines, where kind is `real` (a field of type `S`) or
/// `int(T)` (an integer field of type `T`), and optionally `together method`, the struct's
/// method that checks the rules between fields.
///
/// ```
/// use swarm_core::model::{ModelParams, Range};
///
/// #[derive(Clone, PartialEq)]
/// pub struct WalkParams<S> {
///     pub speed: S,
///     pub turns: u8,
/// }
/// swarm_core::model_params! {
///     WalkParams {
///         speed: real = Range::above(0.0, 10.0), "units/tick";
///         turns: int(u8) = Range::int(1, 8), "";
///     }
/// }
/// let p = WalkParams { speed: 1.0f32, turns: 4 };
/// assert!(p.validate().is_ok());
/// assert_eq!(WalkParams::<f32>::SPECS[1].name, "turns");
/// ```
#[macro_export]
macro_rules! model_params {
    (
        $ty:ident { $($field:ident: $kind:ident $(($int:ty))? = $range:expr, $unit:literal;)* }
        $(together $together:ident)?
    ) => {
        impl<S: $crate::Scalar> $crate::model::ModelParams for $ty<S> {
            type Scalar = S;
            const SPECS: &'static [$crate::model::ParamSpec] = &[$(
                $crate::model::ParamSpec { name: stringify!($field), range: $range, unit: $unit },
            )*];

            fn get(&self, index: usize) -> Option<$crate::model::ParamValue<S>> {
                let mut i = 0;
                $(
                    if index == i {
                        return Some($crate::model_params!(@get self.$field, $kind));
                    }
                    i += 1;
                )*
                let _ = i;
                None
            }

            fn set(&mut self, index: usize, value: $crate::model::ParamValue<S>) -> bool {
                let mut i = 0;
                $(
                    if index == i {
                        return $crate::model_params!(@set self.$field, $kind $(($int))?, value);
                    }
                    i += 1;
                )*
                let _ = i;
                false
            }
            $(
                fn check_together(&self) -> $crate::Result<()> {
                    self.$together()
                }
            )?

            // The same checks as the default, written out field by field with each range a
            // constant: a device then compares with immediate values and carries no table.
            fn validate(&self) -> $crate::Result<()> {
                $({
                    const RANGE: $crate::model::Range = $range;
                    if !RANGE.contains::<S>($crate::model_params!(@get self.$field, $kind)) {
                        return Err($crate::Error::BadParam { field: stringify!($field) });
                    }
                })*
                $crate::model::ModelParams::check_together(self)
            }
        }
    };
    (@get $e:expr, real) => { $crate::model::ParamValue::Real($e) };
    (@get $e:expr, int) => { $crate::model::ParamValue::Int(u32::from($e)) };
    (@set $e:expr, real, $v:expr) => {
        match $v {
            $crate::model::ParamValue::Real(v) => {
                $e = v;
                true
            }
            _ => false,
        }
    };
    (@set $e:expr, int($t:ty), $v:expr) => {
        match $v {
            $crate::model::ParamValue::Int(v) => match <$t>::try_from(v) {
                Ok(v) => {
                    $e = v;
                    true
                }
                Err(_) => false,
            },
            _ => false,
        }
    };
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Fx;
    use crate::ant::AntParams;
    use crate::bee::BeeParams;
    use crate::wang::WangParams;

    /// Every parameter of `P`: the default is in range; the ends of the range are accepted and
    /// a value just outside each end is refused, naming the parameter; `set` of the other kind
    /// is refused.
    fn ranges_hold<P: ModelParams + Clone + Default>(fields: usize) {
        assert_eq!(P::SPECS.len(), fields, "one spec per field");
        let base = P::default();
        base.validate().expect("defaults are valid");
        for (i, spec) in P::SPECS.iter().enumerate() {
            assert_eq!(P::index_of(spec.name), Some(i));
            let with = |v: ParamValue<P::Scalar>| {
                let mut p = base.clone();
                assert!(p.set(i, v), "{}: set", spec.name);
                assert_eq!(p.get(i), Some(v));
                p.validate()
            };
            let refused = |r: Result<()>| r == Err(Error::BadParam { field: spec.name });
            match spec.range {
                Range::Real { min, max, min_open } => {
                    let s = |c: Constant| <P::Scalar as Scalar>::constant(c);
                    // A few steps of the type beyond each end (relative steps for f32).
                    let step = |v: P::Scalar| {
                        let e = <P::Scalar as Scalar>::EPS * s(Constant::new(8.0));
                        e + v.abs() * e
                    };
                    let (lo, hi) = (s(min), s(max));
                    assert!(
                        refused(with(ParamValue::Real(hi + step(hi)))),
                        "{}",
                        spec.name
                    );
                    assert!(
                        refused(with(ParamValue::Real(lo - step(lo)))),
                        "{}",
                        spec.name
                    );
                    let at_min = with(ParamValue::Real(s(min)));
                    assert_eq!(refused(at_min), min_open, "{} at its minimum", spec.name);
                    let mut p = base.clone();
                    assert!(!p.set(i, ParamValue::Int(1)), "{}: an integer", spec.name);
                }
                Range::Int { min, max } => {
                    if min > 0 {
                        assert!(refused(with(ParamValue::Int(min - 1))), "{}", spec.name);
                    }
                    let mut p = base.clone();
                    // Past the range: refused by `set` (too large for the field) or by the check.
                    if p.set(i, ParamValue::Int(max + 1)) {
                        assert!(refused(p.validate()), "{}", spec.name);
                    }
                    assert!(!p.set(i, ParamValue::Real(P::Scalar::ONE)), "{}", spec.name);
                }
            }
        }
        let mut p = base.clone();
        assert!(!p.set(P::SPECS.len(), ParamValue::Int(1)));
        assert_eq!(p.get(P::SPECS.len()), None);
    }

    #[test]
    fn every_parameter_has_its_range_in_both_scalars() {
        ranges_hold::<AntParams<f32>>(13);
        ranges_hold::<AntParams<Fx>>(13);
        ranges_hold::<BeeParams<f32>>(17);
        ranges_hold::<BeeParams<Fx>>(17);
        ranges_hold::<WangParams<f32>>(9);
        ranges_hold::<WangParams<Fx>>(9);
        ranges_hold::<crate::li::LiParams<f32>>(12);
        ranges_hold::<crate::li::LiParams<Fx>>(12);
    }

    #[test]
    fn ranges_read_as_text() {
        extern crate std;
        use std::string::ToString;
        let spec = |name| AntParams::<f32>::SPECS[AntParams::<f32>::index_of(name).unwrap()];
        assert_eq!(
            spec("speed").to_string(),
            "a number in (0, 100] (units/tick)"
        );
        assert_eq!(spec("w0").to_string(), "a number in [0, 1]");
        assert_eq!(spec("k").to_string(), "an integer from 0 to 8");
        assert_eq!(
            spec("collect_ticks").to_string(),
            "an integer from 1 to 65535 (ticks)"
        );
    }

    #[test]
    fn the_wang_rule_between_fields_is_checked() {
        let p = WangParams::<f32> {
            dt: 0.5, // 0.5·(3.2·0.25/0.4 + 1.5) = 1.75 > 0.2
            ..Default::default()
        };
        assert_eq!(p.validate(), Err(Error::BadParam { field: "dt" }));
    }

    #[test]
    fn the_bee_rule_between_fields_is_checked() {
        let p = BeeParams::<f32> {
            damping: 30.0, // damping·dt = 1.5 > 1
            ..Default::default()
        };
        assert_eq!(p.validate(), Err(Error::BadParam { field: "damping" }));
    }
}
