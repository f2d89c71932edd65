//! li2015 parameters: the ORCA values the paper fitted (§4.1, read in decimetres: spec L1),
//! our choices where it is silent (Δt, ε, K, the speed limit), and the learned data the
//! insect samples: the segment-length and turning-angle tables and the visiting-frequency grid
//! (§3.1, §4.2-4.3).

use super::density::DensityGrid;
use super::sampler::Table;
use super::waypoint::{SAMPLING_MH, Screening};
use crate::model::{ModelParams, Range};
use crate::model_params;
use crate::{Error, Result, Scalar, Vec3};

/// The most bins of a learned table (spec §2.1: 64 on devices; the host uses the same tables,
/// so that both decide alike).
pub const BINS: usize = 64;

/// A learned distribution: up to [`BINS`] bins.
pub type LiTable<S> = Table<S, BINS>;

wire_type! {
    /// The parameters of the li2015 insect, the learned data included (a device keeps them
    /// in flash; the session's parameter hash covers every byte).
    ///
    /// Units: metres and seconds ([`Default`]: spec §1.3 in metres, the ORCA values of §4.1
    /// × 0.1). The data default to placeholders (uniform tables, one cell): a scenario or a
    /// model file gives the real ones.
    #[derive(Clone, Debug, PartialEq)]
    pub struct LiParams<S> {
        /// Δt: the time step (s; ours 0.01, the data's 100 frames/s).
        pub dt: S,
        /// v0: the preferred speed (units/s; §4.1 1.48, read as dm/s: 0.148 m/s).
        pub speed: S,
        /// ε of Algorithm 1: arrived when ‖x − g‖ ≤ ε (ours: v0·Δt).
        pub eps: S,
        /// Steps after which a waypoint not reached counts as reached (ours: ORCA can keep an
        /// insect from a waypoint, e.g. one closer to a wall than its radius).
        pub patience: u16,
        /// ORCA radius (ours 4.5 mm, a midge's size: §4.1's 0.45 read as cm; read as dm like
        /// the speed, 100 insects of 4.5 cm cannot fit the density of a swarm a few
        /// decimetres across, docs/models.md).
        pub radius: S,
        /// ORCA's safety margin: ORCA plans with radius·(1 + margin) (ours, as ren2016's).
        pub margin: S,
        /// ORCA time horizon τ (s; §4.1 5.27).
        pub tau: S,
        /// The neighbour distance (§4.1 14.84, read as dm: 1.484 m): the host's frame holds
        /// the nearest insects within it.
        pub range: S,
        /// How many of the frame's neighbours ORCA uses (ours 16, spec L3).
        pub orca_neighbours: u8,
        /// K: proposals per arrival (spec L8, ours 32; 1 is standard Metropolis-Hastings).
        pub proposals: u8,
        /// [`SAMPLING_MH`] (0, the model),
        /// [`SAMPLING_MESO`](super::waypoint::SAMPLING_MESO) (1) or
        /// [`SAMPLING_RANDOM`](super::waypoint::SAMPLING_RANDOM) (2): Fig. 4's methods.
        pub sampling: u8,
        /// An infeasible ORCA program: 0 zero velocity, 1 RVO2-3D's LP4 (the library's own
        /// fallback, spec L4: the default).
        pub fallback: u8,
        /// The segment lengths (units).
        pub lengths: LiTable<S>,
        /// The turning angles (radians; the magnitude is the cone angle, spec §2.2).
        pub turns: LiTable<S>,
        /// The visiting-frequency grid w_c (zero in obstacles and outside).
        pub density: DensityGrid<S>,
    }
}

