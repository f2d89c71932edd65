//! `swarm._swarm`, the native module of the `swarm` Python package (`python/swarm/`): the
//! simulator's scenarios, runs and evaluation, for the Python wrapper that teams call.
//!
//! Scenarios cross the boundary as JSON text of their TOML tables (the wrapper turns it into a
//! `dict` and back), so a scenario written as a `dict` goes through the same loader and rules,
//! with the same messages, as a scenario file. A run keeps its recorded frames in memory
//! ([`swarm_sim::run::run_in_memory`]) and hands them to NumPy without a copy (the arrays own
//! the vectors). Every error is a `swarm.SwarmError` carrying the `swarm` command's message.

use std::path::{Path, PathBuf};

use numpy::ndarray::{Array1, Array2, Array3};
use numpy::{IntoPyArray, PyArray3, PyReadonlyArray3};
use pyo3::create_exception;
use pyo3::exceptions::{PyException, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use swarm_core::model::Range;
use swarm_sim::eval::{Scaling, Tracks, evaluate, report, samples};
use swarm_sim::fit;
use swarm_sim::output::Frame;
use swarm_sim::run::{RunOptions, run_in_memory};
use swarm_sim::scenario::{Backend, Scenario, check_steps};

create_exception!(
    _swarm,
    SwarmError,
    PyException,
    "An error of the simulator; its message is the `swarm` command's."
);

fn err(e: impl std::fmt::Display) -> PyErr {
    SwarmError::new_err(e.to_string())
}

/// The names of the built-in scenarios.
#[pyfunction]
fn builtin_names() -> Vec<&'static str> {
    swarm_sim::scenario::builtin_names().to_vec()
}

/// Every model: (name, dimensions, description).
#[pyfunction]
fn models() -> Vec<(&'static str, usize, &'static str)> {
    swarm_sim::models::all()
        .iter()
        .map(|m| (m.name, m.dim, m.about))
        .collect()
}

/// The scenario as JSON text of its TOML table.
fn to_json(sc: &Scenario) -> PyResult<String> {
    let text = sc.to_toml().map_err(err)?;
    let table: toml::Table = toml::from_str(&text).map_err(err)?;
    serde_json::to_string(&table).map_err(err)
}

/// The scenario of JSON text `json` (a TOML table written as JSON), read by the scenario
/// loader as a file at `source` would be (relative paths in it are relative to `source`'s
/// folder, else to the working directory).
fn from_json(json: &str, source: Option<&str>) -> PyResult<Scenario> {
    let value: serde_json::Value = serde_json::from_str(json)
        .map_err(|e| err(format!("the scenario is not a JSON object: {e}")))?;
    let table = toml::Table::try_from(value)
        .map_err(|e| err(format!("the scenario cannot be a TOML table: {e}")))?;
    let text = toml::to_string(&table).map_err(err)?;
    let mut sc = Scenario::from_str(&text, source.unwrap_or("<dict>")).map_err(err)?;
    sc.source = source.map(PathBuf::from);
    Ok(sc)
}

/// The scenario `name_or_path` (a built-in name or a TOML file) as JSON text, with the path
/// of its file (`None` for a built-in).
#[pyfunction]
fn load(name_or_path: &str) -> PyResult<(String, Option<String>)> {
    let sc = swarm_sim::scenario::resolve(name_or_path).map_err(err)?;
    Ok((to_json(&sc)?, sc.source.map(|p| p.display().to_string())))
}

/// Checks a scenario given as JSON text: the JSON text the loader reads back (defaults filled
/// in), or the loader's error.
#[pyfunction]
#[pyo3(signature = (scenario, source=None))]
fn check(scenario: &str, source: Option<&str>) -> PyResult<String> {
    to_json(&from_json(scenario, source)?)
}

