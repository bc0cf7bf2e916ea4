"""mjwalk.cycle.spectask: one [[task]] table checked against the scene, where the operator
stands and what the hands hold."""

from __future__ import annotations

from pathlib import Path

import pytest

from mjwalk.cycle.specfile import Checker, KeyLines
from mjwalk.cycle.spectask import MAX_REACH, check_task, hands_of
from mjwalk.errors import CycleSpecError
from mjwalk.world import shared_workplace


@pytest.fixture(scope="module")
def workplace(scenes_dir):
    return shared_workplace(scenes_dir / "assembly_station.xml")


def _check(raw: dict, workplace, stand="stand_rack2", held=None, i=0):
    check = Checker(Path("c.toml"), KeyLines(""))
    held = {"left": 0, "right": 0, "both": -1} if held is None else held
    return check_task(check, workplace, raw, i, 0.25, stand, held), held


def test_hands_of():
    assert hands_of("both") == ("left", "right") and hands_of("right") == ("right",)


def test_a_pick_fills_its_hand_and_a_carry_takes_the_hand_that_holds(workplace):
    task, held = _check({"kind": "pick", "site": "rack2_screw1", "mass": 0.2}, workplace)
    assert (task.kind, task.hand, task.mass, task.coupling) == ("pick", "left", 0.2, "poor")
    assert held == {"left": 1, "right": 0, "both": -1}
    carry, held = _check({"kind": "carry", "site": "stand_rack1"}, workplace, held=held, i=1)
    assert (carry.hand, carry.route) == ("left", "stand_rack2->stand_rack1")


@pytest.mark.parametrize(
    ("raw", "words"),
    [
        ({"kind": "jump", "site": "a"}, "is not a task kind"),
        ({"kind": "pick"}, "missing required key 'site'"),
        ({"kind": "wait", "duration": 1.0, "site": "x"}, "does not apply to a 'wait' task"),
        ({"kind": "pick", "site": "rack2_screw1", "hand": "feet"}, "must be 'left', 'right'"),
        ({"kind": "pick", "site": "rack2_screw1", "coupling": "weak"}, "must be one of good"),
        ({"kind": "walk", "site": "stand_rack2"}, "already stands at 'stand_rack2'"),
        ({"kind": "place", "site": "rack2_screw1"}, "with nothing in the left hand"),
        ({"kind": "carry", "site": "stand_rack1"}, "a carry with nothing in the left hand"),
    ],
)
def test_impossible_tasks_are_refused_naming_the_task(workplace, raw, words):
    with pytest.raises(CycleSpecError, match=words) as err:
        _check(raw, workplace)
    assert "in task 1" in str(err.value)


def test_a_site_beyond_arms_reach_is_refused(workplace):
    far = next(
        name
        for name, st in workplace.stations.items()
        if float(((st.xy - workplace.stations["stand_rack2"].xy) ** 2).sum()) > MAX_REACH**2
        and not name.startswith("stand")
    )
    with pytest.raises(CycleSpecError, match="beyond arm's reach"):
        _check({"kind": "pick", "site": far}, workplace)
