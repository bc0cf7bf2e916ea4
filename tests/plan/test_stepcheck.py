"""The planner's step check (mjwalk.plan.stepcheck.check_steps) on sampled steps."""

from __future__ import annotations

import math

import numpy as np
import pytest
from test_lean import FRAME, M

from mjwalk.anthropometry import leg_geometry
from mjwalk.body.legs.stance import REACH_DROP_MAX
from mjwalk.body.legs.synthesis import legs_from_walk
from mjwalk.gait.default import default_model
from mjwalk.gait.walker import Walker
from mjwalk.plan import slots, stepcheck
from mjwalk.plan.hybrid import HybridPlanner
from mjwalk.plan.lean import lean_in_range, stance_lean
from mjwalk.plan.options import SWING_LIFT_TURN, PlannerOptions, foot_reach
from mjwalk.plan.request import WalkRequest
from mjwalk.plan.walks import plan_walk
from mjwalk.timeline.collisions import check_collisions
from mjwalk.world import load_workplace
from mjwalk.world.generate import free_points, generate_hall


@pytest.mark.parametrize("foot_x", [0.1, -0.2])
def test_check_steps_refuses_the_steps_the_stance_leg_cannot_follow(scenes_dir, foot_x, request):
    """In the planner's step check (sampled steps, decoded by the planner's affine map) a step
    is refused exactly when its stance leg leans out of range, by the NumPy form on the
    model's own decoding; the stance foot is the node's landed foot (column 4: its heading).
    Without a heading (a start node) the check is skipped. (The landed foot's reach, shorter
    across the foot when it has a heading, is held the same every way here.)"""
    model = default_model()
    wp = load_workplace(scenes_dir / "open_floor.xml")
    pl = HybridPlanner(wp, "east", model)
    par, ipar = pl.params.vectors()
    par = par.copy()
    par[slots.P_FOOT_ROLL] = np.nan  # the foot's reach the same every way (the lean alone)
    dec = pl.decoder()
    rng = np.random.default_rng(2)
    z = model.sample_next_features(model.sample_first(1, rng, "right").features, "right", 300, rng)
    batch = model.decode(z, "left")  # swing left: the right foot stands
    local, yaw = batch.resample(M)
    stance = np.array([foot_x, 0.05, FRAME])  # the landed right foot, beside the start
    args = (dec.matrix, dec.offset, len(z), len(z), np.array([FRAME]), np.array([True]),
            np.zeros(1, bool))  # fmt: skip
    rest = (pl.params.thresholds, par, ipar, wp.walk_field().values, pl.distance.flat_bound())
    node = np.array([[0j, complex(stance[0], stance[1]), np.nan, 0.0, stance[2]]])
    rows = stepcheck.check_steps(z, *args, node, *rest)[0]
    node[0, 4] = np.nan
    free = stepcheck.check_steps(z, *args, node, *rest)[0]
    want = [
        r
        for r in free
        if lean_in_range(*stance_lean(local[r], FRAME + yaw[r], stance, False, par), par)
    ]
    np.testing.assert_array_equal(rows, want)
    if foot_x > 0:  # a foot under the hip: (measured) all but a few steps pass
        assert len(rows) > 0.9 * len(free)
    else:  # a foot crossed under the other: most are refused
        assert len(rows) < 0.5 * len(free)


@pytest.mark.parametrize("foot_x", [0.1, -0.2])
def test_deferred_legs_checks_accept_what_check_steps_accepts(scenes_dir, foot_x):
    """check_into with ``defer`` accepts every step whose pelvis and ankle keep clear, and
    legs_recheck on each (as the search runs it on the steps it pops) then refuses exactly the
    steps check_steps refuses beyond those: the same steps, with the same scores."""
    model = default_model()
    wp = load_workplace(scenes_dir / "open_floor.xml")
    pl = HybridPlanner(wp, "east", model)
    par, ipar = pl.params.vectors()
    dec = pl.decoder()
    rng = np.random.default_rng(3)
    z = model.sample_next_features(model.sample_first(1, rng, "right").features, "right", 300, rng)
    frame, left = np.array([FRAME]), np.array([True])
    args = (dec.matrix, dec.offset, len(z), len(z), frame, left, np.zeros(1, bool))
    node = np.array([[0j, complex(foot_x, 0.05), complex(0.0, -0.3), 0.0, complex(FRAME, FRAME)]])
    rest = (pl.params.thresholds, par, ipar, wp.walk_field().values, pl.distance.flat_bound())
    eager = stepcheck.check_steps(z, *args, node, *rest)
    out = stepcheck.new_buffers(len(z), ipar[slots.I_M])
    counts = (np.zeros(1, np.int64), np.zeros(1, np.int64))
    n = stepcheck.check_into(z, *args, node, *rest, out, *counts, True)
    loc = np.empty_like(out[10])
    thr, _, _, coef, _ = rest
    kept = [
        c
        for c in range(n)
        if stepcheck.legs_recheck(
            z, out[0][c], *args[:2], FRAME, True, node, thr, par, ipar, coef, loc
        )
    ]
    assert n > len(kept)  # the legs' checks refuse some of the steps deferred to them
    np.testing.assert_array_equal(out[0][kept], eager[0])
    np.testing.assert_array_equal(out[2][kept], eager[2])  # f


