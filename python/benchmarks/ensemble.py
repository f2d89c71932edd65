"""Ensemble throughput: runs per minute one after the other vs on a local Ray pool, and Ray's
overhead per task (docs/benchmarks.md).

    target/python-venv/bin/python python/benchmarks/ensemble.py [--workers 2] [--runs 16]
        [--rounds 2] [--json out.json]

Each member is ``--scenario`` (default: fly-fig1-midges, 100 midges) for ``--steps`` ticks
(default: the scenario's, 2,000 there) on one thread, recorded in memory. The serial pass and the Ray pass alternate ``--rounds`` times
(hosts drift; interleaving keeps the comparison fair). The overhead per task is the round trip
of a one-tick member of 10 insects sent to Ray one at a time, less the same call made here.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import time

import swarm


def cpu_name() -> str:
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def timed(fn) -> float:
    t = time.perf_counter()
    fn()
    return time.perf_counter() - t


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scenario", default="fly-fig1-midges")
    ap.add_argument("--steps", type=int, help="ticks per member (default: the scenario's)")
    ap.add_argument("--runs", type=int, default=16, help="members per pass")
    ap.add_argument("--workers", type=int, default=2, help="Ray worker processes")
    ap.add_argument("--rounds", type=int, default=2, help="serial/Ray alternations")
    ap.add_argument("--json", help="write the figures here")
    a = ap.parse_args()

    import ray

    ray.init(num_cpus=a.workers, include_dashboard=False, log_to_driver=False)
    seeds = list(range(1, a.runs + 1))
    sc = swarm.Scenario.load(a.scenario)
    # Warm up: the workers start and import the package once.
    swarm.ensemble(sc, seeds[: a.workers], steps=2)

    serial, pooled = [], []
    for _ in range(a.rounds):
        serial.append(timed(lambda: swarm.ensemble(sc, seeds, steps=a.steps, threads=1,
                                                   use_ray=False)))
        pooled.append(timed(lambda: swarm.ensemble(sc, seeds, steps=a.steps, threads=1)))

    tiny = sc.with_(groups=[dict(sc.groups[0], count=10)])
    task = ray.remote(num_cpus=1)(lambda s: swarm.run(s, steps=1, threads=1).positions.shape)
    ref = ray.put(tiny)
    ray.get(task.remote(ref))
    trips = [timed(lambda: ray.get(task.remote(ref))) for _ in range(50)]
    direct = [timed(lambda: swarm.run(tiny, steps=1, threads=1)) for _ in range(50)]
    overhead = statistics.median(trips) - statistics.median(direct)
    ray.shutdown()

    per_min = lambda secs: 60.0 * a.runs / statistics.median(secs)  # noqa: E731
    result = {
        "machine": f"{cpu_name()}, {os.cpu_count()} cores",
        "scenario": a.scenario,
        "steps": a.steps or sc.data["steps"],
        "runs": a.runs,
        "workers": a.workers,
        "serial_s": serial,
        "ray_s": pooled,
        "serial_runs_per_min": per_min(serial),
        "ray_runs_per_min": per_min(pooled),
        "speedup": statistics.median(serial) / statistics.median(pooled),
        "task_round_trip_ms": 1e3 * statistics.median(trips),
        "direct_call_ms": 1e3 * statistics.median(direct),
        "overhead_per_task_ms": 1e3 * overhead,
    }
    print(json.dumps(result, indent=2))
    if a.json:
        with open(a.json, "w") as f:
            json.dump(result, f, indent=2)


if __name__ == "__main__":
    main()
