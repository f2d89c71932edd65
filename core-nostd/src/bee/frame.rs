//! The bee's state, its sensor frame and its decision, with input validation.
//!
//! Coordinates are world coordinates with y up (chen eq. 7 uses `[0, 1, 0]` as the up axis).

use crate::check::{check_nonneg as check_density, check_num, check_unit, check_vec};
use crate::{Error, Result, Scalar, Vec3};

wire_type! {
    /// What a bee carries from one step to the next.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct BeeState<S> {
        /// Position r of the mass point.
        pub pos: Vec3<S>,
        /// Velocity u (u_p of §III at the next step).
        pub vel: Vec3<S>,
        /// Last unit forward vector o (§IV-B: the direction of flight), used when the bee
        /// hovers (speed ≈ 0). Need not be normalized; a zero vector means: face the goal, else
        /// +x.
        pub forward: Vec3<S>,
        /// Density ρ_i of eq. 10 from the last step (what the bee broadcasts to neighbours).
        pub density: S,
        /// Whether the bee was avoiding an obstacle at the last step (§IV-B).
        pub avoiding: bool,
        /// u_0 of eq. 5: the velocity u = u_p + aΔt that eq. 5 tuned at the last step (zero
        /// when no obstacle was closer than d0); see
        /// [`tune_velocity`](super::vision::tune_velocity).
        pub u0: Vec3<S>,
        /// Last roll set-point (rad).
        pub roll: S,
        /// Last pitch set-point (rad).
        pub pitch: S,
    }

    /// A neighbour as it broadcast itself.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct BeeNeighbor<S> {
        /// Its position r_j.
        pub pos: Vec3<S>,
        /// Its velocity.
        pub vel: Vec3<S>,
        /// Its density ρ_j (eq. 10), from which its pressure p_j is derived.
        pub density: S,
    }

    /// What the bee sees of the nearest obstacle (§IV-B, Fig. 3b).
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct ObstacleSense<S> {
        /// p_e: the closest point on the obstacle surface.
        pub point: Vec3<S>,
        /// n: the outward unit normal of the surface at p_e (length 1 ± 1 %).
        pub normal: Vec3<S>,
    }

    /// One step's sensor input: `N` neighbours at most, `P` target particles at most.
    #[derive(Clone, Debug, PartialEq)]
    pub struct BeeFrame<S, const N: usize, const P: usize> {
        /// Time t in seconds (eq. 3-4), ≥ 0: the bee's own clock. Each bee runs the
        /// maneuvering functions in its own phase; the host passes
        /// [`bee_time`](super::oscillation::bee_time) (the step's time plus the bee's clock
        /// offset from the seed and its id, wrapped below the input limit).
        pub t: S,
        /// Neighbouring bees (eq. 10-11).
        pub neighbours: heapless::Vec<BeeNeighbor<S>, N>,
        /// Virtual static particles sampled on a target (nest, food source): they repel the
        /// bee, which with the curl noise gives the zig-zag approach (§V-B).
        pub targets: heapless::Vec<Vec3<S>, P>,
        /// The target the bee flies toward by visual cues (§V-B), if any: its thrust (body X of
        /// eq. 2) points there.
        pub goal: Option<Vec3<S>>,
        /// The nearest obstacle, if one is sensed.
        pub obstacle: Option<ObstacleSense<S>>,
    }

    /// The outcome of one step.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct BeeDecision<S> {
        /// Acceleration a = F/m (eq. 1, with the drag).
        pub accel: Vec3<S>,
        /// Velocity set-point u*: u_p + aΔt (§III), tuned by eq. 5 near an obstacle, then
        /// limited to the maximum speed.
        pub velocity: Vec3<S>,
        /// Roll set-point (rad): eq. 6 when avoiding, else eq. 4.
        pub roll: S,
        /// Pitch set-point (rad): eq. 3.
        pub pitch: S,
        /// Whether the bee is avoiding an obstacle (§IV-B).
        pub avoiding: bool,
        /// The new density ρ_i (eq. 10), to broadcast.
        pub density: S,
    }
}

