//! Bee controller parameters: chen Table I for the six calibrated ones (§VI,
//! Γ = {κ1, κ2, κ3, L, ε, h}), and documented choices of ours for the constants the paper leaves
//! open.

use crate::model::{ModelParams, Range};
use crate::model_params;
use crate::{Error, Result, Scalar};

/// Largest magnitude accepted for any input number or parameter (positions, velocities,
/// densities, …). Differences of two positions stay below 32000, inside the ±32768 range of
/// [`Fx`](crate::Fx).
pub const LIMIT: f32 = 16_000.0;

/// Smallest value accepted for the strictly positive parameters (h, L, m, Δt, d0, max speed):
/// keeps `1/h⁴` (spiky kernel) and `1/L` (eq. 8) finite and inside the fixed-point range.
pub const MIN_POSITIVE: f32 = 0.01;

wire_type! {
    /// The parameters of the bee controller.
    ///
    /// Table I gives h, L, κ1-3 and ε ([`Default`]: the "Optimized values" column; see also
    /// [`BeeParams::grassland`] and [`BeeParams::around_nest`]). The paper does not give the
    /// other constants; our choices are marked "ours" (units: one length unit ≈ one body
    /// length, seconds, mass normalized to 1).
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct BeeParams<S> {
        /// h: SPH neighbourhood (kernel) radius (eq. 10-11). Table I: 3.
        pub h: S,
        /// L: edge length of the noise lattice (eq. 8). Table I: 2.7.
        pub grid_edge: S,
        /// κ1: weight of the oscillation force F_o (eq. 1). Table I: 1.4.
        pub kappa1: S,
        /// κ2: weight of the curl-noise force F_curl (eq. 1). Table I: 2.3.
        pub kappa2: S,
        /// κ3: weight of the repulsion force F_repul (eq. 1). Table I: 1.2.
        pub kappa3: S,
        /// ε: magnitude of the Perlin potentials (eq. 8). Table I: 1.7.
        pub epsilon: S,
        /// m: mass of every bee and of every virtual target particle (eq. 1, 2, 10). Ours: 1.
        pub mass: S,
        /// g: gravity in the thrust and sway of eq. 2. The weight m·g itself is carried by the
        /// mean lift (see [`oscillation_force`](super::oscillation::oscillation_force)), so it
        /// is not added to eq. 1. Ours: 9.81.
        pub gravity: S,
        /// ρ: air density in the lift of eq. 2. Ours: 1.225.
        pub air_density: S,
        /// A: wing area in the lift of eq. 2. Ours: 0.05.
        pub wing_area: S,
        /// r: radius of the bee's capsule (eq. 10-11). Ours: 0.25.
        pub radius: S,
        /// d0: distance threshold of obstacle avoidance (eq. 5-6). Ours: 2.
        pub d0: S,
        /// Δt: time step (§III). Ours: 0.05 s.
        pub dt: S,
        /// k: pressure stiffness, p = k·max(ρ − ρ0, 0) (§V-B). Ours, per Table I column:
        /// the smallest round value at which two bees in contact (gap 0) repel each other at
        /// least as hard as the largest sum of the other forces can push one of them,
        /// κ3·m·k·|∇W_spiky(0, h)| ≥ κ1·m·g·(θ_pitch,max + |θ_roll − θ̄_roll|max) + κ2·max|F_curl|
        /// (eq. 2-4 with the sway about its mean; max|∇×ψ| ≈ 4.8·ε/L for our Perlin noise, sampled):
        /// 80 for the optimized values (bound 76.6), 200 over grassland (199.8), 60 around the
        /// nest (58.4). With k = 1 the contact force was 1/15 of the thrust alone and 13-53 % of the bees
        /// had a neighbour closer than 2r; see [`stiffness_for_contact`].
        pub stiffness: S,
        /// ρ0: rest density of the pressure (§V-B). Ours: 0 (any overlap repels).
        pub rest_density: S,
        /// Upper bound of the speed |u*| after each step (a safety limit: the drag keeps
        /// ordinary flight below it). Ours: 4.
        pub max_speed: S,
        /// c: linear drag rate (1/s), F_drag = −m·c·u added to eq. 1. The paper applies no
        /// drag (§IV-A) but notes that drag "plays a role in decreasing the velocity"; without
        /// it every bee flies at the speed limit. Linear in u as the flapping counter-force of
        /// flapping flight is. Ours: 1.5 (a 0.67 s velocity relaxation time). `c·Δt ≤ 1`.
        pub damping: S,
    }
}

