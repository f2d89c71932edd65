//! `swarm bench`: agent-steps per second of the engine on a synthetic world, as JSON.

use std::time::Instant;

use serde::Serialize;
use swarm_core::Vec2;
use swarm_core::ant::{AntParams, AntState};

use crate::Result;
use crate::ants::{AntGroup, AntObjectDef, AntObjectKind, AntSim, AntWorld, Shape2};

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

/// Ants per unit² in the bench world (the density of xiang2018's 500-ant scenes).
const DENSITY: f32 = 0.02;

/// A square world holding `n` ants spread uniformly (density `DENSITY`), with a nest and
/// food sources and a rock, so every kind of interaction happens somewhere.
pub fn bench_ant_world(n: usize, seed: u32) -> AntSim {
    let params = AntParams::<f32>::default();
    let side = ((n.max(1) as f32) / DENSITY).sqrt().clamp(50.0, 16_000.0);
    let mut w = AntWorld::new(
        [0.0, 0.0],
        [side, side],
        params.contact_range,
        params.collision_range,
    );
    let c = side / 2.0;
    let obj = |id, kind, center, radius| AntObjectDef {
        id,
        name: format!("object-{id}"),
        kind,
        shape: Shape2::Circle { center, radius },
        active: true,
    };
    w.objects = vec![
        obj(0, AntObjectKind::Nest, [c, c], 5.0),
        obj(
            1,
            AntObjectKind::Food { amount: None },
            [c + side / 4.0, c],
            5.0,
        ),
        obj(
            2,
            AntObjectKind::Food { amount: None },
            [c - side / 4.0, c],
            5.0,
        ),
        obj(3, AntObjectKind::Obstacle, [c, c + side / 4.0], 8.0),
    ];
    let states = (0..n as u32)
        .map(|i| {
            let r = |k| swarm_core::rand::rand(seed, i, u32::MAX, k) as f32 / u32::MAX as f32;
            let pos = Vec2::new(r(0) * side, r(1) * side);
            let a = r(2) * std::f32::consts::TAU;
            AntState::exploring(0, pos, Vec2::new(a.cos(), a.sin()))
        })
        .collect();
    let params = params.checked().expect("default parameters are valid");
    AntSim::new(
        w,
        vec![AntGroup::new("bench".into(), 0, params, states).into()],
        seed,
    )
}

/// Times `steps` ant ticks of `agents` ants on `threads` threads.
pub fn bench_ants(agents: usize, steps: u32, threads: usize) -> Result<BenchReport> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| crate::SimError::Invalid(format!("cannot start {threads} threads: {e}")))?;
    pool.install(|| {
        let mut sim = bench_ant_world(agents, 1);
        sim.step()?;
        let t0 = Instant::now();
        for _ in 0..steps {
            sim.step()?;
        }
        let seconds = t0.elapsed().as_secs_f64();
        Ok(BenchReport {
            model: "ants".into(),
            backend: "cpu".into(),
            agents,
            steps,
            threads,
            seconds,
            agent_steps_per_s: agents as f64 * steps as f64 / seconds.max(1e-9),
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
