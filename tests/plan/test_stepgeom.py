"""The planner's step geometry (mjwalk.plan.stepgeom).

The landing foot's way in (issue 45, item 2): station run 32 of seed 0 brushed rack 1's left
upright with its left toes one frame before the last step of route T3 landed. The landing
footprint kept FOOT_CLEARANCE at the ankle and the toes, but the step came in 28 degrees off the
foot's heading, so the foot, turned to its landing yaw, slid sideways into place and its toes
swept past the upright's front corner. The planner now probes that approach
(:func:`mjwalk.plan.stepgeom.toe_approach_clear`) and the run has no contact any more."""

from __future__ import annotations

import cmath
import math

import numpy as np
import pytest

from mjwalk.plan.options import FOOT_CLEARANCE, FOOT_LENGTH, TOE_APPROACH_SHARE, TOE_PROBE_STEP
from mjwalk.plan.slots import params
from mjwalk.plan.stepgeom import (
    beyond,
    out_of_reach,
    passes_stance,
    swing_yaw,
    toe_approach_clear,
    unit_turn,
    within,
)
from mjwalk.world import load_workplace
from mjwalk.world.clearance import ClearanceField

# run 32's last step of T3 (main at 8f7a18a): the left foot lifts off at LIFT and lands at LAND
# (ankle footprint, world x + iy, metres) facing YAW (radians from +x), 0.10 m beside rack 1's
# left upright
LIFT = complex(-2.47812, -1.02129)
LAND = complex(-3.10343, -2.02832)
YAW = -1.62589


def _approach_clear(wp, lift, land=LAND, yaw=YAW, share=TOE_APPROACH_SHARE):
    """toe_approach_clear in the world frame (the step frame's turn 1, origin 0)."""
    field = wp.walk_field()
    ny, nx = field.values.shape
    par = params(toe_share=share, toe_step=TOE_PROBE_STEP)
    toe = FOOT_LENGTH * cmath.exp(1j * yaw)
    return toe_approach_clear(
        land, lift, toe, FOOT_CLEARANCE, FOOT_CLEARANCE, 1.0 + 0j, 0j, par,
        field.values, field.x0, field.y0, field.resolution, nx, ny,
    )  # fmt: skip


def _clearance(wp, z: complex) -> float:
    return float(wp.walk_clearance(np.array([[z.real, z.imag]]))[0])


def test_run_32_oblique_landing_beside_the_upright_is_refused(scenes_dir):
    wp = load_workplace(scenes_dir / "assembly_station.xml")
    toe = LAND + FOOT_LENGTH * cmath.exp(1j * YAW)
    # the landing checks that were there pass: ankle and toes keep FOOT_CLEARANCE
    assert _clearance(wp, LAND) >= FOOT_CLEARANCE
    assert _clearance(wp, toe) >= FOOT_CLEARANCE
    # the chord is 28 degrees off the landing yaw
    off = abs(math.remainder(cmath.phase(LAND - LIFT) - YAW, 2 * math.pi))
    assert math.degrees(off) == pytest.approx(28.7, abs=0.5)
    # 5 cm before landing, on its way in, the toes are within FOOT_CLEARANCE of the upright
    u = (LAND - LIFT) / abs(LAND - LIFT)
    assert _clearance(wp, toe - 0.05 * u) < FOOT_CLEARANCE
    assert not _approach_clear(wp, LIFT)


def test_the_same_landing_reached_along_the_foots_heading_is_accepted(scenes_dir):
    wp = load_workplace(scenes_dir / "assembly_station.xml")
    # lifted off 1.2 m straight behind the landing (the toes come in along their own axis)
    assert _approach_clear(wp, LAND - 1.2 * cmath.exp(1j * YAW))


def test_no_approach_check_without_its_slots_or_lift_off(scenes_dir):
    wp = load_workplace(scenes_dir / "assembly_station.xml")
    assert _approach_clear(wp, LIFT, share=math.nan)  # slots unset: no check
    assert _approach_clear(wp, complex(math.nan, math.nan))  # a starter: no foot behind


