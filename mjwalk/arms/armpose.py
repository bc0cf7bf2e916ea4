"""The alignment pose of an arm movement (Al-Zubi & Sommer §4.1): exp and log maps of the unit
sphere, the angular scaling about a centre direction, rotation vectors, the fit of the pose
that brings a movement onto a target, and the normalized linear blend between two directions
(:func:`blend_dir`, :func:`blend_dirs`: how a reach turns the hand and swivels the elbow).

A pose is a (4,) vector ``[rotvec (3, radians), log scale]`` with ``U = R @ E(s, A)``: ``A`` the
aligned directions (n, S, 3), ``E(s, .)`` the angular scaling by ``s = exp(log scale)`` about the
centre direction, ``R`` the rotation. Directions are unit vectors in the caller's frame (mjwalk:
the shoulder frame, x forward, y left, z up); angles in radians.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import least_squares
from scipy.spatial.transform import Rotation

#: Tangent length (radians) below which a direction counts as the centre.
_EPS = 1e-12


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


def remove_poses(center: np.ndarray, U: np.ndarray, X: np.ndarray) -> np.ndarray:
    """Batched :func:`remove_pose`.

    Args:
        center: (3,) unit centre of the angular scaling.
        U: (p, n, S, 3) raw directions.
        X: (p, 4) poses (rotation vector in radians, log scale).

    Returns:
        (p, n, S, 3) aligned directions.
    """
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
        return (remove_poses(center, U, x) - target).reshape(p, -1)

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


def blend_dir(a: np.ndarray, b: np.ndarray, tau: float) -> np.ndarray:
    """Unit vector between unit vectors ``a`` (``tau`` = 0) and ``b`` (``tau`` = 1): the
    normalized linear blend :math:`((1 - \tau) a + \tau b) / \\|(1 - \tau) a + \tau b\\|`.

    Args:
        a: (3,) unit vector.
        b: (3,) unit vector.
        tau: the blend, 0 to 1.

    Returns:
        (3,) unit vector.
    """
    v = (1.0 - tau) * a + tau * b
    # (summed left to right as blend_dirs sums it: np.linalg.norm's BLAS dot may fuse on some CPUs)
    return v / max(math.sqrt(float(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])), 1e-9)


def blend_dirs(a: np.ndarray, b: np.ndarray, taus: np.ndarray) -> np.ndarray:
    """:func:`blend_dir` for many blends at once, the same numbers row by row: unit vectors
    between ``a`` (one (3,) or one per row (n, 3)) and ``b`` (3,) at ``taus`` (n,).

    Args:
        a: (3,) or (n, 3) unit vectors (``tau`` = 0).
        b: (3,) unit vector (``tau`` = 1).
        taus: (n,) the blends, 0 to 1.

    Returns:
        (n, 3) unit vectors.
    """
    t = np.asarray(taus, dtype=float)[:, None]
    v = (1.0 - t) * np.asarray(a, dtype=float) + t * np.asarray(b, dtype=float)
    # (the norm summed left to right, as blend_dir sums it)
    norm = np.sqrt(v[:, 0] * v[:, 0] + v[:, 1] * v[:, 1] + v[:, 2] * v[:, 2])
    return v / np.maximum(norm, 1e-9)[:, None]