impl<S: Scalar> Default for BeeParams<S> {
    /// Table I, "Optimized values": h 3, L 2.7, κ 1.4/2.3/1.2, ε 1.7 (and ours for the rest).
    fn default() -> Self {
        Self::table_i(3.0, 2.7, [1.4, 2.3, 1.2], 1.7, 80.0)
    }
}

impl<S: Scalar> BeeParams<S> {
    /// Table I, "Over grassland": h 3, L 2.2, κ 1.5/5/0.9, ε 2.
    pub fn grassland() -> Self {
        Self::table_i(3.0, 2.2, [1.5, 5.0, 0.9], 2.0, 200.0)
    }

    /// Table I, "Around nest": h 3, L 2.2, κ 1/2.5/1.7, ε 2.
    pub fn around_nest() -> Self {
        Self::table_i(3.0, 2.2, [1.0, 2.5, 1.7], 2.0, 60.0)
    }

    /// One column of Table I plus our constants (and our stiffness for it).
    fn table_i(h: f32, grid_edge: f32, kappa: [f32; 3], epsilon: f32, stiffness: f32) -> Self {
        let c = S::from_f32;
        BeeParams {
            h: c(h),
            grid_edge: c(grid_edge),
            kappa1: c(kappa[0]),
            kappa2: c(kappa[1]),
            kappa3: c(kappa[2]),
            epsilon: c(epsilon),
            mass: S::ONE,
            gravity: c(9.81),
            air_density: c(1.225),
            wing_area: c(0.05),
            radius: c(0.25),
            d0: c(2.0),
            dt: c(0.05),
            stiffness: c(stiffness),
            rest_density: S::ZERO,
            max_speed: c(4.0),
            damping: c(1.5),
        }
    }

    /// The same parameters in another scalar type (through `f32`).
    pub fn cast<T: Scalar>(&self) -> BeeParams<T> {
        let c = |v: S| T::from_f32(v.to_f32());
        BeeParams {
            h: c(self.h),
            grid_edge: c(self.grid_edge),
            kappa1: c(self.kappa1),
            kappa2: c(self.kappa2),
            kappa3: c(self.kappa3),
            epsilon: c(self.epsilon),
            mass: c(self.mass),
            gravity: c(self.gravity),
            air_density: c(self.air_density),
            wing_area: c(self.wing_area),
            radius: c(self.radius),
            d0: c(self.d0),
            dt: c(self.dt),
            stiffness: c(self.stiffness),
            rest_density: c(self.rest_density),
            max_speed: c(self.max_speed),
            damping: c(self.damping),
        }
    }

    /// The parameters, validated once (see [`Checked`](crate::Checked)).
    pub fn checked(self) -> Result<crate::Checked<Self>> {
        ModelParams::checked(self)
    }

    /// Checks every parameter: finite and at most [`LIMIT`]; h, L, m, Δt, d0 and the speed
    /// limit at least [`MIN_POSITIVE`]; all others ≥ 0; and the drag at most one velocity per
    /// step, `damping·dt ≤ 1` (explicit Euler then never reverses the velocity). The error
    /// names the first bad one.
    pub fn validate(&self) -> Result<()> {
        ModelParams::validate(self)
    }
}

model_params! {
    BeeParams {
        h: real = Range::closed(MIN_POSITIVE, LIMIT), "units";
        grid_edge: real = Range::closed(MIN_POSITIVE, LIMIT), "units";
        mass: real = Range::closed(MIN_POSITIVE, LIMIT), "";
        d0: real = Range::closed(MIN_POSITIVE, LIMIT), "units";
        dt: real = Range::closed(MIN_POSITIVE, LIMIT), "s";
        max_speed: real = Range::closed(MIN_POSITIVE, LIMIT), "units/s";
        kappa1: real = Range::closed(0.0, LIMIT), "";
        kappa2: real = Range::closed(0.0, LIMIT), "";
        kappa3: real = Range::closed(0.0, LIMIT), "";
        epsilon: real = Range::closed(0.0, LIMIT), "";
        gravity: real = Range::closed(0.0, LIMIT), "units/s²";
        air_density: real = Range::closed(0.0, LIMIT), "";
        wing_area: real = Range::closed(0.0, LIMIT), "units²";
        radius: real = Range::closed(0.0, LIMIT), "units";
        stiffness: real = Range::closed(0.0, LIMIT), "";
        rest_density: real = Range::closed(0.0, LIMIT), "";
        damping: real = Range::closed(0.0, LIMIT), "1/s, with damping·dt ≤ 1";
    }
    together damping_fits
}

