"""Smooth shaping functions of the leg synthesis: smoothstep, soft clamps and envelopes."""

from __future__ import annotations

import functools
import math

import numpy as np
from scipy.ndimage import gaussian_filter1d, maximum_filter1d

from mjwalk._jit import njit

#: Pitches smaller than this (degrees) count as a flat foot (no roll, so no drift).
FLAT_DEG = 2.0
#: The same in radians.
FLAT = float(np.deg2rad(FLAT_DEG))


def smoothstep(x: np.ndarray) -> np.ndarray:
    """The smoothstep of ``x`` clipped to [0, 1]: 0 to 1 with zero slope at both ends (the
    one easing curve of the package's blends).

    :math:`s(x) = 3u^2 - 2u^3` with :math:`u = \\min(\\max(x, 0), 1)`.

    Args:
        x: values (any shape).

    Returns:
        s(x), the shape of ``x``, in [0, 1].
    """
    x = np.clip(x, 0.0, 1.0)
    return x * x * (3 - 2 * x)


def spread(need: np.ndarray, win: int) -> np.ndarray:
    """A smooth envelope of the non-negative per-sample amounts ``need``: their running
    maximum over +-``win`` samples, Gaussian-smoothed (sigma ``win / 3``), so a correction
    needed at some samples fades in and out over the samples around instead of acting on them
    alone (a jump).

    Args:
        need: (n,) non-negative amounts per sample.
        win: half-width of the running maximum (samples).

    Returns:
        (n,) the envelope (scipy.ndimage's reflecting boundary).
    """
    need = np.asarray(need, dtype=float)
    if need.ndim != 1 or len(need) < 2 * win + 2:
        return gaussian_filter1d(maximum_filter1d(need, 2 * win + 1), win / 3)
    return spread_rows(need, win, gauss_kernel(win))


@functools.lru_cache(maxsize=32)
def gauss_kernel(win: int) -> np.ndarray:
    """scipy.ndimage's Gaussian kernel for sigma ``win / 3`` (truncated at 4 sigma).

    Args:
        win: the spread's half-width (samples).

    Returns:
        (2 r + 1,) weights summing to 1, r = int(4 sigma + 0.5).
    """
    sigma = win / 3
    radius = int(4.0 * float(sigma) + 0.5)
    x = np.arange(-radius, radius + 1)
    phi = np.exp(-0.5 / (sigma * sigma) * x**2)
    return phi / phi.sum()


@njit
def _reflect(j, n):
    """scipy.ndimage's "reflect" boundary (d c b a | a b c d | d c b a) for index ``j``."""
    period = 2 * n
    j = j % period
    return j if j < n else period - 1 - j


@njit
def spread_rows(need, win, kernel):
    """:func:`spread` for ``len(need) > 2 win + 1``: the running maximum over +-``win`` and
    the symmetric Gaussian ``kernel``, both with the reflecting boundary, as scipy.ndimage
    (the symmetric kernel summed pairwise from the centre out, as its correlate1d).

    Args:
        need: (n,) non-negative amounts per sample.
        win: half-width of the running maximum (samples).
        kernel: the Gaussian weights of :func:`gauss_kernel`.

    Returns:
        (n,) the envelope.
    """
    n = len(need)
    out = np.zeros(n)
    for i in range(n):
        if need[i] != 0.0:
            break
    else:  # nothing needed: the envelope is exactly zero (as the sums below give)
        return out
    r = len(kernel) // 2
    pad = win
    ext = np.empty(n + 2 * pad)
    # live[j]: how many of ext[:j] are not +0.0 (a window of +0.0 only has the maximum +0.0,
    # and a sum over such maxima is +0.0: those samples are skipped, their zeros kept)
    live = np.zeros(n + 2 * pad + 1, dtype=np.int64)
    for i in range(-pad, n + pad):
        v = need[i if 0 <= i < n else _reflect(i, n)]  # (inside: the index itself)
        ext[i + pad] = v
        live[i + pad + 1] = live[i + pad] + (v != 0.0 or math.copysign(1.0, v) < 0.0)
    peak = np.zeros(n + 2 * r)
    for i in range(n):
        if live[i + 2 * win + 1] == live[i]:
            continue
        m = ext[i]
        for j in range(i + 1, i + 2 * win + 1):
            if ext[j] > m:
                m = ext[j]
        peak[i + r] = m
    for i in range(r):  # the maximum's reflected borders
        peak[r - 1 - i] = peak[r + _reflect(-1 - i, n)]
        peak[r + n + i] = peak[r + _reflect(n + i, n)]
    hot = np.zeros(n + 2 * r + 1, dtype=np.int64)  # as live, over peak
    for i in range(n + 2 * r):
        v = peak[i]
        hot[i + 1] = hot[i] + (v != 0.0 or math.copysign(1.0, v) < 0.0)
    for i in range(n):
        c = i + r
        if hot[c + r + 1] == hot[c - r]:
            continue
        acc = peak[c] * kernel[r]
        for j in range(1, r + 1):
            acc += (peak[c - j] + peak[c + j]) * kernel[r + j]
        out[i] = acc
    return out


