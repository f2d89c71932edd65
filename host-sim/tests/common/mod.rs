//! Helpers of the tests that run the `swarm` binary.

#![allow(dead_code)]

use std::path::Path;
use std::process::{Command, Output};

use swarm_sim::output::{ATTITUDE_NPY, RUN_FILES, read_npy};

/// The `swarm` binary of this build.
pub fn swarm() -> Command {
    Command::new(env!("CARGO_BIN_EXE_swarm"))
}

/// `swarm run <scenario> --quiet --threads 1 --out <out> <extra...>`.
pub fn run_cmd(scenario: &str, out: &Path, extra: &[&str]) -> Command {
    let mut c = swarm();
    c.args(["run", scenario, "--quiet", "--threads", "1", "--out"])
        .arg(out)
        .args(extra);
    c
}

/// Runs `cmd` to the end; panics with its output unless it succeeded.
#[track_caller]
pub fn ok(cmd: &mut Command) -> Output {
    let out = cmd.output().expect("start swarm");
    assert!(
        out.status.success(),
        "swarm failed: {}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// Runs `cmd` to the end, expects it to fail, returns its stderr.
#[track_caller]
pub fn fails(cmd: &mut Command) -> String {
    let out = cmd.output().expect("start swarm");
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!out.status.success(), "swarm should have failed:\n{err}");
    err
}

/// The sorted names in `dir`.
pub fn entries(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// Which run a folder holds, checked across all of its files: (seed, steps).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RunId {
    pub seed: u64,
    pub steps: u64,
}

/// Reads the run folder `dir` and checks that every file belongs to the same complete run
/// (exactly the files of a run, the summary's seed and steps in the log's first line, the
/// summary's recorded frames and agents in `positions.npy` and `trajectories.csv`, whole
/// pictures); returns that run, or what does not fit.
pub fn identify(dir: &Path) -> Result<RunId, String> {
    if !dir.is_dir() {
        return Err(format!("no folder {}", dir.display()));
    }
    let have = entries(dir);
    // Every run file; `attitude.npy` only for 3D (bee) runs.
    let mut want: Vec<String> = RUN_FILES
        .iter()
        .filter(|&&f| f != ATTITUDE_NPY || have.iter().any(|h| h == ATTITUDE_NPY))
        .map(|s| s.to_string())
        .collect();
    want.sort();
    if have != want {
        return Err(format!("files {have:?}, expected {want:?}"));
    }
    let read = |f: &str| std::fs::read(dir.join(f)).map_err(|e| format!("{f}: {e}"));
    let summary: serde_json::Value =
        serde_json::from_slice(&read("summary.json")?).map_err(|e| format!("summary.json: {e}"))?;
    let num = |k: &str| {
        summary[k]
            .as_u64()
            .ok_or_else(|| format!("summary.json: no {k}"))
    };
    let (seed, steps, agents) = (num("seed")?, num("steps")?, num("agents")?);
    let frames = summary["state_counts"]
        .as_array()
        .map(Vec::len)
        .ok_or("summary.json: no state_counts")?;
    let log = String::from_utf8(read("run.log")?).map_err(|e| e.to_string())?;
    let first = log.lines().next().unwrap_or_default();
    if !first.contains(&format!("{steps} steps, seed {seed},")) {
        return Err(format!(
            "run.log starts `{first}`, summary: seed {seed}, {steps} steps"
        ));
    }
    let npy = read_npy(dir.join("positions.npy")).map_err(|e| e.to_string())?;
    if (npy.frames, npy.agents) != (frames, agents as usize) {
        return Err(format!(
            "positions.npy has {} frames of {} agents, summary {frames} of {agents}",
            npy.frames, npy.agents
        ));
    }
    let rows = read("trajectories.csv")?
        .iter()
        .filter(|b| **b == b'\n')
        .count();
    if rows != 1 + frames * agents as usize {
        return Err(format!(
            "trajectories.csv has {rows} lines for {frames} frames of {agents}"
        ));
    }
    serde_json::from_slice::<serde_json::Value>(&read("scene.json")?)
        .map_err(|e| format!("scene.json: {e}"))?;
    if !read("snapshot.png")?.starts_with(b"\x89PNG") || !read("run.gif")?.starts_with(b"GIF8") {
        return Err("a picture is not whole".into());
    }
    let gif = read("run.gif")?;
    if gif.last() != Some(&0x3b) {
        return Err("run.gif has no trailer".into());
    }
    Ok(RunId { seed, steps })
}

/// Hidden entries and temporary files in `dir` (staging folders, `.tmp` files).
pub fn leftovers(dir: &Path) -> Vec<String> {
    entries(dir)
        .into_iter()
        .filter(|n| n.starts_with('.') || n.ends_with(".tmp"))
        .collect()
}
