"""Ensembles and sweeps: many runs of one scenario (seeds × parameter sets), each a Ray task.

A member is one deterministic run (:func:`swarm.run`) in its own worker process; the same
member gives the same bits serially, in a local Ray pool or on another machine of a cluster.
Ray is the scheduler: ``ray.init()`` starts a local pool, ``ray.init(address="auto")`` (or
``address="ray://head:10001"``) joins a cluster started with ``ray start --head`` and
``ray start --address=HEAD:6379`` on the workers (see the README).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from typing import Any, Dict, List, Mapping, Optional, Sequence

from . import Run, Scenario, ScenarioLike, _scenario, run


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


def _run_member(
    scenario: Scenario,
    member: Member,
    steps: Optional[int],
    backend: Optional[str],
    threads: Optional[int],
) -> Run:
    sc = scenario.with_params(**member.params) if member.params else scenario
    return run(sc, seed=member.seed, steps=steps, backend=backend, threads=threads)


def ensemble(
    scenario: ScenarioLike,
    seeds: Sequence[int],
    params: Optional[Sequence[Mapping[str, Any]]] = None,
    *,
    steps: Optional[int] = None,
    backend: Optional[str] = None,
    threads: Optional[int] = 1,
    use_ray: bool = True,
    address: Optional[str] = None,
    num_cpus: float = 1,
) -> List[Run]:
    """Runs every member (every parameter set of ``params``, each with every seed of
    ``seeds``) of ``scenario``; returns the runs in member order (:func:`members`).

    With ``use_ray`` (the default) each member is a Ray task of ``num_cpus`` CPUs, in the Ray
    of this process: the one already initialised, else ``ray.init(address=address)`` (``None``:
    a local pool of this machine's cores; ``"auto"`` or a head's address: a cluster). The
    arrays come back through Ray's object store. ``use_ray=False`` runs them one after the
    other here, with the same bits. ``threads``: each run's threads (1: one core per task)."""
    sc = _scenario(scenario)
    todo = members(seeds, params)
    if not use_ray:
        return [_run_member(sc, m, steps, backend, threads) for m in todo]
    import ray

    if not ray.is_initialized():
        ray.init(address=address, ignore_reinit_error=True, log_to_driver=False)
    task = ray.remote(num_cpus=num_cpus)(_run_member)
    scenario_ref = ray.put(sc)
    refs = [task.remote(scenario_ref, m, steps, backend, threads) for m in todo]
    return list(ray.get(refs))
