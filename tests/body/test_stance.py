"""The stance leg of one step, compiled (mjwalk.body.legs.stance)."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.body.humanoid import leg_geometry
from mjwalk.body.legs.ik import KNEE_MIN
from mjwalk.body.legs.reference import DEFAULT_REFERENCE, ReferenceGait
from mjwalk.body.legs.stance import (
    REACH_DROP_MAX,
    KneeEnds,
    LandingEase,
    StanceLeg,
    bound_lowering,
    floor_reach_sq,
    lower_to_reach,
    pelvis_height,
    reach_deficit,
    stance_knee,
)
from mjwalk.body.legs.steps import step_frames
from mjwalk.errors import PlanningError
from mjwalk.plan.synthetic import synthetic_walk

PHI = np.array([0.0, 0.2, 0.4, 0.5, 0.6, 0.8, 1.0])


def _stance_case():
    g = leg_geometry(1.75)
    n = len(PHI)
    ankle = np.column_stack([np.zeros((n, 2)), np.full(n, g.ankle_height)])
    k_ref = DEFAULT_REFERENCE("knee", 0.5 * PHI)
    ends = KneeEnds(th0=0.2, v0=0.0, th1=0.15, v1=0.0)
    knee, z = stance_knee(DEFAULT_REFERENCE, PHI, k_ref, ends, np.zeros((n, 2)), ankle, g)
    return g, ankle, k_ref, knee, z


def test_stance_knee_meets_its_ends_and_the_reference_keys():
    """The knee starts at th0, ends at th1 and equals the reference at the key frames
    (phi 0.4, 0.5, 0.6); with the hip over the ankle the pelvis is a leg span above it."""
    g, ankle, k_ref, knee, z = _stance_case()
    assert knee[0] == pytest.approx(0.2) and knee[-1] == pytest.approx(0.15)
    assert np.allclose(knee[2:5], k_ref[2:5])
    assert np.allclose(z, ankle[:, 2] + g.span(knee))


def test_pelvis_height_caps_at_the_swing_legs_reach():
    """Without the landing ease, the pelvis height is the stance leg's, capped where the
    swing leg's ankle (here 0.6 m ahead) is out of its longest reach; nothing is eased."""
    g, ankle, _, knee, z_flat = _stance_case()
    fr = step_frames(synthetic_walk(n_steps=2))[1]
    n = len(PHI)
    ankle_sw = ankle + [0.6, 0.0, 0.0]
    d_max = float(g.span(0.05))
    leg = StanceLeg(np.zeros((n, 2)), knee, np.zeros(n))
    z, eased = pelvis_height(PHI, z_flat, ankle_sw, np.zeros((n, 2)), leg, fr,
                             LandingEase(d_max**2, d_max, 2.0), g)  # fmt: skip
    assert eased is None
    cap = g.ankle_height + np.sqrt(d_max**2 - 0.36)
    assert np.allclose(z, np.minimum(z_flat, cap))
    assert np.any(z < z_flat)


def test_reach_deficit_is_zero_off_the_floor_and_measures_overreach():
    g = leg_geometry(1.75)
    n = 3
    ankle = {s: np.column_stack([np.zeros((n, 2)), np.full(n, g.ankle_height)]) for s in "lr"}
    reach_sq = {s: np.full(n, 0.8**2) for s in "lr"}
    root = np.column_stack([np.zeros((n, 2)), g.ankle_height + np.array([0.7, 0.8, 0.9])])
    off = {s: np.zeros(n, bool) for s in "lr"}
    assert np.all(reach_deficit(root, np.zeros(n), ankle, off, reach_sq, g) == 0)
    on = {"l": np.ones(n, bool), "r": np.zeros(n, bool)}
    d = reach_deficit(root, np.zeros(n), ankle, on, reach_sq, g)
    cap = g.ankle_height + np.sqrt(0.8**2 - g.hip_y**2)
    assert np.allclose(d, np.maximum(root[:, 2] - cap, 0.0))


@pytest.mark.parametrize("over", [0.03, 0.2])
def test_lower_to_reach_lowers_a_little_and_refuses_a_lot(over):
    """A grounded left leg its pelvis ``over`` metres too high to reach its ankle: 3 cm is
    lowered (the pelvis then reaches within the 1 mm the passes stop at); 0.2 m (the platform
    cycle's run 14 lowered 0.21 m for a 120 deg turn in one step) is more than
    REACH_DROP_MAX and raises."""
    g = leg_geometry(1.75)
    n = 41
    ankle = {s: np.column_stack([np.zeros((n, 2)), np.full(n, g.ankle_height)]) for s in "lr"}
    reach_sq = {s: np.full(n, 0.8**2) for s in "lr"}
    cap = g.ankle_height + np.sqrt(0.8**2 - g.hip_y**2)
    root = np.column_stack([np.zeros((n, 2)), np.full(n, cap + over)])
    on = {"l": np.ones(n, bool), "r": np.zeros(n, bool)}
    if over > REACH_DROP_MAX:
        with pytest.raises(PlanningError, match="lowered"):
            lower_to_reach(root, np.zeros(n), ankle, on, reach_sq, g, 5)
        return
    drop = lower_to_reach(root, np.zeros(n), ankle, on, reach_sq, g, 5)
    assert over <= drop <= REACH_DROP_MAX
    assert reach_deficit(root, np.zeros(n), ankle, on, reach_sq, g).max() <= 1e-3


