//! The `swarm` command line: list, run and render scenarios, benchmark the engine, learn a
//! li2015 model from tracks (`swarm li fit`, `swarm li synth`). The `swarm`
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

use crate::fly::temperature::{self, Temperature};
use crate::li::fixture::Fixture;
use crate::li::model::Estimate;
use crate::li::segment::{R2_MIN, Segmentation, TOLERANCE_C};
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
    /// List the models scenarios can use (built in and registered), or one model's parameters:
    /// the names a group's parameter table may set, the values each takes and its unit (what
    /// `swarm fit` and the Python `swarm.calibrate` search within).
    Models {
        /// A model's name: list its parameters.
        model: Option<String>,
    },
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
    /// z-scored PDFs compared by L1, entropy weights, the score E; the polarisation; li2015's
    /// distance to the centroid and accumulated-density total variation on 16³ cells).
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
        /// Whose mean and standard deviation z-score each metric: each set its own (the
        /// paper: only the distributions' shapes count), or the reference's for both (tracks in
        /// the simulation's units: a model too fast or too spread out scores lower).
        #[arg(long, value_enum, default_value_t)]
        scaling: crate::eval::Scaling,
    },
    /// Fit a scenario's parameters to trajectories: a genetic algorithm (chen §VI's budget of
    /// 2,000 runs as 20 individuals × 100 generations, crossover 0.9, mutation 0.15 per
    /// parameter) maximising the evaluation score E against the reference (ren2016 Eq. 6
    /// with equal weights 1/7).
    ///
    /// Each individual is the scenario with its parameters set in every group, run with the
    /// same seeds for `--burn-in` ticks and then recorded every `--every` ticks for `--frames`
    /// frames at the reference's frame interval. Individuals the model's rules refuse (ordered
    /// radii, a stable friction step) score worst and are counted. Example:
    /// `swarm fit fly-fig1-midges tracks.csv --param gamma=1:20:log --param chi_att=0:40`.
    Fit {
        /// Built-in scenario name or path to a scenario file (the parameters not fitted keep
        /// its values).
        scenario: String,
        /// The trajectories to match: a track file (`id,time,x,y,z`) or a run folder.
        reference: PathBuf,
        /// A parameter and its range: `NAME=LOW:HIGH`, `NAME=LOW:HIGH:log` to search its
        /// logarithm (a positive range over decades), or `NAME` alone for the model's whole
        /// range (`swarm models MODEL`). Repeat for each parameter.
        #[arg(long = "param", required = true, value_name = "NAME[=LOW:HIGH[:log]]")]
        params: Vec<String>,
        /// Frame interval of a track file in seconds (default: the smallest time step within
        /// a track).
        #[arg(long)]
        dt: Option<f64>,
        /// Ticks of the model per reference frame.
        #[arg(long, default_value_t = 1)]
        every: u32,
        /// Ticks run before recording.
        #[arg(long, default_value_t = 200)]
        burn_in: u32,
        /// Frames recorded per run.
        #[arg(long, default_value_t = 500)]
        frames: u32,
        /// Runs per individual (seeds SEED, SEED+1, ...), pooled.
        #[arg(long, default_value_t = 1)]
        runs: u32,
        /// The runs' first seed (default: the scenario's).
        #[arg(long)]
        seed: Option<u32>,
        /// Individuals per generation (chen: 10).
        #[arg(long, default_value_t = crate::fit::Ga::default().population)]
        population: usize,
        /// Generations (chen: 200).
        #[arg(long, default_value_t = crate::fit::Ga::default().generations)]
        generations: u32,
        /// Crossover probability.
        #[arg(long, default_value_t = crate::fit::Ga::default().crossover)]
        crossover: f64,
        /// Mutation probability per parameter (chen: 0.01).
        #[arg(long, default_value_t = crate::fit::Ga::default().mutation)]
        mutation: f64,
        /// The genetic algorithm's seed.
        #[arg(long, default_value_t = 1)]
        ga_seed: u32,
        /// Whose moments z-score each metric (default: the reference's, so that speeds and
        /// distances count in the simulation's units; `separate` compares shapes only).
        #[arg(long, value_enum, default_value_t = crate::eval::Scaling::Reference)]
        scaling: crate::eval::Scaling,
        /// Write the fitted scenario here (TOML).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Write the JSON report here (the best values, E per generation).
        #[arg(long)]
        json: Option<PathBuf>,
        /// No progress bar.
        #[arg(long)]
        quiet: bool,
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
    /// ren2016's flying insects: resize a scenario's swarm to a temperature.
    Fly {
        #[command(subcommand)]
        command: FlyCommand,
    },
    /// li2015's data pipeline: learn a model file from tracked trajectories, or write the
    /// synthetic tracks that stand in for the paper's unpublished data.
    Li {
        #[command(subcommand)]
        command: LiCommand,
    },
}

