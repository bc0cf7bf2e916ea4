"""The operator groups' step-up limits (issue 47): parsed from [population], checked against
DIN 18065's riser limit, and looked up for a run's operator."""

from __future__ import annotations

import pytest

from mjwalk.cycle.population import parse_population
from mjwalk.cycle.stepup import parse_step_up, step_up_of
from mjwalk.errors import CycleSpecError
from mjwalk.gait.walker import Walker


def _fail(msg, key):
    return CycleSpecError(msg)


def test_a_number_limits_every_group_and_a_table_its_own():
    assert parse_step_up(0.1, ["adult", "older_adult"], _fail) == (
        ("adult", 0.1),
        ("older_adult", 0.1),
    )
    assert parse_step_up({"older_adult": 0.0}, ["adult", "older_adult"], _fail) == (
        ("older_adult", 0.0),
    )


@pytest.mark.parametrize("value", [-0.01, 0.25, float("nan"), True, "high", {"nobody": 0.1}])
def test_bad_limits_are_refused(value):
    with pytest.raises(CycleSpecError, match="step_up"):
        parse_step_up(value, ["adult"], _fail)


def test_population_keeps_the_limits_beside_a_mix():
    pop = parse_population(
        {"mix": {"adult": 0.8, "older_adult": 0.2}, "step_up": {"older_adult": 0.0}}, 1.75
    )
    assert pop.group_names == ["adult", "older_adult"]
    assert step_up_of(pop, Walker(group="older_adult")) == 0.0
    assert step_up_of(pop, Walker(group="adult")) is None  # the planner's default (0.19 m)
    assert step_up_of(None, Walker()) is None
    assert parse_population({"mix": {"adult": 1.0}}, 1.75).step_up == ()
