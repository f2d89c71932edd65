"""The `swarm` Python package: scenarios, runs, arrays, errors and evaluation (pytest)."""

import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

import swarm

REPO = Path(__file__).resolve().parents[2]


def fixed(name: str) -> swarm.Scenario:
    """Built-in scenario ``name`` with every group in fixed point (the same bits everywhere)."""
    data = swarm.Scenario.load(name).to_dict()
    for g in data["groups"]:
        g["scalar"] = "fixed"
    return swarm.Scenario(data)


def test_the_built_ins_and_models_are_listed():
    names = swarm.builtin_names()
    assert "fly-fig1-midges" in names and "li-fig4-confined" in names
    models = {name: dim for name, dim, _ in swarm.models()}
    assert models["ant"] == 2 and models["fly"] == 3 and models["li"] == 3


def test_a_run_gives_arrays_and_the_summary():
    r = swarm.run("fly-fig1-midges", steps=30, seed=3)
    every = swarm.Scenario.load("fly-fig1-midges").data["outputs"]["every"]
    frames = 30 // every + 1
    assert r.positions.shape == (frames, 100, 3) and r.positions.dtype == np.float32
    assert r.headings.shape == (frames, 100, 3)
    assert r.labels.shape == (frames, 100) and r.labels.dtype == np.uint8
    assert list(r.steps) == [k * every for k in range(frames)]
    assert r.groups.shape == (100,) and not r.groups.any()
    assert r.summary["agents"] == 100 and r.summary["steps"] == 30 and r.summary["seed"] == 3
    assert r.summary["backend"] == "cpu"
    assert any(line.startswith("done: 30 ticks") for line in r.log)
    # The swarm moved, and stayed in its box.
    assert np.abs(r.positions[-1] - r.positions[0]).max() > 0
    assert (r.positions >= 0).all() and (r.positions <= 20).all()


def test_the_same_seed_gives_the_same_bits():
    a = swarm.run("li-fig4-confined", steps=40, seed=5, threads=1)
    b = swarm.run("li-fig4-confined", steps=40, seed=5, threads=2)
    c = swarm.run("li-fig4-confined", steps=40, seed=6)
    assert a.positions.tobytes() == b.positions.tobytes()
    assert a.positions.tobytes() != c.positions.tobytes()


def test_a_dict_runs_as_its_file():
    sc = swarm.Scenario.load("wang-fig9-aggregation")
    again = swarm.Scenario.from_dict(json.loads(json.dumps(sc.to_dict())))
    a = swarm.run(sc, steps=20)
    b = swarm.run(again, steps=20)
    assert a.positions.tobytes() == b.positions.tobytes()


def test_the_command_line_writes_the_same_positions(tmp_path):
    """`swarm run` (the command scripts/python-test.sh builds) and `swarm.run` agree byte for
    byte."""
    exe = Path(os.environ.get("SWARM_EXE", REPO / "target" / "ci" / "swarm"))
    assert exe.exists(), f"{exe}: build the swarm command (cargo build --profile ci)"
    out = tmp_path / "run"
    subprocess.run(
        [str(exe), "run", "fly-fig8-escape", "--steps", "25", "--seed", "4", "--out", str(out),
         "--quiet"],
        check=True,
        capture_output=True,
    )
    npy = np.load(out / "positions.npy")
    r = swarm.run("fly-fig8-escape", steps=25, seed=4)
    assert npy.shape == r.positions.shape
    assert npy.tobytes() == r.positions.tobytes()


def test_parameters_are_overridden_and_checked():
    sc = swarm.Scenario.load("fly-fig1-midges")
    base = swarm.run(sc, steps=20)
    changed = swarm.run(sc.with_params(gamma=8.0), steps=20)
    assert base.positions.tobytes() != changed.positions.tobytes()
    with pytest.raises(swarm.SwarmError, match="gamma"):
        swarm.run(sc.with_params(gamma=-1.0), steps=20)
    with pytest.raises(swarm.SwarmError, match="no group 'bees'"):
        sc.with_params("bees", gamma=1.0)


def test_errors_carry_the_commands_messages():
    with pytest.raises(swarm.SwarmError, match="no-such-scenario"):
        swarm.Scenario.load("no-such-scenario")
    with pytest.raises(swarm.SwarmError, match="steps"):
        swarm.run("fly-fig1-midges", steps=0)
    bad = swarm.Scenario.load("fly-fig1-midges").to_dict()
    bad["groups"][0]["count"] = "many"
    with pytest.raises(swarm.SwarmError, match="count"):
        swarm.Scenario.from_dict(bad)
    with pytest.raises(ValueError, match="backend"):
        swarm.run("fly-fig1-midges", steps=5, backend="tpu")


def test_the_gpu_backend_gives_the_cpus_bits():
    """Fixed point on the GPU (lavapipe where there is none) is the CPU's, bit for bit."""
    sc = fixed("li-fig6-lights")
    cpu = swarm.run(sc, steps=15, backend="cpu")
    gpu = swarm.run(sc, steps=15, backend="gpu")
    assert gpu.summary["backend"] == "gpu"
    assert cpu.positions.tobytes() == gpu.positions.tobytes()


def test_eval_scores_candidates_against_a_reference():
    ref = swarm.run("fly-fig1-midges", steps=200, seed=1)
    same = swarm.run("fly-fig1-midges", steps=200, seed=2)
    other = swarm.run(swarm.Scenario.load("fly-fig1-midges").with_params(chi_att=0.0),
                      steps=200, seed=2)
    dt = 0.01 * 10  # Δt × outputs.every
    report = swarm.eval(ref.tracks(dt), [same.tracks(dt), other.tracks(dt)],
                        scaling="reference")
    rows = report["candidates"]
    assert len(rows) == 2 and rows[0]["path"] == "candidate 0"
    assert set(report["weights"]) == {"v", "a", "omega", "alpha", "mu", "d", "eta"}
    assert rows[0]["score"] > rows[1]["score"]
    with pytest.raises(ValueError, match="scaling"):
        swarm.eval(ref.tracks(dt), [same.tracks(dt)], scaling="log")


def test_an_ensemble_on_ray_gives_the_serial_bits(ray_pool):
    """8 members (2 parameter sets × 4 seeds) as Ray tasks: the same bits as one after the
    other, in member order."""
    params = [{"gamma": 8.0}, {"gamma": 11.16}]
    seeds = [1, 2, 3, 4]
    serial = swarm.ensemble("fly-fig1-midges", seeds, params, steps=30, use_ray=False)
    pooled = swarm.ensemble("fly-fig1-midges", seeds, params, steps=30)
    assert len(pooled) == len(serial) == 8
    for a, b, m in zip(serial, pooled, swarm.members(seeds, params)):
        assert a.summary["seed"] == b.summary["seed"] == m.seed
        assert a.positions.tobytes() == b.positions.tobytes()
    assert len({r.positions.tobytes() for r in pooled}) == 8, "every member differs"
    # The runs did go to Ray's workers (two processes).
    assert ray_pool.cluster_resources().get("CPU") == 2
