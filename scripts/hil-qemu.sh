#!/usr/bin/env bash
# Mirrors every firmware image in QEMU through `swarm-hil qemu` (issues 5 and 16): each node ×
# scalar type mirrors at least 2,000 decisions with zero mismatches (every node in fixed point
# also against the GPU backend's decisions);
# each node survives 64 KiB of random bytes on its UART and a reset of the board mid-run
# (re-handshake, reset reported); an image built with other parameters (<node>-other) is refused
# at the handshake, naming the difference.
#
#   scripts/hil-qemu.sh            (after firmware-examples/build.sh)
#
# Reports go to target/hil-qemu/*.json. Exit status: the number of failed checks (0: all good).
set -uo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

command -v qemu-system-arm >/dev/null 2>&1 \
    || { echo "hil-qemu.sh: error: qemu-system-arm not found (apt-get install qemu-system-arm)" >&2; exit 1; }
# The test suite's build (the same command as `scripts/test.sh`'s cargo test, so the same
# features of every dependency): after it nothing is built again. (`cargo build -p swarm-hil`
# unifies features over swarm-hil alone and built wgpu and the simulator a second time.)
source scripts/lib/workspace-tests.sh
cargo test "${WORKSPACE_TESTS[@]}" -q --no-run || exit 1
HIL=target/ci/swarm-hil
OUT=target/hil-qemu
mkdir -p "$OUT"
FAILED=0

scenario_of() {
    case "$1" in
        ant-node) echo ants-fig7a-single-colony ;;
        bee-node) echo bees-fig14-shafts ;;
        fly-node) echo fly-fig1-midges ;;
    esac
}
# 2,000 decisions: ants plan + resolve for 20 ants × 50 steps; bees 40 bees × 50 steps; flies
# (midges) 40 insects × 50 steps.
agents_of() { case "$1" in ant-node) echo 20 ;; bee-node|fly-node) echo 40 ;; esac; }
field() { grep -o "\"$2\": *[0-9]*" "$1" | head -n1 | grep -o '[0-9]*$'; }

check() { # label, json, want_decisions, want_resets
    local label=$1 json=$2 want=$3 resets=${4:-0} d m r
    d=$(field "$json" decisions); m=$(field "$json" mismatches); r=$(field "$json" resets)
    if [ "${d:-0}" -ge "$want" ] && [ "${m:-1}" = 0 ] && [ "${r:-0}" -ge "$resets" ]; then
        echo "PASS  $label: $d decisions, 0 mismatches, $r resets"
    else
        echo "FAIL  $label: decisions=${d:-?} (want ≥ $want), mismatches=${m:-?}, resets=${r:-?} (want ≥ $resets)"
    fi
}

# Every check of one node, its lines on stdout (PASS/FAIL); the nodes run side by side (each
# QEMU waits on its UART most of the time: on 2 cores the three together take little longer
# than the slowest alone).
node_checks() {
    local node=$1 sc k scalar json log elf rc
    sc=$(scenario_of "$node"); k=$(agents_of "$node")
    for scalar in f32 fixed; do
        json="$OUT/$node-$scalar.json"
        if "$HIL" qemu --firmware $node --scalar $scalar --scenario "$sc" --agents "$k" --steps 50 \
            --timeout-ms 500 --quiet --json "$json" >"$OUT/$node-$scalar.log" 2>&1; then
            check "$node $scalar" "$json" 2000
        else
            echo "FAIL  $node $scalar: swarm-hil exited $? ($(tail -n1 "$OUT/$node-$scalar.log"))"
        fi
    done
    # The promise end to end: the firmware in fixed point against decisions made on the GPU
    # (every model has a GPU engine: ants and bees, issue 14; the fly model, ren2016 with ORCA).
    json="$OUT/$node-fixed-gpu.json"
    if "$HIL" qemu --firmware $node --scalar fixed --backend gpu --scenario "$sc" --agents "$k" \
        --steps 50 --timeout-ms 500 --quiet --json "$json" >"$OUT/$node-fixed-gpu.log" 2>&1; then
        check "$node fixed against the GPU backend" "$json" 2000
    else
        echo "FAIL  $node fixed against the GPU backend: swarm-hil exited $? ($(tail -n1 "$OUT/$node-fixed-gpu.log"))"
    fi
    json="$OUT/$node-garbage-reset.json"
    if "$HIL" qemu --firmware $node --scenario "$sc" --agents "$k" --steps 20 --garbage 65536 \
        --reset-at-step 10 --timeout-ms 500 --quiet --json "$json" >"$OUT/$node-garbage-reset.log" 2>&1; then
        check "$node after 64 KiB of garbage and a reset at step 10" "$json" 800 1
    else
        echo "FAIL  $node garbage/reset: swarm-hil exited $? ($(tail -n1 "$OUT/$node-garbage-reset.log"))"
    fi
    # The image built with other parameters (`<node>-other`) must be refused by the host.
    log="$OUT/$node-other.log"
    elf=$(dirname "$(ls firmware-examples/target/*/release/$node | head -n1)")/$node-other
    "$HIL" qemu --firmware $node --elf "$elf" --scenario "$sc" --agents 2 --steps 1 --quiet >"$log" 2>&1
    rc=$?
    if [ $rc -ne 0 ] && grep -q "params hash 0x" "$log"; then
        echo "PASS  $node-other (built with other parameters) is refused: $(grep -o 'params hash 0x[0-9a-f]* ≠ 0x[0-9a-f]*' "$log" | head -n1)"
    else
        echo "FAIL  $node-other: exit $rc, expected a handshake refusal ($(tail -n1 "$log"))"
    fi
}

for node in ant-node bee-node fly-node; do
    node_checks $node >"$OUT/$node.checks" 2>&1 &
done
wait
for node in ant-node bee-node fly-node; do
    cat "$OUT/$node.checks"
    FAILED=$((FAILED + $(grep -c '^FAIL' "$OUT/$node.checks")))
done

[ $FAILED -eq 0 ] && echo "hil-qemu: all checks passed" || echo "hil-qemu: $FAILED check(s) failed"
exit $FAILED
