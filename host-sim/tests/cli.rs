//! The `swarm` command line: bad input is refused before anything is written, warnings are
//! shown and logged, and an output folder holds exactly one run.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use tempfile::TempDir;

use common::{entries, fails, identify, leftovers, ok, run_cmd, swarm};

const SCENARIO: &str = "ants-fig7a-single-colony";
const STEPS_ZERO: &str = "expected at least 1 step, found 0";

/// The ant world of the scenario sanity tests (a nest at [20, 50], food at [180, 50], a rock
/// of radius 10 at [60, 50] and a concave polygon) with its nest and food moved to `nest` and
/// `food`.
fn scenario(nest: &str, food: &str) -> String {
    include_str!("../src/scenario/tests/ant_world.toml")
        .replacen("center = [20, 50]", &format!("center = {nest}"), 1)
        .replacen("center = [180, 50]", &format!("center = {food}"), 1)
}

/// Writes [`scenario`] with its nest and food at `nest` and `food` to the file `name` of a new
/// temporary folder: the folder and the command that runs the file into its `out`.
fn scenario_run(name: &str, nest: &str, food: &str) -> (TempDir, Command) {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join(name);
    std::fs::write(&file, scenario(nest, food)).unwrap();
    let run = run_cmd(file.to_str().unwrap(), &dir.path().join("out"), &[]);
    (dir, run)
}

/// Runs the built-in [`SCENARIO`] for `steps` steps with `seed` into `out`; it succeeds.
fn run_ok(out: &Path, steps: u32, seed: u32) -> Output {
    let (steps, seed) = (steps.to_string(), seed.to_string());
    ok(&mut run_cmd(
        SCENARIO,
        out,
        &["--steps", &steps, "--seed", &seed],
    ))
}

/// A new temporary folder with a run of 30 steps (seed 1) in its `run`: the folder and the
/// run's path.
fn first_run() -> (TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("run");
    run_ok(&out, 30, 1);
    (dir, out)
}

#[test]
fn steps_zero_is_refused_like_steps_zero_in_a_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out/x");
    let err = fails(&mut run_cmd(SCENARIO, &out, &["--steps", "0"]));
    assert!(err.contains(STEPS_ZERO) && err.contains("--steps"), "{err}");
    assert!(!dir.path().join("out").exists(), "nothing is written");
    let file = dir.path().join("zero.toml");
    std::fs::write(
        &file,
        scenario("[20, 50]", "[180, 50]").replace("steps = 100", "steps = 0"),
    )
    .unwrap();
    let err = fails(&mut run_cmd(file.to_str().unwrap(), &out, &[]));
    assert!(
        err.contains(STEPS_ZERO) && err.contains("zero.toml:1:"),
        "{err}"
    );
    let err = fails(swarm().args(["bench", "--model", "ants", "--agents", "10", "--steps", "0"]));
    assert!(err.contains(STEPS_ZERO) && err.contains("--steps"), "{err}");
    assert!(!dir.path().join("out").exists());
}

#[test]
fn food_inside_an_obstacle_is_refused_before_anything_is_written() {
    let (dir, mut run) = scenario_run("buried.toml", "[20, 50]", "[58, 52]");
    let err = fails(&mut run);
    assert!(
        err.contains("buried.toml:20:")
            && err.contains("`objects[1].center`")
            && err.contains("`food`")
            && err.contains("`boulder`"),
        "{err}"
    );
    assert!(!dir.path().join("out").exists());
}

#[test]
fn warnings_are_printed_and_logged_and_the_run_goes_on() {
    let (dir, mut run) = scenario_run("close.toml", "[52, 50]", "[180, 50]");
    let o = ok(&mut run);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("close.toml:14:10: warning in `objects[0].center`")
            && err.contains("`boulder`"),
        "{err}"
    );
    let log = std::fs::read_to_string(dir.path().join("out/run.log")).unwrap();
    assert!(log.contains("warning in `objects[0].center`"), "{log}");
    assert!(log.contains("warning in `groups[0].spawn`"), "{log}");
}

#[test]
fn a_rerun_replaces_the_whole_folder_and_render_redraws_it() {
    let (dir, out) = first_run();
    // A file a second run does not write disappears with the first run; stale temporary
    // files of a killed render go too.
    std::fs::write(out.join(".run.gif.Ab12Cd.tmp"), "stale").unwrap();
    run_ok(&out, 20, 2);
    assert_eq!(identify(&out).map(|r| (r.seed, r.steps)), Ok((2, 20)));
    std::fs::write(out.join(".snapshot.png.Xy34Zw.tmp"), "stale").unwrap();
    let o = ok(swarm().arg("render").arg(&out));
    assert!(String::from_utf8_lossy(&o.stdout).contains("snapshot.png"));
    assert_eq!(identify(&out).map(|r| r.seed), Ok(2));
    assert_eq!(leftovers(dir.path()), Vec::<String>::new());
}

