//! The crate's error type: one flat enum for the engines, the scenario files and the run
//! outputs.

use std::io;
use std::path::PathBuf;

use crate::scenario::Diagnostic;

/// `Result` with [`SimError`].
pub type Result<T> = std::result::Result<T, SimError>;

/// Everything that can go wrong in the simulator.
///
/// Every message can be shown to a user as it is: it names the step and agent, the scenario
/// file, line and field, or the output file (and line) and what was wrong. The variants come in
/// four groups: the engines and runs; scenarios (a bad scenario file is one
/// [`InvalidScenario`](SimError::InvalidScenario), its [`Diagnostic`] naming file, line, column
/// and field); the data handed to an output writer (`cannot write <file>: ...`); and files of a
/// run folder that cannot be read back (`<file>[:line]: ...`).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SimError {
    // ---- engines and runs ----
    /// A controller refused its input (a bug in the world or in frame building: the report
    /// names the step, the agent and the field).
    #[error("{phase} of agent {agent} at step {step}: {source}")]
    Controller {
        /// Which call.
        phase: &'static str,
        /// Step.
        step: u32,
        /// Agent id.
        agent: u32,
        /// The controller's error.
        source: swarm_core::Error,
    },
    /// The groups of a simulation mirrored on one device compute in different scalar types.
    #[error("groups `{first}` and `{other}` have different scalar types; a device runs one")]
    MixedScalars {
        /// The first group.
        first: String,
        /// A group of another scalar type.
        other: String,
    },
    /// The groups of a simulation mirrored on one device have different parameters.
    #[error(
        "groups `{first}` and `{other}` have different parameters; a device runs one parameter set"
    )]
    DifferentParams {
        /// The first group.
        first: String,
        /// A group with other parameters.
        other: String,
    },
    /// The simulation has no agents.
    #[error("the simulation has no agents")]
    NoAgents,
    /// A model the simulator does not know: neither built in
    /// ([`models::BUILTIN`](crate::models::BUILTIN)) nor registered
    /// ([`models::register`](crate::models::register)).
    #[error("no model `{name}` (known: {known})")]
    UnknownModel {
        /// The name asked for.
        name: String,
        /// The models there are, comma-separated.
        known: String,
    },
    /// A second, different model registered under a name already taken.
    #[error("a model called `{0}` is already registered")]
    ModelTaken(&'static str),
    /// A group's parameter table that does not read as its model's parameters.
    #[error("group `{group}`: its `{model}` parameter table: {source}")]
    ParamsTable {
        /// The group.
        group: String,
        /// Its model.
        model: String,
        /// What the reader refused.
        source: Box<toml::de::Error>,
    },
    /// Parameters that do not write as a table ([`Group::set_params`](crate::scenario::Group::set_params)).
    #[error("group `{group}`: its parameters do not write as a table: {source}")]
    ParamsWrite {
        /// The group.
        group: String,
        /// What the writer refused.
        source: Box<toml::ser::Error>,
    },
    /// An agent id the simulation does not have.
    #[error("no agent {id} (the simulation has {agents})")]
    NoAgent {
        /// The id asked for.
        id: u32,
        /// How many agents there are.
        agents: usize,
    },
    /// A device for the simulation's parameters could not be made.
    #[error("device: {0}")]
    Device(swarm_core::Error),
    /// A message of an exchange (a request or a reply sent to or compared with a device)
    /// could not be encoded.
    #[error("cannot encode a {message} (message kind {kind:#04x}): {source}")]
    Encode {
        /// The message's type.
        message: &'static str,
        /// Its kind.
        kind: u8,
        /// postcard's error.
        source: postcard::Error,
    },
    /// A scenario given to a model that does not live in its world (an ant simulation of a
    /// 3D world, ...).
    #[error("scenario `{scenario}` is not a {dim}D world: the {model} model cannot run it")]
    WrongWorld {
        /// The scenario.
        scenario: String,
        /// The model.
        model: &'static str,
        /// The dimension the model needs.
        dim: usize,
    },
    /// A group names an object the scenario does not have (or of the wrong kind).
    #[error("group `{group}`: no {what} `{name}`")]
    NoObject {
        /// The group.
        group: String,
        /// What it names (`nest`, `goal`).
        what: &'static str,
        /// The name (empty if none was given).
        name: String,
    },
    /// A group's parameters, converted to its scalar type, fail the controller's validation.
    #[error("group `{group}`: {source}")]
    GroupParams {
        /// The group.
        group: String,
        /// The controller's complaint (which parameter).
        source: swarm_core::Error,
    },
    /// A group's spawn region has no room for its agents kept apart (ren2016 insects start
    /// at least two ORCA radii apart).
    #[error(
        "group `{group}`: agent {agent} found no place at least {distance} from the agents \
         before it in {attempts} tries: the spawn region is too small for the group (enlarge \
         `spawn` or lower `count`)"
    )]
    SpawnCrowded {
        /// The group.
        group: String,
        /// The agent (its index in the group) that found no place.
        agent: u32,
        /// The distance kept.
        distance: f32,
        /// Places tried.
        attempts: u32,
    },
    /// A worker-thread count of zero.
    #[error("threads: must be at least 1")]
    NoThreads,
    /// The pool of worker threads could not be started.
    #[error("threads: cannot start {threads} threads: {source}")]
    ThreadPool {
        /// The count asked for.
        threads: usize,
        /// The pool's error.
        source: rayon::ThreadPoolBuildError,
    },
    /// `--backend gpu` on a machine where wgpu finds no adapter.
    #[error("--backend gpu: no GPU adapter ({source}); {hint}")]
    NoGpu {
        /// wgpu's answer.
        source: wgpu::RequestAdapterError,
        /// What to install.
        hint: &'static str,
    },
    /// The adapter refused to open a device.
    #[error("--backend gpu: the adapter {adapter} refused a device: {source}")]
    GpuDevice {
        /// The adapter.
        adapter: String,
        /// wgpu's error.
        source: wgpu::RequestDeviceError,
    },
    /// `--backend gpu` for groups of both scalar types.
    #[error(
        "--backend gpu: groups `{first}` and `{other}` have different scalar types; the GPU \
         engine runs one scalar type per simulation"
    )]
    GpuMixedScalars {
        /// The first group.
        first: String,
        /// A group of another scalar type.
        other: String,
    },
    /// `--backend gpu` for a model that has no GPU engine.
    #[error("--backend gpu: the `{model}` model has no GPU engine yet (run it with --backend cpu)")]
    NoGpuEngine {
        /// The model.
        model: String,
    },
    /// The GPU stopped answering (device lost, or a wait timed out).
    #[error("GPU: {source}")]
    GpuLost {
        /// wgpu's error.
        source: wgpu::PollError,
    },
    /// A result buffer could not be mapped for reading.
    #[error("GPU: cannot read back `{buffer}`: {source}")]
    GpuReadback {
        /// The buffer's label.
        buffer: &'static str,
        /// wgpu's error.
        source: wgpu::BufferAsyncError,
    },
    /// A kernel's WGSL did not compile (a bug in `shaders/`, caught by the naga test).
    #[error("GPU: kernel `{kernel}` does not compile: {message}")]
    GpuShader {
        /// The kernel.
        kernel: &'static str,
        /// The compiler's diagnostic.
        message: String,
    },
    /// A kernel wrote words that the layout of its values does not allow (a bug in `shaders/`:
    /// an enum discriminant or status word no Rust value has).
    #[error("GPU: a kernel wrote {word:#010x}, which is no {what} (a bug in shaders/)")]
    GpuWords {
        /// What the word should have been.
        what: &'static str,
        /// The word.
        word: u32,
    },
    /// A swarm larger than one storage binding of the adapter holds.
    #[error(
        "GPU: `{buffer}` needs {bytes} bytes, more than the adapter's largest storage binding \
         ({limit} bytes): fewer agents, or a GPU with more memory"
    )]
    GpuTooLarge {
        /// The buffer.
        buffer: &'static str,
        /// Its size.
        bytes: u64,
        /// The adapter's limit.
        limit: u64,
    },
    /// A GPU neighbour grid of no cells.
    #[error("GPU grid: a grid needs at least one cell")]
    GpuGridNoCells,
    /// More agents handed to a GPU neighbour grid than it was built for.
    #[error("GPU grid: {agents} agents, more than the {capacity} it was built for")]
    GpuGridCapacity {
        /// The agents to sort.
        agents: u64,
        /// The grid's capacity.
        capacity: u32,
    },
    /// A cells buffer too small for the agents a GPU neighbour grid is asked to sort.
    #[error("GPU grid: the cells buffer holds {bytes} bytes, {agents} agents need {needed}")]
    GpuGridCells {
        /// The buffer's size.
        bytes: u64,
        /// The agents to sort.
        agents: u32,
        /// Their cells' size (4 bytes each).
        needed: u64,
    },
    /// A field grid ([`fields::CellGrid`](crate::fields::CellGrid)) whose box or cell side is
    /// not finite, empty, or not positive.
    #[error(
        "field grid: box min {min:?} max {max:?} with cell side {cell} is not a grid (the corners \
         and the side must be finite, min < max on every axis, cell > 0)"
    )]
    FieldGridInvalid {
        /// The lower corner asked for.
        min: [f32; 3],
        /// The upper corner asked for.
        max: [f32; 3],
        /// The cell side asked for.
        cell: f32,
    },
    /// A field grid with more cells than the limit.
    #[error(
        "field grid: box min {min:?} max {max:?} with cell side {cell} needs {dims:?} = {cells} \
         cells, more than the limit of {limit}: a larger cell side or a smaller box"
    )]
    FieldGridTooLarge {
        /// The lower corner asked for.
        min: [f32; 3],
        /// The upper corner asked for.
        max: [f32; 3],
        /// The cell side asked for.
        cell: f32,
        /// The cells per axis it needs.
        dims: [u64; 3],
        /// Their product.
        cells: u64,
        /// The most cells a grid may have.
        limit: u64,
    },
    /// A li2015 density grid with no cells, or more than a device holds.
    #[error(
        "li density: {cells} cells, a grid needs at least 1 and a device holds at most {max} \
         (one byte each): fewer `cells` along the longest side"
    )]
    LiGrid {
        /// The cells asked for.
        cells: usize,
        /// The most a grid may have.
        max: usize,
    },
    /// Samples a li2015 distribution cannot be tabulated from.
    #[error(
        "li data: cannot tabulate the {what} from {n} samples (they must be finite and not all \
         equal)"
    )]
    LiSamples {
        /// Which distribution.
        what: &'static str,
        /// How many samples there were.
        n: usize,
    },
    /// A li2015 model file that is not TOML, or whose field is missing, unknown or of the
    /// wrong type.
    #[error("{}:{line}:{column}: {}", path.display(), source.message())]
    LiModelToml {
        /// The model file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// The reader's error.
        source: Box<toml::de::Error>,
    },
    /// A file that is not a li2015 model file of the version this build reads.
    #[error(
        "{}: `format = {}`, `version = {}`: expected a li2015 model file, `format = \"{}\"` \
         and `version = {}` (written by `swarm li fit`)",
        path.display(),
        format.as_deref().unwrap_or("(missing)"),
        version.as_deref().unwrap_or("(missing)"),
        crate::li::model::FORMAT,
        crate::li::model::VERSION
    )]
    LiModelVersion {
        /// The file.
        path: PathBuf,
        /// Its `format`, as written (`None`: missing).
        format: Option<String>,
        /// Its `version`, as written (`None`: missing).
        version: Option<String>,
    },
    /// A li2015 model file with a value that breaks a rule.
    #[error("{}:{line}: `{field}`: {problem}", path.display())]
    LiModelField {
        /// The model file.
        path: PathBuf,
        /// 1-based line of the field.
        line: usize,
        /// The field's path (`lengths.counts`, `density.origin[1]`).
        field: String,
        /// What is wrong.
        problem: crate::li::model::ModelProblem,
    },
    /// A model file's density grid that does not fit in the world of the scenario using it.
    #[error(
        "{}: the density grid spans {grid_min:?} to {grid_max:?}, outside the world {world_min:?} \
         to {world_max:?}: widen the world to hold the data's box, or give the group its own \
         `density`",
        path.display()
    )]
    LiModelOutside {
        /// The model file.
        path: PathBuf,
        /// The grid's lower corner.
        grid_min: [f32; 3],
        /// The grid's upper corner.
        grid_max: [f32; 3],
        /// The world's lower corner.
        world_min: [f32; 3],
        /// The world's upper corner.
        world_max: [f32; 3],
    },
    /// Tracks too short for the li2015 pipeline.
    #[error(
        "li data: the segmentation found {segments} segments and {turns} turns between them; \
         fitting needs at least {needed} of each (longer or more tracks)"
    )]
    LiTooFewSegments {
        /// Segments found.
        segments: usize,
        /// Turns found.
        turns: usize,
        /// The least of each.
        needed: usize,
    },
    /// A per-cell array handed to a field solver whose length is not the grid's cell count.
    #[error("field: {what} has {len} values, the grid has {cells} cells")]
    FieldLength {
        /// Which array (`signed distance`, `goal mask`).
        what: &'static str,
        /// Its length.
        len: usize,
        /// The grid's cells.
        cells: usize,
    },
    /// A cost field asked for with no goal cell.
    #[error(
        "cost field: no goal cell (no cell centre of the {cells}-cell grid lies in a goal region)"
    )]
    FieldNoGoal {
        /// The grid's cells.
        cells: usize,
    },
    /// Cost weights that do not give every cell a positive, finite cost per unit length.
    #[error(
        "cost field: weights a = {a}, b = {b}, inside = {inside} must be finite with a > 0, \
         b >= 0, inside > 0"
    )]
    FieldWeights {
        /// Weight of the path length.
        a: f32,
        /// Weight of the repulsion.
        b: f32,
        /// Cost per unit length inside obstacles.
        inside: f32,
    },
    /// A benchmark with nothing to time.
    #[error("bench: needs at least one agent and one step (got {agents} agents, {steps} steps)")]
    EmptyBench {
        /// Agents asked for.
        agents: usize,
        /// Steps asked for.
        steps: u32,
    },
    /// A run failed after it started writing: its output folder was left as it was, and the
    /// run's log (ending with the error) kept beside it, when it could be.
    #[error(
        "{error}\n{} was left untouched{}",
        target.display(),
        log.as_ref().map_or_else(String::new, |l| format!("; the failed run's log is {}", l.display()))
    )]
    RunFailed {
        /// The output folder the run was to replace.
        target: PathBuf,
        /// The failed run's log, if it could be kept.
        log: Option<PathBuf>,
        /// What went wrong.
        error: Box<SimError>,
    },

    // ---- scenarios ----
    /// A scenario file could not be read.
    #[error("cannot read scenario file `{}`: {source}", path.display())]
    ScenarioRead {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        #[source]
        source: io::Error,
    },
    /// A scenario is not valid TOML, does not have the scenario's shape (unknown field, wrong
    /// type, missing field) or breaks a rule of the scenario (a spawn region outside the world,
    /// an event naming a missing object, a bad controller parameter, ...). Loading stops at the
    /// first problem; the diagnostic names the file, line, column and field path.
    #[error("{0}")]
    InvalidScenario(Box<Diagnostic>),
    /// Neither a built-in scenario nor a file of that name (`resolve`).
    #[error(
        "no built-in scenario and no file named `{name}` (built-in scenarios: {})",
        builtins.join(", ")
    )]
    ScenarioNotFound {
        /// The name or path asked for.
        name: String,
        /// The names of the built-in scenarios.
        builtins: &'static [&'static str],
    },

    // ---- output files and folders ----
    /// An I/O operation on `path` failed (`op` says which: "creating", "writing", "reading", ...).
    #[error("{op} {}: {source}", path.display())]
    Io {
        /// What was being done.
        op: &'static str,
        /// The file or folder.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: io::Error,
    },
    /// A JSON file could not be written or parsed.
    #[error("{op} {}: {source}", path.display())]
    Json {
        /// "serialising" or "parsing".
        op: &'static str,
        /// The file.
        path: PathBuf,
        /// The underlying error (its message carries line and column when parsing).
        #[source]
        source: serde_json::Error,
    },
    /// A required file of a run folder is missing.
    #[error("run folder {} has no {file} ({hint})", dir.display())]
    MissingRunFile {
        /// The run folder.
        dir: PathBuf,
        /// The missing file name (or names).
        file: String,
        /// What it is needed for.
        hint: &'static str,
    },
    /// An existing output folder holds something no run writes (a run replaces its folder
    /// whole, so it refuses to delete what may be a user's file).
    #[error(
        "{} holds `{entry}`, which no run writes; a run replaces its output folder whole, so \
         choose another output folder (`--out`) or move `{entry}` away",
        dir.display()
    )]
    NotARunFolder {
        /// The folder.
        dir: PathBuf,
        /// The first entry that is not a run file.
        entry: String,
    },
    /// An output folder whose name is missing or not UTF-8.
    #[error("cannot write {}: the output folder needs a name in UTF-8", path.display())]
    OutputFolderName {
        /// The folder.
        path: PathBuf,
    },
    /// An output file path without a file name.
    #[error("cannot write {}: the path has no file name", path.display())]
    NoFileName {
        /// The path.
        path: PathBuf,
    },

    // ---- data handed to an output writer ----
    /// Nothing to draw: no frames were recorded.
    #[error("cannot write {}: there are no recorded frames to draw", path.display())]
    NoFrames {
        /// The picture to be drawn.
        path: PathBuf,
    },
    /// A frame holds another number of agents than the first.
    #[error(
        "cannot write {}: frame {frame} (step {step}) has {agents} agents, frame 0 has {first}",
        path.display()
    )]
    FrameAgentCount {
        /// The file to be written.
        path: PathBuf,
        /// The frame's index.
        frame: usize,
        /// Its step.
        step: u32,
        /// Its agents.
        agents: usize,
        /// The first frame's agents.
        first: usize,
    },
    /// A frame whose step is not after the previous frame's.
    #[error(
        "cannot write {}: frame {frame} has step {step} after step {previous}: steps must increase",
        path.display()
    )]
    FrameStepOrder {
        /// The file to be written.
        path: PathBuf,
        /// The frame's index.
        frame: usize,
        /// Its step.
        step: u32,
        /// The previous frame's step.
        previous: u32,
    },
    /// A frame holds another agent than the first frame at the same index.
    #[error(
        "cannot write {}: frame {frame} (step {step}) has agent id {id} at index {index}, frame 0 \
         has {first}",
        path.display()
    )]
    FrameAgentId {
        /// The file to be written.
        path: PathBuf,
        /// The frame's index.
        frame: usize,
        /// Its step.
        step: u32,
        /// The agent's index in the frame.
        index: usize,
        /// The agent id there.
        id: u32,
        /// The first frame's agent id there.
        first: u32,
    },
    /// A frame streamed to a CSV writer holds another number of agents than the first.
    #[error(
        "cannot write {}: frame at step {step} has {agents} agents, the first frame had {first}",
        path.display()
    )]
    CsvFrameAgents {
        /// The CSV file.
        path: PathBuf,
        /// The frame's step.
        step: u32,
        /// Its agents.
        agents: usize,
        /// The first frame's agents.
        first: usize,
    },
    /// A frame streamed to a CSV writer whose step is not after the previous frame's.
    #[error(
        "cannot write {}: step {step} follows step {last}: steps must increase",
        path.display()
    )]
    CsvStepOrder {
        /// The CSV file.
        path: PathBuf,
        /// The frame's step.
        step: u32,
        /// The previous frame's step.
        last: u32,
    },
    /// A frame streamed to an NPY writer holds another number of agents than the array.
    #[error(
        "cannot write {}: a frame has {agents} agents, the array has {expected}",
        path.display()
    )]
    NpyFrameAgents {
        /// The NPY file.
        path: PathBuf,
        /// The frame's agents.
        agents: usize,
        /// The array's agents.
        expected: usize,
    },
    /// The NPY header with the final frame count no longer fits the space left for it.
    #[error(
        "cannot write {}: the NPY header changed length (more than 10^21 frames?)",
        path.display()
    )]
    NpyHeaderGrew {
        /// The NPY file.
        path: PathBuf,
    },
    /// A scene that is neither 2D nor 3D.
    #[error("cannot write {}: dim is {dim}, must be 2 or 3", path.display())]
    SceneDim {
        /// The scene file.
        path: PathBuf,
        /// Its dimension.
        dim: u8,
    },
    /// A scene whose world bounds are empty or not finite.
    #[error(
        "cannot write {}: world bounds min {min:?} max {max:?} are empty or not finite",
        path.display()
    )]
    SceneBounds {
        /// The scene file.
        path: PathBuf,
        /// The smallest corner.
        min: [f32; 3],
        /// The largest corner.
        max: [f32; 3],
    },
    /// A scene shape with invalid geometry.
    #[error(
        "cannot write {}: shape {index} ({shape}) has invalid geometry (non-finite numbers, \
         negative radius, fewer than 3 polygon points or min > max)",
        path.display()
    )]
    SceneShape {
        /// The scene file.
        path: PathBuf,
        /// The shape's index.
        index: usize,
        /// The shape's kind and geometry, as `{kind:?} {geom:?}`.
        shape: String,
    },
    /// A scene shape visible from a step after the one it disappears at.
    #[error(
        "cannot write {}: shape {index} has from_step {from} > to_step {to}",
        path.display()
    )]
    SceneShapeSteps {
        /// The scene file.
        path: PathBuf,
        /// The shape's index.
        index: usize,
        /// Its first step.
        from: u32,
        /// Its last step (exclusive).
        to: u32,
    },
    /// An animation too large for a GIF (whose sides are 16-bit).
    #[error("cannot write {}: GIF size {width}x{height} is too large", path.display())]
    GifTooLarge {
        /// The GIF file.
        path: PathBuf,
        /// Width in pixels.
        width: usize,
        /// Height in pixels.
        height: usize,
    },

    // ---- run files that cannot be read back ----
    /// `attitude.npy` has another shape than `positions.npy` beside it.
    #[error(
        "{}: shape ({frames}, {agents}, 2) does not match positions.npy",
        path.display()
    )]
    AttitudeShape {
        /// The attitude file.
        path: PathBuf,
        /// Its frames.
        frames: usize,
        /// Its agents.
        agents: usize,
    },
    /// A track file whose times give no frame interval (every track has one sample).
    #[error(
        "{}: no two samples of one id at different times: cannot tell the frame interval \
         (give it with --dt)",
        path.display()
    )]
    TrackInterval {
        /// The track file.
        path: PathBuf,
    },
    /// A frame interval given for a track file that is not a positive number of seconds.
    #[error("{}: frame interval {dt}: expected a positive number of seconds", path.display())]
    TrackDt {
        /// The track file.
        path: PathBuf,
        /// The interval given.
        dt: f64,
    },
    /// A track sample whose time is not on the frame grid.
    #[error(
        "{}:{line}: time {time} is not on the frame grid (interval {dt} s from the earliest \
         time); tracks must share one frame rate",
        path.display()
    )]
    TrackTime {
        /// The track file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// The row's time.
        time: f64,
        /// The frame interval.
        dt: f64,
    },
    /// A `--param` of `swarm fit` that does not read as `NAME=LOW:HIGH`.
    #[error("--param {spec:?}: {problem}")]
    FitParam {
        /// What was given.
        spec: String,
        /// What is wrong with it.
        problem: &'static str,
    },
    /// A `--param` range that leaves the values the model takes for the parameter.
    #[error("--param {name}={low}:{high}: leaves the model's range for {name}, {range}")]
    FitRange {
        /// The parameter.
        name: String,
        /// The range given.
        low: f64,
        /// The range given.
        high: f64,
        /// What the model takes.
        range: swarm_core::model::Range,
    },
    /// A calibration with nothing to fit: no parameter, no seed, or fewer than 3 frames (the
    /// jerk needs 3 consecutive velocities).
    #[error("fit: needs at least one parameter, one seed and 3 frames")]
    FitNothing,
    /// A calibration in which the model refused every individual (or every run failed).
    #[error(
        "fit: all {evaluations} individuals were refused by the model's rules or failed to run; \
         narrow the parameter ranges"
    )]
    FitRefusedAll {
        /// Individuals tried.
        evaluations: usize,
    },
    /// A temperature at which Eq. 1 of ren2016 gives no swarm (N(T) ≤ 0).
    #[error("{celsius} °C: Eq. 1 gives no swarm there (N(T) > 0 only between 8.74 and 35.66 °C)")]
    TemperatureNoSwarm {
        /// The temperature asked for (°C).
        celsius: f64,
    },
    /// A scenario without enough ren2016 (`fly`) insects to measure a density (more than 5:
    /// each insect's 5th nearest neighbour).
    #[error(
        "scenario `{scenario}`: no ren2016 (`fly`) swarm of more than 5 insects to measure and \
         resize"
    )]
    TemperatureNoInsects {
        /// The scenario.
        scenario: String,
    },
    /// A temperature whose density would need a swarm larger than the world.
    #[error(
        "{celsius} °C: N(T) = {target:.4} insects per unit³ needs {needed:.1} unit³ for the \
         swarm, more than the world's {world:.1}; use a larger world, fewer insects or check \
         --metres-per-unit"
    )]
    TemperatureTooSparse {
        /// The temperature (°C).
        celsius: f64,
        /// N(T) per unit³ of the scenario.
        target: f64,
        /// The volume the insects need at that density (unit³).
        needed: f64,
        /// The world's volume (unit³).
        world: f64,
    },
    /// Resizing that did not reach N(T) within the tolerance in the rounds allowed.
    #[error(
        "{celsius} °C: the density did not reach N(T) = {target:.4} per unit³ (resizing, \
         density by round: {rounds:?}); the world or the spawn region may bound the swarm"
    )]
    TemperatureUnreached {
        /// The temperature (°C).
        celsius: f64,
        /// N(T) per unit³ of the scenario.
        target: f64,
        /// Each round's resizing k and the density measured with it.
        rounds: Vec<(f64, f64)>,
    },
    /// A device (mirror) asked for a li2015 group with a route of lights: the route changes
    /// the density the device holds during the run.
    #[error(
        "group `{group}`: a route of lights changes the insects' density during the run, and a \
         device holds one density; mirror a scenario without a route (or with one light)"
    )]
    LiRouteDevice {
        /// The group.
        group: String,
    },
    /// An empty CSV file.
    #[error("{}:1: empty file, expected the CSV header", path.display())]
    CsvEmpty {
        /// The CSV file.
        path: PathBuf,
    },
    /// A CSV file with another header than a trajectory file's.
    #[error("{}:1: header is {header:?}, expected {expected:?}", path.display())]
    CsvHeader {
        /// The CSV file.
        path: PathBuf,
        /// Its header line.
        header: String,
        /// The header of a trajectory file.
        expected: &'static str,
    },
    /// A CSV row with too few fields.
    #[error(
        "{}:{line}: missing field {field:?} (expected {fields} fields)",
        path.display()
    )]
    CsvMissingField {
        /// The CSV file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// The first missing field.
        field: &'static str,
        /// How many fields a row has.
        fields: usize,
    },
    /// A CSV row with too many fields.
    #[error("{}:{line}: too many fields (expected {fields})", path.display())]
    CsvExtraFields {
        /// The CSV file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// How many fields a row has.
        fields: usize,
    },
    /// A CSV field that is not a number of its type.
    #[error(
        "{}:{line}: field {field:?} is {value:?}, not a valid number",
        path.display()
    )]
    CsvNumber {
        /// The CSV file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// The field.
        field: &'static str,
        /// Its text.
        value: String,
    },
    /// CSV rows not grouped by increasing step.
    #[error(
        "{}:{line}: step {step} after step {previous}: rows must be grouped by increasing step",
        path.display()
    )]
    CsvRowOrder {
        /// The CSV file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// The row's step.
        step: u32,
        /// The step of the rows before.
        previous: u32,
    },
    /// A step of a CSV file with another number of agents than the first step.
    #[error(
        "{}:{line}: step {step} has {agents} agents, the first step has {first}",
        path.display()
    )]
    CsvStepAgents {
        /// The CSV file.
        path: PathBuf,
        /// 1-based line of the step's last row.
        line: usize,
        /// The step.
        step: u32,
        /// Its agents.
        agents: usize,
        /// The first step's agents.
        first: usize,
    },
    /// A CSV row with another agent than the first step has at its position.
    #[error(
        "{}:{line}: agent id {id} at position {position} of step {step}, the first step has id \
         {first} there",
        path.display()
    )]
    CsvAgentId {
        /// The CSV file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// The row's agent id.
        id: u32,
        /// Its position within the step.
        position: usize,
        /// The step.
        step: u32,
        /// The first step's agent id at that position.
        first: u32,
    },
    /// A step of a CSV file with more agents than the first step.
    #[error(
        "{}:{line}: step {step} has more agents than the first step ({first})",
        path.display()
    )]
    CsvExtraAgent {
        /// The CSV file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// The step.
        step: u32,
        /// The first step's agents.
        first: usize,
    },
    /// A file that does not start with the NumPy magic string.
    #[error("{}: not a NumPy .npy file (bad magic)", path.display())]
    NpyMagic {
        /// The file.
        path: PathBuf,
    },
    /// An NPY format version this reader does not know.
    #[error("{}: unsupported NPY version {major}.{minor}", path.display())]
    NpyVersion {
        /// The file.
        path: PathBuf,
        /// Major version.
        major: u8,
        /// Minor version.
        minor: u8,
    },
    /// An NPY file shorter than its header says.
    #[error("{}: truncated header", path.display())]
    NpyTruncated {
        /// The file.
        path: PathBuf,
    },
    /// An NPY header that is not text.
    #[error("{}: header is not text", path.display())]
    NpyHeaderText {
        /// The file.
        path: PathBuf,
    },
    /// An NPY header without a key it must have.
    #[error("{}: header has no '{key}'", path.display())]
    NpyHeaderKey {
        /// The file.
        path: PathBuf,
        /// The key (`descr`, `fortran_order`, `shape`).
        key: &'static str,
    },
    /// An NPY array of another element type than little-endian `f32`.
    #[error(
        "{}: dtype is {dtype:?}, expected '<f4' (little-endian float32)",
        path.display()
    )]
    NpyDtype {
        /// The file.
        path: PathBuf,
        /// Its dtype.
        dtype: String,
    },
    /// An NPY array in Fortran (column-major) order.
    #[error("{}: array is in Fortran order, expected C order", path.display())]
    NpyFortranOrder {
        /// The file.
        path: PathBuf,
    },
    /// An NPY shape that is not a tuple of integers.
    #[error("{}: shape {shape} is not a tuple of integers", path.display())]
    NpyShapeSyntax {
        /// The file.
        path: PathBuf,
        /// The shape as written.
        shape: String,
    },
    /// An NPY array of another shape than `(frames, agents, width)`.
    #[error("{}: shape is {shape}, expected (frames, agents, {width})", path.display())]
    NpyShape {
        /// The file.
        path: PathBuf,
        /// The shape as written.
        shape: String,
        /// The last dimension expected.
        width: usize,
    },
    /// An NPY shape too large to address.
    #[error("{}: shape {shape} is too large", path.display())]
    NpyTooLarge {
        /// The file.
        path: PathBuf,
        /// The shape as written.
        shape: String,
    },
    /// An NPY file whose data is not the size its shape says.
    #[error("{}: holds {bytes} data bytes, shape {shape} needs {needed}", path.display())]
    NpyDataLength {
        /// The file.
        path: PathBuf,
        /// The data bytes it holds.
        bytes: usize,
        /// The shape as written.
        shape: String,
        /// The data bytes the shape needs.
        needed: usize,
    },
}

impl SimError {
    /// A controller's refusal of agent `agent`'s frame in `phase` at `step`.
    pub fn controller(phase: &'static str, step: u32, agent: u32, e: swarm_core::Error) -> Self {
        SimError::Controller {
            phase,
            step,
            agent,
            source: e,
        }
    }

    /// An I/O error on `path`.
    pub fn io(op: &'static str, path: impl Into<PathBuf>, source: io::Error) -> Self {
        SimError::Io {
            op,
            path: path.into(),
            source,
        }
    }

    /// The diagnostic of an [`InvalidScenario`](SimError::InvalidScenario) error.
    pub fn diagnostic(&self) -> Option<&Diagnostic> {
        match self {
            SimError::InvalidScenario(d) => Some(d),
            _ => None,
        }
    }
}
