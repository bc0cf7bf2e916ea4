"""mjwalk.world.generate: reproducible halls of separated obstacles."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk import SceneError
from mjwalk.world.generate import free_points, generate_hall


def test_generated_hall_is_reproducible_and_as_asked():
    a, b = generate_hall(12, 8, seed=5), generate_hall(12, 8, seed=5)
    assert a.xml == b.xml
    assert generate_hall(12, 8, seed=6).xml != a.xml
    assert len(a.circles) == round(0.4 * 12 * 8)
    c = a.circles
    gaps = np.hypot(*(c[:, None, :2] - c[None, :, :2]).transpose(2, 0, 1)) - c[:, 2] - c[:, 2, None]
    np.fill_diagonal(gaps, np.inf)
    assert gaps.min() >= 0.7 - 1e-9  # every gap is passable
    for kind in ("box", "cylinder", "capsule"):
        assert f'type="{kind}"' in a.xml
    with pytest.raises(SceneError, match="cannot place"):
        generate_hall(6, density=3.0)
    with pytest.raises(SceneError, match="kinds"):
        generate_hall(10, kinds=("cone",))


def test_free_points_keep_their_clearance_from_every_obstacle():
    hall = generate_hall(8, seed=2)
    pts = free_points(hall, 20, np.random.default_rng(0), clearance=0.5)
    assert pts.shape == (20, 2)
    c = hall.circles
    gap = np.hypot(pts[:, None, 0] - c[None, :, 0], pts[:, None, 1] - c[None, :, 1]) - c[None, :, 2]
    assert gap.min() >= 0.5 - 1e-9


def test_a_written_hall_is_its_xml(tmp_path):
    hall = generate_hall(6, seed=1)
    path = hall.write(tmp_path / "h.xml")
    assert path.read_text() == hall.xml
