"""Tests of mjwalk.plan.turnsteps: a winder stair's turning steps named where a walk over it is
refused (issue 47)."""

from __future__ import annotations

import itertools
import math
import re

import pytest

from mjwalk.errors import PlanningError
from mjwalk.gait.walker import Walker
from mjwalk.plan.levelplan import endpoint
from mjwalk.plan.levelroute import step_up_limit
from mjwalk.plan.levelsearch import level_route
from mjwalk.plan.occupancy import CELL_SIZE
from mjwalk.plan.options import PlannerOptions
from mjwalk.plan.turnsteps import in_line, stepped_over, turned_chains, turning_steps
from mjwalk.world import load_workplace

#: Riser (m) and the wedges' angle (rad): 0.17 m (ASR A1.8 §4.5); 30 deg treads round a 0.1 m
#: post out to 1.0 m. The wedges are boxes, so the edge each shares with the next lies along
#: the next box's side, 0.2588 m off its centre line: the nosings' middles are 0.608 m from the
#: post and 30 deg apart, a 0.315 m tread on the walk line (DIN 18065:2020 measures a winder's
#: tread as the chord there, 2 r sin 15 deg), 2R + T = 0.655 m: just over the step rule.
RISER, WEDGE = 0.17, math.radians(30.0)


def _winder_xml(treads: int) -> str:
    """A quarter-turn spiral stair: ``treads`` solid wedge boxes anticlockwise from +x round a
    post at the origin, then a platform (one riser above the last) beyond the turn."""
    geoms = ['<geom name="floor" type="plane" size="6 6 0.05"/>']
    rc, hw = 0.55, math.sin(WEDGE / 2)  # the boxes' centre radius and half their outer chord
    for i in range(1, treads + 1):
        th, z = (i - 0.5) * WEDGE, i * RISER
        geoms.append(
            f'<geom name="wedge{i}" type="box" size="0.45 {hw:.4f} {z / 2:.4f}" '
            f'pos="{rc * math.cos(th):.4f} {rc * math.sin(th):.4f} {z / 2:.4f}" '
            f'euler="0 0 {math.degrees(th):.4f}"/>'
        )
    top = (treads + 1) * RISER
    geoms.append(
        f'<geom name="deck" type="box" size="1.5 1.5 {top / 2}" pos="-1.6 1.5 {top / 2}"/>'
    )
    geoms.append('<site name="low" pos="2.0 -2.0 0"/>')
    geoms.append(f'<site name="high" pos="-2.0 2.0 {top}"/>')
    return "<mujoco><worldbody>" + "".join(geoms) + "</worldbody></mujoco>"


@pytest.fixture(scope="module")
def winder(tmp_path_factory):
    path = tmp_path_factory.mktemp("winder") / "winder.xml"
    path.write_text(_winder_xml(3))
    return load_workplace(path)


def test_the_winders_turning_treads_are_named(winder):
    clear = PlannerOptions().radius + CELL_SIZE
    notes = turning_steps(winder.levels, clear)
    assert len(notes) == 1
    assert "turn at wedge1, wedge2, wedge3 (a winder or spiral stair)" in notes[0]


def test_the_wedges_are_stepped_over_and_their_steps_not_in_line(winder):
    graph = winder.levels
    passed = stepped_over(graph, PlannerOptions().radius + CELL_SIZE)
    names = [graph.surfaces[lv.surfaces[0]].name for lv in graph.levels]
    assert {n for n, p in zip(names, passed, strict=True) if p} == {"wedge1", "wedge2", "wedge3"}
    up = {graph.surfaces[graph.levels[k.upper].surfaces[0]].name: k for k in graph.links}
    assert not in_line(up["wedge1"], up["wedge2"])  # the edges 30 deg apart