#[derive(Subcommand)]
enum FlyCommand {
    /// Resize a scenario's ren2016 insects until their swarm holds N(T) insects per m³, Eq.
    /// 1's density at the temperature T.
    ///
    /// Each round runs the scenario (burn-in, then frames), measures the swarm's density (from
    /// each insect's 5th nearest neighbour, the median over insects, averaged over frames and
    /// runs) and resizes every length, speed and force of the insects, with their spawn region, by
    /// (density / N(T))^(1/3) (a similarity of the model: the swarm's shape and dynamics are
    /// kept), until within the tolerance (spec §2.8, docs/models.md). The world and its
    /// objects stay. Example: `swarm fly temperature fly-fig1-midges --celsius 15
    /// --metres-per-unit 2 --out midges-15C.toml` (with its own unit, `--metres-per-unit
    /// 0.0455`, the builtin's 0.91 m box is too small for 100 midges at any N(T): refused).
    Temperature {
        /// Built-in scenario name or path to a scenario file.
        scenario: String,
        /// The temperature T (°C; Eq. 1 has swarms between 8.74 and 35.66).
        #[arg(long, allow_hyphen_values = true)]
        celsius: f64,
        /// The scenario's length unit in metres (N(T) is insects per m³).
        #[arg(long, default_value_t = 1.0)]
        metres_per_unit: f64,
        /// Ticks run before the first measured frame.
        #[arg(long, default_value_t = 2000)]
        burn_in: u32,
        /// Frames measured per run.
        #[arg(long, default_value_t = 20)]
        frames: u32,
        /// Ticks between measured frames.
        #[arg(long, default_value_t = 50)]
        every: u32,
        /// Runs (seeds from the scenario's, or --seed, up) averaged per round.
        #[arg(long, default_value_t = 2)]
        runs: u32,
        /// The first run's seed (default: the scenario's).
        #[arg(long)]
        seed: Option<u32>,
        /// The relative error in the density accepted.
        #[arg(long, default_value_t = 0.05)]
        tolerance: f64,
        /// The most rounds of resizing.
        #[arg(long, default_value_t = 8)]
        rounds: u32,
        /// Write the resized scenario here (replaced whole, or left as it was on an error).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Write the JSON report here (target, resizing, density by round).
        #[arg(long)]
        json: Option<PathBuf>,
        /// No progress bar.
        #[arg(long)]
        quiet: bool,
    },
}

/// How `swarm li fit` cuts tracks into segments.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum SegmentationArg {
    /// Split a run at its sample farthest from the chord while that is more than c times the
    /// run's noise (estimated from its second differences).
    Tolerance,
    /// The paper's rule: a window is one segment when a line explains R² of its scatter.
    R2,
}

/// How `swarm li fit` estimates the tables.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum EstimateArg {
    /// Fit the process whose segmented tracks reproduce the data's statistics (indirect
    /// inference: the segmentation's bias cancels).
    Indirect,
    /// The segments' own lengths and turns (the paper's method; biased by the sampling and
    /// the noise).
    Direct,
}

