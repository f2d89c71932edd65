"""Ensembles and sweeps: many runs of one scenario (seeds × parameter sets), each a Ray task.

A member is one deterministic run (:func:`swarm.run`) in its own worker process; the same
member gives the same bits serially, in a local Ray pool or on another machine of a cluster.
Ray is the scheduler: ``ray.init()`` starts a local pool, ``ray.init(address="auto")`` (or
``address="ray://head:10001"``) joins a cluster started with ``ray start --head`` and
``ray start --address=HEAD:6379`` on the workers (see the README).
"""

from __future__ import annotations

import itertools
import os
import sys
import time
from dataclasses import dataclass
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union

from . import Run, Scenario, ScenarioLike, SwarmError, _scenario, run, run_to


@dataclass(frozen=True)
class Member:
    """One run of an ensemble: the parameter overrides (of every group) and the seed."""

    params: Dict[str, Any]
    seed: int


def members(
    seeds: Sequence[int], params: Optional[Sequence[Mapping[str, Any]]] = None
) -> List[Member]:
    """Every parameter set with every seed, parameter sets outermost."""
    sets = [dict(p) for p in (params or [{}])]
    return [Member(p, int(s)) for p, s in itertools.product(sets, seeds)]


class Pool:
    """Runs one function over many items, ``fn(shared, item)`` each: as Ray tasks of
    ``num_cpus`` CPUs (each a worker process) in the Ray of this process (the one already
    initialised, else ``ray.init(address=address)``: ``None`` a local pool of this machine's
    cores, ``"auto"`` or a head's address a cluster), ``shared`` put once in the object store;
    or, without ``use_ray``, one after the other here. Results come back in item order."""

    def __init__(
        self,
        fn: Callable[[Any, Any], Any],
        shared: Any,
        *,
        use_ray: bool = True,
        address: Optional[str] = None,
        num_cpus: float = 1,
    ) -> None:
        self.fn, self.shared, self.use_ray = fn, shared, use_ray
        if use_ray:
            import ray

            if not ray.is_initialized():
                ray.init(address=address, ignore_reinit_error=True, log_to_driver=False)
            self._task = ray.remote(num_cpus=num_cpus)(fn)
            self._shared = ray.put(shared)

    def map(
        self, items: Sequence[Any], on_done: Optional[Callable[[int], None]] = None
    ) -> List[Any]:
        """``fn(shared, item)`` of every item, in item order; ``on_done`` hears how many are
        done (after each item here, about every second on Ray)."""
        if not self.use_ray:
            out = []
            for x in items:
                out.append(self.fn(self.shared, x))
                if on_done:
                    on_done(len(out))
            return out
        import ray

        refs = [self._task.remote(self._shared, x) for x in items]
        if on_done:
            pending = refs
            while pending:
                _, pending = ray.wait(pending, num_returns=len(pending), timeout=1.0,
                                      fetch_local=False)
                on_done(len(refs) - len(pending))
        return list(ray.get(refs))


class Progress:
    """One line on standard error that rewrites itself (``what: 3/16 ...``), finished by a
    newline; silent when not ``shown``."""

    def __init__(self, what: str, total: int, shown: bool) -> None:
        self.what, self.total, self.shown = what, total, shown
        self.start, self.note, self.done = time.monotonic(), "", 0

    def update(self, done: int, note: Optional[str] = None) -> None:
        """Shows ``done`` of the total (the line ends at the total, once)."""
        if not self.shown:
            return
        self.note = self.note if note is None else note
        self.done = done
        took = time.monotonic() - self.start
        end = "\n" if done >= self.total else ""
        sys.stderr.write(f"\r{self.what}: {done}/{self.total} {self.note} [{took:.0f} s]{end}")
        sys.stderr.flush()
        self.shown = not end

    def finish(self, total: Optional[int] = None) -> None:
        """Ends the line (at ``total`` when the work stopped short of the planned total)."""
        if self.shown:
            self.total = self.done if total is None else total
            self.update(self.total)


def per_run_threads(threads: Optional[int], use_ray: bool) -> Optional[int]:
    """A run's threads: those given, else one on Ray (a core per task), else all cores."""
    if threads is not None and threads < 1:
        raise SwarmError(f"threads {threads}: at least 1")
    return threads if threads is not None else (1 if use_ray else None)


@dataclass(frozen=True)
class _Sweep:
    """What every member of an ensemble shares."""

    scenario: Scenario
    steps: Optional[int]
    backend: Optional[str]
    threads: Optional[int]
    out: Optional[str]


def _run_member(sweep: _Sweep, indexed: Tuple[int, Member]) -> Union[Run, str]:
    index, member = indexed
    sc = sweep.scenario.with_params(**member.params) if member.params else sweep.scenario
    args = dict(seed=member.seed, steps=sweep.steps, backend=sweep.backend,
                threads=sweep.threads)
    if sweep.out is None:
        return run(sc, **args)
    folder = os.path.join(sweep.out, f"member-{index:04}")
    run_to(sc, folder, **args)
    return folder


def ensemble(
    scenario: ScenarioLike,
    seeds: Sequence[int],
    params: Optional[Sequence[Mapping[str, Any]]] = None,
    *,
    steps: Optional[int] = None,
    backend: Optional[str] = None,
    threads: Optional[int] = None,
    out: Optional[str] = None,
    use_ray: bool = True,
    address: Optional[str] = None,
    num_cpus: float = 1,
    progress: bool = False,
) -> List[Any]:
    """Runs every member (every parameter set of ``params``, each with every seed of
    ``seeds``) of ``scenario``; returns the runs in member order (:func:`members`).

    With ``use_ray`` (the default) each member is a Ray task of ``num_cpus`` CPUs (a
    :class:`Pool`): ``address`` ``None`` starts a local pool of this machine's cores,
    ``"auto"`` or a head's address joins a cluster. ``use_ray=False`` runs them one after the
    other here, with the same bits. ``threads``: each run's threads (default: 1 on Ray, one
    core per task; all cores one after the other here).

    Without ``out`` the runs come back as :class:`Run` objects (their arrays through Ray's
    object store). With ``out``, a folder every worker can write (a shared file system on a
    cluster), member ``i`` writes its run there as ``swarm run --out OUT/member-000i`` does
    (``positions.npy``, ``summary.json``, ...) and the folders' paths come back. ``progress``
    shows the runs done on standard error."""
    sc = _scenario(scenario)
    if out is not None:
        out = os.path.abspath(out)
        os.makedirs(out, exist_ok=True)
    threads = per_run_threads(threads, use_ray)
    pool = Pool(_run_member, _Sweep(sc, steps, backend, threads, out), use_ray=use_ray,
                address=address, num_cpus=num_cpus)
    todo = list(enumerate(members(seeds, params)))
    bar = Progress("ensemble", len(todo), progress)
    try:
        return pool.map(todo, (lambda done: bar.update(done, "runs")) if progress else None)
    finally:
        bar.finish()
