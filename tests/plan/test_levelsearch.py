"""Tests of mjwalk.plan.levelsearch: the route over levels, its edges made as the search needs
them (issue 47)."""

from __future__ import annotations

import pytest

from mjwalk.gait.walker import Walker
from mjwalk.plan.levelplan import endpoint
from mjwalk.plan.levelroute import dijkstra, step_up_limit
from mjwalk.plan.levelsearch import (
    _crossings,
    _Edges,
    _head_fits,
    _Leads,
    _legs,
    _route,
    level_route,
)
from mjwalk.plan.occupancy import CELL_SIZE
from mjwalk.plan.options import PlannerOptions
from mjwalk.world import load_workplace
from mjwalk.world.levelview import level_at
from mjwalk.world.norms import HEAD_MARGIN

PAIRS = (
    ("stand_step", "stand_platform1"),
    ("stand_ramp", "stand_platform2"),
    ("stand_stair", "stand_mezz_rack"),
    ("stand_rack1", "stand_mezz_rack"),
    ("stand_mezz_rack", "stand_rack1"),
    ("stand_platform1", "stand_car1"),
    ("stand_mezz_rack", "stand_platform2"),
)


@pytest.fixture
def fresh(scenes_dir):
    """The multi-level station loaded anew (no views, fields or routes kept on it)."""
    return load_workplace(scenes_dir / "multilevel_station.xml")


def _ends(wp, start, goal):
    return endpoint(wp, start, "start"), endpoint(wp, goal, "goal")


def _key(legs) -> list[tuple]:
    """Route legs as comparable tuples (the crossing by identity: they are kept per scene)."""
    return [
        (leg.kind, leg.level, leg.start.tolist(), leg.end.tolist(), id(leg.crossing), leg.direction)
        for leg in legs
    ]


def _levels_set_up(wp) -> set[int]:
    """The levels whose distance fields the route built."""
    return {key[0] for key in wp.__dict__.get("_node_fields", {})}


@pytest.mark.parametrize("stature", [1.55, 1.75, 1.95])
def test_the_route_is_the_one_every_edge_made_up_front_gives(fresh, stature):
    walker, options = Walker(stature=stature), PlannerOptions()
    for start, goal in PAIRS:
        a, b = _ends(fresh, start, goal)
        legs = _route(fresh, a, b, walker, options, step_up_limit(walker))
        # the whole table first, as the route was searched before its edges were made lazily
        nodes = [(a.level, a.xy), (b.level, b.xy)]
        usable = [
            c
            for c in _crossings(fresh, options.radius + CELL_SIZE)
            if c.fits(step_up_limit(walker)) and _head_fits(fresh, c, walker.stature)
        ]
        for c in usable:
            nodes += [(c.lower, c.end(c.lower)), (c.upper, c.end(c.upper))]
        reach = (walker.step_length, options.goal_tolerance)
        leads = _Leads(fresh, usable, reach[0], (options, walker.stature + HEAD_MARGIN))
        lazy = _Edges(fresh, (usable, nodes, leads), walker, options, reach)
        table = {u: list(lazy[u]) for u in range(len(nodes))}
        path, _ = dijkstra(len(nodes), table, 0, 1)
        assert path is not None
        assert _key(legs) == _key(_legs(path, nodes, usable))


def test_a_walk_onto_the_platform_sets_up_no_mezzanine(fresh):
    walker, options = Walker(), PlannerOptions()
    mezzanine = level_at(fresh, fresh.stations["stand_mezz_rack"].pos[:2], 1.02)
    a, b = _ends(fresh, "stand_step", "stand_platform1")
    legs = level_route(fresh, a, b, walker, options, step_up_limit(walker))
    assert [leg.kind for leg in legs] == ["level", "cross", "level"]
    assert mezzanine not in _levels_set_up(fresh)
    assert 0 in _levels_set_up(fresh)


def test_a_walk_from_the_mezzanine_to_the_floor_sets_up_no_platform(fresh):
    walker, options = Walker(), PlannerOptions()
    platform = level_at(fresh, fresh.stations["stand_platform1"].pos[:2], 0.34)
    a, b = _ends(fresh, "stand_mezz_rack", "stand_rack1")
    legs = level_route(fresh, a, b, walker, options, step_up_limit(walker))
    assert [leg.crossing.kind for leg in legs if leg.kind == "cross"] == ["stair"]
    assert platform not in _levels_set_up(fresh)


def test_edges_are_made_once_and_in_node_order(fresh):
    walker, options = Walker(), PlannerOptions()
    a, b = _ends(fresh, "stand_step", "stand_platform1")
    _route(fresh, a, b, walker, options, step_up_limit(walker))
    nodes = [(a.level, a.xy), (b.level, b.xy)]
    reach = (walker.step_length, options.goal_tolerance)
    leads = _Leads(fresh, [], reach[0], (options, walker.stature + HEAD_MARGIN))
    edges = _Edges(fresh, ([], nodes, leads), walker, options, reach)
    assert edges[1] == [] and edges[0] is edges[0]  # nothing from the goal; kept
    assert [v for v, _ in edges[0]] == ([1] if a.level == b.level else [])
    with pytest.raises(KeyError):
        edges[len(nodes)]
