//! The `swarm` command line: bad input is refused before anything is written, warnings are
//! shown and logged, and an output folder holds exactly one run.

mod common;

use common::{entries, fails, identify, leftovers, ok, run_cmd, swarm};

const SCENARIO: &str = "ants-fig7a-single-colony";
const STEPS_ZERO: &str = "expected at least 1 step, found 0";

/// A small ant scenario; `{nest}` and `{food}` are the centres of its nest and food source,
/// next to a rock of radius 10 at [60, 50].
fn scenario(nest: &str, food: &str) -> String {
    format!(
        r#"steps = 20
world = {{ dim = 2, min = [0, 0], max = [200, 100] }}

[[groups]]
name = "colony"
model = "ant"
count = 10
nest = "nest"
spawn = {{ at = "nest", radius = 2 }}

[[objects]]
name = "nest"
kind = "nest"
center = {nest}
radius = 3

[[objects]]
name = "food"
kind = "food"
center = {food}
radius = 3

[[objects]]
name = "boulder"
kind = "rock"
center = [60, 50]
radius = 10
"#
    )
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
        scenario("[20, 50]", "[180, 50]").replace("steps = 20", "steps = 0"),
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
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("buried.toml");
    std::fs::write(&file, scenario("[20, 50]", "[58, 52]")).unwrap();
    let out = dir.path().join("out");
    let err = fails(&mut run_cmd(file.to_str().unwrap(), &out, &[]));
    assert!(
        err.contains("buried.toml:20:")
            && err.contains("`objects[1].center`")
            && err.contains("`food`")
            && err.contains("`boulder`"),
        "{err}"
    );
    assert!(!out.exists());
}

#[test]
fn warnings_are_printed_and_logged_and_the_run_goes_on() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("close.toml");
    std::fs::write(&file, scenario("[52, 50]", "[180, 50]")).unwrap();
    let out = dir.path().join("out");
    let o = ok(&mut run_cmd(file.to_str().unwrap(), &out, &[]));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("close.toml:14:10: warning in `objects[0].center`")
            && err.contains("`boulder`"),
        "{err}"
    );
    let log = std::fs::read_to_string(out.join("run.log")).unwrap();
    assert!(log.contains("warning in `objects[0].center`"), "{log}");
    assert!(log.contains("warning in `groups[0].spawn`"), "{log}");
}

#[test]
fn a_rerun_replaces_the_whole_folder_and_render_redraws_it() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("run");
    ok(&mut run_cmd(
        SCENARIO,
        &out,
        &["--steps", "30", "--seed", "1"],
    ));
    // A file a second run does not write disappears with the first run; stale temporary
    // files of a killed render go too.
    std::fs::write(out.join(".run.gif.Ab12Cd.tmp"), "stale").unwrap();
    ok(&mut run_cmd(
        SCENARIO,
        &out,
        &["--steps", "20", "--seed", "2"],
    ));
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
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("run");
    ok(&mut run_cmd(
        SCENARIO,
        &out,
        &["--steps", "30", "--seed", "1"],
    ));
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
    ok(&mut run_cmd(
        SCENARIO,
        &out,
        &["--steps", "20", "--seed", "4"],
    ));
    assert_eq!(leftovers(dir.path()), Vec::<String>::new());
}
