//! li2015's data pipeline (issue 17, spec §2.5, L-T16): synthetic tracks → `swarm li fit` → a
//! model file → a scenario that uses it, and the synthetic data set shipped in
//! `data/li-synthetic/`.
//!
//! Recovery (L-T16) is measured against the process the synthetic tracks come from (the
//! spec's fixture: segment lengths with mean 14.57 mm and median 7.22 mm, turns |N(2.34°,
//! 40.02°)| with median 27.04°), at the spec's condition: 0.15 m/s, 100 Hz, 0.2 mm noise.
//! docs/models.md has the table over seeds and conditions.

use std::path::{Path, PathBuf};

use swarm_sim::SimError;
use swarm_sim::eval::Tracks;
use swarm_sim::li::fixture::{Fixture, synthetic_tracks};
use swarm_sim::li::model::{Estimate, LiModel};
use swarm_sim::li::{FitOptions, fit, li_params, synthetic_csv};
use swarm_sim::run::{RunOptions, run};
use swarm_sim::scenario::Scenario;

/// The shipped data set's folder.
fn data_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/li-synthetic")
}

/// The process of `data/li-synthetic/tracks.csv` (its README): the fixture's defaults, 20
/// insects × 1,000 samples, seed 1 (`swarm li synth --out tracks.csv`).
fn shipped_process() -> Fixture {
    Fixture {
        insects: 20,
        frames: 1000,
        ..Fixture::default()
    }
}

/// The shipped tracks are exactly what `swarm li synth` writes with the README's parameters.
#[test]
fn the_shipped_tracks_are_what_synth_writes() {
    let shipped = std::fs::read_to_string(data_dir().join("tracks.csv")).expect("shipped tracks");
    let again = synthetic_csv(&shipped_process());
    assert!(
        shipped == again,
        "data/li-synthetic/tracks.csv differs from `swarm li synth --out tracks.csv`: \
         regenerate it (data/li-synthetic/README.md)"
    );
    // A track file the evaluation reads: 20 insects, 1,000 frames each, at 100 Hz.
    let tracks = Tracks::read_csv(&data_dir().join("tracks.csv"), None).unwrap();
    assert_eq!((tracks.by_id.len(), tracks.len()), (20, 20_000));
    assert!((tracks.dt - 0.01).abs() < 1e-9, "{}", tracks.dt);
}

/// The shipped model is what `swarm li fit tracks.csv` writes from the shipped tracks (the
/// same bytes), and it reads back.
#[test]
fn the_shipped_model_is_what_fit_writes() {
    let dir = data_dir();
    let shipped = std::fs::read_to_string(dir.join("model.toml")).expect("shipped model");
    let tracks = Tracks::read_csv(&dir.join("tracks.csv"), None).unwrap();
    let model = fit(&tracks, "tracks.csv", &FitOptions::default()).unwrap();
    assert!(
        shipped == model.to_toml(),
        "data/li-synthetic/model.toml differs from `swarm li fit tracks.csv --out model.toml`: \
         regenerate it (data/li-synthetic/README.md)"
    );
    assert_eq!(LiModel::read(&dir.join("model.toml")).unwrap(), model);
}

/// The median of the process's |turn|, |N(2.34°, 40.02°)| (radians).
const TURN_MEDIAN: f64 = 27.0392 * std::f64::consts::PI / 180.0;

/// The relative error of `got` against `want`.
fn rel(got: f64, want: f64) -> f64 {
    got / want - 1.0
}

