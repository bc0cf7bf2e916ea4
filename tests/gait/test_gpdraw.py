"""Tests of mjwalk.gait.gpdraw: the compiled transition-GP moments and packed quadratic form."""

from __future__ import annotations

import numpy as np
from test_transition import gp  # noqa: F401  (module fixture)

from mjwalk.gait import gpdraw


def test_pack_upper_gives_the_quadratic_form():
    rng = np.random.default_rng(0)
    a = rng.standard_normal((5, 5))
    w = a + a.T
    e = rng.standard_normal(5)
    i, j = np.triu_indices(5)
    assert gpdraw.pack_upper(w).shape == (15,)
    assert np.isclose(np.sum(e[i] * gpdraw.pack_upper(w) * e[j]), e @ w @ e)


def test_compiled_moments_match_the_dense_predictor(gp):  # noqa: F811
    g, x, _ = gp
    mean, var, h = gpdraw.moments(np.ascontiguousarray(x[:7]), g.kernel)
    m_ref, v_ref = g.predict(x[:7])
    assert np.allclose(mean, m_ref, atol=1e-10) and np.allclose(
        np.maximum(var, 0), v_ref, atol=1e-10
    )
    assert np.allclose(g.signal_var * np.exp(-h), g.kernel_rows(x[:7]))
