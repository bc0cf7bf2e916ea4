"""Humanoid model: structure, neutral pose on the floor, collision bits, attachment to scenes."""

from __future__ import annotations

from pathlib import Path

import mujoco
import numpy as np
import pytest

from mjwalk.body.humanoid import (
    HUMAN_GROUP,
    JointMap,
    attach_humanoid,
    build_humanoid,
    humanoid_model,
    leg_geometry,
    pelvis_height,
)
from mjwalk.errors import SceneError

SCENES = Path(__file__).parents[2] / "scenes"
BOX_SCENE = """<mujoco><worldbody><geom name="floor" type="plane" size="5 5 .1"/>
<body name="table" pos="1 0 .4"><geom name="box" type="box" size=".3 .3 .4"/></body>
</worldbody></mujoco>"""


def _lowest_point(model, data, geom_ids):
    z = []
    for g in geom_ids:
        c, R, sz = data.geom_xpos[g], data.geom_xmat[g].reshape(3, 3), model.geom_size[g]
        signs = np.array(np.meshgrid([-1, 1], [-1, 1], [-1, 1])).reshape(3, -1).T
        z.append((c + (signs * sz) @ R.T)[:, 2].min())
    return min(z)


def test_joint_inventory():
    _, jm = humanoid_model()
    names = set(jm.names)
    for side in "lr":
        for j in (
            "hip_{}_flex",
            "hip_{}_abd",
            "hip_{}_rot",
            "knee_{}",
            "ankle_{}_flex",
            "ankle_{}_inv",
            "toe_{}",
            "shoulder_{}_flex",
            "shoulder_{}_abd",
            "shoulder_{}_rot",
            "elbow_{}",
            "forearm_{}_pron",
            "wrist_{}_flex",
            "wrist_{}_dev",
        ):
            assert j.format(side) in names
        assert sum(n.startswith(f"thumb_{side}_") for n in names) >= 2
        for f in ("index", "middle", "ring", "little"):
            assert sum(n.startswith(f"{f}_{side}_") for n in names) >= 2
    for j in ("lumbar_flex", "thoracic_rot", "neck_flex"):
        assert j in names
    # ranges are sane: knee 0..135 deg, hip flexion -30..120 deg
    assert np.allclose(np.rad2deg(jm.limits("knee_l")), (0, 135))
    assert np.allclose(np.rad2deg(jm.limits("hip_r_flex")), (-30, 120))
    assert np.all(jm.range[:, 0] < jm.range[:, 1])


@pytest.mark.parametrize("stature", [1.55, 1.75, 1.95])
def test_neutral_pose_feet_on_floor_and_height(stature):
    model, jm = humanoid_model(stature)
    data = mujoco.MjData(model)
    data.qpos[:] = jm.neutral_qpos(model, stature)
    mujoco.mj_forward(model, data)
    feet = [model.geom(n).id for n in ("foot_l", "foot_r", "toes_l", "toes_r")]
    assert abs(_lowest_point(model, data, feet)) < 1e-6
    everything = [g for g in range(model.ngeom) if model.geom_type[g] == mujoco.mjtGeom.mjGEOM_BOX]
    assert _lowest_point(model, data, everything) > -1e-6
    head = model.geom("head").id
    top = data.geom_xpos[head][2] + model.geom_size[head][0]
    assert top == pytest.approx(stature, abs=0.02)
    assert data.xpos[model.body("pelvis").id][2] == pytest.approx(pelvis_height(stature))
    g = leg_geometry(stature)
    assert g.thigh + g.shank + g.ankle_height == pytest.approx(pelvis_height(stature))


def test_humanoid_faces_plus_x_and_flexion_signs():
    model, jm = humanoid_model()
    data = mujoco.MjData(model)
    q = jm.neutral_qpos(model)
    q[jm.adr("hip_l_flex")] = np.deg2rad(30)
    q[jm.adr("knee_r")] = np.deg2rad(60)
    data.qpos[:] = q
    mujoco.mj_forward(model, data)
    assert data.xpos[model.body("shin_l").id][0] > 0.1  # left knee forward (+x)
    assert data.xpos[model.body("foot_r").id][0] < -0.1  # right ankle behind
    assert data.site_xpos[model.site("sole_l").id][1] > 0  # left is +y


def test_no_self_collision_but_collides_with_scene():
    spec = mujoco.MjSpec.from_string(BOX_SCENE)
    model, jm = attach_humanoid(spec)
    data = mujoco.MjData(model)
    q = jm.neutral_qpos(model)
    q[jm.root : jm.root + 2] = [0.75, 0.0]  # torso overlaps the box at x = 0.7..1.3
    data.qpos[:] = q
    mujoco.mj_forward(model, data)
    box = model.geom("box").id
    pairs = {(int(c.geom1), int(c.geom2)) for c in data.contact[: data.ncon]}
    human = model.geom_group == HUMAN_GROUP
    assert any(box in p for p in pairs)
    assert not any(human[a] and human[b] for a, b in pairs)
    assert all(model.geom(g).name.startswith("human/") for g in np.flatnonzero(human))
    assert model.geom("box").group != HUMAN_GROUP


def test_attach_does_not_modify_spec_and_bad_scene(tmp_path):
    spec = mujoco.MjSpec.from_string(BOX_SCENE)
    n_before = len(spec.bodies)
    attach_humanoid(spec)
    assert len(spec.bodies) == n_before
    with pytest.raises(SceneError, match="no such scene"):
        attach_humanoid(tmp_path / "missing.xml")
    bad = tmp_path / "bad.xml"
    bad.write_text("<mujoco><worldbody><geom type='nonsense'/></worldbody></mujoco>")
    with pytest.raises(SceneError, match=r"bad\.xml"):
        attach_humanoid(bad)
    with pytest.raises(SceneError, match="stature"):
        build_humanoid(0.3)


def test_project_scenes_attach():
    for name in ("assembly_station.xml", "corridor.xml", "open_floor.xml"):
        path = SCENES / name
        if not path.exists():
            continue
        _, jm = attach_humanoid(path)
        assert jm.prefix == "human/"
        assert len(jm.names) == 67


def test_humanoid_xml_matches_builder():
    model = mujoco.MjModel.from_xml_path(str(SCENES / "humanoid.xml"))
    built, jm = humanoid_model()
    assert model.nq == built.nq
    jm2 = JointMap.from_model(model)
    assert jm2.names == jm.names
    assert np.allclose(jm2.range, jm.range)
    assert np.allclose(model.body_pos, built.body_pos)