/// L-T16: at the spec's condition, on 20 synthetic tracks of 1,000 samples (the shipped data
/// set's size), the default pipeline (indirect inference over the tolerance segmentation)
/// recovers the process's mean segment length within 20 %, its median within 35 % and its
/// median |turn| within 10 %.
///
/// Measured with seeds 1-12 (docs/models.md): mean −7 … +13 %, median −12 … +22 %, |turn|
/// −4 … +3 %; the segments as found (the direct estimate) are off by −13 … −6 %, +7 … +24 %,
/// +1 … +8 %. The median is the least certain: a third of the process's segments are shorter
/// than two samples, and shapes that differ only there make nearly the same tracks (with
/// 10⁵ samples the median still comes out 13-23 % high). Across the other conditions of
/// docs/models.md the indirect estimate keeps |turn| within 10 %, where the direct one is off
/// by up to 49 %.
#[test]
fn the_pipeline_recovers_the_synthetic_process() {
    let seed = swarm_tests::seed(1);
    let f = Fixture {
        seed,
        ..shipped_process()
    };
    let (tracks, _) = synthetic_tracks(&f);
    let model = fit(&tracks, "synthetic", &FitOptions::default()).unwrap();
    let p = &model.provenance;
    assert_eq!(p.estimate, Estimate::Indirect);
    let fitted = p.fitted.expect("an indirect estimate");
    let t = p.tables;
    let (mean, median, turn) = (
        rel(t.length.mean, 0.01457),
        rel(t.length.median, 0.00722),
        rel(t.turn.median, TURN_MEDIAN),
    );
    eprintln!(
        "seed {seed}: mean {:+.1} %, median {:+.1} %, |turn| median {:+.1} % (as segmented: \
         {:+.1} %, {:+.1} %, {:+.1} %); speed {:.4}, noise {:.2e}, cost {:.1}",
        mean * 100.0,
        median * 100.0,
        turn * 100.0,
        rel(p.segmented.length.mean, 0.01457) * 100.0,
        rel(p.segmented.length.median, 0.00722) * 100.0,
        rel(p.segmented.turn.median, TURN_MEDIAN) * 100.0,
        fitted.speed,
        fitted.noise,
        fitted.cost
    );
    assert!(mean.abs() < 0.20, "mean length {:+.1} %", mean * 100.0);
    assert!(
        median.abs() < 0.35,
        "median length {:+.1} %",
        median * 100.0
    );
    assert!(turn.abs() < 0.10, "median |turn| {:+.1} %", turn * 100.0);
    // The flight itself is recovered closely: speed and noise within 3 % (seeds 1-7: 1 %).
    assert!(rel(fitted.speed, 0.15).abs() < 0.03, "{}", fitted.speed);
    assert!(rel(fitted.noise, 0.0002).abs() < 0.03, "{}", fitted.noise);
    // The tables are the fitted process's (binned): their moments within 2 % of its own.
    assert!(rel(t.length.mean, fitted.length.mean).abs() < 0.02);
    assert!(rel(t.length.median, fitted.length.median).abs() < 0.02);
    assert!(rel(t.turn.median, fitted.turn.median).abs() < 0.02);
}

/// `text` written to `dir/name`.
fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// A scenario file in `dir` whose insects use `model` (a path relative to the scenario), in
/// a world `[-1, 2]³` that holds the synthetic tracks' box.
fn scenario_text(model: &str, extra: &str) -> String {
    format!(
        "name = \"li-model\"\nseed = 3\nsteps = 300\n\
         world = {{ dim = 3, min = [-1, -1, -1], max = [2, 2, 2] }}\n\n\
         [outputs]\nevery = 50\n\n\
         [[groups]]\nname = \"midges\"\nmodel = \"li\"\ncount = 30\n\
         spawn = {{ min = [0.2, 0.2, 0.2], max = [0.7, 0.7, 0.7] }}\n\
         li = {{ model = \"{model}\"{extra} }}\n"
    )
}

