//! Reading a run folder back (for `swarm render <out-dir>`).

use std::path::{Path, PathBuf};

use super::atomic::remove_stale_temps;
use super::csv::read_csv;
use super::frames::Frame;
use super::npy::{read_attitude_npy, read_npy};
use super::render::{RenderOptions, render_gif, render_png};
use super::scene::Scene;
use super::summary::Summary;
use super::{
    ATTITUDE_NPY, POSITIONS_NPY, RUN_GIF, SCENE_JSON, SNAPSHOT_PNG, SUMMARY_JSON, TRAJECTORIES_CSV,
};
use crate::{Result, SimError};

/// Where the trajectories of a [`RunDir`] came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TrajectorySource {
    /// `trajectories.csv`: everything recorded.
    Csv,
    /// `positions.npy` (the CSV was absent): positions, and roll and pitch from
    /// `attitude.npy` when it is there and matches; steps are the frame indices and headings,
    /// groups, labels and motion states are zero.
    Npy,
}

/// A run's output folder, read back.
#[derive(Clone, Debug)]
pub struct RunDir {
    /// The folder.
    pub dir: PathBuf,
    /// `scene.json`.
    pub scene: Scene,
    /// The recorded frames.
    pub frames: Vec<Frame>,
    /// Which file the frames came from.
    pub source: TrajectorySource,
    /// `summary.json`, if the folder has one (a malformed one is an error).
    pub summary: Option<Summary>,
}

impl RunDir {
    /// Reads `scene.json`, the trajectories (`trajectories.csv`, or `positions.npy` if the CSV
    /// is absent) and `summary.json` (optional) from `dir`. Errors name the folder and the
    /// missing or malformed file.
    pub fn open(dir: impl AsRef<Path>) -> Result<Self> {
        let dir = dir.as_ref();
        let meta =
            std::fs::metadata(dir).map_err(|e| SimError::io("opening run folder", dir, e))?;
        if !meta.is_dir() {
            return Err(SimError::io(
                "opening run folder",
                dir,
                std::io::Error::other("not a folder"),
            ));
        }
        let scene_path = dir.join(SCENE_JSON);
        if !scene_path.exists() {
            return Err(SimError::MissingRunFile {
                dir: dir.to_path_buf(),
                file: SCENE_JSON.into(),
                hint: "it holds the world bounds and objects to draw; `swarm run` writes it",
            });
        }
        let scene = Scene::read(&scene_path)?;
        let csv = dir.join(TRAJECTORIES_CSV);
        let npy = dir.join(POSITIONS_NPY);
        let (frames, source) = if csv.exists() {
            (read_csv(&csv)?, TrajectorySource::Csv)
        } else if npy.exists() {
            let mut frames = read_npy(&npy)?.to_frames();
            let attitude = dir.join(ATTITUDE_NPY);
            if attitude.exists() {
                let a = read_attitude_npy(&attitude)?;
                if (a.frames, a.agents)
                    != (frames.len(), frames.first().map_or(0, |f| f.agents.len()))
                {
                    return Err(SimError::AttitudeShape {
                        path: attitude,
                        frames: a.frames,
                        agents: a.agents,
                    });
                }
                for (fi, f) in frames.iter_mut().enumerate() {
                    for (ai, s) in f.agents.iter_mut().enumerate() {
                        let i = (fi * a.agents + ai) * 2;
                        (s.roll, s.pitch) = (a.data[i], a.data[i + 1]);
                    }
                }
            }
            (frames, TrajectorySource::Npy)
        } else {
            return Err(SimError::MissingRunFile {
                dir: dir.to_path_buf(),
                file: format!("{TRAJECTORIES_CSV} or {POSITIONS_NPY}"),
                hint: "the recorded agent positions to draw",
            });
        };
        let summary_path = dir.join(SUMMARY_JSON);
        let summary = if summary_path.exists() {
            Some(Summary::read(&summary_path)?)
        } else {
            None
        };
        Ok(Self {
            dir: dir.to_path_buf(),
            scene,
            frames,
            source,
            summary,
        })
    }

    /// Writes `snapshot.png` and `run.gif` into the folder, each whole or not at all (the
    /// temporary files an earlier, killed render left are removed first).
    pub fn render(&self, opts: &RenderOptions) -> Result<RenderedFiles> {
        let files = RenderedFiles {
            png: self.dir.join(SNAPSHOT_PNG),
            gif: self.dir.join(RUN_GIF),
        };
        remove_stale_temps(&files.png);
        remove_stale_temps(&files.gif);
        render_png(&self.scene, &self.frames, &files.png, opts)?;
        render_gif(&self.scene, &self.frames, &files.gif, opts)?;
        Ok(files)
    }
}