#[test]
fn a_folder_with_files_no_run_writes_is_refused_and_left_alone() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("mine");
    std::fs::create_dir(&out).unwrap();
    std::fs::write(out.join("thesis.tex"), "precious").unwrap();
    let err = fails(&mut run_cmd(SCENARIO, &out, &["--steps", "5"]));
    assert!(err.contains("thesis.tex") && err.contains("--out"), "{err}");
    assert_eq!(entries(&out), vec!["thesis.tex"]);
    assert_eq!(entries(dir.path()), vec!["mine"]);
}

/// A write error (here EFBIG from a file-size limit, which fails like a full disk) leaves the
/// old run untouched, says so, and keeps the failed run's log with the error at its end.
#[cfg(unix)]
#[test]
fn a_failed_write_leaves_the_old_run_and_records_the_error() {
    let (dir, out) = first_run();
    let before = identify(&out).unwrap();
    // `trap '' XFSZ`: the write fails with EFBIG instead of the signal killing the process.
    let o = std::process::Command::new("sh")
        .arg("-c")
        .arg("trap '' XFSZ; ulimit -f 64; exec \"$@\"")
        .arg("sh")
        .arg(env!("CARGO_BIN_EXE_swarm"))
        .args([
            "run", SCENARIO, "--quiet", "--steps", "300", "--seed", "3", "--out",
        ])
        .arg(&out)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{err}");
    assert!(
        err.contains("was left untouched") && err.contains("failed run's log"),
        "{err}"
    );
    assert_eq!(identify(&out), Ok(before));
    let log_path = err
        .split("failed run's log is ")
        .nth(1)
        .map(str::trim)
        .expect("the log's path");
    let log = std::fs::read_to_string(log_path).unwrap();
    let last = log.lines().last().unwrap_or_default();
    assert!(
        last.contains("error:") && last.contains("File too large"),
        "{log}"
    );
    // The next run removes the failed run's folder.
    run_ok(&out, 20, 4);
    assert_eq!(leftovers(dir.path()), Vec::<String>::new());
}

/// `--backend gpu`: a run on the GPU prints its adapter and writes the run (lavapipe in CI);
/// with no adapter (no API wgpu may use) it fails naming what to install, and writes nothing;
/// `swarm bench --backend gpu` reports the
/// adapter, the passes and the device memory.
#[test]
fn the_gpu_backend_names_its_adapter_and_what_to_install_without_one() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("gpu");
    let o = ok(&mut run_cmd(
        SCENARIO,
        &out,
        &["--steps", "5", "--backend", "gpu"],
    ));
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("on the GPU: "), "{text}");
    let log = std::fs::read_to_string(out.join("run.log")).unwrap();
    assert!(log.contains("backend gpu: "), "{log}");

    let none = dir.path().join("none");
    let mut cmd = run_cmd(SCENARIO, &none, &["--steps", "5", "--backend", "gpu"]);
    // An API with no driver on this machine: wgpu finds no adapter.
    cmd.env(
        "WGPU_BACKEND",
        if cfg!(target_os = "linux") {
            "dx12"
        } else {
            "gl"
        },
    );
    let err = fails(&mut cmd);
    assert!(
        err.contains("no GPU adapter") && err.contains("mesa-vulkan-drivers"),
        "{err}"
    );
    assert!(!none.exists(), "nothing is written");

    let o = ok(swarm()
        .args([
            "bench", "--model", "ant", "--agents", "2000", "--steps", "2",
        ])
        .args(["--backend", "gpu", "--scalar", "fixed"]));
    let report: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(report["backend"], "gpu");
    assert!(report["adapter"].is_string(), "{report}");
    assert!(
        report["device_bytes_per_agent"].as_f64().unwrap() > 100.0,
        "{report}"
    );
    assert_eq!(report["scalar"], "I16F16");
}

