"""Tests of mjwalk.gait.transition: fitting, predicting and saving a transition GP."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.errors import MjwalkError
from mjwalk.gait.transition import TransitionGP


@pytest.fixture(scope="module")
def gp():
    rng = np.random.default_rng(0)
    x = rng.standard_normal((120, 2))
    y = np.column_stack([0.8 * x[:, 0], -0.5 * x[:, 1]]) + 0.1 * rng.standard_normal((120, 2))
    return TransitionGP.fit(x, y, rng=np.random.default_rng(1), n_hyper=60, n_inducing=20), x, y


def test_fit_learns_the_mapping(gp):
    g, x, y = gp
    assert g.inducing.shape == (20, 2) and g.res_pool.shape == (20, 6, 2)  # ceil(120 / 20)
    mean, var = g.predict(x)
    assert mean.shape == (120, 2) and var.shape == (120,) and np.all(var >= 0)
    assert np.mean((mean - y) ** 2) < 0.05
    assert g.kernel_rows(x[:3]).shape == (3, 20)
    draws = g.sample(x[:4], 5, np.random.default_rng(2))
    assert draws.shape == (4, 5, 2) and np.all(np.isfinite(draws))


def test_arrays_roundtrip(gp):
    g, x, _ = gp
    back = TransitionGP.from_arrays(g.arrays("p_"), "p_")
    assert np.array_equal(back.predict(x)[0], g.predict(x)[0]) and back.n_pairs == 120


def test_too_few_pairs():
    with pytest.raises(MjwalkError, match="at least 5"):
        TransitionGP.fit(np.zeros((4, 2)), np.zeros((4, 2)), rng=np.random.default_rng(0))


def test_the_mean_reach_bounds_the_mean_everywhere(gp):
    """mean_reach: f(x) = μ(x)·v stays within r·√(2(1 - k(x, z_j)/C)) of f(z_j) for every
    inducing input j, at the data, between and far from it (the RKHS bound); the bound is
    not vacuous: at an inducing input it is 0 and f_z is f there."""
    g, x, _ = gp
    v = np.array([0.3 - 0.2j, -0.1 + 0.4j])
    r, f_z, slack = g.mean_reach(v)
    rng = np.random.default_rng(5)
    probes = np.vstack([x, 3.0 * rng.standard_normal((300, 2)), g.inducing + 0.01])
    f = g.predict(probes)[0] @ v
    e = g.kernel_rows(probes) / g.signal_var
    bound = r * np.sqrt(2.0 * np.maximum(1.0 - e, 0.0)) + slack + 1e-9
    assert np.all(np.abs(f[:, None] - f_z[None, :]) <= bound)
    np.testing.assert_allclose(g.predict(g.inducing)[0] @ v, f_z, atol=1e-9)
    assert 0.0 < r < np.abs(g.alpha @ v).sum() * g.signal_var  # tighter than Σ|k α v|
