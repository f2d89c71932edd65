//! An output folder always holds exactly one run: `swarm run` killed with SIGKILL at random
//! moments, 20 times into a new folder and 20 times over the folder of a different run, never
//! leaves a folder mixing two runs or a partial one, and the next run leaves no staging folder
//! or temporary file behind.
//!
//! The moments are drawn from a seeded generator (`SWARM_KILL_SEED`, default 12) over the
//! measured length of a whole run, so kills fall while the trajectories stream, while the
//! pictures are drawn and around the swap. Runs on every Unix, CI included (about 30 s).

#![cfg(unix)]

mod common;

use std::path::Path;
use std::time::{Duration, Instant};

use common::{RunId, entries, identify, leftovers, ok, run_cmd};

const SCENARIO: &str = "ants-fig7a-single-colony";
/// The run that gets killed.
const NEW: RunId = RunId {
    seed: 5,
    steps: 500,
};
/// The run it replaces in the second half: another seed and length, so every file differs.
const OLD: RunId = RunId { seed: 9, steps: 40 };
const KILLS: usize = 20;

fn args(id: RunId) -> [String; 4] {
    [
        "--seed".into(),
        id.seed.to_string(),
        "--steps".into(),
        id.steps.to_string(),
    ]
}

fn complete(out: &Path, id: RunId) {
    let a = args(id);
    let a: Vec<&str> = a.iter().map(String::as_str).collect();
    ok(&mut run_cmd(SCENARIO, out, &a));
    assert_eq!(identify(out), Ok(id));
}

/// splitmix64: seeded, no dependency.
struct Rng(u64);

impl Rng {
    fn unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Starts the NEW run into `out`, kills it (SIGKILL) after `after` unless it ended before,
/// and reaps it. Returns whether it was killed.
fn run_and_kill(out: &Path, after: Duration) -> bool {
    let a = args(NEW);
    let a: Vec<&str> = a.iter().map(String::as_str).collect();
    let mut child = run_cmd(SCENARIO, out, &a)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .expect("start swarm");
    let t0 = Instant::now();
    while t0.elapsed() < after {
        if child.try_wait().expect("wait").is_some() {
            return false;
        }
        std::thread::sleep(Duration::from_millis(2).min(after.saturating_sub(t0.elapsed())));
    }
    let killed = child.try_wait().expect("wait").is_none();
    let _ = child.kill(); // SIGKILL on Unix
    child.wait().expect("reap");
    killed
}

#[test]
fn killed_runs_never_leave_a_folder_mixing_two_runs_or_stray_files() {
    let seed = std::env::var("SWARM_KILL_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(12u64);
    let mut rng = Rng(seed);
    let root = tempfile::tempdir().unwrap();
    let parent = root.path();

    // How long a whole run takes here (the longer of two).
    let mut whole: f64 = 0.0;
    for _ in 0..2 {
        let t0 = Instant::now();
        complete(&parent.join("probe"), NEW);
        whole = whole.max(t0.elapsed().as_secs_f64());
    }
    std::fs::remove_dir_all(parent.join("probe")).unwrap();
    // Uniform over a bit more than a whole run, so some kills fall after it ended.
    let moment = |rng: &mut Rng| Duration::from_secs_f64(whole * 1.4 * rng.unit());
    eprintln!("seed {seed}: a whole run takes {whole:.2} s");

    // Into a new folder: afterwards it is missing or the whole new run.
    let mut interrupted = 0;
    for i in 0..KILLS {
        let out = parent.join(format!("new-{i}"));
        let at = moment(&mut rng);
        let killed = run_and_kill(&out, at);
        if out.exists() {
            assert_eq!(
                identify(&out),
                Ok(NEW),
                "kill {i} at {at:?} (killed: {killed})"
            );
        } else {
            assert!(killed, "kill {i}: the run ended but left no folder");
            interrupted += 1;
        }
    }
    eprintln!("new folder: {interrupted} of {KILLS} kills left no folder, the rest the new run");
    assert!(interrupted > 0, "no kill fell inside a run");

    // Over the folder of another run: afterwards it is the old run or the new one, whole.
    let out = parent.join("over");
    let (mut old, mut new) = (0, 0);
    for i in 0..KILLS {
        if identify(&out) != Ok(OLD) {
            complete(&out, OLD);
        }
        let at = moment(&mut rng);
        let killed = run_and_kill(&out, at);
        match identify(&out) {
            Ok(id) if id == OLD => old += 1,
            Ok(id) if id == NEW => new += 1,
            other => panic!("kill {i} at {at:?} (killed: {killed}): {other:?}"),
        }
    }
    eprintln!("over an old run: {old} kills left the old run, {new} the new one");
    assert!(old > 0, "no kill fell inside a run");

    // The next runs clean up what the killed ones left beside their folders.
    complete(&out, NEW);
    complete(&parent.join("new-0"), NEW);
    assert_eq!(
        leftovers(parent),
        Vec::<String>::new(),
        "{:?}",
        entries(parent)
    );
    for name in entries(parent) {
        assert_eq!(identify(&parent.join(&name)), Ok(NEW), "{name}");
    }
}
