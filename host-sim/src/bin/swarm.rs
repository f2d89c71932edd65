//! The `swarm` command line (in progress: `bench`).

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand, ValueEnum};

/// Insect-swarm simulator: ant colonies (xiang2018) and bee swarms (chen) driven through the
/// swarm-core controllers.
#[derive(Parser)]
#[command(version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Clone, Copy, ValueEnum)]
enum Model {
    Ants,
    Bees,
}

#[derive(Subcommand)]
enum Command {
    /// Measure agent-steps per second on a synthetic world and write JSON.
    Bench {
        /// Which model.
        #[arg(long, value_enum)]
        model: Model,
        /// Number of agents.
        #[arg(long, default_value_t = 100_000)]
        agents: usize,
        /// Timed steps.
        #[arg(long, default_value_t = 50)]
        steps: u32,
        /// Worker threads (default: all cores).
        #[arg(long)]
        threads: Option<usize>,
        /// Write the JSON report here (it is printed too).
        #[arg(long)]
        json: Option<PathBuf>,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run(cli: Cli) -> Result<(), Box<dyn std::error::Error>> {
    match cli.command {
        Command::Bench {
            model,
            agents,
            steps,
            threads,
            json,
        } => {
            let threads = threads
                .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
            let report = match model {
                Model::Ants => swarm_sim::bench::bench_ants(agents, steps, threads)?,
                Model::Bees => return Err("the bee engine is not in the simulator yet".into()),
            };
            let text = serde_json::to_string_pretty(&report)?;
            println!("{text}");
            if let Some(path) = json {
                std::fs::write(&path, text + "\n")
                    .map_err(|e| format!("writing {}: {e}", path.display()))?;
            }
            Ok(())
        }
    }
}
