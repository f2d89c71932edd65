use super::*;
use crate::output::testing::entries;
use tempfile::TempDir;

/// A pid no process has (above Linux's largest `pid_max`).
const DEAD_PID: u32 = 4_000_000_000;

/// A run folder holding `files`, each containing `tag`.
fn write_run(dir: &Path, files: &[&str], tag: &str) {
    fs::create_dir_all(dir).unwrap();
    for f in files {
        fs::write(dir.join(f), tag).unwrap();
    }
}

/// A temporary folder holding the run folder `run` with `files`, each containing "old".
fn old_run(files: &[&str]) -> (TempDir, PathBuf) {
    let root = tempfile::tempdir().unwrap();
    let target = root.path().join("run");
    write_run(&target, files, "old");
    (root, target)
}

/// The text of the `summary.json` in `dir`.
fn summary_in(dir: &Path) -> String {
    fs::read_to_string(dir.join(SUMMARY_JSON)).unwrap()
}

fn stale(parent: &Path, target: &str, kind: Sibling, pid: u32) -> PathBuf {
    let p = parent.join(format!(".{target}.{}-{pid}-Ab3dE6gH", kind.tag()));
    write_run(&p, &[SUMMARY_JSON, ".positions.npy.xYz123.tmp"], "stale");
    p
}

#[test]
fn sibling_names_parse_back() {
    let name = format!("{}{}", Sibling::Staging.prefix("fig.7a"), "a1B2c3D4");
    let (target, kind, pid) = parse_sibling(&name).unwrap();
    assert_eq!(
        (target, kind, pid),
        ("fig.7a", Sibling::Staging, std::process::id())
    );
    assert_eq!(
        parse_sibling(".x.old-12-abcdefgh"),
        Some(("x", Sibling::Old, 12))
    );
    for bad in [
        "x.staging-12-abcdefgh",  // not hidden
        ".x.staging-12-abcdefg",  // random part too short
        ".x.staging-1a-abcdefgh", // pid not a number
        ".x.backup-12-abcdefgh",  // unknown kind
        "..staging-12-abcdefgh",  // no target
        ".x.staging-12-abcd/fgh", // not alphanumeric
        ".positions.npy.abc123.tmp",
    ] {
        assert_eq!(parse_sibling(bad), None, "{bad}");
    }
}

#[test]
fn run_file_names() {
    for ok in [
        SUMMARY_JSON,
        RUN_GIF,
        ".positions.npy.Xy12Zq.tmp",
        ".run.log.a.tmp",
    ] {
        assert!(is_run_file_name(ok), "{ok}");
    }
    for bad in [
        "notes.txt",
        ".positions.npy.tmp",
        ".positions.npy..tmp",
        "positions.npy.abc.tmp",
        ".other.abc.tmp",
        "summary.json.bak",
    ] {
        assert!(!is_run_file_name(bad), "{bad}");
    }
}

#[test]
fn a_new_folder_appears_whole_on_commit() {
    let root = tempfile::tempdir().unwrap();
    let target = root.path().join("deep/run");
    let s = Staging::begin(&target).unwrap();
    assert!(!target.exists(), "the target appears only on commit");
    assert_eq!(s.path().parent(), Some(root.path().join("deep").as_path()));
    write_run(s.path(), &[SUMMARY_JSON, POSITIONS_NPY], "new");
    s.commit().unwrap();
    assert_eq!(entries(&target), vec![POSITIONS_NPY, SUMMARY_JSON]);
    assert_eq!(entries(&root.path().join("deep")), vec!["run"]);
}

#[test]
fn a_run_replaces_the_whole_previous_run() {
    let (root, target) = old_run(&[SUMMARY_JSON, SNAPSHOT_PNG, RUN_GIF, ".run.gif.abc.tmp"]);
    let s = Staging::begin(&target).unwrap();
    write_run(s.path(), &[SUMMARY_JSON, POSITIONS_NPY], "new");
    // Until the commit the target is the old run.
    assert_eq!(summary_in(&target), "old");
    s.commit().unwrap();
    // Files the new run does not write are gone with the old run.
    assert_eq!(entries(&target), vec![POSITIONS_NPY, SUMMARY_JSON]);
    assert_eq!(summary_in(&target), "new");
    assert_eq!(entries(root.path()), vec!["run"]);
}

#[test]
fn the_fallback_swap_replaces_the_previous_run_too() {
    let (root, target) = old_run(&[SUMMARY_JSON, RUN_GIF]);
    let s = Staging::begin(&target).unwrap();
    write_run(s.path(), &[SUMMARY_JSON], "new");
    s.swap_by_renames().unwrap();
    assert_eq!(entries(&target), vec![SUMMARY_JSON]);
    assert_eq!(summary_in(&target), "new");
    drop(s);
    assert_eq!(entries(root.path()), vec!["run"]);
}

#[test]
fn a_dropped_staging_folder_leaves_nothing() {
    let (root, target) = old_run(&[SUMMARY_JSON]);
    {
        let s = Staging::begin(&target).unwrap();
        write_run(s.path(), &[POSITIONS_NPY], "partial");
    }
    assert_eq!(entries(root.path()), vec!["run"]);
    assert_eq!(summary_in(&target), "old");
}