def soft_clip01(x: np.ndarray, w: float) -> np.ndarray:
    """``x`` clamped to [0, 1] with rounded corners (C1): unchanged in [w, 1 - w], quadratic
    blends over ``w`` either side of 0 and 1, constant beyond.

    Args:
        x: values (any shape).
        w: half-width of the rounded corners, <= 0.5.

    Returns:
        the clamped values, the shape of ``x``.
    """
    x = np.asarray(x, float)
    lo = np.where(x < -w, 0.0, np.where(x < w, (x + w) ** 2 / (4 * w), x))
    return np.where(lo > 1 + w, 1.0, np.where(lo > 1 - w, 1 - (1 + w - lo) ** 2 / (4 * w), lo))


def soft_max(a: np.ndarray, b: np.ndarray, w: float) -> np.ndarray:
    """The larger of ``a`` and ``b`` with the corner rounded (C1): exactly the larger where
    they differ by ``w`` or more, a quadratic blend nearer (at most ``w / 4`` above both,
    never below either).

    Args:
        a: values (any shape).
        b: values (broadcast with ``a``).
        w: the half-width of the rounding (> 0), in the values' units.

    Returns:
        the soft maximum, the broadcast shape.
    """
    e = np.maximum(w - np.abs(a - b), 0.0)
    return np.maximum(a, b) + e * e / (4 * w)


def soft_flat(p: np.ndarray) -> np.ndarray:
    """Pitches within +-FLAT_DEG become exactly 0 (flat foot), continuously:
    ``sign(p) max(|p| - FLAT, 0)``.

    Args:
        p: pitches, radians (any shape).

    Returns:
        the pitches shrunk towards 0 by FLAT, radians.
    """
    t = np.deg2rad(FLAT_DEG)
    return np.sign(p) * np.maximum(np.abs(p) - t, 0.0)


def soft_excess(x: np.ndarray, w: float) -> np.ndarray:
    """max(x, 0) rounded over ``[0, 2 w]`` (C1): 0 for x <= 0, x^2 / (4 w) below 2 w,
    x - w from 2 w on.

    Args:
        x: values (any shape).
        w: the rounding width (> 0).

    Returns:
        the soft excess, the shape of ``x``.
    """
    x = np.maximum(x, 0.0)
    return np.where(x < 2 * w, x * x / (4 * w), x - w)


# one value at a time, for compiled callers (the same arithmetic as the array functions)


@njit
def smoothstep1(x):
    """:func:`smoothstep` of one value.

    Args:
        x: the value.

    Returns:
        3u^2 - 2u^3 for u = x clipped to [0, 1].
    """
    x = min(max(x, 0.0), 1.0)
    return x * x * (3 - 2 * x)


@njit
def maximum1(a, b):
    """``np.maximum`` of two values (the first on ties and NaN).

    Args:
        a: first value.
        b: second value.

    Returns:
        the larger value.
    """
    return a if a >= b or a != a else b


@njit
def minimum1(a, b):
    """``np.minimum`` of two values (the first on ties and NaN).

    Args:
        a: first value.
        b: second value.

    Returns:
        the smaller value.
    """
    return a if a <= b or a != a else b


@njit
def soft_flat1(p, flat):
    """:func:`soft_flat` of one pitch.

    Args:
        p: the pitch, radians.
        flat: the flat threshold, radians.

    Returns:
        the pitch shrunk towards 0 by ``flat`` (NaN stays NaN).
    """
    sign = 1.0 if p > 0 else (-1.0 if p < 0 else (0.0 if p == 0 else p))
    return sign * maximum1(abs(p) - flat, 0.0)


@njit
def soft_excess1(x, w):
    """:func:`soft_excess` of one value.

    Args:
        x: the value.
        w: the rounding width (> 0).

    Returns:
        the soft excess.
    """
    x = maximum1(x, 0.0)
    return x * x / (4 * w) if x < 2 * w else x - w