@pytest.mark.slow
def test_station_run_32_has_no_contact(scenes_dir):
    # the whole run (about 40 s): the walk to rack 1 now ends where the swing clears the upright
    from mjwalk.cycle.simulate import simulate_cycle
    from mjwalk.cycle.spec import load_cycle_spec

    spec = load_cycle_spec(scenes_dir / "assembly_station.toml")
    rng = np.random.default_rng(np.random.SeedSequence([0, 32]))
    r = simulate_cycle(spec, rng, run=32, ergonomics=False)
    assert r.collisions == []


def test_beyond_and_within_agree_with_abs_off_the_band():
    rng = np.random.default_rng(1)
    v = rng.normal(size=200) + 1j * rng.normal(size=200)
    for z in v:
        assert beyond(z, 1.0) == (abs(z) > 1.0)
        assert within(z, 1.0) == (abs(z) <= 1.0)
    assert not beyond(complex(np.nan, 0.0), 1.0) and not within(complex(np.nan, 0.0), 1.0)


def test_unit_turn_is_exp_i_angle():
    for angle in (0.0, 0.5, -2.0, math.pi):
        assert unit_turn(angle) == complex(math.cos(angle), math.sin(angle))
        assert abs(unit_turn(angle) - cmath.exp(1j * angle)) < 1e-15


def test_swing_yaw_turns_the_short_way_round():
    assert swing_yaw(0.5, 1.5, 0.0) == 0.5
    assert swing_yaw(0.5, 1.5, 1.0) == pytest.approx(1.5)
    # from 170 to -170 deg: through 180, not back through 0
    half = swing_yaw(math.radians(170), math.radians(-170), 0.5)
    assert math.cos(half) == pytest.approx(-1.0)
    assert swing_yaw(math.radians(170), math.radians(-170), 1.0) == pytest.approx(math.radians(190))


def test_a_closing_draw_said_to_miss_the_goal_misses_it_at_its_true_variance():
    """closing_ends_miss (the search skips such draws' variance): over the default model's
    closing draws near a goal, every draw it says misses has all its steps' true end points
    (the full draw, decoder column m - 1) outside the goal disc; and it says so of most
    draws whose ends all lie well outside, not of draws with an end inside."""
    from mjwalk.gait.default import default_model
    from mjwalk.gait.gpdraw import compose, draw_parts, variance
    from mjwalk.plan.decoder import decoder_of
    from mjwalk.plan.slots import iparams
    from mjwalk.plan.stepgeom import closing_ends_miss, decode_col, in_goal

    model = default_model(progress=False)
    m = 16
    dec = decoder_of(model, m)
    gp = model.stop_gp["left"].kernel
    rng = np.random.default_rng(0)
    xs = model.gp["left"].inducing  # predecessors where the model has data
    said, hit, all_out = 0, 0, 0
    for k in range(400):
        x = np.ascontiguousarray(xs[k % len(xs)][None, :])
        frame = rng.uniform(-math.pi, math.pi)
        p = complex(*rng.uniform(-0.8, 0.8, 2))
        par = params(goal_x=0.0, goal_y=0.0, tolerance=0.25)
        ipar = iparams(m=m, n_discs=0)
        mean, e, rows, eps = draw_parts(x, 5, rng, gp, 10.0)
        z = compose(mean, variance(e, gp), rows, eps, 5, gp[7])[0]
        rot = complex(math.sin(frame), -math.cos(frame))
        ends = [decode_col(z, r, dec.matrix, dec.offset, m - 1) * rot + p for r in range(5)]
        inside = [in_goal(end, 0.0, par, ipar) for end in ends]
        miss = closing_ends_miss(
            mean, rows, eps, gp[7], math.sqrt(gp[9]), dec.matrix, dec.offset, m, frame, p, par,
            ipar,
        )  # fmt: skip
        if miss:
            said += 1
            assert not any(inside)
        hit += any(inside)
        all_out += min(abs(end) for end in ends) > 0.5
    assert hit > 0 and said > 0.5 * all_out


