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
from scipy.optimize import least_squares
from scipy.spatial.transform import Rotation
from sklearn.decomposition import PCA

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


# ---------------------------------------------------------------- sphere exp/log and scaling
def sphere_log(c: np.ndarray, a: np.ndarray) -> np.ndarray:
    """Tangent vector at unit ``c`` (3,) pointing to unit ``a`` (..., 3), length = angle.

    Args:
        c: (3,) unit centre.
        a: (..., 3) unit vectors.

    Returns:
        (..., 3) tangent vectors at ``c`` (orthogonal to it), length the angle in radians.
    """
    cos = np.clip(a @ c, -1.0, 1.0)
    v = a - cos[..., None] * c
    nv = np.linalg.norm(v, axis=-1, keepdims=True)
    ang = np.arccos(cos)[..., None]
    return np.where(nv > _EPS, v * ang / np.maximum(nv, _EPS), 0.0)


def sphere_exp(c: np.ndarray, w: np.ndarray) -> np.ndarray:
    """Unit vector reached from ``c`` (3,) along tangent ``w`` (..., 3) (inverse of log).

    Args:
        c: (3,) unit centre.
        w: (..., 3) tangent vectors at ``c``, length in radians.

    Returns:
        (..., 3) unit vectors.
    """
    ang = np.linalg.norm(w, axis=-1, keepdims=True)
    safe = np.maximum(ang, _EPS)
    return np.cos(ang) * c + np.where(ang > _EPS, np.sin(ang) * w / safe, 0.0)


def angular_scale(c: np.ndarray, a: np.ndarray, s: float) -> np.ndarray:
    """Scale the angular distance of directions ``a`` from centre ``c`` by ``s``.

    Args:
        c: (3,) unit centre.
        a: (..., 3) unit directions.
        s: scale factor of the angle from ``c``.

    Returns:
        (..., 3) unit directions ``exp_c(s log_c(a))``.
    """
    return sphere_exp(c, s * sphere_log(c, a))


def rotvec_matrix(rotvec: np.ndarray) -> np.ndarray:
    """(3, 3) rotation matrix of a rotation vector (3,) (axis times angle, radians): scipy's
    ``Rotation.from_rotvec(r).as_matrix()`` (through the unit quaternion, with its Taylor
    series below 1e-3 rad) without the per-call overhead of a Rotation object.

    Args:
        rotvec: (3,) rotation vector, radians.

    Returns:
        (3, 3) rotation matrix.
    """
    r = np.asarray(rotvec, dtype=float)
    angle = float(np.sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]))
    if angle <= 1e-3:
        a2 = angle * angle
        scale = 0.5 - a2 / 48 + a2 * a2 / 3840
    else:
        scale = np.sin(angle / 2) / angle
    x, y, z = scale * r[0], scale * r[1], scale * r[2]
    w = np.cos(angle / 2)
    x2, y2, z2, w2 = x * x, y * y, z * z, w * w
    xy, zw, xz, yw, yz, xw = x * y, z * w, x * z, y * w, y * z, x * w
    return np.array(
        [
            [x2 - y2 - z2 + w2, 2 * (xy - zw), 2 * (xz + yw)],
            [2 * (xy + zw), -x2 + y2 - z2 + w2, 2 * (yz - xw)],
            [2 * (xz - yw), 2 * (yz + xw), -x2 - y2 + z2 + w2],
        ]
    )


def apply_pose(center: np.ndarray, a: np.ndarray, pose: np.ndarray) -> np.ndarray:
    """``R @ E(s, a)``: the raw directions of aligned directions ``a`` (n, S, 3) for one pose.

    Args:
        center: (3,) unit centre of the angular scaling.
        a: (n, S, 3) aligned directions.
        pose: (4,) rotation vector (radians) and log scale.

    Returns:
        (n, S, 3) raw directions.
    """
    scaled = angular_scale(center, a, float(np.exp(pose[3])))
    return scaled @ rotvec_matrix(pose[:3]).T


def remove_pose(center: np.ndarray, u: np.ndarray, pose: np.ndarray) -> np.ndarray:
    """Inverse of :func:`apply_pose`: aligned directions of raw directions ``u`` (n, S, 3).

    Args:
        center: (3,) unit centre of the angular scaling.
        u: (n, S, 3) raw directions.
        pose: (4,) rotation vector (radians) and log scale.

    Returns:
        (n, S, 3) aligned directions.
    """
    rot = Rotation.from_rotvec(pose[:3])
    back = rot.inv().apply(u.reshape(-1, 3)).reshape(u.shape)
    return angular_scale(center, back, float(np.exp(-pose[3])))


