//! What an ant senses: the sensor frames of the two phases of a tick (xiang2018 §3-4).
//!
//! A real robot fills these from its sensors and radio; the simulator fills them from the
//! world with exactly the same meaning.

use heapless::Vec;

use super::state::{Label, check_point, check_range};
use crate::{Error, Rect, Result, Scalar, Vec2};

wire_type! {
    /// A neighbour as sensed in the plan phase: what body contact tells (§4.2.1, Fig. 6).
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct AntNeighbor<S> {
        /// The neighbour's id (unique in the frame, never the sensing ant's own id).
        pub id: u32,
        /// Its position p_j(t).
        pub pos: Vec2<S>,
        /// Its label S_c^j.
        pub label: Label,
        /// Its home nest.
        pub nest: u16,
        /// The place its label refers to (food source id for `Food`, its nest for `Nest`).
        pub origin: u16,
        /// Its latest arrival position at that place.
        pub arrival: Vec2<S>,
    }

    /// An object of the environment in sensing range (§4.2.2, Fig. 4b).
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub enum AntObject<S> {
        /// An obstacle, given by the closest point of its boundary to the ant.
        Obstacle {
            /// Closest boundary point.
            closest: Vec2<S>,
        },
        /// An external disturbance: a dangerous circle.
        Disturbance {
            /// Centre of the attack.
            center: Vec2<S>,
            /// Radius of the dangerous circle.
            radius: S,
        },
        /// A food source (a circle).
        Food {
            /// Food source id.
            id: u16,
            /// Centre.
            center: Vec2<S>,
            /// Radius: the ant has arrived when inside it.
            radius: S,
        },
        /// A nest (a circle).
        Nest {
            /// Nest id.
            id: u16,
            /// Centre.
            center: Vec2<S>,
            /// Radius: the ant has arrived when inside it.
            radius: S,
        },
    }

    /// The sensor frame of `plan`: neighbours in contact range, nearby objects, the arena.
    ///
    /// `N` and `O` are the capacities (neighbours, objects), fixed at compile time.
    #[derive(Clone, Debug, PartialEq)]
    pub struct PlanFrame<S, const N: usize, const O: usize> {
        /// The arena (boundary check, §4.3).
        pub bounds: Rect<S>,
        /// Neighbours; those beyond `contact_range` are ignored.
        pub neighbours: Vec<AntNeighbor<S>, N>,
        /// Objects in sensing range.
        pub objects: Vec<AntObject<S>, O>,
    }

    /// The sensor frame of `resolve`: the neighbours' broadcast plans (predicted positions
    /// p_d*(t+1), eq. 1) and the arena.
    #[derive(Clone, Debug, PartialEq)]
    pub struct ResolveFrame<S, const N: usize> {
        /// The arena.
        pub bounds: Rect<S>,
        /// Predicted positions of nearby ants; those farther than `collision_range` from the
        /// ant's own prediction are ignored.
        pub neighbours: Vec<Vec2<S>, N>,
    }
}

impl<S: Scalar, const N: usize, const O: usize> PlanFrame<S, N, O> {
    /// An empty frame in `bounds`.
    pub fn new(bounds: Rect<S>) -> Self {
        PlanFrame {
            bounds,
            neighbours: Vec::new(),
            objects: Vec::new(),
        }
    }

    /// Checks every field; `agent` is the sensing ant's own id.
    pub fn validate(&self, agent: u32) -> Result<()> {
        check_bounds(self.bounds)?;
        for (i, n) in self.neighbours.iter().enumerate() {
            check_point(n.pos, "neighbours.pos").map_err(|e| e.at(i))?;
            check_point(n.arrival, "neighbours.arrival").map_err(|e| e.at(i))?;
            if n.id == agent || self.neighbours[..i].iter().any(|m| m.id == n.id) {
                return Err(Error::inconsistent("neighbours.id").at(i));
            }
            if n.label == Label::Nest && n.origin != n.nest {
                return Err(Error::inconsistent("neighbours.origin").at(i));
            }
        }
        let big = S::from_f32(super::state::COORD_LIMIT);
        for (i, o) in self.objects.iter().enumerate() {
            let r = match *o {
                AntObject::Obstacle { closest } => {
                    check_point(closest, "objects.closest").map(|_| ())
                }
                AntObject::Disturbance { center, radius }
                | AntObject::Food { center, radius, .. }
                | AntObject::Nest { center, radius, .. } => check_point(center, "objects.center")
                    .and_then(|_| check_range(radius, S::EPS, big, "objects.radius"))
                    .map(|_| ()),
            };
            r.map_err(|e| e.at(i))?;
        }
        Ok(())
    }
}

impl<S: Scalar, const N: usize> ResolveFrame<S, N> {
    /// An empty frame in `bounds`.
    pub fn new(bounds: Rect<S>) -> Self {
        ResolveFrame {
            bounds,
            neighbours: Vec::new(),
        }
    }

    /// Checks every field.
    pub fn validate(&self) -> Result<()> {
        check_bounds(self.bounds)?;
        for (i, p) in self.neighbours.iter().enumerate() {
            check_point(*p, "neighbours").map_err(|e| e.at(i))?;
        }
        Ok(())
    }
}

fn check_bounds<S: Scalar>(b: Rect<S>) -> Result<()> {
    check_point(b.min, "bounds")?;
    check_point(b.max, "bounds")?;
    if b.min.x < b.max.x && b.min.y < b.max.y {
        Ok(())
    } else {
        Err(Error::out_of_range("bounds"))
    }
}
