//! The insect's state and its two sensor frames (advect, separate), with input validation.
//!
//! World coordinates, y up, metres (spec §1.3).

use crate::check::{check_length, check_nonneg, check_unit, check_vec};
use crate::{Error, Result, Scalar, Vec3};

/// The largest boundary curvature 1/ρ accepted in a frame (1/m): a radius of curvature of
/// 1 cm or more. Keeps the curvature term H_d·P of the bounded curl (at most
/// 100·1.04·gain ≤ 1700 for gain ≤ 16) inside the range of [`Fx`](crate::Fx).
pub const MAX_CURVATURE: f32 = 100.0;

/// The longest accepted navigation direction ([`AdvectFrame::guide`]): a unit vector with
/// 1 % slack, or shorter (trilinear interpolation of unit vectors shortens them).
pub const MAX_GUIDE: f32 = 1.01;

wire_type! {
    /// What an insect carries from one step to the next (spec §1.4): the model is first
    /// order, so only its position; its velocity is an output.
    #[derive(Clone, Copy, Debug, Default, PartialEq)]
    pub struct WangState<S> {
        /// Position x.
        pub pos: Vec3<S>,
        /// The velocity V = V_l + V_g (eq. 9, plus the phototaxis bias) used in the last step
        /// (for rendering and metrics; not read by the step).
        pub vel: Vec3<S>,
    }

    /// The nearest boundary surface within d0: the "n" of eq. 2, and the curvature of the
    /// distance field there (ours, spec §2.1: the Hessian H_d of the distance, which the
    /// closed form of ∇ × N needs to be exact off planes).
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct Boundary<S> {
        /// The closest point of the surface.
        pub point: Vec3<S>,
        /// The outward unit normal there, pointing into the free space the insect is in
        /// (length 1 ± 1 %).
        pub normal: Vec3<S>,
        /// 1/ρ of the distance field's Hessian H_d: 0 for a plane (or box face), 1/|x − c|
        /// for a sphere of centre c, 1/ρ_xz for the side of a vertical shaft; ≥ 0 and at most
        /// [`MAX_CURVATURE`]. A device that cannot tell sends 0 (locally planar).
        pub curvature: S,
        /// The unit axis of a cylindrical boundary (a shaft), zero otherwise:
        /// H_d = curvature·(I − n nᵀ − a aᵀ).
        pub axis: Vec3<S>,
    }

    /// The advect phase's sensor input (spec §1.6 step 1).
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct AdvectFrame<S> {
        /// The unit descent direction −∇C/‖∇C‖ of the cost field at the insect (eq. 8), or
        /// zero inside the goal (ours); V_g = s0·guide. Length at most [`MAX_GUIDE`].
        pub guide: Vec3<S>,
        /// The nearest boundary within d0, if any (eq. 2); none: V_l = ∇ × P.
        pub boundary: Option<Boundary<S>>,
        /// The phototaxis lamp holder (§7), if any.
        pub lamp: Option<Vec3<S>>,
    }

    /// A neighbour as the separate phase sees it: its id and its tentative position x*_j.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct Close<S> {
        /// Its agent id (the coincident-pair draw uses the lower id of the pair).
        pub id: u32,
        /// Its tentative position x*_j (its advect reply).
        pub pos: Vec3<S>,
    }

    /// The separate phase's sensor input: up to `K` neighbours' tentative positions (MDE,
    /// §6).
    #[derive(Clone, Debug, PartialEq)]
    pub struct SeparateFrame<S, const K: usize> {
        /// The neighbours; those not closer than d_min and an entry with the insect's own id
        /// are ignored.
        pub neighbours: heapless::Vec<Close<S>, K>,
    }
}

impl<S: Scalar> WangState<S> {
    /// An insect at `pos`, at rest.
    pub fn new(pos: Vec3<S>) -> Self {
        WangState {
            pos,
            vel: Vec3::zero(),
        }
    }

    /// The same state in another scalar type (through `f32`).
    pub fn cast<T: Scalar>(&self) -> WangState<T> {
        WangState {
            pos: self.pos.cast(),
            vel: self.vel.cast(),
        }
    }

    /// Checks both fields: finite and within ±[`LIMIT`](super::params::LIMIT)
    /// (`{prefix}.pos`, `{prefix}.vel` with prefix `state` or `moved`).
    pub fn validate(&self) -> Result<()> {
        self.validate_as("state.pos", "state.vel")
    }

