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

/// Every package's features as `cargo tree` unifies them over what `args` selects.
fn unified_features(
    args: &[&str],
) -> std::collections::BTreeMap<String, std::collections::BTreeSet<String>> {
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let out = std::process::Command::new(cargo)
        .current_dir(root())
        .args([
            "tree", "--locked", "--prefix", "none", "--format", "{p}|{f}",
        ])
        .args(args)
        .output()
        .expect("cargo tree runs");
    assert!(
        out.status.success(),
        "cargo tree {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let mut features = std::collections::BTreeMap::new();
    for line in String::from_utf8_lossy(&out.stdout).lines() {
        let Some((package, list)) = line.split_once('|') else {
            continue;
        };
        // "name v1.2.3 (path)" or "name v1.2.3": name and version.
        let package = package.split(" (").next().unwrap_or(package).to_string();
        let list = list.split(" (").next().unwrap_or(list);
        features
            .entry(package)
            .or_insert_with(std::collections::BTreeSet::new)
            .extend(list.split(',').filter(|f| !f.is_empty()).map(String::from));
    }
    features
}

/// `scripts/python-test.sh` builds the Python module (a workspace member) on what the test
/// command's `cargo test --workspace --exclude swarm-py` built only if cargo unifies the same
/// features of every dependency the two share (otherwise wgpu, naga and swarm-sim are compiled
/// again: four minutes on CI's machine). `workspace-hack/`
/// asks for the union; a new dependency or feature that splits them again fails here, naming
/// the crates and features to add there.
#[test]
fn the_python_module_and_the_workspace_build_the_same_dependencies() {
    let ours = unified_features(&[
        "--workspace",
        "--exclude",
        "swarm-py",
        "--edges",
        "normal,build,dev",
    ]);
    let python = unified_features(&["--package", "swarm-py", "--edges", "normal,build"]);
    let apart: Vec<String> = python
        .iter()
        .filter_map(|(package, theirs)| {
            let mine = ours.get(package)?;
            (mine != theirs).then(|| {
                format!(
                    "{package}: the workspace's only {:?}, the module's only {:?}",
                    mine.difference(theirs).collect::<Vec<_>>(),
                    theirs.difference(mine).collect::<Vec<_>>()
                )
            })
        })
        .collect();
    assert!(
        apart.is_empty(),
        "add these to workspace-hack/Cargo.toml: {apart:#?}"
    );
}
