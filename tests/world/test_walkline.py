"""Tests of mjwalk.world.walkline: a winder's treads measured on its walk line (DIN 18065;
issue 47)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mjwalk.world import load_workplace, norms
from mjwalk.world.levels import LevelGraph, LevelLink
from mjwalk.world.walkline import (
    WalkLineTread,
    usable_span,
    walk_line_faults,
    walk_line_nosings,
    walk_line_treads,
)

#: How far a measured tread may lie from the laid-out one, metres: the contact edges between
#: surfaces are found on a sampled edge (``mjwalk.world.contacts``), a few millimetres.
EDGE_TOL = 0.01


def _stair(tmp_path, xml: str) -> tuple[LevelGraph, list[LevelLink]]:
    """The scene's levels and its chain of steps from the floor up (one step off each)."""
    path = tmp_path / "winder.xml"
    path.write_text(xml)
    graph = load_workplace(path).levels
    up = {k.lower: k for k in graph.links if k.kind == "step"}
    chain = [up[0]]
    while chain[-1].upper in up:
        chain.append(up[chain[-1].upper])
    return graph, chain


def test_a_balanced_winder_meets_the_step_rule_on_its_walk_line(tmp_path, winder_xml):
    graph, chain = _stair(tmp_path, winder_xml("balanced"))
    treads = walk_line_treads(graph, chain)
    assert [t.name for t in treads] == [f"tread{i}" for i in range(1, 8)]
    for t in treads:  # laid out 0.290-0.298 m on the walk line, 0.109 m at the narrow end
        assert 0.29 - EDGE_TOL <= t.tread <= 0.298 + EDGE_TOL, t
        assert t.riser == pytest.approx(0.17, abs=1e-6)
        assert t.faults() == []
    assert all(t.narrow == pytest.approx(0.109, abs=EDGE_TOL) for t in treads[1:-1])
    # a straight tread is as deep at either end as on its walk line
    assert treads[0].narrow == pytest.approx(treads[0].tread, abs=1e-6)
    assert walk_line_faults(treads) == []


def test_three_wedges_in_a_quarter_turn_break_the_step_rule(tmp_path, winder_xml):
    graph, chain = _stair(tmp_path, winder_xml("wedges"))
    treads = walk_line_treads(graph, chain)
    by = {t.name: t for t in treads}
    # laid out: the wedges' nosing middles 0.422, 0.384 and 0.427 m apart
    for name, tread in (("tread2", 0.422), ("tread3", 0.384), ("tread4", 0.427)):
        assert by[name].tread == pytest.approx(tread, abs=EDGE_TOL)
        assert by[name].step > norms.STEP_RULE[1]
    faults = walk_line_faults(treads)
    assert [f.split(":")[0] for f in faults] == ["tread tread2", "tread tread3", "tread tread4"]
    assert (
        "2R + T = 2 x 0.170 + 0.422 = 0.762 m on the walk line, outside the step rule"
        in (faults[0])
    )


def test_the_walk_line_crosses_each_nosing_at_its_middle(tmp_path, winder_xml):
    graph, chain = _stair(tmp_path, winder_xml("balanced"))
    first = walk_line_treads(graph, chain)[0]
    assert first.start == pytest.approx((-0.5861, -0.5), abs=EDGE_TOL)
    assert first.end == pytest.approx((-0.2961, -0.5), abs=EDGE_TOL)


@pytest.mark.parametrize(
    ("tread", "narrow", "riser", "fault"),
    [
        (0.29, 0.05, 0.17, "0.050 m deep at its narrow end, under 0.10 m"),
        (0.24, 0.12, 0.18, "walk-line tread 0.240 m outside 0.26-0.37 m"),
        (0.30, 0.12, 0.19, "2R + T = 2 x 0.190 + 0.300 = 0.680 m on the walk line"),
    ],
)
def test_each_fault_is_named_with_its_numbers(tread, narrow, riser, fault):
    t = WalkLineTread("w", 1, tread, riser, narrow, (0.0, 0.0), (tread, 0.0))
    assert len(t.faults()) == 1 and fault in t.faults()[0]


