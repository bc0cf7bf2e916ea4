"""Trajectory representation of an arm movement (Al-Zubi & Sommer §4.1).

A movement of a kinematic chain (shoulder -> elbow -> wrist -> hand tip) is sampled at ``n``
equal time intervals, each segment (upper arm, forearm, hand) becomes a unit *direction* vector,
and each trajectory is aligned to the mean of all trajectories by one 3-D rotation and one
*angular scaling* about a centre direction (generalized Procrustes analysis, iterated until the
mean converges). The aligned directions are written as spherical angles (azimuth ``phi`` and
polar angle ``theta`` in a per-segment frame chosen so that the wrap-around and the poles stay
away from the data) and PCA keeps ``q`` modes covering a chosen share of the variance (eq. 1,
``S = mean + Psi_q b``).

Shapes: ``U`` direction trajectories are (p, n, S, 3) (p movements, n samples, S segments), or
(n, S, 3) for a single movement. A *pose* is the alignment transform of one movement, a (4,)
vector ``[rotvec (3, radians), log scale]`` with ``U = R @ E(s, A)``: ``A`` the aligned
directions, ``E(s, .)`` the angular scaling by ``s`` about :attr:`ArmRepresentation.center_`
(exp/log map of the unit sphere), ``R`` the rotation. Optional ``extras`` (p, n, C) are scalar
channels that ride along unaligned (grip aperture in metres, forearm roll in radians...).

Directions are in whatever frame the caller used (mjwalk: the body frame at the shoulder, x
forward, y left, z up); angles are radians.
"""

from __future__ import annotations

import numpy as np
from scipy.interpolate import CubicSpline

from mjwalk.arms.armpose import apply_pose, fit_pose, fit_poses, remove_pose, remove_poses
from mjwalk.errors import MjwalkError

_EPS = 1e-12


# ---------------------------------------------------------------- sampling and directions
def resample_trajectory(positions: np.ndarray, n: int, t: np.ndarray | None = None) -> np.ndarray:
    """Sample a trajectory ``positions`` (T, ...) at ``n`` equal time intervals, start to end.

    ``t`` (T,) are the sample times (default: uniform); interpolation is a cubic spline in time,
    so the samples crowd where the movement is slow, as in the paper.

    Args:
        positions: (T, ...) samples of the trajectory, T >= 2.
        n: number of samples wanted.
        t: (T,) sample times (any unit), or None for 0..T-1.

    Returns:
        (n, ...) samples at n equal intervals from t[0] to t[-1].
    """
    positions = np.asarray(positions, dtype=float)
    if len(positions) < 2:
        raise MjwalkError(f"resample_trajectory: need >= 2 frames, got {len(positions)}")
    if t is None:
        t = np.arange(len(positions), dtype=float)
    spline = CubicSpline(t, positions, axis=0)
    return spline(np.linspace(t[0], t[-1], n))


#: Movement onset/offset threshold as a share of the peak tangential hand speed: the usual
#: kinematic criterion of reaching studies (5 % of peak velocity, e.g. Flash & Hogan 1985 data
#: analysis; Gordon, Ghilardi & Ghez 1994).
ONSET_SPEED_SHARE = 0.05


def movement_span(
    hand: np.ndarray, until: int | None = None, share: float = ONSET_SPEED_SHARE
) -> tuple[int, int]:
    """Frames ``(a, b)`` (inclusive) of the one movement of ``hand`` (T, 3) that holds the
    fastest frame up to frame ``until`` (default: the last): from the last frame before it
    whose speed is at most ``share`` of that peak speed to the first such frame after it.

    This is the time alignment of a clip before it is sampled at n equal time intervals (Al-Zubi
    & Sommer §4.1 "from the start of the sequence to its end"): a rest before the movement or a
    hold after it would otherwise stretch or squeeze the movement differently in every clip.
    Speed is the frame-to-frame displacement (any unit; frames evenly spaced).

    Args:
        hand: (T, 3) hand path, frames evenly spaced (any length unit).
        until: last frame the fastest frame is searched in (default: the last frame).
        share: onset/offset speed threshold as a share of the peak speed.

    Returns:
        ``(a, b)`` first and last frame of the movement, inclusive.
    """
    hand = np.asarray(hand, dtype=float)
    if hand.ndim != 2 or len(hand) < 2:
        raise MjwalkError(f"movement_span: need a (T >= 2, 3) hand path, got {hand.shape}")
    last = len(hand) - 1 if until is None else int(np.clip(until, 1, len(hand) - 1))
    step = np.linalg.norm(np.diff(hand, axis=0), axis=1)
    # speed[t]: displacement into frame t (frame 0 takes its successor's).
    speed = np.r_[step[0], step]
    peak = int(np.argmax(speed[: last + 1]))
    thr = share * speed[peak]
    a = peak
    while a > 0 and speed[a - 1] > thr:
        a -= 1
    a = max(a - 1, 0)  # speed[a] is the step into frame a: the hand was still at a - 1
    b = peak
    while b < last and speed[b + 1] > thr:
        b += 1
    if b - a < 1:
        b = min(a + 1, len(hand) - 1)
        a = b - 1
    return a, b


