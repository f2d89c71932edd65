//! ren2016 parameters: Table 1's per-scenario columns (γ, scale, gain, the three zones'
//! weights and radii, the stimulus response) and our choices for what the paper leaves open
//! (Δt, the ORCA radius, time horizon and speed limit, the noise source, the fallback).

use crate::model::{ModelParams, Range};
use crate::model_params;
use crate::{Error, Result, Scalar};

/// Largest magnitude accepted for a coordinate or velocity component of a fly request: the
/// bee's limit ([`bee::params::LIMIT`](crate::bee::params::LIMIT)).
pub const LIMIT: f32 = crate::bee::params::LIMIT;

/// [`FlyParams::noise`]: F_ξ = ∇ × P, the curl noise of Eq. 4 (the model).
pub const NOISE_CURL: u8 = 0;
/// [`FlyParams::noise`]: F_ξ = P(r_i), the Perlin vector itself (Fig. 10 candidate).
pub const NOISE_PERLIN: u8 = 1;
/// [`FlyParams::noise`]: F_ξ = gain·U(−1, 1)³ per insect and step (Fig. 10's white noise).
pub const NOISE_WHITE: u8 = 2;
/// [`FlyParams::noise`]: F_ξ = gain·(three standard normals) per insect and step (Fig. 10's
/// Gaussian noise; see [`noise_force`](super::force::noise_force)).
pub const NOISE_GAUSSIAN: u8 = 3;
/// [`FlyParams::noise`]: F_ξ = 0 ("dynamics only", Fig. 13).
pub const NOISE_NONE: u8 = 4;

/// [`FlyParams::fallback`]: an infeasible ORCA program gives zero velocity for the frame (the
/// paper's choice).
pub const FALLBACK_STOP: u8 = 0;
/// [`FlyParams::fallback`]: an infeasible ORCA program is solved by RVO2-3D's
/// `linearProgram4` (the least penetration).
pub const FALLBACK_LP4: u8 = 1;

/// The Δt of every Table 1 column (spec §2.2, ours: the 100 frames/s of the midge data).
pub const DT: f32 = 0.01;

/// ORCA's safety margin of every Table 1 column ([`FlyParams::margin`], ours): 5 % of the
/// radius (docs/models.md: 1 % let 2.2 % of random worlds' jams through 2·radius).
pub const MARGIN: f32 = 0.05;

/// The speed limit of ORCA unless friction bounds it lower (spec R4, ours): 10 units/s.
pub const MAX_SPEED: f32 = 10.0;

