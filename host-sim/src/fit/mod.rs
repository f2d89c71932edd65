//! Calibration: a scenario's parameters fitted to trajectories by maximising the evaluation
//! score E (ren2016 §"Evaluation" Steps 1-2, Eq. 6-7; spec §2.6 "Par-Est") with a genetic
//! algorithm ([`Ga`]: chen §VI's, with the changes its notes give), for any model.
//!
//! Every individual is the scenario with its genes written into each group's parameter table
//! (what a scenario file's `fly = { gamma = 2.0 }` does), checked by the model's own rules
//! (an individual they refuse scores −∞ and is counted), run with the same seeds (common random
//! numbers) for a burn-in and then recorded, and scored against the reference by
//! [`score`]: E = 1 − (1/7) Σ_φ E_φ, Eq. 6 with Step 1's weights (w = 1/7, p1 = 0, p2 = 1),
//! which depends on the individual alone.
//!
//! ```
//! use swarm_sim::{eval::Scaling, fit::{self, Calibration, Ga, Param, Sampling}, scenario};
//!
//! let mut sc = scenario::builtin("fly-fig1-midges").unwrap();
//! sc.groups[0].count = 10;
//! // The "measured" tracks: the scenario itself, another seed.
//! let sampling = Sampling { burn_in: 5, frames: 20, every: 1, seeds: vec![3] };
//! let reference = fit::simulate(&sc, 0.01, &sampling).unwrap();
//! let sampling = Sampling { seeds: vec![7], ..sampling };
//! let cal = Calibration {
//!     params: vec!["gamma=0.5:4".parse().unwrap()],
//!     sampling,
//!     scaling: Scaling::Reference,
//!     ga: Ga { generations: 2, ..Ga::default() },
//! };
//! let fitted = fit::calibrate(&sc, &reference, &cal, |_, _| {}).unwrap();
//! assert_eq!(fitted.values[0].0, "gamma");
//! assert!((0.5..=4.0).contains(&fitted.values[0].1));
//! ```

mod ga;

use std::str::FromStr;
use std::sync::atomic::{AtomicUsize, Ordering};

pub use ga::{Ga, Outcome, Search};

use swarm_core::model::{ParamSpec, Range};

use crate::engine::{Engine, apply_due_events};
use crate::error::{Result, SimError};
use crate::eval::score::{BINS, RANGE};
use crate::eval::{METRICS, Samples, Scaling, Tracks, energy, samples};
use crate::scenario::Scenario;

/// One real parameter to fit and its range, `NAME=LOW:HIGH` (searched uniformly) or
/// `NAME=LOW:HIGH:log` (uniformly in its logarithm: for a positive range over decades) on the
/// command line.
#[derive(Clone, Debug, PartialEq)]
pub struct Param {
    /// The parameter's name in the model's table (`gamma`, `chi_rep`; `swarm models`).
    pub name: String,
    /// The smallest value tried.
    pub low: f64,
    /// The largest value tried.
    pub high: f64,
    /// Whether the search runs over ln(value).
    pub log: bool,
}

impl Param {
    /// The gene's range: the value's, or its logarithm's.
    pub fn gene_range(&self) -> (f64, f64) {
        (self.gene(self.low), self.gene(self.high))
    }

    /// The gene of value `v`: `v`, or ln `v`.
    pub fn gene(&self, v: f64) -> f64 {
        if self.log { v.ln() } else { v }
    }

    /// The value of gene `g`.
    pub fn value(&self, g: f64) -> f64 {
        if self.log {
            g.exp().clamp(self.low, self.high)
        } else {
            g
        }
    }
}

