"""Insect-swarm simulation from Python: the `swarm` command's scenarios, runs and evaluation.

Load a scenario (a built-in name, a TOML file or a ``dict``), override its parameters, run it on
the CPU or the GPU backend and get its trajectories as NumPy arrays and its summary as a
``dict``::

    import swarm

    sc = swarm.Scenario.load("fly-fig1-midges").with_params(gamma=10.0)
    r = swarm.run(sc, steps=200, seed=7)
    r.positions.shape          # (frames, insects, 3), float32
    r.summary["agents"]        # the summary.json of `swarm run`

The same scenario and seed give the same bits, whoever runs them. Every error of the simulator
is a :class:`SwarmError` carrying the `swarm` command's message.
"""

from __future__ import annotations

import copy
import json
import os
from dataclasses import dataclass, field
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _swarm
from ._swarm import SwarmError

__all__ = [
    "Bound",
    "Fit",
    "Member",
    "Parameter",
    "Pool",
    "Run",
    "Scenario",
    "SwarmError",
    "builtin_names",
    "calibrate",
    "ensemble",
    "eval",
    "members",
    "models",
    "parameters",
    "read_tracks",
    "run",
    "run_to",
    "score",
    "search_space",
    "simulate",
]


def builtin_names() -> List[str]:
    """The names of the built-in scenarios (``swarm list``)."""
    return list(_swarm.builtin_names())


def models() -> List[Tuple[str, int, str]]:
    """Every model: its name, its dimensions (2 or 3) and what it is (``swarm models``)."""
    return list(_swarm.models())


class Scenario:
    """A scenario: its TOML table as a ``dict`` (:attr:`data`) and the file it came from
    (:attr:`source`, against which relative paths in it are read; ``None``: the working
    directory).

    Scenarios are values: :meth:`with_params` and :meth:`with_` return changed copies.
    """

    def __init__(self, data: Mapping[str, Any], source: Optional[str] = None) -> None:
        self.data: Dict[str, Any] = copy.deepcopy(dict(data))
        self.source = source

    @classmethod
    def load(cls, name_or_path: str) -> "Scenario":
        """A built-in scenario by name, or a scenario file (TOML)."""
        text, source = _swarm.load(str(name_or_path))
        return cls(json.loads(text), source)

    @classmethod
    def from_dict(cls, data: Mapping[str, Any], source: Optional[str] = None) -> "Scenario":
        """A scenario written as a ``dict`` (the TOML file's table), checked by the scenario
        loader's rules: an error names the field, as for a file."""
        return cls(data, source).checked()

    def checked(self) -> "Scenario":
        """This scenario as the loader reads it (defaults filled in); raises
        :class:`SwarmError` for one that cannot run."""
        text = _swarm.check(json.dumps(self.data), self.source)
        return Scenario(json.loads(text), self.source)

    def to_dict(self) -> Dict[str, Any]:
        """A copy of the scenario's table."""
        return copy.deepcopy(self.data)

    @property
    def name(self) -> str:
        return str(self.data.get("name", ""))

    @property
    def groups(self) -> List[Dict[str, Any]]:
        """The groups' tables (a copy)."""
        return copy.deepcopy(list(self.data.get("groups", [])))

    def with_(self, **fields: Any) -> "Scenario":
        """A copy with top-level fields replaced (``steps``, ``seed``, ``backend``, ...)."""
        data = self.to_dict()
        data.update(copy.deepcopy(fields))
        return Scenario(data, self.source)

    def with_params(self, group: Optional[str] = None, **params: Any) -> "Scenario":
        """A copy with model parameters overridden in the parameter table of group ``group``
        (every group when ``None``): ``with_params(gamma=10.0)``. The run checks them against
        the model's ranges."""
        data = self.to_dict()
        groups = data.get("groups", [])
        chosen = [g for g in groups if group is None or g.get("name") == group]
        if not chosen:
            names = [g.get("name") for g in groups]
            raise SwarmError(f"no group {group!r} in scenario {self.name!r} (groups: {names})")
        for g in chosen:
            table = g.setdefault(g.get("model", ""), {})
            table.update(copy.deepcopy(params))
        return Scenario(data, self.source)

    def __repr__(self) -> str:
        return f"Scenario({self.name!r}, source={self.source!r})"


ScenarioLike = Union[Scenario, str, Mapping[str, Any]]


def _scenario(s: ScenarioLike) -> Scenario:
    if isinstance(s, Scenario):
        return s
    if isinstance(s, str):
        return Scenario.load(s)
    return Scenario(s)