@njit
def soft_max1(a, b, w):
    """:func:`soft_max` of two values.

    Args:
        a: the one value.
        b: the other value.
        w: the half-width of the rounding (> 0).

    Returns:
        the soft maximum.
    """
    e = maximum1(w - abs(a - b), 0.0)
    return maximum1(a, b) + e * e / (4 * w)


@njit
def soft_clip01_1(x, w):
    """:func:`soft_clip01` of one value.

    Args:
        x: the value.
        w: half-width of the rounded corners, <= 0.5.

    Returns:
        the softly clamped value.
    """
    lo = 0.0 if x < -w else ((x + w) * (x + w) / (4 * w) if x < w else x)
    if lo > 1 + w:
        return 1.0
    if lo > 1 - w:
        return 1 - (1 + w - lo) * (1 + w - lo) / (4 * w)
    return lo


def clamped_cubic(x, y, d0, d1, xq) -> np.ndarray:
    """The cubic spline through knots ``x`` with values ``y`` and first derivatives ``d0`` /
    ``d1`` at the ends, evaluated at ``xq`` (extrapolated beyond the knots): scipy's
    ``CubicSpline(x, y, bc_type=((1, d0), (1, d1)))(xq)`` (same equations, slopes from the
    tridiagonal system, power-sum evaluation) in one compiled call, without scipy's per-spline
    set-up cost (the leg synthesis builds three splines per step).

    Args:
        x: (m,) increasing knots.
        y: (m,) or (m, k) values at the knots.
        d0: the first derivative at ``x[0]`` (scalar or (k,)).
        d1: the first derivative at ``x[-1]`` (scalar or (k,)).
        xq: (q,) query points.

    Returns:
        (q,) for (m,) values, else (q, k).
    """
    y = np.asarray(y, dtype=float)
    vec = y.ndim == 2
    y2 = y if vec else y[:, None]
    k = y2.shape[1]
    out = clamped_cubic_rows(
        np.asarray(x, dtype=float),
        np.ascontiguousarray(y2),
        np.broadcast_to(np.asarray(d0, dtype=float), (k,)).copy(),
        np.broadcast_to(np.asarray(d1, dtype=float), (k,)).copy(),
        np.atleast_1d(np.asarray(xq, dtype=float)),
    )
    return out if vec else out[:, 0]


@njit
def clamped_cubic_rows(x, y, d0, d1, xq):
    """The arithmetic of :func:`clamped_cubic` for column values.

    Args:
        x: (m,) increasing knots, m >= 2.
        y: (m, k) values at the knots.
        d0: (k,) first derivatives at ``x[0]``.
        d1: (k,) first derivatives at ``x[-1]``.
        xq: (q,) query points.

    Returns:
        (q, k) the splines at ``xq``.
    """
    n, k = y.shape
    dx = x[1:] - x[:-1]
    out = np.empty((len(xq), k))
    s = np.empty(n)
    for c in range(k):
        slope = (y[1:, c] - y[:-1, c]) / dx
        # slopes: identity rows at the ends, dx[i] s[i-1] + 2 (dx[i-1] + dx[i]) s[i]
        # + dx[i-1] s[i+1] = 3 (dx[i] slope[i-1] + dx[i-1] slope[i]) inside (Thomas algorithm)
        s[0], s[n - 1] = d0[c], d1[c]
        if n > 2:
            m = n - 2
            rhs = np.empty(m)
            for i in range(1, n - 1):
                rhs[i - 1] = 3 * (dx[i] * slope[i - 1] + dx[i - 1] * slope[i])
            rhs[0] -= dx[1] * s[0]
            rhs[m - 1] -= dx[n - 3] * s[n - 1]
            diag = np.empty(m)
            for i in range(m):
                diag[i] = 2 * (dx[i] + dx[i + 1])
            # forward sweep: row j (knot j + 1) has lower dx[j + 1], upper dx[j]
            for j in range(1, m):
                w = dx[j + 1] / diag[j - 1]
                diag[j] -= w * dx[j - 1]
                rhs[j] -= w * rhs[j - 1]
            s[m] = rhs[m - 1] / diag[m - 1]
            for j in range(m - 2, -1, -1):
                s[j + 1] = (rhs[j] - dx[j] * s[j + 2]) / diag[j]
        for q in range(len(xq)):
            xv = xq[q]
            i = np.searchsorted(x, xv, side="right") - 1
            i = min(max(i, 0), n - 2)
            t = (s[i] + s[i + 1] - 2 * slope[i]) / dx[i]
            c0 = t / dx[i]
            c1 = (slope[i] - s[i]) / dx[i] - t
            z = xv - x[i]
            out[q, c] = y[i, c] + s[i] * z + c1 * (z * z) + c0 * (z * z * z)
    return out