def test_the_approach_over_an_adversarial_cell_keeps_the_stated_clearance():
    """Every point of the ankle's and the toes' way in keeps FOOT_CLEARANCE - TOE_PROBE_STEP
    / 2 when the approach is accepted, in a field whose lookup is sqrt(2)-Lipschitz: nodes
    c + |i| + |j| spacings (each node difference one spacing, as a distance's), a valley along
    the diagonal; taken as 1-Lipschitz, the probes' cover overreaches it."""
    res = 0.02
    target = FOOT_CLEARANCE - TOE_PROBE_STEP / 2
    k = np.arange(-40, 41)
    field = ClearanceField(
        -0.8, -0.8, res, target - 0.004 + res * (abs(k)[None, :] + abs(k)[:, None])
    )
    ny, nx = field.values.shape

    def clear(land, lift, toe, lip):
        par = params(toe_share=1.0, toe_step=TOE_PROBE_STEP, field_lip=lip)
        start = min(field(np.array([z.real, z.imag])) for z in (land, land + toe))
        return toe_approach_clear(
            land, lift, toe, FOOT_CLEARANCE, float(start), 1.0 + 0j, 0j, par, field.values,
            field.x0, field.y0, res, nx, ny,
        )  # fmt: skip

    def lowest(a, b):
        t = np.linspace(0.0, 1.0, int(abs(b - a) / 2e-4) + 2)
        z = a + t * (b - a)
        return float(field(np.stack([z.real, z.imag], axis=-1)).min())

    diag = complex(1.0, 1.0) / math.sqrt(2.0)
    toe = 0.14 * diag * 1j  # across the valley's floor, the toes out of it
    land, lift = 0.14 * diag, -0.14 * diag  # the ankle's way in crosses the floor
    assert lowest(lift, land) < target - 0.003
    assert clear(land, lift, toe, 1.0)  # the 1-Lipschitz rule lets it through
    assert not clear(land, lift, toe, field.lipschitz)
    rng = np.random.default_rng(6)
    accepted = 0
    for _ in range(400):
        u = complex(*rng.normal(size=2))
        u /= abs(u)
        land = rng.uniform(-0.06, 0.06) * 1j * u + rng.uniform(0.0, 0.3) * u
        lift = land - rng.uniform(0.1, 0.4) * u
        toe = 0.14 * complex(*rng.normal(size=2)) / math.sqrt(2.0)
        if clear(land, lift, toe, field.lipschitz):
            accepted += 1
            assert lowest(lift, land) >= target - 1e-12
            assert lowest(lift + toe, land + toe) >= target - 1e-12
    assert accepted > 40


