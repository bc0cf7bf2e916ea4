"""Fidelity metrics and report: sway definition, straight walks, KS figures, table, entry points."""

from __future__ import annotations

import json

import numpy as np
import pytest
from test_features import make_steps

from mjwalk.errors import MjwalkError
from mjwalk.gait.fidelity import (
    capture_step_metrics,
    fidelity_from_steps,
    format_fidelity_table,
    load_capture,
    sway_amplitude,
)
from mjwalk.gait.model import StepModel
from mjwalk.gait.straight import captured_straight_walks, model_straight_walks


@pytest.fixture(scope="module")
def steps():
    return make_steps(np.random.default_rng(2), n_takes=60, steps_per_take=16, stops=True)


@pytest.fixture(scope="module")
def model(steps):
    return StepModel.fit(steps, seed=0, variance=0.95, n_hyper=200, n_inducing=60)


def test_sway_amplitude_is_half_peak_to_peak_from_chord():
    u = np.linspace(0, 1, 101)
    # chord along +y, lateral sine of amplitude 3 cm: half peak-to-peak = 0.03
    p = np.column_stack([0.03 * np.sin(2 * np.pi * u), 0.6 * u])
    assert sway_amplitude(p) == pytest.approx(0.03, abs=1e-4)
    # one-sided bulge of 2 cm: half peak-to-peak = 0.01; invariant to rotation
    q = np.column_stack([0.02 * np.sin(np.pi * u), 0.6 * u])
    rot = np.array([[np.cos(0.7), -np.sin(0.7)], [np.sin(0.7), np.cos(0.7)]])
    np.testing.assert_allclose(sway_amplitude(np.stack([q, q @ rot.T])), 0.01, atol=1e-6)


def test_captured_straight_walks_compose_steps(steps):
    walks = captured_straight_walks(steps, straight_deg=180.0)
    assert len(walks) == 60
    i = int(
        np.argmin([abs(sum(s.end_yaw for s in steps[j * 16 : j * 16 + 16])) for j in range(60)])
    )
    w = walks[i]
    assert w["n_steps"] == 16
    # a straight synthetic walk: distance close to the sum of step lengths, path a bit longer
    take = steps[i * 16 : i * 16 + 16]
    assert w["distance"] <= sum(s.length for s in take) + 1e-9
    assert w["distance"] > 0.9 * sum(s.length for s in take)
    assert w["path_length"] >= w["distance"]
    assert w["time"] == pytest.approx(sum(s.duration for s in take))
    assert captured_straight_walks(steps, straight_deg=0.0) == []


def test_model_straight_walks_reach_the_goal(model):
    d = np.array([3.0, 5.0, 8.0])
    walks = model_straight_walks(model, d, np.random.default_rng(0))
    for w, dist in zip(walks, d, strict=True):
        assert w["end_error"] < 0.45  # stops within about half a step
        assert dist - 0.45 < w["path_length"] < 1.15 * dist
        assert w["n_steps"] == pytest.approx(dist / 0.6, rel=0.35)


def test_fidelity_report_in_sample(model, steps):
    """Seeded: the model's chains match the steps it was trained on (KS <= 0.2 at n~800);
    steady state against steady state, KDE starters against the captured initiations."""
    rep = fidelity_from_steps(model, steps, np.random.default_rng(0), n_chains=120)
    json.dumps(rep)
    steady = [s for s in steps if not (s.meta["initiation"] or s.meta["termination"])]
    cap = capture_step_metrics(steady)
    assert rep["n_capture_steps"] == 60 * 14 and rep["n_model_steps"] == 120 * 7
    for k in ("length", "duration", "sway"):
        assert rep["steps"][k]["ks"] < 0.2, (k, rep["steps"][k])
        assert rep["steps"][k]["capture"]["mean"] == pytest.approx(cap[k].mean())
    ini = rep["initiation"]
    assert ini["n_capture"] == 60 and ini["n_model"] == 120
    assert ini["length"]["ks"] < 0.3  # 60 vs 120 steps: the 5 % critical value is ~0.21
    # model durations are compared as played back at the capture's 120 Hz (whole frames)
    frames = np.array(rep["steps"]["duration"]["model"]["median"]) * 120.0
    assert frames == pytest.approx(round(float(frames)), abs=1e-9)
    w = rep["straight_walks"]
    assert w["n"] == len(captured_straight_walks(steps)) > 10
    c, m = w["path_length"]["capture"], w["path_length"]["model"]
    assert m["median"] == pytest.approx(c["median"], rel=0.1)
    table = format_fidelity_table(rep)
    assert "length [m]" in table and "path_length [m]" in table and "gait initiation" in table


def test_entry_points_errors(tmp_path):
    with pytest.raises(MjwalkError, match="no BVH files match"):
        load_capture(bvh=str(tmp_path / "*.bvh"))
    with pytest.raises(MjwalkError, match="without its ASF"):
        load_capture(amc=str(tmp_path / "*.amc"))
