//! 3D ORCA, optimal reciprocal collision avoidance (van den Berg, Guy, Lin and Manocha,
//! *Reciprocal n-body collision avoidance*, ISRR 2009), with the semantics of the reference
//! library RVO2-3D (`Agent::computeNewVelocity`, `linearProgram1..4`), as the ren2016 spec
//! §2.5 prescribes, plus one hard half-space per sensed static obstacle surface (ours).
//!
//! One call of [`solve`] is one agent's velocity decision:
//!
//! 1. the obstacle planes ([`plane::obstacle_plane`]), in the caller's order, then one ORCA
//!    plane per neighbour ([`plane::neighbour_plane`], agent i takes half the responsibility),
//!    nearest first as the caller orders them, at most [`OrcaParams::max_neighbors`];
//! 2. [`lp::linear_program3`]: the velocity closest to the preferred one within the speed
//!    sphere `‖v‖ ≤ max_speed` and every plane;
//! 3. if that is infeasible, the [`Fallback`]: [`Fallback::ZeroVelocity`] (the paper's
//!    default: stop for this frame) or [`Fallback::Lp4`] (RVO2-3D's `linearProgram4`,
//!    minimising the largest penetration of the neighbour planes, obstacle planes kept hard).
//!
//! `no_std`, no allocation (planes in a [`heapless::Vec`] of const capacity `N`), no recursion,
//! no panics. In `f32` the arithmetic follows RVO2-3D operation by operation; a 44-agent run
//! of RVO2-3D's `Sphere` example, given neighbours in RVO2-3D's kd-tree order (exact distance
//! ties included), matches the reference library bit for bit for 100 steps
//! (`tests.rs`, R-T7; the reference comes from `scripts/rvo2-sphere-reference.sh`).
//!
//! **Fixed point.** `Fx` (feature `fixed`) runs the same code, in small-unit scenes only (positions
//! and velocities of a few units: the cone's `|p × u_rel|²/(|p|² − R²)` divides by a small
//! number near contact, squared distances saturate beyond ~181 units, and the parallelism
//! threshold 1e-5 is within a few ulps of I16F16). Its results follow `f32` closely in such
//! scenes, not bit for bit: 1.8e-4 m at most over 160 steps of a head-on pair (positions
//! ±2, radius 0.25; tested within 1e-3), and it is total on random inputs (tested).
//!
//! ## Example
//!
//! ```
//! use swarm_core::orca3d::{self, Body, OrcaParams};
//! use swarm_core::Vec3;
//!
//! let params = OrcaParams::<f32> { time_horizon: 2.0, dt: 0.1, ..OrcaParams::default() };
//! let me = Body { pos: Vec3::new(0.0, 0.0, 0.0), vel: Vec3::new(1.0, 0.0, 0.0), radius: 0.5 };
//! let other = Body { pos: Vec3::new(3.0, 0.2, 0.0), vel: Vec3::new(-1.0, 0.0, 0.0), radius: 0.5 };
//! // Keep flying at 1 m/s along x if possible; N = 8 planes at most.
//! let out = orca3d::solve::<f32, 8>(&me, &[other], &[], me.vel, &params).unwrap();
//! assert!(!out.infeasible);
//! // Head-on within the horizon: the agent veers away from the neighbour (−y).
//! assert!(out.velocity.y < -0.1, "{:?}", out.velocity);
//! ```

pub mod lp;
pub mod plane;

#[cfg(test)]
mod tests;

use heapless::Vec as HVec;

use crate::check::{check_nonneg, check_num, check_vec};
use crate::{Error, Result, Scalar, Vec3};
pub use lp::{
    Line, RVO_EPSILON, linear_program1, linear_program2, linear_program3, linear_program4,
};
pub use plane::{Plane, neighbour_plane, obstacle_plane};