/// `cpu`, `gpu` or none.
fn backend_of(name: Option<&str>) -> PyResult<Option<Backend>> {
    match name {
        None => Ok(None),
        Some("cpu") => Ok(Some(Backend::Cpu)),
        Some("gpu") => Ok(Some(Backend::Gpu)),
        Some(other) => Err(PyValueError::new_err(format!(
            "backend {other:?}: `cpu` or `gpu`"
        ))),
    }
}

/// One array of every recorded agent's values: `frames × agents × K`, agents in id order.
fn per_agent<T: Copy, const K: usize>(
    frames: &[Frame],
    of: impl Fn(&swarm_sim::output::AgentSample) -> [T; K],
) -> Vec<T> {
    frames
        .iter()
        .flat_map(|f| f.agents.iter().flat_map(&of))
        .collect()
}

/// The options of a run into `out` with the overrides given.
fn run_options(
    out: PathBuf,
    backend: Option<&str>,
    seed: Option<u32>,
    steps: Option<u32>,
    threads: Option<usize>,
) -> PyResult<RunOptions> {
    if let Some(s) = steps {
        check_steps(s, "steps").map_err(err)?;
    }
    Ok(RunOptions {
        out,
        steps,
        seed,
        threads,
        backend: backend_of(backend)?,
        progress: false,
        warnings: Vec::new(),
    })
}

/// Runs the scenario of JSON text `scenario` as `swarm run --out OUT` does (every output
/// written whole into folder `out`, or nothing), the GIL released; returns the summary as
/// JSON text.
#[pyfunction]
#[pyo3(signature = (scenario, source, out, *, backend=None, seed=None, steps=None, threads=None))]
#[allow(clippy::too_many_arguments)]
fn run_to(
    py: Python<'_>,
    scenario: &str,
    source: Option<&str>,
    out: PathBuf,
    backend: Option<&str>,
    seed: Option<u32>,
    steps: Option<u32>,
    threads: Option<usize>,
) -> PyResult<String> {
    let sc = from_json(scenario, source)?;
    let opts = run_options(out, backend, seed, steps, threads)?;
    let done = py.detach(|| swarm_sim::run::run(&sc, &opts)).map_err(err)?;
    serde_json::to_string(&done.summary).map_err(err)
}

/// The most positions [`read_tracks`] puts in one array (1.5 GiB).
const MAX_POSITIONS: usize = 1 << 26;

/// A tracks CSV file (or a run folder) as `(positions, dt)`: a `frames × columns × 3` array,
/// NaN where a column holds no insect, and the frame interval (`dt`, else the file's). A
/// track takes the first column free since at least one frame before it starts, so tracks of
/// insects lost and numbered anew share columns and the array stays about as wide as the most
/// insects seen at once; every metric reads the same tracks from it.
///
/// # Errors
///
/// What the evaluation command refuses in the file, and tracks spanning more than
/// [`MAX_POSITIONS`] positions.
#[pyfunction]
#[pyo3(signature = (path, dt=None))]
fn read_tracks<'py>(
    py: Python<'py>,
    path: &str,
    dt: Option<f64>,
) -> PyResult<(Bound<'py, PyArray3<f64>>, f64)> {
    let tracks = tracks_at(path, dt)?;
    let mut runs: Vec<&Vec<(i64, [f64; 3])>> =
        tracks.by_id.values().filter(|t| !t.is_empty()).collect();
    runs.sort_by_key(|t| t[0].0);
    let first = runs.first().map_or(0, |t| t[0].0);
    // Each column's last frame; a track goes into the first column free before it.
    let mut ends: Vec<i64> = Vec::new();
    let mut placed = Vec::with_capacity(runs.len());
    for t in &runs {
        let (start, end) = (t[0].0, t[t.len() - 1].0);
        let column = match ends.iter().position(|&e| e.saturating_add(1) < start) {
            Some(c) => c,
            None => {
                ends.push(end);
                ends.len() - 1
            }
        };
        ends[column] = end;
        placed.push(column);
    }
    let last = runs.iter().map(|t| t[t.len() - 1].0).max().unwrap_or(first);
    let frames = last
        .checked_sub(first)
        .and_then(|d| usize::try_from(d).ok())
        .map_or(usize::MAX, |d| {
            d.saturating_add(usize::from(!runs.is_empty()))
        });
    if frames.saturating_mul(ends.len()) > MAX_POSITIONS {
        return Err(err(format!(
            "{path}: the tracks span {frames} frames of {} columns, more than one array \
             holds ({MAX_POSITIONS} positions): is a time far off the others, or dt too small?",
            ends.len()
        )));
    }
    let mut a = Array3::from_elem((frames, ends.len(), 3), f64::NAN);
    for (t, column) in runs.iter().zip(placed) {
        for &(k, p) in t.iter() {
            for (d, v) in p.into_iter().enumerate() {
                a[[(k - first) as usize, column, d]] = v;
            }
        }
    }
    Ok((a.into_pyarray(py), tracks.dt))
}

