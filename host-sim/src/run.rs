//! `swarm run`: a scenario from its first tick to its last, with a progress bar, a run log
//! and every output written whole into one folder.

use std::path::{Path, PathBuf};
use std::time::Instant;

use indicatif::{ProgressBar, ProgressStyle};

use crate::engine::{Engine, StateNames};
use crate::output::{
    self, Frame, RenderOptions, RunLog, Scene, Shape, ShapeKind, Summary,
    summary::{GroupSummary, pair_stats, state_counts_of},
};
use crate::scenario::{Action, Backend, ObjectKind, Scenario, ScenarioWarning, World};
use crate::{Result, SimError};

/// How to run a scenario.
#[derive(Clone, Debug)]
pub struct RunOptions {
    /// Output folder: created, or replaced whole, when the run completes (an existing one must
    /// hold only run files).
    pub out: PathBuf,
    /// Override the scenario's steps.
    pub steps: Option<u32>,
    /// Override the scenario's seed.
    pub seed: Option<u32>,
    /// Worker threads (default: all cores).
    pub threads: Option<usize>,
    /// Override the scenario's backend.
    pub backend: Option<Backend>,
    /// Show a progress bar.
    pub progress: bool,
    /// The scenario's warnings (from [`scenario::resolve_with_warnings`]), recorded in the run
    /// log; those of events that `steps` drops are left out.
    ///
    /// [`scenario::resolve_with_warnings`]: crate::scenario::resolve_with_warnings
    pub warnings: Vec<ScenarioWarning>,
}

/// What a run produced.
#[derive(Clone, Debug)]
pub struct RunReport {
    /// The summary also written to `summary.json`.
    pub summary: Summary,
    /// The files written.
    pub files: Vec<PathBuf>,
}

/// Runs `scenario` as `opts` say and writes its outputs.
///
/// The outputs appear together or not at all: the run writes into a staging folder beside
/// `opts.out` and swaps it in at the end ([`output::Staging`]), so `opts.out` holds exactly one
/// run at every instant. A scenario that cannot run (`--steps 0`, ...) is refused before any
/// folder is touched; a run that fails leaves `opts.out` as it was and reports where its log
/// went ([`SimError::RunFailed`]).
pub fn run(scenario: &Scenario, opts: &RunOptions) -> Result<RunReport> {
    run_with(scenario, opts, crate::models::engine)
}

/// [`run`] with the engine `engine(scenario, seed)` builds: any model's, also one defined
/// outside this crate.
pub fn run_with(
    scenario: &Scenario,
    opts: &RunOptions,
    engine: impl FnOnce(&Scenario, u32) -> Result<Box<dyn Engine>> + Send,
) -> Result<RunReport> {
    let sc = overridden(scenario, opts.steps, opts.backend)?;
    let seed = opts.seed.unwrap_or(sc.seed);
    let (pool, threads) = crate::par::pool(opts.threads)?;
    let stage = output::Staging::begin(&opts.out)?;
    let mut log = match RunLog::create(stage.path().join(output::RUN_LOG)) {
        Ok(log) => log,
        Err(e) => return Err(failed(opts, None, e)),
    };
    let result = log
        .line(format_args!(
            "scenario {} ({} agents, {} steps, seed {seed}, {threads} threads)",
            sc.name,
            sc.agent_count(),
            sc.steps
        ))
        .and_then(|()| {
            for w in opts.warnings.iter().filter(|w| w.applies_to(&sc)) {
                log.line(w)?;
            }
            let dir = stage.path();
            pool.install(|| {
                let mut engine = engine(&sc, seed)?;
                for note in engine.notes() {
                    log.line(note)?;
                }
                if let Some(a) = engine.adapter() {
                    log.line(format_args!("backend gpu: {a}"))?;
                }
                let mut summary = summary_for(&sc, seed, threads, &*engine);
                let mut rec = Recorder::new(&sc, dir, engine.agents())?;
                drive(
                    &sc,
                    &mut *engine,
                    &mut summary,
                    opts.progress,
                    &mut rec,
                    &mut log,
                )?;
                let names = rec.finish(&sc, dir, &summary)?;
                // The paths the files will have once the staging folder is swapped in.
                let files: Vec<PathBuf> = names.iter().map(|n| opts.out.join(n)).collect();
                for f in &files {
                    log.line(format_args!("wrote {}", f.display()))?;
                }
                Ok(RunReport { summary, files })
            })
        });
    let (stage, error) = match result {
        Ok(report) => match stage.commit() {
            Ok(()) => return Ok(report),
            Err(failure) => *failure,
        },
        Err(e) => (stage, e),
    };
    // Best effort: the disk may be full, or the log itself the file that failed.
    let _ = log.line(format_args!("error: {error}"));
    drop(log);
    Err(failed(opts, stage.abandon(), error))
}