impl<S: Scalar> BeeState<S> {
    /// A bee at `pos` flying with `vel`, not avoiding anything, facing +x until it moves.
    pub fn new(pos: Vec3<S>, vel: Vec3<S>) -> Self {
        BeeState {
            pos,
            vel,
            forward: Vec3::new(S::ONE, S::ZERO, S::ZERO),
            density: S::ZERO,
            avoiding: false,
            u0: Vec3::zero(),
            roll: S::ZERO,
            pitch: S::ZERO,
        }
    }

    /// The same state in another scalar type (through `f32`).
    pub fn cast<T: Scalar>(&self) -> BeeState<T> {
        let c = |v: S| T::from_f32(v.to_f32());
        BeeState {
            pos: self.pos.cast(),
            vel: self.vel.cast(),
            forward: self.forward.cast(),
            density: c(self.density),
            avoiding: self.avoiding,
            u0: self.u0.cast(),
            roll: c(self.roll),
            pitch: c(self.pitch),
        }
    }

    /// Checks every field: finite, within ±[`LIMIT`](super::params::LIMIT), density ≥ 0.
    pub fn validate(&self) -> Result<()> {
        check_vec(self.pos, "state.pos")?;
        check_vec(self.vel, "state.vel")?;
        check_vec(self.forward, "state.forward")?;
        check_density(self.density, "state.density")?;
        check_vec(self.u0, "state.u0")?;
        check_num(self.roll, "state.roll")?;
        check_num(self.pitch, "state.pitch")
    }
}

impl<S: Scalar, const N: usize, const P: usize> BeeFrame<S, N, P> {
    /// A frame at time `t` with no neighbours, targets, goal or obstacle.
    pub fn new(t: S) -> Self {
        BeeFrame {
            t,
            neighbours: heapless::Vec::new(),
            targets: heapless::Vec::new(),
            goal: None,
            obstacle: None,
        }
    }

    /// The same frame in another scalar type (through `f32`).
    pub fn cast<T: Scalar>(&self) -> BeeFrame<T, N, P> {
        let mut f = BeeFrame::new(T::from_f32(self.t.to_f32()));
        // Same capacities: no push can fail (and none could panic).
        for n in &self.neighbours {
            let density = T::from_f32(n.density.to_f32());
            let _ = f.neighbours.push(BeeNeighbor {
                pos: n.pos.cast(),
                vel: n.vel.cast(),
                density,
            });
        }
        for p in &self.targets {
            let _ = f.targets.push(p.cast());
        }
        f.goal = self.goal.map(Vec3::cast);
        f.obstacle = self.obstacle.map(|o| ObstacleSense {
            point: o.point.cast(),
            normal: o.normal.cast(),
        });
        f
    }

    /// Checks every field: finite numbers within ±[`LIMIT`](super::params::LIMIT), t ≥ 0, densities ≥ 0, a unit
    /// normal (±1 %). List errors carry the entry's index.
    pub fn validate(&self) -> Result<()> {
        check_num(self.t, "frame.t")?;
        if self.t < S::ZERO {
            return Err(Error::out_of_range("frame.t"));
        }
        for (i, nb) in self.neighbours.iter().enumerate() {
            check_vec(nb.pos, "frame.neighbours.pos").map_err(|e| e.at(i))?;
            check_vec(nb.vel, "frame.neighbours.vel").map_err(|e| e.at(i))?;
            check_density(nb.density, "frame.neighbours.density").map_err(|e| e.at(i))?;
        }
        for (i, p) in self.targets.iter().enumerate() {
            check_vec(*p, "frame.targets").map_err(|e| e.at(i))?;
        }
        if let Some(g) = self.goal {
            check_vec(g, "frame.goal")?;
        }
        if let Some(ob) = self.obstacle {
            check_vec(ob.point, "frame.obstacle.point")?;
            check_unit(ob.normal, "frame.obstacle.normal")?;
        }
        Ok(())
    }
}
