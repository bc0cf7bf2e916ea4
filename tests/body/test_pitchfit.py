"""Pitch corrections of the leg synthesis (mjwalk.body.legs.pitchfit)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from mjwalk.body.humanoid import ROM_DEG, leg_geometry, pelvis_height
from mjwalk.body.legs.footpivot import pivot_ankle
from mjwalk.body.legs.ikcache import LegIKCache
from mjwalk.body.legs.pitchfit import AnkleFit, fit_ankle_range, repitch_foot
from mjwalk.body.legs.steps import FootTracks

DORSI = np.deg2rad(ROM_DEG["ankle_flex"][1] - 1.0)
PLANTAR = np.deg2rad(ROM_DEG["ankle_flex"][0] + 1.0)


def _one_foot(ankle, fyaw, pitch, toe, ground, prints):
    return FootTracks(*({"l": a} for a in (ankle, fyaw, pitch, toe, ground, prints)))


def test_repitch_grounded_foot_turns_about_its_pivot():
    """A grounded flat foot pitched toes up turns about its heel, heel up about its ball
    (pivot_ankle's ankle); the toes keep their angle to the floor while the heel is up; the
    inputs are not changed."""
    g = leg_geometry()
    prints = np.array([[0.2, 0.1, 0.3], [0.2, 0.1, 0.3]])
    pitch = np.zeros(2)
    ankle = pivot_ankle(prints, pitch, g)
    toe = np.zeros(2)
    dp = np.array([-0.2, 0.3])  # lowered by dp: toes up 0.2, heel up 0.3
    a, p = repitch_foot(ankle, pitch, toe, np.full(2, 0.3), np.ones(2, bool), prints, dp, g)
    assert np.allclose(p, [0.2, -0.3])
    assert np.allclose(a, pivot_ankle(prints, p, g))
    assert np.allclose(toe, [0.0, 0.3])
    assert np.all(pitch == 0) and np.allclose(ankle, pivot_ankle(prints, np.zeros(2), g))


def test_fit_ankle_range_pitches_a_trailing_foot_down():
    """A flat grounded foot behind a pelvis moving ahead dorsiflexes its ankle past the range
    (28 deg vs 19); the fit raises the heel until the ankle is (about) back in range."""
    g = leg_geometry(1.75)
    n = 60
    yaw = np.zeros(n)
    root = np.column_stack(
        [np.linspace(0, 0.3, n), np.zeros(n), np.full(n, pelvis_height(1.75) - 0.05)]
    )
    prints = np.tile([-0.1, g.hip_y, 0.0], (n, 1))
    pitch = np.zeros(n)
    feet = _one_foot(pivot_ankle(prints, pitch, g), yaw.copy(), pitch, np.zeros(n),
                     np.ones(n, bool), prints)  # fmt: skip
    before = LegIKCache("l", g)(feet.ankle["l"], yaw, pitch, root, yaw)["ankle_l_flex"]
    fit = fit_ankle_range(LegIKCache("l", g), feet, root, yaw, AnkleFit(DORSI, PLANTAR, 3, 8))
    assert fit is not None
    ankle, p = fit
    after = LegIKCache("l", g)(ankle, yaw, p, root, yaw)["ankle_l_flex"]
    assert before.max() > DORSI + 0.1
    assert after.max() <= DORSI + 0.01
    assert p.min() < -0.2 and np.all(pitch == 0)  # heel up; the input is not changed
    assert np.allclose(ankle, pivot_ankle(prints, p, g))  # still on its footprint


def test_fit_ankle_range_leaves_short_walks_to_the_caller():
    """Walks shorter than 2 win + 2 samples return None; the bounds record is frozen."""
    g = leg_geometry()
    n = 7
    prints = np.zeros((n, 3))
    feet = _one_foot(pivot_ankle(prints, np.zeros(n), g), np.zeros(n), np.zeros(n),
                     np.zeros(n), np.ones(n, bool), prints)  # fmt: skip
    root = np.tile([0.0, 0.0, 0.9], (n, 1))
    bounds = AnkleFit(DORSI, PLANTAR, 3, 8)
    assert fit_ankle_range(LegIKCache("l", g), feet, root, np.zeros(n), bounds) is None
    with pytest.raises(dataclasses.FrozenInstanceError):
        bounds.rounds = 2  # type: ignore[misc]


def test_fit_ankle_range_stops_at_its_tolerance():
    """With a tolerance the rounds stop once no grounded ankle is more than it past the bound
    (before the eight rounds of the exact fit): the ankle ends within it, and nearer the bound
    than without the rounds' stop would leave it less corrected."""
    g = leg_geometry(1.75)
    n = 60
    yaw = np.zeros(n)
    root = np.column_stack(
        [np.linspace(0, 0.3, n), np.zeros(n), np.full(n, pelvis_height(1.75) - 0.05)]
    )
    prints = np.tile([-0.1, g.hip_y, 0.0], (n, 1))

    def fitted(tol):
        feet = _one_foot(pivot_ankle(prints, np.zeros(n), g), yaw.copy(), np.zeros(n),
                         np.zeros(n), np.ones(n, bool), prints)  # fmt: skip
        bounds = AnkleFit(DORSI, PLANTAR, 3, 8, tol)
        ankle, p = fit_ankle_range(LegIKCache("l", g), feet, root, yaw, bounds)
        return LegIKCache("l", g)(ankle, yaw, p, root, yaw)["ankle_l_flex"].max() - DORSI

    exact, loose = fitted(0.0), fitted(np.deg2rad(0.5))
    assert loose <= np.deg2rad(0.5)
    assert exact < loose  # the loose fit stopped earlier, further from the bound


def test_fit_passes_in_one_call_give_the_python_loops_tracks_bit_for_bit(monkeypatch):
    """``synthesis._fit_ankles``' passes in one compiled call (``fit_ankle_passes``) and pass
    by pass in Python give every track of 36 seeded walks (straight and turning, short quick
    and long slow steps, statures 1.5-2.0 m) to the byte; the compiled call ran for each."""
    from mjwalk.body.legs import pitchfit, synthesis
    from mjwalk.plan.synthetic import synthetic_walk

    ran = []
    kept = pitchfit.fit_ankle_passes

    def counted(*args):
        z = kept(*args)
        ran.append(z is not None)
        return z

    monkeypatch.setattr(synthesis, "fit_ankle_passes", counted)

    def tracks(walk, stature, compiled):
        monkeypatch.setattr(synthesis, "COMPILED_FIT", compiled)
        legs = synthesis.legs_from_walk(walk, stature)
        arrays = [legs.root, legs.yaw, legs.contact, legs.phase]
        for d in (legs.angles, legs.ankle, legs.pitch):
            arrays += [d[k] for k in sorted(d)]
        return [a.dtype.str.encode() + a.tobytes() for a in arrays]

    rng = np.random.default_rng(50)
    for case in range(36):
        radius = None if case % 3 == 0 else float(rng.choice([-1, 1]) * rng.uniform(0.6, 3))
        walk = synthetic_walk(
            n_steps=int(rng.integers(2, 9)),
            step_len=float(rng.uniform(0.1, 0.9)),
            width=float(rng.uniform(0.08, 0.3)),
            step_time=float(rng.uniform(0.4, 0.8)),
            radius=radius,
            start=(float(rng.uniform(-3, 3)), float(rng.uniform(-3, 3)), rng.uniform(-3, 3)),
            hold=float(rng.choice([0.0, 0.25])),
        )
        stature = float(rng.uniform(1.5, 2.0))
        assert tracks(walk, stature, True) == tracks(walk, stature, False), case
    assert len(ran) == 36 and all(ran)