#: Station run 330 of 2000 (seed 0, main at ae71305): route T4's eighth step, the left foot
#: swinging from (0.664, -1.711) heading -88.5 deg to (0.303, -1.714) heading -155.8 deg while
#: the pelvis (16 samples, world x, y) turned from -136.8 to -178.5 deg beside rack 2's frame.
RUN330_PELVIS = [
    (0.543, -1.719), (0.524, -1.712), (0.506, -1.706), (0.487, -1.701), (0.470, -1.696),
    (0.453, -1.692), (0.437, -1.689), (0.423, -1.688), (0.409, -1.687), (0.395, -1.687),
    (0.382, -1.689), (0.369, -1.691), (0.357, -1.694), (0.344, -1.698), (0.332, -1.703),
    (0.319, -1.709),
]  # fmt: skip


def _one_step(pl, wp, vectors, pelvis, fr, ankle, yaws, landed, behind, right=False):
    """Whether :func:`stepcheck.check_steps` accepts one decoded step, as a function of the
    lifting foot's heading: the pelvis's samples ``pelvis`` (world x, y), the step's frame
    heading ``fr``, the landing ankle (x, y), the landing foot's and the end pelvis's yaw,
    the landed and the behind footprints (complex x + iy); radians, metres. The swing foot is
    the left one (``right``: the right one)."""
    par, ipar = vectors
    m = int(ipar[slots.I_M])
    assert m == len(pelvis)
    rot = complex(math.sin(fr), -math.cos(fr))  # local (x right, y forward) to world
    p = complex(*pelvis[0])
    offset = np.zeros(2 * m + 3, dtype=np.complex128)
    offset[:m] = [(complex(x, y) - p) / rot for x, y in pelvis]
    offset[m] = (complex(*ankle) - p) / rot  # the landing ankle
    offset[m + 1] = complex(yaws[0] - fr, yaws[1] - fr)  # landing foot's and end pelvis's yaw
    matrix = np.zeros((1, 2 * m + 3), dtype=np.complex128)  # z = 0 decodes to the offset
    rest = (pl.params.thresholds, par, ipar, wp.walk_field().values, pl.distance.flat_bound())

    def accepted(lift_heading: float) -> bool:
        # column 4: no landed heading (no stance-lean check), the lifting foot's heading
        node = np.array([[p, landed, behind, 0.0, complex(math.nan, lift_heading)]])
        args = (np.zeros((1, 1)), matrix, offset, 1, 1, np.array([fr]), np.array([not right]),
                np.zeros(1, bool), node)  # fmt: skip
        return len(stepcheck.check_steps(*args, *rest)[0]) == 1

    return accepted