/// End to end: synth → fit → a scenario file naming the model beside it → `swarm run`. The
/// insects sample the model's tables and its grid is their density, placed as it is.
#[test]
fn a_scenario_runs_on_a_fitted_model() {
    let dir = tempfile::tempdir().unwrap();
    let f = Fixture {
        insects: 8,
        frames: 600,
        seed: 5,
        ..Fixture::default()
    };
    let csv = write(dir.path(), "tracks.csv", &synthetic_csv(&f));
    let tracks = Tracks::read_csv(&csv, None).unwrap();
    let opts = FitOptions {
        cells: 8,
        sim_samples: 20_000,
        ..FitOptions::default()
    };
    let model = fit(&tracks, "tracks.csv", &opts).unwrap();
    std::fs::create_dir(dir.path().join("models")).unwrap();
    let model_path = dir.path().join("models/m.toml");
    model.write(&model_path).unwrap();
    let sc_path = write(
        dir.path(),
        "scenario.toml",
        &scenario_text("models/m.toml", ""),
    );
    let sc = Scenario::from_path(&sc_path).unwrap();
    let params = li_params(&sc, &sc.groups[0]).unwrap();
    assert_eq!(params.lengths, model.lengths.table().unwrap());
    assert_eq!(params.turns, model.turns.table().unwrap());
    assert_eq!(params.density.dims, model.density.dims);
    assert_eq!(params.density.cell, model.density.cell);
    // The file's weights, unvisited cells raised to the floor of 1.
    let floored: Vec<u8> = model.density.weights.iter().map(|&w| w.max(1)).collect();
    assert_eq!(&params.density.weights[..], &floored[..]);
    // The scenario's own density wins over the model's grid; the tables stay the model's.
    let own = write(
        dir.path(),
        "own.toml",
        &scenario_text(
            "models/m.toml",
            ", density = { cells = 4, points = [[0.5, 0.5, 0.5]], sigma = 0.2 }",
        ),
    );
    let sc_own = Scenario::from_path(&own).unwrap();
    let p_own = li_params(&sc_own, &sc_own.groups[0]).unwrap();
    assert_eq!(
        (p_own.density.dims, p_own.lengths),
        ([4, 4, 4], params.lengths.clone())
    );

    let out = dir.path().join("run");
    let opts = RunOptions {
        out: out.clone(),
        steps: None,
        seed: None,
        threads: Some(2),
        backend: None,
        progress: false,
        warnings: Vec::new(),
    };
    let report = run(&sc, &opts).expect("run");
    assert_eq!((report.summary.agents, report.summary.steps), (30, 300));
    assert!(out.join("positions.npy").is_file());
    // Every insect stays in the world and moved.
    let frames = swarm_sim::output::RunDir::open(&out).unwrap().frames;
    let (first, last) = (&frames[0], frames.last().unwrap());
    for (a, b) in first.agents.iter().zip(&last.agents) {
        assert!(
            b.pos.iter().all(|&v| (-1.0..=2.0).contains(&v)),
            "{:?}",
            b.pos
        );
        assert_ne!(a.pos, b.pos);
    }
}

/// A broken model file is refused when the scenario is loaded, naming the scenario's field,
/// the model file, its line and its field; read alone, the error is typed.
#[test]
fn broken_model_files_are_refused_with_file_and_field() {
    let dir = tempfile::tempdir().unwrap();
    let shipped = std::fs::read_to_string(data_dir().join("model.toml")).unwrap();
    // A grid with one weight too few.
    let start = shipped.find("weights = [\n").unwrap() + "weights = [\n".len();
    let end = shipped[start..].find(',').unwrap() + start + 1;
    let broken = format!("{}{}", &shipped[..start], &shipped[end..]);
    let path = write(dir.path(), "broken.toml", &broken);
    match LiModel::read(&path) {
        Err(SimError::LiModelField {
            path: p,
            field,
            line,
            ..
        }) => {
            assert_eq!((p, field.as_str()), (path.clone(), "density.weights"));
            let at = broken
                .lines()
                .position(|l| l.starts_with("weights"))
                .unwrap()
                + 1;
            assert_eq!(line, at);
        }
        other => panic!("{other:?}"),
    }
    let sc_path = write(dir.path(), "sc.toml", &scenario_text("broken.toml", ""));
    let err = Scenario::from_path(&sc_path).unwrap_err();
    let d = err.diagnostic().expect("an invalid scenario");
    assert_eq!(d.field, "groups[0].li.model");
    assert!(
        d.message.contains("broken.toml") && d.message.contains("`density.weights`"),
        "{}",
        d.message
    );
    eprintln!("{err}");

    // A model file that is not one, and one that is missing.
    let path = write(
        dir.path(),
        "other.toml",
        "format = \"swarm-li-model\"\nversion = 9\n",
    );
    let err = LiModel::read(&path).unwrap_err();
    assert!(matches!(err, SimError::LiModelVersion { .. }), "{err}");
    let sc_path = write(dir.path(), "sc2.toml", &scenario_text("missing.toml", ""));
    let err = Scenario::from_path(&sc_path).unwrap_err().to_string();
    assert!(
        err.contains("li.model") && err.contains("missing.toml"),
        "{err}"
    );

    // A grid outside the world: refused before the run, naming the file.
    let model = data_dir().join("model.toml");
    let text = scenario_text(model.to_str().unwrap(), "").replace(
        "min = [-1, -1, -1], max = [2, 2, 2]",
        "min = [0, 0, 0], max = [0.91, 0.91, 0.91]",
    );
    let sc_path = write(dir.path(), "small.toml", &text);
    let err = Scenario::from_path(&sc_path).unwrap_err();
    let d = err.diagnostic().expect("an invalid scenario");
    assert_eq!(d.field, "groups[0].li.model");
    assert!(d.message.contains("outside the world"), "{}", d.message);
}
