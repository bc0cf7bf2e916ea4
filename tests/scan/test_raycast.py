"""mjwalk.scan.raycast: synthetic scans of an MJCF scene by MuJoCo's rays."""

from __future__ import annotations

import mujoco
import numpy as np

from mjwalk.scan.raycast import cast, synthetic_scan

ROOM = mujoco.MjModel.from_xml_string(
    """<mujoco><worldbody>
    <geom name="floor" type="plane" size="3 3 0.1"/>
    <geom name="box" type="box" pos="1.5 0 0.5" size="0.3 0.3 0.5"/>
    </worldbody></mujoco>"""
)


def test_noiseless_hits_lie_on_the_scene():
    hits = cast(ROOM, np.array([0.0, 0.0, 1.5]), 5.0, rng=np.random.default_rng(0), noise=0.0)
    assert hits.ndim == 2 and hits.shape[1] == 3 and len(hits) > 100
    on_floor = np.abs(hits[:, 2]) < 1e-9
    on_box = (np.abs(hits[:, 0] - 1.5) <= 0.3 + 1e-9) & (hits[:, 2] <= 1.0 + 1e-9)
    assert (on_floor | on_box).all() and on_box.any()


def test_to_scene_undoes_the_tilt_and_lift():
    scan = synthetic_scan(ROOM, [(0.0, 0.0, 1.5)], step_deg=5.0, noise=0.0, seed=1)
    np.testing.assert_array_equal(scan.scanners, [[0.0, 0.0, 1.5]])
    back = scan.points @ scan.to_scene[:3, :3].T + scan.to_scene[:3, 3]
    assert np.abs(back[:, 2]).min() < 1e-9  # floor hits back at z = 0
    assert back[:, 2].min() > -1e-9
    assert scan.points[:, 2].min() < -1.3  # the floor was moved to -1.37 m
