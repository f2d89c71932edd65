//! `swarm bench`: agent-steps per second of the engine on a synthetic world, as JSON: the
//! timing loop over any model's [`Engine`](crate::engine::Engine); each model's folder builds
//! its own bench world ([`crate::models::bench_engine`]).

use std::time::Instant;

use serde::Serialize;

use crate::Result;
use crate::scenario::{Backend, ScalarType};

/// What to benchmark.
#[derive(Clone, Debug)]
pub struct BenchSpec {
    /// The model (`ant`, `bee`, ...).
    pub model: String,
    /// Number of agents.
    pub agents: usize,
    /// Timed steps.
    pub steps: u32,
    /// Worker threads (`None`: one per core).
    pub threads: Option<usize>,
    /// The controllers' scalar type.
    pub scalar: ScalarType,
    /// Who decides: the CPU engine or the model's GPU engine.
    pub backend: Backend,
}

impl BenchSpec {
    /// `agents` agents of `model` for `steps` steps, in `f32` on the CPU with all cores.
    pub fn new(model: &str, agents: usize, steps: u32) -> BenchSpec {
        BenchSpec {
            model: model.into(),
            agents,
            steps,
            threads: None,
            scalar: ScalarType::F32,
            backend: Backend::Cpu,
        }
    }
}

/// What `swarm bench` measures and prints.
#[derive(Clone, Debug, Serialize)]
pub struct BenchReport {
    /// The model (`ant`, `bee`, ...).
    pub model: String,
    /// `cpu` or `gpu`.
    pub backend: String,
    /// The GPU adapter (`gpu` backend).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub adapter: Option<String>,
    /// Number of agents.
    pub agents: usize,
    /// Steps timed (after one untimed warm-up step).
    pub steps: u32,
    /// Worker threads.
    pub threads: usize,
    /// Wall time of the timed steps.
    pub seconds: f64,
    /// agents × steps / seconds.
    pub agent_steps_per_s: f64,
    /// Milliseconds per tick (seconds / steps).
    pub ms_per_tick: f64,
    /// GPU: the milliseconds of each pass of a tick (timestamp queries, the mean of
    /// [`PROFILED_TICKS`] ticks after the timed ones), where the adapter has timestamps.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kernel_ms: Option<std::collections::BTreeMap<String, f64>>,
    /// GPU: the bytes the engine holds on the device, and per agent.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub device_bytes: Option<u64>,
    /// GPU: [`BenchReport::device_bytes`] per agent.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub device_bytes_per_agent: Option<f64>,
    /// Peak resident memory of the process (VmHWM), bytes; 0 where unavailable.
    pub peak_rss_bytes: u64,
    /// Scalar type of the controllers.
    pub scalar: String,
    /// The machine (CPU model, cores).
    pub machine: String,
}

/// Times `spec.steps` ticks of `spec.agents` agents of `spec.model` in its benchmark world
/// ([`bench_engine`](crate::models::bench_engine)) on `spec.backend`, inside a pool of
/// `spec.threads` workers, after one untimed warm-up tick; the timing ends when the engine
/// has finished (a GPU engine is synchronised).
///
/// # Errors
///
/// [`SimError::EmptyBench`](crate::SimError::EmptyBench) for no agents or no steps, the pool's
/// error, a controller's refusal, [`SimError::NoGpuEngine`](crate::SimError::NoGpuEngine) and
/// the GPU's errors.
pub fn bench(spec: &BenchSpec) -> Result<BenchReport> {
    let (agents, steps) = (spec.agents, spec.steps);
    if agents == 0 || steps == 0 {
        return Err(crate::SimError::EmptyBench { agents, steps });
    }
    let (pool, threads) = crate::par::pool(spec.threads)?;
    pool.install(|| {
        let mut engine =
            crate::models::bench_engine(&spec.model, agents, 1, spec.scalar, spec.backend)?;
        engine.tick()?;
        engine.sync()?;
        let t0 = Instant::now();
        for _ in 0..steps {
            engine.tick()?;
        }
        engine.sync()?;
        let seconds = t0.elapsed().as_secs_f64();
        let mut kernel_ms: Option<std::collections::BTreeMap<String, f64>> = None;
        for _ in 0..PROFILED_TICKS {
            let Some(passes) = engine.profile_tick()? else {
                break;
            };
            let sums = kernel_ms.get_or_insert_default();
            for (name, ms) in passes {
                *sums.entry(name.into()).or_default() += ms / f64::from(PROFILED_TICKS);
            }
        }
        let device_bytes = engine.device_bytes();
        Ok(BenchReport {
            model: engine.model().to_owned(),
            backend: engine.backend().into(),
            adapter: engine.adapter(),
            agents,
            steps,
            threads,
            seconds,
            agent_steps_per_s: agents as f64 * f64::from(steps) / seconds.max(1e-9),
            ms_per_tick: seconds * 1e3 / f64::from(steps),
            kernel_ms,
            device_bytes,
            device_bytes_per_agent: device_bytes.map(|b| b as f64 / agents as f64),
            peak_rss_bytes: peak_rss_bytes(),
            scalar: format!("{:?}", spec.scalar.kind()),
            machine: machine(),
        })
    })
}

/// Ticks profiled after the timed ones (GPU engines on adapters with timestamp queries).
pub const PROFILED_TICKS: u32 = 3;

/// Peak resident set size (Linux `VmHWM`), 0 where unavailable.
pub fn peak_rss_bytes() -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1)?.parse::<u64>().ok())
        })
        .map_or(0, |kib| kib * 1024)
}

/// CPU model and core count, for reports.
pub fn machine() -> String {
    let model = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|m| m.trim().to_string())
        })
        .unwrap_or_else(|| std::env::consts::ARCH.to_string());
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    format!("{model}, {cores} cores")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_bench_reports_what_ran_and_refuses_an_empty_one() {
        let spec = |model, agents, steps, threads| BenchSpec {
            threads,
            ..BenchSpec::new(model, agents, steps)
        };
        let r = bench(&spec("ant", 500, 2, Some(1))).unwrap();
        assert_eq!(
            (r.model.as_str(), r.agents, r.steps, r.threads),
            ("ant", 500, 2, 1)
        );
        assert!(r.seconds > 0.0 && r.agent_steps_per_s > 0.0);
        let r = bench(&spec("bee", 200, 1, Some(2))).unwrap();
        assert_eq!((r.model.as_str(), r.agents, r.threads), ("bee", 200, 2));
        for (agents, steps, threads) in [(0, 5, Some(1)), (10, 0, Some(1)), (10, 5, Some(0))] {
            let e = bench(&spec("ant", agents, steps, threads))
                .unwrap_err()
                .to_string();
            assert!(e.contains("at least"), "{e}");
        }
    }
}