def test_the_knee_probes_lead_along_the_turning_swing_foot(scenes_dir):
    """The knee bends in its foot's plane, and a swing foot turns to its landing yaw only by
    0.9 of the step: in run 330's turning step the left knee went 0.33 m beside the pelvis and
    3 cm into rack 2's frame (a 1.81 m operator) while the probes, ahead along the pelvis's
    yaw, stayed clear. The step passes with the lifting foot's heading unknown (the probes
    along the pelvis's yaw, as before) and is refused with it (along the foot's yaw)."""
    model = default_model()
    wp = load_workplace(scenes_dir / "assembly_station.xml")
    pl = HybridPlanner(wp, "stand_rack2", model, PlannerOptions(radius=0.30))
    fr = -2.388  # the pelvis's heading at the step's start (the step's frame)
    accepted = _one_step(
        pl, wp, pl.params.vectors(1.81), RUN330_PELVIS, fr, (0.303, -1.714),
        (-2.718, -3.115), complex(0.426, -1.726), complex(0.664, -1.711),
    )  # fmt: skip
    assert accepted(math.nan)  # the pelvis, ankle, toes, landing leg and reach all pass
    assert not accepted(-1.545)  # the knee, ahead along the lagging foot, meets the frame
    assert accepted(-2.3)  # a foot already turned with the pelvis keeps its knee clear
    # a foot past the hip's rotation range off the pelvis spins about its ball before it lifts
    # (mjwalk.body.legs.spin): a footprint 69-160 deg off lifts as one at the range
    at_range = accepted(fr + SWING_LIFT_TURN)
    assert not at_range
    assert all(accepted(fr + off) == at_range for off in (1.2, 2.0, 2.8))


#: Station run 1865 of 2000 (seed 0, main at c7f4517): route T4's last step, a 1.87 m operator's
#: right foot from (0.071, -1.409) to (0.262, -1.834) at yaw -60.6 deg beside rack 2's frame
#: post, the pelvis (16 samples, world x, y) turning from -70.5 to -60.9 deg.
RUN1865_PELVIS = [
    (0.229, -1.524), (0.217, -1.524), (0.206, -1.525), (0.197, -1.528), (0.190, -1.532),
    (0.185, -1.538), (0.181, -1.546), (0.179, -1.555), (0.178, -1.564), (0.179, -1.576),
    (0.181, -1.590), (0.185, -1.605), (0.190, -1.623), (0.197, -1.642), (0.205, -1.663),
    (0.215, -1.686),
]  # fmt: skip


def test_the_landing_toes_keep_clear_for_a_tall_walker(scenes_dir):
    """A tall walker's toes reach past the fixed toe probe (FOOT_LENGTH ahead of the ankle): in
    run 1865's last step the right toes' corner went 3.6 mm into rack 2's frame post while the
    probe lay 9.4 cm from it. The toes' corner probes for the stature refuse the step; without
    them (nan slot, as before) the step passes, and a 1.55 m walker's toes clear."""
    model = default_model()
    wp = load_workplace(scenes_dir / "assembly_station.xml")
    pl = HybridPlanner(wp, "stand_rack2", model, PlannerOptions(radius=0.30))

    def accepted(stature: float, centre: bool = True) -> bool:
        par, ipar = pl.params.vectors(stature)
        par = par.copy()
        if not centre:
            par[slots.P_TOE_FRONT] = math.nan
        m = int(ipar[slots.I_M])
        assert m == len(RUN1865_PELVIS)
        fr = -1.231  # the pelvis's heading at the step's start (the step's frame)
        rot = complex(math.sin(fr), -math.cos(fr))  # local (x right, y forward) to world
        p = complex(*RUN1865_PELVIS[0])
        offset = np.zeros(2 * m + 3, dtype=np.complex128)
        offset[:m] = [(complex(x, y) - p) / rot for x, y in RUN1865_PELVIS]
        offset[m] = (complex(0.262, -1.834) - p) / rot  # the landing ankle
        offset[m + 1] = complex(-1.058 - fr, -1.063 - fr)  # landing foot's and end pelvis's yaw
        matrix = np.zeros((1, 2 * m + 3), dtype=np.complex128)
        landed, behind = complex(0.157, -1.483), complex(0.071, -1.409)
        node = np.array([[p, landed, behind, 0.0, complex(math.nan, math.nan)]])
        rest = (pl.params.thresholds, par, ipar, wp.walk_field().values, pl.distance.flat_bound())
        args = (np.zeros((1, 1)), matrix, offset, 1, 1, np.array([fr]), np.array([False]),
                np.zeros(1, bool), node)  # fmt: skip
        return len(stepcheck.check_steps(*args, *rest)[0]) == 1

    assert accepted(1.87, centre=False)  # pelvis, ankle, toe probe, leg and knees pass
    assert not accepted(1.87)  # the left corner, 0.213 m ahead, is within 2.5 cm of the post
    assert accepted(1.55)  # 0.177 m ahead, 0.042 m aside: clear