    pub(crate) fn validate_as(&self, pos: &'static str, vel: &'static str) -> Result<()> {
        check_vec(self.pos, pos)?;
        check_vec(self.vel, vel)
    }
}

impl<S: Scalar> Boundary<S> {
    /// A planar boundary (curvature 0, no axis).
    pub fn plane(point: Vec3<S>, normal: Vec3<S>) -> Self {
        Boundary {
            point,
            normal,
            curvature: S::ZERO,
            axis: Vec3::zero(),
        }
    }

    /// The same boundary in another scalar type (through `f32`).
    pub fn cast<T: Scalar>(&self) -> Boundary<T> {
        Boundary {
            point: self.point.cast(),
            normal: self.normal.cast(),
            curvature: T::from_f32(self.curvature.to_f32()),
            axis: self.axis.cast(),
        }
    }

    /// Checks: `point` a vector within the limit; `normal` a unit vector (±1 %); `curvature`
    /// in [0, [`MAX_CURVATURE`]]; `axis` zero or a unit vector (±1 %).
    pub fn validate(&self) -> Result<()> {
        check_vec(self.point, "frame.boundary.point")?;
        check_unit(self.normal, "frame.boundary.normal")?;
        check_nonneg(self.curvature, "frame.boundary.curvature")?;
        if self.curvature > S::from_f32(MAX_CURVATURE) {
            return Err(Error::out_of_range("frame.boundary.curvature"));
        }
        check_vec(self.axis, "frame.boundary.axis")?;
        if self.axis != Vec3::zero() {
            check_unit(self.axis, "frame.boundary.axis")?;
        }
        Ok(())
    }
}

impl<S: Scalar> AdvectFrame<S> {
    /// A frame with the navigation direction `guide`, no boundary and no lamp.
    pub fn new(guide: Vec3<S>) -> Self {
        AdvectFrame {
            guide,
            boundary: None,
            lamp: None,
        }
    }

    /// The same frame in another scalar type (through `f32`).
    pub fn cast<T: Scalar>(&self) -> AdvectFrame<T> {
        AdvectFrame {
            guide: self.guide.cast(),
            boundary: self.boundary.as_ref().map(Boundary::cast),
            lamp: self.lamp.map(Vec3::cast),
        }
    }

    /// Checks every field: `guide` finite with length ≤ [`MAX_GUIDE`]
    /// (`frame.guide`), the boundary ([`Boundary::validate`]), the lamp a vector within the
    /// limit (`frame.lamp`).
    pub fn validate(&self) -> Result<()> {
        check_length(self.guide, 0.0, MAX_GUIDE, "frame.guide")?;
        if let Some(b) = &self.boundary {
            b.validate()?;
        }
        if let Some(l) = self.lamp {
            check_vec(l, "frame.lamp")?;
        }
        Ok(())
    }
}

impl<S: Scalar, const K: usize> SeparateFrame<S, K> {
    /// A frame with no neighbours.
    pub fn new() -> Self {
        SeparateFrame {
            neighbours: heapless::Vec::new(),
        }
    }

    /// The same frame in another scalar type (through `f32`).
    pub fn cast<T: Scalar>(&self) -> SeparateFrame<T, K> {
        let mut f = SeparateFrame::new();
        for c in &self.neighbours {
            // Same capacity: no push can fail.
            let _ = f.neighbours.push(Close {
                id: c.id,
                pos: c.pos.cast(),
            });
        }
        f
    }

    /// Checks every entry: `pos` a vector within the limit (`frame.neighbours.pos`), and no
    /// id twice (`Inconsistent`, `frame.neighbours.id`). List errors carry the entry's index.
    pub fn validate(&self) -> Result<()> {
        for (i, c) in self.neighbours.iter().enumerate() {
            check_vec(c.pos, "frame.neighbours.pos").map_err(|e| e.at(i))?;
            if self.neighbours[..i].iter().any(|o| o.id == c.id) {
                return Err(Error::inconsistent("frame.neighbours.id").at(i));
            }
        }
        Ok(())
    }
}

impl<S: Scalar, const K: usize> Default for SeparateFrame<S, K> {
    fn default() -> Self {
        Self::new()
    }
}