/// Runs the scenario of JSON text `scenario` (see [`from_json`]) with the overrides given,
/// the GIL released; returns the recorded frames as arrays (`steps`, `positions`, `headings`,
/// `labels`, `motions`, `roll`, `pitch`, `groups`), the summary as JSON text and the log's
/// lines.
#[pyfunction]
#[pyo3(signature = (scenario, source=None, *, backend=None, seed=None, steps=None, threads=None, progress=false))]
#[allow(clippy::too_many_arguments)]
fn run<'py>(
    py: Python<'py>,
    scenario: &str,
    source: Option<&str>,
    backend: Option<&str>,
    seed: Option<u32>,
    steps: Option<u32>,
    threads: Option<usize>,
    progress: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let sc = from_json(scenario, source)?;
    let opts = RunOptions {
        progress,
        ..run_options(PathBuf::new(), backend, seed, steps, threads)?
    };
    let done = py.detach(|| run_in_memory(&sc, &opts)).map_err(err)?;
    let frames = &done.frames;
    let (f, n) = (frames.len(), frames.first().map_or(0, |x| x.agents.len()));
    let shape3 = |v: Vec<f32>| Array3::from_shape_vec((f, n, 3), v).map_err(err);
    let shape2 = |v| Array2::from_shape_vec((f, n), v).map_err(err);
    let out = PyDict::new(py);
    let steps: Vec<u32> = frames.iter().map(|x| x.step).collect();
    out.set_item("steps", Array1::from(steps).into_pyarray(py))?;
    out.set_item(
        "positions",
        shape3(per_agent(frames, |a| a.pos))?.into_pyarray(py),
    )?;
    out.set_item(
        "headings",
        shape3(per_agent(frames, |a| a.heading))?.into_pyarray(py),
    )?;
    out.set_item(
        "labels",
        shape2(per_agent(frames, |a| [a.label]))?.into_pyarray(py),
    )?;
    out.set_item(
        "motions",
        shape2(per_agent(frames, |a| [a.motion]))?.into_pyarray(py),
    )?;
    let roll = Array2::from_shape_vec((f, n), per_agent(frames, |a| [a.roll])).map_err(err)?;
    out.set_item("roll", roll.into_pyarray(py))?;
    let pitch = Array2::from_shape_vec((f, n), per_agent(frames, |a| [a.pitch])).map_err(err)?;
    out.set_item("pitch", pitch.into_pyarray(py))?;
    let groups: Vec<u16> = frames
        .first()
        .map(|x| x.agents.iter().map(|a| a.group).collect())
        .unwrap_or_default();
    out.set_item("groups", Array1::from(groups).into_pyarray(py))?;
    out.set_item(
        "summary",
        serde_json::to_string(&done.summary).map_err(err)?,
    )?;
    out.set_item("log", done.log)?;
    Ok(out)
}