#[derive(Subcommand)]
enum LiCommand {
    /// Learn a li2015 model file from tracked trajectories: segment lengths, turning angles
    /// and the visiting-frequency grid, with their provenance.
    ///
    /// TRACKS is a track file (CSV with the header `id,time,x,y,z`, one row per insect and
    /// frame; a missing frame splits a track). By default the tables are those of the
    /// process whose tracks, segmented the same way, give the data's segment and bending
    /// statistics (indirect inference, a few seconds per 10⁵ samples); `--estimate direct`
    /// tabulates the segments as found. The density counts every sample in cubic cells over
    /// the data's box. Scenarios use the file with `li = { model = "MODEL.toml" }`.
    Fit {
        /// The track file.
        tracks: PathBuf,
        /// The model file to write (replaced whole, or left as it was on an error).
        #[arg(long)]
        out: PathBuf,
        /// Frame interval in seconds (default: the smallest time step within a track).
        #[arg(long)]
        dt: Option<f64>,
        /// Density cells along the longest side of the data's box (at most 4096 cells in
        /// all).
        #[arg(long, default_value_t = 16)]
        cells: u16,
        /// How tracks are cut into segments.
        #[arg(long, value_enum, default_value_t = SegmentationArg::Tolerance)]
        segmentation: SegmentationArg,
        /// The tolerance in multiples of the noise (`--segmentation tolerance`).
        #[arg(long, default_value_t = TOLERANCE_C)]
        c: f64,
        /// The goodness of fit (`--segmentation r2`; the paper's 0.9).
        #[arg(long, default_value_t = R2_MIN)]
        r2: f64,
        /// How the tables are estimated.
        #[arg(long, value_enum, default_value_t = EstimateArg::Indirect)]
        estimate: EstimateArg,
        /// Seed of the indirect fit's simulations (the same seed gives the same file).
        #[arg(long, default_value_t = 1)]
        seed: u32,
    },
    /// Write synthetic insect tracks (a track file, `id,time,x,y,z`) from a documented
    /// random process with the paper's segment statistics.
    ///
    /// The process (`swarm_sim::li::fixture`, spec §2.1): each insect starts at a uniform
    /// point of a cube in a uniform direction and flies at constant speed along a polyline
    /// whose segment lengths follow the generalised gamma with the paper's mean 14.57 mm,
    /// median 7.22 mm and sd 19.01 mm, turning at each vertex by |θ|, θ ~ N(2.34°, 40.02°),
    /// at a uniform azimuth; every sample gets Gaussian noise. The data are synthetic (the
    /// paper's are not public). The same options give the same bytes; data/li-synthetic/ was
    /// made with the defaults.
    Synth {
        /// The track file to write.
        #[arg(long)]
        out: PathBuf,
        /// Seed.
        #[arg(long, default_value_t = 1)]
        seed: u32,
        /// Insects (tracks).
        #[arg(long, default_value_t = 20)]
        tracks: u32,
        /// Samples per track.
        #[arg(long, default_value_t = 1000)]
        samples: u32,
        /// Flight speed (m/s).
        #[arg(long, default_value_t = 0.15)]
        speed: f64,
        /// Samples per second.
        #[arg(long, default_value_t = 100.0)]
        fps: f64,
        /// Measurement noise, sd per coordinate (m).
        #[arg(long, default_value_t = 0.0002)]
        noise: f64,
        /// Side of the cube the insects start in (m).
        #[arg(long, default_value_t = 0.91)]
        side: f64,
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
        Command::Models { model: None } => {
            for m in models::all() {
                println!("{:<8} {}D  {}", m.name, m.dim, m.about);
            }
            Ok(())
        }
        Command::Models { model: Some(name) } => {
            let m = models::get(&name)?;
            println!("{} ({}D): {}", m.name, m.dim, m.about);
            for spec in m.params {
                println!("  {:<16} {spec}", spec.name);
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
            scaling,
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
            let e = crate::eval::evaluate(&reference_tracks, &refs, scaling);
            let report = crate::eval::report(&reference, &candidates, &e);
            println!("{}", crate::eval::table(&candidates, &e));
            if let Some(path) = json {
                write_json(&path, &report)?;
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
            if let Some(path) = &json {
                folder_exists("--json", path)?;
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
                write_text(&path, &(text + "\n"))?;
            }
            Ok(())
        }
        Command::Fit {
            scenario,
            reference,
            params,
            dt,
            every,
            burn_in,
            frames,
            runs,
            seed,
            population,
            generations,
            crossover,
            mutation,
            ga_seed,
            scaling,
            out,
            json,
            quiet,
        } => {
            if let Some(dt) = dt {
                positive("--dt", dt)?;
            }
            for (name, p) in [("--crossover", crossover), ("--mutation", mutation)] {
                if !(0.0..=1.0).contains(&p) {
                    return Err(format!("{name}: {p} is not a probability").into());
                }
            }
            if population < 2 || generations == 0 || runs == 0 || every == 0 {
                return Err(
                    "--population needs at least 2; --generations, --runs, --every at least 1"
                        .into(),
                );
            }
            for (name, path) in [("--out", &out), ("--json", &json)] {
                if let Some(path) = path {
                    folder_exists(name, path)?;
                }
            }
            let sc = crate::scenario::resolve(&scenario)?;
            let model = sc
                .groups
                .first()
                .ok_or(crate::SimError::NoAgents)?
                .model
                .as_str();
            let table = models::get(model)?.params;
            let params = params
                .iter()
                .map(|p| crate::fit::Param::resolve(p, table))
                .collect::<crate::Result<Vec<_>>>()?;
            for (k, p) in params.iter().enumerate() {
                if params[..k].iter().any(|q| q.name == p.name) {
                    let spec = p.name.clone();
                    let problem = "named more than once";
                    return Err(crate::SimError::FitParam { spec, problem }.into());
                }
            }
            let reference_tracks = crate::eval::Tracks::open(&reference, dt)?;
            let first = seed.unwrap_or(sc.seed);
            let cal = crate::fit::Calibration {
                params,
                sampling: crate::fit::Sampling {
                    burn_in,
                    frames,
                    every,
                    seeds: (0..runs).map(|k| first.wrapping_add(k)).collect(),
                },
                scaling,
                ga: crate::fit::Ga {
                    population,
                    generations,
                    crossover,
                    mutation,
                    seed: ga_seed,
                },
            };
            let bar = crate::run::generations_bar(!quiet, u64::from(generations));
            let fitted = crate::fit::calibrate(&sc, &reference_tracks, &cal, |_, best| {
                bar.set_message(format!("best E {best:.4}"));
                bar.inc(1);
            })?;
            bar.finish_and_clear();
            println!(
                "{}: E {:.4} after {} runs ({} refused)",
                sc.name, fitted.score, fitted.evaluations, fitted.refused
            );
            for (name, v) in &fitted.values {
                println!("  {name} = {v:.6}");
            }
            let report = serde_json::json!({
                    "scenario": sc.name,
                    "reference": reference,
                    "scaling": scaling,
                    "score": fitted.score,
                    "values": fitted
                        .values
                        .iter()
                        .map(|(n, v)| (n.clone(), (*v).into()))
                        .collect::<serde_json::Map<_, _>>(),
                    "evaluations": fitted.evaluations,
                    "refused": fitted.refused,
                "history": fitted.history,
            });
            write_results(out, &fitted.scenario, json, &report)
        }
        Command::Fly { command } => fly(command),
        Command::Li { command } => li(command),
    }
}

fn fly(command: FlyCommand) -> Result<(), Box<dyn std::error::Error>> {
    let FlyCommand::Temperature {
        scenario,
        celsius,
        metres_per_unit,
        burn_in,
        frames,
        every,
        runs,
        seed,
        tolerance,
        rounds,
        out,
        json,
        quiet,
    } = command;
    positive("--metres-per-unit", metres_per_unit)?;
    positive("--tolerance", tolerance)?;
    if !celsius.is_finite() {
        return Err(format!("--celsius: {celsius} is not a temperature").into());
    }
    if frames == 0 || every == 0 || runs == 0 {
        return Err("--frames, --every and --runs need at least 1".into());
    }
    for (name, path) in [("--out", &out), ("--json", &json)] {
        if let Some(path) = path {
            folder_exists(name, path)?;
        }
    }
    let sc = crate::scenario::resolve(&scenario)?;
    let first = seed.unwrap_or(sc.seed);
    let t = Temperature {
        celsius,
        metres_per_unit,
        sampling: crate::fit::Sampling {
            burn_in,
            frames,
            every,
            seeds: (0..runs).map(|k| first.wrapping_add(k)).collect(),
        },
        tolerance,
        rounds,
    };
    let bar = crate::run::rounds_bar(!quiet, u64::from(rounds) + 1);
    let done = temperature::adjust(&sc, &t, |k, rho| {
        bar.set_message(format!("k {k:.3}: {rho:.4} per unit³"));
        bar.inc(1);
    });
    bar.finish_and_clear();
    let done = done?;
    println!(
        "{} at {celsius} °C: N(T) = {:.4} per unit³; insects resized by {:.4}, density {:.4} ({} rounds)",
        sc.name,
        done.target,
        done.scale,
        done.density,
        done.rounds.len()
    );
    let report = serde_json::json!({
            "scenario": sc.name,
            "celsius": celsius,
            "metres_per_unit": metres_per_unit,
            "target": done.target,
            "scale": done.scale,
            "density": done.density,
        "rounds": done.rounds,
    });
    write_results(out, &done.scenario, json, &report)
}

/// Writes a command's scenario to `out` and its report to `json`, each when asked for, saying
/// so (`swarm fit`, `swarm fly temperature`).
fn write_results(
    out: Option<PathBuf>,
    scenario: &crate::scenario::Scenario,
    json: Option<PathBuf>,
    report: &serde_json::Value,
) -> Result<(), Box<dyn std::error::Error>> {
    if let Some(path) = out {
        write_text(&path, &scenario.to_toml()?)?;
        println!("  wrote {}", path.display());
    }
    if let Some(path) = json {
        write_json(&path, report)?;
        println!("  wrote {}", path.display());
    }
    Ok(())
}

/// Writes `text` to `path` whole (a failure leaves the file as it was), first removing what a
/// killed earlier write left beside it.
fn write_text(path: &std::path::Path, text: &str) -> Result<(), Box<dyn std::error::Error>> {
    crate::output::remove_stale_temps(path);
    crate::output::write_atomic_bytes(path, text.as_bytes())?;
    Ok(())
}

/// Writes `report` to `path` as pretty JSON with a final newline ([`write_text`]).
fn write_json(
    path: &std::path::Path,
    report: &impl serde::Serialize,
) -> Result<(), Box<dyn std::error::Error>> {
    write_text(path, &(serde_json::to_string_pretty(report)? + "\n"))
}

/// Refuses output path `path` of option `name` when its folder does not exist (checked before
/// a long computation, not after).
fn folder_exists(name: &str, path: &std::path::Path) -> Result<(), Box<dyn std::error::Error>> {
    match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() && !dir.is_dir() => {
            Err(format!("{name}: no folder {}", dir.display()).into())
        }
        _ => Ok(()),
    }
}

/// A positive finite number given as option `name`.
fn positive(name: &str, v: f64) -> Result<f64, Box<dyn std::error::Error>> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(format!("{name}: {v} is not a positive number").into())
    }
}