wire_type! {
    /// An agent as ORCA sees it: position, velocity, radius.
    #[derive(Clone, Copy, Debug, Default, PartialEq)]
    pub struct Body<S> {
        /// Position.
        pub pos: Vec3<S>,
        /// Current velocity.
        pub vel: Vec3<S>,
        /// Radius (≥ 0).
        pub radius: S,
    }

    /// A neighbour as a swarm agent senses it (what it broadcast at its last step).
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct Neighbour<S> {
        /// Its agent id.
        pub id: u32,
        /// Its position.
        pub pos: Vec3<S>,
        /// Its current actual velocity.
        pub vel: Vec3<S>,
    }

    /// A sensed static obstacle surface: its point closest to the agent and its outward unit
    /// normal (pointing to the agent's side; container walls point inward).
    #[derive(Clone, Copy, Debug, Default, PartialEq)]
    pub struct Surface<S> {
        /// The surface's point closest to the agent.
        pub point: Vec3<S>,
        /// Outward normal (normalised by [`solve`]; must not be zero).
        pub normal: Vec3<S>,
    }

    /// What [`solve`] does when LP3 is infeasible.
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
    pub enum Fallback {
        /// v_new = 0 for this frame (the ren2016 paper's default).
        #[default]
        ZeroVelocity,
        /// RVO2-3D's `linearProgram4` (least maximal penetration), obstacle planes kept hard.
        Lp4,
    }

    /// ORCA's parameters (RVO2-3D's agent defaults less `neighborDist`, which belongs to the
    /// caller's neighbour search).
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct OrcaParams<S> {
        /// τ: time horizon (s, > 0).
        pub time_horizon: S,
        /// Δt: simulation time step (s, > 0), the horizon of the collision case.
        pub dt: S,
        /// Radius of the speed sphere (≥ 0).
        pub max_speed: S,
        /// How many neighbours (the first ones given) take part.
        pub max_neighbors: u16,
        /// What acts when LP3 is infeasible.
        pub fallback: Fallback,
    }

    /// The decision of [`solve`].
    #[derive(Clone, Copy, Debug, Default, PartialEq)]
    pub struct Solution<S> {
        /// The new velocity.
        pub velocity: Vec3<S>,
        /// Whether LP3 was infeasible (then [`Solution::fallback`] says what acted).
        pub infeasible: bool,
        /// The fallback that produced `velocity`, `None` when LP3 succeeded.
        pub fallback: Option<Fallback>,
        /// The index of the plane LP3 failed on (obstacle planes first), if it failed.
        pub failed_plane: Option<u16>,
        /// How many planes the program had (obstacles + neighbours).
        pub planes: u16,
    }
}

impl Fallback {
    /// The fallback of a model parameter's code: 1 is [`Fallback::Lp4`], anything else
    /// [`Fallback::ZeroVelocity`] (the models' `fallback` fields: 0 stop, 1 lp4).
    pub fn of_code(code: u8) -> Self {
        if code == 1 {
            Fallback::Lp4
        } else {
            Fallback::ZeroVelocity
        }
    }
}

impl<S: Scalar> Default for OrcaParams<S> {
    /// ren2016 spec §2.5: τ = 0.5 s, max speed 10; ours Δt = 0.01 s, 10 neighbours, the
    /// paper's zero-velocity fallback.
    fn default() -> Self {
        OrcaParams {
            time_horizon: S::from_f32(0.5),
            dt: S::from_f32(0.01),
            max_speed: S::from_f32(10.0),
            max_neighbors: 10,
            fallback: Fallback::ZeroVelocity,
        }
    }
}

impl<S: Scalar> OrcaParams<S> {
    /// `Err(BadParam)` unless τ and Δt are finite and positive and `max_speed` is finite and
    /// non-negative (all within the crate's coordinate limit).
    pub fn validate(&self) -> Result<()> {
        let pos = |v: S, field: &'static str| {
            if check_num(v, field).is_ok() && v > S::ZERO {
                Ok(())
            } else {
                Err(Error::BadParam { field })
            }
        };
        pos(self.time_horizon, "time_horizon")?;
        pos(self.dt, "dt")?;
        check_nonneg(self.max_speed, "max_speed")
            .map_err(|_| Error::BadParam { field: "max_speed" })
    }
}

/// Checks a body's numbers (field names for the agent or a neighbour).
fn check_body<S: Scalar>(
    b: &Body<S>,
    pos: &'static str,
    vel: &'static str,
    r: &'static str,
) -> Result<()> {
    check_vec(b.pos, pos)?;
    check_vec(b.vel, vel)?;
    check_nonneg(b.radius, r)
}

/// Checks a sensor frame's neighbours and surfaces: positions and velocities within the
/// crate's limit (`frame.neighbours.pos`, `.vel`) with no id twice (`Inconsistent`,
/// `frame.neighbours.id`); surfaces' points within the limit and unit normals
/// (`frame.surfaces.point`, `.normal`). Errors carry the entry's index.
pub(crate) fn check_sensed<S: Scalar>(
    neighbours: &[Neighbour<S>],
    surfaces: &[Surface<S>],
) -> Result<()> {
    for (i, n) in neighbours.iter().enumerate() {
        check_vec(n.pos, "frame.neighbours.pos").map_err(|e| e.at(i))?;
        check_vec(n.vel, "frame.neighbours.vel").map_err(|e| e.at(i))?;
        if neighbours[..i].iter().any(|o| o.id == n.id) {
            return Err(Error::inconsistent("frame.neighbours.id").at(i));
        }
    }
    for (i, s) in surfaces.iter().enumerate() {
        check_vec(s.point, "frame.surfaces.point").map_err(|e| e.at(i))?;
        crate::check::check_unit(s.normal, "frame.surfaces.normal").map_err(|e| e.at(i))?;
    }
    Ok(())
}

