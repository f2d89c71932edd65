#!/usr/bin/env bash
# The `swarm` Python package (python/): installs it with pip (`pip install ./python`, which
# builds it with maturin) into a virtual environment (target/python-venv, created when
# missing), then runs its pytest suite against it.
#
#   scripts/python-test.sh [pytest arguments]
#   scripts/python-test.sh --prepare     only the virtual environment and its packages
#                                        (scripts/test.sh downloads them while Rust builds)
#
# Needs python3 with venv (scripts/test.sh installs python3-venv when missing) and the Python
# package index, or a pip mirror, for numpy, pytest, ray, cma and maturin (pip's build of
# ./python). The module (a workspace member) builds with the test suite's profile (`ci`) on what
# `cargo test` built: the same workspace, target folder and features (workspace-hack/). Its
# formatting and lints are the workspace's (`cargo fmt --all`, `cargo clippy --workspace` in
# scripts/test.sh). The tests compare with the `swarm` command built here (target/ci/swarm).
set -euo pipefail
cd "$(dirname "$0")/.."
venv=target/python-venv
if [[ ! -x $venv/bin/python ]]; then
    python3 -m venv "$venv"
fi
py="$venv/bin/python"
"$py" -m pip install -q --disable-pip-version-check "numpy>=1.21" "pytest>=7" "ray>=2.9" "cma>=3.2"
[[ "${1:-}" == "--prepare" ]] && exit 0
# The README's install command; maturin builds the wheel with the `ci` profile.
MATURIN_PEP517_ARGS="--profile ci" "$py" -m pip install -q --disable-pip-version-check \
    --force-reinstall --no-deps ./python
# The `swarm` command from the test suite's build (scripts/hil-qemu.sh says why not `-p`).
source scripts/lib/workspace-tests.sh
cargo test -q "${WORKSPACE_TESTS[@]}" --no-run
SWARM_EXE="$PWD/target/ci/swarm" "$py" -m pytest -q python/tests "$@"
