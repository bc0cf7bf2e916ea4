"""mjwalk.world.levelgen: generated multi-level halls are legal and their level graphs hold the
levels and links they were drawn with (issue 47)."""

from __future__ import annotations

import math

import mujoco
import pytest

from mjwalk.world.levelgen import (
    APPROACH,
    MAX_RAMP_RUN,
    WALKWAY,
    generate_levels,
)
from mjwalk.world.levels import level_graph
from mjwalk.world.norms import (
    MAX_RAMP_SLOPE,
    MAX_RISER,
    MAX_TREAD,
    MIN_RISER,
    MIN_STAIR_RISERS,
    MIN_TREAD,
    STEP_RULE,
)
from mjwalk.world.surfaces import find_walk_surfaces


@pytest.mark.parametrize("seed", range(40))
def test_drawn_dimensions_stay_inside_the_norms(seed):
    hall = generate_levels(seed)
    assert hall.links and any(k.kind == "stair" for k in hall.links)
    for k in hall.links:
        if k.kind == "stair":
            assert MIN_RISER <= k.riser <= MAX_RISER and MIN_TREAD <= k.tread <= MAX_TREAD
            assert STEP_RULE[0] <= 2 * k.riser + k.tread <= STEP_RULE[1] + 1e-9
            assert k.risers >= MIN_STAIR_RISERS
        elif k.kind == "step":
            assert k.risers in (1, 2) and MIN_RISER <= k.riser <= MAX_RISER + 1e-9
        else:
            rise = k.upper - k.lower
            assert 0 < rise <= MAX_RAMP_RUN * math.tan(MAX_RAMP_SLOPE)
    names = [s.name for s in hall.sites]
    assert len(names) == len(set(names))
    assert {s.level for s in hall.sites} >= {"floor", "mezz"}
    assert WALKWAY >= 1.0 and APPROACH >= WALKWAY


def test_same_seed_same_hall():
    assert generate_levels(7).xml == generate_levels(7).xml
    assert generate_levels(7).xml != generate_levels(8).xml


@pytest.mark.parametrize("seed", [3, 6, 1065])
def test_level_graph_holds_the_drawn_levels_and_links(seed):
    """Hall 3 (a straight stair, a two-riser step, a ramp and a one-riser step), hall 6 (a
    pit, a stair turned at a landing) and hall 1065 (a stair with a landing drawn at the step
    rule's limit: written before as treads 0.2 mm apart, 2 h + g over 0.65 m, single steps):
    every drawn height is a level and every drawn stair and ramp a link of the compiled scene's
    level graph."""
    hall = generate_levels(seed)
    model = mujoco.MjModel.from_xml_string(hall.xml)
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    g = level_graph(find_walk_surfaces(model, data))
    heights = [lv.height for lv in g.levels]
    for h in hall.heights:
        assert min(abs(h - x) for x in heights) < 1e-3
    got = {
        (k.kind, round(heights[k.lower], 2), round(heights[k.upper], 2), len(k.risers))
        for k in g.links
    }
    for k in hall.links:
        if k.kind == "step":
            continue  # a two-riser step is two step links (over its tread)
        n = k.risers if k.kind == "stair" else 0
        assert (k.kind, round(k.lower, 2), round(k.upper, 2), n) in got
