"""The compiled row arithmetic of the arm chain (mjwalk.arms.anglerows): arm_joint_angles and
two_link_ik_rows give the same numbers to the bit as the NumPy code they replaced (kept here
as the reference), over seeded random arms and the rare branches (straight elbows, gimbal
lock, elbow hints along the shoulder-wrist axis, targets out of reach, forearm roll, two
segments, batches of alternatives, the unwrap across +-pi)."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from mjwalk.anthropometry import ROM_DEG
from mjwalk.arms.anglerows import (
    all_close,
    min_jerk_steps,
    retrace_rows,
    unit_steps,
    unwrap_col,
)
from mjwalk.arms.chain import arm_joint_angles, min_jerk, two_link_ik_rows

#: |sin| of the middle YXZ angle beyond which scipy decomposes a frame (chain's gimbal limit).
GIMBAL = 1.0 - 1e-7


def _dot(u, v):
    return u[:, 0] * v[:, 0] + u[:, 1] * v[:, 1] + u[:, 2] * v[:, 2]


def _cross(u, v):
    out = np.empty_like(u)
    out[:, 0] = u[:, 1] * v[:, 2] - u[:, 2] * v[:, 1]
    out[:, 1] = u[:, 2] * v[:, 0] - u[:, 0] * v[:, 2]
    out[:, 2] = u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]
    return out


def _shoulder_branch(a, b, c, s):
    """The shoulder's other Y-X-Z set where it keeps the joints in range and this one does not
    (chain's compiled branch choice), in NumPy."""
    lim = np.radians([ROM_DEG[k] for k in ("shoulder_flex", "shoulder_abd", "shoulder_rot")])

    def excess(a, b, c):
        out = 0.0
        for v, (lo, hi) in zip((-a, s * b, -s * c), lim, strict=True):
            out = out + (np.maximum(lo - v, 0.0) + np.maximum(v - hi, 0.0))
        return out

    a2 = ((a + np.pi) + np.pi) % (2.0 * np.pi) - np.pi
    b2 = np.where(b >= 0.0, np.pi, -np.pi) - b
    c2 = ((c + np.pi) + np.pi) % (2.0 * np.pi) - np.pi
    other = excess(a2, b2, c2) < excess(a, b, c) - 1e-9
    return np.where(other, a2, a), np.where(other, b2, b), np.where(other, c2, c)


def _ik_ref(target, l1, l2, elbow_hint):
    """two_link_ik_rows as it was in NumPy (e749e69)."""
    target = np.asarray(target, dtype=float)
    hint = np.asarray(elbow_hint, dtype=float)
    norm = np.sqrt(_dot(target, target))
    d = np.clip(norm, abs(l1 - l2) + 1e-6, l1 + l2 - 1e-6)
    axis = target / np.maximum(norm, 1e-9)[:, None]
    perp = hint - _dot(hint, axis)[:, None] * axis
    bad = np.sqrt(_dot(perp, perp)) < 1e-9
    if bad.any():
        alt = np.cross(axis[bad], [0.0, 1.0, 0.0])
        flat = np.sqrt(_dot(alt, alt)) < 1e-9
        alt[flat] = np.cross(axis[bad][flat], [1.0, 0.0, 0.0])
        perp[bad] = alt
    perp = perp / np.sqrt(_dot(perp, perp))[:, None]
    a = (l1**2 - l2**2 + d**2) / (2 * d)
    h = np.sqrt(np.maximum(l1**2 - a**2, 0.0))
    elbow = a[:, None] * axis + h[:, None] * perp
    wrist = d[:, None] * axis
    return elbow / l1, (wrist - elbow) / l2


def _euler_ref(r):
    sb = -r[:, 1, 2]
    b = np.arcsin(np.clip(sb, -1.0, 1.0))
    a = np.arctan2(r[:, 0, 2], r[:, 2, 2])
    c = np.arctan2(r[:, 1, 0], r[:, 1, 1])
    lock = np.abs(sb) > GIMBAL
    if lock.any():
        a[lock], b[lock], c[lock] = Rotation.from_matrix(r[lock]).as_euler("YXZ").T
    return a, b, c


def _angles_ref(directions, side="left", roll=None, independent=False):
    """arm_joint_angles as it was in NumPy (e749e69)."""
    s = 1.0 if side == "left" else -1.0
    U = np.asarray(directions, dtype=float)
    n = len(U)
    q = np.zeros((n, 7))
    u1, u2 = U[:, 0], U[:, 1]
    z = -u1
    x = u2 - _dot(u2, u1)[:, None] * u1
    norm = np.linalg.norm(x, axis=1)
    straight = norm < 1e-3
    x[~straight] /= norm[~straight, None]
    for t in np.flatnonzero(straight):
        xt = x[t - 1] if t > 0 and not independent else np.array([1.0, 0.0, 0.0])
        xt = xt - (xt @ z[t]) * z[t]
        x[t] = xt / np.linalg.norm(xt)
    y = _cross(z, x)
    r_sh = np.stack([x, y, z], axis=-1)
    a, b, c = _shoulder_branch(*_euler_ref(r_sh), s)
    elbow = np.arccos(np.clip(_dot(u1, u2), -1, 1))
    pron = np.zeros(n) if roll is None else np.asarray(roll, dtype=float)[:n]
    q[:, 0], q[:, 1], q[:, 2], q[:, 3], q[:, 4] = -a, s * b, -s * c, elbow, pron
    if U.shape[1] > 2:
        h = np.einsum("nji,nj->ni", r_sh, U[:, 2])
        ce, se = np.cos(-elbow), np.sin(-elbow)
        h = np.column_stack([ce * h[:, 0] - se * h[:, 2], h[:, 1], se * h[:, 0] + ce * h[:, 2]])
        cp, sp = np.cos(-s * pron), np.sin(-s * pron)
        h = np.column_stack([cp * h[:, 0] + sp * h[:, 1], -sp * h[:, 0] + cp * h[:, 1], h[:, 2]])
        beta = np.arcsin(np.clip(h[:, 1], -1, 1))
        q[:, 5] = np.arctan2(h[:, 0], -h[:, 2])
        q[:, 6] = s * beta
    if n > 1 and not independent:
        q[:, 0] = np.unwrap(q[:, 0])
        q[:, 2] = np.unwrap(q[:, 2])
    return q


def _unit(v):
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def _movement(rng, n):
    """A smooth random arm movement (n, 3, 3): unit directions drifting from random starts
    (some elbows near straight, some frames near gimbal lock, shoulders wrapping past pi)."""
    start, end = rng.normal(size=(2, 3, 3))
    t = np.linspace(0.0, 1.0, n)[:, None, None]
    return _unit((1 - t) * start + t * end + 0.05 * rng.normal(size=(n, 3, 3)))


def _same(a, b):
    """Equal to the bit (NaNs in the same places, the signs of zeros too)."""
    return np.array_equal(np.asarray(a).view(np.int64), np.asarray(b).view(np.int64))


@pytest.mark.parametrize("side", ["left", "right"])
def test_arm_joint_angles_equal_the_numpy_code_to_the_bit(side):
    rng = np.random.default_rng(50)
    for k in range(300):
        n = int(rng.integers(1, 60))
        U = _movement(rng, n)
        if k % 5 == 1:  # straight elbows: the forearm along the upper arm in some frames
            U[:: max(1, n // 3), 1] = U[:: max(1, n // 3), 0]
        if k % 5 == 2:  # gimbal lock: the upper arm along y in some frames
            U[:: max(1, n // 4), 0] = [0.0, 1.0, 0.0] if k % 2 else [0.0, -1.0, 0.0]
        if k % 5 == 3:  # axis-aligned rows (zeros, signed zeros in the products)
            U[:, :, int(rng.integers(3))] = 0.0
            U = np.where(np.linalg.norm(U, axis=2, keepdims=True) > 0, _unit(U + 0.0), U)
            U[:, :, 0] = np.where(np.isnan(U[:, :, 0]), 1.0, U[:, :, 0])
        roll = rng.uniform(-2.0, 2.0, n) if k % 3 == 0 else None
        for segments in (3, 2):
            V = np.ascontiguousarray(U[:, :segments])
            for independent in (False, True):
                got = arm_joint_angles(V, side, roll, independent)
                ref = _angles_ref(V, side, roll, independent)
                assert _same(got, ref), (k, segments, independent)


def test_arm_joint_angles_take_views_and_lists_as_before():
    rng = np.random.default_rng(7)
    U = _movement(rng, 20)
    big = np.zeros((20, 4, 3))
    big[:, :3] = U
    view = big[:, :3]  # not contiguous
    assert _same(arm_joint_angles(view, "right"), _angles_ref(view, "right"))
    assert _same(arm_joint_angles(U.tolist()), _angles_ref(U.tolist()))
    roll = np.linspace(-1, 1, 40)[::2]  # a strided roll, longer than needed
    assert _same(arm_joint_angles(U, "left", roll), _angles_ref(U, "left", roll))


def test_two_link_ik_rows_equal_the_numpy_code_to_the_bit():
    rng = np.random.default_rng(51)
    for k in range(300):
        n = int(rng.integers(1, 60))
        l1, l2 = (float(v) for v in rng.uniform(0.15, 0.4, 2))
        if k % 2:
            l1, l2 = np.float64(l1), np.float64(l2)  # as the cycle passes them
        target = rng.normal(size=(n, 3)) * rng.uniform(0.0, 0.9)
        hint = rng.normal(size=(n, 3))
        if k % 4 == 1:  # hints along the shoulder-wrist axis
            hint[::2] = target[::2] * rng.uniform(-2, 2)
        if k % 4 == 2:  # targets along y and along x (the perpendicular's fallbacks)
            target[::2] = [0.0, rng.uniform(-0.5, 0.5), 0.0]
            target[1::2] = [rng.uniform(-0.5, 0.5), 0.0, 0.0]
            hint = target * 3.0
        if k % 4 == 3:  # at the shoulder, and beyond reach
            target[0] = 0.0
            target[-1] *= 10.0
        got = two_link_ik_rows(target, l1, l2, hint)
        ref = _ik_ref(target, l1, l2, hint)
        assert _same(got[0], ref[0]) and _same(got[1], ref[1]), k


def test_unwrap_col_is_numpys_unwrap():
    rng = np.random.default_rng(52)
    for k in range(200):
        n = int(rng.integers(1, 80))
        p = np.cumsum(rng.normal(scale=rng.uniform(0.1, 4.0), size=n))
        p = (p + np.pi) % (2 * np.pi) - np.pi
        if k % 4 == 1:  # steps of exactly +-pi (the boundary fix)
            p[1::3] = p[0::3][: len(p[1::3])] + np.pi * rng.choice([-1, 1])
        if k % 4 == 2:
            p[::5] = -0.0
        q = np.column_stack([p, p])
        unwrap_col(q, 1)
        assert _same(q[:, 1], np.unwrap(p)), k
        assert _same(q[:, 0], p)


def test_unit_steps_are_linspace_and_new_each_time():
    for n in range(0, 400):
        a = unit_steps(n)
        assert _same(a, np.linspace(0.0, 1.0, n)) and _same(a, np.linspace(0, 1, n))
        a[:] = 7.0  # a copy: the next call is not changed
        assert _same(unit_steps(n), np.linspace(0.0, 1.0, n))


def test_min_jerk_steps_are_min_jerk_of_linspace_and_new_each_time():
    for n in range(0, 300):
        w = min_jerk_steps(n)
        assert _same(w, min_jerk(np.linspace(0.0, 1.0, n)))
        w[:] = 7.0
        assert _same(min_jerk_steps(n), min_jerk(np.linspace(0, 1, n)))


def test_all_close_is_numpys_allclose():
    rng = np.random.default_rng(53)
    specials = [0.0, -0.0, 1e-8, -1e-8, 1.0, np.inf, -np.inf, np.nan, 1e300, 5e-324]
    for k in range(20000):
        b = rng.normal(size=3) * 10.0 ** rng.integers(-12, 3)
        a = b + rng.normal(size=3) * 10.0 ** rng.integers(-14, 0)
        if k % 7 == 0:
            a[rng.integers(3)] = specials[rng.integers(len(specials))]
        if k % 11 == 0:
            b[rng.integers(3)] = specials[rng.integers(len(specials))]
        if k % 13 == 0:
            a = b.copy()
        assert all_close(a, b) == bool(np.allclose(a, b)), (a, b)


def _retraced_ref(out, n_back):
    """mjwalk.cycle.reaching._retraced as it was in NumPy (e749e69)."""
    n_out = len(out)
    src = np.linspace(0.0, n_out - 1.0, n_back)
    i0 = np.minimum(np.floor(src).astype(int), n_out - 1)
    i1 = np.minimum(i0 + 1, n_out - 1)
    w = (src - i0)[:, None]
    rev = out[::-1]
    return (1.0 - w) * rev[i0] + w * rev[i1]


def test_retrace_rows_equal_the_numpy_retrace():
    rng = np.random.default_rng(54)
    for _ in range(300):
        out = rng.normal(size=(int(rng.integers(1, 90)), int(rng.integers(1, 40))))
        n_back = int(rng.integers(2, 150))
        back = np.empty((n_back, out.shape[1]))
        retrace_rows(out, np.linspace(0.0, len(out) - 1.0, n_back), back)
        assert _same(back, _retraced_ref(out, n_back))
