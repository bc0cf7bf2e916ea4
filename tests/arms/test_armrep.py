"""The arm trajectory representation (mjwalk.arms.armrep): directions and angles, the movement
span and the PCA of aligned trajectories."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from mjwalk.arms.armrep import (
    ArmRepresentation,
    angles_to_directions,
    directions_to_angles,
    movement_span,
    resample_trajectory,
    segment_directions,
    trajectory_error,
)
from mjwalk.errors import MjwalkError


def _synthetic_set(p, seed):
    """Planar-ish two-segment arcs with random rotations and angular spreads."""
    rng = np.random.default_rng(seed)

    out = []
    for _ in range(p):
        t = np.linspace(0, 1, 15)
        a = rng.normal(1.2, 0.1) * t
        u1 = np.stack([np.sin(a), np.zeros_like(a), -np.cos(a)], 1)
        b = a + rng.normal(0.8, 0.1) * t
        u2 = np.stack([np.sin(b), 0.1 * t, -np.cos(b)], 1)
        U = np.stack([u1, u2], 1)
        U /= np.linalg.norm(U, axis=-1, keepdims=True)
        R = Rotation.from_rotvec(rng.normal(0, 0.15, 3))
        out.append(R.apply(U.reshape(-1, 3)).reshape(U.shape))
    return np.array(out)


def test_angles_roundtrip_and_segment_directions():
    rng = np.random.default_rng(0)
    u = rng.normal(size=(50, 3))
    u /= np.linalg.norm(u, axis=1, keepdims=True)
    np.testing.assert_allclose(angles_to_directions(directions_to_angles(u)), u, atol=1e-12)
    P = np.array([[[0, 0, 0], [0, 0, -2], [1, 0, -2]]], dtype=float)
    np.testing.assert_allclose(segment_directions(P)[0], [[0, 0, -1], [1, 0, 0]])
    r = resample_trajectory(np.arange(10.0)[:, None] * np.ones((1, 3)), 4)
    np.testing.assert_allclose(r[:, 0], [0, 3, 6, 9])


def _reach_clip(rest, hold, creep=0.0, n_move=30):
    """Hand path (T, 3): ``rest`` still frames, a min-jerk rise of 0.8 m over ``n_move``
    frames, ``hold`` frames creeping up by ``creep`` m in all."""
    tau = np.linspace(0, 1, n_move)
    rise = tau**3 * (10 - 15 * tau + 6 * tau**2)
    z = np.r_[np.zeros(rest), 0.8 * rise, 0.8 + creep * np.linspace(0, 1, hold + 1)[1:]]
    return np.c_[0.1 * z, np.zeros_like(z), z - 0.5]


def test_movement_span_cuts_rest_and_creeping_hold():
    for rest, hold, creep in [(0, 0, 0.0), (5, 20, 0.0), (12, 40, 0.02)]:
        hand = _reach_clip(rest, hold, creep)
        a, b = movement_span(hand, until=int(np.argmax(hand[:, 2])))
        # min-jerk speed is under 5 % of its peak for the first/last ~6 % of the movement
        assert rest - 1 <= a <= rest + 3
        assert rest + 26 <= b <= rest + 30
    # the same movement sampled at 20 equal intervals is the same whatever rest and hold
    spans = []
    for rest, hold in [(0, 0), (9, 35)]:
        hand = _reach_clip(rest, hold, 0.02)
        a, b = movement_span(hand, until=int(np.argmax(hand[:, 2])))
        spans.append(resample_trajectory(hand[a : b + 1], 20))
    assert np.abs(spans[0] - spans[1]).max() < 0.01
    # first frame to highest hand (the old cut) stretches it: the hold's creep is sampled
    hand = _reach_clip(9, 35, 0.02)
    old = resample_trajectory(hand[: int(np.argmax(hand[:, 2])) + 1], 20)
    assert np.abs(old - spans[0]).max() > 0.2
    with pytest.raises(MjwalkError, match="hand path"):
        movement_span(np.zeros((1, 3)))


def test_representation_alignment_pca_and_exact_inverse():
    U = _synthetic_set(40, 1)
    rep = ArmRepresentation(variance=1.0).fit(U)
    b, poses = rep.transform(U)
    back, _ = rep.inverse_transform(b, poses)
    assert trajectory_error(back, U).max() < 1e-8  # all modes kept: exact
    rep98 = ArmRepresentation(variance=0.98).fit(U)
    assert rep98.n_modes_ <= 6  # 2 shape parameters (+ noise) after removing rotation
    # alignment removes the random rotations: aligned spread far below the raw spread
    A, _ = rep98.align(U)
    raw = trajectory_error(U, U.mean(0, keepdims=True) / 1).mean()
    assert trajectory_error(A, rep98.mean_[None]).mean() < 0.5 * raw


def test_representation_extras_roundtrip():
    U = _synthetic_set(20, 2)
    rng = np.random.default_rng(3)
    E = rng.normal(size=(20, 15, 2)) * [0.01, 0.5]
    rep = ArmRepresentation(variance=1.0).fit(U, E)
    b, poses = rep.transform(U, E)
    _, E2 = rep.inverse_transform(b, poses)
    np.testing.assert_allclose(E2, E, atol=1e-9)


def test_loaded_pca_decodes_without_scikit_learn_and_encodes_as_it_did(tmp_path):
    """A representation read back from its arrays holds a LoadedPCA: the same arrays, the same
    coefficients from transform and features from inverse_transform as the fitted PCA, and
    loading it imports no scikit-learn (a fresh process loads the default reach model)."""
    import subprocess
    import sys

    from mjwalk.arms.armrep import LoadedPCA

    rng = np.random.default_rng(3)
    X = rng.normal(size=(40, 12))
    fitted = _fitted_pca(X)
    arrays = {
        "rep_pca_mean": fitted.mean_,
        "rep_pca_components": fitted.components_,
        "rep_pca_var": fitted.explained_variance_,
        "rep_pca_var_ratio": fitted.explained_variance_ratio_,
    }
    loaded = LoadedPCA(
        arrays["rep_pca_components"],
        arrays["rep_pca_mean"],
        arrays["rep_pca_var"],
        arrays["rep_pca_var_ratio"],
    )
    np.testing.assert_array_equal(loaded.transform(X), fitted.transform(X))
    b = fitted.transform(X[:3])
    np.testing.assert_array_equal(loaded.inverse_transform(b), fitted.inverse_transform(b))
    assert loaded.n_components_ == fitted.n_components_ and not loaded.whiten
    code = (
        "import sys; from mjwalk.arms.reachdefault import default_reach_model; "
        "m = default_reach_model(); print(type(m.rep_.pca_).__name__, 'sklearn' in sys.modules)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["LoadedPCA", "False"]


def _fitted_pca(X):
    from sklearn.decomposition import PCA

    return PCA(n_components=5, svd_solver="full").fit(X)