#: Generated hall 317 (``generate_hall`` with /work/dbg/flatstress.py's draws, seed 317), walk
#: 1 (rng 3171, main 39c83c0): the eleventh step, the left foot swinging from (3.812, -0.087)
#: heading 142.6 deg to (4.183, 0.598) heading 50.2 deg while the pelvis (16 samples, world x,
#: y) turned from 84.8 to 47.5 deg beside the thin box ``box7``.
HALL317_PELVIS = [
    (3.897, -0.031), (3.904, -0.009), (3.913, 0.017), (3.921, 0.039), (3.929, 0.060),
    (3.939, 0.085), (3.948, 0.106), (3.957, 0.128), (3.968, 0.154), (3.978, 0.176),
    (3.989, 0.200), (4.004, 0.230), (4.017, 0.257), (4.031, 0.287), (4.051, 0.326),
    (4.069, 0.361),
]  # fmt: skip


def _hall317(path):
    """Generated hall 317 as the flat-hall stress draws it (size and density from the seed),
    and its second walk's start and goal (free points drawn on after them)."""
    rng = np.random.default_rng(317)
    w, d, density = rng.uniform(6, 14), rng.uniform(5, 12), rng.uniform(0.15, 0.5)
    hall = generate_hall(w, d, density=density, seed=317)
    ends = free_points(hall, 8, rng)[2:4]
    return load_workplace(hall.write(path), cache=False), (tuple(ends[0]), tuple(ends[1]))


def test_the_knee_probes_cover_the_early_swing_of_a_turning_step(tmp_path):
    """Just after toe-off the swing foot still points along its lift-off yaw, and the knee
    bends in its plane: in hall 317's turning step the left knee was 0.24 m beside the pelvis
    at 0.31 of the step and the thigh went 2.2 cm into ``box7``, while the probes at half and
    four fifths of the step, the foot turned towards its landing yaw by then, kept 0.27 and
    0.47 m. The probe at a third of the step refuses it; a foot lifting along the pelvis's
    heading keeps its knee clear."""
    model = default_model()
    wp, (_, goal) = _hall317(tmp_path / "hall317.xml")
    pl = HybridPlanner(wp, goal, model)
    fr = 1.480  # the pelvis's heading at the step's start (the step's frame)
    accepted = _one_step(
        pl, wp, pl.params.vectors(), HALL317_PELVIS, fr, (4.183, 0.598), (0.877, 0.829),
        complex(4.017, -0.028), complex(3.812, -0.087),
    )  # fmt: skip
    assert accepted(fr)  # pelvis, ankle, toes, landing leg, reach and knees pass
    assert not accepted(2.489)  # the lifting footprint's heading: the early knee meets box7


@pytest.mark.slow
def test_hall317_s_turning_walk_keeps_its_knees_off_the_thin_box(tmp_path):
    """The walk of hall 317 (walk 1 of the flat-hall stress draws, rng 3171) played back: at
    39c83c0 the left thigh went 2.2 cm and the shin 0.8 cm into ``box7`` at 6.1 s, in the early
    swing of a step turning the foot 92 deg; with the early knee probe no contact."""
    wp, (start, goal) = _hall317(tmp_path / "hall317.xml")
    assert np.allclose(start, (6.0879, -1.9730), atol=1e-4)
    walk = plan_walk(wp, start, goal, default_model(), rng=3171)
    assert check_collisions(walk, tmp_path / "hall317.xml") == []


#: Station runs 5909 and 9828 of 10 000 (seed 0, main at eea2d7c): walk 4 (to rack 3's stand
#: zone), the step whose right foot lands behind its start pelvis, the pelvis (16 samples, world
#: x, y) going back; the stature, the frame heading (the pelvis's at the step's start), the
#: landing ankle (x, y), the landing foot's and the end pelvis's yaw, the landed and the behind
#: footprints (x, y) and the behind foot's heading. Leg synthesis then lowered the pelvis 6.3
#: cm (5909, in the next step) and 7.5 cm (9828) below its gait's height to reach the stance
#: foot: more than REACH_DROP_MAX, the run refused.
BACKWARD_STEPS = {
    5909: (
        [
            (-2.882, -1.003), (-2.891, -1.034), (-2.898, -1.063), (-2.903, -1.088),
            (-2.906, -1.110), (-2.907, -1.129), (-2.906, -1.143), (-2.903, -1.154),
            (-2.897, -1.160), (-2.889, -1.163), (-2.878, -1.163), (-2.865, -1.159),
            (-2.850, -1.151), (-2.831, -1.139), (-2.809, -1.123), (-2.784, -1.103),
        ],
        1.67, 3.447, (-2.460, -0.924), (3.141, 3.672), (-2.927, -1.165), (-2.831, -0.855),
        3.329,
    ),
    9828: (
        [
            (-2.880, -1.153), (-2.871, -1.181), (-2.862, -1.208), (-2.854, -1.234),
            (-2.846, -1.257), (-2.838, -1.277), (-2.829, -1.295), (-2.820, -1.311),
            (-2.811, -1.324), (-2.800, -1.336), (-2.789, -1.345), (-2.776, -1.353),
            (-2.761, -1.359), (-2.743, -1.364), (-2.723, -1.368), (-2.701, -1.370),
        ],
        1.71, 3.026, (-2.431, -1.398), (3.104, 3.551), (-3.084, -1.295), (-2.461, -0.912),
        3.129,
    ),
}  # fmt: skip


