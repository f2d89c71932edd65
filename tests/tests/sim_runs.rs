//! Whole runs through the public API: a built-in scenario runs, writes every output, and its
//! trajectories are bit-identical whatever the thread count.

use std::path::Path;

use swarm_sim::run::{RunOptions, run};
use swarm_sim::scenario;

fn run_fig7a(out: &Path, threads: usize) -> swarm_sim::output::Summary {
    let sc = scenario::builtin("ants-fig7a-single-colony").expect("built-in");
    let opts = RunOptions {
        out: out.to_path_buf(),
        steps: Some(600),
        seed: None,
        threads: Some(threads),
        backend: None,
        progress: false,
        warnings: Vec::new(),
    };
    run(&sc, &opts).expect("run").summary
}

#[test]
fn trajectories_are_bit_identical_at_1_and_2_threads_and_every_output_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("t1"), dir.path().join("t2"));
    let s1 = run_fig7a(&a, 1);
    let s2 = run_fig7a(&b, 2);
    let csv = |d: &Path| std::fs::read(d.join("trajectories.csv")).unwrap();
    assert_eq!(
        csv(&a),
        csv(&b),
        "trajectories differ between 1 and 2 threads"
    );
    assert_eq!(s1.deliveries_per_nest, s2.deliveries_per_nest);
    for f in [
        "scene.json",
        "trajectories.csv",
        "positions.npy",
        "summary.json",
        "snapshot.png",
        "run.gif",
        "run.log",
    ] {
        assert!(a.join(f).is_file(), "{f} missing");
    }
    // No temporary files left behind.
    for e in std::fs::read_dir(&a).unwrap() {
        let name = e.unwrap().file_name().into_string().unwrap();
        assert!(!name.ends_with(".tmp"), "leftover {name}");
    }
    // The folder renders again.
    swarm_sim::output::render_dir(&a).expect("render");
}

#[test]
fn a_bad_scenario_file_is_refused_with_file_line_and_field() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.toml");
    let text = scenario::builtin("ants-fig7a-single-colony")
        .unwrap()
        .to_toml()
        .unwrap()
        .replacen("count = 500", "count = 0", 1);
    std::fs::write(&path, text).unwrap();
    let err = scenario::resolve(path.to_str().unwrap())
        .unwrap_err()
        .to_string();
    assert!(err.contains("bad.toml:") && err.contains("count"), "{err}");
}
