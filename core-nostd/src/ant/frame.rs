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

    /// A point of an obstacle's surface near the ant and the surface's outward normal there:
    /// what a range or bump sensor reports. The obstacle (or the convex piece of it this point
    /// belongs to: an edge of a polygon, a disc) lies behind the line through `closest`
    /// perpendicular to `normal`, so staying in front of that line keeps the ant out of it.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct Surface<S> {
        /// The surface point closest to the ant.
        pub closest: Vec2<S>,
        /// Unit normal at `closest`, pointing out of the obstacle into free space. For an ant
        /// outside a convex piece it is the direction from `closest` to the ant; for an ant
        /// inside an obstacle it points from the ant through `closest`, the way out.
        pub normal: Vec2<S>,
    }

    /// An object of the environment in sensing range (§4.2.2, Fig. 4b).
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub enum AntObject<S> {
        /// An obstacle, given by the closest point of its boundary to the ant and the outward
        /// normal there.
        Obstacle(Surface<S>),
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
    /// p_d*(t+1), eq. 1), the obstacle surfaces within one step, and the arena.
    #[derive(Clone, Debug, PartialEq)]
    pub struct ResolveFrame<S, const N: usize> {
        /// The arena.
        pub bounds: Rect<S>,
        /// Predicted positions of nearby ants; those farther than `collision_range` from the
        /// ant's own prediction are ignored.
        pub neighbours: Vec<Vec2<S>, N>,
        /// The obstacle surfaces the move of eq. 5 could reach: one [`Surface`] per convex
        /// piece (a disc, a polygon edge) within `speed·dt` of the ant, nearest first. The move
        /// never crosses one of them ([`constrain`](super::constrain)); a piece missing from
        /// the frame is not avoided.
        pub obstacles: Vec<Surface<S>, SURFACES>,
    }
}

/// Capacity of [`ResolveFrame::obstacles`]: the obstacle pieces within one step of an ant (a
/// corner is two, a narrow gap four).
pub const SURFACES: usize = 6;

impl<S: Scalar> Surface<S> {
    /// The surface point `closest` as seen by an ant at `at` outside the obstacle: the normal
    /// points from `closest` to the ant (`None` if they coincide).
    pub fn seen_from(at: Vec2<S>, closest: Vec2<S>) -> Option<Self> {
        let normal = (at - closest).normalized()?;
        Some(Surface { closest, normal })
    }

    /// The same surface in another scalar type (through `f32`).
    pub fn cast<T: Scalar>(&self) -> Surface<T> {
        Surface {
            closest: self.closest.cast(),
            normal: self.normal.cast(),
        }
    }

    /// Checks the point (finite, inside the coordinate limit) and that the normal is a unit
    /// vector (±2 %).
    pub fn validate(&self) -> Result<()> {
        self.check("closest", "normal")
    }

    /// [`Surface::validate`] naming the fields as the frame knows them.
    pub(crate) fn check(&self, closest: &'static str, normal: &'static str) -> Result<()> {
        check_point(self.closest, closest)?;
        let l2 = self.normal.length_sq();
        if !(l2 > S::from_f32(0.96) && l2 < S::from_f32(1.04)) {
            self.normal.check(normal)?;
            return Err(Error::out_of_range(normal));
        }
        Ok(())
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
            self.check_neighbour(i, n, agent).map_err(|e| e.at(i))?;
        }
        for (i, o) in self.objects.iter().enumerate() {
            check_object(o).map_err(|e| e.at(i))?;
        }
        Ok(())
    }

    /// Neighbour `i` (`n`): its points, an id other than the ant's and the earlier
    /// neighbours', a consistent origin.
    fn check_neighbour(&self, i: usize, n: &AntNeighbor<S>, agent: u32) -> Result<()> {
        check_point(n.pos, "neighbours.pos")?;
        check_point(n.arrival, "neighbours.arrival")?;
        if n.id == agent || self.neighbours[..i].iter().any(|m| m.id == n.id) {
            return Err(Error::inconsistent("neighbours.id"));
        }
        if n.label == Label::Nest && n.origin != n.nest {
            return Err(Error::inconsistent("neighbours.origin"));
        }
        Ok(())
    }
}

/// An object of a plan frame: a finite point and, for a disc, a positive radius.
fn check_object<S: Scalar>(o: &AntObject<S>) -> Result<()> {
    match *o {
        AntObject::Obstacle(surface) => surface.check("objects.closest", "objects.normal"),
        AntObject::Disturbance { center, radius }
        | AntObject::Food { center, radius, .. }
        | AntObject::Nest { center, radius, .. } => {
            check_point(center, "objects.center")?;
            let big = S::from_f32(super::state::COORD_LIMIT);
            check_range(radius, S::EPS, big, "objects.radius").map(|_| ())
        }
    }
}

impl<S: Scalar, const N: usize> ResolveFrame<S, N> {
    /// An empty frame in `bounds`.
    pub fn new(bounds: Rect<S>) -> Self {
        ResolveFrame {
            bounds,
            neighbours: Vec::new(),
            obstacles: Vec::new(),
        }
    }

    /// Checks every field.
    pub fn validate(&self) -> Result<()> {
        check_bounds(self.bounds)?;
        for (i, p) in self.neighbours.iter().enumerate() {
            check_point(*p, "neighbours").map_err(|e| e.at(i))?;
        }
        for (i, s) in self.obstacles.iter().enumerate() {
            s.check("obstacles.closest", "obstacles.normal")
                .map_err(|e| e.at(i))?;
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
