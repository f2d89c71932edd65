#!/usr/bin/env bash
# The GPU backend next to the CPU backend, in one run on one machine (issue 14): `swarm bench`
# for each model × agent count × scalar type on both backends, interleaved (CPU, GPU, CPU, GPU,
# ...) so both see the same load. Prints a Markdown table for docs/benchmarks.md: agent-steps/s
# of each backend, ms per tick, the GPU's per-pass ms (timestamp queries) and device memory.
#
#   scripts/bench-gpu.sh [--models "ant bee wang"] [--agents "100000 1000000"] [--threads 2]
#                        [--steps-per-million 3] [--min-steps 3] [--swarm target/release/swarm]
#
# A model without a GPU engine gets a row saying so. JSON reports go to target/bench-gpu/.
set -euo pipefail
if [[ ${1:-} == -h || ${1:-} == --help ]]; then
    sed -n '2,10p' "$0" | sed 's/^# \{0,1\}//'
    exit 0
fi
cd "$(dirname "${BASH_SOURCE[0]}")/.."
models="ant bee wang" agents="100000 1000000" threads=2 per_million=3 min_steps=3 swarm=""
while [[ $# -gt 0 ]]; do
    case $1 in
        --models) models=$2 ;;
        --agents) agents=$2 ;;
        --threads) threads=$2 ;;
        --steps-per-million) per_million=$2 ;;
        --min-steps) min_steps=$2 ;;
        --swarm) swarm=$2 ;;
        *) echo "bench-gpu.sh: unknown option $1" >&2; exit 64 ;;
    esac
    shift 2
done
if [[ -z $swarm ]]; then
    cargo build --release -q -p swarm-sim
    swarm=target/release/swarm
fi
out=target/bench-gpu
mkdir -p "$out"
echo "| model | agents | scalar | CPU agent-steps/s | GPU agent-steps/s | GPU/CPU | GPU ms/tick | GPU passes (ms) | GPU bytes/agent |"
echo "|---|---:|---|---:|---:|---:|---:|---|---:|"
for model in $models; do
    for n in $agents; do
        # Fewer steps for larger swarms: about the same time per measurement.
        steps=$(( per_million * 1000000 / n )); (( steps < min_steps )) && steps=$min_steps
        for scalar in f32 fixed; do
            for backend in cpu gpu; do
                json="$out/$model-$n-$scalar-$backend.json"
                if ! "$swarm" bench --model "$model" --agents "$n" --steps "$steps" --threads "$threads" \
                    --scalar "$scalar" --backend "$backend" --json "$json" >"$json.log" 2>&1; then
                    echo "failed: $(grep -v XDG_RUNTIME "$json.log" | tail -n1)" >"$json.error"
                    rm -f "$json"
                fi
            done
            python3 - "$out/$model-$n-$scalar" "$model" "$n" "$scalar" <<'PY'
import json, os, sys
base, model, n, scalar = sys.argv[1:]
def load(b):
    p = f"{base}-{b}.json"
    return json.load(open(p)) if os.path.exists(p) else None
cpu, gpu = load("cpu"), load("gpu")
def rate(r): return f"{r['agent_steps_per_s']:.3e}" if r else "—"
if gpu is None:
    err = open(f"{base}-gpu.json.error").read().strip() if os.path.exists(f"{base}-gpu.json.error") else "no report"
    print(f"| {model} | {int(n):,} | {scalar} | {rate(cpu)} | {err} | | | | |")
else:
    ratio = f"{gpu['agent_steps_per_s'] / cpu['agent_steps_per_s']:.2f}" if cpu else "—"
    passes = ", ".join(f"{k} {v:.1f}" for k, v in (gpu.get("kernel_ms") or {}).items()) or "—"
    per = gpu.get("device_bytes_per_agent")
    per = f"{per:.0f}" if per else "—"
    print(f"| {model} | {int(n):,} | {scalar} | {rate(cpu)} | {rate(gpu)} | {ratio} | "
          f"{gpu['ms_per_tick']:.1f} | {passes} | {per} |")
PY
        done
    done
done
adapter=$(python3 -c 'import json,glob
for p in sorted(glob.glob("target/bench-gpu/*-gpu.json")):
    print(json.load(open(p)).get("adapter","")); break' 2>/dev/null || true)
echo
echo "Machine: $("$swarm" bench --model ant --agents 10 --steps 1 | python3 -c 'import json,sys; print(json.load(sys.stdin)["machine"])'); GPU adapter: ${adapter:-none}."