/// ORCA for agent `id` of a swarm from its sensor frame (ren2016 Algorithm 1 step 6, li2015
/// §4.1): the obstacle `surfaces` first, then the first min(`params.max_neighbors`,
/// `N` − surfaces) of `neighbours` (nearest first as given; an entry with the agent's own id
/// is skipped), every body of radius `radius`, by [`solve`] with plane capacity `N`.
///
/// # Errors
///
/// As [`solve`].
#[allow(clippy::too_many_arguments)]
pub fn solve_frame<S: Scalar, const N: usize>(
    id: u32,
    pos: Vec3<S>,
    vel: Vec3<S>,
    radius: S,
    neighbours: &[Neighbour<S>],
    surfaces: &[Surface<S>],
    pref: Vec3<S>,
    params: &OrcaParams<S>,
) -> Result<Solution<S>> {
    let body = |pos, vel| Body { pos, vel, radius };
    let room = N.saturating_sub(surfaces.len());
    let mut others: HVec<Body<S>, N> = HVec::new();
    for n in neighbours.iter().filter(|n| n.id != id).take(room) {
        // At most `room` ≤ N entries: no push can fail.
        let _ = others.push(body(n.pos, n.vel));
    }
    solve::<S, N>(&body(pos, vel), &others, surfaces, pref, params)
}

/// One agent's ORCA velocity (ren2016 spec §2.5, RVO2-3D `computeNewVelocity`): obstacle
/// planes, then the planes of the first `max_neighbors` of `neighbours` (nearest first, the
/// caller's order), LP3 toward `pref` within `‖v‖ ≤ max_speed`, and the [`Fallback`] when
/// that is infeasible.
///
/// `N` is the plane capacity: `obstacles.len()` plus the neighbours used must fit, else
/// `Err(OutOfRange("neighbours"))` (nothing is dropped silently). Errors: `BadParam` for
/// invalid [`OrcaParams`], `NonFinite`/`OutOfRange` naming the input (`agent.pos`,
/// `neighbours.vel` with its index, `obstacles.normal`, `pref`, ...).
pub fn solve<S: Scalar, const N: usize>(
    agent: &Body<S>,
    neighbours: &[Body<S>],
    obstacles: &[Surface<S>],
    pref: Vec3<S>,
    params: &OrcaParams<S>,
) -> Result<Solution<S>> {
    params.validate()?;
    check_body(agent, "agent.pos", "agent.vel", "agent.radius")?;
    check_vec(pref, "pref")?;
    let used = neighbours
        .get(..usize::from(params.max_neighbors).min(neighbours.len()))
        .unwrap_or(neighbours);
    for (i, n) in used.iter().enumerate() {
        check_body(n, "neighbours.pos", "neighbours.vel", "neighbours.radius")
            .map_err(|e| e.at(i))?;
    }
    if obstacles.len() + used.len() > N {
        return Err(Error::OutOfRange {
            field: "neighbours",
            index: None,
        });
    }

    let inv_tau = S::ONE / params.time_horizon;
    let inv_dt = S::ONE / params.dt;
    let mut planes: HVec<Plane<S>, N> = HVec::new();
    for (i, o) in obstacles.iter().enumerate() {
        check_vec(o.point, "obstacles.point").map_err(|e| e.at(i))?;
        check_vec(o.normal, "obstacles.normal").map_err(|e| e.at(i))?;
        let n = o.normal.normalized().ok_or(Error::OutOfRange {
            field: "obstacles.normal",
            index: Some(u16::try_from(i).unwrap_or(u16::MAX)),
        })?;
        let surface = Surface {
            point: o.point,
            normal: n,
        };
        let p = obstacle_plane(agent, &surface, inv_tau, inv_dt);
        planes
            .push(p)
            .map_err(|_| Error::out_of_range("obstacles"))?;
    }
    let hard = planes.len();
    for n in used {
        if let Some(p) = neighbour_plane(agent, n, inv_tau, inv_dt) {
            planes
                .push(p)
                .map_err(|_| Error::out_of_range("neighbours"))?;
        }
    }

    let count = u16::try_from(planes.len()).unwrap_or(u16::MAX);
    let (v, fail) = linear_program3(&planes, params.max_speed, pref, false);
    if fail >= planes.len() {
        return Ok(Solution {
            velocity: v,
            infeasible: false,
            fallback: None,
            failed_plane: None,
            planes: count,
        });
    }
    let velocity = match params.fallback {
        Fallback::ZeroVelocity => Vec3::zero(),
        Fallback::Lp4 => linear_program4::<S, N>(&planes, fail, hard, params.max_speed, v),
    };
    Ok(Solution {
        velocity,
        infeasible: true,
        fallback: Some(params.fallback),
        failed_plane: Some(u16::try_from(fail).unwrap_or(u16::MAX)),
        planes: count,
    })
}
