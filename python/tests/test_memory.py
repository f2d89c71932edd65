"""GPU runs leave nothing behind: ``swarm.run(..., backend="gpu")`` in a loop, and Ray workers
taking GPU ensemble task after task, hold the memory of their first runs (one device per
process, kernels compiled once)."""

import gc
import os
from pathlib import Path
from typing import Dict

import swarm
from test_swarm import fixed

#: Runs before the baseline is read: the first opens the device and compiles the kernels.
WARM_UP = 2
#: The most resident memory the later runs may add, in MiB.
MAX_GROWTH_MIB = 100


def resident_mib(pid: object = "self") -> float:
    """Resident memory of process ``pid`` in MiB (``VmRSS``)."""
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) / 1024
    raise AssertionError(f"no VmRSS for process {pid}")


def gpu_workers() -> Dict[int, float]:
    """The Ray worker processes of this machine that have a Vulkan driver loaded (those that
    ran a GPU task) and their resident memory in MiB."""
    out = {}
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit() or int(entry.name) == os.getpid():
            continue
        try:
            if not (entry / "cmdline").read_bytes().startswith(b"ray::"):
                continue
            if "libvulkan" not in (entry / "maps").read_text():
                continue
            out[int(entry.name)] = resident_mib(entry.name)
        except OSError:  # the process ended, or is not ours
            continue
    return out


def test_gpu_runs_in_a_loop_hold_memory_flat():
    sc = fixed("li-fig4-confined")
    base = None
    for i in range(20):
        r = swarm.run(sc, steps=20, seed=i + 1, backend="gpu")
        assert r.summary["backend"] == "gpu"
        del r
        gc.collect()
        if i + 1 == WARM_UP:
            base = resident_mib()
    growth = resident_mib() - base
    print(f"20 GPU runs: {growth:+.1f} MiB after the first {WARM_UP}")
    assert growth <= MAX_GROWTH_MIB, (
        f"20 GPU runs in one process grew resident memory by {growth:.0f} MiB after the "
        f"first {WARM_UP} (at most {MAX_GROWTH_MIB})"
    )


def test_a_gpu_ensemble_on_ray_holds_worker_memory_flat(ray_pool):
    sc = fixed("li-fig4-confined")
    cpus = int(ray_pool.cluster_resources()["CPU"])
    # Warm-up: every worker takes its first runs (device, kernels).
    first = swarm.ensemble(sc, seeds=range(1, WARM_UP * cpus + 1), steps=20, backend="gpu")
    assert all(r.summary["backend"] == "gpu" for r in first)
    before = gpu_workers()
    assert before, "no Ray worker ran on the GPU"
    runs = swarm.ensemble(sc, seeds=range(100, 100 + 10 * cpus), steps=20, backend="gpu")
    assert len(runs) == 10 * cpus
    after = gpu_workers()
    kept = sorted(set(before) & set(after))
    assert kept, f"the GPU workers {sorted(before)} are gone: {sorted(after)}"
    for pid in kept:
        growth = after[pid] - before[pid]
        print(f"Ray worker {pid}: {growth:+.1f} MiB over the ensemble")
        assert growth <= MAX_GROWTH_MIB, (
            f"Ray worker {pid} grew by {growth:.0f} MiB over {10 * cpus} GPU runs after its "
            f"first (at most {MAX_GROWTH_MIB})"
        )
