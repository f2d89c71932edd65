# Sourced by the scripts that run or reuse the test command's build (scripts/test.sh,
# scripts/hil-qemu.sh, scripts/python-test.sh): what `cargo test` selects and the profile. Every
# script passes exactly these, so cargo unifies the same features and builds nothing a second
# time. The Python module (swarm-py) is left out: maturin builds it, on this build
# (workspace-hack/Cargo.toml).
WORKSPACE_TESTS=(--workspace --exclude swarm-py --profile ci)