@dataclass
class Run:
    """A finished run: its recorded frames (the first, every ``outputs.every`` steps, and the
    last) as arrays, agents in id order, and its summary."""

    steps: np.ndarray
    """The step of each recorded frame, ``(frames,)``."""
    positions: np.ndarray
    """Positions, ``(frames, agents, 3)`` float32 (2D worlds: z = 0)."""
    headings: np.ndarray
    """Unit headings (velocity directions), ``(frames, agents, 3)`` float32."""
    labels: np.ndarray
    """State label codes, ``(frames, agents)`` uint8 (``summary["state_names"]``)."""
    motions: np.ndarray
    """Motion state codes, ``(frames, agents)`` uint8."""
    roll: np.ndarray
    """Roll angles in degrees, ``(frames, agents)`` float32 (0 for ants)."""
    pitch: np.ndarray
    """Pitch angles in degrees, ``(frames, agents)`` float32 (0 for ants)."""
    groups: np.ndarray
    """Each agent's group index, ``(agents,)`` uint16."""
    summary: Dict[str, Any]
    """``summary.json`` of ``swarm run``."""
    log: List[str] = field(default_factory=list)
    """The lines of ``run.log`` (notes, events, the closing line)."""

    def tracks(self, dt: float) -> Tuple[np.ndarray, float]:
        """The positions as tracks for :func:`eval`: ``(positions as float64, dt)``, ``dt`` the
        time between recorded frames in seconds."""
        return self.positions.astype(np.float64), float(dt)


def run(
    scenario: ScenarioLike,
    *,
    backend: Optional[str] = None,
    seed: Optional[int] = None,
    steps: Optional[int] = None,
    threads: Optional[int] = None,
    progress: bool = False,
) -> Run:
    """Runs ``scenario`` (a :class:`Scenario`, a built-in name, a file or a ``dict``) as
    ``swarm run`` does, writing nothing: ``backend`` ``"cpu"`` or ``"gpu"`` (default: the
    scenario's), ``seed`` and ``steps`` (default: the scenario's), ``threads`` (default: all
    cores; the results do not depend on it). The GIL is released while it runs."""
    sc = _scenario(scenario)
    out = _swarm.run(
        json.dumps(sc.data),
        sc.source,
        backend=backend,
        seed=seed,
        steps=steps,
        threads=threads,
        progress=progress,
    )
    out["summary"] = json.loads(out["summary"])
    return Run(**out)


def run_to(
    scenario: ScenarioLike,
    out: str,
    *,
    backend: Optional[str] = None,
    seed: Optional[int] = None,
    steps: Optional[int] = None,
    threads: Optional[int] = None,
) -> Dict[str, Any]:
    """Runs ``scenario`` as ``swarm run --out OUT`` does: every output (``positions.npy``,
    ``summary.json``, ``run.log``, ...) written whole into folder ``out`` (created, or replaced
    when it holds a run) or nothing at all; returns the summary."""
    sc = _scenario(scenario)
    text = _swarm.run_to(json.dumps(sc.data), sc.source, str(out), backend=backend, seed=seed,
                         steps=steps, threads=threads)
    return json.loads(text)


Tracks = Union[str, "os.PathLike[str]", Tuple[Any, float]]


def _pair(t: Tracks) -> Tracks:
    """A tracks path (``str`` or ``os.PathLike``) as a ``str``, a ``(positions, dt)`` pair as
    float64 positions and a float."""
    if isinstance(t, (str, os.PathLike)):
        return os.fspath(t)
    positions, step = t
    return np.ascontiguousarray(positions, dtype=np.float64), float(step)


def eval(
    reference: Tracks,
    candidates: Sequence[Tracks],
    *,
    dt: Optional[float] = None,
    scaling: str = "separate",
) -> Dict[str, Any]:
    """Scores ``candidates`` against ``reference`` as ``swarm eval`` does (ren2016's seven
    metrics, the energies, the entropy weights and the score E; li2015's polarisation,
    distance to the centroid and accumulated-density difference). Each is a tracks CSV path
    (``dt``: its frame interval when the file does not say) or a ``(positions, dt)`` pair,
    ``positions`` ``(frames, insects, 3)`` with NaN where an insect was not seen
    (:meth:`Run.tracks`). ``scaling``: ``"separate"`` (the paper) or ``"reference"``."""

    text = _swarm.evaluate_tracks(
        _pair(reference), [_pair(c) for c in candidates], dt=dt, scaling=scaling
    )
    return json.loads(text)


# These use the names above.
from .ensemble import Member, Pool, ensemble, members  # noqa: E402
from .calibrate import (  # noqa: E402
    Bound,
    Fit,
    Parameter,
    calibrate,
    parameters,
    read_tracks,
    score,
    search_space,
    simulate,
)