def test_the_limits_themselves_pass():
    """2R + T exactly 0.59 and 0.65 m, a narrow end exactly 0.10 m: no fault."""
    for tread, riser in ((0.26, 0.165), (0.31, 0.17)):
        t = WalkLineTread("w", 1, tread, riser, norms.WINDER_MIN_NARROW_TREAD, (0, 0), (0, 0))
        assert t.faults() == []


#: The spirals' post radius, metres (``tests/conftest.py``'s ``_spiral_xml``).
POST = 0.10


@pytest.mark.parametrize(("kind", "turn", "treads", "outer"), [("half", 180.0, 7, 0.98)])
def test_a_spiral_stairs_walk_line_is_the_middle_of_its_usable_width(
    tmp_path, spiral_xml, kind, turn, treads, outer
):
    """Round a 0.10 m post the treads are 0.045 m deep at the post; the usable width starts
    where they are 0.10 m deep (r10 = 0.05 / sin(step / 2) = 0.225 m), and the walk line, its
    middle, 0.602 m from the post's axis, measures each tread 0.268 m (2R + T = 0.648 m): the
    stair meets DIN 18065 there. Before: the walk line was the middle of the whole nosing
    (0.54 m out), each tread 0.240 m, 0.045 m at its narrow end, three faults each."""
    graph, chain = _stair(tmp_path, spiral_xml(kind))
    treads_ = walk_line_treads(graph, chain)
    assert [t.name for t in treads_] == [f"spiral{i}" for i in range(1, treads + 1)]
    half = 0.5 * math.radians(turn) / treads
    r10 = 0.5 * norms.USABLE_TREAD_DEPTH / math.sin(half)
    radius = 0.5 * (r10 + outer)
    for t in treads_:
        assert t.tread == pytest.approx(2.0 * radius * math.sin(half), abs=EDGE_TOL), t
        assert t.riser == pytest.approx(0.19, abs=1e-6)
        assert t.narrow == pytest.approx(norms.USABLE_TREAD_DEPTH, abs=EDGE_TOL)
        for p in (t.start, t.end):
            assert math.hypot(*p) == pytest.approx(radius, abs=EDGE_TOL)
    assert walk_line_faults(treads_) == []
    # the nosings cut to that width: each one's middle is where the walk line crosses it
    nosings = walk_line_nosings(chain)
    assert len(nosings) == treads + 1
    for e in nosings:
        assert sorted(np.hypot(e[:, 0], e[:, 1])) == pytest.approx([r10, outer], abs=EDGE_TOL)
        assert math.hypot(*e.mean(axis=0)) == pytest.approx(radius, abs=EDGE_TOL)


def test_a_spiral_too_steep_on_its_walk_line_names_the_rule_it_breaks(tmp_path, spiral_xml):
    """Three 30 deg treads turning a quarter: 0.304 m on the walk line, 2R + T = 0.684 m."""
    graph, chain = _stair(tmp_path, spiral_xml("steep"))
    faults = walk_line_faults(walk_line_treads(graph, chain))
    assert [f.split(":")[0] for f in faults] == ["tread spiral1", "tread spiral2", "tread spiral3"]
    assert (
        "2R + T = 2 x 0.190 + 0.304 = 0.684 m on the walk line, outside the step rule"
        in (faults[0])
    )
    assert all("narrow end" not in f for f in faults)  # within the usable width: 0.10 m


def test_a_winder_deep_enough_all_across_keeps_its_whole_nosings(tmp_path, winder_xml):
    """The balanced winder's treads are at least 0.109 m deep at their narrow end: nothing is
    cut, its nosings are the steps' own edges and the walk line their middles (as before)."""
    _, chain = _stair(tmp_path, winder_xml("balanced"))
    assert usable_span(chain)[1] is None
    for e, k in zip(walk_line_nosings(chain), chain, strict=True):
        assert np.array_equal(e, np.asarray(k.lower_edge, dtype=float))