wire_type! {
    /// The parameters of the ren2016 insect (Eq. 2-5, friction, response, noise, ORCA).
    ///
    /// Radii are absolute (`r_rep ≤ r_ali ≤ r_att`); Table 1 prints the outer two as
    /// differences (r_ali* = r_ali − r_rep, r_att* = r_att − r_ali) and the presets add them
    /// up. [`Default`] is the Midge column ([`FlyParams::midge`]). Units: the scenario's
    /// (`metres_per_unit`), seconds.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct FlyParams<S> {
        /// γ: quadratic friction coefficient, F_fric = −γ‖v‖v.
        pub gamma: S,
        /// scale: Perlin lattice spacing of the noise, P(r/scale).
        pub scale: S,
        /// gain: noise magnitude (Perlin gain; the strength of the white and Gaussian
        /// noises).
        pub gain: S,
        /// χ_rep: repulsion weight (Eq. 5).
        pub chi_rep: S,
        /// r_rep: repulsion radius, zone [0, r_rep).
        pub r_rep: S,
        /// χ_ali: alignment weight.
        pub chi_ali: S,
        /// r_ali: alignment radius, zone [r_rep, r_ali).
        pub r_ali: S,
        /// χ_att: attraction weight.
        pub chi_att: S,
        /// r_att: attraction radius, zone [r_ali, r_att]; also the neighbour radius.
        pub r_att: S,
        /// χ_res: stimulus response weight.
        pub chi_res: S,
        /// r_res: the insects' visual range for stimuli (H(r_res − r_ie)).
        pub r_res: S,
        /// Δt: time step (s; ours 0.01, the paper gives none).
        pub dt: S,
        /// ORCA radius of an insect (ours: 0.25·r_rep, so the repulsion zone acts before ORCA
        /// does).
        pub radius: S,
        /// ORCA's safety margin (ours 0.05): ORCA plans every insect as a sphere of
        /// radius·(1 + margin), so that the few contacts a jam leaves (an LP's planes are
        /// exact only in exact arithmetic, and an infeasible program's fallback penetrates
        /// by design) stay outside 2·radius, the distance R-T8 counts as a collision.
        pub margin: S,
        /// ORCA time horizon τ (s; ours 0.5).
        pub tau: S,
        /// ORCA speed limit (units/s; ours min(10, 0.5/(γΔt)), so that the explicit friction
        /// step stays stable: γ·max_speed·Δt ≤ ½).
        pub max_speed: S,
        /// How many of the frame's neighbours (nearest first) ORCA uses (RVO2's
        /// `maxNeighbors`); the zone forces use them all.
        pub orca_neighbours: u8,
        /// The noise source: [`NOISE_CURL`] (0, the model), [`NOISE_PERLIN`] (1),
        /// [`NOISE_WHITE`] (2), [`NOISE_GAUSSIAN`] (3), [`NOISE_NONE`] (4).
        pub noise: u8,
        /// What an infeasible ORCA program gives: [`FALLBACK_STOP`] (0, the paper) or
        /// [`FALLBACK_LP4`] (1, RVO2-3D).
        pub fallback: u8,
        /// The escape angle θ: 0 draws θ ~ U[−π/2, 0] (one side, as printed), 1 draws
        /// θ ~ U[−π/2, π/2] (both sides, ours).
        pub escape_sides: u8,
    }
}

impl<S: Scalar> Default for FlyParams<S> {
    /// Table 1, "Midge" ([`FlyParams::midge`]).
    fn default() -> Self {
        Self::midge()
    }
}

/// One Table 1 column in the paper's form: γ, scale, gain, χ_rep, r_rep, χ_ali, r_ali*,
/// χ_att, r_att*, χ_res, r_res (spec §3.1).
type Column = [f32; 11];

impl<S: Scalar> FlyParams<S> {
    /// Table 1, "Midge" (fitted to dataset 1): γ 11.16, scale 2.20, gain 2.51, χ_rep 5.61,
    /// r_rep 0.17, no alignment, χ_att 14.29, r_att* 5.12, no stimulus.
    pub fn midge() -> Self {
        Self::column([
            11.16, 2.20, 2.51, 5.61, 0.17, 0.0, 0.0, 14.29, 5.12, 0.0, 0.0,
        ])
    }

    /// Table 1, "Aggregation": the midge set with χ_ali 5.0, r_ali* 1.0.
    pub fn aggregation() -> Self {
        Self::column([
            11.16, 2.20, 2.51, 5.61, 0.17, 5.0, 1.0, 14.29, 5.12, 0.0, 0.0,
        ])
    }

    /// Table 1, "Fruitfly" (fitted to datasets 2-4): γ 8.76, scale 2.75, gain 1.79, χ_rep
    /// 1.74, r_rep 1.48, no alignment, χ_att 10.39, r_att* 4.49, no stimulus.
    pub fn fruitfly() -> Self {
        Self::column([
            8.76, 2.75, 1.79, 1.74, 1.48, 0.0, 0.0, 10.39, 4.49, 0.0, 0.0,
        ])
    }

    /// Table 1, "Mating": the fruit-fly set with χ_ali 3.0, r_ali* 10.0 and a pursuit
    /// response χ_res 10.0, r_res 2.0 (the female is the stimulus).
    pub fn mating() -> Self {
        Self::column([
            8.76, 2.75, 1.79, 1.74, 1.48, 3.0, 10.0, 10.39, 4.49, 10.0, 2.0,
        ])
    }