/// The error of a run that failed after it began: `opts.out` was left untouched.
fn failed(opts: &RunOptions, log: Option<PathBuf>, error: SimError) -> SimError {
    SimError::RunFailed {
        target: opts.out.clone(),
        log,
        error: Box::new(error),
    }
}

/// `scenario` with the overrides of a run (`steps`, `backend`), checked by the scenario's own
/// rules (`--steps 0` like `steps = 0`).
fn overridden(
    scenario: &Scenario,
    steps: Option<u32>,
    backend: Option<Backend>,
) -> Result<Scenario> {
    let mut sc = scenario.clone();
    if let Some(steps) = steps {
        sc.set_steps(steps);
    }
    if let Some(backend) = backend {
        sc.backend = backend;
    }
    sc.validate()?;
    Ok(sc)
}

/// A run kept in memory ([`run_in_memory`]): its summary, every recorded frame (the first, every
/// `outputs.every` ticks, and the last) and its log's lines.
#[derive(Clone, Debug)]
pub struct MemoryRun {
    /// The summary `swarm run` writes to `summary.json`.
    pub summary: Summary,
    /// The recorded frames, in step order.
    pub frames: Vec<Frame>,
    /// The lines `swarm run` writes to `run.log` (without their times).
    pub log: Vec<String>,
}

/// Runs `scenario` as [`run`] does (`opts.steps`, `seed`, `threads`, `backend`, `progress`),
/// writing nothing: the frames stay in memory (the Python package's `swarm.run`). The same
/// seed gives the same bits as [`run`]'s outputs.
///
/// # Errors
///
/// What [`run`] refuses before it starts, and what the run fails with.
pub fn run_in_memory(scenario: &Scenario, opts: &RunOptions) -> Result<MemoryRun> {
    let sc = overridden(scenario, opts.steps, opts.backend)?;
    let seed = opts.seed.unwrap_or(sc.seed);
    let (pool, threads) = crate::par::pool(opts.threads)?;
    pool.install(|| {
        let mut engine = crate::models::engine(&sc, seed)?;
        let mut log = engine.notes();
        log.extend(engine.adapter().map(|a| format!("backend gpu: {a}")));
        let mut summary = summary_for(&sc, seed, threads, &*engine);
        let mut frames = Vec::new();
        drive(
            &sc,
            &mut *engine,
            &mut summary,
            opts.progress,
            &mut frames,
            &mut log,
        )?;
        Ok(MemoryRun {
            summary,
            frames,
            log,
        })
    })
}

/// Where a run's recorded frames go: the output files ([`Recorder`]) or memory.
trait Sink {
    fn push(&mut self, frame: Frame) -> Result<()>;
}

impl Sink for Vec<Frame> {
    fn push(&mut self, frame: Frame) -> Result<()> {
        Vec::push(self, frame);
        Ok(())
    }
}

/// Where a run's log lines go: `run.log` ([`RunLog`]) or memory.
trait Lines {
    fn line(&mut self, msg: impl std::fmt::Display) -> Result<()>;
}

impl Lines for RunLog {
    fn line(&mut self, msg: impl std::fmt::Display) -> Result<()> {
        RunLog::line(self, msg)
    }
}

impl Lines for Vec<String> {
    fn line(&mut self, msg: impl std::fmt::Display) -> Result<()> {
        self.push(msg.to_string());
        Ok(())
    }
}

/// The summary fields every run shares.
fn summary_for(sc: &Scenario, seed: u32, threads: usize, engine: &dyn Engine) -> Summary {
    let mut summary = Summary {
        scenario: sc.name.clone(),
        seed: seed as u64,
        steps: sc.steps,
        agents: engine.agents() as u32,
        groups: sc
            .groups
            .iter()
            .map(|g| GroupSummary {
                name: g.name.clone(),
                model: engine.model().into(),
                count: g.count,
                scalar: format!("{:?}", g.scalar.kind()),
            })
            .collect(),
        backend: engine.backend().into(),
        adapter: engine.adapter(),
        threads: threads as u32,
        collision_distance: engine.collision_distance(),
        ..Summary::default()
    };
    engine.begin_summary(&mut summary);
    summary
}

