//! The ant's own state (xiang2018 §4): position, orientation, label S_c, motion state, timers.

use crate::{Error, Result, Scalar, Vec2};

/// The largest winding of a [`Follow`] (quarter turns): four turns round an obstacle.
pub const WINDING_LIMIT: f32 = 16.0;

/// Largest absolute coordinate accepted from outside: keeps every intermediate value inside the
/// range of [`Fx`](crate::Fx) (±32768) so both scalar types compute the same thing.
pub const COORD_LIMIT: f32 = 16_384.0;

wire_type! {
    /// The status label S_c (xiang2018 §4): where the ant comes from, hence what it can tell.
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
    pub enum Label {
        /// S_nothing: has visited neither a food source nor its nest.
        #[default]
        Nothing,
        /// S_food: has visited a food source and is laden with food.
        Food,
        /// S_nest: has visited its nest (and looks for food).
        Nest,
    }

    /// The four motion states of xiang2018 §4 (Fig. 4a): what the ant did this tick.
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
    pub enum MotionState {
        /// Stays at its position and holds its orientation (§4.1).
        Stop,
        /// Random exploration: a turn within (−θ, θ) (§4.1).
        #[default]
        BasicMovement,
        /// Turned by information from a neighbour (§4.2.1, Table 1).
        InteractNeighbors,
        /// Turned or relabelled by the environment (§4.2.2).
        InteractEnvironment,
    }

    /// Why an ant is stopped (§4.1, the three ways into the stop state).
    #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
    pub enum StopReason {
        /// 1) Casual stop: a rest, probability `p_stop` per tick.
        Casual,
        /// 2) Collecting food at a food source; S_c becomes S_food when the time runs out.
        CollectingFood,
        /// 3) Dropping food at the nest; S_c becomes S_nest when the time runs out.
        DroppingFood,
    }

    /// A running stop (§4.1).
    #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
    pub struct StopTimer {
        /// Why the ant stopped.
        pub reason: StopReason,
        /// Ticks left, ≥ 1 (the ant stays still this many more ticks, including this one).
        pub remaining: u16,
        /// The food source (collecting) or nest (dropping) id; unused for a casual stop.
        pub place: u16,
    }

    /// Which way round an obstacle a following ant goes (ours, see [`Follow`]).
    #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
    pub enum Turn {
        /// Counter-clockwise round the obstacle: along `normal.perp()` = (−n.y, n.x), the
        /// obstacle on the ant's left.
        Ccw,
        /// Clockwise round the obstacle: along `−normal.perp()` = (n.y, −n.x), the obstacle on
        /// the ant's right.
        Cw,
    }

    /// An ant going round an obstacle that blocks the way to its goal (ours: §4.2.2 gives the
    /// avoiding turn of Fig. 5b and the priority of obstacles, not how an ant gets round a wall
    /// or out of a dead end). The ant keeps to the side it chose when it met the obstacle until
    /// the way toward its goal is free again: the goal lies in front of the surface and the
    /// heading has not wound round the obstacle by more than a quarter turn (the counter of
    /// Pledge's wall-following rule, which gets out of any cup).
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct Follow<S> {
        /// The way round.
        pub turn: Turn,
        /// The angle from the goal direction to the way along the surface, followed
        /// continuously since the start, in quarter turns (a *diamond angle*: monotonic in the
        /// angle, exact at every quarter turn; counter-clockwise positive), limited to
        /// ±[`WINDING_LIMIT`].
        pub winding: S,
    }

    /// Everything an ant carries from one tick to the next.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct AntState<S> {
        /// Position p(t).
        pub pos: Vec2<S>,
        /// Moving orientation O(t), a unit vector.
        pub heading: Vec2<S>,
        /// Status label S_c.
        pub label: Label,
        /// Id of the ant's own (belonging) nest.
        pub nest: u16,
        /// Id of the place the label refers to: the food source for `Food`, the nest for
        /// `Nest` (then equal to `nest`); ignored for `Nothing`.
        pub origin: u16,
        /// Where the ant last arrived at its label's place (food collected / nest reached): the
        /// "latest arrival position" a neighbour turns toward (§4.2.1, Fig. 6).
        pub arrival: Vec2<S>,
        /// The place the ant is heading for, if it knows one: the latest arrival position a
        /// neighbour told it (§4.2.1, Fig. 6), or after collecting (dropping) food the nest
        /// (food source) it last came from (§4.1: "start to move toward the nest / back to the
        /// food"). Forgotten on arrival, or when the ant reaches the point and finds nothing.
        pub goal: Option<Vec2<S>>,
        /// Going round an obstacle on the way to the goal.
        pub follow: Option<Follow<S>>,
        /// What the ant did in the last tick.
        pub motion: MotionState,
        /// The running stop, if the ant is stopped (`motion == Stop` exactly when `Some`).
        pub stop: Option<StopTimer>,
    }
}