impl<S: Scalar> BeeParams<S> {
    /// The one rule between fields: the velocity damping may not overshoot in a step.
    fn damping_fits(&self) -> Result<()> {
        if self.damping * self.dt > S::ONE {
            return Err(Error::BadParam { field: "damping" });
        }
        Ok(())
    }
}

/// The stiffness bound behind [`BeeParams::stiffness`]'s defaults, in `f32`: the k at which
/// the SPH pair force at contact, κ3·m·k·45/(π h⁴) (the symmetric eq. 11 with
/// (p_i + p_j)/(2ρ_j) ≥ k, kernel at gap 0), equals the largest sum of the driving forces,
/// κ1·m·g·(θ_pitch,max + the sway amplitude) + κ2·4.8·ε/L (eq. 2-4, 8-9).
pub fn stiffness_for_contact(p: &BeeParams<f32>) -> f32 {
    let angles = (19.929_f32 + 18.914).to_radians();
    let drive = p.kappa1 * p.mass * p.gravity * angles + p.kappa2 * 4.8 * p.epsilon / p.grid_edge;
    let contact = p.kappa3 * p.mass * 45.0 / (core::f32::consts::PI * p.h * p.h * p.h * p.h);
    drive / contact
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Fx;

    #[test]
    fn table_i_columns() {
        let p = BeeParams::<f32>::default();
        assert_eq!((p.h, p.grid_edge, p.epsilon), (3.0, 2.7, 1.7));
        assert_eq!((p.kappa1, p.kappa2, p.kappa3), (1.4, 2.3, 1.2));
        let g = BeeParams::<f32>::grassland();
        assert_eq!(
            (g.grid_edge, g.kappa1, g.kappa2, g.kappa3, g.epsilon),
            (2.2, 1.5, 5.0, 0.9, 2.0)
        );
        let n = BeeParams::<f32>::around_nest();
        assert_eq!((n.kappa1, n.kappa2, n.kappa3), (1.0, 2.5, 1.7));
        for p in [p, g, n] {
            assert_eq!(p.validate(), Ok(()));
            assert_eq!(p.cast::<Fx>().validate(), Ok(()));
        }
        assert_eq!(BeeParams::<Fx>::default().h, Fx::from_f32(3.0));
    }

    #[test]
    fn default_stiffness_lets_the_contact_force_match_the_driving_forces() {
        for (p, lo) in [
            (BeeParams::<f32>::default(), 70.0),
            (BeeParams::grassland(), 190.0),
            (BeeParams::around_nest(), 55.0),
        ] {
            let k = stiffness_for_contact(&p);
            assert!(k > lo && p.stiffness >= k, "{k} vs {}", p.stiffness);
            assert!(p.stiffness < 1.1 * k, "{k} vs {}", p.stiffness);
        }
    }

    #[test]
    fn validate_names_the_bad_parameter() {
        let ok = BeeParams::<f32>::default();
        type Breaker = fn(&mut BeeParams<f32>);
        let cases: [(Breaker, &str); 8] = [
            (|p| p.h = 0.0, "h"),
            (|p| p.grid_edge = f32::NAN, "grid_edge"),
            (|p| p.mass = -1.0, "mass"),
            (|p| p.dt = f32::INFINITY, "dt"),
            (|p| p.d0 = 0.0, "d0"),
            (|p| p.kappa2 = -0.5, "kappa2"),
            (|p| p.damping = -1.0, "damping"),
            (|p| p.damping = 20.5, "damping"), // c·Δt > 1
        ];
        for (break_it, field) in cases {
            let mut p = ok;
            break_it(&mut p);
            assert_eq!(p.validate(), Err(Error::BadParam { field }));
        }
        let p = BeeParams {
            stiffness: Fx::MAX,
            ..BeeParams::<Fx>::default()
        };
        assert_eq!(p.validate(), Err(Error::BadParam { field: "stiffness" }));
    }
}