/// The run loop every model shares: events before each tick, the tick, recording every
/// `outputs.every` ticks (and the last) into `rec`, a progress bar; the summary's timing and the
/// model's closing figures. Trajectories stream to their files as they are recorded (a
/// [`Recorder`] keeps only the frames the pictures need).
fn drive(
    sc: &Scenario,
    engine: &mut dyn Engine,
    summary: &mut Summary,
    progress: bool,
    rec: &mut impl Sink,
    log: &mut impl Lines,
) -> Result<()> {
    let every = sc.outputs.every.max(1);
    let first = engine.frame();
    record(summary, &first, 0, engine.state_names());
    rec.push(first)?;
    let bar = progress_bar(progress, sc.steps as u64);
    let mut pending = std::collections::VecDeque::new();
    let t0 = Instant::now();
    for step in 0..sc.steps {
        for e in crate::engine::apply_due_events(engine, sc) {
            let (verb, object) = (e.action.verb(), e.action.object());
            log.line(format_args!("step {step}: {verb} {object}"))?;
        }
        engine.tick()?;
        for note in engine.notes() {
            log.line(format_args!("step {step}: {note}"))?;
        }
        engine.after_tick(summary);
        let done = step + 1;
        if done % every == 0 || done == sc.steps {
            // A GPU engine reads the step back while it goes on; the frame is written when
            // the next one is on its way.
            engine.snapshot()?;
            pending.push_back(done);
            while pending.len() > engine.frames_in_flight() {
                let Some(at) = pending.pop_front() else {
                    break;
                };
                take_frame(engine, summary, rec, at)?;
            }
        }
        bar.inc(1);
    }
    while let Some(at) = pending.pop_front() {
        take_frame(engine, summary, rec, at)?;
    }
    engine.sync()?;
    bar.finish_and_clear();
    summary.wall_seconds = t0.elapsed().as_secs_f64();
    summary.agent_steps_per_s =
        engine.agents() as f64 * sc.steps as f64 / summary.wall_seconds.max(1e-9);
    let closing = engine.closing(summary);
    log.line(format_args!(
        "done: {} ticks in {:.2} s ({:.3e} agent-steps/s), {closing}",
        sc.steps, summary.wall_seconds, summary.agent_steps_per_s
    ))
}

/// Takes the engine's oldest snapshot, of step `at`, and records its frame.
fn take_frame(
    engine: &mut dyn Engine,
    summary: &mut Summary,
    rec: &mut impl Sink,
    at: u32,
) -> Result<()> {
    engine.take_snapshot()?;
    let f = engine.frame();
    debug_assert_eq!(f.step, at, "the snapshot of the recorded step");
    record(summary, &f, at, engine.state_names());
    engine.on_record(summary, at);
    rec.push(f)
}

/// The most frames kept in memory for the pictures: longer runs keep every k-th recorded frame
/// (and the last), so memory stays bounded however long the run.
const MAX_PICTURE_FRAMES: u32 = 1000;

/// Where recorded frames go: the trajectory files (streamed, each committed whole at the end)
/// and the frames kept for the pictures.
struct Recorder {
    csv: Option<output::CsvWriter>,
    npy: Option<output::NpyWriter>,
    /// `attitude.npy` (3D worlds: bees; ants are level and have none).
    attitude: Option<output::NpyWriter>,
    /// Keep every `stride`-th frame for the pictures (0: keep none).
    stride: u32,
    /// Frames recorded so far.
    count: u32,
    kept: Vec<Frame>,
    /// The latest frame not kept, in case it is the last one.
    last: Option<Frame>,
}

impl Recorder {
    fn new(sc: &Scenario, out: &Path, agents: usize) -> Result<Self> {
        let o = &sc.outputs;
        let frames = sc.steps / o.every.max(1) + 2;
        Ok(Recorder {
            csv: o
                .trajectories
                .then(|| output::CsvWriter::create(out.join(output::TRAJECTORIES_CSV)))
                .transpose()?,
            npy: o
                .npy
                .then(|| output::NpyWriter::create(out.join(output::POSITIONS_NPY), agents))
                .transpose()?,
            attitude: (o.npy && matches!(sc.world, crate::scenario::World::Space { .. }))
                .then(|| {
                    output::NpyWriter::create_of(
                        out.join(output::ATTITUDE_NPY),
                        agents,
                        output::NpyField::Attitude,
                    )
                })
                .transpose()?,
            stride: if o.render || o.gif {
                frames.div_ceil(MAX_PICTURE_FRAMES)
            } else {
                0
            },
            count: 0,
            kept: Vec::new(),
            last: None,
        })
    }

