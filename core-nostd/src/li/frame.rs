//! The li2015 insect's state and sensor frame (spec §1.4, §1.6), with input validation.

use crate::check::check_vec;
use crate::orca3d::{Neighbour, Surface};
use crate::{Result, Scalar, Vec3};

wire_type! {
    /// What an insect carries from one step to the next (spec §1.4).
    #[derive(Clone, Copy, Debug, Default, PartialEq)]
    pub struct LiState<S> {
        /// Position x.
        pub pos: Vec3<S>,
        /// The actual (post-ORCA) velocity.
        pub vel: Vec3<S>,
        /// g: the current waypoint.
        pub waypoint: Vec3<S>,
        /// s: where the current segment began (x − s is the direction it came from).
        pub seg_start: Vec3<S>,
        /// Steps since the waypoint was set ([`LiParams::patience`](super::LiParams)).
        pub age: u16,
    }

    /// The sensor input of one step: up to `N` neighbours within the neighbour distance
    /// (nearest first, ties by id: ORCA's result depends on their order), up to `O` obstacle
    /// surfaces within ORCA's reach (spec §2.4).
    #[derive(Clone, Debug, PartialEq)]
    pub struct LiFrame<S, const N: usize, const O: usize> {
        /// Neighbours, nearest first; an entry with the insect's own id is ignored.
        pub neighbours: heapless::Vec<Neighbour<S>, N>,
        /// Obstacle surfaces: the closest point and the unit normal pointing into the free
        /// space the insect is in.
        pub surfaces: heapless::Vec<Surface<S>, O>,
    }
}

impl<S: Scalar> LiState<S> {
    /// An insect at rest at `pos`, arrived (g = s = x: its first step proposes a waypoint in a
    /// uniform direction, spec §2.2).
    pub fn at(pos: Vec3<S>) -> Self {
        LiState {
            pos,
            vel: Vec3::zero(),
            waypoint: pos,
            seg_start: pos,
            age: 0,
        }
    }

    /// The same state in another scalar type (through `f32`).
    pub fn cast<T: Scalar>(&self) -> LiState<T> {
        LiState {
            pos: self.pos.cast(),
            vel: self.vel.cast(),
            waypoint: self.waypoint.cast(),
            seg_start: self.seg_start.cast(),
            age: self.age,
        }
    }

    /// Checks every vector (`state.pos`, `state.vel`, `state.waypoint`, `state.seg_start`):
    /// finite and within the crate's coordinate limit.
    pub fn validate(&self) -> Result<()> {
        check_vec(self.pos, "state.pos")?;
        check_vec(self.vel, "state.vel")?;
        check_vec(self.waypoint, "state.waypoint")?;
        check_vec(self.seg_start, "state.seg_start")
    }
}

impl<S: Scalar, const N: usize, const O: usize> LiFrame<S, N, O> {
    /// A frame with nothing sensed.
    pub fn new() -> Self {
        LiFrame {
            neighbours: heapless::Vec::new(),
            surfaces: heapless::Vec::new(),
        }
    }

    /// Checks every field: neighbours' `pos` and `vel` within the limit
    /// (`frame.neighbours.pos`, `.vel`) with no id twice (`Inconsistent`,
    /// `frame.neighbours.id`); surfaces' points within the limit and unit normals
    /// (`frame.surfaces.point`, `.normal`). List errors carry the entry's index.
    pub fn validate(&self) -> Result<()> {
        crate::orca3d::check_sensed(&self.neighbours, &self.surfaces)
    }
}

impl<S: Scalar, const N: usize, const O: usize> Default for LiFrame<S, N, O> {
    fn default() -> Self {
        Self::new()
    }
}
