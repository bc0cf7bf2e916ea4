"""mjwalk.world.probe: MuJoCo's own distance from floor probes to the scene's geoms."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.world.probe import ClearanceProbe, path_clearance

SCENE = """<mujoco><worldbody>
  <geom name="floor" type="plane" size="3 3 0.1"/>
  <geom name="post" type="cylinder" pos="1 0 0.5" size="0.2 0.5"/>
  <geom name="shelf" type="box" pos="-1 0 0.5" size="0.1 0.1 0.5"/>
</worldbody></mujoco>"""


@pytest.fixture(scope="module")
def probe(tmp_path_factory):
    path = tmp_path_factory.mktemp("probe") / "scene.xml"
    path.write_text(SCENE)
    return ClearanceProbe(path)


def test_distances_per_geom_and_the_nearest(probe):
    assert probe.names == ["post", "shelf"]
    d = probe.distances(np.array([[0.0, 0.0], [1.0, 1.0]]))
    assert d.shape == (2, 2)
    np.testing.assert_allclose(d[0], [0.8, 0.9], atol=1e-6)
    np.testing.assert_allclose(probe.clearance(np.array([[1.0, 1.0]])), [0.8], atol=1e-6)


def test_path_clearance_samples_the_polyline(probe):
    c = path_clearance(probe, np.array([[0.0, -1.0], [0.0, 1.0]]), spacing=0.1)
    assert c.shape == (21,)  # the start and 20 samples
    assert c.min() == pytest.approx(0.8, abs=1e-6)  # at (0, 0)


def test_a_probe_of_a_box_floor_scene_measures_from_its_top_past_the_floor(tmp_path):
    """A scene file whose floor is a box with its top at 0.5 m: the probes stand on it and
    measure the obstacles, not the floor under them."""
    path = tmp_path / "slab.xml"
    path.write_text(
        '<mujoco><worldbody><geom name="slab" type="box" size="3 3 0.05" pos="0 0 0.45"/>'
        '<geom name="post" type="box" size="0.1 0.1 1" pos="1 0 1.5"/></worldbody></mujoco>'
    )
    probe = ClearanceProbe(path)
    assert probe.names == ["post"]
    assert probe.distances(np.array([[0.0, 0.0]]))[0, 0] == pytest.approx(0.9, abs=1e-6)
