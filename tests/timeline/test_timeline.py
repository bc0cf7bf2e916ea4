"""mjwalk.timeline.timeline: the Timeline record's frame count, duration, root and joint
angles."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.body.humanoid import humanoid_model
from mjwalk.timeline.timeline import Event, Timeline


def test_timeline_reads_its_frames():
    model, jm = humanoid_model()
    q = np.tile(jm.neutral_qpos(model), (4, 1))
    q[:, jm.root] = [0.0, 0.1, 0.2, 0.3]
    q[:, jm.adr("elbow_l")] = np.radians(30.0)
    tl = Timeline(model=model, jointmap=jm, fps=10.0, t=np.arange(4) / 10.0, qpos=q,
                  events=[Event(0.1, "heel_strike", "left")])  # fmt: skip
    assert tl.n_frames == 4 and tl.duration == pytest.approx(0.3)
    assert tl.root().shape == (4, 3)  # the root's x, y, z, metres
    np.testing.assert_allclose(tl.root()[:, 0], [0.0, 0.1, 0.2, 0.3])
    np.testing.assert_allclose(tl.angle("elbow_l"), np.radians(30.0))
    assert tl.events[0].kind == "heel_strike"
