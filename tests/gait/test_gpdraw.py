"""Tests of mjwalk.gait.gpdraw: the compiled transition-GP moments and packed quadratic form."""

from __future__ import annotations

import numpy as np
import pytest
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


def test_a_draw_in_parts_is_the_draw(gp):  # noqa: F811
    """sample = draw_parts + variance + compose, bit for bit and with the same random numbers
    (the planner skips the variance of closing draws that cannot end a walk)."""
    g, x, _ = gp
    xs = np.ascontiguousarray(x[:3])
    whole = gpdraw.sample(xs, 6, np.random.default_rng(4), g.kernel, 10.0)
    rng = np.random.default_rng(4)
    mean, e, rows, eps = gpdraw.draw_parts(xs, 6, rng, g.kernel, 10.0)
    parts = gpdraw.compose(mean, gpdraw.variance(e, g.kernel), rows, eps, 6, g.kernel[7])
    np.testing.assert_array_equal(parts, whole)
    after = np.random.default_rng(4)
    gpdraw.sample(xs, 6, after, g.kernel, 10.0)
    assert rng.random() == after.random()  # the same numbers drawn


def test_the_variance_cap_bounds_every_variance(gp):  # noqa: F811
    """kernel[9] (transition.variance_cap) is at least every variance the draws compute: at
    the data, far from it and at kernel rows of every inducing input."""
    g, x, _ = gp
    cap = g.kernel[9]
    rng = np.random.default_rng(0)
    probes = np.vstack([x, 4.0 * rng.standard_normal((200, x.shape[1])), g.inducing])
    _, var, _ = gpdraw.moments(np.ascontiguousarray(probes), g.kernel)
    assert var.max() <= cap
    assert cap == pytest.approx(g.signal_var, rel=1e-3)  # a positive definite form: about C
    e = rng.uniform(0.0, 1.0, (500, g.inducing.shape[0]))  # any kernel row in [0, 1]^m
    assert gpdraw.variance(e, g.kernel).max() <= cap


def test_a_draw_into_work_arrays_is_the_draw(gp):  # noqa: F811
    """sample_into (the search's draws: work arrays kept, successors written into its node
    rows) gives sample's numbers bit for bit and draws the same random numbers; so does
    draw_parts, now made of draw_parts_into."""
    g, x, _ = gp
    work = gpdraw.new_work(1, g.kernel)
    rows = np.empty(8, dtype=np.intp)
    out = np.full((12, x.shape[1]), np.nan)
    for k in range(20):
        xs = np.ascontiguousarray(x[k : k + 1])
        a, b = np.random.default_rng(k), np.random.default_rng(k)
        whole = gpdraw.sample(xs, 6, a, g.kernel, 10.0)[0]
        gpdraw.sample_into(xs, 6, b, g.kernel, 10.0, work, rows, out, 3)
        np.testing.assert_array_equal(out[3:9], whole)
        assert np.isnan(out[:3]).all() and np.isnan(out[9:]).all()  # only its rows written
        assert a.random() == b.random()


def test_the_draws_numbers_come_in_samples_order(gp):  # noqa: F811
    """draw_numbers takes sample's p·n uniforms, p·n pool members, then p·n·d normals."""
    g, x, _ = gp
    u, member, eps = gpdraw.draw_numbers(np.random.default_rng(3), 2, 5, g.kernel)
    ref = np.random.default_rng(3)
    np.testing.assert_array_equal(u, ref.random(10))
    np.testing.assert_array_equal(member, ref.integers(0, g.kernel[8], 10))
    np.testing.assert_array_equal(eps, ref.standard_normal(10 * x.shape[1]))
