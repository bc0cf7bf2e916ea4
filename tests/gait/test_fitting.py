"""Tests of mjwalk.gait.fitting: first steps, captured transitions, KDE starters, GP fitter."""

from __future__ import annotations

import numpy as np
import pytest
from test_features import make_steps

from mjwalk.errors import MjwalkError
from mjwalk.gait.features import StepFeatures, raw_features, side_array
from mjwalk.gait.fitting import GPFitter, first_step_indices, fit_starters, transition_pairs


@pytest.fixture(scope="module")
def steps():
    return make_steps(np.random.default_rng(0), n_takes=80, steps_per_take=15)


@pytest.fixture(scope="module")
def encoded(steps):
    raw = raw_features(steps)
    z = StepFeatures.fit(raw, variance=0.95).encode_raw(raw)
    return z, side_array(steps)


def test_pairs_and_first_steps(steps):
    prev, nxt = transition_pairs(steps)
    assert len(prev) == 80 * 14
    assert all(steps[i].side != steps[j].side for i, j in zip(prev, nxt, strict=True))
    first = first_step_indices(steps)
    assert len(first) == 80 and all(steps[i].index == 0 for i in first)


def test_starters_fall_back_to_all_steps(steps, encoded):
    z, sides = encoded
    first = first_step_indices(steps)
    data, factor, source = fit_starters(z, sides, first)
    for s in ("left", "right"):
        n = int((sides[first] == s).sum())
        assert data[s].shape == (z.shape[1], n) and source[s] == {"source": "first steps", "n": n}
        assert factor[s] == pytest.approx(n ** (-1.0 / (z.shape[1] + 4)))  # Scott's factor
    # two first steps are too few for a KDE of d >= 2 dimensions: all steps of the side instead
    data, _, source = fit_starters(z, sides, first[:2])
    assert source["left"]["source"].startswith("all steps")
    assert data["left"].shape[1] == int((sides == "left").sum())
    with pytest.raises(MjwalkError, match="KDE"):
        fit_starters(z[:4], sides[:4], first_step_indices(steps[:4]))


def test_gp_fitter_skips_sides_with_too_few_pairs(steps, encoded):
    z, sides = encoded
    prev, nxt = transition_pairs(steps)
    rng = np.random.default_rng(0)
    fitter = GPFitter(z, sides, rng, n_hyper=50, progress=False)
    state = rng.bit_generator.state
    gps, counts = fitter.fit("GP ", prev, nxt, len(prev), lambda n: 10, None)
    assert gps == {} and sum(counts.values()) == len(prev)
    assert rng.bit_generator.state == state  # nothing fitted, nothing drawn