/// Tracks of `positions` (`frames × insects × 3`, NaN where an insect was not seen) at frame
/// interval `dt`.
fn tracks_of(positions: &PyReadonlyArray3<'_, f64>, dt: f64) -> PyResult<Tracks> {
    if !(dt.is_finite() && dt > 0.0) {
        return Err(PyValueError::new_err(format!(
            "dt {dt}: the frame interval must be a positive number of seconds"
        )));
    }
    let a = positions.as_array();
    if a.shape()[2] != 3 {
        return Err(PyValueError::new_err(format!(
            "positions of shape {:?}: frames × insects × 3 expected",
            a.shape()
        )));
    }
    let (frames, insects, _) = a.dim();
    let mut samples = Vec::new();
    for k in 0..frames {
        for i in 0..insects {
            let p = [a[[k, i, 0]], a[[k, i, 1]], a[[k, i, 2]]];
            if p.iter().all(|v| v.is_finite()) {
                samples.push((i as u64, k as i64, p));
            }
        }
    }
    Ok(Tracks::from_samples(dt, samples))
}

/// Tracks read from a CSV file (the evaluation command's format).
fn tracks_at(path: &str, dt: Option<f64>) -> PyResult<Tracks> {
    Tracks::open(Path::new(path), dt).map_err(err)
}

/// `separate` or `reference`.
fn scaling_of(name: &str) -> PyResult<Scaling> {
    match name {
        "separate" => Ok(Scaling::Separate),
        "reference" => Ok(Scaling::Reference),
        other => Err(PyValueError::new_err(format!(
            "scaling {other:?}: `separate` or `reference`"
        ))),
    }
}

/// The tracks of argument `x` called `name`: a CSV path (frame interval `dt`, else the
/// file's) or a `(positions, dt)` pair; with the name a report gives them.
fn tracks_arg(x: &Bound<'_, PyAny>, name: String, dt: Option<f64>) -> PyResult<(Tracks, PathBuf)> {
    if let Ok(path) = x.extract::<String>() {
        return Ok((tracks_at(&path, dt)?, PathBuf::from(path)));
    }
    let (positions, step): (PyReadonlyArray3<'_, f64>, f64) = x.extract().map_err(|_| {
        PyValueError::new_err(format!(
            "{name}: a CSV path or a (positions, dt) pair of a frames × insects × 3 array of \
             floats and the frame interval"
        ))
    })?;
    Ok((tracks_of(&positions, step)?, PathBuf::from(name)))
}

/// The evaluation command's report (JSON text) of `candidates` against `reference`: each is
/// a CSV path or a `(positions, dt)` pair; `scaling` is `separate` or `reference`.
#[pyfunction]
#[pyo3(signature = (reference, candidates, *, dt=None, scaling="separate"))]
fn evaluate_tracks(
    reference: &Bound<'_, PyAny>,
    candidates: Vec<Bound<'_, PyAny>>,
    dt: Option<f64>,
    scaling: &str,
) -> PyResult<String> {
    let scaling = scaling_of(scaling)?;
    let (real, real_name) = tracks_arg(reference, "reference".into(), dt)?;
    let mut sims = Vec::new();
    let mut names = Vec::new();
    for (i, c) in candidates.iter().enumerate() {
        let (t, name) = tracks_arg(c, format!("candidate {i}"), dt)?;
        sims.push(t);
        names.push(name);
    }
    if sims.is_empty() {
        return Err(PyValueError::new_err("no candidates to evaluate"));
    }
    let refs: Vec<&Tracks> = sims.iter().collect();
    let e = evaluate(&real, &refs, scaling);
    serde_json::to_string(&report(&real_name, &names, &e)).map_err(err)
}

