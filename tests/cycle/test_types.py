"""mjwalk.cycle.types: the task kinds' grip sites, a run's walk lengths by route and its
plain-data summary."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from mjwalk.cycle.types import (
    CycleResult,
    CycleSpec,
    Task,
    WalkRecord,
    grip_sites,
    operator_dict,
)
from mjwalk.gait.walker import Walker
from mjwalk.plan.walkpath import WalkPath


def test_grip_sites_of_one_and_both_hands():
    assert grip_sites("box", "right") == [("right", "box")]
    assert grip_sites("box", "both") == [("left", "box_left"), ("right", "box_right")]


def _walk(route: str, dx: float) -> WalkRecord:
    path = WalkPath(np.array([0.0, 1.0]), np.array([[0.0, 0.0], [dx, 0.0]]), np.zeros(2), [])
    return WalkRecord(0, route, "a", "b", path, dx)


def test_a_results_walk_lengths_and_summary():
    spec = CycleSpec(path=Path("c.toml"), scene=Path("s.xml"), start="a", tasks=[Task("walk")])
    walks = [_walk("T1", 2.0), _walk("T2", 1.0), _walk("T1", 3.0)]
    r = CycleResult(spec=spec, run=1, seed=5, tasks=[], walks=walks, arms=[], cycle_time=9.5)
    assert r.walk_lengths() == {"T1": [2.0, 3.0], "T2": [1.0]}
    s = r.summary()
    assert (s["run"], s["seed"], s["cycle_time"], s["operator"]) == (1, 5, 9.5, None)
    assert [w["length"] for w in s["walks"]] == [2.0, 1.0, 3.0]
    assert s["max_hand_error"] == 0.0 and s["collisions"] == 0
    json.dumps(s)  # plain data


def test_operator_dict():
    assert operator_dict(None) is None
    d = operator_dict(Walker(stature=1.6, speed=1.1, cadence=105.0))
    assert d is not None and (d["stature"], d["speed"], d["cadence"]) == (1.6, 1.1, 105.0)


def test_a_walks_length_is_its_paths_kept_once_read():
    """A report reads each walk's length about a dozen times: it is the path's, read once; a
    record that has read it pickles and summarises as one that has not."""
    import pickle

    w = _walk("T1", 2.5)
    assert w.length == w.path.length == 2.5
    back = pickle.loads(pickle.dumps(w))
    assert back.length == 2.5
    spec = CycleSpec(path=Path("c.toml"), scene=Path("s.xml"), start="a", tasks=[Task("walk")])
    runs = [
        CycleResult(spec=spec, run=0, seed=0, tasks=[], walks=[v], arms=[], cycle_time=1.0)
        for v in (back, _walk("T1", 2.5))
    ]
    assert runs[0].summary() == runs[1].summary()