fn li(command: LiCommand) -> Result<(), Box<dyn std::error::Error>> {
    match command {
        LiCommand::Fit {
            tracks,
            out,
            dt,
            cells,
            segmentation,
            c,
            r2,
            estimate,
            seed,
        } => {
            if let Some(dt) = dt {
                positive("--dt", dt)?;
            }
            let segmentation = match segmentation {
                SegmentationArg::Tolerance => Segmentation::Tolerance {
                    c: positive("--c", c)?,
                },
                SegmentationArg::R2 if r2 > 0.0 && r2 < 1.0 => Segmentation::R2 { r2 },
                SegmentationArg::R2 => {
                    return Err(format!("--r2: {r2} is not in (0, 1)").into());
                }
            };
            // Refuse an output path that cannot be written before the fit, not after.
            folder_exists("--out", &out)?;
            let data = crate::eval::Tracks::read_csv(&tracks, dt)?;
            let opts = crate::li::FitOptions {
                segmentation,
                estimate: match estimate {
                    EstimateArg::Indirect => Estimate::Indirect,
                    EstimateArg::Direct => Estimate::Direct,
                },
                cells,
                seed,
                ..crate::li::FitOptions::default()
            };
            let name = tracks.file_name().map_or_else(
                || tracks.display().to_string(),
                |n| n.to_string_lossy().into_owned(),
            );
            let model = crate::li::fit(&data, &name, &opts)?;
            model.write(&out)?;
            let p = &model.provenance;
            let t = &p.tables;
            println!(
                "{}: {} tracks, {} samples, {} segments ({} {}, {} estimate)",
                tracks.display(),
                p.tracks,
                p.samples,
                p.segments,
                segmentation.method(),
                segmentation.parameter(),
                match p.estimate {
                    Estimate::Indirect => "indirect",
                    Estimate::Direct => "direct",
                },
            );
            println!(
                "  segment length: mean {:.4}, median {:.4} (as segmented: {:.4}, {:.4})",
                t.length.mean, t.length.median, p.segmented.length.mean, p.segmented.length.median
            );
            println!(
                "  |turn|: median {:.1}° (as segmented: {:.1}°)",
                t.turn.median.to_degrees(),
                p.segmented.turn.median.to_degrees()
            );
            if let Some(f) = &p.fitted {
                println!(
                    "  fitted: speed {:.4}/s, noise {:.2e}, cost {:.1} after {} simulations",
                    f.speed, f.noise, f.cost, f.evals
                );
            }
            let d = &model.density;
            println!(
                "  density: {}x{}x{} cells of {:.4} from {:?}",
                d.dims[0], d.dims[1], d.dims[2], d.cell, d.origin
            );
            println!("  wrote {}", out.display());
            Ok(())
        }
        LiCommand::Synth {
            out,
            seed,
            tracks,
            samples,
            speed,
            fps,
            noise,
            side,
        } => {
            if tracks == 0 || samples == 0 {
                return Err("--tracks and --samples: at least 1".into());
            }
            let f = Fixture {
                insects: tracks,
                frames: samples,
                speed: positive("--speed", speed)?,
                fps: positive("--fps", fps)?,
                noise: if noise.is_finite() && noise >= 0.0 {
                    noise
                } else {
                    return Err(format!("--noise: {noise} is not a number >= 0").into());
                },
                side: positive("--side", side)?,
                seed,
            };
            let text = crate::li::synthetic_csv(&f);
            write_text(&out, &text)?;
            println!(
                "wrote {}: {tracks} synthetic tracks of {samples} samples (seed {seed})",
                out.display()
            );
            Ok(())
        }
    }
}
