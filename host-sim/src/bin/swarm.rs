//! The `swarm` command line: list, run and render scenarios, benchmark the engine.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand, ValueEnum};
use swarm_sim::scenario::Model as SimModel;

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
    /// List the built-in scenarios.
    List,
    /// Run a scenario (a built-in name or a TOML file) and write its outputs.
    Run {
        /// Built-in scenario name (see `swarm list`) or path to a scenario file.
        scenario: String,
        /// Number of ticks (default: the scenario's).
        #[arg(long)]
        steps: Option<u32>,
        /// Seed (default: the scenario's).
        #[arg(long)]
        seed: Option<u32>,
        /// Worker threads (default: all cores; results are identical for any count).
        #[arg(long)]
        threads: Option<usize>,
        /// Output folder (default: `out/<scenario name>`); a finished run replaces it whole, a
        /// killed or failed one leaves it as it was.
        #[arg(long)]
        out: Option<PathBuf>,
        /// No progress bar.
        #[arg(long)]
        quiet: bool,
    },
    /// Draw a run folder again: snapshot.png and run.gif from its scene and trajectories.
    Render {
        /// The folder a `swarm run` wrote.
        dir: PathBuf,
    },
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
        Command::List => {
            for b in swarm_sim::scenario::BUILTINS {
                println!("{:<32} {}", b.name, b.summary);
            }
            Ok(())
        }
        Command::Run {
            scenario,
            steps,
            seed,
            threads,
            out,
            quiet,
        } => {
            if let Some(steps) = steps {
                swarm_sim::scenario::check_steps(steps, "--steps")?;
            }
            let (sc, mut warnings) = swarm_sim::scenario::resolve_with_warnings(&scenario)?;
            if let Some(steps) = steps {
                // Not those of the events `--steps` drops.
                let mut shortened = sc.clone();
                shortened.set_steps(steps);
                warnings.retain(|w| w.applies_to(&shortened));
            }
            for w in &warnings {
                eprintln!("{w}");
            }
            let out = out.unwrap_or_else(|| PathBuf::from("out").join(&sc.name));
            let opts = swarm_sim::run::RunOptions {
                out: out.clone(),
                steps,
                seed,
                threads,
                progress: !quiet && std::io::IsTerminal::is_terminal(&std::io::stderr()),
                warnings,
            };
            let report = swarm_sim::run::run(&sc, &opts)?;
            let s = &report.summary;
            println!(
                "{}: {} agents, {} ticks in {:.2} s ({:.3e} agent-steps/s, {} threads)",
                s.scenario, s.agents, s.steps, s.wall_seconds, s.agent_steps_per_s, s.threads
            );
            for (nest, n) in &s.deliveries_per_nest {
                println!("  delivered to {nest}: {n}");
            }
            if let Some(d) = s.min_distance {
                println!(
                    "  closest approach {d:.3}, {} collisions (< {})",
                    s.collisions, s.collision_distance
                );
            }
            for f in &report.files {
                println!("  wrote {}", f.display());
            }
            Ok(())
        }
        Command::Render { dir } => {
            let files = swarm_sim::output::render_dir(&dir)?;
            println!(
                "wrote {}\nwrote {}",
                files.png.display(),
                files.gif.display()
            );
            Ok(())
        }
        Command::Bench {
            model,
            agents,
            steps,
            threads,
            json,
        } => {
            swarm_sim::scenario::check_steps(steps, "--steps")?;
            // Refuse an output path that cannot be written before a long run, not after.
            if let Some(dir) = json.as_ref().and_then(|p| p.parent())
                && !dir.as_os_str().is_empty()
                && !dir.is_dir()
            {
                return Err(format!("--json: no folder {}", dir.display()).into());
            }
            let report = match model {
                Model::Ants => swarm_sim::bench::bench(SimModel::Ant, agents, steps, threads)?,
                Model::Bees => swarm_sim::bench::bench(SimModel::Bee, agents, steps, threads)?,
            };
            let text = serde_json::to_string_pretty(&report)?;
            println!("{text}");
            if let Some(path) = json {
                // What a killed earlier bench left beside the report.
                swarm_sim::output::remove_stale_temps(&path);
                swarm_sim::output::write_atomic_bytes(&path, (text + "\n").as_bytes())?;
            }
            Ok(())
        }
    }
}