@pytest.mark.parametrize("run", sorted(BACKWARD_STEPS))
def test_a_step_going_backward_is_refused(scenes_dir, run):
    """A walking step goes forward (options.MIN_STEP_ADVANCE: no step of the virtual corpus
    ends its pelvis or lands its foot behind its start pelvis): the backward steps of station
    runs 5909 and 9828, which every other check passes (the slot nan: the check as it was),
    are refused."""
    model = default_model()
    wp = load_workplace(scenes_dir / "assembly_station.xml")
    pl = HybridPlanner(wp, "stand_rack3", model, PlannerOptions(radius=0.30))
    pelvis, stature, fr, ankle, yaws, landed, behind, lift = BACKWARD_STEPS[run]
    par, ipar = pl.params.vectors(stature)
    assert par[slots.P_STEP_ADVANCE] == 0.0
    before = par.copy()
    before[slots.P_STEP_ADVANCE] = math.nan  # no forward test
    # the end pelvis and the landing ankle lie behind the start pelvis along the frame heading
    rot = complex(math.sin(fr), -math.cos(fr))
    p = complex(*pelvis[0])
    assert ((complex(*pelvis[-1]) - p) / rot).imag < -0.06
    assert ((complex(*ankle) - p) / rot).imag < -0.4

    def accepted(vectors, right=True) -> bool:
        return _one_step(
            pl, wp, vectors, pelvis, fr, ankle, yaws, complex(*landed), complex(*behind),
            right=right,
        )(lift)  # fmt: skip

    assert accepted((before, ipar))  # every other check passes it
    assert not accepted((par, ipar))


#: Station run 4395 of 10 000 (seed 0, main at bebb988): walk 6 (to rack 2's stand zone) of a
#: 1.56 m operator, its sixth step: the left foot swinging from (0.042, -0.401) to land at
#: (0.501, -0.909), 0.24 m behind the right (stance) foot at (0.714, -1.026) along the step's
#: heading, while the pelvis (16 samples, world x, y) went 0.19 m on and turned from -36.9 to
#: -67.5 deg. The leg synthesis then reached the stance foot, 0.29 m ahead of its hip at the
#: landing, only with the pelvis 6.8 cm lowered: more than REACH_DROP_MAX, the run refused.
RUN4395_PELVIS = [
    (0.345, -0.725), (0.354, -0.739), (0.363, -0.752), (0.372, -0.764), (0.381, -0.777),
    (0.389, -0.789), (0.397, -0.800), (0.406, -0.811), (0.414, -0.821), (0.421, -0.831),
    (0.429, -0.840), (0.436, -0.849), (0.443, -0.858), (0.450, -0.866), (0.456, -0.873),
    (0.461, -0.880),
]  # fmt: skip


