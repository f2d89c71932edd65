//! The Rust side of issue 16's ORCA benchmark: the random cube of `scripts/rvo2/random_cube.cc`
//! stepped by [`swarm_sim::orca::OrcaCrowd`] (`scripts/bench-orca.sh` runs both).
//!
//! ```text
//! cargo run --release -p swarm-sim --example orca_cube -- AGENTS STEPS SEED [SPACING] [--threads T]
//! ```
//!
//! Only the steps are timed; the overlaps (pairs closer than two radii) are counted after each
//! step, untimed. Prints one JSON line in the C++ driver's shape.

use std::process::ExitCode;
use std::time::Instant;

use clap::Parser;
use swarm_sim::orca::{CrowdParams, OrcaCrowd, random_cube, toward};

/// Command line.
#[derive(Parser, Debug)]
#[command(about = "ORCA on the random cube (issue 16's benchmark, the Rust side)")]
struct Args {
    /// Number of agents.
    agents: usize,
    /// Number of steps.
    steps: u32,
    /// Seed of the lattice jitter and the goal permutation.
    seed: u32,
    /// Lattice spacing (≥ 4: no two agents start closer than two radii).
    #[arg(default_value_t = 4.0)]
    spacing: f32,
    /// Worker threads (default: one per core).
    #[arg(long)]
    threads: Option<usize>,
    /// Safety margin added to the radius in ORCA's planes (not in the overlap count; see
    /// `CrowdParams::margin`). 0: RVO2-3D's parameters exactly.
    #[arg(long, default_value_t = 0.0)]
    margin: f32,
    /// Reorder the agents' memory slots by grid cell every this many steps (0: never; default:
    /// the crate's).
    #[arg(long)]
    reorder_every: Option<u32>,
}

fn main() -> ExitCode {
    let args = Args::parse();
    match run(&args) {
        Ok(line) => {
            println!("{line}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("orca_cube: {e}");
            ExitCode::FAILURE
        }
    }
}

/// Runs the benchmark; the JSON line.
fn run(args: &Args) -> Result<String, Box<dyn std::error::Error>> {
    let threads = args
        .threads
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()?;
    let cube = random_cube(args.agents, args.seed, args.spacing);
    let params = CrowdParams {
        margin: args.margin,
        ..CrowdParams::rvo2_cube()
    };
    let mut crowd = OrcaCrowd::new(&cube.positions, params)?;
    if let Some(every) = args.reorder_every {
        crowd.set_reorder_every(every);
    }
    let (mut seconds, mut overlaps) = (0.0f64, 0u64);
    pool.install(|| -> swarm_sim::Result<()> {
        for _ in 0..args.steps {
            let t0 = Instant::now();
            crowd.step(|id, p| toward(cube.goals[id as usize], p))?;
            seconds += t0.elapsed().as_secs_f64();
            overlaps += crowd.overlaps();
        }
        Ok(())
    })?;
    let agent_steps = args.agents as f64 * f64::from(args.steps);
    Ok(format!(
        "{{\"impl\": \"swarm orca3d\", \"agents\": {}, \"steps\": {}, \"seconds\": {:.6}, \
         \"agent_steps_per_s\": {:.1}, \"overlaps\": {}, \"spacing\": {}, \"threads\": {}, \"margin\": {}}}",
        args.agents,
        args.steps,
        seconds,
        agent_steps / seconds,
        overlaps,
        args.spacing,
        threads,
        args.margin
    ))
}