    /// Table 1, "Escape": the fruit-fly set (spec R1) with χ_ali 3.0, r_ali* 10.0, χ_res 20.0,
    /// r_res 8.0.
    pub fn escape() -> Self {
        Self::column([
            8.76, 2.75, 1.79, 1.74, 1.48, 3.0, 10.0, 10.39, 4.49, 20.0, 8.0,
        ])
    }

    /// Table 1, "Bats": γ 10.21, scale 2.20, gain 2.51, χ_rep 8.0, r_rep 2.0, χ_ali 20.0,
    /// r_ali* 3.0, χ_att 25.0, r_att* 10.0, χ_res 10.0, r_res 10.0.
    pub fn bats() -> Self {
        Self::column([
            10.21, 2.20, 2.51, 8.0, 2.0, 20.0, 3.0, 25.0, 10.0, 10.0, 10.0,
        ])
    }

    /// Table 1, "Locust": γ 1.40, scale 1.72, gain 0.36, χ_rep 3.0, r_rep 0.45, χ_ali 5.0
    /// with r_ali* 0 (an empty zone), χ_att 5.0, r_att* 5.0, pursuit χ_res 60.0, r_res 25.0.
    pub fn locust() -> Self {
        Self::column([1.40, 1.72, 0.36, 3.0, 0.45, 5.0, 0.0, 5.0, 5.0, 60.0, 25.0])
    }

    /// Table 1, "Phase" (after the transition): γ 1.40, scale 0.72, gain 0.10, χ_rep 5.0,
    /// r_rep 0.2, χ_ali 10.0, r_ali* 2.2, χ_att 7.0, r_att* 9.2, no stimulus.
    pub fn phase() -> Self {
        Self::column([1.40, 0.72, 0.10, 5.0, 0.2, 10.0, 2.2, 7.0, 9.2, 0.0, 0.0])
    }

    /// Table 1, "Phototaxis": γ 1.40, scale 0.42, gain 1.0, χ_rep 3.0, r_rep 0.2, no
    /// alignment, χ_att 8.0, r_att* 10.0, pursuit of the lamp holder χ_res 1.0, r_res 5.0.
    pub fn phototaxis() -> Self {
        Self::column([1.40, 0.42, 1.0, 3.0, 0.2, 0.0, 0.0, 8.0, 10.0, 1.0, 5.0])
    }