impl<S: Scalar> AntState<S> {
    /// An ant leaving its nest `nest` at `pos` (the paper's initialisation, §4: p0 at the nest,
    /// S_c = S_nest, a given orientation). `heading` is normalised (zero → +x).
    pub fn at_nest(nest: u16, pos: Vec2<S>, heading: Vec2<S>) -> Self {
        AntState {
            pos,
            heading: heading.normalized().unwrap_or(Vec2::new(S::ONE, S::ZERO)),
            label: Label::Nest,
            nest,
            origin: nest,
            arrival: pos,
            goal: None,
            follow: None,
            motion: MotionState::BasicMovement,
            stop: None,
        }
    }

    /// An ant that has seen nothing yet (S_nothing), e.g. one spawned away from its nest.
    pub fn exploring(nest: u16, pos: Vec2<S>, heading: Vec2<S>) -> Self {
        AntState {
            label: Label::Nothing,
            ..AntState::at_nest(nest, pos, heading)
        }
    }

    /// The same state in another scalar type (through `f32`).
    pub fn cast<T: Scalar>(&self) -> AntState<T> {
        AntState {
            pos: self.pos.cast(),
            heading: self.heading.cast(),
            label: self.label,
            nest: self.nest,
            origin: self.origin,
            arrival: self.arrival.cast(),
            goal: self.goal.map(Vec2::cast),
            follow: self.follow.map(|f| Follow {
                turn: f.turn,
                winding: T::from_f32(f.winding.to_f32()),
            }),
            motion: self.motion,
            stop: self.stop,
        }
    }

    /// Whether the ant stands still this tick.
    pub fn is_stopped(&self) -> bool {
        self.stop.is_some()
    }

    /// Checks the state read from outside: finite coordinates inside [`COORD_LIMIT`], a unit
    /// heading (±1 %), consistent label/origin and stop fields.
    pub fn validate(&self) -> Result<()> {
        check_point(self.pos, "state.pos")?;
        check_point(self.arrival, "state.arrival")?;
        // |heading| in (0.99, 1.01), compared squared (no square root on the hot path); a NaN
        // or infinite component fails the comparison too.
        let l2 = self.heading.length_sq();
        if !(l2 > S::from_f32(0.9801) && l2 < S::from_f32(1.0201)) {
            self.heading.check("state.heading")?;
            return Err(Error::out_of_range("state.heading"));
        }
        if self.label == Label::Nest && self.origin != self.nest {
            return Err(Error::inconsistent("state.origin"));
        }
        if let Some(goal) = self.goal {
            check_point(goal, "state.goal")?;
        }
        if let Some(f) = self.follow {
            if self.goal.is_none() {
                return Err(Error::inconsistent("state.follow"));
            }
            let lim = S::from_f32(WINDING_LIMIT);
            check_range(f.winding, -lim, lim, "state.follow.winding")?;
        }
        match (self.motion, self.stop) {
            (MotionState::Stop, Some(t)) if t.remaining == 0 => {
                Err(Error::out_of_range("state.stop.remaining"))
            }
            (MotionState::Stop, Some(t)) => match (t.reason, self.label) {
                (StopReason::CollectingFood, Label::Food) => {
                    Err(Error::inconsistent("state.stop.reason"))
                }
                (StopReason::DroppingFood, l) if l != Label::Food || t.place != self.nest => {
                    Err(Error::inconsistent("state.stop.reason"))
                }
                _ => Ok(()),
            },
            (MotionState::Stop, None) | (_, Some(_)) => Err(Error::inconsistent("state.stop")),
            _ => Ok(()),
        }
    }
}

/// `Err` unless `p` is finite and inside ±[`COORD_LIMIT`].
#[inline]
pub(crate) fn check_point<S: Scalar>(p: Vec2<S>, field: &'static str) -> Result<Vec2<S>> {
    let lim = S::from_f32(COORD_LIMIT);
    // NaN fails the comparison too; which error it is, is worked out off the hot path.
    if p.x.abs() <= lim && p.y.abs() <= lim {
        return Ok(p);
    }
    p.check(field)?;
    Err(Error::out_of_range(field))
}

/// `Err` unless `v` is finite and within `[lo, hi]`.
pub(crate) fn check_range<S: Scalar>(v: S, lo: S, hi: S, field: &'static str) -> Result<S> {
    if !v.is_finite() {
        return Err(Error::non_finite(field));
    }
    if v < lo || v > hi {
        return Err(Error::out_of_range(field));
    }
    Ok(v)
}
