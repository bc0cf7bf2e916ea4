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
from mjwalk.world.clearance import ClearanceField

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


def _valley(c: float, res: float = 0.02) -> ClearanceField:
    """An adversarial walk field: nodes c + |i| + |j| spacings about the node at the origin,
    each node difference one spacing (as a distance's), so that along the diagonal the lookup
    falls and rises by sqrt(2) metres a metre: lipschitz sqrt(2)."""
    k = np.arange(-40, 41)
    values = c + res * (np.abs(k)[None, :] + np.abs(k)[:, None])
    return ClearanceField(-40 * res, -40 * res, res, values)


def _leg(field, ankle, end, lip, ankle_clear=None, end_clear=None):
    """landing_leg_clear of a leg from ``ankle`` to the end pelvis ``end`` (world x + iy; the
    hip on the pelvis: P_HIP_Y 0) in ``field``, its constant taken as ``lip``."""
    par = stepcheck.params(
        leg_step=LEG_PROBE_STEP, leg_clearance=leg_clearance(1.75), hip_y=0.0, field_lip=lip
    )
    loc = np.zeros(M + 2, dtype=np.complex128)
    loc[M - 1], loc[M] = end, ankle
    f = field
    a = f(np.array([ankle.real, ankle.imag])) if ankle_clear is None else ankle_clear
    e = f(np.array([end.real, end.imag])) if end_clear is None else end_clear
    ny, nx = f.values.shape
    return stepcheck.landing_leg_clear(
        loc, M, True, 0.0, 1.0 + 0j, 0j, float(a), float(e), par, f.values, f.x0, f.y0,
        f.resolution, nx, ny,
    )  # fmt: skip


def _lowest(field, a, b):
    t = np.linspace(0.0, 1.0, int(abs(b - a) / 2e-4) + 2)
    z = a + t * (b - a)
    return float(field(np.stack([z.real, z.imag], axis=-1)).min())


def test_a_leg_over_an_adversarial_cell_keeps_the_stated_clearance():
    """Every point of an accepted leg keeps P_LEG_CLEARANCE - LEG_PROBE_STEP / 2 in a field
    whose lookup is sqrt(2)-Lipschitz (the shipped ones are): taken as 1-Lipschitz, the
    probes' cover overreaches and a leg through the valley passes with its low point 5 mm
    short of it."""
    target = leg_clearance(1.75) - LEG_PROBE_STEP / 2
    field = _valley(target - 0.005)
    assert field.lipschitz == pytest.approx(math.sqrt(2.0), abs=1e-12)
    diag = complex(1.0, 1.0) / math.sqrt(2.0)
    ankle, end = -0.2 * diag, 0.3 * diag
    assert _lowest(field, ankle, end) < target - 0.004  # the valley's floor at the origin
    assert _leg(field, ankle, end, 1.0)  # the 1-Lipschitz rule lets it through
    assert not _leg(field, ankle, end, field.lipschitz)
    # seeded sweep: legs of 0.2-0.55 m in every direction across the valley
    rng = np.random.default_rng(5)
    accepted = 0
    for _ in range(400):
        u = complex(*rng.normal(size=2))
        u /= abs(u)
        off = rng.uniform(-0.06, 0.06) * 1j * u
        back = rng.uniform(0.05, 0.5)
        ankle = off - back * u
        end = ankle + rng.uniform(0.2, 0.55) * u
        if _leg(field, ankle, end, field.lipschitz):
            accepted += 1
            assert _lowest(field, ankle, end) >= target - 1e-12
    assert accepted > 40
