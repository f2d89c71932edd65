"""Calibration: a model's parameters fitted to measured trajectories by maximising the
evaluation score E, with chen §VI's genetic algorithm or with CMA-ES.

Every individual is the scenario with its parameters written into every group's parameter
table, checked by the model's own rules (an individual they refuse, or whose run fails, scores
worst and is counted), run with the same seeds (common random numbers) for a burn-in and then
recorded, and scored against the reference by E = 1 − (1/7) Σ_φ E_φ (ren2016 Eq. 6 with Step
1's weights; :func:`swarm.score`). A generation's individuals are scored as tasks of
:func:`swarm.ensemble`'s pool: a local Ray pool, a Ray cluster, or one after the other here,
with the same fit.

The search ranges come from the model's own parameter table (:func:`parameters`): a parameter
named alone is searched over its whole range, a range given for it must lie inside the model's.
"""

from __future__ import annotations

import json
import math
import os
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import Scenario, ScenarioLike, SwarmError, Tracks, _pair, _scenario, _swarm
from .ensemble import Pool, Progress, per_run_threads

__all__ = ["Bound", "Fit", "Parameter", "calibrate", "parameters", "read_tracks", "score",
           "search_space", "simulate"]


@dataclass(frozen=True)
class Parameter:
    """One row of a model's parameter table (``swarm.parameters("fly")``)."""

    name: str
    kind: str
    """``"real"`` or ``"int"``."""
    low: float
    high: float
    low_open: bool
    """Whether ``low`` itself is excluded."""
    unit: str

    def __str__(self) -> str:
        if self.kind == "int":
            text = f"an integer from {self.low:g} to {self.high:g}"
        else:
            text = f"a number in {'(' if self.low_open else '['}{self.low:g}, {self.high:g}]"
        return f"{text} ({self.unit})" if self.unit else text


def parameters(model: str) -> List[Parameter]:
    """The parameter table of ``model`` (``"fly"``, ``"bee"``, ...): every parameter a group's
    table may set and the values each may take."""
    return [Parameter(*row) for row in _swarm.parameters(model)]


@dataclass(frozen=True)
class Bound:
    """A parameter to fit and the range searched: ``low`` to ``high``, uniformly in the value,
    or in its logarithm with ``log`` (for a positive range spanning decades)."""

    name: str
    low: float
    high: float
    log: bool = False

    def gene_range(self) -> Tuple[float, float]:
        return (self.gene(self.low), self.gene(self.high))

    def gene(self, value: float) -> float:
        return math.log(value) if self.log else value

    def value(self, gene: float) -> float:
        v = math.exp(gene) if self.log else gene
        return min(max(v, self.low), self.high)


ParamsLike = Union[Sequence[str], Mapping[str, Any]]


def _model_of(sc: Scenario) -> str:
    models = {g.get("model") for g in sc.groups}
    if len(models) != 1:
        raise SwarmError(f"scenario {sc.name!r}: its groups must share one model to calibrate "
                         f"(models: {sorted(map(str, models))})")
    return str(models.pop())


def search_space(scenario: ScenarioLike, params: ParamsLike) -> List[Bound]:
    """The ranges searched for ``params`` of ``scenario``'s model: a list of names (each over
    the model's whole range) or a ``dict`` of name → ``None`` (the model's range), ``(low,
    high)`` or ``(low, high, "log")``, each inside the model's range. A name the model does
    not have, an integer parameter, or a range outside the model's is a :class:`SwarmError`
    naming it."""
    sc = _scenario(scenario)
    model = _model_of(sc)
    table = {p.name: p for p in parameters(model)}
    if isinstance(params, str):
        params = [params]
    if isinstance(params, Mapping):
        given: Mapping[str, Any] = params
    else:
        names = list(params)
        repeated = sorted({n for n in names if names.count(n) > 1})
        if repeated:
            raise SwarmError(f"{', '.join(repeated)}: named more than once")
        given = {n: None for n in names}
    if not given:
        raise SwarmError("nothing to calibrate: name at least one parameter")
    space = []
    for name, bounds in given.items():
        spec = table.get(name)
        if spec is None:
            raise SwarmError(f"{name}: the {model} model has no such parameter "
                             f"(it has: {', '.join(table)})")
        if spec.kind != "real":
            raise SwarmError(f"{name}: {spec}; calibration fits real parameters only")
        if bounds is None:
            # `swarm fit --param NAME`'s range: an open end moved just inside, where both
            # number types the model checks in accept it.
            space.append(Bound(name, *_swarm.whole_range(model, name)))
            continue
        try:
            bounds = list(bounds)
        except TypeError:
            bounds = [bounds]
        if len(bounds) not in (2, 3) or (len(bounds) == 3 and bounds[2] != "log"):
            raise SwarmError(f"{name}: {bounds!r}: give (low, high) or (low, high, \"log\")")
        low, high, log = float(bounds[0]), float(bounds[1]), len(bounds) == 3
        if not (math.isfinite(low) and math.isfinite(high)) or low > high:
            raise SwarmError(f"{name}: {low:g}..{high:g} is not a range (low ≤ high, finite)")
        inside = (low > spec.low if spec.low_open else low >= spec.low) and high <= spec.high
        if not inside:
            raise SwarmError(f"{name}: {low:g}..{high:g} leaves the {model} model's range, "
                             f"{spec}")
        if log and low <= 0:
            raise SwarmError(f"{name}: a log scale needs low > 0, not {low:g}")
        space.append(Bound(name, low, high, log))
    return space


