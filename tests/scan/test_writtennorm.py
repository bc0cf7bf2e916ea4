"""mjwalk.scan.writtennorm: steps and stairs the scan measured a hair outside DIN 18065's riser
limits are written inside them, so the written scene keeps the links the scan recognised."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from mjwalk.scan import build_scene
from mjwalk.scan.raycast import synthetic_scan
from mjwalk.scan.scanlevels import ScanLink
from mjwalk.scan.scanramps import ScanRamp
from mjwalk.scan.stairfit import WRITE_MARGIN
from mjwalk.scan.writtennorm import (
    WRITTEN_UNDER,
    ramps_to_levels,
    stairs_within_norm,
    steps_within_norm,
)
from mjwalk.world.levels import level_graph
from mjwalk.world.norms import MAX_RAMP_SLOPE, MAX_RISER, MIN_RISER
from mjwalk.world.surfaces import find_walk_surfaces

#: A straight flight of four 0.19 m risers (DIN 18065's largest) and 0.265 m treads
#: (2 h + g = 0.645 m) up to a deck at 0.76 m.
RISER, TREAD, N = 0.19, 0.265, 4


def _flight_xml(riser: float = RISER, tread: float = TREAD) -> str:
    geoms = ['<geom name="floor" type="plane" size="4 3 0.05"/>']
    for k in range(N - 1):
        h = (k + 1) * riser
        geoms.append(
            f'<geom name="t{k + 1}" type="box" pos="{tread * k + tread / 2:.4f} 0 {h / 2:.4f}" '
            f'size="{tread / 2:.4f} 0.5 {h / 2:.4f}"/>'
        )
    top, x0 = N * riser, tread * (N - 1)
    geoms.append(
        f'<geom name="deck" type="box" pos="{x0 + 0.75:.4f} 0 {top / 2:.4f}" '
        f'size="0.75 1.0 {top / 2:.4f}"/>'
    )
    return "<mujoco><worldbody>" + "".join(geoms) + "</worldbody></mujoco>"


@pytest.mark.slow  # a synthetic scan: about 12 s on a loaded 2-core machine
def test_a_flight_of_0_19_m_risers_fitted_a_hair_over_stays_a_stair_in_the_written_scene():
    """Scan seed 4 (0.4 deg rays, 5 mm noise) fits the flight's riser at 0.190008 m, within the
    scan's noise over the norm: the scan keeps the stair, and so must the scene it writes
    (before: written with 0.19001 m risers, only the first tread was a step up, the deck and
    the upper treads were no levels of the written scene)."""
    model = mujoco.MjModel.from_xml_string(_flight_xml())
    scanners = [(-1.0, 0.3, 1.6), (-2.5, -0.3, 1.7), (1.8, 0.5, 2.4)]
    scan = synthetic_scan(model, scanners, step_deg=0.4, noise=0.005, seed=4)
    scene = build_scene(scan.points, source="flight")
    assert scene.levels is not None
    graph = level_graph(find_walk_surfaces(mujoco.MjModel.from_xml_string(scene.xml)))
    heights = sorted(lv.height for lv in graph.levels)
    assert heights == pytest.approx([k * RISER for k in range(N + 1)], abs=0.002)
    stairs = [k for k in graph.links if k.kind == "stair"]
    assert len(stairs) == 1 and len(stairs[0].risers) == N
    assert graph.levels[stairs[0].upper].height == pytest.approx(N * RISER, abs=0.002)
    (stair,) = [k for k in scene.levels.links if k.kind == "stair"]
    assert stair.risers == (MAX_RISER - WRITE_MARGIN,) * N  # as written


def test_a_flight_at_the_least_riser_and_largest_tread_stays_a_stair_in_the_written_scene():
    """Four 0.14 m risers and 0.37 m treads (2 h + g = 0.65 m, the step rule's bound): scan seed
    1 measures the riser a hair under 0.14 m, written at ``MIN_RISER + WRITE_MARGIN``; the
    tread is fitted for that riser, so the written flight keeps the step rule and is a stair
    (before: tread 0.3699 m, 2 h + g = 0.6501 m written, four single steps)."""
    model = mujoco.MjModel.from_xml_string(_flight_xml(0.14, 0.37))
    scanners = [(-1.0, 0.3, 1.6), (-2.5, -0.3, 1.7), (1.8, 0.5, 2.4)]
    scan = synthetic_scan(model, scanners, step_deg=0.4, noise=0.005, seed=1)
    scene = build_scene(scan.points, source="flight")
    assert scene.levels is not None
    (stair,) = [k for k in scene.levels.links if k.kind == "stair"]
    assert 2 * stair.risers[0] + (stair.tread or 0.0) <= 0.65 - WRITE_MARGIN + 1e-9
    graph = level_graph(find_walk_surfaces(mujoco.MjModel.from_xml_string(scene.xml)))
    assert [(k.kind, len(k.risers)) for k in graph.links] == [("stair", N)]


def _deck_by_flight_and_ramp_xml(
    riser: float = 0.14, tread: float = 0.33, floor: float = 8.0
) -> str:
    """Four ``riser`` risers up to a 1.5 m deck, and from its far edge a 4 m ramp (7.97 deg)
    down to the floor (its foot at x = 6.49 m): the deck is the flight's top and the ramp's.
    The floor plane reaches x = ``floor`` metres (4: the ramp runs off its end)."""
    flight = _flight_xml(riser, tread).removesuffix("</worldbody></mujoco>")
    flight = flight.replace('size="4 3 0.05"', f'size="{floor} 3 0.05"')
    top, run = N * riser, 4.0
    th = math.atan(top / run)
    x = tread * (N - 1) + 1.5 + run / 2 - 0.05 * math.sin(th)
    z = top / 2 - 0.05 * math.cos(th)
    return (
        flight + f'<geom name="ramp" type="box" pos="{x:.5f} 0 {z:.5f}" '
        f'size="{run / 2 / math.cos(th):.5f} 0.5 0.05" euler="0 {math.degrees(th):.5f} 0"/>'
        "</worldbody></mujoco>"
    )


@pytest.mark.slow  # a synthetic scan: about 15 s on a loaded 2-core machine
def test_a_flight_a_hair_under_the_least_riser_to_a_deck_a_ramp_also_reaches_stays_a_stair():
    """Scan seed 0 fits the flight's riser a hair under 0.14 m: the flight is written at
    ``MIN_RISER + WRITE_MARGIN``, the deck raised with the ramp's end, and the written scene
    reads a stair (before: risers 0.13997 m as measured, four single steps) and the ramp (the
    floor plane now reaches the ramp's foot; it ended 2.49 m short of it, and neither the
    hall nor its written scene linked the ramp)."""
    model = mujoco.MjModel.from_xml_string(_deck_by_flight_and_ramp_xml())
    scanners = [(-1.0, 0.3, 1.6), (-2.5, -0.3, 1.7), (1.8, 0.5, 2.4), (5.5, 1.2, 2.4)]
    scan = synthetic_scan(model, scanners, step_deg=0.4, noise=0.005, seed=0)
    scene = build_scene(scan.points, source="deck")
    assert scene.levels is not None
    r = MIN_RISER + WRITE_MARGIN
    (stair,) = [k for k in scene.levels.links if k.kind == "stair"]
    assert stair.risers == pytest.approx((r,) * N, abs=1e-12)
    (ramp,) = scene.levels.ramps
    assert ramp.h_hi == pytest.approx(N * r, abs=1e-12) and ramp.slope <= MAX_RAMP_SLOPE
    assert scene.levels.heights == pytest.approx([k * 0.14 for k in range(N + 1)], abs=0.02)
    graph = level_graph(find_walk_surfaces(mujoco.MjModel.from_xml_string(scene.xml)))
    assert [(k.kind, len(k.risers)) for k in graph.links] == [("ramp", 0), ("stair", N)]
    assert graph.levels[-1].height == pytest.approx(N * r, abs=2e-5)


@pytest.mark.slow  # a synthetic scan: about 15 s on a loaded 2-core machine
def test_a_ramp_running_off_the_floors_end_is_linked_in_neither_the_hall_nor_the_scan():
    """The hall above with its floor plane ending at x = 4 m: the ramp's foot (x = 6.49 m)
    ends 2.49 m past it, in the air, and the hall's own graph links no ramp ("its ends do
    not meet two levels"). The ramp's toe, within ``FLOOR_TOL`` of the floor's height, was
    floor to the scan, which linked the ramp L0 -> L4 (before; the written scene did not:
    its floor stopped 9 mm past the toe); a level must lie past a ramp's end, where a
    walker steps off it (``scanramps``), so the scan now links the stair alone, as the hall."""
    model = mujoco.MjModel.from_xml_string(_deck_by_flight_and_ramp_xml(floor=4.0))
    hall = level_graph(find_walk_surfaces(model))
    assert [k.kind for k in hall.links] == ["stair"] and "ramp 'ramp'" in hall.notes[0]
    scanners = [(-1.0, 0.3, 1.6), (-2.5, -0.3, 1.7), (1.8, 0.5, 2.4), (5.5, 1.2, 2.4)]
    scan = synthetic_scan(model, scanners, step_deg=0.4, noise=0.005, seed=0)
    scene = build_scene(scan.points, source="deck")
    assert scene.levels is not None
    assert [k.kind for k in scene.levels.links] == ["stair"] and not scene.levels.ramps
    graph = level_graph(find_walk_surfaces(mujoco.MjModel.from_xml_string(scene.xml)))
    assert [(k.kind, len(k.risers)) for k in graph.links] == [("stair", N)]


def _stair(riser: float, lower: int = 0, upper: int = 4) -> ScanLink:
    return ScanLink("stair", lower, upper, (riser,) * 4, 0.265, (1, 2, 3))


def test_a_stair_over_the_norm_moves_its_treads_and_top_to_the_limit():
    heights = [0.0, 0.19002, 0.38004, 0.57006, 0.76008]
    (out,) = stairs_within_norm([_stair(0.19002)], heights)
    r = MAX_RISER - WRITE_MARGIN
    assert out.risers == (r,) * 4
    assert heights == pytest.approx([0.0, r, 2 * r, 3 * r, 4 * r], abs=1e-12)


def test_a_stair_under_the_least_riser_moves_up_to_it():
    heights = [0.1, 0.2398, 0.3796, 0.5194, 0.6592]
    (out,) = stairs_within_norm([_stair(0.1398)], heights)
    r = MIN_RISER + WRITE_MARGIN
    assert out.risers[0] == pytest.approx(r, abs=1e-12)
    assert heights[4] == pytest.approx(0.1 + 4 * r, abs=1e-12)


def test_a_stair_inside_the_norm_is_unchanged():
    heights = [0.0, 0.17, 0.34, 0.51, 0.68]
    links = [_stair(0.17)]
    assert stairs_within_norm(links, heights) == links
    assert heights == [0.0, 0.17, 0.34, 0.51, 0.68]


def test_a_stair_whose_top_is_another_links_lower_end_keeps_its_riser():
    heights = [0.0, 0.19002, 0.38004, 0.57006, 0.76008, 0.93]
    links = [_stair(0.19002), ScanLink("step", 4, 5, (0.16992,))]
    assert stairs_within_norm(links, list(heights)) == links


def test_flights_on_from_a_landing_are_written_bottom_up():
    """Hall 1169: 4 risers fitted at 0.139995 m up to a landing, 3 more at 0.140008 m on to a
    deck; raising the landing to the first flight's 0.1401 m takes the second under the norm,
    so it is written from the landing as written, at 0.1401 m too."""
    heights = [0.0, 0.139995, 0.27999, 0.419985, 0.55998, 0.699988, 0.839996, 0.980004]
    links = [
        ScanLink("stair", 4, 7, (0.140008,) * 3, 0.34, (5, 6)),  # the upper flight first
        ScanLink("stair", 0, 4, (0.139995,) * 4, 0.35, (1, 2, 3)),
    ]
    out = stairs_within_norm(links, heights)
    r = MIN_RISER + WRITE_MARGIN
    assert [k.risers[0] for k in out] == pytest.approx([r, r], abs=1e-12)
    assert heights == pytest.approx([k * r for k in range(8)], abs=1e-12)


def test_a_step_platform_over_the_norm_is_lowered_under_it():
    heights = [0.0, 0.19001]
    (out,) = steps_within_norm([ScanLink("step", 0, 1, (0.19001,))], heights)
    assert heights[1] == pytest.approx(MAX_RISER - WRITTEN_UNDER, abs=1e-12)
    assert out.risers[0] == pytest.approx(heights[1], abs=1e-12)


def _ramp(rise: float, run: float, lower: int = 0, upper: int = 4) -> ScanRamp:
    slope = math.atan2(rise, run)
    return ScanRamp(
        lower, upper, np.array([1.0, 0.0]), 0.0, run, -0.5, 0.5, 0.0, rise, 0.001, slope
    )


def test_a_stair_to_a_deck_a_ramp_also_reaches_moves_the_deck_and_the_ramp_with_it():
    """A deck reached by a ramp and by four risers fitted at 0.139995 m (under DIN 18065's
    0.14 m): the deck, otherwise only the ramp's end, goes up to four written risers (before:
    the flight kept 0.139995 m, four single steps in the written scene), and the ramp's high
    end with it, still under 10 deg."""
    heights = [0.0, 0.139995, 0.27999, 0.419985, 0.55998]
    ramp = _ramp(0.55998, 4.0)
    links = [_stair(0.139995), ScanLink("ramp", 0, 4, (), slope=ramp.slope, run=ramp.length)]
    before = list(heights)
    out = stairs_within_norm(links, heights)
    r = MIN_RISER + WRITE_MARGIN
    assert out[0].risers == pytest.approx((r,) * 4, abs=1e-12)
    assert heights == pytest.approx([k * r for k in range(5)], abs=1e-12)
    assert abs(heights[4] - before[4]) < 0.02  # within 2 cm of the scan's fit
    (moved,), out = ramps_to_levels([ramp], out, before, heights)
    assert (moved.h_lo, moved.h_hi) == pytest.approx((0.0, 4 * r), abs=1e-12)
    assert moved.length == ramp.length  # 7.97 deg: no need to lengthen it
    assert out[1].slope == pytest.approx(moved.slope, abs=1e-15) and out[1].slope < MAX_RAMP_SLOPE


def test_a_ramp_at_the_limit_whose_deck_a_flight_raises_is_lengthened_to_stay_under_it():
    heights = [0.0, 0.139995, 0.27999, 0.419985, 0.55998]
    run = (0.55998 + WRITE_MARGIN) / math.tan(MAX_RAMP_SLOPE)
    ramp = _ramp(0.55998, run)
    links = [_stair(0.139995), ScanLink("ramp", 0, 4, (), slope=ramp.slope, run=ramp.length)]
    before = list(heights)
    out = stairs_within_norm(links, heights)
    (moved,), out = ramps_to_levels([ramp], out, before, heights)
    assert moved.slope <= MAX_RAMP_SLOPE and moved.length > ramp.length
    assert moved.s_hi == ramp.s_hi  # its high end stays at the deck's edge
    assert out[1].run == moved.length


def test_ramps_whose_levels_kept_their_heights_are_unchanged():
    ramp = _ramp(0.5, 4.0, 0, 1)
    links = [ScanLink("ramp", 0, 1, (), slope=ramp.slope, run=ramp.length)]
    ramps, out = ramps_to_levels([ramp], links, [0.0, 0.5], [0.0, 0.5])
    assert ramps == [ramp] and out == links


def test_a_stair_to_a_deck_a_step_also_reaches_keeps_its_riser():
    heights = [0.0, 0.139995, 0.27999, 0.419985, 0.55998, 0.4]
    links = [_stair(0.139995), ScanLink("step", 5, 4, (0.15998,))]
    assert stairs_within_norm(links, list(heights)) == links
