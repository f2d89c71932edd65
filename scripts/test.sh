#!/usr/bin/env bash
# Runs every test of the project: formatting, clippy, docs, the workspace's unit, property and
# integration tests (the GPU backend's on whatever Vulkan adapter there is, lavapipe without a
# GPU), the Python package's tests (scripts/python-test.sh: pip installs the package, numpy,
# pytest, ray and cma into target/python-venv; a local Ray cluster runs ensembles and
# calibrations), and the no_std firmware images built for real Cortex-M
# targets and run in QEMU.
# Installs the system packages it needs with apt-get when they are missing.
#
#   scripts/test.sh            everything
#   scripts/test.sh --quick    skip the firmware build and QEMU runs
#
# In CI (CI=true) a missing tool is an error. On a developer's machine where packages cannot be
# installed, the stages that need them are skipped with a loud warning.
set -uo pipefail
cd "$(dirname "$0")/.."
source scripts/lib/workspace-tests.sh

QUICK=0
[[ "${1:-}" == "--quick" ]] && QUICK=1
CI="${CI:-false}"
passed=0
failed=0
failures=()
timings=()
started=$SECONDS
# The most resident memory one test process may hold (CI's machine has 24 GiB and 2 cores).
MAX_TEST_PROCESS_GIB=6
peaks=$(mktemp -d)
trap 'rm -rf "$peaks"' EXIT

say() { printf '\n\033[1m==> %s\033[0m\n' "$*"; }
warn() { printf '\n\033[1;33m!!! %s\033[0m\n' "$*" >&2; }

# GiB of a KiB count, one decimal.
gib() { awk -v k="$1" 'BEGIN { printf "%.1f", k / 1048576 }'; }

# Runs one stage, noting its time and the peak resident memory of its largest process (a
# stage that is a shell function of this script measures itself into $peaks/stage).
stage() {
    local name="$1"; shift
    say "$name"
    local start=$SECONDS log="$peaks/stage" run=("$@")
    rm -f "$log"
    declare -F "$1" >/dev/null || run=(python3 scripts/lib/peak-rss.py "$log" "$@")
    if "${run[@]}"; then
        passed=$((passed + 1))
    else
        failed=$((failed + 1))
        failures+=("$name")
        warn "FAILED: $name"
    fi
    local peak
    peak=$(cut -d' ' -f1 "$log" 2>/dev/null || echo 0)
    timings+=("$(printf '%5d s %6s GiB  %s' $((SECONDS - start)) "$(gib "${peak:-0}")" "$name")")
}

# `cargo test`, each test process run by scripts/lib/peak-rss.py (cargo's runner): prints the
# largest peaks and the longest processes, and fails if a test process held more than MAX_TEST_PROCESS_GIB.
cargo_test_within_memory() {
    local log="$peaks/tests" host status=0
    rm -f "$log"
    host=$(rustc -vV | sed -n 's/^host: //p' | tr 'a-z.-' 'A-Z__')
    python3 scripts/lib/peak-rss.py "$peaks/stage" \
        env "CARGO_TARGET_${host}_RUNNER=$PWD/scripts/lib/peak-rss.py $log" "$@" || status=$?
    [[ -s $log ]] || { warn "no test process reported its memory"; return 1; }
    printf 'peak resident memory of the largest test processes:\n'
    sort -rn "$log" | head -5 | while read -r kib bin secs cpu; do
        printf '  %6s GiB  %5s s  %s\n' "$(gib "$kib")" "$secs" "$bin"
    done
    # Cores: CPU seconds over wall seconds (2 on CI's machine when a process keeps both busy).
    printf 'the longest test processes (wall, cores used, peak):\n'
    sort -k3 -rn "$log" | head -12 | while read -r kib bin secs cpu; do
        printf '  %5s s  %4s cores  %6s GiB  %s\n' "$secs" \
            "$(awk -v c="$cpu" -v s="$secs" 'BEGIN { printf "%.1f", (s > 0 ? c / s : 0) }')" \
            "$(gib "$kib")" "$bin"
    done
    local over
    over=$(awk -v max=$((MAX_TEST_PROCESS_GIB * 1048576)) '$1 > max { print $2 }' "$log")
    if [[ -n $over ]]; then
        warn "test processes above ${MAX_TEST_PROCESS_GIB} GiB resident: $over"
        return 1
    fi
    return $status
}

# --- system packages -------------------------------------------------------------------
# Debian packages the firmware stages need, with the command that proves each is present.
need_pkgs=()
have_embedded_rustup() {
    command -v rustup >/dev/null 2>&1 &&
        rustup target list --installed 2>/dev/null | grep thumbv7m-none-eabi >/dev/null &&
        rustup target list --installed 2>/dev/null | grep thumbv7em-none-eabihf >/dev/null
}
if ! have_embedded_rustup; then
    [[ -x /usr/bin/cargo && -x /usr/bin/rustc && -d /usr/lib/rustlib/src/rust/library ]] ||
        need_pkgs+=(rustc-web cargo-web rust-web-src)
    command -v ld.lld >/dev/null 2>&1 || need_pkgs+=(lld)
