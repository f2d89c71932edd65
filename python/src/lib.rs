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
use numpy::{IntoPyArray, PyReadonlyArray3};
use pyo3::create_exception;
use pyo3::exceptions::{PyException, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use swarm_sim::eval::{Scaling, Tracks, evaluate, report};
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
    if let Some(s) = steps {
        check_steps(s, "steps").map_err(err)?;
    }
    let opts = RunOptions {
        out: PathBuf::new(),
        steps,
        seed,
        threads,
        backend: backend_of(backend)?,
        progress,
        warnings: Vec::new(),
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
    let scaling = match scaling {
        "separate" => Scaling::Separate,
        "reference" => Scaling::Reference,
        other => {
            return Err(PyValueError::new_err(format!(
                "scaling {other:?}: `separate` or `reference`"
            )));
        }
    };
    let read = |x: &Bound<'_, PyAny>, name: String| -> PyResult<(Tracks, PathBuf)> {
        if let Ok(path) = x.extract::<String>() {
            return Ok((tracks_at(&path, dt)?, PathBuf::from(path)));
        }
        let (positions, step): (PyReadonlyArray3<'_, f64>, f64) = x.extract().map_err(|_| {
            PyValueError::new_err(format!(
                "{name}: a CSV path or a (positions, dt) pair of a frames × insects × 3 \
                 array of floats and the frame interval"
            ))
        })?;
        Ok((tracks_of(&positions, step)?, PathBuf::from(name)))
    };
    let (real, real_name) = read(reference, "reference".into())?;
    let mut sims = Vec::new();
    let mut names = Vec::new();
    for (i, c) in candidates.iter().enumerate() {
        let (t, name) = read(c, format!("candidate {i}"))?;
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
    Ok(())
}
