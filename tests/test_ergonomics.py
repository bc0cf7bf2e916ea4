"""The ergonomic methods (mjwalk.ergonomics): published tables and worked examples, the angles
measured on the humanoid, and monotonicity."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.ergonomics import iso11226, niosh, owas, reba, rula
from mjwalk.errors import InputError


def _monotone(table: np.ndarray) -> bool:
    """Never decreasing along any axis (a property of every published score table: a worse
    part score never lowers the result), which catches most transcription slips."""
    return all(bool((np.diff(table, axis=ax) >= 0).all()) for ax in range(table.ndim))


@pytest.mark.parametrize(
    "table", [rula.TABLE_A, rula.TABLE_B, rula.TABLE_C, reba.TABLE_A, reba.TABLE_B, reba.TABLE_C]
)
def test_score_tables_never_decrease(table):
    assert _monotone(table)


def test_table_shapes_and_corners():
    assert rula.TABLE_A.shape == (6, 3, 4, 2) and rula.TABLE_B.shape == (6, 6, 2)
    assert rula.TABLE_C.shape == (8, 7) and reba.TABLE_C.shape == (12, 12)
    assert owas.TABLE.shape == (4, 3, 7, 3)
    # the tables' first and last cells (McAtamney & Corlett 1993; Hignett & McAtamney 2000)
    assert rula.grand_score(1, 1, 1, 1, 1, 1, 1) == 1
    assert rula.grand_score(6, 3, 4, 2, 6, 6, 2, 1, 3, 1, 3) == 7
    assert reba.reba_score(1, 1, 1, 1, 1, 1) == 1
    assert reba.reba_score(5, 3, 4, 6, 2, 3, 3, 3, 3) == 15


def test_reba_worked_example():
    """A worked example (third-party, rs9000/ergonomics README, 'Pose Left'; NOT from Hignett &
    McAtamney 2000, whose text was not at hand): neck 2, trunk 2, legs 2, upper arm 1, lower
    arm 2, wrist 3 -> score A 4, B 3, C 4, REBA 4; with wrist 2 -> B 2, REBA 4."""
    assert reba.TABLE_A[2 - 1, 2 - 1, 2 - 1] == 4
    assert reba.TABLE_B[1 - 1, 2 - 1, 3 - 1] == 3
    assert reba.reba_score(2, 2, 2, 1, 2, 3) == 4
    assert reba.TABLE_B[1 - 1, 2 - 1, 2 - 1] == 2
    assert reba.reba_score(2, 2, 2, 1, 2, 2) == 4


def test_rula_action_levels_and_force():
    assert list(rula.action_level([1, 2, 3, 4, 5, 6, 7])) == [1, 1, 2, 2, 3, 3, 4]
    assert list(reba.risk_level([1, 2, 3, 4, 7, 8, 10, 11, 15])) == [0, 1, 1, 2, 2, 3, 3, 4, 4]
    # McAtamney & Corlett 1993 Fig. 2: < 2 kg 0; 2-10 kg intermittent 1; 2-10 static or
    # repeated 2; >= 10 kg intermittent 2; >= 10 kg static or repeated 3
    assert rula.force_score(1.0, False) == 0
    assert rula.force_score(5.0, False) == 1
    assert rula.force_score(5.0, True) == 2
    assert rula.force_score(12.0, False) == 2
    assert rula.force_score(12.0, True) == 3
    assert reba.load_score(4.9) == 0 and reba.load_score(5) == 1 and reba.load_score(11) == 2


def test_owas_table_known_cells():
    # straight back, arms down, standing on both straight legs, light: no action (1111 -> 1)
    assert owas.action_category(1, 1, 2, 1) == 1
    # bent and twisted back, both arms up, both knees bent: action immediately
    assert owas.action_category(4, 3, 4, 3) == 4
    assert owas.load_code(9.9) == 1 and owas.load_code(15) == 2 and owas.load_code(21) == 3


def test_niosh_example_4_package_inspection():
    """Applications Manual (Waters et al. 1994), Example 4 'Package Inspection', Figure 14
    (p. 46), U.S. units: origin H 10 in, V 22 in, D 37 in, A 0, FM .88, coupling fair;
    destination H 20 in, V 59 in. The worksheet multiplies multipliers rounded to two
    decimals (p. 29): RWL 34.9 lb at the origin, 15.2 lb at the destination; at full
    precision 34.8 and 15.3 lb. (The worksheet figures are taken from a transcription of the
    manual in a public method specification; Table 5 gives FM .88 for 3 lifts/min over
    <= 1 h, the inputs used here.)"""
    kw = dict(d=37.0, a=0.0, f=3.0, duration="short", coupling="fair", units="us")
    o = niosh.multipliers(10.0, 22.0, v_origin=22.0, **kw)
    d = niosh.multipliers(20.0, 59.0, v_origin=22.0, **kw)
    assert (o.hm, round(o.vm, 2), round(o.dm, 2), o.am, o.fm, o.cm) == (
        1.0,
        0.94,
        0.87,
        1.0,
        0.88,
        0.95,
    )
    assert (d.hm, round(d.vm, 2), d.fm, d.cm) == (0.5, 0.78, 0.88, 1.0)
    assert round(niosh.rwl(o, "us", round_multipliers=True), 1) == 34.9
    assert round(niosh.rwl(d, "us", round_multipliers=True), 1) == 15.2
    assert round(niosh.rwl(o, "us"), 1) == 34.8
    assert round(niosh.rwl(d, "us"), 1) == 15.3


def test_niosh_ideal_lift_is_the_load_constant_and_limits():
    m = niosh.multipliers(25.0, 75.0, 25.0, 0.0, 0.2, "short", "good")
    assert niosh.rwl(m) == pytest.approx(23.0)
    assert niosh.multipliers(70.0, 75.0, 25.0, 0.0, 1, "long").hm == 0.0  # H > 63 cm
    assert niosh.multipliers(30.0, 180.0, 25.0, 0.0, 1, "long").vm == 0.0  # V > 175 cm
    assert niosh.multipliers(30.0, 75.0, 25.0, 140.0, 1, "long").am == 0.0  # A > 135 deg
    assert niosh.frequency_multiplier(16.0, "short", 80.0) == 0.0
    assert niosh.frequency_multiplier(2.5, "long", 50.0) == pytest.approx(0.60)  # interpolated
    with pytest.raises(InputError):
        niosh.multipliers(30.0, 75.0, 25.0, 0.0, 1, "forever")
    with pytest.raises(InputError):
        niosh.multipliers(30.0, 75.0, 25.0, 0.0, 1, "long", coupling="sticky")


def test_niosh_heavier_low_pick_raises_the_lifting_index():
    """Adding 10 kg to a low pick raises its lifting index (the RWL does not depend on mass)."""
    a = niosh.lift(0, "pick", "both", 5.0, (40.0, 30.0), (20.0, 90.0), (0.0, 0.0), 1.0, "fair")
    b = niosh.lift(0, "pick", "both", 15.0, (40.0, 30.0), (20.0, 90.0), (0.0, 0.0), 1.0, "fair")
    assert b.rwl == pytest.approx(a.rwl) and b.li == pytest.approx(3 * a.li) and b.li > 1.0


def test_iso11226_holding_times():
    assert iso11226.max_holding_time(10.0) == float("inf")
    assert iso11226.max_holding_time(20.0) == 240.0
    assert iso11226.max_holding_time(60.0) == 60.0
    assert iso11226.max_holding_time(70.0) == 0.0
    fps = 10.0
    ang = np.r_[np.zeros(10), np.full(30, 40.0), np.zeros(10)]  # 3 s at 40 deg: not static
    assert iso11226.holding(ang, fps, "trunk", iso11226.TRUNK_HOLD).held == 0.0
    ang = np.r_[np.zeros(10), np.full(1000, 40.0)]  # 100 s at 40 deg: limit 150 s
    h = iso11226.holding(ang, fps, "trunk", iso11226.TRUNK_HOLD)
    assert h.held == 100.0 and h.limit == pytest.approx(150.0) and h.acceptable
    ang = np.r_[np.zeros(10), np.full(100, 70.0)]  # 10 s beyond 60 deg: not acceptable
    assert not iso11226.holding(ang, fps, "trunk", iso11226.TRUNK_HOLD).acceptable


def _humanoid_angles(**joints):
    from mjwalk.body.humanoid import humanoid_model, pelvis_height
    from mjwalk.ergonomics.angles import angles_from_qpos

    model, jm = humanoid_model()
    q = jm.neutral_qpos(model)
    for name, deg in joints.items():
        q[jm.adr(name)] = np.radians(deg)
    q[jm.root + 2] = pelvis_height(1.75)
    return angles_from_qpos(model, jm, q[None])


def test_neutral_humanoid_measures_neutral():
    a = _humanoid_angles()
    assert abs(a.trunk_flexion[0]) < 1e-6 and abs(a.neck_flexion[0]) < 1e-6
    assert np.allclose(a.upper_arm_angle[0], 0.0, atol=1e-6)
    assert np.allclose(a.elbow_flexion[0], 0.0, atol=1e-6)
    assert a.legs_supported[0]
    p = rula.part_scores(a, 0)
    assert (p.upper_arm[0], p.neck[0], p.trunk[0], p.legs[0]) == (1, 1, 1, 1)


@pytest.mark.parametrize("deg", [10.0, 30.0, 60.0, 100.0])
def test_joint_angles_read_back(deg):
    """The body angles measured by forward kinematics equal the humanoid's hinge angles; the
    trunk's flexion (pelvis to C7) follows a lumbar flexion, less the part of the trunk below
    the lumbar joint."""
    a = _humanoid_angles(shoulder_l_flex=deg, elbow_l=deg / 2, neck_flex=deg / 3)
    assert a.upper_arm_angle[0, 0] == pytest.approx(deg, abs=1e-6)
    assert a.upper_arm_elevation[0, 0] == pytest.approx(deg, abs=1e-6)
    assert a.elbow_flexion[0, 0] == pytest.approx(deg / 2, abs=1e-6)
    assert a.neck_flexion[0] == pytest.approx(deg / 3, abs=1e-6)
    b = _humanoid_angles(lumbar_flex=deg / 2)
    assert 0.8 * deg / 2 < b.trunk_flexion[0] <= deg / 2 + 1e-9
    assert b.trunk_inclination[0] == pytest.approx(b.trunk_flexion[0])


def test_raising_the_arm_never_lowers_the_upper_arm_score():
    """Monotonicity: a higher reach (more shoulder flexion) gives an upper-arm score and a
    RULA score at least as high."""
    ua, score = [], []
    for deg in np.arange(0.0, 180.0, 5.0):
        a = _humanoid_angles(shoulder_l_flex=deg, elbow_l=30.0)
        ua.append(int(rula.part_scores(a, 0).upper_arm[0]))
        score.append(int(rula.rula(a, 0)[0]))
    assert ua == sorted(ua) and ua[0] == 1 and ua[-1] == 4
    assert score == sorted(score)