impl<S: Scalar> Default for LiParams<S> {
    /// Spec §1.3 in metres: v0 0.148 m/s, τ 5.27 s, range 1.484 m; radius 4.5 mm; Δt 0.01 s,
    /// ε = v0·Δt, patience 300 steps, margin 0.05, 16 ORCA neighbours, K = 32,
    /// Metropolis-Hastings, LP4; placeholder data: lengths uniform in [2, 30] mm, turns
    /// uniform in [0, 0.7] rad, one cell over the 0.91 m cube of the data.
    fn default() -> Self {
        let f = S::from_f32;
        let uniform = |lo, hi| Table {
            lo: f(lo),
            hi: f(hi),
            cdf: heapless::Vec::from_slice(&[S::ONE]).unwrap_or_default(),
        };
        LiParams {
            dt: f(0.01),
            speed: f(0.148),
            eps: f(0.00148),
            patience: 300,
            radius: f(0.0045),
            margin: f(0.05),
            tau: f(5.27),
            range: f(1.484),
            orca_neighbours: 16,
            proposals: 32,
            sampling: SAMPLING_MH,
            fallback: 1,
            lengths: uniform(0.002, 0.03),
            turns: uniform(0.0, 0.7),
            density: DensityGrid {
                origin: Vec3::zero(),
                cell: f(0.91),
                dims: [1, 1, 1],
                weights: heapless::Vec::from_slice(&[1]).unwrap_or_default(),
            },
        }
    }
}

impl<S: Scalar> LiParams<S> {
    /// The same parameters in another scalar type (through `f32`).
    pub fn cast<T: Scalar>(&self) -> LiParams<T> {
        let c = |v: S| T::from_f32(v.to_f32());
        let table = |t: &LiTable<S>| Table {
            lo: c(t.lo),
            hi: c(t.hi),
            cdf: t.cdf.iter().map(|&v| c(v)).collect(),
        };
        LiParams {
            dt: c(self.dt),
            speed: c(self.speed),
            eps: c(self.eps),
            patience: self.patience,
            radius: c(self.radius),
            margin: c(self.margin),
            tau: c(self.tau),
            range: c(self.range),
            orca_neighbours: self.orca_neighbours,
            proposals: self.proposals,
            sampling: self.sampling,
            fallback: self.fallback,
            lengths: table(&self.lengths),
            turns: table(&self.turns),
            density: DensityGrid {
                origin: self.density.origin.cast(),
                cell: c(self.density.cell),
                dims: self.density.dims,
                weights: self.density.weights.clone(),
            },
        }
    }

    /// ORCA's planning radius: radius·(1 + margin).
    pub fn orca_radius(&self) -> S {
        self.radius * (S::ONE + self.margin)
    }

    /// The waypoint level's part of the parameters.
    pub fn screening(&self) -> Screening<S> {
        Screening {
            eps: self.eps,
            proposals: self.proposals,
            sampling: self.sampling,
        }
    }

    /// The parameters, validated once (see [`Checked`](crate::Checked)).
    ///
    /// # Errors
    ///
    /// As [`LiParams::validate`].
    pub fn checked(self) -> Result<crate::Checked<Self>> {
        ModelParams::checked(self)
    }

    /// Checks every parameter against its range, then the data ([`LiParams::lengths`],
    /// [`LiParams::turns`], [`LiParams::density`]); the error names the first bad one.
    pub fn validate(&self) -> Result<()> {
        ModelParams::validate(self)
    }

    /// The data: well-formed tables (lengths ≥ 0, turns within [−π, π]) and a grid of the
    /// right shape with a positive, finite cell.
    fn data(&self) -> Result<()> {
        self.lengths.validate("lengths")?;
        if self.lengths.lo < S::ZERO {
            return Err(Error::BadParam { field: "lengths" });
        }
        self.turns.validate("turns")?;
        let pi = S::from_f32(core::f32::consts::PI + 1e-3);
        if self.turns.lo < -pi || self.turns.hi > pi {
            return Err(Error::BadParam { field: "turns" });
        }
        self.density
            .view()
            .map(|_| ())
            .map_err(|_| Error::BadParam { field: "density" })
    }
}

model_params! {
    LiParams {
        dt: real = Range::above(0.0, 1.0), "s";
        speed: real = Range::above(0.0, 100.0), "units/s";
        eps: real = Range::closed(0.0, 100.0), "units";
        patience: int(u16) = Range::int(1, 65535), "steps";
        radius: real = Range::closed(0.0, 100.0), "units";
        margin: real = Range::closed(0.0, 1.0), "share of radius";
        tau: real = Range::above(0.0, 100.0), "s";
        range: real = Range::closed(0.0, 100.0), "units";
        orca_neighbours: int(u8) = Range::int(0, 64), "";
        proposals: int(u8) = Range::int(1, 255), "";
        sampling: int(u8) = Range::int(0, 2), "0 mh, 1 meso, 2 random";
        fallback: int(u8) = Range::int(0, 1), "0 stop, 1 lp4";
    }
    together data
}
