#!/usr/bin/env bash
# Issue 16: our ORCA crowd (swarm_sim::orca, example orca_cube) side by side with RVO2-3D
# (scripts/rvo2/random_cube.cc) on the same random cube, interleaved (C++, Rust, C++, Rust, ...)
# so that both sides see the same machine load.
#
#   scripts/bench-orca.sh [--agents 10000,100000] [--steps 50,20] [--runs 3] [--threads 2]
#                         [--seed 1] [--spacing 8] [--margin 0.01] [--cxxflags FLAGS]
#                         [--json FILE]
#
# --agents and --steps are comma-separated lists (one step count per size, or one for all).
# Each run times only the steps (RVO2-3D's doStep; OrcaCrowd::step) and counts the overlaps,
# pairs closer than two radii, after every step (untimed). Prints every run, then a table of
# the median agent-steps/s of each side, their ratio and the overlaps; writes a JSON report
# (default target/bench-orca/report.json). Exit status 1 if our side has any overlap, or more
# than RVO2-3D.
#
# Spacing 8 by default: at the lattice spacing 4 (the C++ driver's default) RVO2-3D itself
# lets agents overlap. Our side runs with a safety margin of 0.01 added to the radius in the
# ORCA planes (CrowdParams::margin; not in the overlap count): ORCA steers agents onto each
# other's boundary, where f32 rounding leaves pairs a few 1e-6 inside two radii (most of the
# 13 overlaps of a default 10k run with --margin 0), and where the planes cannot all be met
# its fallback program spreads the penetration (1e-2 deep at most over 200 steps of 10k
# agents). --margin 0 runs RVO2-3D's parameters exactly (and counts as many overlaps as
# RVO2-3D).
#
# RVO2-3D is built from source with g++ -O3 -fopenmp (plus --cxxflags, e.g. "-march=native
# -flto" for the peer at its best) from $RVO2_3D (default /work/shared/peers/RVO2-3D);
# OMP_NUM_THREADS and --threads both get --threads.
set -euo pipefail
usage() { sed -n '2,28p' "$0" | sed 's/^# \{0,1\}//'; }
cmd="scripts/bench-orca.sh"
[[ $# -eq 0 ]] || cmd+=$(printf ' %q' "$@")
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/.." && pwd)"

agents=10000,100000 steps=50,20 runs=3 threads=2 seed=1 spacing=8 margin=0.01 cxxflags=""
target="${CARGO_TARGET_DIR:-$root/target}"
json="$target/bench-orca/report.json"
while [[ $# -gt 0 ]]; do
    case $1 in
        -h | --help) usage; exit 0 ;;
        --agents | --steps | --runs | --threads | --seed | --spacing | --margin | --cxxflags | --json)
            [[ $# -ge 2 ]] || { echo "bench-orca: $1 needs a value" >&2; exit 64; }
            v=$2
            case $1 in
                --agents) agents=$v ;; --steps) steps=$v ;; --runs) runs=$v ;;
                --threads) threads=$v ;; --seed) seed=$v ;; --spacing) spacing=$v ;;
                --margin) margin=$v ;; --cxxflags) cxxflags=$v ;; --json) json=$v ;;
            esac
            shift 2 ;;
        *) echo "bench-orca: unknown option $1 (see --help)" >&2; exit 64 ;;
    esac