/// Calibration's score E of `candidate` against `reference` (each a CSV path or a
/// `(positions, dt)` pair): 1 − (1/7) Σ_φ E_φ, ren2016 Eq. 6 with Step 1's weights
/// (`swarm_sim::fit::score`), each metric z-scored by `scaling`.
#[pyfunction]
#[pyo3(signature = (reference, candidate, *, dt=None, scaling="reference"))]
fn score(
    py: Python<'_>,
    reference: &Bound<'_, PyAny>,
    candidate: &Bound<'_, PyAny>,
    dt: Option<f64>,
    scaling: &str,
) -> PyResult<f64> {
    let scaling = scaling_of(scaling)?;
    let (real, _) = tracks_arg(reference, "reference".into(), dt)?;
    let (sim, _) = tracks_arg(candidate, "candidate".into(), dt)?;
    Ok(py.detach(|| fit::score(&samples(&real), &sim, scaling)))
}

/// The positions of the scenario of JSON text `scenario` run with each seed of `seeds`
/// (`swarm_sim::fit::record`): after `burn_in` ticks, every `every` ticks for `frames` frames,
/// as a `frames × insects × 3` array (the runs' insects side by side, NaN where one was not
/// there), on `threads` workers (default: the process's pool), the GIL released.
#[pyfunction]
#[pyo3(signature = (scenario, source=None, *, seeds, burn_in, frames, every=1, backend=None, threads=None))]
#[allow(clippy::too_many_arguments)]
fn simulate<'py>(
    py: Python<'py>,
    scenario: &str,
    source: Option<&str>,
    seeds: Vec<u32>,
    burn_in: u32,
    frames: u32,
    every: u32,
    backend: Option<&str>,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyArray3<f64>>> {
    let mut sc = from_json(scenario, source)?;
    if let Some(b) = backend_of(backend)? {
        sc.backend = b;
    }
    check_steps(frames, "frames").map_err(err)?;
    if every == 0 || seeds.is_empty() {
        return Err(PyValueError::new_err(
            "every needs at least 1 tick a frame and seeds at least one seed",
        ));
    }
    let sampling = fit::Sampling {
        burn_in,
        frames,
        every,
        seeds,
    };
    let points = py
        .detach(|| match threads {
            Some(t) => fit::record_on(&sc, &sampling, t),
            None => fit::record(&sc, &sampling),
        })
        .map_err(err)?;
    let insects = points.iter().map(|p| p.0 + 1).max().unwrap_or(0) as usize;
    let mut a = Array3::from_elem((frames as usize, insects, 3), f64::NAN);
    for (id, k, p) in points {
        for (d, v) in p.into_iter().enumerate() {
            a[[k as usize, id as usize, d]] = v;
        }
    }
    Ok(a.into_pyarray(py))
}