impl Param {
    /// `NAME=LOW:HIGH[:log]` as [`FromStr`] reads it, inside the values the model's table
    /// `params` gives the parameter ([`ModelEntry::params`]), or `NAME` alone: the whole range
    /// of that real parameter (an open lower end moved just inside, where f32 and fixed point
    /// both accept it; what the Python package's `search_space` uses).
    ///
    /// [`ModelEntry::params`]: crate::models::ModelEntry::params
    ///
    /// # Errors
    ///
    /// What [`FromStr`] refuses; a name alone that is not a real parameter of the table; an
    /// integer parameter; a range leaving the model's ([`SimError::FitRange`]). A name the
    /// table lacks, given with a range, is left to [`calibrate`]'s check (which names it).
    pub fn resolve(spec: &str, params: &[ParamSpec]) -> Result<Param> {
        let bad = |problem: &'static str| SimError::FitParam {
            spec: spec.into(),
            problem,
        };
        let given = match spec.contains('=') {
            true => Some(spec.parse::<Param>()?),
            false => None,
        };
        let name = given
            .as_ref()
            .map_or(spec.trim(), |p| p.name.as_str())
            .to_string();
        let Some(found) = params.iter().find(|p| p.name == name) else {
            return given.ok_or(bad(
                "not a parameter of the scenario's model (`swarm models MODEL` lists them)",
            ));
        };
        let Range::Real { min, max, min_open } = found.range else {
            return Err(bad("an integer parameter: calibration fits real ones"));
        };
        if let Some(p) = given {
            let (lo, hi) = (f64::from(min.f32()), f64::from(max.f32()));
            let inside = if min_open { p.low > lo } else { p.low >= lo } && p.high <= hi;
            if !inside {
                return Err(SimError::FitRange {
                    name: p.name,
                    low: p.low,
                    high: p.high,
                    range: found.range,
                });
            }
            return Ok(p);
        }
        let (mut low, high) = (f64::from(min.f32()), f64::from(max.f32()));
        if min_open {
            // A part in a million of the range inside, and at least the fixed point's step.
            low += ((high - low) * 1e-6).max(1.0 / 65536.0);
        }
        Ok(Param {
            name,
            low,
            high,
            log: false,
        })
    }
}

impl FromStr for Param {
    type Err = SimError;

    /// Reads `NAME=LOW:HIGH` or `NAME=LOW:HIGH:log` (finite bounds, LOW ≤ HIGH; LOW > 0
    /// on a log scale).
    fn from_str(spec: &str) -> Result<Param> {
        let bad = |problem: &'static str| SimError::FitParam {
            spec: spec.into(),
            problem,
        };
        let (name, range) = spec.split_once('=').ok_or(bad("expected NAME=LOW:HIGH"))?;
        let (range, log) = match range.strip_suffix(":log") {
            Some(r) => (r, true),
            None => (range, false),
        };
        let (low, high) = range
            .split_once(':')
            .ok_or(bad("expected a range LOW:HIGH after `=`"))?;
        let number = |s: &str| {
            s.trim()
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or(bad("a bound is not a finite number"))
        };
        let (low, high) = (number(low)?, number(high)?);
        if name.trim().is_empty() {
            return Err(bad("the parameter has no name"));
        }
        if low > high {
            return Err(bad("LOW is above HIGH"));
        }
        if log && low <= 0.0 {
            return Err(bad("a log scale needs LOW > 0"));
        }
        Ok(Param {
            name: name.trim().into(),
            low,
            high,
            log,
        })
    }
}

/// How a scenario is run to compare with the reference.
#[derive(Clone, Debug, PartialEq)]
pub struct Sampling {
    /// Ticks run before the first recorded frame.
    pub burn_in: u32,
    /// Frames recorded per run.
    pub frames: u32,
    /// Ticks per recorded frame (the reference's frame interval in ticks).
    pub every: u32,
    /// The seeds of the runs pooled into one set of tracks (the same for every individual).
    pub seeds: Vec<u32>,
}

/// `sc` with every group's parameter `name` set to `value`, for each pair, checked by the
/// models' rules.
///
/// # Errors
///
/// What [`Scenario::validate`] refuses (a name the model does not have, a value out of its
/// range, rules between parameters such as ordered radii).
pub fn with_params(sc: &Scenario, values: &[(&str, f64)]) -> Result<Scenario> {
    let mut sc = sc.clone();
    for g in &mut sc.groups {
        let table = g.params.get_or_insert_with(toml::Table::new);
        for &(name, value) in values {
            table.insert(name.into(), toml::Value::Float(value));
        }
    }
    sc.validate()?;
    Ok(sc)
}

/// The tracks of `sc` run with each of `sampling.seeds` ([`record`]) at frame interval `dt`
/// (s).
///
/// # Errors
///
/// What building the engine or a tick refuses.
pub fn simulate(sc: &Scenario, dt: f64, sampling: &Sampling) -> Result<Tracks> {
    Ok(Tracks::from_samples(dt, record(sc, sampling)?))
}

/// The `(insect, frame, position)` samples of `sc` run with each of `sampling.seeds`: after
/// the burn-in, every agent's position every `sampling.every` ticks for `sampling.frames`
/// frames; the runs' agents are distinct insects (the second run's ids follow the first's).
///
/// # Errors
///
/// What building the engine or a tick refuses.
pub fn record(sc: &Scenario, sampling: &Sampling) -> Result<Vec<(u64, i64, [f64; 3])>> {
    let mut points = Vec::new();
    let mut first_id = 0u64;
    for &seed in &sampling.seeds {
        let mut engine = crate::models::engine(sc, seed)?;
        let tick = |engine: &mut Box<dyn Engine>| -> Result<()> {
            apply_due_events(&mut **engine, sc);
            engine.tick()
        };
        for _ in 0..sampling.burn_in {
            tick(&mut engine)?;
        }
        for frame in 0..sampling.frames {
            for _ in 0..sampling.every.max(1) {
                tick(&mut engine)?;
            }
            engine.sync()?;
            let agents = engine.frame().agents;
            points.extend(agents.iter().map(|a| {
                (
                    first_id + u64::from(a.id),
                    i64::from(frame),
                    a.pos.map(f64::from),
                )
            }));
        }
        first_id += engine.agents() as u64;
    }
    Ok(points)
}

