"""mjwalk.ergonomics.lifting: the NIOSH lifts of a cycle's tasks, measured on its body angles."""

from __future__ import annotations

import pytest
from test_assess import reach_cycle

from mjwalk.ergonomics.lifting import LIFT_DURATION, NioshScore, cycle_lifts


def test_a_pick_is_one_lift_at_the_site_and_the_frequency_is_per_cycle():
    ang, spans = reach_cycle(mass=3.0)
    lifts = cycle_lifts(ang, spans, cycle_time=4.0)
    assert len(lifts) == 1
    lf = lifts[0]
    assert (lf.task, lf.kind, lf.hand, lf.mass, lf.coupling) == (1, "pick", "left", 3.0, "fair")
    assert lf.f == pytest.approx(15.0)  # 1 lift in 4 s
    assert lf.one_handed and lf.d == pytest.approx(abs(lf.v[1] - lf.v[0]))
    assert all(h > 0 for h in lf.h) and LIFT_DURATION in ("short", "moderate", "long")
    # 15 lifts/min is beyond the frequency table for this duration: no index, and why
    assert lf.li is None and "lifting frequency" in lf.reason
    slow = cycle_lifts(ang, spans, cycle_time=120.0)[0]
    assert slow.li == pytest.approx(3.0 / slow.rwl) and slow.reason == ""


def test_no_lift_without_a_mass():
    ang, spans = reach_cycle(mass=0.0)
    assert cycle_lifts(ang, spans, cycle_time=4.0) == []
    assert NioshScore().name == "niosh"
