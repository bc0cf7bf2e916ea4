"""mjwalk.ergonomics.posturejit: the compiled RULA, REBA and OWAS give the NumPy functions'
part scores and scores, frame for frame (thresholds met exactly and NaN angles included)."""

from __future__ import annotations

import numpy as np

from mjwalk.ergonomics import owas, reba, rula
from mjwalk.ergonomics.angles import BodyAngles
from mjwalk.ergonomics.posturejit import posture_inputs
from mjwalk.ergonomics.postures import OwasScore, RebaScore, RulaScore
from mjwalk.ergonomics.score import ScoreContext

#: Angles (deg) at and beside every threshold the methods use.
EDGES = np.array([-60, -20, -5, 0, 5, 10, 15, 20, 30, 45, 60, 90, 100, 120], dtype=float)


def _random_angles(n: int, seed: int) -> BodyAngles:
    rng = np.random.default_rng(seed)

    def ang(*shape):
        a = rng.choice(EDGES, size=(n, *shape)) + rng.choice([0.0, 1e-9, -1e-9, 3.0], (n, *shape))
        a[rng.random((n, *shape)) < 0.02] = np.nan
        return a

    def flag(*shape):
        return rng.random((n, *shape)) < 0.4

    return BodyAngles(
        trunk_flexion=ang(), trunk_side_bend=ang(), trunk_twist=ang(), trunk_inclination=ang(),
        neck_flexion=ang(), neck_side_bend=ang(), neck_twist=ang(), upper_arm_angle=ang(2),
        upper_arm_elevation=ang(2), upper_arm_plane=ang(2), elbow_flexion=ang(2),
        wrist_flexion=ang(2), wrist_deviation=ang(2), wrist_twist=ang(2), twist_range=80.0,
        knee_flexion=ang(2), feet_down=flag(2), walking=flag(), hands=rng.normal(size=(n, 2, 3)),
        ankles=rng.normal(size=(n, 3)), forward=rng.normal(size=(n, 3)),
        shoulder_raised=flag(2), lower_arm_out=flag(2),
    )  # fmt: skip


def _context(n: int, seed: int) -> ScoreContext:
    rng = np.random.default_rng(seed + 100)
    load = rng.choice([0.0, 2.0, 4.9, 5.0, 9.0, 10.0, 12.0, 25.0], size=(n, 2))
    muscle = rng.integers(0, 2, (n, 2))
    coupling = rng.integers(0, 4, (n, 2))
    return ScoreContext((), 60.0, 30.0, load, muscle, coupling)


def test_kernels_give_the_numpy_scores_frame_for_frame():
    n = 4000
    for seed in range(3):
        a, ctx = _random_angles(n, seed), _context(n, seed)
        got = RulaScore().per_frame(a, ctx)
        body = rula.body_parts(a)
        for s in (0, 1):
            p = rula.part_scores(a, s, body)
            for name in p.__dataclass_fields__:
                assert np.array_equal(getattr(got.parts[s], name), getattr(p, name)), name
            m = ctx.muscle[:, s]
            want = rula.parts_score(p, m, rula.force_score(ctx.load[:, s], m > 0))
            assert np.array_equal(got.arm[:, s], want)
        got = RebaScore().per_frame(a, ctx)
        body = reba.body_parts(a)
        for s in (0, 1):
            p = reba.part_scores(a, s, body)
            for name in p.__dataclass_fields__:
                assert np.array_equal(getattr(got.parts[s], name), getattr(p, name)), name
            load = reba.load_score(ctx.load[:, s])
            want = reba.parts_score(p, load, ctx.coupling[:, s], ctx.muscle[:, s])
            assert np.array_equal(got.arm[:, s], want)
        body, arms, flags = posture_inputs(a)
        assert body.shape == (6, n) and arms.shape == (6, n, 2) and flags.shape == (4, n, 2)
        codes = owas.codes(a)
        codes[:, 3] = owas.load_codes(ctx.load.sum(axis=1))
        assert np.array_equal(OwasScore().per_frame(a, ctx), owas.action_category(*codes.T))