def read_tracks(path: str, dt: Optional[float] = None) -> Tuple[np.ndarray, float]:
    """A tracks CSV file (``id,time,x,y,z``, the evaluation command's format) or a run folder as
    ``(positions, dt)``: positions ``(frames, columns, 3)`` float64, NaN where a column holds
    no insect; ``dt`` the frame interval (given, else the file's). A track takes the first
    column free since at least one frame before it starts (insects lost and numbered anew
    share a column), so the array is about as wide as the most insects seen at once and every
    metric reads the same tracks from it."""
    positions, step = _swarm.read_tracks(os.fspath(path), dt)
    return positions, step


def _tracks(t: Tracks, dt: Optional[float] = None) -> Tuple[np.ndarray, float]:
    if isinstance(t, (str, os.PathLike)):
        return read_tracks(os.fspath(t), dt)
    if dt is not None:
        raise SwarmError("dt is for a tracks file; a (positions, dt) pair carries its own")
    positions, step = _pair(t)
    return positions, float(step)


def score(
    reference: Tracks,
    candidate: Tracks,
    *,
    dt: Optional[float] = None,
    scaling: str = "reference",
) -> float:
    """Calibration's score E of ``candidate`` against ``reference`` (each a tracks CSV path, its
    frame interval ``dt`` when the file does not say, or a ``(positions, dt)`` pair): 1 − (1/7)
    Σ_φ E_φ, ren2016 Eq. 6 with Step 1's weights, each metric z-scored by the reference's
    moments (``scaling="reference"``) or its own (``"separate"``). 1 for identical
    distributions."""
    if dt is not None and not any(isinstance(t, (str, os.PathLike)) for t in (reference, candidate)):
        raise SwarmError("dt is for a tracks file; a (positions, dt) pair carries its own")
    return _swarm.score(_pair(reference), _pair(candidate), dt=dt, scaling=scaling)


def simulate(
    scenario: ScenarioLike,
    *,
    seeds: Sequence[int],
    burn_in: int,
    frames: int,
    every: int = 1,
    backend: Optional[str] = None,
    threads: Optional[int] = None,
) -> np.ndarray:
    """The positions of ``scenario`` run with each seed: after ``burn_in`` ticks, every
    ``every`` ticks for ``frames`` frames, ``(frames, insects, 3)`` float64, the runs'
    insects side by side (what calibration scores); ``threads`` workers (default: all cores;
    the same bits for any count)."""
    sc = _scenario(scenario)
    return _swarm.simulate(json.dumps(sc.data), sc.source, seeds=[int(s) for s in seeds],
                           burn_in=burn_in, frames=frames, every=every, backend=backend,
                           threads=threads)


@dataclass(frozen=True)
class _Job:
    """What every individual of a calibration shares (put once in Ray's object store)."""

    scenario: Scenario
    reference: Tuple[np.ndarray, float]
    seeds: Tuple[int, ...]
    burn_in: int
    frames: int
    every: int
    backend: Optional[str]
    threads: Optional[int]
    scaling: str


def _score_individual(job: _Job, values: Dict[str, float]) -> Union[float, str]:
    """E of the scenario with ``values``, or why the model refused them or the run failed."""
    try:
        sc = job.scenario.with_params(**values).checked()
        positions = simulate(sc, seeds=job.seeds, burn_in=job.burn_in, frames=job.frames,
                             every=job.every, backend=job.backend, threads=job.threads)
    except SwarmError as e:
        return str(e)
    return _swarm.score(job.reference, (positions, job.reference[1]), scaling=job.scaling)


