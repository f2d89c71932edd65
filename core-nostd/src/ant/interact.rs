//! Interactions (xiang2018 §4.2): information transfer with neighbours (Table 1) and the
//! environment with priority obstacles > disturbance > food = nest (Fig. 4b).

use super::frame::{AntNeighbor, AntObject};
use super::obstacle::obstacle_heading;
use super::params::AntParams;
use super::state::{AntState, Follow, Label};
use crate::rand::{self, stream};
use crate::{Scalar, StepCtx, Vec2};

/// Whether neighbour `j` can tell ant `i` about `i`'s destination (Table 1, §4.2.1):
///
/// | S_c^i   | S_c^j | transfer                                       |
/// |---------|-------|------------------------------------------------|
/// | Nothing | Food  | situation 1: the food source j comes from      |
/// | Nest    | Food  | situation 2: the food source j comes from      |
/// | Food    | Nest  | situation 3: the nest j comes from — only if it is *i's own* nest |
///
/// Every other pair transfers nothing.
pub fn transfers<S: Scalar>(i: &AntState<S>, j: &AntNeighbor<S>) -> bool {
    match (i.label, j.label) {
        (Label::Nothing | Label::Nest, Label::Food) => true,
        (Label::Food, Label::Nest) => j.nest == i.nest,
        _ => false,
    }
}

/// Algorithm 2: among the neighbours in contact range that transfer information, the nearest
/// (ties: the lower id) — returns its latest arrival position, the point ant `i` turns toward
/// (Fig. 6).
pub fn informer<S: Scalar>(
    i: &AntState<S>,
    neighbours: &[AntNeighbor<S>],
    params: &AntParams<S>,
) -> Option<Vec2<S>> {
    // Distances, not squared distances: squares saturate in fixed point beyond ~181.
    let mut best: Option<(S, u32, Vec2<S>)> = None;
    for j in neighbours.iter().filter(|j| transfers(i, j)) {
        let d = (j.pos - i.pos).length();
        if d > params.contact_range {
            continue;
        }
        let better = match best {
            None => true,
            Some((bd, bid, _)) => d < bd || (d == bd && j.id < bid),
        };
        if better {
            best = Some((d, j.id, j.arrival));
        }
    }
    best.map(|(_, _, arrival)| arrival)
}

/// What the environment makes the ant do this tick (at most one thing, by priority).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum EnvAction<S> {
    /// Nothing in the environment concerns the ant.
    None,
    /// Avoiding an obstacle: turn to this heading (Fig. 5b), and keep going round it toward the
    /// goal with this [`Follow`] (ours, see [`obstacle_heading`]).
    Avoid(Vec2<S>, Option<Follow<S>>),
    /// Escaping: run along this heading, away from the disturbance centre (Fig. 5c).
    Escape(Vec2<S>),
    /// Arrived unladen at food source `id`: stop and collect (§4.1 stop 2).
    Collect(u16),
    /// Arrived laden at its own nest `id`: stop and drop the food (§4.1 stop 3).
    Drop(u16),
    /// Arrived at its own nest: S_nothing becomes S_nest without stopping, and an S_nest ant
    /// refreshes its latest arrival position (§4.2.2).
    AtNest,
}

/// The environment interaction of §4.2.2 for an ant at `s.pos` heading `s.heading`, by
/// priority:
///
/// * Food / nest where the ant stops: it is inside the circle of a food source (unladen) or of
///   its own nest (laden). Ours: before obstacles, of which the paper says they come first,
///   because a stop never runs into anything, and an ant going round a rock next to its nest
///   would otherwise never drop its food.
/// * Obstacle: see [`obstacle_heading`].
/// * Disturbance: the ant is inside the dangerous circle; runs away from the centre (nearest
///   centre if several; a random direction if exactly on the centre).
/// * Its own nest, unladen: relabels as S_nest.
pub fn environment<S: Scalar>(
    s: &AntState<S>,
    objects: &[AntObject<S>],
    params: &AntParams<S>,
    ctx: StepCtx,
) -> EnvAction<S> {
    let mut at_nest = false;
    for o in objects {
        match *o {
            AntObject::Food { id, center, radius }
                if s.label != Label::Food && inside(s.pos, center, radius) =>
            {
                return EnvAction::Collect(id);
            }
            AntObject::Nest { id, center, radius }
                if id == s.nest && inside(s.pos, center, radius) =>
            {
                if s.label == Label::Food {
                    return EnvAction::Drop(id);
                }
                at_nest = true;
            }
            _ => {}
        }
    }
    if let Some((h, follow)) = obstacle_heading(s, s.heading, objects, params, ctx) {
        return EnvAction::Avoid(h, follow);
    }
    if let Some(h) = escape_disturbance(s, objects, ctx) {
        return EnvAction::Escape(h);
    }
    if at_nest {
        return EnvAction::AtNest;
    }
    EnvAction::None
}

fn inside<S: Scalar>(p: Vec2<S>, center: Vec2<S>, radius: S) -> bool {
    (p - center).length() <= radius
}

/// The object nearest to the ant among those `pick` accepts; `pick` gives its distance and a
/// direction vector.
fn nearest<S: Scalar>(
    objects: &[AntObject<S>],
    pick: impl Fn(&AntObject<S>) -> Option<(S, Vec2<S>)>,
) -> Option<Vec2<S>> {
    let mut best: Option<(S, Vec2<S>)> = None;
    for (dist, v) in objects.iter().filter_map(pick) {
        if best.is_none_or(|(bd, _)| dist < bd) {
            best = Some((dist, v));
        }
    }
    best.map(|(_, v)| v)
}

fn escape_disturbance<S: Scalar>(
    s: &AntState<S>,
    objects: &[AntObject<S>],
    ctx: StepCtx,
) -> Option<Vec2<S>> {
    let away = nearest(objects, |o| match *o {
        AntObject::Disturbance { center, radius } => {
            let away = s.pos - center;
            let dist = away.length();
            (dist < radius).then_some((dist, away))
        }
        _ => None,
    })?;
    Some(away.normalized().unwrap_or_else(|| {
        let a = rand::angle(ctx, stream::ANT_FALLBACK, crate::scalar::pi::<S>());
        Vec2::from_angle(a)
    }))
}
