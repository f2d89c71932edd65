//! Host-side conversions of the controller scalars.
//!
//! The simulator keeps the *sensed* world (what neighbours see of an agent) in `f64`, which
//! holds every `f32` and every I16F16 value exactly, so groups of different scalar types can
//! share a world and a fixed-point group still senses bit-exact fixed-point positions.

use swarm_core::{Fx, Scalar, Vec2, Vec3};

/// A [`Scalar`] the simulator can run: exact conversions to and from `f64`, and the wire
/// encoding its messages need.
pub trait SimScalar:
    Scalar + serde::Serialize + serde::de::DeserializeOwned + Send + Sync + 'static
{
    /// The value as `f64` (exact).
    fn to_f64(self) -> f64;
    /// The nearest value to `v` (exact for values that came from `to_f64`).
    fn from_f64(v: f64) -> Self;
    /// A sensed position in this scalar, from the grid's `f32` copy `copy` where that is exact
    /// (`f32`: the same bits as converting the `f64`, without reading it), else from `exact()`.
    fn sensed(copy: [f32; 3], exact: impl FnOnce() -> [f64; 2]) -> Vec2<Self> {
        let _ = copy;
        v2(exact())
    }
    /// [`SimScalar::sensed`] in 3D.
    fn sensed3(copy: [f32; 3], exact: impl FnOnce() -> [f64; 3]) -> Vec3<Self> {
        let _ = copy;
        v3(exact())
    }
    /// The bits of a value `≥ 0` as a `u32` that orders like the values (selection keys).
    fn order_bits(self) -> u32;
}

impl SimScalar for f32 {
    fn to_f64(self) -> f64 {
        self as f64
    }
    fn from_f64(v: f64) -> f32 {
        v as f32
    }
    fn sensed(copy: [f32; 3], _: impl FnOnce() -> [f64; 2]) -> Vec2<f32> {
        Vec2::new(copy[0], copy[1])
    }
    fn sensed3(copy: [f32; 3], _: impl FnOnce() -> [f64; 3]) -> Vec3<f32> {
        Vec3::new(copy[0], copy[1], copy[2])
    }
    fn order_bits(self) -> u32 {
        self.to_bits()
    }
}

impl SimScalar for Fx {
    fn to_f64(self) -> f64 {
        self.0.to_num::<f64>()
    }
    fn from_f64(v: f64) -> Fx {
        if v.is_nan() {
            Fx::ZERO
        } else {
            Fx(swarm_core::scalar::I16F16::saturating_from_num(v))
        }
    }
    fn order_bits(self) -> u32 {
        self.to_bits().max(0) as u32
    }
}

/// `[x, y]` as a `Vec2<S>`.
pub fn v2<S: SimScalar>(p: [f64; 2]) -> Vec2<S> {
    Vec2::new(S::from_f64(p[0]), S::from_f64(p[1]))
}

/// A `Vec2<S>` as `[x, y]`.
pub fn a2<S: SimScalar>(v: Vec2<S>) -> [f64; 2] {
    [v.x.to_f64(), v.y.to_f64()]
}

/// `[x, y, z]` as a `Vec3<S>`.
pub fn v3<S: SimScalar>(p: [f64; 3]) -> Vec3<S> {
    Vec3::new(S::from_f64(p[0]), S::from_f64(p[1]), S::from_f64(p[2]))
}

/// A `Vec3<S>` as `[x, y, z]`.
pub fn a3<S: SimScalar>(v: Vec3<S>) -> [f64; 3] {
    [v.x.to_f64(), v.y.to_f64(), v.z.to_f64()]
}

/// A vector as `f32` coordinates (the obstacle broad phase's key,
/// [`ObstacleIndex`](crate::obstacle_index::ObstacleIndex)).
#[inline(always)]
pub fn a3f<S: Scalar>(v: Vec3<S>) -> [f32; 3] {
    let v = v.to_f32();
    [v.x, v.y, v.z]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn conversions_through_f64_are_exact() {
        for bits in [0i32, 1, -1, i32::MAX, i32::MIN, 0x1234_5678, -0x0765_4321] {
            let x = Fx::from_bits(bits);
            assert_eq!(Fx::from_f64(x.to_f64()), x);
        }
        for x in [0.1f32, -3.75e-9, 16_383.999, f32::MIN_POSITIVE] {
            assert_eq!(f32::from_f64(x.to_f64()).to_bits(), x.to_bits());
        }
    }
}

/// One value per scalar type: a group of agents runs either `f32` or I16F16 controllers. The
/// engines alias it (`AnyAntGroup`, `AnyBeeGroup`); [`by_scalar!`](crate::by_scalar) runs one generic body on
/// either variant.
#[derive(Clone, Debug)]
pub enum ByScalar<F, X> {
    /// `f32` controllers.
    F32(F),
    /// I16F16 controllers.
    Fixed(X),
}

/// Runs `$body` with `$g` bound to the value inside a [`ByScalar`], whatever its variant.
#[macro_export]
macro_rules! by_scalar {
    ($value:expr, $g:ident => $body:expr) => {
        match $value {
            $crate::scalar::ByScalar::F32($g) => $body,
            $crate::scalar::ByScalar::Fixed($g) => $body,
        }
    };
}

/// What every agent group tells about itself.
pub trait AgentGroup {
    /// Group name.
    fn name(&self) -> &str;
    /// Number of agents.
    fn len(&self) -> usize;
    /// First world slot.
    fn first(&self) -> usize;
    /// Whether the group is empty.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// Implements [`AgentGroup`] for a model's group type (generic over the scalar, with fields
/// `name`, `first` and `states`) and its conversions into [`ByScalar`].
macro_rules! agent_group {
    ($group:ident) => {
        impl<S> $crate::scalar::AgentGroup for $group<S> {
            fn name(&self) -> &str {
                &self.name
            }
            fn len(&self) -> usize {
                self.states.len()
            }
            fn first(&self) -> usize {
                self.first
            }
        }
        impl From<$group<f32>> for $crate::scalar::ByScalar<$group<f32>, $group<swarm_core::Fx>> {
            fn from(g: $group<f32>) -> Self {
                $crate::scalar::ByScalar::F32(g)
            }
        }
        impl From<$group<swarm_core::Fx>>
            for $crate::scalar::ByScalar<$group<f32>, $group<swarm_core::Fx>>
        {
            fn from(g: $group<swarm_core::Fx>) -> Self {
                $crate::scalar::ByScalar::Fixed(g)
            }
        }
    };
}
pub(crate) use agent_group;

impl<F: AgentGroup, X: AgentGroup> AgentGroup for ByScalar<F, X> {
    fn name(&self) -> &str {
        by_scalar!(self, g => g.name())
    }
    fn len(&self) -> usize {
        by_scalar!(self, g => g.len())
    }
    fn first(&self) -> usize {
        by_scalar!(self, g => g.first())
    }
}
