"""The planner's step costs (mjwalk.plan.stepcost): the energy of a step at a speed, the
heading factor towards a goal in sight."""

from __future__ import annotations

import math

import pytest

from mjwalk.plan.stepcost import heading_factor, step_energy


def test_step_energy_is_least_at_the_preferred_speed():
    """c(v) = (v*/v + v/v*)/2 per metre: 1 at the preferred speed, the same at v and v*²/v,
    2.5 % more at 0.8 v*; a step that stands still costs v*·T/2."""
    pace, dur = 1.3, 0.55
    at_pace = step_energy(pace * dur, dur, pace)
    assert at_pace == pytest.approx(pace * dur)
    for f in (0.5, 0.8, 0.95, 1.05, 1.25, 2.0):
        length = f * pace * dur
        c = step_energy(length, dur, pace) / length
        assert c == pytest.approx(0.5 * (1 / f + f)) and c > 1.0
    assert step_energy(0.8 * 0.8 * pace * dur, 0.8 * dur, pace) / (
        0.8 * 0.8 * pace * dur
    ) == pytest.approx(1.025, abs=1e-3)
    assert step_energy(0.0, dur, pace) == pytest.approx(0.5 * pace * dur)


def test_heading_factor_grows_with_the_wrapped_heading_error():
    """1 + weight * psi^2, psi the heading error wrapped into [-pi, pi)."""
    assert heading_factor(0.3, 0.3, 5.2) == pytest.approx(1.0)
    assert heading_factor(0.0, 0.5, 2.0) == pytest.approx(1.0 + 2.0 * 0.25)
    assert heading_factor(0.5, 0.0, 2.0) == pytest.approx(1.0 + 2.0 * 0.25)
    # a heading error of 2 pi - 0.1 is 0.1 the other way round
    assert heading_factor(0.0, 2 * math.pi - 0.1, 1.0) == pytest.approx(1.0 + 0.01)
    assert heading_factor(1.0, 2.0, 0.0) == 1.0