/// [`record`] on a pool of `threads` workers (the results are the same for any count).
///
/// # Errors
///
/// What [`record`] refuses, [`SimError::NoThreads`] for zero threads.
pub fn record_on(
    sc: &Scenario,
    sampling: &Sampling,
    threads: usize,
) -> Result<Vec<(u64, i64, [f64; 3])>> {
    let (pool, _) = crate::par::pool(Some(threads))?;
    pool.install(|| record(sc, sampling))
}

/// The largest E_φ there is: two densities of [`BINS`] bins over [`RANGE`] with no mass in
/// common. A metric with no sample on either side scores it.
pub const WORST_ENERGY: f64 = 2.0 * BINS as f64 / (RANGE.1 - RANGE.0);

/// E = 1 − (1/7) Σ_φ E_φ (Eq. 6 with Step 1's weights 1/7 and Eq. 8's p1 = 0, p2 = 1) of
/// tracks `sim` against the reference's metric samples `real`, each metric's sets z-scored by
/// `scaling`. 1 for identical distributions; never below 1 − [`WORST_ENERGY`].
pub fn score(real: &Samples, sim: &Tracks, scaling: Scaling) -> f64 {
    let sim = samples(sim);
    let total: f64 = (0..METRICS.len())
        .map(|k| energy(&real.0[k], &sim.0[k], scaling).unwrap_or(WORST_ENERGY))
        .sum();
    1.0 - total / METRICS.len() as f64
}

/// What to fit and how.
#[derive(Clone, Debug, PartialEq)]
pub struct Calibration {
    /// The parameters and their ranges (the genes).
    pub params: Vec<Param>,
    /// How each individual is run.
    pub sampling: Sampling,
    /// Whose moments z-score each metric ([`Scaling`]).
    pub scaling: Scaling,
    /// The genetic algorithm.
    pub ga: Ga,
}

/// A finished calibration.
#[derive(Clone, Debug, PartialEq)]
pub struct Fitted {
    /// The best value of each parameter, in [`Calibration::params`] order.
    pub values: Vec<(String, f64)>,
    /// The scenario with them.
    pub scenario: Scenario,
    /// Its score E ([`score`]).
    pub score: f64,
    /// The best score after each generation.
    pub history: Vec<f64>,
    /// Individuals scored.
    pub evaluations: usize,
    /// Individuals the model's rules refused or whose run failed (scored −∞).
    pub refused: usize,
}