def segment_directions(positions: np.ndarray) -> np.ndarray:
    """Unit directions (..., J-1, 3) of the segments of a chain of joint positions (..., J, 3).

    Args:
        positions: (..., J, 3) joint positions along the chain.

    Returns:
        (..., J-1, 3) unit directions, same frame as ``positions``.
    """
    seg = np.diff(np.asarray(positions, dtype=float), axis=-2)
    norm = np.linalg.norm(seg, axis=-1, keepdims=True)
    if np.any(norm < 1e-9):
        raise MjwalkError("segment_directions: a segment has zero length (coincident joints)")
    return seg / norm


def directions_to_angles(u: np.ndarray) -> np.ndarray:
    """Spherical angles (..., 2) = (phi, theta) of unit vectors (..., 3): phi the azimuth from
    +x counter-clockwise about +z, theta the polar angle from +z (radians).

    Args:
        u: (..., 3) unit vectors.

    Returns:
        (..., 2) ``(phi, theta)`` in radians.
    """
    u = np.asarray(u, dtype=float)
    phi = np.arctan2(u[..., 1], u[..., 0])
    theta = np.arccos(np.clip(u[..., 2], -1.0, 1.0))
    return np.stack([phi, theta], axis=-1)


def angles_to_directions(angles: np.ndarray) -> np.ndarray:
    """Inverse of :func:`directions_to_angles`: unit vectors (..., 3) from (phi, theta).

    Args:
        angles: (..., 2) ``(phi, theta)`` in radians.

    Returns:
        (..., 3) unit vectors.
    """
    phi, theta = angles[..., 0], angles[..., 1]
    st = np.sin(theta)
    return np.stack([st * np.cos(phi), st * np.sin(phi), np.cos(theta)], axis=-1)