def test_a_straight_flights_steps_are_in_line(tmp_path):
    """Three single 0.4 m deep blocks (no tread, no stair: deeper than 0.37 m) in a row."""
    boxes = "".join(
        f'<geom name="block{i}" type="box" size="0.2 0.6 {0.085 * i}" pos="{0.4 * i - 0.2} 0 '
        f'{0.085 * i}"/>'
        for i in (1, 2)
    )
    deck = '<geom name="deck" type="box" size="1 1 0.255" pos="1.8 0 0.255"/>'
    xml = f'<mujoco><worldbody><geom name="floor" type="plane" size="5 5 0.05"/>{boxes}{deck}'
    path = tmp_path / "blocks.xml"
    path.write_text(xml + "</worldbody></mujoco>")
    graph = load_workplace(path).levels
    up = {graph.surfaces[graph.levels[k.upper].surfaces[0]].name: k for k in graph.links}
    assert in_line(up["block1"], up["block2"])


def test_a_walk_up_the_winder_is_refused_saying_why(winder):
    """Before turnsteps the refusal read only "no route from level L0 to level L4 ... for this
    walker (step-up limit 0.19 m, stature 1.75 m)", as if the walker were the cause."""
    walker, options = Walker(), PlannerOptions()
    a, b = endpoint(winder, "low", "start"), endpoint(winder, "high", "goal")
    want = r"turn at wedge1.*walk line.*tread wedge1: 2R \+ T = 2 x 0.170 \+ 0.315 = 0.655 m"
    with pytest.raises(PlanningError, match=want) as err:
        level_route(winder, a, b, walker, options, step_up_limit(walker))
    assert "\n" not in str(err.value)


def test_a_straight_stair_has_no_turning_steps(scenes_dir):
    station = load_workplace(scenes_dir / "multilevel_station.xml")
    assert turning_steps(station.levels, PlannerOptions().radius + CELL_SIZE) == []


def _route(tmp_path, xml: str, ends: tuple[str, str] = ("low", "high")):
    """Plan the level route between two sites of ``xml`` (raises if none)."""
    path = tmp_path / "stair.xml"
    path.write_text(xml)
    workplace, walker, options = load_workplace(path), Walker(), PlannerOptions()
    a, b = endpoint(workplace, ends[0], "start"), endpoint(workplace, ends[1], "goal")
    return level_route(workplace, a, b, walker, options, step_up_limit(walker))


@pytest.mark.parametrize("ends", [("low", "high"), ("high", "low")])
def test_a_winder_breaking_the_step_rule_is_refused_naming_its_walk_line_tread(
    tmp_path, winder_xml, ends
):
    """Three wedges turning a 1 m stair a quarter: 0.42 m on the walk line; refused up and down.
    Before the walk-line check the refusal named only the turning treads, not the rule they
    break."""
    with pytest.raises(PlanningError) as err:
        _route(tmp_path, winder_xml("wedges"), ends)
    msg = str(err.value)
    assert "turn at tread2, tread3, tread4 (a winder or spiral stair) and break DIN 18065" in msg
    assert (
        "tread tread2: 2R + T = 2 x 0.170 + 0.422 = 0.762 m on the walk line, outside the " in msg
    )
    assert "step rule 0.59-0.65 m" in msg and "\n" not in msg


def test_a_winder_meeting_the_step_rule_says_so(tmp_path, winder_xml):
    """Such a winder is routed now (tests/plan/test_winderroute.py); its line says so."""
    path = tmp_path / "balanced.xml"
    path.write_text(winder_xml("balanced"))
    (note,) = turning_steps(load_workplace(path).levels, PlannerOptions().radius + CELL_SIZE)
    assert re.search(r"2R \+ T 0.63\d-0.63\d m, within DIN 18065's step rule\): walked", note)
    assert len(_route(tmp_path, winder_xml("balanced"))) == 3  # level, winder, level


def test_turned_chains_gives_the_winders_chain_bottom_up(winder):
    """The spiral's one chain: floor -> wedge1 -> wedge2 -> wedge3 -> deck, each link onto the
    level the next leaves (the chain windercross walks)."""
    graph = winder.levels
    chains = turned_chains(graph, PlannerOptions().radius + CELL_SIZE)
    assert len(chains) == 1
    (((lo, up), chain),) = chains.items()
    assert (chain[0].lower, chain[-1].upper) == (lo, up) and len(chain) == 4
    assert all(a.upper == b.lower for a, b in itertools.pairwise(chain))
    names = [graph.surfaces[graph.levels[k.upper].surfaces[0]].name for k in chain[:-1]]
    assert names == ["wedge1", "wedge2", "wedge3"]