def fit_pose(
    center: np.ndarray, u: np.ndarray, target: np.ndarray, max_log_scale: float = 1.0
) -> np.ndarray:
    """The pose (4,) whose :func:`remove_pose` brings ``u`` (n, S, 3) closest to ``target``
    (n, S, 3) in summed squared chord distance (rotation from Kabsch, refined with scale).

    Args:
        center: (3,) unit centre of the angular scaling.
        u: (n, S, 3) raw directions of one movement.
        target: (n, S, 3) aligned directions to match.
        max_log_scale: bound on |log scale|.

    Returns:
        (4,) pose: rotation vector (radians) and log scale.
    """
    r0, _ = Rotation.align_vectors(u.reshape(-1, 3), target.reshape(-1, 3))
    x0 = np.r_[r0.as_rotvec(), 0.0]

    def resid(x):
        return (remove_pose(center, u, x) - target).ravel()

    lb = np.r_[-np.inf, -np.inf, -np.inf, -max_log_scale]
    ub = np.r_[np.inf, np.inf, np.inf, max_log_scale]
    return least_squares(resid, x0, bounds=(lb, ub), x_scale=1.0).x


def _remove_poses(center: np.ndarray, U: np.ndarray, X: np.ndarray) -> np.ndarray:
    """Batched :func:`remove_pose`: U (p, n, S, 3), poses X (p, 4) -> (p, n, S, 3)."""
    mats = Rotation.from_rotvec(X[:, :3]).as_matrix()  # (p, 3, 3)
    back = np.einsum("pji,pnsj->pnsi", mats, U)  # R^T u
    s = np.exp(-X[:, 3])[:, None, None, None]
    return sphere_exp(center, s * sphere_log(center, back))


def fit_poses(
    center: np.ndarray,
    U: np.ndarray,
    target: np.ndarray,
    max_log_scale: float = 1.0,
    n_iter: int = 30,
    tol: float = 1e-10,
) -> np.ndarray:
    """Batched :func:`fit_pose` for U (p, n, S, 3) against one target (n, S, 3): Kabsch
    rotations, then Levenberg-Marquardt on all p 4-parameter problems at once (finite-difference
    Jacobians, per-problem damping). Returns poses (p, 4).

    Args:
        center: (3,) unit centre of the angular scaling.
        U: (p, n, S, 3) raw directions.
        target: (n, S, 3) aligned directions to match.
        max_log_scale: bound on |log scale|.
        n_iter: Levenberg-Marquardt iterations at most.
        tol: stop once every problem improves its cost by less than this (relative).

    Returns:
        (p, 4) poses.
    """
    p = len(U)
    flat_t = target.reshape(-1, 3)
    X = np.zeros((p, 4))
    for k in range(p):
        r0, _ = Rotation.align_vectors(U[k].reshape(-1, 3), flat_t)
        X[k, :3] = r0.as_rotvec()

    def resid(x):
        return (_remove_poses(center, U, x) - target).reshape(p, -1)

    r = resid(X)
    cost = (r**2).sum(axis=1)
    lam = np.full(p, 1e-3)
    h = 1e-6
    eye = np.eye(4)
    for _ in range(n_iter):
        J = np.empty((*r.shape, 4))
        for k in range(4):
            xk = X.copy()
            xk[:, k] += h
            J[:, :, k] = (resid(xk) - r) / h
        JtJ = np.einsum("pmi,pmj->pij", J, J)
        g = np.einsum("pmi,pm->pi", J, r)
        A = JtJ + lam[:, None, None] * (
            eye * np.maximum(JtJ.diagonal(axis1=1, axis2=2), 1e-9)[:, None, :]
        )
        dx = -np.linalg.solve(A, g[..., None])[..., 0]
        Xn = X + dx
        Xn[:, 3] = np.clip(Xn[:, 3], -max_log_scale, max_log_scale)
        rn = resid(Xn)
        cn = (rn**2).sum(axis=1)
        better = cn < cost
        X[better], r[better], lam[better] = Xn[better], rn[better], lam[better] * 0.3
        gain = cost - np.where(better, cn, cost)
        cost = np.where(better, cn, cost)
        lam[~better] *= 10.0
        converged = np.where(better, gain <= tol * np.maximum(cost, 1e-12), lam > 1e4)
        if converged.all():
            break
    return X


def _normalize(v: np.ndarray) -> np.ndarray:
    return v / np.maximum(np.linalg.norm(v, axis=-1, keepdims=True), _EPS)


# ---------------------------------------------------------------- the representation
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
        return _remove_poses(self.center_, U, poses), poses

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
        pca = PCA(n_components=comps.shape[0], svd_solver="full")
        pca.components_ = comps
        pca.mean_ = np.asarray(data["rep_pca_mean"], dtype=float)
        pca.explained_variance_ = np.asarray(data["rep_pca_var"], dtype=float)
        pca.explained_variance_ratio_ = np.asarray(data["rep_pca_var_ratio"], dtype=float)
        pca.n_components_ = comps.shape[0]
        pca.n_features_in_ = comps.shape[1]
        pca.whiten = False
        rep.pca_ = pca
        rep.n_modes_ = comps.shape[0]
        return rep
