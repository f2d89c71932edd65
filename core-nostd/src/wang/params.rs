//! wang2014 parameters: Table 1's per-scenario values (scale, gain, s0) and our choices for
//! what the paper leaves open (Δt, d0, d_min, the phototaxis bias, the noise source).

use crate::model::{ModelParams, Range};
use crate::model_params;
use crate::{Error, Result, Scalar};

/// Largest magnitude accepted for a coordinate or velocity component of a wang request: the
/// bee's limit ([`bee::params::LIMIT`](crate::bee::params::LIMIT)), so that differences of two
/// positions stay inside the range of [`Fx`](crate::Fx).
pub const LIMIT: f32 = crate::bee::params::LIMIT;

/// [`WangParams::noise`]: V_l is the bounded curl noise of eq. 1-3 (the model).
pub const NOISE_CURL: u8 = 0;
/// [`WangParams::noise`]: V_l = P(x), the Perlin vector itself (compressible; §7.1 baseline,
/// ours).
pub const NOISE_PERLIN: u8 = 1;
/// [`WangParams::noise`]: V_l uniform in [−gain, gain]³, drawn afresh per insect and step
/// (§7.1 baseline, ours).
pub const NOISE_RANDOM: u8 = 2;

/// The factor of the peak curl-noise speed in the time-step bound: max‖∇×P‖ ≈ 3.1·gain/scale
/// (spec §2.6, measured), rounded up.
pub const PEAK_CURL: f32 = 3.2;

/// The factor of the peak speed of the other sources in the time-step bound: ‖P‖ ≤ √3·1.04·gain
/// for Perlin noise, √3·gain for random noise, rounded up.
pub const PEAK_BASELINE: f32 = 1.81;

wire_type! {
    /// The parameters of the wang2014 insect (per-insect part: eq. 1-3, 8-9, §6, §7).
    ///
    /// [`Default`] is Table 1's "Two blocks" column ([`WangParams::two_blocks`]); see also
    /// [`WangParams::aggregation`], [`WangParams::phototaxis`], [`WangParams::locusts`].
    /// World unit: metre, the cost-grid cell l = 1 (spec §1.3, ours).
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct WangParams<S> {
        /// scale: Perlin lattice spacing (m); the noise argument is x/scale (§4). Table 1:
        /// 0.2-0.6.
        pub scale: S,
        /// gain: Perlin magnitude (§4). Table 1: 0.25-1.0.
        pub gain: S,
        /// s0: inherent speed (m/s), V_g = s0·(−∇C/‖∇C‖) (eq. 8). Table 1: 1.5-8.
        pub s0: S,
        /// Δt: time step (s) of the explicit Euler step (ours; the paper gives none). Bounded
        /// by `dt·(peak noise speed + s0 + u_photo) ≤ ½·min(scale, d0)` (spec §2.6), the
        /// peak noise speed being 3.2·gain/scale for curl noise ([`PEAK_CURL`]) and 1.81·gain
        /// for the baselines ([`PEAK_BASELINE`]).
        pub dt: S,
        /// d0: ramp width of eq. 3 (m), "equivalent to the side length of the grid" (§4):
        /// l = 1.
        pub d0: S,
        /// d_min: minimum-distance threshold of MDE (m, §6; ours: 0.1·l); 0 disables MDE.
        pub d_min: S,
        /// Phototaxis (§7): probability per step of the bias toward the lamp holder (ours:
        /// 0.05 in the phototaxis scene, 0 elsewhere).
        pub p_photo: S,
        /// Phototaxis (§7): the bias speed (m/s) toward the lamp holder (ours: 0.2·s0).
        pub u_photo: S,
        /// The V_l source: [`NOISE_CURL`] (0, the model), [`NOISE_PERLIN`] (1) or
        /// [`NOISE_RANDOM`] (2), the baselines of §7.1.
        pub noise: u8,
    }
}

impl<S: Scalar> Default for WangParams<S> {
    /// Table 1, "Two blocks" ([`WangParams::two_blocks`]).
    fn default() -> Self {
        Self::two_blocks()
    }
}

impl<S: Scalar> WangParams<S> {
    /// Table 1, "Two blocks" (also "Chasing"): scale 0.4, gain 0.25, s0 1.5; ours Δt 0.01,
    /// d0 1, d_min 0.1, no phototaxis, curl noise.
    pub fn two_blocks() -> Self {
        Self::table_1(0.4, 0.25, 1.5, 0.01)
    }

    /// Table 1, "Aggregation": scale 0.2, gain 0.7, s0 2.5; Δt 0.005 (spec §2.6: the
    /// 0.01 s step breaks the bound here).
    pub fn aggregation() -> Self {
        Self::table_1(0.2, 0.7, 2.5, 0.005)
    }

    /// Table 1, "Phototaxis": scale 0.6, gain 1.0, s0 2.5, Δt 0.01; with probability 0.05 per
    /// step a bias of 0.5 m/s (0.2·s0) toward the lamp (§7, ours).
    pub fn phototaxis() -> Self {
        WangParams {
            p_photo: S::from_f32(0.05),
            u_photo: S::from_f32(0.5),
            ..Self::table_1(0.6, 1.0, 2.5, 0.01)
        }
    }

    /// Table 1, "Locusts": s0 8; scale 0.6 and gain 1.0 (the cells missing from the
    /// extracted table, spec W1), Δt 0.01 (bound: 0.01·(3.2/0.6 + 8) = 0.133 ≤ 0.3).
    pub fn locusts() -> Self {
        Self::table_1(0.6, 1.0, 8.0, 0.01)
    }

