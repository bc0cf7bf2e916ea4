"""mjwalk.scan.hiddentread: a tall flight's top tread that the level above hides from every
scanner is inferred from the flight's regular rise and run, so the flight and the level above
it are found (issue 47, scan47h)."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

from mjwalk.scan.hiddentread import hidden_treads
from mjwalk.scan.level import find_floor
from mjwalk.scan.levelboxes import scan_levels
from mjwalk.scan.obstacles import floor_plan
from mjwalk.scan.raycast import synthetic_scan
from mjwalk.scan.scanlevels import find_regions

#: Six 0.18 m risers and 0.28 m treads rising along +x from x = 0 to a 1.08 m deck at x = 1.40.
RISER, TREAD, N = 0.18, 0.28, 6
SCANNERS = [(-1.2, 0.4, 1.6), (-2.4, -0.5, 1.7), (2.6, 0.6, 2.6)]


def _xml(deck_at: float) -> str:
    treads = "\n".join(
        f'  <geom name="t{k}" type="box" pos="{TREAD * k - TREAD / 2:.3f} 0 {RISER * k / 2:.3f}" '
        f'size="{TREAD / 2:.3f} 0.6 {RISER * k / 2:.3f}"/>'
        for k in range(1, N)
    )
    h = RISER * N
    return f"""<mujoco><worldbody>
  <geom name="floor" type="plane" size="5 3 0.05"/>
{treads}
  <geom name="deck" type="box" pos="{deck_at + 0.75:.3f} 0 {h / 2:.3f}"
        size="0.75 1.2 {h / 2:.3f}"/>
</worldbody></mujoco>"""


def _scan(deck_at: float = TREAD * (N - 1), seen: float = 0.06, hidden: int = 1):
    """The seeded scan, levelled, with all of the top ``hidden`` treads but their front ``seen``
    metres taken out (what the deck's edge hides), and its floor plan."""
    model = mujoco.MjModel.from_xml_string(_xml(deck_at))
    pts = synthetic_scan(model, SCANNERS, step_deg=0.4, noise=0.005, seed=7).points
    pts = find_floor(pts).apply(pts)
    for k in range(N - hidden, N):  # tread k: from x = TREAD (k - 1) at RISER k
        x0, top = TREAD * (k - 1), RISER * k
        gone = (pts[:, 0] > x0 + seen) & (pts[:, 0] < x0 + TREAD) & (np.abs(pts[:, 2] - top) < 0.03)
        pts = pts[~gone]
    return pts, floor_plan(pts)


@pytest.fixture(scope="module")
def hidden_scan():
    return _scan()


def test_the_hidden_tread_is_no_region_of_its_own(hidden_scan):
    pts, plan = hidden_scan
    found, _, _ = find_regions(pts, plan)
    assert not any(abs(r.height - RISER * (N - 1)) < 0.02 for r in found)


def test_the_flight_puts_the_hidden_tread_where_it_is(hidden_scan):
    pts, plan = hidden_scan
    found, steps, layers = find_regions(pts, plan)
    more, pairs, layers2 = hidden_treads(found, steps, pts, plan, layers)
    assert len(more) == len(found) + 1
    t = more[-1]
    assert t.kind == "tread" and t.height == pytest.approx(RISER * (N - 1), abs=0.01)
    assert t.depth == pytest.approx(TREAD, abs=0.02)
    assert layers2.heights[t.peak] == pytest.approx(t.height)
    _, ix = np.nonzero(t.cells)
    xs = plan.x0 + (ix + 0.5) * plan.resolution  # cell centres: half a cell inside the edges
    half = 0.5 * plan.resolution
    assert xs.min() == pytest.approx(TREAD * (N - 2) + half, abs=0.03)
    assert xs.max() == pytest.approx(TREAD * (N - 1) - half, abs=0.03)
    deck = [i for i, r in enumerate(found) if abs(r.height - RISER * N) < 0.02]
    assert (len(more) - 1, deck[0]) in pairs


def test_the_stair_and_the_deck_are_found(hidden_scan):
    lp = scan_levels(*hidden_scan)
    assert lp is not None
    stairs = [k for k in lp.links if k.kind == "stair"]
    assert len(stairs) == 1, [(k.kind, k.lower, k.upper) for k in lp.links]
    s = stairs[0]
    assert len(s.risers) == N and s.risers[0] == pytest.approx(RISER, abs=0.005)
    assert s.tread == pytest.approx(TREAD, abs=0.01)
    assert lp.heights[s.upper] == pytest.approx(RISER * N, abs=0.02)


def test_no_tread_is_inferred_where_the_deck_does_not_begin_a_tread_further():
    """The deck 0.4 m beyond the flight's next riser: a gap, not a hidden tread."""
    pts, plan = _scan(deck_at=TREAD * (N - 1) + 0.4)
    found, steps, layers = find_regions(pts, plan)
    more, _, _ = hidden_treads(found, steps, pts, plan, layers)
    assert len(more) == len(found)


def test_two_hidden_treads_of_a_flight_pinned_at_both_ends():
    """The top two treads hidden (three seen): both put back, the flight and the deck found."""
    pts, plan = _scan(hidden=2)
    found, steps, layers = find_regions(pts, plan)
    more, _, _ = hidden_treads(found, steps, pts, plan, layers)
    added = sorted(r.height for r in more[len(found) :])
    assert added == pytest.approx([RISER * (N - 2), RISER * (N - 1)], abs=0.01)
    lp = scan_levels(pts, plan)
    assert lp is not None
    stairs = [k for k in lp.links if k.kind == "stair"]
    assert len(stairs) == 1 and len(stairs[0].risers) == N
    assert lp.heights[stairs[0].upper] == pytest.approx(RISER * N, abs=0.02)
