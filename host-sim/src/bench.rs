//! `swarm bench`: agent-steps per second of the engine on a synthetic world, as JSON: the
//! timing loop over any model's [`Engine`](crate::engine::Engine); each model's folder builds
//! its own bench world ([`crate::models::bench_engine`]).

use std::time::Instant;

use serde::Serialize;

use crate::Result;
use crate::scenario::Model;

/// What `swarm bench` measures and prints.
#[derive(Clone, Debug, Serialize)]
pub struct BenchReport {
    /// `ants` or `bees`.
    pub model: String,
    /// `cpu` or `gpu`.
    pub backend: String,
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
    /// Peak resident memory of the process (VmHWM), bytes; 0 where unavailable.
    pub peak_rss_bytes: u64,
    /// Scalar type of the controllers.
    pub scalar: String,
    /// The machine (CPU model, cores).
    pub machine: String,
}

/// Times `steps` ticks of `agents` agents of `model` in its benchmark world
/// ([`bench_engine`](crate::models::bench_engine)), inside a pool of `threads` workers (`None`:
/// one per core), after one untimed warm-up tick.
///
/// # Errors
///
/// [`SimError::EmptyBench`](crate::SimError::EmptyBench) for no agents or no steps, the pool's
/// error, a controller's refusal.
pub fn bench(
    model: Model,
    agents: usize,
    steps: u32,
    threads: Option<usize>,
) -> Result<BenchReport> {
    if agents == 0 || steps == 0 {
        return Err(crate::SimError::EmptyBench { agents, steps });
    }
    let (pool, threads) = crate::par::pool(threads)?;
    pool.install(|| {
        let mut engine = crate::models::bench_engine(model, agents, 1)?;
        engine.tick()?;
        let t0 = Instant::now();
        for _ in 0..steps {
            engine.tick()?;
        }
        let seconds = t0.elapsed().as_secs_f64();
        Ok(BenchReport {
            model: engine.plural(),
            backend: engine.backend().into(),
            agents,
            steps,
            threads,
            seconds,
            agent_steps_per_s: agents as f64 * f64::from(steps) / seconds.max(1e-9),
            peak_rss_bytes: peak_rss_bytes(),
            scalar: "f32".into(),
            machine: machine(),
        })
    })
}

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
        let r = bench(Model::Ant, 500, 2, Some(1)).unwrap();
        assert_eq!(
            (r.model.as_str(), r.agents, r.steps, r.threads),
            ("ants", 500, 2, 1)
        );
        assert!(r.seconds > 0.0 && r.agent_steps_per_s > 0.0);
        let r = bench(Model::Bee, 200, 1, Some(2)).unwrap();
        assert_eq!((r.model.as_str(), r.agents, r.threads), ("bees", 200, 2));
        for (agents, steps, threads) in [(0, 5, Some(1)), (10, 0, Some(1)), (10, 5, Some(0))] {
            let e = bench(Model::Ant, agents, steps, threads)
                .unwrap_err()
                .to_string();
            assert!(e.contains("at least"), "{e}");
        }
    }
}
