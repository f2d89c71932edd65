#!/usr/bin/env bash
# The `swarm` Python package (python/): installs it with pip (`pip install ./python`, which
# builds it with maturin) into a virtual environment (target/python-venv, created when
# missing), then runs its pytest suite against it.
#
#   scripts/python-test.sh [pytest arguments]
#
# Needs python3 with venv (scripts/test.sh installs python3-venv when missing) and the Python
# package index, or a pip mirror, for numpy, pytest, ray, cma and maturin (pip's build of
# ./python). The module builds with the test suite's profile (`ci`) in the workspace's target
# folder, so that it reuses every dependency `cargo test` built (python/Cargo.lock pins the
# workspace's versions: tests/tests/architecture.rs); the tests compare with the `swarm` command
# built here (target/ci/swarm).
set -euo pipefail
cd "$(dirname "$0")/.."
venv=target/python-venv
if [[ ! -x $venv/bin/python ]]; then
    python3 -m venv "$venv"
fi
py="$venv/bin/python"
"$py" -m pip install -q --disable-pip-version-check "numpy>=1.21" "pytest>=7" "ray>=2.9" "cma>=3.2"
# The native crate is outside the workspace (maturin builds it): its own formatting and lints.
cargo fmt --manifest-path python/Cargo.toml -- --check
export CARGO_TARGET_DIR="$PWD/target"
cargo clippy -q --manifest-path python/Cargo.toml --all-targets -- -D warnings
# The README's install command; maturin builds the wheel with the `ci` profile.
MATURIN_PEP517_ARGS="--profile ci" "$py" -m pip install -q --disable-pip-version-check \
    --force-reinstall --no-deps ./python
unset CARGO_TARGET_DIR
# The `swarm` command from the test suite's build (scripts/hil-qemu.sh says why not `-p`).
cargo test -q --workspace --profile ci --no-run
SWARM_EXE="$PWD/target/ci/swarm" "$py" -m pytest -q python/tests "$@"