    /// Writes the scene, commits the trajectory files, writes the summary and the pictures
    /// into `out`; returns the names of the files written, in that order.
    fn finish(mut self, sc: &Scenario, out: &Path, summary: &Summary) -> Result<Vec<&'static str>> {
        let scene = scene_of(sc);
        let mut files = Vec::new();
        scene.write(out.join(output::SCENE_JSON))?;
        files.push(output::SCENE_JSON);
        if let Some(w) = self.csv {
            w.finish()?;
            files.push(output::TRAJECTORIES_CSV);
        }
        if let Some(w) = self.npy {
            w.finish()?;
            files.push(output::POSITIONS_NPY);
        }
        if let Some(w) = self.attitude {
            w.finish()?;
            files.push(output::ATTITUDE_NPY);
        }
        summary.write(out.join(output::SUMMARY_JSON))?;
        files.push(output::SUMMARY_JSON);
        self.kept.extend(self.last.take());
        let opts = RenderOptions::default();
        if sc.outputs.render {
            output::render_png(&scene, &self.kept, out.join(output::SNAPSHOT_PNG), &opts)?;
            files.push(output::SNAPSHOT_PNG);
        }
        if sc.outputs.gif {
            output::render_gif(&scene, &self.kept, out.join(output::RUN_GIF), &opts)?;
            files.push(output::RUN_GIF);
        }
        Ok(files)
    }
}

impl Sink for Recorder {
    fn push(&mut self, frame: Frame) -> Result<()> {
        if let Some(w) = &mut self.csv {
            w.push(&frame)?;
        }
        if let Some(w) = &mut self.npy {
            w.push(&frame)?;
        }
        if let Some(w) = &mut self.attitude {
            w.push(&frame)?;
        }
        if self.stride > 0 {
            if self.count.is_multiple_of(self.stride) {
                self.kept.push(frame);
                self.last = None;
            } else {
                self.last = Some(frame);
            }
        }
        self.count += 1;
        Ok(())
    }
}

fn record(summary: &mut Summary, frame: &Frame, step: u32, names: StateNames) {
    let mut counts = state_counts_of(frame, names);
    counts.step = step;
    summary.state_counts.push(counts);
    summary.add_pair_stats(pair_stats(frame, summary.collision_distance));
}

fn progress_bar(show: bool, len: u64) -> ProgressBar {
    bar_of(
        show,
        len,
        "{elapsed_precise} [{bar:40}] {pos}/{len} ticks ({per_sec}, eta {eta})",
    )
}

/// The progress bar of a calibration (`swarm fit`): generations done and the best score (the
/// message), on a terminal only.
pub fn generations_bar(show: bool, len: u64) -> ProgressBar {
    bar_of(
        show,
        len,
        "{elapsed_precise} [{bar:40}] {pos}/{len} generations, {msg} (eta {eta})",
    )
}

/// The progress bar of a resizing to a temperature (`swarm fly temperature`): rounds measured
/// and the last one's resizing and density (the message), on a terminal only.
pub fn rounds_bar(show: bool, len: u64) -> ProgressBar {
    bar_of(
        show,
        len,
        "{elapsed_precise} [{bar:40}] round {pos}/{len}, {msg}",
    )
}

