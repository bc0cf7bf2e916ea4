"""The planner's landing-leg check (issue 17 item 5): a foot landing far ahead of the pelvis
beside an obstacle's corner keeps its ankle's clearance while the shin and the toes-up heel
between ankle and hip touch the corner; the step is refused, and station run 727 (seed 0), where
that happened at the end of route T4, has no contact any more."""

from __future__ import annotations

import cmath
import math

import numpy as np
import pytest

from mjwalk.plan import stepcheck
from mjwalk.plan.options import FOOT_CLEARANCE, LEG_PROBE_STEP, lean_params, leg_clearance
from mjwalk.world import load_workplace

M = 16


def _leg_clear(wp, pelvis, yaw, ankle, left=True, stature=1.64):
    """landing_leg_clear of a step whose end pelvis is ``pelvis`` (world x, y; facing ``yaw``,
    radians from +x) and whose landing ankle is ``ankle``: the step frame is the world (rot 1,
    origin 0), whose forward is +y, so the end yaw relative to it is yaw - 90 deg."""
    field = wp.walk_field()
    par = stepcheck.params(
        **lean_params(), leg_step=LEG_PROBE_STEP, leg_clearance=leg_clearance(stature)
    )
    loc = np.zeros(M + 2, dtype=np.complex128)
    loc[M - 1] = complex(*pelvis)
    loc[M] = complex(*ankle)
    ny, nx = field.values.shape
    return stepcheck.landing_leg_clear(
        loc, M, left, yaw - math.pi / 2, 1.0 + 0j, 0j, FOOT_CLEARANCE, 0.31, par,
        field.values, field.x0, field.y0, field.resolution, nx, ny,
    )  # fmt: skip


def test_a_leg_reaching_past_a_post_corner_is_refused(scenes_dir):
    wp = load_workplace(scenes_dir / "assembly_station.xml")
    # run 727's last step of T4 (main at 1c3c662): pelvis ends 0.36 m before rack 2's front,
    # the left foot lands 0.51 m ahead, beside the corner of the rack's right frame post
    pelvis, yaw, ankle = (0.1809, -1.7097), math.radians(-67.47), (0.483, -2.123)
    # the old checks pass: the ankle keeps FOOT_CLEARANCE, the pelvis the body radius
    assert wp.walk_clearance(np.array([ankle]))[0] >= FOOT_CLEARANCE
    assert wp.walk_clearance(np.array([pelvis]))[0] >= 0.31
    # the shin on the line from ankle to hip passes within its radius of the post's corner
    assert not _leg_clear(wp, pelvis, yaw, ankle)
    # the same step landing its foot nearer the pelvis (short of the rack front) is fine
    head = cmath.exp(1j * yaw)
    near = complex(*pelvis) + 0.25 * head + 0.1 * 1j * head
    assert wp.walk_clearance(np.array([[near.real, near.imag]]))[0] >= FOOT_CLEARANCE
    assert _leg_clear(wp, pelvis, yaw, (near.real, near.imag))


def test_landing_leg_slots_unset_means_no_check(scenes_dir):
    wp = load_workplace(scenes_dir / "assembly_station.xml")
    field = wp.walk_field()
    par = stepcheck.params(**lean_params())  # no leg_step / leg_clearance: nan
    loc = np.zeros(M + 2, dtype=np.complex128)
    loc[M - 1], loc[M] = complex(0.1809, -1.7097), complex(0.483, -2.123)
    ny, nx = field.values.shape
    assert stepcheck.landing_leg_clear(
        loc, M, True, 0.0, 1.0 + 0j, 0j, FOOT_CLEARANCE, 0.31, par,
        field.values, field.x0, field.y0, field.resolution, nx, ny,
    )  # fmt: skip


def test_leg_clearance_scales_with_stature():
    # shin radius 0.027 H + 1 cm margin + half the probe spacing
    assert leg_clearance(1.75) == pytest.approx(0.027 * 1.75 + 0.01 + 0.02)
    assert leg_clearance(1.95) > leg_clearance(1.55)


def test_station_run_727_has_no_contact(scenes_dir):
    """Re-simulated alone (its operator, 1.64 m, drawn from the run's SeedSequence): on main
    at 1c3c662 the left shin and foot touched rack2_frame_r 5-9 mm deep at t = 62.83-62.87 s,
    the heel strike of T4's last step."""
    from mjwalk.cycle.simulate import simulate_cycles

    (r,) = simulate_cycles(scenes_dir / "assembly_station.toml", 1000, seed=0, only=[727])
    assert r.operator is not None and r.operator.stature == pytest.approx(1.64, abs=0.005)
    assert [w.route for w in r.walks] == ["T1", "T2", "T2", "T3", "T3", "T4", "T5"]
    assert r.collisions == []
