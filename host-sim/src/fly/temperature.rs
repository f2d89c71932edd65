//! ren2016's temperature extension (§2.8 of the spec, ours): a scenario's insects resized until
//! their swarm's density is N(T) insects per unit volume, N from Eq. 1
//! ([`swarm_core::fly::temperature::density`], insects per m³).
//!
//! The density of a frame is [`local_density`] (from each insect's 5th nearest neighbour);
//! [`measure`] averages it over the recorded frames of a few seeds. The spec scales the three
//! zone radii by (ρ/N)^{1/3} until within 5 %; measured, the density does not follow those
//! radii alone (docs/models.md: ×2 on the midges' radii multiplies it by 4000), so we resize
//! the whole insect ([`FlyParams::scaled`]: every length, speed and force k times, a
//! similarity of Algorithm 1) with its spawn region. A swarm that the world does not bound is
//! then k times larger, its density k⁻³ times, and the iteration k ← k·(ρ/N)^{1/3} settles in
//! a round or two. The world, its objects and Δt stay.
//!
//! ```
//! use swarm_sim::fit::Sampling;
//! use swarm_sim::fly::temperature::{Temperature, adjust};
//!
//! let mut sc = swarm_sim::scenario::builtin("fly-fig1-midges").unwrap();
//! sc.groups[0].count = 20;
//! let t = Temperature {
//!     celsius: 20.0,
//!     metres_per_unit: 0.3,
//!     sampling: Sampling { burn_in: 200, frames: 5, every: 20, seeds: vec![1] },
//!     tolerance: 0.05,
//!     rounds: 8,
//! };
//! let done = adjust(&sc, &t, |_, _| {}).unwrap();
//! assert!((done.density / done.target - 1.0).abs() <= 0.05);
//! ```

use std::collections::BTreeMap;

use swarm_core::fly::FlyParams;
use swarm_core::fly::temperature::density;
use swarm_core::model::ModelParams;

use super::scenario::FlyParamsOverride;
use crate::error::{Result, SimError};
use crate::fit::{Sampling, simulate};
use crate::scenario::{Model, Scenario, SpawnRegion, World};

/// What [`adjust`] aims at and how it measures.
#[derive(Clone, Debug, PartialEq)]
pub struct Temperature {
    /// The environment's temperature T (°C).
    pub celsius: f64,
    /// The scenario's length unit in metres (N(T) is per m³).
    pub metres_per_unit: f64,
    /// How each round runs the scenario (its frames' interval is irrelevant here).
    pub sampling: Sampling,
    /// The relative error in the density accepted (the spec's 5 %).
    pub tolerance: f64,
    /// The most rounds of measuring and resizing.
    pub rounds: u32,
}

impl Temperature {
    /// N(T) in insects per unit³ of the scenario.
    pub fn target(&self) -> f64 {
        density(self.celsius) * self.metres_per_unit.powi(3)
    }
}

/// A scenario resized to a temperature.
#[derive(Clone, Debug)]
pub struct Adjusted {
    /// The scenario with every ren2016 group resized by [`Adjusted::scale`].
    pub scenario: Scenario,
    /// N(T) in insects per unit³.
    pub target: f64,
    /// The resizing k of the insects (1: as given).
    pub scale: f64,
    /// The density measured on [`Adjusted::scenario`] (per unit³, [`local_density`]).
    pub density: f64,
    /// Each round's resizing and the density measured with it, the given scenario
    /// (k = 1) first.
    pub rounds: Vec<(f64, f64)>,
}

/// The neighbours counted by [`local_density`]: the K of its K-th nearest neighbour.
pub const NEIGHBOURS: usize = 5;

/// The swarm's density in one frame (insects per unit³): (K − ⅓) / (4/3·π·d³), d the median
/// over the insects of the distance to their K-th nearest neighbour (K = [`NEIGHBOURS`]);
/// `None` for K insects or fewer, or a median of 0.
///
/// For insects scattered uniformly at density ρ the volume of that ball is Gamma(K, 1/ρ)
/// distributed, with median ≈ (K − ⅓)/ρ, so the estimate is unbiased there; and it is exactly
/// k⁻³ times as large for every position k times as far apart. Ours, in place of the spec's
/// "core = the 90 % nearest the centroid": ren2016's swarms fragment (the midges into clumps
/// held apart by ORCA), and the 90 % radius then spans the gaps between fragments; measured,
/// it varied two- to fourfold between seeds of the same midges, the local density by a few
/// per cent (docs/models.md).
pub fn local_density(points: &[[f64; 3]]) -> Option<f64> {
    let n = points.len();
    if n <= NEIGHBOURS {
        return None;
    }
    let mut kth: Vec<f64> = points
        .iter()
        .map(|p| {
            let mut d: Vec<f64> = points.iter().map(|q| dist2(p, q)).collect();
            // d[0] is the insect itself (or a twin at 0: a neighbour at distance 0).
            *d.select_nth_unstable_by(NEIGHBOURS, f64::total_cmp).1
        })
        .collect();
    let median = *kth.select_nth_unstable_by(n / 2, f64::total_cmp).1;
    let r = median.sqrt();
    let k = NEIGHBOURS as f64 - 1.0 / 3.0;
    (r > 0.0).then(|| k / (4.0 / 3.0 * std::f64::consts::PI * r.powi(3)))
}