fi
command -v qemu-system-arm >/dev/null 2>&1 || need_pkgs+=(qemu-system-arm)
((QUICK == 1)) && need_pkgs=()
# The GPU backend's tests (part of cargo test, so also with --quick) need a Vulkan loader and a
# driver: Mesa's lavapipe runs them on the CPU where there is no GPU.
have_vulkan() {
    ldconfig -p 2>/dev/null | grep 'libvulkan\.so\.1' >/dev/null &&
        compgen -G '/usr/share/vulkan/icd.d/*.json' >/dev/null
}
have_vulkan || need_pkgs+=(mesa-vulkan-drivers libvulkan1)
# docs/protocol.md's reference appendices are Python; the Python package builds into a venv.
command -v python3 >/dev/null 2>&1 || need_pkgs+=(python3)
have_venv() {
    local d ok
    d=$(mktemp -d) && python3 -m venv "$d/v" >/dev/null 2>&1
    ok=$?
    rm -rf "$d"
    return $ok
}
have_venv || need_pkgs+=(python3-venv)

firmware_ok=1
if ((${#need_pkgs[@]} > 0)); then
    say "installing system packages: ${need_pkgs[*]}"
    SUDO=""
    [[ $(id -u) -ne 0 ]] && command -v sudo >/dev/null 2>&1 && SUDO="sudo -n"
    if ! { $SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${need_pkgs[@]}"; }; then
        if [[ "$CI" == "true" ]]; then
            warn "cannot install ${need_pkgs[*]} with apt-get; the firmware and GPU tests need them (CI=true: failing)"
            exit 1
        fi
        warn "cannot install ${need_pkgs[*]}: SKIPPING the firmware build and QEMU tests on this machine"
        warn "(install them with: sudo apt-get install ${need_pkgs[*]}); without a Vulkan driver the GPU tests fail"
        firmware_ok=0
    fi
fi

# --- stages ----------------------------------------------------------------------------
# The Python stage's packages (numpy, ray, ...: mostly download) install in the background
# while the Rust stages compile; the Python stage waits for them.
python_prepare_log="$peaks/python-prepare.log"
scripts/python-test.sh --prepare >"$python_prepare_log" 2>&1 &
python_prepare=$!
python_tests() {
    if ! wait "$python_prepare"; then
        cat "$python_prepare_log" >&2
        warn "the Python packages did not install (log above)"
        return 1
    fi
    python3 scripts/lib/peak-rss.py "$peaks/stage" scripts/python-test.sh
}

stage "cargo fmt --check" cargo fmt --all -- --check
stage "cargo clippy (warnings are errors)" cargo clippy --workspace --all-targets -- -D warnings
stage "swarm-core builds without std, every backend" bash -c '
    cargo build -q -p swarm-core --no-default-features --features micromath,fixed,serde &&
    cargo build -q -p swarm-core --no-default-features --features libm &&
    cargo build -q -p swarm-core --features fixed,serde,defmt'
stage "cargo doc (warnings are errors)" env RUSTDOCFLAGS="-D warnings" cargo doc -q --workspace --no-deps
stage "docs/protocol.md: the Python reference appendices run and every assertion holds" python3 scripts/protocol-reference.py
stage "cargo test --workspace (unit, property, integration, doc tests; each test process within ${MAX_TEST_PROCESS_GIB} GiB)" \
    cargo_test_within_memory cargo test "${WORKSPACE_TESTS[@]}"
# After the workspace's tests: their build of swarm-core's dependencies serves this one.
stage "swarm-core with feature small (the ant node's size options) passes its unit tests" \
    cargo test -q -p swarm-core --profile ci --features small --lib
stage "python: the swarm package (pip install ./python into a venv, pytest on a 2-worker Ray cluster)" python_tests

if ((QUICK == 1)); then
    warn "--quick: SKIPPING the firmware build and QEMU tests"
elif ((firmware_ok == 1)); then
    stage "firmware: build ant-node, bee-node and fly-node (f32, fixed) for Cortex-M, within their size budgets" firmware-examples/build.sh --enforce-budgets
    stage "firmware: scenario branch coverage (host)" bash -c 'cd firmware-examples && cargo test -q -p fw-scenario --features std,fixed && cargo test -q -p fw-scenario --features std'
    stage "firmware: node loop and parameters (host)" bash -c 'cd firmware-examples && cargo test -q -p fw-node'
    stage "firmware: every image in qemu-system-arm equals the host, and a corrupted table fails" scripts/qemu-run.sh --self-test
    stage "firmware: serial nodes in QEMU answer Hello with the documented Identity, replay a session byte for byte, stack peaks" \
        scripts/qemu-serial.sh --check --steps 30
    stage "firmware: instructions per controller step in QEMU -icount (counted-loop cross-check; a wrong shift fails)" scripts/qemu-cycles.sh --self-test
    stage "firmware: swarm-hil mirrors every serial node in QEMU (2,000 decisions each, garbage, reset, refusal)" scripts/hil-qemu.sh
fi

echo
printf 'time and peak memory (largest process) per stage:\n'; printf '  %s\n' "${timings[@]}"
printf 'total: %d min %d s\n' $(((SECONDS - started) / 60)) $(((SECONDS - started) % 60))
if ((failed > 0)); then
    printf 'failed stages:\n'; printf '  - %s\n' "${failures[@]}"
fi
echo "stages: ${passed} passed, ${failed} failed"
((failed == 0))