    /// One column of Table 1 plus our constants.
    fn table_1(scale: f32, gain: f32, s0: f32, dt: f32) -> Self {
        let c = S::from_f32;
        WangParams {
            scale: c(scale),
            gain: c(gain),
            s0: c(s0),
            dt: c(dt),
            d0: S::ONE,
            d_min: c(0.1),
            p_photo: S::ZERO,
            u_photo: S::ZERO,
            noise: NOISE_CURL,
        }
    }

    /// The same parameters in another scalar type (through `f32`).
    pub fn cast<T: Scalar>(&self) -> WangParams<T> {
        let c = |v: S| T::from_f32(v.to_f32());
        WangParams {
            scale: c(self.scale),
            gain: c(self.gain),
            s0: c(self.s0),
            dt: c(self.dt),
            d0: c(self.d0),
            d_min: c(self.d_min),
            p_photo: c(self.p_photo),
            u_photo: c(self.u_photo),
            noise: self.noise,
        }
    }

    /// The parameters, validated once (see [`Checked`](crate::Checked)).
    pub fn checked(self) -> Result<crate::Checked<Self>> {
        ModelParams::checked(self)
    }

    /// Checks every parameter against its range, then the time-step bound
    /// ([`WangParams::dt`]); the error names the first bad one.
    pub fn validate(&self) -> Result<()> {
        ModelParams::validate(self)
    }

    /// The rule between fields (spec §2.6): a step moves at most half the finest feature,
    /// `dt·(peak noise speed + s0 + u_photo) ≤ ½·min(scale, d0)`; else `BadParam("dt")`.
    fn dt_fits(&self) -> Result<()> {
        let noise = if self.noise == NOISE_CURL {
            S::from_f32(PEAK_CURL) * (self.gain / self.scale)
        } else {
            S::from_f32(PEAK_BASELINE) * self.gain
        };
        let speed = noise + self.s0 + self.u_photo;
        let step = self.dt * speed;
        let half = self.scale.min(self.d0) * S::from_f32(0.5);
        if step <= half {
            Ok(())
        } else {
            Err(Error::BadParam { field: "dt" })
        }
    }
}

model_params! {
    WangParams {
        scale: real = Range::above(0.0, 64.0), "m";
        gain: real = Range::closed(0.0, 16.0), "";
        s0: real = Range::closed(0.0, 100.0), "m/s";
        dt: real = Range::above(0.0, 1.0), "s, with dt·(peak noise speed + s0 + u_photo) ≤ ½·min(scale, d0)";
        d0: real = Range::above(0.0, 64.0), "m";
        d_min: real = Range::closed(0.0, 8.0), "m";
        p_photo: real = Range::closed(0.0, 1.0), "";
        u_photo: real = Range::closed(0.0, 100.0), "m/s";
        noise: int(u8) = Range::int(0, 2), "0 curl, 1 perlin, 2 random";
    }
    together dt_fits
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Fx;

    #[test]
    fn table_1_columns_hold_the_time_step_bound() {
        let d = WangParams::<f32>::default();
        assert_eq!(d, WangParams::two_blocks());
        assert_eq!((d.scale, d.gain, d.s0, d.dt), (0.4, 0.25, 1.5, 0.01));
        assert_eq!(
            (d.d0, d.d_min, d.p_photo, d.u_photo, d.noise),
            (1.0, 0.1, 0.0, 0.0, 0)
        );
        let a = WangParams::<f32>::aggregation();
        assert_eq!((a.scale, a.gain, a.s0, a.dt), (0.2, 0.7, 2.5, 0.005));
        let p = WangParams::<f32>::phototaxis();
        assert_eq!(
            (p.scale, p.gain, p.s0, p.p_photo, p.u_photo),
            (0.6, 1.0, 2.5, 0.05, 0.5)
        );
        let l = WangParams::<f32>::locusts();
        assert_eq!((l.scale, l.gain, l.s0, l.dt), (0.6, 1.0, 8.0, 0.01));
        for p in [d, a, p, l] {
            assert_eq!(p.validate(), Ok(()));
            assert_eq!(p.cast::<Fx>().validate(), Ok(()));
            assert_eq!(p.cast::<Fx>().cast::<f32>().noise, p.noise);
        }
        // Aggregation at the default 0.01 s breaks the bound (0.137 > 0.1).
        let fast = WangParams::<f32> { dt: 0.01, ..a };
        assert_eq!(fast.validate(), Err(Error::BadParam { field: "dt" }));
        assert_eq!(
            fast.cast::<Fx>().validate(),
            Err(Error::BadParam { field: "dt" })
        );
    }

    #[test]
    fn validate_names_the_bad_parameter() {
        let ok = WangParams::<f32>::default();
        type Breaker = fn(&mut WangParams<f32>);
        let cases: [(Breaker, &str); 9] = [
            (|p| p.scale = 0.0, "scale"),
            (|p| p.gain = f32::NAN, "gain"),
            (|p| p.s0 = -1.0, "s0"),
            (|p| p.dt = f32::INFINITY, "dt"),
            (|p| p.d0 = 0.0, "d0"),
            (|p| p.d_min = 9.0, "d_min"),
            (|p| p.p_photo = 1.5, "p_photo"),
            (|p| p.noise = 3, "noise"),
            (|p| p.dt = 0.1, "dt"), // the bound: 0.1·3.5 > 0.2
        ];
        for (break_it, field) in cases {
            let mut p = ok;
            break_it(&mut p);
            assert_eq!(p.validate(), Err(Error::BadParam { field }));
        }
        // Extreme but in-range values: no overflow panics in fixed point.
        let p = WangParams::<Fx> {
            scale: Fx::from_bits(1),
            gain: Fx::from_f32(16.0),
            ..WangParams::default()
        };
        assert_eq!(p.validate(), Err(Error::BadParam { field: "dt" }));
    }
}
