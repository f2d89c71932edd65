#!/usr/bin/env python3
"""W-T21 (wang2014 linear scaling, Fig. 14b) from the `wang_scaling` criterion bench.

Runs `cargo bench -p swarm-sim --bench wang_scaling [-- CRITERION_ARGS]` (unless --no-run), reads criterion's
mean per-step time of wang_scaling/insects/N (N = 1k ... 256k) and wang_scaling/world/
{base,grid2x,obstacles4x} from <target>/criterion, fits time = a + b*N by least squares and
checks W-T21: R^2 >= 0.98, and a 2x finer cost grid or 4x the obstacles changing the
per-step time by less than 15 %. Prints PASS or FAIL; exits 1 on FAIL, 2 when results are
missing. <target> is --target-dir, else $CARGO_TARGET_DIR, else ./target of the workspace.
"""

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
SIZES = [1_000, 4_000, 16_000, 64_000, 256_000]
WORLDS = ["base", "grid2x", "obstacles4x"]
MIN_R2 = 0.98
MAX_CHANGE = 0.15


def mean_ns(criterion: Path, bench: str) -> float:
    """Criterion's mean point estimate (ns per iteration, here per tick) of `bench`."""
    path = criterion / "wang_scaling" / bench / "new" / "estimates.json"
    try:
        with open(path, encoding="utf-8") as f:
            return float(json.load(f)["mean"]["point_estimate"])
    except FileNotFoundError:
        print(f"wang-scaling: no results at {path} (run without --no-run first)", file=sys.stderr)
        sys.exit(2)


def main() -> int:
    ap = argparse.ArgumentParser(
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog="Thresholds: R^2 >= %.2f, |change| < %d %%." % (MIN_R2, MAX_CHANGE * 100),
    )
    ap.add_argument(
        "--no-run",
        action="store_true",
        help="read the existing criterion results instead of running the bench",
    )
    ap.add_argument(
        "--target-dir",
        type=Path,
        help="cargo's target directory (default: $CARGO_TARGET_DIR, else ./target)",
    )
    ap.add_argument(
        "criterion_args",
        nargs="*",
        help="passed to the bench after `--` (e.g. a filter, wang_scaling/world, to rerun a group)",
    )
    args = ap.parse_args()
    target = args.target_dir or Path(os.environ.get("CARGO_TARGET_DIR") or ROOT / "target")
    if not target.is_absolute():
        target = ROOT / target
    if not args.no_run:
        cmd = ["cargo", "bench", "-p", "swarm-sim", "--bench", "wang_scaling"]
        if args.criterion_args:
            cmd += ["--", *args.criterion_args]
        env = dict(os.environ, CARGO_TARGET_DIR=str(target))
        print("+", " ".join(cmd), flush=True)
        if subprocess.run(cmd, cwd=ROOT, env=env).returncode != 0:
            print("wang-scaling: the bench failed", file=sys.stderr)
            return 2
    criterion = target / "criterion"

    n = np.array(SIZES, dtype=float)
    t = np.array([mean_ns(criterion, f"insects/{k}") for k in SIZES]) / 1e6  # ms per step
    b, a = np.polyfit(n, t, 1)
    fit = a + b * n
    r2 = 1.0 - float(np.sum((t - fit) ** 2) / np.sum((t - t.mean()) ** 2))
    print("W-T21 per-step time against N (wang_scaling/insects, mean of criterion):")
    print(f"{'insects':>9} {'ms/step':>10} {'fit':>10} {'ns/insect':>10}")
    for k, tk, fk in zip(SIZES, t, fit):
        print(f"{k:>9} {tk:>10.3f} {fk:>10.3f} {tk * 1e6 / k:>10.1f}")
    print(f"fit: {a:.4f} ms + {b * 1e6:.2f} ns x N, R^2 = {r2:.4f} (>= {MIN_R2})")

    w = {k: mean_ns(criterion, f"world/{k}") / 1e6 for k in WORLDS}
    print("per-step time against the world (wang_scaling/world, 64k insects):")
    print(f"  base        {w['base']:.3f} ms")
    changes = {}
    for k in WORLDS[1:]:
        changes[k] = w[k] / w["base"] - 1.0
        print(f"  {k:<11} {w[k]:.3f} ms, {changes[k] * 100:+.1f} % (|change| < {MAX_CHANGE * 100:.0f} %)")

    ok_r2 = r2 >= MIN_R2
    ok_world = {k: abs(c) < MAX_CHANGE for k, c in changes.items()}
    fails = ([] if ok_r2 else ["R^2"]) + [k for k, ok in ok_world.items() if not ok]
    if fails:
        print("W-T21: FAIL (" + ", ".join(fails) + ")")
        return 1
    print("W-T21: PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
