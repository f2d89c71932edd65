//! The walker's controller (what would be its folder in `swarm-core`): each tick an agent
//! turns to a random heading and steps `speed` forward; a step through a wall (at
//! ±`half_width` on both axes) is mirrored back inside and counted.

use serde::{Deserialize, Serialize};
use swarm_core::model::{Model, Phase, Range};
use swarm_core::wire::{Capacities, Controller, ControllerKind};
use swarm_core::{Checked, Error, Result, Scalar, StepCtx, Vec2, rand};

/// The walker's parameters.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct WalkParams<S> {
    /// Step length.
    pub speed: S,
    /// The walls stand at ±`half_width` on both axes.
    pub half_width: S,
}

swarm_core::model_params! {
    WalkParams {
        speed: real = Range::above(0.0, 10.0), "units/tick";
        half_width: real = Range::above(0.0, 1000.0), "units";
    }
    together step_fits
}

impl<S: Scalar> WalkParams<S> {
    /// The same parameters in scalar `T` (through `f32`).
    pub fn cast<T: Scalar>(&self) -> WalkParams<T> {
        WalkParams {
            speed: T::from_f32(self.speed.to_f32()),
            half_width: T::from_f32(self.half_width.to_f32()),
        }
    }

    /// A step longer than the box's half width could be reflected and still land outside.
    fn step_fits(&self) -> Result<()> {
        if self.speed > self.half_width {
            return Err(Error::BadParam { field: "speed" });
        }
        Ok(())
    }
}

impl<S: Scalar> Default for WalkParams<S> {
    fn default() -> Self {
        WalkParams {
            speed: S::from_f32(0.5),
            half_width: S::from_f32(20.0),
        }
    }
}

/// What a walker carries from tick to tick.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct WalkState<S> {
    /// Position.
    pub pos: Vec2<S>,
    /// Heading of the last step (unit length).
    pub heading: Vec2<S>,
    /// Walls hit so far.
    pub bounces: u32,
}

/// Request: take one step.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct WalkRequest<S> {
    /// The walker's state.
    pub state: WalkState<S>,
    /// Seed, id and step: the inputs of its random heading.
    pub ctx: StepCtx,
}

/// Reply: the state after the step.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct WalkReply<S> {
    /// The new state.
    pub state: WalkState<S>,
}

swarm_core::message_kinds! {
    WalkRequest = 0x80;
    WalkReply = 0x81;
}

/// The walker's one phase.
#[derive(Clone, Copy, Debug)]
pub struct Walk;

/// Mirrors `x` back inside `[-w, w]`; whether it had to.
fn reflect<S: Scalar>(x: &mut S, w: S) -> bool {
    if *x > w {
        *x = w + w - *x;
        true
    } else if *x < -w {
        *x = -w - w - *x;
        true
    } else {
        false
    }
}

impl<S: Scalar> Phase<WalkParams<S>> for Walk {
    const NAME: &'static str = "walk";
    type Request = WalkRequest<S>;
    type Reply = WalkReply<S>;

    fn run(params: &Checked<WalkParams<S>>, req: &WalkRequest<S>) -> Result<WalkReply<S>> {
        let (p, w) = (req.state.pos, params.half_width);
        if !(p.x.is_finite() && p.y.is_finite()) {
            return Err(Error::NonFinite {
                field: "pos",
                index: None,
            });
        }
        if p.x.abs() > w || p.y.abs() > w {
            return Err(Error::OutOfRange {
                field: "pos",
                index: None,
            });
        }
        let heading = Vec2::from_angle(rand::angle(req.ctx, 0, S::from_f32(core::f32::consts::PI)));
        let mut next = p + heading * params.speed;
        let hit_x = reflect(&mut next.x, w);
        let hit_y = reflect(&mut next.y, w);
        Ok(WalkReply {
            state: WalkState {
                pos: next,
                heading,
                bounces: req.state.bounces + u32::from(hit_x) + u32::from(hit_y),
            },
        })
    }
}

impl<S: Scalar> Model for WalkParams<S> {
    const NAME: &'static str = "walker";
    type State = WalkState<S>;
    type Phases = (Walk,);
}

impl<S: Scalar + Serialize + serde::de::DeserializeOwned> Controller for WalkParams<S> {
    /// A number from the range kept for applications and tests.
    const KIND: ControllerKind = ControllerKind(200);
    const CAPACITIES: Capacities = Capacities::NONE;
    // State (two vectors and a varint) and context: well below these.
    const MAX_REQUEST_PAYLOAD: usize = 64;
    const MAX_REPLY_PAYLOAD: usize = 48;
}
