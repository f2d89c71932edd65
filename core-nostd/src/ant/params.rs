//! Ant controller parameters (xiang2018 §4), defaulting to the paper's values where it gives
//! them.

use crate::model::{ModelParams, Range};
use crate::model_params;
use crate::{Result, Scalar};

wire_type! {
    /// The parameters of the ant controller.
    ///
    /// The paper fixes θ = π/6 (§4.1), the casual-stop probability 0.005 (§4.1) and Δt = 1 s
    /// (eq. 1). It leaves the speed, ranges, stop durations and the constants w0, C, k of
    /// eq. 2-3 open; our defaults for those are marked "ours" and are in body lengths (one ant
    /// is 1 unit long) and ticks.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct AntParams<S> {
        /// Moving speed v (units/s), shared by all ants (§3). Ours: 1.
        pub speed: S,
        /// Time step Δt (s). Paper: 1 (eq. 1).
        pub dt: S,
        /// Critical deviation angle θ of the random turn (rad). Paper: π/6 (§4.1).
        pub theta: S,
        /// Casual-stop probability per tick. Paper: 0.005 (§4.1).
        pub p_stop: S,
        /// Length of a casual stop (ticks). Ours: 5.
        pub casual_stop_ticks: u16,
        /// Time to collect food at a food source (ticks). Ours: 10.
        pub collect_ticks: u16,
        /// Time to drop food at the nest (ticks). Ours: 10.
        pub drop_ticks: u16,
        /// Radius within which two ants touch and transfer information (§4.2.1). Ours: 2.
        pub contact_range: S,
        /// Distance at which an obstacle ahead triggers avoidance (§4.2.2). Ours: 2.
        pub avoid_range: S,
        /// Predicted distance below which another ant "could collide" (n_c of eq. 3). Ours: 1.5.
        pub collision_range: S,
        /// w0: weight of the preferred orientation O* in eq. 2. Ours: 0.6.
        pub w0: S,
        /// C of the repulsion weight w_d = C/‖p_d* − p*‖^k (eq. 3). Ours: 1.
        pub c: S,
        /// k of the repulsion weight (eq. 3), a small integer power. Ours: 2.
        pub k: u8,
    }
}

impl<S: Scalar> Default for AntParams<S> {
    fn default() -> Self {
        AntParams {
            speed: S::ONE,
            dt: S::ONE,
            // π/6 as one constant, so that the fixed-point default is the f32 default converted
            // (π/6 computed in fixed point would truncate one step lower).
            theta: S::from_f32(core::f32::consts::FRAC_PI_6),
            p_stop: S::from_f32(0.005),
            casual_stop_ticks: 5,
            collect_ticks: 10,
            drop_ticks: 10,
            contact_range: S::from_i32(2),
            avoid_range: S::from_i32(2),
            collision_range: S::from_f32(1.5),
            w0: S::from_f32(0.6),
            c: S::ONE,
            k: 2,
        }
    }
}

impl<S: Scalar> AntParams<S> {
    /// The same parameters in another scalar type (through `f32`).
    pub fn cast<T: Scalar>(&self) -> AntParams<T> {
        let c = |v: S| T::from_f32(v.to_f32());
        AntParams {
            speed: c(self.speed),
            dt: c(self.dt),
            theta: c(self.theta),
            p_stop: c(self.p_stop),
            casual_stop_ticks: self.casual_stop_ticks,
            collect_ticks: self.collect_ticks,
            drop_ticks: self.drop_ticks,
            contact_range: c(self.contact_range),
            avoid_range: c(self.avoid_range),
            collision_range: c(self.collision_range),
            w0: c(self.w0),
            c: c(self.c),
            k: self.k,
        }
    }

    /// The parameters, validated once (see [`Checked`](crate::Checked)).
    pub fn checked(self) -> Result<crate::Checked<Self>> {
        ModelParams::checked(self)
    }

    /// Checks every parameter against its range ([`ModelParams::SPECS`]); the error names the
    /// first bad one.
    pub fn validate(&self) -> Result<()> {
        ModelParams::validate(self)
    }
}

model_params! {
    AntParams {
        speed: real = Range::above(0.0, 100.0), "units/tick";
        dt: real = Range::above(0.0, 100.0), "s";
        theta: real = Range::above(0.0, core::f32::consts::PI), "rad";
        p_stop: real = Range::closed(0.0, 1.0), "per tick";
        contact_range: real = Range::above(0.0, 1000.0), "units";
        avoid_range: real = Range::above(0.0, 1000.0), "units";
        collision_range: real = Range::above(0.0, 1000.0), "units";
        w0: real = Range::closed(0.0, 1.0), "";
        c: real = Range::closed(0.0, 1000.0), "";
        k: int(u8) = Range::int(0, 8), "";
        casual_stop_ticks: int(u16) = Range::int(1, u16::MAX as u32), "ticks";
        collect_ticks: int(u16) = Range::int(1, u16::MAX as u32), "ticks";
        drop_ticks: int(u16) = Range::int(1, u16::MAX as u32), "ticks";
    }
}
