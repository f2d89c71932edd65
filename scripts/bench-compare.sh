#!/usr/bin/env bash
# Compares two builds of `swarm bench` side by side, interleaved (A, B, A, B, ...), so that both
# see the same machine load: hosts and moments differ far more than builds do.
#
#   scripts/bench-compare.sh OLD_SWARM NEW_SWARM [--model ants|bees] (the plural names the model in builds before and after the model table) [--agents N] [--threads T]
#                            [--steps S] [--runs R]
#
# Prints one line per run and the median agent-steps/s of each build.
set -euo pipefail
if [[ $# -lt 2 || $1 == -h || $1 == --help ]]; then
    sed -n '2,8p' "$0" | sed 's/^# \{0,1\}//'
    exit 64
fi
old=$1 new=$2
shift 2
model=ants agents=100000 threads=2 steps=20 runs=7
while [[ $# -gt 0 ]]; do
    case $1 in
        --model) model=$2 ;;
        --agents) agents=$2 ;;
        --threads) threads=$2 ;;
        --steps) steps=$2 ;;
        --runs) runs=$2 ;;
        *) echo "unknown option $1" >&2; exit 64 ;;
    esac
    shift 2
done
for b in "$old" "$new"; do
    [[ -x $b ]] || { echo "$b: not an executable" >&2; exit 64; }
done
rate() {
    "$1" bench --model "$model" --agents "$agents" --steps "$steps" --threads "$threads" |
        python3 -c 'import json,sys; print(json.load(sys.stdin)["agent_steps_per_s"])'
}
a=() b=()
for ((i = 1; i <= runs; i++)); do
    x=$(rate "$old"); y=$(rate "$new")
    a+=("$x"); b+=("$y")
    printf 'run %d: old %.3e  new %.3e\n' "$i" "$x" "$y"
done
python3 - "${a[*]}" "${b[*]}" <<'PY'
import statistics, sys
old = [float(x) for x in sys.argv[1].split()]
new = [float(x) for x in sys.argv[2].split()]
mo, mn = statistics.median(old), statistics.median(new)
print(f"median: old {mo:.3e}, new {mn:.3e} agent-steps/s; new/old {mn / mo:.3f}")
PY