    /// Every Table 1 column, named as the scenario presets name it.
    pub fn table_1() -> [(&'static str, Self); 9] {
        [
            ("midge", Self::midge()),
            ("aggregation", Self::aggregation()),
            ("fruitfly", Self::fruitfly()),
            ("mating", Self::mating()),
            ("escape", Self::escape()),
            ("bats", Self::bats()),
            ("locust", Self::locust()),
            ("phase", Self::phase()),
            ("phototaxis", Self::phototaxis()),
        ]
    }

    /// A Table 1 column plus our constants: Δt [`DT`], ORCA radius 0.25·r_rep with the
    /// [`MARGIN`], τ 0.5 s,
    /// speed limit min([`MAX_SPEED`], 0.5/(γΔt)), 16 ORCA neighbours, curl noise, the
    /// paper's zero-velocity fallback, one-sided escape.
    pub fn column(c: Column) -> Self {
        let [
            gamma,
            scale,
            gain,
            chi_rep,
            r_rep,
            chi_ali,
            r_ali_d,
            chi_att,
            r_att_d,
            chi_res,
            r_res,
        ] = c;
        let r_ali = r_rep + r_ali_d;
        let f = S::from_f32;
        FlyParams {
            gamma: f(gamma),
            scale: f(scale),
            gain: f(gain),
            chi_rep: f(chi_rep),
            r_rep: f(r_rep),
            chi_ali: f(chi_ali),
            r_ali: f(r_ali),
            chi_att: f(chi_att),
            r_att: f(r_ali + r_att_d),
            chi_res: f(chi_res),
            r_res: f(r_res),
            dt: f(DT),
            radius: f(0.25 * r_rep),
            margin: f(MARGIN),
            tau: f(0.5),
            max_speed: f(MAX_SPEED.min(0.5 / (gamma * DT))),
            orca_neighbours: 16,
            noise: NOISE_CURL,
            fallback: FALLBACK_STOP,
            escape_sides: 0,
        }
    }

    /// The same parameters in another scalar type (through `f32`).
    pub fn cast<T: Scalar>(&self) -> FlyParams<T> {
        let c = |v: S| T::from_f32(v.to_f32());
        FlyParams {
            gamma: c(self.gamma),
            scale: c(self.scale),
            gain: c(self.gain),
            chi_rep: c(self.chi_rep),
            r_rep: c(self.r_rep),
            chi_ali: c(self.chi_ali),
            r_ali: c(self.r_ali),
            chi_att: c(self.chi_att),
            r_att: c(self.r_att),
            chi_res: c(self.chi_res),
            r_res: c(self.r_res),
            dt: c(self.dt),
            radius: c(self.radius),
            margin: c(self.margin),
            tau: c(self.tau),
            max_speed: c(self.max_speed),
            orca_neighbours: self.orca_neighbours,
            noise: self.noise,
            fallback: self.fallback,
            escape_sides: self.escape_sides,
        }
    }

    /// The same insect `k` times larger at the same Δt: every length (the radii of Eq. 5,
    /// r_res, the noise's lattice `scale`, the ORCA radius) and speed (`max_speed`) × k,
    /// every force weight (χ_rep, χ_ali, χ_att, χ_res: they weigh unit vectors) × k, γ / k
    /// (F_fric = −γ‖v‖v is quadratic in v), and the noise gain × k (white, Gaussian and
    /// Perlin noise are the force itself) or × k² (the curl noise, Eq. 4, differentiates
    /// gain·Per(r/scale)). τ, the margin, Δt and the codes are unchanged.
    ///
    /// Every term of Algorithm 1 is then k times the original's at k times the positions
    /// and velocities, and ORCA's velocity obstacles scale with them: a swarm started k
    /// times larger stays k times larger, its density k⁻³ times the original's (the
    /// temperature rule of spec §2.8, ours; docs/models.md).
    pub fn scaled(&self, k: S) -> Self {
        let gain = if self.noise == NOISE_CURL { k * k } else { k };
        let (gamma, mut max_speed) = (self.gamma / k, self.max_speed * k);
        // γ·max_speed·Δt is unchanged but for rounding: keep a limit that was within ½ there.
        let half = S::from_f32(0.5);
        if self.gamma * self.max_speed * self.dt <= half && gamma * max_speed * self.dt > half {
            max_speed *= S::from_f32(0.999_99);
        }
        FlyParams {
            gamma,
            scale: self.scale * k,
            gain: self.gain * gain,
            chi_rep: self.chi_rep * k,
            r_rep: self.r_rep * k,
            chi_ali: self.chi_ali * k,
            r_ali: self.r_ali * k,
            chi_att: self.chi_att * k,
            r_att: self.r_att * k,
            chi_res: self.chi_res * k,
            r_res: self.r_res * k,
            radius: self.radius * k,
            max_speed,
            ..*self
        }
    }

    /// The radius ORCA plans with: radius·(1 + margin).
    pub fn orca_radius(&self) -> S {
        self.radius * (S::ONE + self.margin)
    }

    /// The parameters, validated once (see [`Checked`](crate::Checked)).
    pub fn checked(self) -> Result<crate::Checked<Self>> {
        ModelParams::checked(self)
    }

    /// Checks every parameter against its range, then the rules between them
    /// ([`FlyParams::r_ali`], [`FlyParams::max_speed`]); the error names the first bad one.
    pub fn validate(&self) -> Result<()> {
        ModelParams::validate(self)
    }

    /// The rules between fields: the zones nest (`r_rep ≤ r_ali ≤ r_att`, else
    /// `BadParam("r_ali")` or `BadParam("r_att")`), and the explicit friction step is
    /// stable at the speed limit (`γ·max_speed·Δt ≤ ½`, else `BadParam("max_speed")`).
    fn fits(&self) -> Result<()> {
        if self.r_ali < self.r_rep {
            return Err(Error::BadParam { field: "r_ali" });
        }
        if self.r_att < self.r_ali {
            return Err(Error::BadParam { field: "r_att" });
        }
        if self.gamma * self.max_speed * self.dt > S::from_f32(0.5) {
            return Err(Error::BadParam { field: "max_speed" });
        }
        Ok(())
    }
}

model_params! {
    FlyParams {
        gamma: real = Range::closed(0.0, 100.0), "1/unit";
        scale: real = Range::above(0.0, 64.0), "units";
        gain: real = Range::closed(0.0, 64.0), "";
        chi_rep: real = Range::closed(0.0, 1000.0), "units/s²";
        r_rep: real = Range::closed(0.0, 100.0), "units";
        chi_ali: real = Range::closed(0.0, 1000.0), "units/s²";
        r_ali: real = Range::closed(0.0, 100.0), "units, ≥ r_rep";
        chi_att: real = Range::closed(0.0, 1000.0), "units/s²";
        r_att: real = Range::closed(0.0, 100.0), "units, ≥ r_ali";
        chi_res: real = Range::closed(0.0, 1000.0), "units/s²";
        r_res: real = Range::closed(0.0, 1000.0), "units";
        dt: real = Range::above(0.0, 1.0), "s";
        radius: real = Range::closed(0.0, 100.0), "units";
        margin: real = Range::closed(0.0, 1.0), "share of radius";
        tau: real = Range::above(0.0, 100.0), "s";
        max_speed: real = Range::above(0.0, 1000.0), "units/s, with γ·max_speed·dt ≤ ½";
        orca_neighbours: int(u8) = Range::int(0, 64), "";
        noise: int(u8) = Range::int(0, 4), "0 curl, 1 perlin, 2 white, 3 gaussian, 4 none";
        fallback: int(u8) = Range::int(0, 1), "0 stop, 1 lp4";
        escape_sides: int(u8) = Range::int(0, 1), "0 one side, 1 both";
    }
    together fits
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Fx;

    /// Every Table 1 column validates in both scalars, and the absolute radii add up.
    #[test]
    fn table_1_columns_validate() {
        for (name, p) in FlyParams::<f32>::table_1() {
            assert_eq!(p.validate(), Ok(()), "{name}");
            assert_eq!(p.cast::<Fx>().validate(), Ok(()), "{name} in Fx");
            assert!(p.gamma * p.max_speed * p.dt <= 0.5 + 1e-6, "{name}");
        }
        // Spec §3.1's absolute radii.
        let m = FlyParams::<f32>::mating();
        assert!((m.r_ali - 11.48).abs() < 1e-5 && (m.r_att - 15.97).abs() < 1e-5);
        let b = FlyParams::<f32>::bats();
        assert!((b.r_ali - 5.0).abs() < 1e-6 && (b.r_att - 15.0).abs() < 1e-6);
    }

    #[test]
    fn rules_between_fields_name_the_field() {
        let mut p = FlyParams::<f32>::fruitfly();
        p.r_ali = 1.0;
        assert_eq!(p.validate(), Err(Error::BadParam { field: "r_ali" }));
        let mut p = FlyParams::<f32>::fruitfly();
        p.r_att = 1.0;
        assert_eq!(p.validate(), Err(Error::BadParam { field: "r_att" }));
        let mut p = FlyParams::<f32>::midge();
        p.max_speed = 10.0;
        assert_eq!(p.validate(), Err(Error::BadParam { field: "max_speed" }));
        let mut p = FlyParams::<f32>::midge();
        p.noise = 5;
        assert_eq!(p.validate(), Err(Error::BadParam { field: "noise" }));
    }
}