/// `swarm eval` scores run folders and track files against a reference, writes its JSON,
/// and names the line and field of a bad track file.
#[test]
fn eval_scores_runs_and_track_files() {
    let dir = tempfile::tempdir().unwrap();
    let runs: Vec<PathBuf> = (1..=2)
        .map(|seed| {
            let out = dir.path().join(format!("run{seed}"));
            common::ok(&mut common::run_cmd(
                "wang-fig10-phototaxis",
                &out,
                &["--steps", "60", "--seed", &seed.to_string()],
            ));
            out
        })
        .collect();
    // A track file: three insects on straight lines, 0.1 s apart.
    let tracks = dir.path().join("tracks.csv");
    let mut text = String::from("id,time,x,y,z\n");
    for id in 0..3 {
        for k in 0..40 {
            text += &format!("{id},{},{},{id},1\n", k as f64 * 0.1, k as f64 * 0.05);
        }
    }
    std::fs::write(&tracks, text).unwrap();
    let json = dir.path().join("eval.json");
    let out = common::ok(
        common::swarm()
            .arg("eval")
            .arg(&runs[0])
            .arg(&runs[1])
            .arg(&tracks)
            .arg("--json")
            .arg(&json),
    );
    let table = String::from_utf8_lossy(&out.stdout);
    assert!(
        table.contains("score") && table.contains("tracks.csv"),
        "{table}"
    );
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let rows = report["candidates"].as_array().unwrap();
    assert_eq!(rows.len(), 2);
    // The same model with another seed is closer to the reference than straight lines.
    let score = |k: usize| rows[k]["score"].as_f64().unwrap();
    assert!(score(0) > score(1), "{report}");
    let weights: f64 = report["weights"]
        .as_object()
        .unwrap()
        .values()
        .map(|v| v.as_f64().unwrap())
        .sum();
    assert!((weights - 1.0).abs() < 1e-9);
    assert_eq!(report["scaling"], "separate");
    // li2015's measures: the run of another seed spreads like the reference, the straight
    // lines (0.05 units/s at x ≤ 2, far from the insects) share almost no cell with it.
    let tv = |k: usize| rows[k]["density_tv"].as_f64().unwrap();
    assert!(tv(0) < tv(1) && tv(1) > 0.9, "{report}");
    let centroid = |k: usize| rows[k]["centroid_distance"].as_f64().unwrap();
    assert!(report["reference_centroid_distance"].as_f64().unwrap() > 0.0);
    // Every frame of the track file: y = 0, 1, 2 about y = 1.
    assert!((centroid(1) - 2.0 / 3.0).abs() < 1e-9, "{report}");
    assert!(table.contains("densTV"), "{table}");
    // With the reference's moments (`--scaling reference`) the energies change and the ranking
    // holds.
    let again = dir.path().join("eval-reference.json");
    common::ok(
        common::swarm()
            .args(["eval", "--scaling", "reference", "--json"])
            .arg(&again)
            .arg(&runs[0])
            .arg(&runs[1])
            .arg(&tracks),
    );
    let scaled: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&again).unwrap()).unwrap();
    assert_eq!(scaled["scaling"], "reference");
    let rows2 = scaled["candidates"].as_array().unwrap();
    assert!(
        rows2[0]["score"].as_f64() > rows2[1]["score"].as_f64(),
        "{scaled}"
    );
    assert_ne!(rows2[1]["energies"], rows[1]["energies"]);
    std::fs::write(&tracks, "id,time,x,y,z\n0,0,0,0,0\n0,0.1,0,oops,0\n").unwrap();
    let err = common::fails(common::swarm().arg("eval").arg(&tracks).arg(&runs[0]));
    assert!(
        err.contains("tracks.csv:3") && err.contains("\"y\""),
        "{err}"
    );
}

