"""Ramp gait (mjwalk.gait.slope): speed, cadence and step length on slopes against cited figures."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mjwalk.cycle.population import Population, preset_group
from mjwalk.errors import InputError
from mjwalk.gait.slope import frequency_factor, slope_gait, speed_factor
from mjwalk.gait.walker import Walker

DEG = math.radians


def test_level_ramp_is_level_walking():
    w = Walker.preset("adult")
    g = slope_gait(w, 0.0)
    assert g.speed == pytest.approx(w.speed)
    assert g.cadence * 60.0 == pytest.approx(w.cadence)
    assert g.step_length == pytest.approx(w.step_length)
    assert g.vertical_speed == 0.0


@pytest.mark.parametrize("angle", [float("nan"), DEG(25.0), DEG(-25.0), True, "5"])
def test_impossible_ramps_are_refused_in_one_line(angle):
    with pytest.raises(InputError, match="ramp angle") as err:
        slope_gait(Walker(), angle)
    assert "\n" not in str(err.value)


def test_tobler_speed_factor():
    # Tobler 1993, normalised to the level: exp(-3.5 tan a) uphill
    assert speed_factor(DEG(5.0)) == pytest.approx(math.exp(-3.5 * math.tan(DEG(5.0))))
    assert speed_factor(DEG(5.0)) == pytest.approx(0.736, abs=0.001)
    assert speed_factor(DEG(-2.86)) == 1.0  # capped: no faster than on the level
    assert speed_factor(DEG(-10.0)) < 1.0


def test_franz_kram_step_frequency_downhill():
    # Franz & Kram 2012, Table 1 at 1.25 m/s: 0.99 Hz at -9 deg over 0.93 Hz level
    assert frequency_factor(DEG(-9.0)) == pytest.approx(0.99 / 0.93)
    assert frequency_factor(DEG(-12.0)) == pytest.approx(0.99 / 0.93)
    assert frequency_factor(DEG(6.0)) == 1.0


@pytest.mark.parametrize("group", ["adult", "older_adult", "elderly", "fatigued", "brisk"])
def test_uphill_slower_and_downhill_shorter_steps_for_every_walker(group):
    rng = np.random.default_rng(47)
    pop = Population((preset_group(group),))
    for _ in range(100):
        w = pop.draw(rng)
        level = slope_gait(w, 0.0)
        up = slope_gait(w, DEG(5.5))  # the ramp
        down = slope_gait(w, DEG(-5.5))
        assert up.speed < level.speed and up.vertical_speed > 0.0
        assert down.speed <= level.speed and down.vertical_speed < 0.0
        # Sun et al. 1996: shorter steps going down; Franz & Kram 2012: faster steps down
        assert down.step_length < level.step_length
        assert down.cadence > level.cadence * math.sqrt(speed_factor(DEG(-5.5)))
        # steeper uphill is slower still
        assert slope_gait(w, DEG(8.0)).speed < up.speed


def test_relative_pace_carries_over_to_ramps():
    slow, fast = Walker(speed=1.0), Walker(speed=1.5)
    for a in (DEG(-6.0), DEG(6.0)):
        assert slope_gait(fast, a).speed / slope_gait(slow, a).speed == pytest.approx(1.5)


def test_ramp_duration_and_steps():
    g = slope_gait(Walker.preset("adult"), DEG(5.5))
    run = 0.34 / math.tan(DEG(5.5))  # the 0.34 m platform
    assert g.duration(run) == pytest.approx(run / (g.speed * math.cos(DEG(5.5))))
    assert g.steps(run) == math.ceil(g.duration(run) * g.cadence - 1e-9)
    with pytest.raises(InputError, match="run"):
        g.duration(-1.0)
