//! What the end-to-end GPU tests share (`gpu_runs.rs`, `gpu_runs_li.rs`): a built-in scenario
//! in fixed point over [`STEPS`] ticks, run by `swarm run` on each backend, its files compared.

#![allow(dead_code)] // each test binary uses its part

use std::path::Path;

use swarm_sim::run::{RunOptions, run};
use swarm_sim::scenario::{self, Backend, ScalarType, Scenario};

/// Ticks per run.
pub const STEPS: u32 = 1000;

/// The files compared byte for byte (the summary separately, normalised).
pub const FILES: &[&str] = &["positions.npy", "trajectories.csv", "scene.json"];

/// Built-in scenario `name` in fixed point over [`STEPS`] ticks, its events moved into them
/// (scaled by their step), no pictures.
pub fn fixed(name: &str) -> Scenario {
    let mut sc = scenario::builtin(name).expect("built-in");
    for g in &mut sc.groups {
        g.scalar = ScalarType::Fixed;
    }
    for e in &mut sc.events {
        e.step = (u64::from(e.step) * u64::from(STEPS) / u64::from(sc.steps)) as u32;
    }
    sc.steps = STEPS;
    sc.outputs.render = false;
    sc.outputs.gif = false;
    sc.outputs.trajectories = true;
    sc.outputs.npy = true;
    sc
}

/// The summary without what depends on the machine, the moment and the backend.
pub fn normalised_summary(dir: &Path) -> serde_json::Value {
    let text = std::fs::read_to_string(dir.join("summary.json")).expect("summary.json");
    let mut v: serde_json::Value = serde_json::from_str(&text).expect("summary is JSON");
    let obj = v.as_object_mut().expect("summary is an object");
    for k in [
        "wall_seconds",
        "agent_steps_per_s",
        "threads",
        "backend",
        "adapter",
    ] {
        obj.remove(k);
    }
    v
}

/// Runs `sc` on `backend` with `threads` threads into `dir`; returns the backend the summary
/// names.
pub fn run_on(sc: &Scenario, backend: Backend, threads: usize, dir: &Path) -> String {
    let opts = RunOptions {
        out: dir.to_path_buf(),
        steps: None,
        seed: None,
        threads: Some(threads),
        backend: Some(backend),
        progress: false,
        warnings: Vec::new(),
    };
    let report = run(sc, &opts).unwrap_or_else(|e| panic!("{} on {backend:?}: {e}", sc.name));
    report.summary.backend
}

pub fn same_bytes_on_the_gpu(name: &str) {
    let sc = fixed(name);
    let tmp = tempfile::tempdir().expect("temp dir");
    let (cpu, gpu) = (tmp.path().join("cpu"), tmp.path().join("gpu"));
    assert_eq!(run_on(&sc, Backend::Cpu, 1, &cpu), "cpu");
    assert_eq!(run_on(&sc, Backend::Gpu, 2, &gpu), "gpu");
    // 3D worlds (bees) also record the bodies' attitude.
    for f in FILES
        .iter()
        .chain(Some(&"attitude.npy").filter(|f| cpu.join(f).exists()))
    {
        let (a, b) = (std::fs::read(cpu.join(f)), std::fs::read(gpu.join(f)));
        let (a, b) = (a.expect("CPU output"), b.expect("GPU output"));
        assert!(a == b, "{name}: {f} differs on the GPU");
    }
    assert_eq!(
        normalised_summary(&cpu),
        normalised_summary(&gpu),
        "{name}: summary.json differs on the GPU"
    );
}

/// [`same_bytes_on_the_gpu`] for every built-in scenario whose name starts with `prefix`
/// (found by name: a scenario added to `scenarios/` is compared without a line in a test),
/// `example` among them.
pub fn every_scenario_of(prefix: &str, example: &str) {
    let names: Vec<&str> = swarm_sim::scenario::builtin_names()
        .iter()
        .copied()
        .filter(|n| n.starts_with(prefix))
        .collect();
    assert!(names.contains(&example), "{names:?}");
    for name in names {
        same_bytes_on_the_gpu(name);
    }
}