@pytest.mark.parametrize("stature", [1.55, 1.75, 1.95])
def test_floor_reach_sq_is_the_numpy_expression_bit_for_bit(stature):
    """The compiled squared spans are ``geom.span(np.clip(ref("knee", cyc), KNEE_MIN, hi))
    ** 2`` to the bit, wrapped fractions (negative, past 1, exactly 1) and the clip's both
    ends included; a table off the unit cycle takes the NumPy path with the same numbers."""
    g = leg_geometry(stature)
    rng = np.random.default_rng(5)
    cyc = np.r_[rng.uniform(-0.5, 1.5, 4000), 0.0, 1.0, 0.5, -0.0, 2.0]
    hi = float(np.deg2rad(10.0))
    want = g.span(np.clip(DEFAULT_REFERENCE("knee", cyc), KNEE_MIN, hi)) ** 2
    got = floor_reach_sq(DEFAULT_REFERENCE, cyc, hi, g)
    assert got.tobytes() == want.tobytes()
    k = DEFAULT_REFERENCE("knee", cyc)
    assert (k < KNEE_MIN).any() and (k > hi).any()  # both bounds clip somewhere
    ref = DEFAULT_REFERENCE
    shifted = ReferenceGait(ref.cycle * 2.0, ref.hip, ref.knee, ref.pitch)
    want2 = g.span(np.clip(shifted("knee", cyc), KNEE_MIN, hi)) ** 2
    assert floor_reach_sq(shifted, cyc, hi, g).tobytes() == want2.tobytes()


def test_reach_deficit_with_kept_yaw_sines_is_the_same():
    """The compiled ankle fit's deficit with the pelvis yaw's cosines and sines read from an
    IK cache (where its kept yaw is the row's, to the bit; else taken) is reach_deficit's,
    bit for bit: rows kept, rows kept for another yaw, a -0.0 against a kept +0.0, NaN."""
    from mjwalk.body.legs.ikcache import LegIKCache
    from mjwalk.body.legs.stance import reach_deficit_kept

    g = leg_geometry(1.75)
    rng = np.random.default_rng(9)
    n = 90
    yaw = rng.uniform(-3.5, 3.5, n)
    yaw[:4] = (0.0, -0.0, np.nan, np.pi)
    root = np.column_stack([rng.uniform(-0.1, 0.1, (n, 2)), rng.uniform(0.85, 0.95, n)])
    left, right = LegIKCache("l", g), LegIKCache("r", g)
    kept_yaw = yaw.copy()
    kept_yaw[1], kept_yaw[10:20] = 0.0, kept_yaw[10:20] + 0.1  # another yaw kept there
    left.share_trig(right, kept_yaw, kept_yaw, kept_yaw)
    for s_, cache in (("l", left), ("r", right)):
        ankle = np.column_stack([root[:, :2] + rng.uniform(-0.2, 0.2, (n, 2)), np.full(n, 0.08)])
        ground = rng.uniform(size=n) < 0.7
        reach_sq = np.full(n, rng.uniform(0.6, 0.8) ** 2)
        o = "r" if s_ == "l" else "l"  # (the other leg off the floor: no deficit)
        want = reach_deficit(
            root, yaw, {s_: ankle, o: ankle}, {s_: ground, o: np.zeros(n, bool)},
            {s_: reach_sq, o: reach_sq}, g,
        )  # fmt: skip
        out = np.zeros(n)
        c = (1.0 if s_ == "l" else -1.0) * float(g.hip_y)
        reach_deficit_kept(root, yaw, ankle, ground, reach_sq, c, *cache.trig_buffers(n), out)
        assert out.tobytes() == want.tobytes()
        assert (want > 0).any()


def test_bound_lowering_refuses_over_the_bound_in_one_line_naming_the_point():
    """The whole lowering is bounded by REACH_DROP_MAX: within it the largest is returned, over
    it a one-line PlanningError names where (the pelvis's x, y)."""
    root = np.column_stack([np.arange(5.0), np.full(5, 2.0), np.full(5, 0.9)])
    low = np.array([0.0, 0.01, REACH_DROP_MAX + 0.004, 0.02, 0.0])
    with pytest.raises(PlanningError, match=r"0\.054 m lowered at \(2\.00, 2\.00\)") as err:
        bound_lowering(low, root)
    assert "\n" not in str(err.value)
    assert bound_lowering(np.minimum(low, REACH_DROP_MAX), root) == REACH_DROP_MAX
    assert bound_lowering(np.zeros(0), root[:0]) == 0.0


def test_lower_to_reach_bounds_its_lowering_with_the_one_before():
    """A 3 cm lowering is within the bound alone, but not on top of a flat synthesis's 3 cm
    (``before``): the two are one lowering of the pelvis, bounded once; ``before`` holds the
    sum afterwards."""
    g = leg_geometry(1.75)
    n = 41
    ankle = {s: np.column_stack([np.zeros((n, 2)), np.full(n, g.ankle_height)]) for s in "lr"}
    reach_sq = {s: np.full(n, 0.8**2) for s in "lr"}
    cap = g.ankle_height + np.sqrt(0.8**2 - g.hip_y**2)
    on = {"l": np.ones(n, bool), "r": np.zeros(n, bool)}

    def root():
        return np.column_stack([np.zeros((n, 2)), np.full(n, cap + 0.03)])

    alone = lower_to_reach(root(), np.zeros(n), ankle, on, reach_sq, g, 5)
    before = np.full(n, 0.01)
    total = lower_to_reach(root(), np.zeros(n), ankle, on, reach_sq, g, 5, before)
    assert total == pytest.approx(alone + 0.01)
    assert before.max() == pytest.approx(total)
    with pytest.raises(PlanningError, match="lowered"):
        lower_to_reach(root(), np.zeros(n), ankle, on, reach_sq, g, 5, np.full(n, 0.03))