/// The pictures [`render_dir`] wrote.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RenderedFiles {
    /// `snapshot.png`.
    pub png: PathBuf,
    /// `run.gif`.
    pub gif: PathBuf,
}

/// Reads the run folder `dir` and writes `snapshot.png` and `run.gif` into it (default options).
pub fn render_dir(dir: impl AsRef<Path>) -> Result<RenderedFiles> {
    render_dir_with(dir, &RenderOptions::default())
}

/// [`render_dir`] with explicit options.
pub fn render_dir_with(dir: impl AsRef<Path>, opts: &RenderOptions) -> Result<RenderedFiles> {
    RunDir::open(dir)?.render(opts)
}

#[cfg(test)]
mod tests {
    use super::super::frames::AgentSample;
    use super::super::scene::{Shape, ShapeKind};
    use super::super::write_run;
    use super::*;
    use crate::output::testing::temp_path;

    fn run(dir: &Path) -> (Scene, Vec<Frame>, Summary) {
        let mut scene = Scene::new_2d([-50.0, -50.0], [50.0, 50.0]);
        scene
            .shapes
            .push(Shape::circle([0.0, 0.0, 0.0], 5.0, ShapeKind::Nest));
        let frames: Vec<Frame> = (0..12)
            .map(|f| Frame {
                step: f * 10,
                agents: (0..40)
                    .map(|i| {
                        let a = i as f32 * 0.3 + f as f32 * 0.1;
                        AgentSample {
                            id: i,
                            pos: [30.0 * a.cos(), 30.0 * a.sin(), 0.0],
                            heading: [-a.sin(), a.cos(), 0.0],
                            label: (i % 3) as u8,
                            ..Default::default()
                        }
                    })
                    .collect(),
            })
            .collect();
        let summary = Summary {
            scenario: "test".into(),
            steps: 110,
            agents: 40,
            ..Default::default()
        };
        write_run(dir, &scene, &frames, &summary).unwrap();
        (scene, frames, summary)
    }

    #[test]
    fn write_open_render() {
        let (_dir, out) = temp_path("out");
        let (scene, frames, summary) = run(&out);
        let rd = RunDir::open(&out).unwrap();
        assert_eq!(rd.scene, scene);
        assert_eq!(rd.frames, frames);
        assert_eq!(rd.source, TrajectorySource::Csv);
        assert_eq!(rd.summary.as_ref(), Some(&summary));
        let files = render_dir(&out).unwrap();
        assert!(image::open(&files.png).is_ok());
        assert!(
            gif::DecodeOptions::new()
                .read_info(std::fs::File::open(&files.gif).unwrap())
                .is_ok()
        );
        let mut names: Vec<String> = std::fs::read_dir(&out)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        assert_eq!(
            names,
            [
                "positions.npy",
                "run.gif",
                "scene.json",
                "snapshot.png",
                "summary.json",
                "trajectories.csv"
            ]
        );
    }

    #[test]
    fn falls_back_to_npy_and_names_missing_files() {
        let (dir, out) = temp_path("out");
        let (_, frames, _) = run(&out);
        std::fs::remove_file(out.join(TRAJECTORIES_CSV)).unwrap();
        std::fs::remove_file(out.join(SUMMARY_JSON)).unwrap();
        let rd = RunDir::open(&out).unwrap();
        assert_eq!(rd.source, TrajectorySource::Npy);
        assert!(rd.summary.is_none());
        assert_eq!(rd.frames.len(), frames.len());
        assert_eq!(rd.frames[3].agents[7].pos, frames[3].agents[7].pos);
        render_dir(&out).unwrap();

        std::fs::remove_file(out.join(POSITIONS_NPY)).unwrap();
        let msg = RunDir::open(&out).unwrap_err().to_string();
        assert!(msg.contains("trajectories.csv or positions.npy"), "{msg}");
        std::fs::remove_file(out.join(SCENE_JSON)).unwrap();
        let msg = RunDir::open(&out).unwrap_err().to_string();
        assert!(msg.contains("scene.json") && msg.contains("out"), "{msg}");
        let msg = RunDir::open(dir.path().join("nope"))
            .unwrap_err()
            .to_string();
        assert!(msg.contains("nope"), "{msg}");
    }
}
