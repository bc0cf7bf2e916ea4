"""Step features: landmarks, B-spline decoding, PCA/scaler chain and StepBatch."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.errors import MjwalkError
from mjwalk.gait.features import (
    N_RAW,
    StepBatch,
    StepFeatures,
    raw_features,
    spline_basis,
)
from mjwalk.gait.step import Step


def make_steps(
    rng: np.random.Generator,
    n_takes: int = 20,
    steps_per_take: int = 12,
    fps: float = 120.0,
    stops: bool = False,
) -> list[Step]:
    """Synthetic aligned steps: alternating sides, sinusoidal sway, lengths 0.5-0.8 m,
    durations 0.45-0.65 s; length and duration follow an AR(1) process within a take so
    transitions carry information. Take starts are shorter (gait initiation). With ``stops``
    every take also ends in a closing step of 60 % length, and ``meta`` flags initiations and
    terminations as ``mjwalk.gait.segment`` does (same random stream either way)."""
    steps = []
    for t in range(n_takes):
        side = "left" if rng.random() < 0.5 else "right"
        u_len, u_dur = rng.uniform(0, 1, 2)
        turn_rate = rng.normal(0.0, 0.05)
        for i in range(steps_per_take):
            u_len = np.clip(0.7 * u_len + 0.3 * rng.uniform(0, 1), 0, 1)
            u_dur = np.clip(0.7 * u_dur + 0.3 * rng.uniform(0, 1), 0, 1)
            length = 0.5 + 0.3 * u_len
            dur = 0.45 + 0.2 * u_dur
            if i == 0:
                length *= 0.8
            last = stops and i == steps_per_take - 1
            if last:
                length *= 0.6
            k = round(dur * fps) + 1
            u = np.linspace(0.0, 1.0, k)
            sgn = -1.0 if side == "left" else 1.0  # pelvis sways over the stance foot
            amp = 0.025 + 0.01 * rng.random()
            yaw_end = turn_rate + rng.normal(0.0, 0.02)
            x = sgn * amp * np.sin(np.pi * u) - 0.5 * yaw_end * length * u**2
            y = length * (u + 0.05 * np.sin(2 * np.pi * u))
            yaw = yaw_end * u
            foot_x = -sgn * 0.1
            steps.append(
                Step(
                    side=side,
                    fps=fps,
                    pelvis=np.column_stack([x, y]),
                    yaw=yaw,
                    footprint=np.array([foot_x, length * 0.5 + 0.02 * rng.normal(), yaw_end]),
                    stance=np.array([-foot_x, -length * 0.5, 0.0]),
                    take=f"syn{t:03d}",
                    index=i,
                    meta={"initiation": i == 0, "termination": last} if stops else {},
                )
            )
            side = "right" if side == "left" else "left"
    return steps


@pytest.fixture(scope="module")
def steps() -> list[Step]:
    return make_steps(np.random.default_rng(1))


def test_raw_features_landmarks_equidistant_in_time(steps):
    s = steps[3]
    raw = raw_features([s])[0]
    assert raw.shape == (N_RAW,)
    k = s.n_samples
    # landmark 5 is the end, landmark j at sample j*(K-1)/5 (interpolated)
    np.testing.assert_allclose(raw[8:10], s.pelvis[-1], atol=1e-12)
    t = np.arange(k) / s.fps
    tl = 2 * t[-1] / 5
    np.testing.assert_allclose(raw[2], np.interp(tl, t, s.pelvis[:, 0]), atol=1e-12)
    assert raw[15] == pytest.approx(s.duration)
    assert raw[14] == pytest.approx(s.end_yaw)
    np.testing.assert_allclose(raw[16:19], s.footprint)


def test_spline_basis_interpolates_landmarks():
    b = spline_basis(11)  # u = 0, 0.1, ..., 1: landmarks at rows 0, 2, 4, ..., 10
    np.testing.assert_allclose(b[::2], np.eye(6), atol=1e-12)
    np.testing.assert_allclose(b.sum(axis=1), 1.0, atol=1e-12)  # reproduces constants
    with pytest.raises(MjwalkError):
        spline_basis(1)


def test_roundtrip_exact_with_all_components(steps):
    feats = StepFeatures.fit(steps, variance=1.0)
    raw = raw_features(steps)
    z = feats.encode(steps)
    assert z.shape[0] == len(steps) and z.shape[1] <= N_RAW
    np.testing.assert_allclose(feats.decode_raw(z), raw, atol=1e-9)
    # standardized: zero mean, unit variance
    np.testing.assert_allclose(z.mean(axis=0), 0.0, atol=1e-9)
    batch = feats.decode(z, [s.side for s in steps])
    np.testing.assert_allclose(
        batch.landmarks[:, 1:].reshape(len(steps), -1), raw[:, :10], atol=1e-9
    )


def test_roundtrip_within_pca_truncation(steps):
    feats = StepFeatures.fit(steps, variance=0.95)
    assert feats.variance_kept >= 0.95
    assert feats.n_components < N_RAW
    raw = raw_features(steps)
    rec = feats.decode_raw(feats.encode(steps))
    # error in z-scored units matches the discarded variance fraction
    err = ((rec - raw) / feats.raw_scale) ** 2
    total = (((raw - feats.raw_mean) / feats.raw_scale) ** 2).sum(axis=1).mean()
    lost = err.sum(axis=1).mean() / total
    assert lost == pytest.approx(1.0 - feats.variance_kept, rel=1e-6, abs=1e-9)
    # landmark path within a few centimetres
    assert np.abs(rec[:, :10] - raw[:, :10]).max() < 0.05


def test_decoded_trajectory_and_resample(steps):
    feats = StepFeatures.fit(steps, variance=1.0)
    batch = feats.decode(feats.encode(steps[:5]), "left")
    assert isinstance(batch, StepBatch) and len(batch) == 5
    for i in range(5):
        pelvis, yaw = batch.trajectory(i)
        k = round(batch.duration[i] * 120) + 1
        assert pelvis.shape == (k, 2) and yaw.shape == (k,)
        assert k == steps[i].n_samples
        assert np.all(pelvis[0] == 0.0) and yaw[0] == 0.0
        np.testing.assert_allclose(pelvis[-1], steps[i].pelvis[-1], atol=1e-9)
        # the spline through 6 landmarks follows the smooth original within a few mm
        assert np.abs(pelvis - steps[i].pelvis).max() < 0.005
    p, y = batch.resample(7)
    assert p.shape == (5, 7, 2) and y.shape == (5, 7)
    np.testing.assert_allclose(p[:, 0], 0.0, atol=0)
    np.testing.assert_allclose(p[:, -1], batch.end_xy, atol=1e-12)
    np.testing.assert_allclose(y[:, -1], batch.end_yaw, atol=1e-12)
    # resample agrees with trajectory when the sample grids coincide
    k = batch.n_samples(2)
    p2, _ = batch.resample(k)
    np.testing.assert_allclose(p2[2], batch.trajectory(2)[0], atol=1e-12)
    assert batch.side.tolist() == ["left"] * 5
    assert len(batch.take([0, 2]).to_steps()) == 2


def test_bad_input_raises(steps):
    with pytest.raises(MjwalkError, match="at least 3"):
        StepFeatures.fit(steps[:2])
    bad = Step(
        side="up",
        fps=120.0,
        pelvis=np.zeros((5, 2)),
        yaw=np.zeros(5),
        footprint=np.zeros(3),
        stance=np.zeros(3),
        take="t",
        index=0,
    )
    from mjwalk.gait.features import side_array

    with pytest.raises(MjwalkError, match="'up'"):
        side_array([bad])
    bad2 = Step(
        side="left",
        fps=120.0,
        pelvis=np.zeros((5, 3)),
        yaw=np.zeros(5),
        footprint=np.zeros(3),
        stance=np.zeros(3),
        take="t",
        index=4,
    )
    with pytest.raises(MjwalkError, match="t'#4"):
        raw_features([bad2])
    feats = StepFeatures.fit(steps)
    with pytest.raises(MjwalkError, match="dimensions"):
        feats.decode(np.zeros((2, feats.n_components + 1)), "left")


def test_the_spline_pieces_are_the_landmark_spline():
    """spline_pieces (the cubic pieces the planner's compiled assembly evaluates) give
    spline_basis's rows to 1e-12 at every sample count a step can have at 120 Hz."""
    from mjwalk.gait.features import spline_basis, spline_pieces

    starts, coef = spline_pieces()
    assert starts[0] == 0.0 and np.all(np.diff(starts) > 0) and coef.shape[0] == 4
    for m in (3, 37, 97, 120, 241):
        u = np.linspace(0.0, 1.0, m)[1:-1]
        j = np.searchsorted(starts, u, side="right") - 1
        d = (u - starts[j])[:, None]
        got = ((coef[0, j] * d + coef[1, j]) * d + coef[2, j]) * d + coef[3, j]
        assert np.allclose(got, spline_basis(m)[1:-1], atol=1e-12)
