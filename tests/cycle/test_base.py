"""The cycle's actions (mjwalk.cycle.actions, their base in mjwalk.cycle.actions.base): each
task kind names its Action class, the state passed from action to action is immutable, and the
README's worked example of a new task kind (an ``inspect`` action) runs as written."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from mjwalk.cycle.actions import Reach, Wait, Walk
from mjwalk.cycle.actions.base import Action, CycleState, action_class
from mjwalk.cycle.spec import load_cycle_spec
from mjwalk.cycle.types import TASK_KINDS, TaskKind
from mjwalk.errors import CycleSpecError, InputError

ROOT = Path(__file__).parents[2]


def _readme_block(marker: str) -> str:
    """The README's ```python block that contains ``marker``."""
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    at = text.index(marker)
    start = text.rindex("```python\n", 0, at) + len("```python\n")
    return text[start : text.index("```", at)]


def test_every_kind_names_its_action_class():
    classes = {name: action_class(kind) for name, kind in TASK_KINDS.items()}
    assert classes == {
        "walk": Walk,
        "carry": Walk,
        "pick": Reach,
        "place": Reach,
        "fasten": Reach,
        "wait": Wait,
    }
    # the motion the spec checks and the stand zones read agrees with the action
    assert {k for k, v in TASK_KINDS.items() if v.motion == "walk"} == {"walk", "carry"}


def test_a_kind_naming_no_action_is_refused():
    kind = TaskKind("look", ("kind",), "wait", "Look")
    with pytest.raises(CycleSpecError, match="no action class named 'Look'"):
        action_class(kind)


def test_a_second_action_of_the_same_name_is_refused():
    with pytest.raises(InputError, match="'Walk' is defined twice"):
        type("Walk", (Action,), {"__module__": "elsewhere"})


def test_cycle_state_does_not_change():
    state = CycleState(x=1.0, y=2.0, yaw=0.5, here="a", home=(1.0, 2.0), pose=np.zeros(3))
    with pytest.raises(dataclasses.FrozenInstanceError):
        state.x = 3.0  # type: ignore[misc]
    moved = state.moved(x=3.0, here="b")
    assert (moved.x, moved.here, state.x, state.here) == (3.0, "b", 1.0, "a")
    assert moved.home == state.home and moved.t == 0.0 and moved.grip is None


def test_a_new_kinds_own_keys_are_read_into_options(tmp_path, monkeypatch):
    kind = TaskKind("inspect", ("kind", "site", "look", "duration"), "walk", "Walk")
    monkeypatch.setitem(TASK_KINDS, "inspect", kind)
    scene = ROOT / "scenes" / "assembly_station.xml"
    text = (
        f'scene = "{scene.as_posix()}"\nstart = "stand_rack2"\n\n[[task]]\nkind = "inspect"\n'
        'site = "stand_car1"\nlook = "car_screw1"\nduration = 2.0\n'
    )
    (tmp_path / "c.toml").write_text(text)
    task = load_cycle_spec(tmp_path / "c.toml").tasks[0]
    assert (task.kind, task.site, task.duration) == ("inspect", "stand_car1", 2.0)
    assert task.options == {"look": "car_screw1"}
    (tmp_path / "d.toml").write_text(text.replace("look =", "loook ="))
    with pytest.raises(CycleSpecError, match=r"unknown key 'loook'.*did you mean 'look'"):
        load_cycle_spec(tmp_path / "d.toml")


def test_built_in_tasks_have_no_options():
    spec = load_cycle_spec(ROOT / "scenes" / "assembly_station.toml")
    assert all(t.options == {} for t in spec.tasks)


def test_readme_inspect_example_runs(monkeypatch):
    """The README's "Adding a task kind" example, as written: its Inspect action walks to
    stand_car1 and turns to face car_screw1 (its own test asserts the walk, the time and the
    final heading); a scene without the looked-at site is refused before any work."""
    monkeypatch.chdir(ROOT)
    monkeypatch.setitem(TASK_KINDS, "inspect", TASK_KINDS["wait"])  # restored afterwards
    namespace: dict = {"__name__": "readme"}
    exec(compile(_readme_block("class Inspect(Walk)"), "README.md", "exec"), namespace)
    assert action_class(TASK_KINDS["inspect"]) is namespace["Inspect"]
    namespace["test_inspect_walks_and_looks"]()
    station = load_cycle_spec("scenes/assembly_station.toml")
    task = namespace["Task"]("inspect", site="stand_car1", options={"look": "nowhere"})
    spec = dataclasses.replace(station, tasks=[task], population=None)
    with pytest.raises(CycleSpecError, match="'look' must name a site"):
        namespace["mjwalk"].simulate_cycle(spec, rng=0)