fn bar_of(show: bool, len: u64, template: &str) -> ProgressBar {
    if !show || !std::io::IsTerminal::is_terminal(&std::io::stderr()) {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(len);
    bar.set_style(
        ProgressStyle::with_template(template)
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    bar
}

/// The scene of a scenario: every object, with the steps it is visible (events included).
pub fn scene_of(sc: &Scenario) -> Scene {
    let mut scene = match sc.world {
        World::Plane { min, max } => Scene::new_2d(min, max),
        World::Space { min, max } => Scene::new_3d(min, max),
    };
    for o in &sc.objects {
        let mut kind = o.kind.clone();
        let mut from = if o.active { Some(0) } else { None };
        for e in sc.events.iter().filter(|e| e.action.object() == o.name) {
            match &e.action {
                Action::Add(_) | Action::Start(_) => from = Some(e.step),
                Action::Remove(_) | Action::Stop(_) => {
                    if let Some(f) = from.take() {
                        scene
                            .shapes
                            .extend(shape_of(&o.name, &kind, f, Some(e.step)));
                    }
                }
                Action::Move { to, .. } => {
                    if let Some(f) = from {
                        scene
                            .shapes
                            .extend(shape_of(&o.name, &kind, f, Some(e.step)));
                        from = Some(e.step);
                    }
                    kind.set_center(to);
                }
            }
        }
        if let Some(f) = from {
            scene.shapes.extend(shape_of(&o.name, &kind, f, None));
        }
    }
    scene
}

fn shape_of(name: &str, kind: &ObjectKind, from: u32, to: Option<u32>) -> Option<Shape> {
    let c2 = |c: [f32; 2]| [c[0], c[1], 0.0];
    let shape = match kind {
        ObjectKind::Nest { center, radius } => Shape::circle(c2(*center), *radius, ShapeKind::Nest),
        ObjectKind::Food { center, radius, .. } => {
            Shape::circle(c2(*center), *radius, ShapeKind::Food)
        }
        ObjectKind::Rock { center, radius } => Shape::circle(c2(*center), *radius, ShapeKind::Rock),
        ObjectKind::Polygon { points } => Shape::polygon(points.clone(), ShapeKind::Rock),
        ObjectKind::Disturbance { center, radius } => {
            Shape::circle(c2(*center), *radius, ShapeKind::Disturbance)
        }
        ObjectKind::Waypoint { center, radius, .. } => {
            Shape::circle(c2(*center), *radius, ShapeKind::Waypoint)
        }
        ObjectKind::Sphere { center, radius } => Shape::circle(*center, *radius, ShapeKind::Sphere),
        ObjectKind::Box { min, max } => Shape::cuboid(*min, *max, ShapeKind::Rock),
        ObjectKind::Shaft { center, radius, .. } => {
            Shape::circle([center[0], 0.0, center[1]], *radius, ShapeKind::Shaft)
        }
        ObjectKind::Target { center, radius, .. } | ObjectKind::Zone { center, radius } => {
            Shape::circle(*center, *radius, ShapeKind::Target)
        }
        ObjectKind::Region { min, max } => Shape::cuboid(*min, *max, ShapeKind::Target),
        // The cave is the world the insects fly in: its walls are the render's frame.
        ObjectKind::Cave { .. } => return None,
    };
    let from = (from > 0).then_some(from);
    Some(shape.named(name).during(from, to))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_runs_keep_a_bounded_number_of_picture_frames_and_the_last_one() {
        let mut sc = crate::scenario::builtin("ants-fig7a-single-colony").unwrap();
        sc.set_steps(10_000);
        sc.outputs.every = 1;
        sc.outputs.trajectories = false;
        sc.outputs.npy = false;
        let dir = tempfile::tempdir().unwrap();
        let mut rec = Recorder::new(&sc, dir.path(), 0).unwrap();
        for step in 0..=10_000 {
            rec.push(Frame {
                step,
                agents: Vec::new(),
            })
            .unwrap();
        }
        rec.kept.extend(rec.last.take());
        assert!(rec.kept.len() <= MAX_PICTURE_FRAMES as usize + 1);
        assert!(rec.kept.len() >= MAX_PICTURE_FRAMES as usize / 2);
        assert_eq!(rec.kept.last().map(|f| f.step), Some(10_000));
        assert!(rec.kept.windows(2).all(|w| w[0].step < w[1].step));
    }

    /// A run kept in memory records what `run` writes: the same frames (positions.npy's
    /// bytes) and summary, for any thread count; its log has the closing line.
    #[test]
    fn a_run_in_memory_is_the_written_run() {
        let sc = crate::scenario::builtin("fly-fig8-escape").unwrap();
        let dir = tempfile::tempdir().unwrap();
        let opts = RunOptions {
            out: dir.path().join("run"),
            steps: Some(30),
            seed: Some(4),
            threads: Some(1),
            backend: None,
            progress: false,
            warnings: Vec::new(),
        };
        let written = run(&sc, &opts).unwrap();
        let kept = run_in_memory(
            &sc,
            &RunOptions {
                threads: Some(2),
                ..opts.clone()
            },
        )
        .unwrap();
        let steps: Vec<u32> = kept.frames.iter().map(|f| f.step).collect();
        assert_eq!(steps, [0, 10, 20, 30]);
        let agents = kept.frames[0].agents.len();
        let mut npy = output::NpyWriter::create(dir.path().join("again.npy"), agents).unwrap();
        for f in &kept.frames {
            npy.push(f).unwrap();
        }
        npy.finish().unwrap();
        let a = std::fs::read(opts.out.join(output::POSITIONS_NPY)).unwrap();
        let b = std::fs::read(dir.path().join("again.npy")).unwrap();
        assert!(a == b, "the frames differ from positions.npy");
        let (mut x, mut y) = (written.summary, kept.summary);
        for s in [&mut x, &mut y] {
            (s.wall_seconds, s.agent_steps_per_s, s.threads) = (0.0, 0.0, 0);
        }
        assert_eq!(x, y);
        assert!(kept.log.iter().any(|l| l.starts_with("done: 30 ticks")));
        // Refused before it starts, as `run` is.
        let zero = RunOptions {
            steps: Some(0),
            ..opts
        };
        assert!(run_in_memory(&sc, &zero).is_err());
    }
}
