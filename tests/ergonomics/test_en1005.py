"""EN 1005-4 zones, excursions and verdicts, and ISO 11226's holding-time step, on synthetic
angle traces."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.ergonomics import en1005, iso11226

FPS = 30.0


def trace(*pieces: tuple[float, float]) -> np.ndarray:
    """An angle trace of (degrees, seconds) pieces."""
    return np.concatenate([np.full(round(s * FPS), a, dtype=float) for a, s in pieces])


def test_an_exposure_held_longer_than_the_acceptable_time_is_not_acceptable():
    limit = iso11226.max_holding_time(40.0, iso11226.ARM_HOLD)  # 120 s at 40 deg
    assert limit == pytest.approx(120.0)
    within = trace((10, 5), (40, limit - 5), (10, 5))
    beyond = trace((10, 5), (40, limit + 5), (10, 5))
    assert en1005.iso11226_verdict(within, FPS, iso11226.ARM_HOLD)[0] == "conditionally acceptable"
    verdict, ratio = en1005.iso11226_verdict(beyond, FPS, iso11226.ARM_HOLD)
    assert verdict == "not acceptable" and ratio == pytest.approx((limit + 5) / limit, rel=1e-3)
    # static beyond 60 deg is never acceptable; shorter than 4 s is not static
    assert en1005.iso11226_verdict(trace((70, 5)), FPS, iso11226.ARM_HOLD)[0] == "not acceptable"
    assert en1005.iso11226_verdict(trace((70, 3)), FPS, iso11226.ARM_HOLD)[0] == "acceptable"


def test_zones_count_time_excursions_and_judge_frequency():
    # one minute: three 1 s raises above 60 deg (3/min: high frequency), the rest at 10 deg
    a = trace(*[(10, 9), (75, 1)] * 3, (10, 30))
    z = en1005.zones(a, FPS)
    assert [x.name for x in z] == ["0-20", "20-60", ">60"]
    assert z[0].time == pytest.approx(57.0) and z[2].time == pytest.approx(3.0)
    assert (z[1].excursions, z[2].excursions, z[2].static) == (3, 3, 0)
    assert z[2].per_min == pytest.approx(3.0)
    assert z[2].verdict == "not acceptable" and z[1].verdict == "conditionally acceptable"
    # one raise a minute: low frequency, conditionally acceptable above 60, acceptable in 20-60
    z1 = en1005.zones(trace((10, 29), (75, 1), (10, 30)), FPS)
    assert (z1[1].verdict, z1[2].verdict) == ("acceptable", "conditionally acceptable")
    assert sum(x.share for x in z1) == pytest.approx(1.0)


def test_worst_and_runs():
    assert en1005.worst() == "acceptable"
    assert (
        en1005.worst("acceptable", "not acceptable", "conditionally acceptable") == "not acceptable"
    )
    assert en1005.runs_above(np.array([0, 30, 30, 0, 30]), 20) == [(1, 3), (4, 5)]
    assert en1005.zone_verdict(2, 1, 0.5, 1) == "not acceptable"  # static above 60 deg


def test_a_dip_across_the_limit_is_not_a_second_excursion():
    # a raise above 60 deg that dips to 57 deg for 0.1 s: one excursion (hysteresis 5 deg);
    # a return to 50 deg between two raises: two
    dip = trace((10, 5), (75, 1), (57, 0.1), (75, 1), (10, 5))
    back = trace((10, 5), (75, 1), (50, 0.5), (75, 1), (10, 5))
    assert en1005.HYSTERESIS_DEG == 5.0
    assert en1005.runs_above(dip, 60) == [(150, 213)]
    assert len(en1005.runs_above(dip, 60, hysteresis=0.0)) == 2
    assert len(en1005.runs_above(back, 60)) == 2
    assert en1005.zones(dip, FPS)[2].excursions == 1
