"""Crouching for a reach into a low compartment (mjwalk.cycle.crouch): the feet stay planted,
the body stays balanced over them, and a reach that touches the shelf above from a standing or
stooping shoulder becomes clear by MuJoCo's collision check."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

import mjwalk.cycle.reaching as reaching
from mjwalk.cycle.crouch import _com_ahead, crouch_frames, crouch_pose
from mjwalk.cycle.handling import BODY_MOTION_TMU, TMU
from mjwalk.cycle.poses import _standing, frame_contacts
from mjwalk.cycle.simulate import prepare
from mjwalk.cycle.spec import load_cycle_spec

SHELF = '<geom name="rack1_shelf" type="box" size="0.4 0.25 0.02" pos="0 0 1.0" material="shelf"/>'
#: A shelf at 0.7 m under rack 1's (at 1.0 m) and a site on it, 20 cm into the rack: a
#: compartment 26 cm high at knuckle height.
LOW = (
    '<geom name="rack1_shelf_mid" type="box" size="0.4 0.25 0.02" pos="0 0 0.7" '
    'material="shelf"/>\n<site name="rack1_low" pos="0.1 0.05 0.76" size="0.02"/>'
)
CYCLE = """name = "low compartment"
scene = "assembly_station.xml"
start = "stand_rack1"
[humanoid]
stature = 1.75
[[task]]
kind = "pick"
site = "rack1_low"
hand = "left"
"""


@pytest.fixture(scope="module")
def ctx(scenes_dir, tmp_path_factory):
    folder = tmp_path_factory.mktemp("low")
    xml = (scenes_dir / "assembly_station.xml").read_text()
    assert SHELF in xml
    (folder / "assembly_station.xml").write_text(xml.replace(SHELF, f"{SHELF}\n{LOW}"))
    (folder / "cycle.toml").write_text(CYCLE)
    return prepare(load_cycle_spec(folder / "cycle.toml"))


def _feet(ctx, q):
    """Ankle joint centres (2, 3) and the lowest point of the foot geoms (m) in pose ``q``."""
    m, jm = ctx.model, ctx.jointmap
    d = mujoco.MjData(m)
    d.qpos[:] = q
    mujoco.mj_kinematics(m, d)
    ankles = np.array([d.xanchor[m.joint(f"{jm.prefix}ankle_{p}_flex").id] for p in "lr"])
    return ankles


def _com(ctx, q):
    """How far the centre of mass lies ahead of the ankles in pose ``q`` (m)."""
    d = mujoco.MjData(ctx.model)
    d.qpos[:] = q
    mujoco.mj_kinematics(ctx.model, d)
    return _com_ahead(ctx, d)


@pytest.mark.parametrize("drop", [0.05, 0.15, 0.25])
def test_a_crouch_lowers_the_pelvis_with_the_feet_planted_and_balanced(ctx, drop):
    jm = ctx.jointmap
    q0 = _standing(ctx, 0.3, -0.2, 0.7)
    q = crouch_pose(ctx, q0, drop)
    assert q[jm.root + 2] == pytest.approx(q0[jm.root + 2] - drop)
    assert np.abs(_feet(ctx, q) - _feet(ctx, q0)).max() < 1e-6  # ankles where they stood
    assert q[jm.adr("knee_l")] > 0.3 and q[jm.adr("knee_r")] > 0.3  # the knees bend
    # the pelvis goes back; the trunk bends until the centre of mass is over the feet as
    # standing (within one balance step's worth)
    assert _com(ctx, q) >= _com(ctx, q0) - 1e-9
    for name in ("hip_l_flex", "knee_l", "ankle_l_flex", "lumbar_flex", "thoracic_flex"):
        lo, hi = jm.limits(name)
        assert lo - 1e-9 <= q[jm.adr(name)] <= hi + 1e-9
    # the way down keeps the feet planted at every pose, from standing to the crouch
    w = np.linspace(0.0, 1.0, 9)
    frames = crouch_frames(ctx, q0, q, w)
    assert np.allclose(frames[0], q0)
    assert np.allclose(frames[-1], q)
    for f in frames:
        assert np.abs(_feet(ctx, f) - _feet(ctx, q0)).max() < 1e-6
    assert np.all(np.diff(frames[:, jm.root + 2]) < 0)  # the pelvis goes down all the way


def test_no_drop_is_the_standing_pose(ctx):
    q0 = _standing(ctx, 0.0, 0.0, 0.0)
    assert np.array_equal(crouch_pose(ctx, q0, 0.0), q0)


def test_a_reach_into_a_low_compartment_crouches_and_is_clear(ctx, monkeypatch):
    """Standing or stooping, the thumb and forearm go through the upper shelf's front edge;
    crouched, the reach is clear, the hand on its target, the feet planted; it takes the
    MTM-1 bend and arise on top of the reach."""
    jm = ctx.jointmap
    task = ctx.spec.tasks[0]
    st = ctx.workplace.station("stand_rack1")

    def reach():
        return reaching._reach_task(
            ctx, task, st.pos[0], st.pos[1], st.yaw, 0.4, 30.0, reaching._default_timing
        )

    with monkeypatch.context() as m:
        m.setattr(reaching, "CROUCH_DROPS", ())
        standing = reach()
    assert standing.distance < 0.0
    assert {c.scene_geom for c in frame_contacts(ctx, standing.frames)} & {"rack1_shelf"}
    r = reach()
    assert r.distance == np.inf
    assert not frame_contacts(ctx, np.vstack([r.turn, r.frames]))
    assert r.error < 0.01
    z = r.frames[:, jm.root + 2]
    assert z.min() < r.turn[-1, jm.root + 2] - 0.05  # crouched
    assert z[-1] == pytest.approx(r.turn[-1, jm.root + 2])  # and up again
    ankles = _feet(ctx, r.turn[-1])
    for f in r.frames[:: max(1, len(r.frames) // 20)]:
        assert np.abs(_feet(ctx, f) - ankles).max() < 1e-6
    # the way down and up each last at least the MTM-1 bend / arise (reference adult)
    down = np.flatnonzero(z <= z.min() + 1e-9)[0]
    up = len(z) - 1 - np.flatnonzero(z <= z.min() + 1e-9)[-1]
    assert (down + 1) / 30.0 >= BODY_MOTION_TMU["B"] * TMU - 1 / 30.0
    assert up / 30.0 >= BODY_MOTION_TMU["AB"] * TMU - 1 / 30.0