def test_a_closing_draw_said_far_from_the_goal_misses_it_at_any_mean():
    """closing_ends_far (the search then draws no kernel row): with the default model's
    closing GP and decoder, over draws near a goal, every draw it says is far has all its
    steps' true end points (the full draw) outside the goal disc; it says so of some draws."""
    from mjwalk.gait.default import default_model
    from mjwalk.gait.gpdraw import compose, draw_parts, variance
    from mjwalk.plan.decoder import decoder_of
    from mjwalk.plan.slots import iparams
    from mjwalk.plan.stepgeom import closing_ends_far, decode_col, in_goal

    model = default_model(progress=False)
    m = 16
    dec = decoder_of(model, m)
    tgp = model.stop_gp["left"]
    gp = tgp.kernel
    (r_, spread), f_z = dec.closing_reach(tgp)
    rng = np.random.default_rng(0)
    xs = model.gp["left"].inducing
    said = 0
    for k in range(400):
        x = np.ascontiguousarray(xs[k % len(xs)][None, :] + rng.normal(0.0, 0.3, (1, 6)))
        frame = rng.uniform(-math.pi, math.pi)
        p = complex(*rng.uniform(-1.2, 1.2, 2))
        par = params(goal_x=0.0, goal_y=0.0, tolerance=0.1)
        ipar = iparams(m=m, n_discs=0)
        state = np.random.default_rng(k)
        mean, e, rows, eps = draw_parts(x, 5, state, gp, 10.0)
        z = compose(mean, variance(e, gp), rows, eps, 5, gp[7])[0]
        rot = complex(math.sin(frame), -math.cos(frame))
        ends = [decode_col(z, r, dec.matrix, dec.offset, m - 1) * rot + p for r in range(5)]
        h = -np.log(e[0])
        j = int(np.argmin(h))
        grow = r_ * math.sqrt(2.0 * -math.expm1(-h[j])) + spread
        if closing_ends_far(f_z[j], grow, eps, 5, math.sqrt(gp[9]), dec.matrix, dec.offset, m,
                            frame, p, par, ipar):  # fmt: skip
            said += 1
            assert not any(in_goal(end, 0.0, par, ipar) for end in ends)
            for s in (0.0, 0.5, 1.0):  # the mean and residual alone, at any sd up to the cap
                zs = compose(mean, np.array([s * gp[9]]), rows, eps, 5, gp[7])[0]
                for r in range(5):
                    end = decode_col(zs, r, dec.matrix, dec.offset, m - 1) * rot + p
                    assert abs(end) > 0.1
    assert said > 40


def test_a_planted_foot_reaches_farther_along_its_heading_than_across_it():
    """Issue 50: a foot rolls (heel rise about its ball, heel strike toes up) in its own plane
    only, so the pelvis may lie ``reach`` from its ankle along the foot, behind or ahead, and
    ``reach - roll`` across it; at θ between, ``reach - roll (1 - |cos θ|)``."""
    reach, roll = 0.55, 0.07
    ahead = unit_turn(math.radians(30.0))  # the foot's heading
    for deg, limit in ((30.0, reach), (210.0, reach), (120.0, reach - roll),
                       (90.0, reach - roll * (1 - math.cos(math.radians(60.0)))),
                       (-30.0, reach - roll * (1 - math.cos(math.radians(60.0)))),
                       ):  # fmt: skip
        way = unit_turn(math.radians(deg))
        assert not out_of_reach((limit - 1e-6) * way, ahead, reach, roll), deg
        assert out_of_reach((limit + 1e-6) * way, ahead, reach, roll), deg
    # no foot (nan) is never out of reach; a nan roll is none (the reach alone)
    assert not out_of_reach(complex(math.nan, math.nan), ahead, reach, roll)
    assert not out_of_reach(0.549j, 1 + 0j, reach, math.nan)
    assert out_of_reach(0.551j, 1 + 0j, reach, math.nan)
    nowhere = complex(math.nan, math.nan)  # no heading: the reach every way
    assert not out_of_reach(0.549j, nowhere, reach, roll)
    assert out_of_reach(0.551j, nowhere, reach, roll)


def test_passes_stance_measures_along_the_step_s_start_heading():
    """A walking step's landing ankle (step frame) against its stance ankle (world) along the
    step frame's y, its start heading; a nan stance foot (a starter's) or a nan advance (no
    test) passes."""
    fr = 0.0  # the step's start heading: its frame's y is the world's +x
    rot = complex(math.sin(fr), -math.cos(fr))
    p = complex(1.0, 2.0)
    stance = p + 0.3 * 1j * rot  # 0.3 m ahead of the start pelvis, along the step's heading
    assert passes_stance(0.31j, stance, p, rot, 0.0)  # lands 0.01 m ahead of it
    assert not passes_stance(0.29j + 0.2, stance, p, rot, 0.0)  # 0.01 m behind, aside
    assert not passes_stance(0.31j, stance, p, rot, 0.02)
    assert passes_stance(-0.5j, complex(math.nan, math.nan), p, rot, 0.0)
    assert passes_stance(-0.5j, stance, p, rot, math.nan)
