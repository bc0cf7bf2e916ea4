"""The stance leg up a ramp (mjwalk.body.legs.rampstance, issue 47 deliverable 4)."""

import numpy as np
import pytest

from mjwalk.anthropometry import leg_geometry
from mjwalk.body.legs import legs_from_walk
from mjwalk.body.legs.rampstance import RAMP_STANCE_DORSI_GAIN, uphill_stance_raise
from mjwalk.body.legs.stance import REACH_DROP_MAX
from mjwalk.body.legs.steps import FootTracks
from mjwalk.plan.synthetic import synthetic_ramp_walk, synthetic_walk


def _stance_peaks(angle):
    """On a synthetic ramp of ``angle`` (radians; 0: level), per mid step (not the first two
    or the last): the stance foot's peak ankle flexion over the step's single support and its
    knee flexion at mid-step, degrees."""
    walk = synthetic_ramp_walk(angle)
    motion = legs_from_walk(walk)
    out = []
    for st in walk.steps[2:-1]:
        s, single = ("r", 1) if st.side == "left" else ("l", 0)
        sl = np.arange(st.start, st.end + 1)
        sl = sl[motion.contact[sl] == single]
        mid = (st.start + st.end) // 2
        dorsi = np.rad2deg(motion.angles[f"ankle_{s}_flex"][sl].max())
        out.append((dorsi, float(np.rad2deg(motion.angles[f"knee_{s}"][mid]))))
    return np.array(out)


def test_gain_is_the_cited_end_points_slope():
    assert RAMP_STANCE_DORSI_GAIN == pytest.approx((21.0 - 10.1) / 20.0)


def test_uphill_stance_ankle_gains_the_cited_share_of_the_slope():
    """Up a 5.5 deg ramp the stance ankle's peak dorsiflexion over single support exceeds the
    level walk's by at most the cited share of the slope (0.545 x 5.5 = 3.0 deg, +0.3 deg for
    the solve), stays inside the 20 deg range, and the stance knee at mid-step extends from
    32.4-34.2 deg (the ramp before) to 27-29 deg (level walk: 31.7 deg). The loading response
    (double support) is left as it was: 17-19.6 deg uphill against 6-9 deg level."""
    slope = 5.5
    level, ramp = _stance_peaks(0.0), _stance_peaks(np.deg2rad(slope))
    gain = RAMP_STANCE_DORSI_GAIN * slope
    assert np.all(ramp[:, 0] <= level[:, 0].max() + gain + 0.3)
    assert np.all(ramp[:, 0] <= 20.0 + 1e-6)
    assert np.all((ramp[:, 1] > 24.0) & (ramp[:, 1] < 31.0))


def test_no_raise_downhill_on_level_ground_or_in_double_support():
    """The raise is nil off uphill slopes (down a ramp, level ground) and while both feet are
    grounded; up a slope it is positive in single support and at most REACH_DROP_MAX."""
    walk = synthetic_walk(n_steps=4)
    n = len(walk.t)
    rng = np.random.default_rng(0)
    ankle = {s: np.column_stack([np.linspace(0, 2, n), np.full(n, y), np.full(n, 0.08)])
             for s, y in (("l", 0.09), ("r", -0.09))}  # fmt: skip
    feet = FootTracks(ankle, {s: np.zeros(n) for s in "lr"}, {s: np.zeros(n) for s in "lr"},
                      {s: np.zeros(n) for s in "lr"}, {s: np.ones(n, bool) for s in "lr"},
                      {s: np.zeros((n, 3)) for s in "lr"})  # fmt: skip
    root = np.column_stack([np.linspace(0, 2, n), np.zeros(n), np.full(n, 0.9)])
    root[:, 0] += rng.uniform(-0.1, 0.1, n)
    flat = ({s: ankle[s].copy() for s in "lr"}, {s: np.zeros(n) for s in "lr"}, root.copy())
    air = {"l": np.arange(n) % 40 < 15, "r": (np.arange(n) + 20) % 40 < 15}
    yaw = np.zeros(n)
    geom = leg_geometry()
    for pitch in (0.0, np.deg2rad(-5.5)):
        surface = {s: np.full(n, pitch) for s in "lr"}
        assert not uphill_stance_raise(feet, flat, root, yaw, air, surface, geom, 3).any()
    both = {s: np.zeros(n, bool) for s in "lr"}  # double support throughout
    up = {s: np.full(n, np.deg2rad(5.5)) for s in "lr"}
    assert not uphill_stance_raise(feet, flat, root, yaw, both, up, geom, 3).any()
    for s in "lr":  # the feet pitched to an uphill slope: the ankles dorsiflex more
        feet.pitch[s][:] = np.deg2rad(5.5)
    raise_ = uphill_stance_raise(feet, flat, root, yaw, air, up, geom, 3)
    assert raise_.max() > 0.0 and raise_.max() <= REACH_DROP_MAX + 1e-12
