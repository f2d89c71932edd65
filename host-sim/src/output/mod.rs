//! Run outputs: what a run leaves in its output folder, and reading it back for `swarm render`.
//!
//! | file               | written by                         | content                                   |
//! |--------------------|------------------------------------|-------------------------------------------|
//! | `trajectories.csv` | [`write_csv`] / [`CsvWriter`]      | `step,id,group,x,y,z,hx,hy,hz,label,motion,roll_deg,pitch_deg` |
//! | `positions.npy`    | [`write_npy`] / [`NpyWriter`]      | `<f4` array `(frames, agents, 3)`          |
//! | `attitude.npy`     | [`write_npy_of`] / [`NpyWriter`]   | 3D (bees) only: `<f4` `(frames, agents, 2)`, roll and pitch in degrees |
//! | `summary.json`     | [`Summary::write`]                 | the run's numbers                          |
//! | `scene.json`       | [`Scene::write`]                   | world bounds and objects to draw           |
//! | `snapshot.png`     | [`render_png`]                     | last frame with fading trails              |
//! | `run.gif`          | [`render_gif`]                     | the run, animated, looping                 |
//! | `run.log`          | [`RunLog`]                         | timestamped lines, flushed as they come    |
//!
//! Every file but the log is written whole or not at all ([`write_atomic`], [`AtomicFile`]): it
//! appears complete under its final name, or not at all. A whole run goes further
//! ([`Staging`]): `swarm run` writes every file into a staging folder beside the output folder
//! and swaps it in when the run is complete, so an output folder always holds exactly one run,
//! never files of two, and a run killed at any moment leaves the previous run as it was.

pub mod atomic;
pub mod csv;
pub mod frames;
mod json;
pub mod npy;
pub mod read;
pub mod render;
pub mod scene;
pub mod stage;
pub mod summary;
#[cfg(test)]
mod testing;

use std::path::Path;

use crate::{Result, SimError};

pub use atomic::{AtomicFile, remove_stale_temps, write_atomic, write_atomic_bytes};
pub use csv::{CSV_HEADER, CSV_HEADER_V1, CsvWriter, read_csv, write_csv};
pub use frames::{AgentSample, Frame, check_frames, label_name};
pub use npy::{
    NpyField, NpyWriter, Positions, npy_header, npy_header_of, read_attitude_npy, read_npy,
    write_npy, write_npy_of,
};
pub use read::{RenderedFiles, RunDir, render_dir, render_dir_with};
pub use render::{ColorBy, RenderOptions, render_gif, render_png};
pub use scene::{Geometry, Scene, Shape, ShapeKind};
pub use stage::{RUN_FILES, Staging, clean_stale, is_run_file_name};
pub use summary::{
    GroupSummary, PairStats, RunLog, StateCounts, Summary, pair_stats, state_counts_of,
};

/// Trajectories as CSV.
pub const TRAJECTORIES_CSV: &str = "trajectories.csv";
/// Positions as NumPy `.npy`.
pub const POSITIONS_NPY: &str = "positions.npy";
/// Roll and pitch (degrees) as NumPy `.npy`.
pub const ATTITUDE_NPY: &str = "attitude.npy";
/// The run summary.
pub const SUMMARY_JSON: &str = "summary.json";
/// The scene to draw.
pub const SCENE_JSON: &str = "scene.json";
/// The run log.
pub const RUN_LOG: &str = "run.log";
/// The PNG snapshot.
pub const SNAPSHOT_PNG: &str = "snapshot.png";
/// The animated GIF.
pub const RUN_GIF: &str = "run.gif";

/// Writes the data files of a run into `dir` (created if missing): `scene.json`,
/// `trajectories.csv`, `positions.npy`, `attitude.npy` (3D scenes: bees; ants are level) and
/// `summary.json`, each whole or not at all. Pictures are
/// made separately by [`render_dir`] (or [`render_png`] / [`render_gif`]).
pub fn write_run(
    dir: impl AsRef<Path>,
    scene: &Scene,
    frames: &[Frame],
    summary: &Summary,
) -> Result<()> {
    let dir = dir.as_ref();
    std::fs::create_dir_all(dir).map_err(|e| SimError::io("creating folder", dir, e))?;
    check_frames(frames, &dir.join(TRAJECTORIES_CSV))?;
    scene.write(dir.join(SCENE_JSON))?;
    write_csv(dir.join(TRAJECTORIES_CSV), frames)?;
    write_npy(dir.join(POSITIONS_NPY), frames)?;
    if scene.dim == 3 {
        write_npy_of(dir.join(ATTITUDE_NPY), frames, NpyField::Attitude)?;
    }
    summary.write(dir.join(SUMMARY_JSON))
}