@dataclass
class Fit:
    """A finished calibration."""

    values: Dict[str, float]
    """The best value of each parameter."""
    score: float
    """Its score E."""
    scenario: Scenario
    """The scenario with them."""
    history: List[float]
    """The best score after each generation (non-decreasing)."""
    evaluations: int
    """Individuals scored."""
    refused: int
    """Individuals the model's rules refused or whose run failed (scored worst)."""
    method: str
    space: List[Bound] = field(default_factory=list)
    """The ranges searched."""


class _Best:
    """The best individual scored so far (CMA-ES keeps no elite of its own)."""

    def __init__(self) -> None:
        self.genes: List[float] = []
        self.score = -math.inf

    def see(self, genes: Sequence[float], scores: Sequence[float]) -> None:
        for g, s in zip(genes, scores):
            if s > self.score:
                self.genes, self.score = list(g), s


def calibrate(
    scenario: ScenarioLike,
    reference: Tracks,
    params: ParamsLike,
    *,
    method: str = "ga",
    dt: Optional[float] = None,
    seeds: Optional[Sequence[int]] = None,
    burn_in: int = 200,
    frames: int = 500,
    every: int = 1,
    scaling: str = "reference",
    population: Optional[int] = None,
    generations: Optional[int] = None,
    crossover: Optional[float] = None,
    mutation: Optional[float] = None,
    sigma: float = 0.3,
    seed: int = 1,
    backend: Optional[str] = None,
    threads: Optional[int] = None,
    use_ray: bool = True,
    address: Optional[str] = None,
    num_cpus: float = 1,
    on_generation: Optional[Callable[[int, float], None]] = None,
    progress: bool = False,
) -> Fit:
    """Fits ``params`` of ``scenario`` (:func:`search_space`) to ``reference`` (a tracks CSV
    path, ``dt`` its frame interval when the file does not say, or a ``(positions, dt)``
    pair) by maximising E (:func:`score`).

    Each individual runs the scenario with every seed of ``seeds`` (default: the scenario's),
    ``burn_in`` ticks and then ``frames`` frames of ``every`` ticks (the reference's frame
    interval). ``method``: ``"ga"``, chen §VI's genetic algorithm as ``swarm fit`` runs it
    (``population`` 20 × ``generations`` 100, ``crossover`` 0.9, ``mutation`` 0.15 per gene
    by default; chen prints 10 × 200, 0.9, 0.01), or ``"cma"``, CMA-ES (the ``cma`` package;
    ``population`` default 4 + 3 ln d, ``generations`` default 100, initial step ``sigma``
    as a share of each range, started at the ranges' middle; it may stop before its last
    generation when its step has shrunk to nothing; two parameters or more). ``seed`` (a
    positive integer) seeds the search. Each generation is scored by the pool of
    :func:`swarm.ensemble` (``use_ray``, ``address``, ``num_cpus``; ``threads`` per run as
    there, on ``backend``); the fit is the same either way. ``on_generation`` hears the generation and
    the best score so far; ``progress`` shows them on standard error.

    Individuals the model's rules refuse, or whose run fails, score worst and are counted
    (:attr:`Fit.refused`); a first generation refused whole ends the fit with the first
    refusal's message."""
    sc = _scenario(scenario).checked()
    space = search_space(sc, params)
    ref = _tracks(reference, dt)
    if frames < 3 or burn_in < 0 or every < 1:
        raise SwarmError(f"frames {frames}, burn_in {burn_in}, every {every}: at least 3 frames, "
                         "a burn-in of 0 or more and 1 tick a frame")
    _check_search(method, len(space), population, generations, crossover, mutation, sigma, seed)
    # A misspelt name or a range the model cannot take fails here, not 2,000 runs later.
    middle = {b.name: b.value(sum(b.gene_range()) / 2) for b in space}
    sc.with_params(**middle).checked()
    job = _Job(sc, ref, tuple(int(s) for s in (seeds or [sc.data.get("seed", 1)])), burn_in,
               frames, every, backend, per_run_threads(threads, use_ray), scaling)
    pool = Pool(_score_individual, job, use_ray=use_ray, address=address, num_cpus=num_cpus)
    refusals: List[str] = []
    scored = 0

    def judge(genes: Sequence[Sequence[float]]) -> List[float]:
        nonlocal scored
        values = [{b.name: b.value(g) for b, g in zip(space, x)} for x in genes]
        out = pool.map(values)
        refusals.extend(r for r in out if isinstance(r, str))
        scored += sum(not isinstance(r, str) for r in out)
        if not scored:
            raise SwarmError(f"the model refused every individual of the first generation, or "
                             f"its runs failed; the first: {refusals[0]}")
        return [math.nan if isinstance(r, str) else float(r) for r in out]

    ranges = [b.gene_range() for b in space]
    bar = Progress(f"calibrate ({method})", generations or 100, progress)

    def heard(generation: int, best: float) -> None:
        bar.update(generation, f"generations, best E {best:.4f}")
        if on_generation:
            on_generation(generation, best)

    try:
        if method == "ga":
            best, history, evaluations = _by_ga(ranges, judge, population, generations,
                                                crossover, mutation, seed, heard)
        else:
            best, history, evaluations = _by_cma(ranges, judge, population, generations, sigma,
                                                 seed, heard)
    finally:
        bar.finish()  # CMA-ES may stop before its last generation
    values = {b.name: b.value(g) for b, g in zip(space, best.genes)}
    return Fit(values, best.score, sc.with_params(**values).checked(), history, evaluations,
               len(refusals), method, space)