#[test]
fn a_folder_with_other_files_is_refused_and_left_alone() {
    let root = tempfile::tempdir().unwrap();
    let target = root.path().join("mine");
    write_run(&target, &[SUMMARY_JSON, "notes.txt"], "user");
    let err = Staging::begin(&target).unwrap_err();
    assert!(
        matches!(&err, SimError::NotARunFolder { entry, .. } if entry == "notes.txt"),
        "{err}"
    );
    let msg = err.to_string();
    assert!(msg.contains("mine") && msg.contains("notes.txt"), "{msg}");
    assert_eq!(entries(&target), vec!["notes.txt", SUMMARY_JSON]);
    assert_eq!(entries(root.path()), vec!["mine"]);
    // A sub-folder is not a run file either.
    let sub = root.path().join("sub");
    fs::create_dir_all(sub.join("inner")).unwrap();
    assert!(matches!(
        Staging::begin(&sub),
        Err(SimError::NotARunFolder { .. })
    ));
    // Nor is a plain file a folder.
    let file = root.path().join("file");
    fs::write(&file, "x").unwrap();
    assert!(
        Staging::begin(&file)
            .unwrap_err()
            .to_string()
            .contains("not a folder")
    );
    assert_eq!(fs::read_to_string(&file).unwrap(), "x");
}

#[test]
fn an_abandoned_run_keeps_only_its_log_beside_the_untouched_target() {
    let (_root, target) = old_run(&[SUMMARY_JSON]);
    let s = Staging::begin(&target).unwrap();
    write_run(
        s.path(),
        &[POSITIONS_NPY, ".positions.npy.abc.tmp"],
        "partial",
    );
    fs::write(s.path().join(RUN_LOG), "error: disk full\n").unwrap();
    let log = s.abandon().expect("the log is kept");
    assert_eq!(fs::read_to_string(&log).unwrap(), "error: disk full\n");
    let failed = log.parent().unwrap();
    assert_eq!(entries(failed), vec![RUN_LOG]);
    let name = failed.file_name().unwrap().to_str().unwrap();
    assert_eq!(
        parse_sibling(name).map(|(t, k, _)| (t, k)),
        Some(("run", Sibling::Failed))
    );
    assert_eq!(summary_in(&target), "old");
}

#[test]
fn stale_siblings_of_dead_runs_are_cleaned_and_nothing_else() {
    let root = tempfile::tempdir().unwrap();
    let parent = root.path();
    write_run(&parent.join("a"), &[SUMMARY_JSON], "a");
    let staging = stale(parent, "a", Sibling::Staging, DEAD_PID);
    let failed = stale(parent, "a", Sibling::Failed, DEAD_PID);
    let old_of_present = stale(parent, "a", Sibling::Old, DEAD_PID);
    // The fallback swap was killed between its renames: `b` is missing, its old run aside.
    let old_of_missing = stale(parent, "b", Sibling::Old, DEAD_PID);
    // Not ours to touch: a live process, a foreign file inside, a name of another pattern.
    let live = stale(parent, "a", Sibling::Staging, std::process::id());
    let foreign = stale(parent, "c", Sibling::Staging, DEAD_PID);
    fs::write(foreign.join("notes.txt"), "user").unwrap();
    let other = parent.join(".a.staging-12-short");
    write_run(&other, &[SUMMARY_JSON], "x");

    let mut cleaned = clean_stale(parent);
    cleaned.sort();
    let mut expected = vec![staging, failed, old_of_present, old_of_missing.clone()];
    expected.sort();
    assert_eq!(cleaned, expected);
    assert!(!old_of_missing.exists());
    assert_eq!(
        summary_in(&parent.join("b")),
        "stale",
        "the old run is put back"
    );
    for kept in [&live, &foreign, &other] {
        assert!(kept.is_dir(), "{}", kept.display());
    }
    assert_eq!(summary_in(&parent.join("a")), "a");
}

#[test]
fn begin_cleans_stale_siblings_first() {
    let root = tempfile::tempdir().unwrap();
    let target = root.path().join("run");
    stale(root.path(), "run", Sibling::Staging, DEAD_PID);
    stale(root.path(), "other", Sibling::Failed, DEAD_PID);
    let s = Staging::begin(&target).unwrap();
    write_run(s.path(), &[SUMMARY_JSON], "new");
    s.commit().unwrap();
    assert_eq!(entries(root.path()), vec!["run"]);
}

#[cfg(unix)]
#[test]
fn a_link_to_a_run_folder_replaces_the_folder_it_points_to() {
    let root = tempfile::tempdir().unwrap();
    let real = root.path().join("real");
    write_run(&real, &[SUMMARY_JSON, RUN_GIF], "old");
    let link = root.path().join("link");
    std::os::unix::fs::symlink(&real, &link).unwrap();
    let s = Staging::begin(&link).unwrap();
    write_run(s.path(), &[SUMMARY_JSON], "new");
    s.commit().unwrap();
    assert!(
        fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert_eq!(entries(&link), vec![SUMMARY_JSON]);
    assert_eq!(summary_in(&real), "new");
}