fn dist2(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum()
}

/// The mean [`local_density`] of `sc`'s agents over the recorded frames of every seed of
/// `sampling` (each seed's frames on their own).
///
/// # Errors
///
/// What running the scenario refuses; [`SimError::TemperatureNoInsects`] when no frame has a
/// density (no more than [`NEIGHBOURS`] agents).
pub fn measure(sc: &Scenario, sampling: &Sampling) -> Result<f64> {
    let (mut sum, mut count) = (0.0, 0u32);
    for &seed in &sampling.seeds {
        let one = Sampling {
            seeds: vec![seed],
            ..sampling.clone()
        };
        let mut frames: BTreeMap<i64, Vec<[f64; 3]>> = BTreeMap::new();
        for track in simulate(sc, 1.0, &one)?.by_id.into_values() {
            for (k, p) in track {
                frames.entry(k).or_default().push(p);
            }
        }
        for rho in frames.values().filter_map(|f| local_density(f)) {
            sum += rho;
            count += 1;
        }
    }
    if count == 0 {
        return Err(SimError::TemperatureNoInsects {
            scenario: sc.name.clone(),
        });
    }
    Ok(sum / f64::from(count))
}

fn is_fly(model: &Model) -> bool {
    *model == Model::new("fly")
}

/// `sc` with every ren2016 group's insects `k` times larger
/// ([`FlyParams::scaled`](swarm_core::fly::FlyParams::scaled); the parameters that change are
/// written into the group's table over its preset) and its spawn region `k` times larger
/// about its centre (a box within the world), checked by the model's rules.
///
/// # Errors
///
/// What [`Scenario::validate`] refuses (parameters out of their ranges for large `k`).
pub fn resized(sc: &Scenario, k: f64) -> Result<Scenario> {
    let mut sc = sc.clone();
    let (lo, hi) = match &sc.world {
        World::Space { min, max } => (min.to_vec(), max.to_vec()),
        World::Plane { min, max } => (min.to_vec(), max.to_vec()),
    };
    for g in sc.groups.iter_mut().filter(|g| is_fly(&g.model)) {
        let mut table = g.params_as::<FlyParamsOverride>()?;
        let given = table.params();
        let scaled = given.scaled(k as f32);
        for (i, spec) in FlyParams::<f32>::SPECS.iter().enumerate() {
            if let Some(v) = scaled.get(i).filter(|v| Some(*v) != given.get(i)) {
                table.overrides.set(spec.name, v);
            }
        }
        g.set_params(&table)?;
        match &mut g.spawn.region {
            SpawnRegion::Around { radius, .. } => *radius *= k as f32,
            SpawnRegion::Box { min, max } => {
                for i in 0..min.len() {
                    let (c, half) = ((min[i] + max[i]) / 2.0, (max[i] - min[i]) / 2.0);
                    let half = half * k as f32;
                    min[i] = (c - half).max(lo[i]);
                    max[i] = (c + half).min(hi[i]);
                }
            }
        }
    }
    sc.validate()?;
    Ok(sc)
}

