"""Ramp gait (mjwalk.gait.slope): speed, cadence and step length on slopes against cited figures."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mjwalk.body.legs import legs_from_walk
from mjwalk.body.legs.stance import REACH_DROP_MAX
from mjwalk.cycle.population import Population, preset_group
from mjwalk.errors import InputError
from mjwalk.gait.slope import (
    DOWNHILL_DROP,
    downhill_step_max,
    frequency_factor,
    slope_gait,
    speed_factor,
)
from mjwalk.gait.walker import Walker
from mjwalk.plan.synthetic import synthetic_ramp_walk

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


def test_downhill_drop_is_the_leg_stages_limit_less_its_tolerance():
    # the gait stage's copy of the body's figure (it cannot import it): 3 mm under it
    assert DOWNHILL_DROP == pytest.approx(REACH_DROP_MAX - 0.003)
    assert downhill_step_max(0.0) == math.inf and downhill_step_max(DEG(5.0)) == math.inf
    assert downhill_step_max(DEG(-9.5)) == pytest.approx(2 * DOWNHILL_DROP / math.sin(DEG(9.5)))


def test_downhill_step_length_ratio_vs_slope():
    """The reference adult's step down a slope over its level step: Franz & Kram's cadence and
    Tobler's speed while the step's front foot falls within the legs' reach (the ratio
    sqrt(f) / (F&K frequency ratio): 0.979 at -3 deg), then the reach's step, shorter and
    shorter with the slope (Sun et al. 1996: steps shorten going down ramps up to 9 deg);
    the cadence stays Franz & Kram's throughout."""
    w = Walker()
    level = slope_gait(w, 0.0).step_length
    degs = np.arange(0.0, -10.01, -0.5)
    gaits = [slope_gait(w, DEG(d)) for d in degs]
    ratio = np.array([g.step_length for g in gaits]) / level
    assert np.all(np.diff(ratio) <= 1e-12)  # never longer for a steeper descent
    assert ratio[6] == pytest.approx(0.93 / 0.95)  # -3 deg: Tobler capped at 1, F&K 0.95 Hz
    for d, g in zip(degs, gaits, strict=True):
        a = DEG(float(d))
        assert g.step_length * math.sin(-a) / 2 <= DOWNHILL_DROP + 1e-12
        cited = math.sqrt(speed_factor(a)) / frequency_factor(a)  # Tobler and F&K alone
        assert g.step_length / level == pytest.approx(min(cited, downhill_step_max(a) / level))
        assert g.cadence * 60.0 == pytest.approx(
            w.cadence * math.sqrt(speed_factor(a)) * frequency_factor(a)
        )
        assert g.duration(1.0) == pytest.approx(1.0 / (g.step_length * g.cadence * math.cos(a)))
    # the reference adult (0.73 m level step) shortens for its reach from about 8.8 deg on
    assert ratio[degs == -8.5][0] == pytest.approx(
        math.sqrt(speed_factor(DEG(-8.5))) / frequency_factor(DEG(-8.5))
    )
    assert ratio[-1] == pytest.approx(downhill_step_max(DEG(-10.0)) / level)


@pytest.mark.parametrize("stature", [1.59, 1.83])
@pytest.mark.parametrize("deg", [-8.5, -9.5, -9.9])
def test_long_stepping_walker_reaches_its_feet_down_a_steep_ramp(stature, deg):
    """A walker with long steps (0.86 m level) down the steepest ramps a hall has: its ramp
    steps (0.72 m at 9.5 deg from Tobler and Franz & Kram alone) asked the pelvis to lower
    0.066 m (1.83 m) for the leading leg to reach its foot, more than the leg stage's
    REACH_DROP_MAX (PlanningError); the reach-bound step asks for less."""
    w = Walker(stature=stature, speed=1.5, cadence=105.0)
    a = DEG(deg)
    g = slope_gait(w, a)
    walk = synthetic_ramp_walk(a, n_steps=6, step_len=g.step_length * math.cos(a),
                               step_time=g.step_time)  # fmt: skip
    legs_from_walk(walk, stature)  # raised "the legs reach their feet only with ..." before
