"""Tests of mjwalk.world.walkline: a winder's treads measured on its walk line (DIN 18065;
issue 47)."""

from __future__ import annotations

import pytest

from mjwalk.world import load_workplace, norms
from mjwalk.world.levels import LevelGraph, LevelLink
from mjwalk.world.walkline import WalkLineTread, walk_line_faults, walk_line_treads

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
