//! The insect's state and its sensor frame, with input validation (spec §1.4, §1.5 step 1).

use crate::check::check_vec;
pub use crate::orca3d::Neighbour;
use crate::orca3d::Surface;
use crate::{Error, Result, Scalar, Vec3};

/// [`Stimulus::kind`]: food or a female, pursued (s_e = 0).
pub const STIMULUS_TARGET: u8 = 0;
/// [`Stimulus::kind`]: a predator, escaped (s_e = 1).
pub const STIMULUS_PREDATOR: u8 = 1;

wire_type! {
    /// What an insect carries from one step to the next (spec §1.4).
    #[derive(Clone, Copy, Debug, Default, PartialEq)]
    pub struct FlyState<S> {
        /// Position r_i.
        pub pos: Vec3<S>,
        /// The actual (post-ORCA) velocity v_i: v'_i of the next step (Algorithm 1).
        pub vel: Vec3<S>,
        /// θ of the current escape episode (ours, spec §2.3: drawn when a predator enters
        /// r_res, kept while it stays in range).
        pub escape_theta: S,
        /// Whether a predator was in range at the last step (ours).
        pub escaping: bool,
    }

    /// The stimulus the insect responds to (the nearest within r_res, a predator before a
    /// target: the host's choice, spec §2.3).
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct Stimulus<S> {
        /// Its position r_e.
        pub pos: Vec3<S>,
        /// [`STIMULUS_TARGET`] (pursuit) or [`STIMULUS_PREDATOR`] (escape).
        pub kind: u8,
    }

    /// The sensor input of one step: up to `N` neighbours (nearest first, ties by id: ORCA's
    /// result depends on their order), the stimulus, up to `O` obstacle surfaces.
    #[derive(Clone, Debug, PartialEq)]
    pub struct FlyFrame<S, const N: usize, const O: usize> {
        /// Neighbours within r_att, nearest first; an entry with the insect's own id is
        /// ignored.
        pub neighbours: heapless::Vec<Neighbour<S>, N>,
        /// The stimulus in range, if any.
        pub stimulus: Option<Stimulus<S>>,
        /// Obstacle surfaces within ORCA's reach: the closest point and the outward unit
        /// normal, pointing into the free space the insect is in (a container's walls point
        /// inward). ORCA keeps the insect on the free side (spec §2.5, ours).
        pub surfaces: heapless::Vec<Surface<S>, O>,
    }
}

impl<S: Scalar> FlyState<S> {
    /// An insect at `pos` with velocity `vel`, not escaping.
    pub fn new(pos: Vec3<S>, vel: Vec3<S>) -> Self {
        FlyState {
            pos,
            vel,
            escape_theta: S::ZERO,
            escaping: false,
        }
    }

    /// The same state in another scalar type (through `f32`).
    pub fn cast<T: Scalar>(&self) -> FlyState<T> {
        FlyState {
            pos: self.pos.cast(),
            vel: self.vel.cast(),
            escape_theta: T::from_f32(self.escape_theta.to_f32()),
            escaping: self.escaping,
        }
    }

    /// Checks every field: `pos` and `vel` finite and within ±[`LIMIT`](super::params::LIMIT)
    /// (`state.pos`, `state.vel`), `escape_theta` in [−π/2, π/2] (`state.escape_theta`).
    pub fn validate(&self) -> Result<()> {
        check_vec(self.pos, "state.pos")?;
        check_vec(self.vel, "state.vel")?;
        let half_pi = S::from_f32(core::f32::consts::FRAC_PI_2 + 1e-3);
        if crate::check::within(self.escape_theta, half_pi) {
            Ok(())
        } else if !self.escape_theta.is_finite() {
            Err(Error::non_finite("state.escape_theta"))
        } else {
            Err(Error::out_of_range("state.escape_theta"))
        }
    }
}

impl<S: Scalar> Stimulus<S> {
    /// Whether the insect escapes from it (s_e = 1).
    pub fn is_predator(&self) -> bool {
        self.kind == STIMULUS_PREDATOR
    }
}

impl<S: Scalar, const N: usize, const O: usize> FlyFrame<S, N, O> {
    /// A frame with nothing sensed.
    pub fn new() -> Self {
        FlyFrame {
            neighbours: heapless::Vec::new(),
            stimulus: None,
            surfaces: heapless::Vec::new(),
        }
    }

    /// The same frame in another scalar type (through `f32`).
    pub fn cast<T: Scalar>(&self) -> FlyFrame<T, N, O> {
        let mut f = FlyFrame::new();
        // Same capacities: no push can fail.
        for n in &self.neighbours {
            let _ = f.neighbours.push(Neighbour {
                id: n.id,
                pos: n.pos.cast(),
                vel: n.vel.cast(),
            });
        }
        f.stimulus = self.stimulus.map(|s| Stimulus {
            pos: s.pos.cast(),
            kind: s.kind,
        });
        for s in &self.surfaces {
            let _ = f.surfaces.push(Surface {
                point: s.point.cast(),
                normal: s.normal.cast(),
            });
        }
        f
    }

    /// Checks every field: neighbours' `pos` and `vel` within the limit
    /// (`frame.neighbours.pos`, `.vel`) with no id twice (`Inconsistent`,
    /// `frame.neighbours.id`); the stimulus position within the limit and a known kind
    /// (`frame.stimulus.pos`, `frame.stimulus.kind`); surfaces' points within the limit and
    /// unit normals (`frame.surfaces.point`, `.normal`). List errors carry the entry's index.
    pub fn validate(&self) -> Result<()> {
        crate::orca3d::check_sensed(&self.neighbours, &self.surfaces)?;
        if let Some(s) = &self.stimulus {
            check_vec(s.pos, "frame.stimulus.pos")?;
            if s.kind > STIMULUS_PREDATOR {
                return Err(Error::out_of_range("frame.stimulus.kind"));
            }
        }
        Ok(())
    }
}

impl<S: Scalar, const N: usize, const O: usize> Default for FlyFrame<S, N, O> {
    fn default() -> Self {
        Self::new()
    }
}