/// `sc` resized ([`resized`]) until its density is N(T) within `t.tolerance`, the
/// iteration of spec §2.8 on the whole insect; `progress(k, density)` after each round.
///
/// Refused before any run: a temperature where Eq. 1 gives no swarm, a scenario without a
/// ren2016 group, and a swarm that at N(T) would not fit in the world.
///
/// # Errors
///
/// [`SimError::TemperatureNoSwarm`], [`SimError::TemperatureNoInsects`],
/// [`SimError::TemperatureTooSparse`], what running or
/// resizing refuses, and [`SimError::TemperatureUnreached`] after `t.rounds` rounds.
pub fn adjust(
    sc: &Scenario,
    t: &Temperature,
    mut progress: impl FnMut(f64, f64),
) -> Result<Adjusted> {
    let target = t.target();
    let insects: u32 = sc
        .groups
        .iter()
        .filter(|g| is_fly(&g.model))
        .map(|g| g.count)
        .sum();
    if target.is_nan() || target <= 0.0 {
        return Err(SimError::TemperatureNoSwarm { celsius: t.celsius });
    }
    if insects as usize <= NEIGHBOURS {
        return Err(SimError::TemperatureNoInsects {
            scenario: sc.name.clone(),
        });
    }
    let needed = f64::from(insects) / target;
    let world = match &sc.world {
        World::Space { min, max } => min.iter().zip(max).map(|(a, b)| f64::from(b - a)).product(),
        World::Plane { .. } => 0.0,
    };
    if needed > world {
        return Err(SimError::TemperatureTooSparse {
            celsius: t.celsius,
            target,
            needed,
            world,
        });
    }
    let (mut k, mut rounds) = (1.0, Vec::new());
    let mut current = sc.clone();
    for round in 0..=t.rounds {
        let rho = measure(&current, &t.sampling)?;
        rounds.push((k, rho));
        progress(k, rho);
        if (rho / target - 1.0).abs() <= t.tolerance {
            return Ok(Adjusted {
                scenario: current,
                target,
                scale: k,
                density: rho,
                rounds,
            });
        }
        if round == t.rounds {
            break;
        }
        k *= (rho / target).cbrt();
        current = resized(sc, k)?;
    }
    Err(SimError::TemperatureUnreached {
        celsius: t.celsius,
        target,
        rounds,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Points scattered uniformly at a known density (a 20³ cube, 8000 points: density 1)
    /// give it within 10 % (the faces' insects see fewer neighbours); k times farther apart,
    /// exactly k⁻³ times; too few points or all at one place have none.
    #[test]
    fn the_local_density_of_a_uniform_cloud() {
        let ctx = |i: u32| swarm_core::StepCtx {
            seed: 3,
            agent: i,
            step: 0,
        };
        let pts: Vec<[f64; 3]> = (0..8000)
            .map(|i| [0, 1, 2].map(|s| 20.0 * f64::from(swarm_core::rand::unit::<f32>(ctx(i), s))))
            .collect();
        let rho = local_density(&pts).unwrap();
        assert!((rho - 1.0).abs() < 0.1, "{rho}");
        let far: Vec<[f64; 3]> = pts.iter().map(|p| p.map(|x| 3.0 * x)).collect();
        let ratio = local_density(&far).unwrap() * 27.0 / rho;
        assert!((ratio - 1.0).abs() < 1e-9, "{ratio}");
        assert_eq!(local_density(&pts[..NEIGHBOURS]), None);
        assert_eq!(local_density(&[[1.0; 3]; 9]), None);
    }

    /// Resizing writes the scaled parameters over the preset, keeps what does not scale and
    /// grows the spawn box about its centre within the world.
    #[test]
    fn resizing_scales_the_insect_and_its_spawn() {
        let sc = crate::scenario::builtin("fly-fig1-midges").unwrap();
        let big = resized(&sc, 2.0).unwrap();
        let p = super::super::fly_params(&big.groups[0]).unwrap();
        let q = super::super::fly_params(&sc.groups[0]).unwrap();
        assert_eq!(p, q.scaled(2.0));
        assert_eq!((p.tau, p.dt), (q.tau, q.dt));
        let SpawnRegion::Box { min, max } = &big.groups[0].spawn.region else {
            panic!("a box");
        };
        // [4, 16] about 10, doubled: [−2, 22] within the world [0, 20].
        assert_eq!(
            (min.as_slice(), max.as_slice()),
            (&[0.0; 3][..], &[20.0; 3][..])
        );
        let back = resized(&big, 0.5).unwrap();
        let r = super::super::fly_params(&back.groups[0]).unwrap();
        assert!((r.r_att - q.r_att).abs() < 1e-6 && (r.gain - q.gain).abs() < 1e-5);
    }

    /// Refused before running: no swarm at 40 °C, a scenario without ren2016 insects, and 100
    /// midges at 20 °C (18.9 per m³: 5.3 m³) in the 20-unit box of 4.55 cm units (0.75 m³).
    #[test]
    fn impossible_temperatures_are_refused_first() {
        let sc = crate::scenario::builtin("fly-fig1-midges").unwrap();
        let t = |celsius, metres_per_unit| Temperature {
            celsius,
            metres_per_unit,
            sampling: Sampling {
                burn_in: 1,
                frames: 1,
                every: 1,
                seeds: vec![1],
            },
            tolerance: 0.05,
            rounds: 1,
        };
        let none = |_, _| panic!("no run");
        assert!(matches!(
            adjust(&sc, &t(40.0, 1.0), none),
            Err(SimError::TemperatureNoSwarm { .. })
        ));
        let err = adjust(&sc, &t(20.0, 0.0455), none).unwrap_err();
        assert!(
            matches!(err, SimError::TemperatureTooSparse { .. }),
            "{err}"
        );
        let ants = crate::scenario::builtin("ants-fig7a-single-colony").unwrap();
        assert!(matches!(
            adjust(&ants, &t(20.0, 1.0), none),
            Err(SimError::TemperatureNoInsects { .. })
        ));
    }
}
