"""Easing and smoothing curves of the leg synthesis (mjwalk.body.legs.curves)."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.body.legs.curves import (
    clamped_cubic,
    smoothstep,
    soft_clip01,
    soft_max,
    soft_max1,
    spread,
)


def test_smoothstep_eases_from_0_to_1():
    """0 before 0, 1 after 1, 0.5 half-way, increasing and flat at both ends."""
    x = np.linspace(-0.5, 1.5, 201)
    y = smoothstep(x)
    assert y[0] == 0.0 and y[-1] == 1.0
    assert smoothstep(np.array(0.5)) == pytest.approx(0.5)
    assert np.all(np.diff(y) >= 0)
    assert smoothstep(np.array(1e-3)) < 1e-5  # zero slope at the ends


def test_spread_covers_a_need_and_fades_around_it():
    """A single needed amount is met at its sample (the running maximum's plateau smoothed),
    fades out over the window around and is zero far away."""
    need = np.zeros(101)
    need[50] = 1.0
    out = spread(need, 9)
    assert out.shape == need.shape
    assert out[50] == pytest.approx(1.0, abs=0.05)
    assert out[45] > 0.9 and out[25] == 0.0 and out[0] == 0.0  # support: +-(9 + 12)
    assert np.all(np.diff(out[:50]) >= -1e-12)


def test_soft_clip01_is_the_identity_inside_and_clips_outside():
    x = np.array([-1.0, 0.3, 0.5, 0.7, 2.0])
    y = soft_clip01(x, 0.1)
    assert np.allclose(y[1:4], x[1:4])
    assert y[0] == pytest.approx(0.0, abs=1e-9) and y[-1] == pytest.approx(1.0, abs=1e-9)


def test_clamped_cubic_meets_its_knots_and_end_slopes():
    """The clamped spline passes through its values with the given end slopes."""
    knots = [0.0, 0.4, 0.5, 0.6, 1.0]
    values = [0.2, 0.0, 0.0, 0.0, -0.1]
    y = clamped_cubic(knots, values, 0.5, -0.3, np.array(knots)).ravel()
    assert np.allclose(y, values)
    h = 1e-6
    ends = clamped_cubic(knots, values, 0.5, -0.3, np.array([0.0, h, 1.0 - h, 1.0])).ravel()
    assert (ends[1] - ends[0]) / h == pytest.approx(0.5, abs=1e-4)
    assert (ends[3] - ends[2]) / h == pytest.approx(-0.3, abs=1e-4)


def test_soft_max_rounds_the_corner_of_the_larger():
    """Exactly the larger beyond ``w`` apart, never below it, ``w / 4`` above it where equal;
    its slope goes from 0 to 1 without a jump (C1); the compiled one-value twin agrees."""
    b = np.zeros(4001)
    a = np.linspace(-0.2, 0.2, 4001)
    y = soft_max(a, b, 0.05)
    far = np.abs(a) >= 0.05
    assert np.array_equal(y[far], np.maximum(a, b)[far])
    assert np.all(y >= np.maximum(a, b))
    assert soft_max(np.array(0.0), np.array(0.0), 0.05) == pytest.approx(0.0125)
    slope = np.diff(y) / np.diff(a)
    assert slope[0] == pytest.approx(0.0) and slope[-1] == pytest.approx(1.0)
    assert np.abs(np.diff(slope)).max() < 0.01
    assert all(soft_max1(x, 0.0, 0.05) == v for x, v in zip(a[::97], y[::97], strict=True))
