//! The `swarm` command line: list, run and render scenarios, benchmark the engine. The `swarm`
//! binary is [`main`]; a team that adds a model builds its own `swarm` by registering the
//! model first:
//!
//! ```no_run
//! fn main() -> std::process::ExitCode {
//!     // swarm_sim::models::register(&MY_MODEL).expect("a free name");
//!     swarm_sim::cli::main()
//! }
//! ```

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

use crate::models;
use crate::scenario::{Backend, ScalarType};

/// Insect-swarm simulator: ant colonies (xiang2018) and bee swarms (chen) driven through the
/// swarm-core controllers.
#[derive(Parser)]
#[command(version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// List the built-in scenarios.
    List,
    /// List the models scenarios can use (built in and registered).
    Models,
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
        /// Who decides: `cpu` or `gpu` (wgpu; Mesa's lavapipe where there is no GPU). Default:
        /// the scenario's `backend`, else `cpu`. In fixed point both decide the same bits.
        #[arg(long, value_enum)]
        backend: Option<Backend>,
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
    /// Score trajectories against a reference (ren2016's evaluation: seven metrics, their
    /// z-scored PDFs compared by L1, entropy weights, the score E; and the polarisation).
    ///
    /// Each of REFERENCE and CANDIDATES is a track file (CSV with the header `id,time,x,y,z`,
    /// one row per insect and time) or a run folder written by `swarm run`. With two
    /// candidates or more, the weights and scores rank them (E in [0, 1], higher is closer to
    /// the reference); with one, every weight is 1/7 and only the energies tell.
    Eval {
        /// The reference trajectories (measured tracks, or a run).
        reference: PathBuf,
        /// The trajectories to score.
        #[arg(required = true)]
        candidates: Vec<PathBuf>,
        /// Frame interval of the track files in seconds (default: the smallest time step
        /// within a track).
        #[arg(long)]
        dt: Option<f64>,
        /// Write the JSON report here (it is printed too).
        #[arg(long)]
        json: Option<PathBuf>,
    },
    /// Measure agent-steps per second on a synthetic world and write JSON.
    Bench {
        /// Which model (`ant`, `bee`; see `swarm models`).
        #[arg(long)]
        model: String,
        /// Number of agents.
        #[arg(long, default_value_t = 100_000)]
        agents: usize,
        /// Timed steps.
        #[arg(long, default_value_t = 50)]
        steps: u32,
        /// Worker threads (default: all cores).
        #[arg(long)]
        threads: Option<usize>,
        /// Who decides: `cpu` or `gpu`.
        #[arg(long, value_enum, default_value_t = Backend::Cpu)]
        backend: Backend,
        /// The controllers' scalar type: `f32` or `fixed` (I16F16).
        #[arg(long, value_enum, default_value_t = ScalarType::F32)]
        scalar: ScalarType,
        /// Write the JSON report here (it is printed too).
        #[arg(long)]
        json: Option<PathBuf>,
    },
}

/// The `swarm` command line, on the process's arguments, with the models of
/// [`models::all`]: prints what it did or the error, and returns the exit status.
pub fn main() -> ExitCode {
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
            for b in crate::scenario::BUILTINS {
                println!("{:<32} {}", b.name, b.summary);
            }
            Ok(())
        }
        Command::Models => {
            for m in models::all() {
                println!("{:<8} {}D  {}", m.name, m.dim, m.about);
            }
            Ok(())
        }
        Command::Run {
            scenario,
            steps,
            seed,
            threads,
            backend,
            out,
            quiet,
        } => {
            if let Some(steps) = steps {
                crate::scenario::check_steps(steps, "--steps")?;
            }
            let (sc, mut warnings) = crate::scenario::resolve_with_warnings(&scenario)?;
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
            let opts = crate::run::RunOptions {
                out: out.clone(),
                steps,
                seed,
                threads,
                backend,
                progress: !quiet && std::io::IsTerminal::is_terminal(&std::io::stderr()),
                warnings,
            };
            let report = crate::run::run(&sc, &opts)?;
            let s = &report.summary;
            println!(
                "{}: {} agents, {} ticks in {:.2} s ({:.3e} agent-steps/s, {} threads)",
                s.scenario, s.agents, s.steps, s.wall_seconds, s.agent_steps_per_s, s.threads
            );
            if let Some(a) = &s.adapter {
                println!("  on the GPU: {a}");
            }
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
            let files = crate::output::render_dir(&dir)?;
            println!(
                "wrote {}\nwrote {}",
                files.png.display(),
                files.gif.display()
            );
            Ok(())
        }
        Command::Eval {
            reference,
            candidates,
            dt,
            json,
        } => {
            if let Some(dt) = dt
                && !(dt.is_finite() && dt > 0.0)
            {
                return Err(format!("--dt: {dt} is not a positive number of seconds").into());
            }
            let open = |p: &PathBuf| crate::eval::Tracks::open(p, dt);
            let reference_tracks = open(&reference)?;
            let tracks = candidates.iter().map(open).collect::<Result<Vec<_>, _>>()?;
            let refs: Vec<&crate::eval::Tracks> = tracks.iter().collect();
            let e = crate::eval::evaluate(&reference_tracks, &refs);
            let report = crate::eval::report(&reference, &candidates, &e);
            println!("{}", crate::eval::table(&candidates, &e));
            if let Some(path) = json {
                crate::output::remove_stale_temps(&path);
                let text = serde_json::to_string_pretty(&report)?;
                crate::output::write_atomic_bytes(&path, (text + "\n").as_bytes())?;
            }
            Ok(())
        }
        Command::Bench {
            model,
            agents,
            steps,
            threads,
            backend,
            scalar,
            json,
        } => {
            crate::scenario::check_steps(steps, "--steps")?;
            // Refuse an output path that cannot be written before a long run, not after.
            if let Some(dir) = json.as_ref().and_then(|p| p.parent())
                && !dir.as_os_str().is_empty()
                && !dir.is_dir()
            {
                return Err(format!("--json: no folder {}", dir.display()).into());
            }
            // The plural the option took before models were open (`ants`) still names one.
            let model = match model.strip_suffix('s') {
                Some(one) if models::find(&model).is_none() && models::find(one).is_some() => one,
                _ => &model,
            };
            let report = crate::bench::bench(&crate::bench::BenchSpec {
                model: model.into(),
                agents,
                steps,
                threads,
                scalar,
                backend,
            })?;
            let text = serde_json::to_string_pretty(&report)?;
            println!("{text}");
            if let Some(path) = json {
                // What a killed earlier bench left beside the report.
                crate::output::remove_stale_temps(&path);
                crate::output::write_atomic_bytes(&path, (text + "\n").as_bytes())?;
            }
            Ok(())
        }
    }
}