def _check_search(method: str, genes: int, population: Optional[int],
                  generations: Optional[int], crossover: Optional[float],
                  mutation: Optional[float], sigma: float, seed: int) -> None:
    """Refuses a search that cannot run, before any process starts."""
    if method not in ("ga", "cma"):
        raise SwarmError(f"method {method!r}: \"ga\" or \"cma\"")
    if population is not None and population < 2:
        raise SwarmError(f"population {population}: at least 2 individuals")
    if generations is not None and generations < 1:
        raise SwarmError(f"generations {generations}: at least 1")
    for name, p in [("crossover", crossover), ("mutation", mutation)]:
        if p is not None and not 0 <= p <= 1:
            raise SwarmError(f"{name} {p}: not a probability")
    if not 0 < sigma <= 1:
        raise SwarmError(f"sigma {sigma}: a share of each range in (0, 1]")
    if not 1 <= seed < 2**32:
        raise SwarmError(f"seed {seed}: a positive 32-bit integer (cma takes 0 as \"from the "
                         "clock\")")
    if method == "cma" and genes < 2:
        raise SwarmError("CMA-ES needs at least two parameters (the cma package's bounds do not "
                         "work in one dimension); fit one with method=\"ga\"")


Judge = Callable[[Sequence[Sequence[float]]], List[float]]


def _by_ga(ranges, judge: Judge, population, generations, crossover, mutation, seed,
           on_generation) -> Tuple[_Best, List[float], int]:
    ga = _swarm.GeneticAlgorithm(ranges, population=population, generations=generations,
                                 crossover=crossover, mutation=mutation, seed=seed)
    while not ga.done:
        ga.tell(judge(ga.ask()))
        if on_generation:
            on_generation(len(ga.history), ga.history[-1])
    genes, top, evaluations = ga.best()
    best = _Best()
    best.see([genes], [top])
    return best, ga.history, evaluations


def _by_cma(ranges, judge: Judge, population, generations, sigma, seed,
            on_generation) -> Tuple[_Best, List[float], int]:
    import warnings

    with warnings.catch_warnings():  # cma warns when matplotlib is missing (only its plots need it)
        warnings.simplefilter("ignore")
        import cma

    low = np.array([r[0] for r in ranges])
    span = np.array([r[1] - r[0] for r in ranges])
    options = {"bounds": [0.0, 1.0], "seed": int(seed), "maxiter": int(generations or 100),
               "verbose": -9, "tolfun": 0, "tolflatfitness": 1000}
    if population:
        options["popsize"] = int(population)
    # CMA-ES searches the unit cube (one step size for ranges of any width); cma minimises.
    es = cma.CMAEvolutionStrategy([0.5] * len(ranges), sigma, options)
    best, history, evaluations = _Best(), [], 0
    while not es.stop():
        unit = es.ask()
        genes = [list(low + span * np.asarray(u)) for u in unit]
        scores = judge(genes)
        evaluations += len(scores)
        best.see(genes, scores)
        worst = min([s for s in scores if not math.isnan(s)], default=0.0) - 1.0
        es.tell(unit, [-(worst if math.isnan(s) else s) for s in scores])
        history.append(best.score)
        if on_generation:
            on_generation(len(history), best.score)
    return best, history, evaluations