done
IFS=, read -r -a sizes <<< "$agents"
IFS=, read -r -a counts <<< "$steps"
if [[ ${#counts[@]} -ne 1 && ${#counts[@]} -ne ${#sizes[@]} ]]; then
    echo "bench-orca: --steps needs one count, or one per size of --agents" >&2
    exit 64
fi
for n in "${sizes[@]}" "${counts[@]}" "$runs" "$threads"; do
    [[ $n =~ ^[0-9]+$ && $n -gt 0 ]] || { echo "bench-orca: not a positive integer: $n" >&2; exit 64; }
done
[[ $seed =~ ^[0-9]+$ ]] || { echo "bench-orca: --seed: not an integer: $seed" >&2; exit 64; }

# ---- RVO2-3D ----
rvo="${RVO2_3D:-/work/shared/peers/RVO2-3D}"
if [[ ! -f $rvo/src/RVOSimulator.cc ]]; then
    echo "bench-orca: no RVO2-3D source at $rvo (set RVO2_3D to its checkout)" >&2
    exit 69
fi
if ! command -v g++ > /dev/null; then
    if command -v apt-get > /dev/null && [[ $(id -u) -eq 0 ]]; then
        echo "bench-orca: installing g++ (apt-get)" >&2
        apt-get install -y g++ > /dev/null
    fi
    command -v g++ > /dev/null || { echo "bench-orca: g++ not found; install it (Debian: apt-get install g++)" >&2; exit 69; }
fi
build="$target/bench-orca"
mkdir -p "$build" "$(dirname "$json")"
cxx="$build/random_cube"
# shellcheck disable=SC2086 # --cxxflags is a list of flags
g++ -std=c++11 -O3 -fopenmp -DNDEBUG $cxxflags -I "$rvo/src" -I "$rvo/gen" \
    "$rvo"/src/*.cc "$here/rvo2/random_cube.cc" -o "$cxx"

# ---- ours ----
(cd "$root" && CARGO_TARGET_DIR="$target" cargo build --quiet --release -p swarm-sim --example orca_cube)
rust="$target/release/examples/orca_cube"

# ---- interleaved runs ----
lines="$build/runs.jsonl"
: > "$lines"
for i in "${!sizes[@]}"; do
    n=${sizes[$i]}
    s=${counts[$i]:-${counts[0]}}
    for ((r = 1; r <= runs; r++)); do
        a=$(OMP_NUM_THREADS=$threads "$cxx" "$n" "$s" "$seed" "$spacing")
        b=$("$rust" "$n" "$s" "$seed" "$spacing" --threads "$threads" --margin "$margin")
        echo "$a" | tee -a "$lines"
        echo "$b" | tee -a "$lines"
    done
done

python3 - "$lines" "$json" "$threads" "$seed" "$spacing" "$margin" "$cxxflags" "$cmd" <<'PY'
import json, platform, statistics, subprocess, sys, datetime
lines, out, threads, seed, spacing, margin, cxxflags, cmd = sys.argv[1:]
runs = [json.loads(l) for l in open(lines) if l.strip()]
def cpu():
    try:
        for l in subprocess.run(["lscpu"], capture_output=True, text=True).stdout.splitlines():
            if l.startswith("Model name:"):
                return l.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor()
sizes, bad = [], False
for n, s in dict.fromkeys((r["agents"], r["steps"]) for r in runs):
    side = {}
    for impl, key in (("RVO2-3D", "rvo2"), ("swarm orca3d", "swarm")):
        rs = [r for r in runs if r["impl"] == impl and r["agents"] == n and r["steps"] == s]
        side[key] = {
            "agent_steps_per_s": [r["agent_steps_per_s"] for r in rs],
            "median_agent_steps_per_s": statistics.median(r["agent_steps_per_s"] for r in rs),
            "overlaps": max(r["overlaps"] for r in rs),
        }
    ratio = side["swarm"]["median_agent_steps_per_s"] / side["rvo2"]["median_agent_steps_per_s"]
    bad |= side["swarm"]["overlaps"] > 0 or side["swarm"]["overlaps"] > side["rvo2"]["overlaps"]
    sizes.append({"agents": n, "steps": s, **side, "ratio": ratio})
report = {
    "benchmark": "ORCA random cube, RVO2-3D vs swarm orca3d (issue 16)",
    "command": cmd,
    "date": datetime.date.today().isoformat(),
    "machine": {"cpu": cpu(), "threads": int(threads)},
    "seed": int(seed), "spacing": float(spacing), "margin": float(margin),
    "cxxflags": "-O3 -fopenmp " + cxxflags,
    "sizes": sizes,
}
json.dump(report, open(out, "w"), indent=2)
print()
print(f"{'agents':>8} {'steps':>5} {'RVO2-3D /s':>12} {'swarm /s':>12} {'ratio':>6} "
      f"{'overlaps RVO2-3D':>16} {'overlaps swarm':>14}")
for z in sizes:
    print(f"{z['agents']:>8} {z['steps']:>5} {z['rvo2']['median_agent_steps_per_s']:>12.3e} "
          f"{z['swarm']['median_agent_steps_per_s']:>12.3e} {z['ratio']:>6.2f} "
          f"{z['rvo2']['overlaps']:>16} {z['swarm']['overlaps']:>14}")
print(f"(medians of {len(runs) // (2 * len(sizes))} interleaved runs, {threads} threads; "
      f"report: {out})")
if bad:
    print("FAIL: our side has overlaps", file=sys.stderr)
    sys.exit(1)
PY
