//! The crate boundaries of DESIGN.md, checked on the sources: a model's folder in swarm-sim
//! does not reach into a sibling model's folder, and swarm-core depends on nothing of the host.

use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("workspace root")
        .to_path_buf()
}

/// Every `.rs` file under `dir`.
fn sources(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut todo = vec![dir.to_path_buf()];
    while let Some(d) = todo.pop() {
        for e in std::fs::read_dir(&d).unwrap_or_else(|e| panic!("{}: {e}", d.display())) {
            let p = e.expect("dir entry").path();
            if p.is_dir() {
                todo.push(p);
            } else if p.extension().is_some_and(|x| x == "rs") {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}

/// The model folders of swarm-sim: every folder of `host-sim/src` that is a model (has a
/// `sim.rs`).
fn model_folders(src: &Path) -> Vec<String> {
    let mut out: Vec<String> = std::fs::read_dir(src)
        .expect("host-sim/src")
        .filter_map(|e| {
            let p = e.ok()?.path();
            (p.is_dir() && p.join("sim.rs").exists())
                .then(|| p.file_name()?.to_str().map(str::to_string))?
        })
        .collect();
    out.sort();
    out
}

#[test]
fn no_model_folder_of_swarm_sim_uses_a_sibling_model() {
    let src = root().join("host-sim/src");
    let models = model_folders(&src);
    assert!(
        models.len() >= 2,
        "expected the model folders, found {models:?}"
    );
    let mut found = Vec::new();
    for m in &models {
        for file in sources(&src.join(m)) {
            let text = std::fs::read_to_string(&file).expect("source");
            for other in models.iter().filter(|o| *o != m) {
                for pat in [format!("crate::{other}"), format!("super::super::{other}")] {
                    for (n, line) in text.lines().enumerate() {
                        let code = line.split("//").next().unwrap_or("");
                        if code.contains(&pat) {
                            found.push(format!("{}:{}: {}", file.display(), n + 1, line.trim()));
                        }
                    }
                }
            }
        }
    }
    assert!(
        found.is_empty(),
        "a model folder uses a sibling model:\n{}",
        found.join("\n")
    );
}

#[test]
fn swarm_core_depends_on_nothing_of_the_host() {
    let core = root().join("core-nostd");
    let manifest = std::fs::read_to_string(core.join("Cargo.toml")).expect("manifest");
    // Only the [dependencies] table (dev-dependencies may use anything).
    let deps = manifest
        .split("\n[")
        .find(|t| t.starts_with("dependencies]"))
        .expect("[dependencies]");
    for host in [
        "swarm-sim",
        "swarm-hil",
        "swarm-tests",
        "std",
        "rayon",
        "wgpu",
    ] {
        assert!(
            !deps.lines().any(|l| l.trim_start().starts_with(host)),
            "swarm-core depends on `{host}`"
        );
    }
    let lib = std::fs::read_to_string(core.join("src/lib.rs")).expect("lib.rs");
    assert!(
        lib.contains("#![cfg_attr(not(test), no_std)]"),
        "swarm-core is no_std"
    );
    for file in sources(&core.join("src")) {
        let text = std::fs::read_to_string(&file).expect("source");
        for (n, line) in text.lines().enumerate() {
            let code = line.split("//").next().unwrap_or("");
            assert!(
                !code.contains("swarm_sim") && !code.contains("swarm_hil"),
                "{}:{}: swarm-core names a host crate",
                file.display(),
                n + 1
            );
            assert!(
                !code.contains("extern crate alloc"),
                "{}:{}: swarm-core allocates",
                file.display(),
                n + 1
            );
        }
    }
}

/// The `(name, version)` of every package a `Cargo.lock` pins.
fn locked(path: &Path) -> std::collections::BTreeSet<(String, String)> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let quoted = |line: &str, key: &str| {
        line.strip_prefix(key).map(|v| {
            v.trim_matches(|c| c == ' ' || c == '=' || c == '"')
                .to_string()
        })
    };
    let mut out = std::collections::BTreeSet::new();
    let mut name = None;
    for line in text.lines() {
        if let Some(n) = quoted(line, "name") {
            name = Some(n);
        } else if let (Some(v), Some(n)) = (quoted(line, "version"), name.take()) {
            out.insert((n, v));
        }
    }
    out
}

/// The Python module (`python/`, a workspace of its own for maturin) pins the workspace's
/// version of every package the two share (in one semver series), so that
/// `scripts/python-test.sh` builds it on what `cargo test` built (the same versions, profile
/// and target folder) instead of building every dependency again. After `cargo update`: `cp Cargo.lock python/ && cargo tree --manifest-path
/// python/Cargo.toml`.
#[test]
fn the_python_module_pins_the_workspaces_versions() {
    let (ours, python) = (
        locked(&root().join("Cargo.lock")),
        locked(&root().join("python/Cargo.lock")),
    );
    // Semver-compatible: the same leading component, and the next one too below 1.0.
    let series = |v: &str| -> Vec<String> {
        let parts: Vec<&str> = v.split('.').collect();
        let n = if parts[0] == "0" { 2 } else { 1 };
        parts.iter().take(n).map(|s| s.to_string()).collect()
    };
    let apart: Vec<String> = python
        .iter()
        .filter(|p| !ours.contains(*p))
        .filter(|(n, v)| ours.iter().any(|(m, w)| m == n && series(w) == series(v)))
        .map(|(n, v)| format!("{n} {v}"))
        .collect();
    assert!(
        apart.is_empty(),
        "python/Cargo.lock pins other versions than Cargo.lock: {apart:?} (cp Cargo.lock \
         python/ && cargo tree --manifest-path python/Cargo.toml)"
    );
}