def test_a_step_landing_behind_its_stance_foot_is_refused(scenes_dir):
    """A walking step's swing foot passes its stance foot (options.MIN_STEP_ADVANCE: every
    walking step of the virtual corpus lands at least 0.043 m ahead of it): run 4395's step,
    which lands its foot 0.24 m behind the stance foot but ahead of its start pelvis, and
    keeps the pelvis within the stance foot's reach (from the pelvis's centre and from the
    stance hip alike), passes every other check (the slot nan) and is refused."""
    model = default_model()
    wp = load_workplace(scenes_dir / "assembly_station.xml")
    pl = HybridPlanner(wp, "stand_rack2", model, PlannerOptions(radius=0.30))
    stature, fr, ankle, stance = 1.56, -0.644, (0.501, -0.909), complex(0.714, -1.026)
    par, ipar = pl.params.vectors(stature)
    assert par[slots.P_STEP_ADVANCE] == 0.0
    before = par.copy()
    before[slots.P_STEP_ADVANCE] = math.nan  # no forward tests
    rot = complex(math.sin(fr), -math.cos(fr))
    p = complex(*RUN4395_PELVIS[0])
    # ahead of the start pelvis (the end pelvis and the ankle: the backward-step test passes)
    assert ((complex(*RUN4395_PELVIS[-1]) - p) / rot).imag > 0.18
    assert ((complex(*ankle) - p) / rot).imag > 0.23
    assert ((complex(*ankle) - stance) / rot).imag < -0.23  # behind the stance foot
    # within the stance foot's reach, from the pelvis and from the right (stance) hip
    reach = foot_reach(stature)[0]
    hip_y = leg_geometry(stature).hip_y
    yaws = np.linspace(fr, -1.179, len(RUN4395_PELVIS))  # the pelvis turning, about
    for (x, y), yaw in zip(RUN4395_PELVIS, yaws, strict=True):
        assert abs(complex(x, y) - stance) < reach
        assert abs(complex(x, y) + hip_y * complex(math.sin(yaw), -math.cos(yaw)) - stance) < reach

    def accepted(vectors) -> bool:
        return _one_step(
            pl, wp, vectors, RUN4395_PELVIS, fr, ankle, (-0.916, -1.179), stance,
            complex(0.042, -0.401),
        )(0.053)  # fmt: skip

    assert accepted((before, ipar))  # every other check passes it
    assert not accepted((par, ipar))


#: Run 4395's walk 6 as the cycle plans it: the planner's goal area, the request, the 1.56 m
#: operator and the generator's state at the planner's call (captured with a patched
#: HybridPlanner.plan).
RUN4395_OPTIONS = {
    "goal_tolerance": 0.3315,
    "radius": 0.3,
    "field_tolerance": 0.1,
    "goal_within": (
        (-999.79798, -1.700000000000283, 1000.0),
        (1000.0, -1.6999999999997164, 1000.0),
        (0.0, -2.32, 0.663911822078503),
    ),
}
RUN4395_RNG = {
    "bit_generator": "PCG64",
    "state": {
        "state": 71085363061274267203554025669402711488,
        "inc": 17108495919640527093914482573125731175,
    },
    "has_uint32": 0,
    "uinteger": 2044463890,
}


def test_station_run_4395s_walk_keeps_its_stance_feet_behind_the_swing_feet(scenes_dir):
    """Run 4395's walk, planned as the cycle plans it: at bebb988 its sixth step landed the
    left foot 0.24 m behind the right one and the leg synthesis refused the walk
    (PlanningError: the pelvis 0.068 m lowered, 0.05 m at most). Now every walking step's
    foot lands ahead of its stance foot along its start heading, and the legs synthesize
    with the pelvis lowered at most REACH_DROP_MAX."""
    wp = load_workplace(scenes_dir / "assembly_station.xml")
    model = default_model()
    walker = Walker(1.56, 1.3413849790568098, 121.30946832727464, None, "adult")
    planner = HybridPlanner(wp, (0.0, -1.7), model, PlannerOptions(**RUN4395_OPTIONS))
    request = WalkRequest(
        (-0.6433779808699324, -0.054628615131999014, 1.2916376933297675),
        model.for_walker(walker),
        (0.039255240267781814, -1.6961176612557949, 0.33172636832550173),
        turn_on_spot=True,
        goal_heading=-np.pi / 2,
        at_work=True,
        work_heading=np.pi / 2,
    )
    rng = np.random.default_rng()
    rng.bit_generator.state = RUN4395_RNG
    walk = planner.plan(request, rng)
    legs = legs_from_walk(walk, walker.stature)  # raised PlanningError at bebb988
    assert float(np.max(legs.meta["pelvis_lowering"])) <= REACH_DROP_MAX
    walking = walk.steps[1:-1] if walk.meta.get("closing_step") else walk.steps[1:]
    assert len(walking) >= 5
    for s in walking:  # (the first step's stance foot is where the walker stood)
        fr = walk.yaw[s.start]
        ahead = (complex(*s.foot[:2]) - complex(*s.stance[:2])) / complex(
            math.sin(fr), -math.cos(fr)
        )
        assert ahead.imag > 0.0