def angular_distance(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Angle (radians) between corresponding unit vectors of ``u`` and ``v`` (..., 3).

    Args:
        u: (..., 3) unit vectors.
        v: (..., 3) unit vectors, same shape.

    Returns:
        (...) angles in radians, in [0, pi].
    """
    cross = np.linalg.norm(np.cross(u, v), axis=-1)
    return np.arctan2(cross, np.sum(u * v, axis=-1))


def trajectory_error(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Mean joint-direction angle error (radians) per movement between (p, n, S, 3) arrays
    (or a single (n, S, 3) movement -> scalar): the paper's mean radial distance.

    Args:
        u: (p, n, S, 3) or (n, S, 3) unit directions.
        v: directions of the same shape.

    Returns:
        (p,) or scalar mean angle, radians.
    """
    return angular_distance(u, v).mean(axis=(-2, -1))


def _normalize(v: np.ndarray) -> np.ndarray:
    return v / np.maximum(np.linalg.norm(v, axis=-1, keepdims=True), _EPS)


# ---------------------------------------------------------------- the representation
class LoadedPCA:
    """A PCA read from a model file (:meth:`ArmRepresentation.from_arrays`): its arrays at once,
    scikit-learn's ``PCA`` made from them on the first :meth:`transform` or
    :meth:`inverse_transform`. Importing scikit-learn (and scipy.stats with it) takes ~1 s, 3.5 s
    on a loaded machine, in every process that loads a reach model, and a cycle only decodes
    (``b @ components_ + mean_``, :meth:`ArmRepresentation.from_modes`).

    Args:
        components: (q, d) the principal axes.
        mean: (d,) the features' mean.
        variance: (q,) each axis's explained variance.
        variance_ratio: (q,) each axis's share of the variance.
    """

    whiten = False

    def __init__(self, components, mean, variance, variance_ratio):
        self.components_, self.mean_ = components, mean
        self.explained_variance_, self.explained_variance_ratio_ = variance, variance_ratio
        self.n_components_, self.n_features_in_ = components.shape
        self._pca = None

    def sklearn(self):
        """The same PCA as a fitted scikit-learn ``PCA`` (made on first use).

        Returns:
            The ``sklearn.decomposition.PCA`` with these arrays.
        """
        if self._pca is None:
            # deferred: scikit-learn takes ~1 s to import; only fitting and encoding need it
            from sklearn.decomposition import PCA

            pca = PCA(n_components=self.n_components_, svd_solver="full")
            pca.components_, pca.mean_ = self.components_, self.mean_
            pca.explained_variance_ = self.explained_variance_
            pca.explained_variance_ratio_ = self.explained_variance_ratio_
            pca.n_components_, pca.n_features_in_ = self.n_components_, self.n_features_in_
            pca.whiten = False
            self._pca = pca
        return self._pca

    def transform(self, X):
        """PCA coefficients of features (scikit-learn's ``PCA.transform``).

        Args:
            X: (p, d) features.

        Returns:
            (p, q) coefficients.
        """
        return self.sklearn().transform(X)

    def inverse_transform(self, b):
        """Features of PCA coefficients (scikit-learn's ``PCA.inverse_transform``, its checks).

        Args:
            b: (p, q) coefficients.

        Returns:
            (p, d) features.
        """
        return self.sklearn().inverse_transform(b)


class ArmRepresentation:
    """Aligned spherical-angle trajectories + PCA (Al-Zubi & Sommer §4.1, eq. 1).

    Args:
        variance: share of the variance the kept PCA modes cover (0 < variance <= 1), or an
            int number of modes.
        max_iter: generalized Procrustes iterations at most.
        tol: convergence tolerance of the alignment (largest change of a mean direction,
            radians).

    Fitted attributes: ``mean_`` (n, S, 3) aligned mean directions, ``center_`` (3,) centre of
    the angular scaling, ``frames_`` (S, 3, 3) per-segment spherical frames (rows: axes in the
    aligned frame), ``phi_ref_`` (n, S) branch reference for azimuths, ``extras_scale_`` (C,),
    ``pca_`` (sklearn PCA), ``n_modes_``, ``n_iter_``, ``poses_`` (p, 4) training poses.
    """

    def __init__(self, variance: float | int = 0.98, max_iter: int = 30, tol: float = 1e-6):
        self.variance = variance
        self.max_iter = max_iter
        self.tol = tol

    # ------------------------------------------------------------ alignment
    def _align_all(self, U: np.ndarray, target: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        poses = fit_poses(self.center_, U, target)
        return remove_poses(self.center_, U, poses), poses

    def fit(self, U: np.ndarray, extras: np.ndarray | None = None) -> ArmRepresentation:
        """Align direction trajectories ``U`` (p, n, S, 3) by GPA and fit the PCA.

        Args:
            U: (p, n, S, 3) unit directions, p >= 2.
            extras: (p, n, C) extra channels, or None.

        Returns:
            this representation, fitted.
        """
        U = self._check_u(U)
        if len(U) < 2:
            raise MjwalkError(f"ArmRepresentation.fit: need >= 2 movements, got {len(U)}")
        p, n, S, _ = U.shape
        reference = U[0]
        self.center_ = _normalize(reference.reshape(-1, 3).mean(axis=0))
        mean = reference
        self.n_iter_ = 0
        for it in range(self.max_iter):
            A, poses = self._align_all(U, mean)
            new = _normalize(A.mean(axis=0))
            # Gauge: keep the mean registered to the reference movement (no drift of R, s).
            new = remove_pose(self.center_, new, fit_pose(self.center_, new, reference))
            change = float(angular_distance(new, mean).max())
            mean = new
            self.n_iter_ = it + 1
            if change < self.tol:
                break
        A, poses = self._align_all(U, mean)
        self.mean_ = mean
        self.poses_ = poses

        # Per-segment spherical frames: pole = least-variance axis of the segment's directions.
        frames = np.empty((S, 3, 3))
        for j in range(S):
            D = A[:, :, j].reshape(-1, 3)
            _, vecs = np.linalg.eigh(D.T @ D)
            e3 = vecs[:, 0]
            m = D.mean(axis=0)
            e1 = m - (m @ e3) * e3
            if np.linalg.norm(e1) < 1e-6:  # degenerate: any axis orthogonal to the pole
                e1 = np.cross(e3, [1.0, 0.0, 0.0] if abs(e3[0]) < 0.9 else [0.0, 1.0, 0.0])
            e1 = _normalize(e1)
            frames[j] = np.stack([e1, np.cross(e3, e1), e3])
        self.frames_ = frames
        local = np.einsum("sij,pnsj->pnsi", frames, A)
        ang = directions_to_angles(local)
        phi = np.unwrap(ang[..., 0], axis=1)
        self.phi_ref_ = np.zeros((n, S))
        phi = self._branch(phi)
        self.phi_ref_ = phi.mean(axis=0)
        angles = np.stack([phi, ang[..., 1]], axis=-1)
        self.n_extras_ = 0 if extras is None else int(np.asarray(extras).shape[-1])
        if extras is not None:
            E = self._check_extras(extras, p, n)
            ang_sd = float(angles.std()) or 1.0
            sd = E.reshape(-1, self.n_extras_).std(axis=0)
            self.extras_scale_ = np.where(sd > 1e-12, sd / ang_sd, 1.0)
        else:
            self.extras_scale_ = np.zeros(0)
            E = None
        X = self._pack(angles, E)
        self.shape_ = (n, S)
        n_comp = self.variance
        if isinstance(n_comp, float) and n_comp >= 1.0:
            n_comp = min(X.shape)
        # a loaded model decodes with LoadedPCA, without scikit-learn
        from sklearn.decomposition import PCA  # deferred: ~1 s import, only fitting needs it

        self.pca_ = PCA(n_components=n_comp, svd_solver="full").fit(X)
        self.n_modes_ = int(self.pca_.n_components_)
        return self

    def _branch(self, phi: np.ndarray) -> np.ndarray:
        """Shift each movement's unwrapped azimuths by 2*pi*k to the branch nearest phi_ref_."""
        k = np.round((phi - self.phi_ref_).mean(axis=1, keepdims=True) / (2 * np.pi))
        return phi - 2 * np.pi * k

    def _pack(self, angles, E):
        X = angles.reshape(len(angles), -1)
        if E is not None and self.n_extras_:
            X = np.hstack([X, (E / self.extras_scale_).reshape(len(E), -1)])
        return X

    @staticmethod
    def _check_u(U):
        U = np.asarray(U, dtype=float)
        if U.ndim != 4 or U.shape[-1] != 3:
            raise MjwalkError(f"ArmRepresentation: directions must be (p, n, S, 3), got {U.shape}")
        if not np.isfinite(U).all():
            raise MjwalkError("ArmRepresentation: directions hold NaN or infinite values")
        return _normalize(U)

    def _check_extras(self, extras, p, n):
        E = np.asarray(extras, dtype=float)
        if E.shape != (p, n, self.n_extras_):
            raise MjwalkError(
                f"ArmRepresentation: extras must be ({p}, {n}, {self.n_extras_}), got {E.shape}"
            )
        return E

    # ------------------------------------------------------------ forward / inverse
    def align(self, U: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Aligned directions (p, n, S, 3) and poses (p, 4) of raw directions (p, n, S, 3).

        Args:
            U: (p, n, S, 3) raw unit directions.

        Returns:
            ``(A, poses)``: (p, n, S, 3) aligned directions and (p, 4) poses.
        """
        return self._align_all(self._check_u(U), self.mean_)

    def unalign(self, A: np.ndarray, poses: np.ndarray) -> np.ndarray:
        """Raw directions (p, n, S, 3) from aligned ones and poses (p, 4) (exact inverse).

        Args:
            A: (p, n, S, 3) aligned directions.
            poses: (p, 4) poses (rotation vector in radians, log scale).

        Returns:
            (p, n, S, 3) raw directions.
        """
        return np.array(
            [apply_pose(self.center_, a, x) for a, x in zip(A, np.atleast_2d(poses), strict=True)]
        )

    def to_features(self, A: np.ndarray, extras: np.ndarray | None = None) -> np.ndarray:
        """(p, F) feature rows (spherical angles, then scaled extras) of aligned directions.

        Args:
            A: (p, n, S, 3) aligned directions.
            extras: (p, n, C) extra channels, or None.

        Returns:
            (p, F) feature rows.
        """
        local = np.einsum("sij,pnsj->pnsi", self.frames_, A)
        ang = directions_to_angles(local)
        phi = self._branch(np.unwrap(ang[..., 0], axis=1))
        angles = np.stack([phi, ang[..., 1]], axis=-1)
        E = None if extras is None else self._check_extras(extras, len(A), A.shape[1])
        if self.n_extras_ and E is None:
            raise MjwalkError(f"ArmRepresentation: {self.n_extras_} extra channels expected")
        return self._pack(angles, E)

    def from_features(self, X: np.ndarray) -> tuple[np.ndarray, np.ndarray | None]:
        """Aligned directions (p, n, S, 3) and extras (p, n, C) or None from feature rows.

        Args:
            X: (p, F) feature rows.

        Returns:
            ``(A, extras)``: (p, n, S, 3) aligned directions and (p, n, C) extras or None.
        """
        X = np.atleast_2d(X)
        n, S = self.shape_
        angles = X[:, : n * S * 2].reshape(-1, n, S, 2)
        local = angles_to_directions(angles)
        A = np.einsum("sji,pnsj->pnsi", self.frames_, local)
        E = None
        if self.n_extras_:
            E = X[:, n * S * 2 :].reshape(-1, n, self.n_extras_) * self.extras_scale_
        return A, E

    def transform(
        self, U: np.ndarray, extras: np.ndarray | None = None
    ) -> tuple[np.ndarray, np.ndarray]:
        """PCA coefficients b (p, q) and poses (p, 4) of raw direction trajectories.

        Args:
            U: (p, n, S, 3) raw unit directions.
            extras: (p, n, C) extra channels, or None.

        Returns:
            ``(b, poses)``: (p, q) coefficients and (p, 4) poses.
        """
        A, poses = self.align(U)
        return self.pca_.transform(self.to_features(A, extras)), poses

    def inverse_transform(
        self, b: np.ndarray, poses: np.ndarray | None = None
    ) -> tuple[np.ndarray, np.ndarray | None]:
        """Directions (p, n, S, 3) and extras from coefficients b (p, q) (eq. 1); aligned
        directions when ``poses`` is None, raw ones (pose applied) otherwise.

        Args:
            b: (p, q) PCA coefficients.
            poses: (p, 4) poses, or None for aligned directions.

        Returns:
            ``(U, extras)``: (p, n, S, 3) directions and (p, n, C) extras or None.
        """
        b = np.atleast_2d(np.asarray(b, dtype=float))
        if self.pca_.whiten or not np.isfinite(b).all():  # (scikit-learn's checks and errors)
            X = self.pca_.inverse_transform(b)
        else:  # PCA.inverse_transform's arithmetic without its input validation (~60 us)
            X = b @ self.pca_.components_ + self.pca_.mean_
        A, E = self.from_features(X)
        if poses is not None:
            A = self.unalign(A, poses)
        return A, E

    # ------------------------------------------------------------ persistence helpers
    def to_arrays(self) -> dict[str, np.ndarray]:
        """Fitted state as plain arrays (for a composite model file).

        Returns:
            ``{name: array}``, the names prefixed ``rep_``.
        """
        return {
            "rep_mean": self.mean_,
            "rep_center": self.center_,
            "rep_frames": self.frames_,
            "rep_phi_ref": self.phi_ref_,
            "rep_extras_scale": self.extras_scale_,
            "rep_pca_mean": self.pca_.mean_,
            "rep_pca_components": self.pca_.components_,
            "rep_pca_var": self.pca_.explained_variance_,
            "rep_pca_var_ratio": self.pca_.explained_variance_ratio_,
            "rep_poses": self.poses_,
        }

    @classmethod
    def from_arrays(cls, data: dict) -> ArmRepresentation:
        """Rebuild from :meth:`to_arrays` (raises KeyError/ValueError on missing/bad arrays).

        Args:
            data: the arrays :meth:`to_arrays` returned.

        Returns:
            the fitted representation.
        """
        rep = cls()
        rep.mean_ = np.asarray(data["rep_mean"], dtype=float)
        rep.center_ = np.asarray(data["rep_center"], dtype=float)
        rep.frames_ = np.asarray(data["rep_frames"], dtype=float)
        rep.phi_ref_ = np.asarray(data["rep_phi_ref"], dtype=float)
        rep.extras_scale_ = np.asarray(data["rep_extras_scale"], dtype=float)
        rep.n_extras_ = len(rep.extras_scale_)
        rep.poses_ = np.asarray(data["rep_poses"], dtype=float)
        n, S = rep.mean_.shape[:2]
        rep.shape_ = (n, S)
        comps = np.asarray(data["rep_pca_components"], dtype=float)
        if comps.shape[1] != n * S * 2 + n * rep.n_extras_:
            raise ValueError(f"PCA components {comps.shape} do not match trajectories {(n, S)}")
        pca = LoadedPCA(
            comps,
            np.asarray(data["rep_pca_mean"], dtype=float),
            np.asarray(data["rep_pca_var"], dtype=float),
            np.asarray(data["rep_pca_var_ratio"], dtype=float),
        )
        rep.pca_ = pca
        rep.n_modes_ = comps.shape[0]
        return rep