/// `swarm fit` fits a scenario's parameter to a run of it, writes the fitted scenario (which
/// loads) and its JSON report, and refuses a bad `--param` or a parameter the model lacks
/// before running anything.
#[test]
fn fit_writes_a_scenario_that_loads() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = dir.path().join("midges.toml");
    std::fs::write(
        &scenario,
        "name = \"small-midges\"\nseed = 4\nsteps = 40\n\
         world = { dim = 3, min = [0, 0, 0], max = [20, 20, 20] }\n\
         [outputs]\nevery = 1\n\
         [[groups]]\nname = \"midges\"\nmodel = \"fly\"\ncount = 10\n\
         spawn = { min = [6, 6, 6], max = [14, 14, 14] }\nfly = { preset = \"midge\" }\n",
    )
    .unwrap();
    let reference = dir.path().join("reference");
    ok(&mut run_cmd(scenario.to_str().unwrap(), &reference, &[]));
    let (fitted, json) = (dir.path().join("fitted.toml"), dir.path().join("fit.json"));
    let out = ok(swarm()
        .arg("fit")
        .arg(&scenario)
        .arg(&reference)
        .args(["--dt", "0.01", "--burn-in", "0", "--frames", "30"])
        .args(["--generations", "3", "--population", "4"])
        .args(["--param", "gamma=2:20:log", "--param", "chi_att=5:20"])
        .args(["--param", "gain"]) // the model's whole range, [0, 64]
        .arg("--out")
        .arg(&fitted)
        .arg("--json")
        .arg(&json));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("gamma = ") && text.contains("chi_att = "),
        "{text}"
    );
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(report["history"].as_array().unwrap().len(), 3);
    assert_eq!(report["evaluations"], 4 + 2 * 3);
    let gamma = report["values"]["gamma"].as_f64().unwrap();
    assert!((2.0..=20.0).contains(&gamma), "{report}");
    let gain = report["values"]["gain"].as_f64().unwrap();
    assert!((0.0..=64.0).contains(&gain), "{report}");
    let sc = swarm_sim::scenario::Scenario::from_path(&fitted).unwrap();
    let p = swarm_sim::fly::fly_params(&sc.groups[0]).unwrap();
    assert!((f64::from(p.gamma) - gamma).abs() < 1e-4 * gamma, "{p:?}");
    for (param, says) in [
        ("gamma=2", "expected a range"),
        ("orca_neighbours", "an integer parameter"),
        ("gamma=0:500", "leaves the model's range"),
        ("gamma_typo=1:2", "gamma_typo"),
    ] {
        let err = fails(
            swarm()
                .arg("fit")
                .arg(&scenario)
                .arg(&reference)
                .args(["--param", param, "--dt", "0.01"]),
        );
        assert!(err.contains(says), "{param}: {err}");
    }
    let err = fails(swarm().arg("fit").arg(&scenario).arg(&reference).args([
        "--param",
        "gamma",
        "--param",
        "gamma=1:2",
        "--dt",
        "0.01",
    ]));
    assert!(
        err.contains("gamma") && err.contains("named more than once"),
        "{err}"
    );
}

/// `swarm fly temperature` writes a resized scenario that loads, with the density it reports
/// within the tolerance of N(T), and refuses a temperature without swarms and a world too small
/// before it runs anything.
#[test]
fn fly_temperature_writes_a_resized_scenario() {
    let dir = tempfile::tempdir().unwrap();
    let (resized, json) = (dir.path().join("warm.toml"), dir.path().join("t.json"));
    let base = [
        "fly",
        "temperature",
        "fly-fig2-fruitfly",
        "--burn-in",
        "300",
        "--frames",
        "5",
        "--runs",
        "1",
    ];
    ok(swarm()
        .args(base)
        .args(["--celsius", "25", "--metres-per-unit", "0.5", "--quiet"])
        .arg("--out")
        .arg(&resized)
        .arg("--json")
        .arg(&json));
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let (target, density) = (
        report["target"].as_f64().unwrap(),
        report["density"].as_f64().unwrap(),
    );
    assert!((density / target - 1.0).abs() <= 0.05, "{report}");
    let k = report["scale"].as_f64().unwrap();
    let sc = swarm_sim::scenario::Scenario::from_path(&resized).unwrap();
    let p = swarm_sim::fly::fly_params(&sc.groups[0]).unwrap();
    let r_rep = f64::from(swarm_core::fly::FlyParams::<f32>::fruitfly().r_rep);
    assert!(
        (f64::from(p.r_rep) / r_rep - k).abs() < 1e-4 * k,
        "{p:?} k {k}"
    );
    for (celsius, metres, says) in [
        ("40", "0.5", "no swarm"),
        ("20", "0.01", "more than the world's"),
    ] {
        let err =
            fails(
                swarm()
                    .args(base)
                    .args(["--celsius", celsius, "--metres-per-unit", metres]),
            );
        assert!(err.contains(says), "{celsius} °C: {err}");
    }
}

/// `swarm models NAME` prints the model's parameter table; an unknown name lists the known.
#[test]
fn models_lists_a_models_parameters() {
    let out = ok(swarm().args(["models", "fly"]));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.starts_with("fly (3D)"), "{text}");
    let gamma = text
        .lines()
        .find(|l| l.trim_start().starts_with("gamma"))
        .unwrap();
    assert!(gamma.contains("a number in [0, 100] (1/unit)"), "{gamma}");
    assert!(text.contains("orca_neighbours") && text.contains("an integer from 0 to 64"));
    let err = fails(swarm().args(["models", "wasp"]));
    assert!(err.contains("wasp") && err.contains("fly"), "{err}");
}