/// One row of a model's parameter table: name, `"real"` or `"int"`, low, high, whether low
/// itself is excluded, unit.
type ParamRow = (&'static str, &'static str, f64, f64, bool, &'static str);

/// A model's parameter table: a [`ParamRow`] for each parameter a group's table may set.
#[pyfunction]
fn parameters(model: &str) -> PyResult<Vec<ParamRow>> {
    let entry = swarm_sim::models::get(model).map_err(err)?;
    Ok(entry
        .params
        .iter()
        .map(|spec| match spec.range {
            Range::Real { min, max, min_open } => (
                spec.name,
                "real",
                f64::from(min.f32()),
                f64::from(max.f32()),
                min_open,
                spec.unit,
            ),
            Range::Int { min, max } => (
                spec.name,
                "int",
                f64::from(min),
                f64::from(max),
                false,
                spec.unit,
            ),
        })
        .collect())
}

/// The whole range of real parameter `name` of `model` as calibration searches it
/// (`swarm_sim::fit::Param::resolve`: an open lower end moved just inside).
#[pyfunction]
fn whole_range(model: &str, name: &str) -> PyResult<(f64, f64)> {
    let entry = swarm_sim::models::get(model).map_err(err)?;
    let p = fit::Param::resolve(name, entry.params).map_err(err)?;
    Ok((p.low, p.high))
}

/// The genetic algorithm of `swarm fit` (chen §VI's, `swarm_sim::fit::Ga`), asked and told
/// one generation at a time so that a pool or a cluster scores the individuals.
#[pyclass(module = "swarm._swarm")]
struct GeneticAlgorithm(fit::Search);

#[pymethods]
impl GeneticAlgorithm {
    #[new]
    #[pyo3(signature = (ranges, *, population=None, generations=None, crossover=None, mutation=None, seed=1))]
    fn new(
        ranges: Vec<(f64, f64)>,
        population: Option<usize>,
        generations: Option<u32>,
        crossover: Option<f64>,
        mutation: Option<f64>,
        seed: u32,
    ) -> PyResult<Self> {
        let d = fit::Ga::default();
        let ga = fit::Ga {
            population: population.unwrap_or(d.population),
            generations: generations.unwrap_or(d.generations),
            crossover: crossover.unwrap_or(d.crossover),
            mutation: mutation.unwrap_or(d.mutation),
            seed,
        };
        if ga.population < 2 || ga.generations == 0 {
            return Err(PyValueError::new_err(format!(
                "population {} and generations {}: at least 2 individuals and 1 generation",
                ga.population, ga.generations
            )));
        }
        for (name, p) in [("crossover", ga.crossover), ("mutation", ga.mutation)] {
            if !(0.0..=1.0).contains(&p) {
                return Err(PyValueError::new_err(format!(
                    "{name} {p}: not a probability"
                )));
            }
        }
        if let Some((i, r)) = ranges
            .iter()
            .enumerate()
            .find(|(_, r)| !(r.0.is_finite() && r.1.is_finite()))
        {
            return Err(PyValueError::new_err(format!(
                "range {i} {r:?}: both ends must be finite"
            )));
        }
        Ok(Self(fit::Search::new(ga, &ranges)))
    }

    /// The individuals to score next (genes in the ranges' order).
    fn ask(&self) -> Vec<Vec<f64>> {
        self.0.ask().to_vec()
    }

    /// The scores of the individuals `ask` gave, in their order (NaN: refused).
    fn tell(&mut self, scores: Vec<f64>) -> PyResult<()> {
        if self.0.done() {
            return Err(PyValueError::new_err(
                "the search is done: every generation is scored",
            ));
        }
        let asked = self.0.ask().len();
        if scores.len() != asked {
            return Err(PyValueError::new_err(format!(
                "{} scores for {asked} individuals asked",
                scores.len()
            )));
        }
        self.0.tell(&scores);
        Ok(())
    }

    /// Whether the last generation is scored.
    #[getter]
    fn done(&self) -> bool {
        self.0.done()
    }

    /// The best score after each generation so far.
    #[getter]
    fn history(&self) -> Vec<f64> {
        self.0.history().to_vec()
    }

    /// The best genes so far, their score and the individuals scored.
    fn best(&self) -> (Vec<f64>, f64, usize) {
        let o = self.0.outcome();
        (o.best, o.score, o.evaluations)
    }
}

/// The native module.
#[pymodule]
fn _swarm(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("SwarmError", m.py().get_type::<SwarmError>())?;
    m.add_function(wrap_pyfunction!(builtin_names, m)?)?;
    m.add_function(wrap_pyfunction!(models, m)?)?;
    m.add_function(wrap_pyfunction!(load, m)?)?;
    m.add_function(wrap_pyfunction!(check, m)?)?;
    m.add_function(wrap_pyfunction!(run, m)?)?;
    m.add_function(wrap_pyfunction!(evaluate_tracks, m)?)?;
    m.add_function(wrap_pyfunction!(score, m)?)?;
    m.add_function(wrap_pyfunction!(run_to, m)?)?;
    m.add_function(wrap_pyfunction!(read_tracks, m)?)?;
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(parameters, m)?)?;
    m.add_function(wrap_pyfunction!(whole_range, m)?)?;
    m.add_class::<GeneticAlgorithm>()?;
    Ok(())
}