/// Fits `cal.params` of `sc` to `reference` ([`Ga::maximise`] of [`score`]); `each` hears the
/// generation and the best score after every generation.
///
/// # Errors
///
/// [`SimError::FitNothing`] without parameters, what [`with_params`] refuses for the
/// parameters' names or the range midpoints (checked before the first generation), and
/// [`SimError::FitRefusedAll`] if every individual was refused.
pub fn calibrate(
    sc: &Scenario,
    reference: &Tracks,
    cal: &Calibration,
    each: impl FnMut(u32, f64),
) -> Result<Fitted> {
    if cal.params.is_empty() || cal.sampling.seeds.is_empty() || cal.sampling.frames < 3 {
        return Err(SimError::FitNothing);
    }
    let pairs = |genes: &[f64]| -> Vec<(&str, f64)> {
        cal.params
            .iter()
            .zip(genes)
            .map(|(p, &g)| (p.name.as_str(), p.value(g)))
            .collect()
    };
    let ranges: Vec<(f64, f64)> = cal.params.iter().map(Param::gene_range).collect();
    // A misspelt name or a range a model cannot take fails here, not 2,000 runs later.
    let middle: Vec<f64> = ranges.iter().map(|r| 0.5 * (r.0 + r.1)).collect();
    with_params(sc, &pairs(&middle))?;
    let real = samples(reference);
    let refused = AtomicUsize::new(0);
    let objective = |genes: &[f64]| {
        let run =
            with_params(sc, &pairs(genes)).and_then(|s| simulate(&s, reference.dt, &cal.sampling));
        match run {
            Ok(tracks) => score(&real, &tracks, cal.scaling),
            Err(_) => {
                refused.fetch_add(1, Ordering::Relaxed);
                f64::NAN
            }
        }
    };
    let outcome = cal.ga.maximise(&ranges, objective, each);
    if outcome.score == f64::NEG_INFINITY {
        return Err(SimError::FitRefusedAll {
            evaluations: outcome.evaluations,
        });
    }
    let best = pairs(&outcome.best);
    Ok(Fitted {
        scenario: with_params(sc, &best)?,
        values: best.iter().map(|&(n, v)| (n.to_string(), v)).collect(),
        score: outcome.score,
        history: outcome.history,
        evaluations: outcome.evaluations,
        refused: refused.into_inner(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A name alone is the model's whole range; an open end starts just inside.
    #[test]
    fn a_name_alone_takes_the_models_range() {
        let fly = crate::models::get("fly").unwrap().params;
        let p = Param::resolve("gamma", fly).unwrap();
        assert_eq!((p.low, p.high, p.log), (0.0, 100.0, false));
        let p = Param::resolve("scale", fly).unwrap();
        assert!(p.low > 0.0 && p.low < 1e-4 && p.high == 64.0, "{p:?}");
        assert_eq!(
            Param::resolve("gamma=1:2:log", fly).unwrap(),
            "gamma=1:2:log".parse().unwrap()
        );
        let e = Param::resolve("gamma=1:200", fly).unwrap_err().to_string();
        assert!(e.contains("a number in [0, 100]"), "{e}");
        assert!(
            Param::resolve("scale=0:1", fly).is_err(),
            "an open end is left out"
        );
        let typo = Param::resolve("gama=1:2", fly).unwrap();
        assert_eq!(
            typo.name, "gama",
            "left to calibrate's check, which names it"
        );
        for (bad, says) in [
            ("gama", "not a parameter"),
            ("orca_neighbours", "integer"),
            ("orca_neighbours=1:4", "integer"),
        ] {
            let e = Param::resolve(bad, fly).unwrap_err().to_string();
            assert!(e.contains(bad) && e.contains(says), "{e}");
        }
    }

    #[test]
    fn params_read_and_refuse() {
        let p: Param = "gamma=0.1:20".parse().unwrap();
        assert_eq!((p.name.as_str(), p.low, p.high), ("gamma", 0.1, 20.0));
        for bad in [
            "gamma",
            "gamma=1",
            "gamma=2:1",
            "=0:1",
            "gamma=a:1",
            "gamma=0:inf",
        ] {
            let e = bad.parse::<Param>().unwrap_err();
            assert!(e.to_string().contains(bad), "{e}");
        }
    }

    /// A parameter the model does not have, or a value its rules refuse, is an error naming it.
    #[test]
    fn with_params_checks_the_model_rules() {
        let sc = crate::scenario::builtin("fly-fig1-midges").unwrap();
        let ok = with_params(&sc, &[("gamma", 2.0)]).unwrap();
        assert_ne!(ok, sc);
        let e = with_params(&sc, &[("gamma_typo", 2.0)]).unwrap_err();
        assert!(e.to_string().contains("gamma_typo"), "{e}");
        let e = with_params(&sc, &[("r_rep", 50.0)]).unwrap_err();
        assert!(e.to_string().contains("r_ali"), "{e}");
    }

    /// The score is 1 for the reference itself and lower for another model; a calibration
    /// whose every individual is refused says so.
    #[test]
    fn scores_and_refusals() {
        let mut sc = crate::scenario::builtin("fly-fig1-midges").unwrap();
        sc.groups[0].count = 12;
        let sampling = Sampling {
            burn_in: 10,
            frames: 30,
            every: 1,
            seeds: vec![5],
        };
        let reference = simulate(&sc, 0.01, &sampling).unwrap();
        let real = samples(&reference);
        assert_eq!(score(&real, &reference, Scaling::Reference), 1.0);
        let fast = with_params(&sc, &[("gamma", 0.3)]).unwrap();
        let other = simulate(&fast, 0.01, &sampling).unwrap();
        assert!(score(&real, &other, Scaling::Reference) < 0.9);
        let mut cal = Calibration {
            params: vec![],
            sampling,
            scaling: Scaling::Reference,
            ga: Ga::default(),
        };
        let fit = |cal: &Calibration| calibrate(&sc, &reference, cal, |_, _| {});
        assert!(matches!(fit(&cal), Err(SimError::FitNothing)));
        // A range whose middle the model refuses fails before the first generation.
        cal.params = vec!["r_rep=0:60".parse().unwrap()];
        let e = fit(&cal).unwrap_err();
        assert!(e.to_string().contains("r_ali"), "{e}");
    }
}
