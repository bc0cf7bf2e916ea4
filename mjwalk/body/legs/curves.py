"""Smooth shaping functions of the leg synthesis: smoothstep, soft clamps and envelopes."""

from __future__ import annotations

import numpy as np
from scipy.ndimage import gaussian_filter1d, maximum_filter1d

#: Pitches smaller than this (degrees) count as a flat foot (no roll, so no drift).
FLAT_DEG = 2.0


def smoothstep(x: np.ndarray) -> np.ndarray:
    x = np.clip(x, 0.0, 1.0)
    return x * x * (3 - 2 * x)


def spread(need: np.ndarray, win: int) -> np.ndarray:
    """A smooth (n,) envelope of the non-negative per-sample amounts ``need`` (n,): their
    running maximum over +-``win`` samples, Gaussian-smoothed (sigma ``win / 3``), so a
    correction needed at some samples fades in and out over the samples around instead of
    acting on them alone (a jump)."""
    return gaussian_filter1d(maximum_filter1d(need, 2 * win + 1), win / 3)


def soft_clip01(x: np.ndarray, w: float) -> np.ndarray:
    """``x`` clamped to [0, 1] with rounded corners (C1): unchanged in [w, 1 - w], quadratic
    blends over ``w`` either side of 0 and 1, constant beyond (``w`` <= 0.5)."""
    x = np.asarray(x, float)
    lo = np.where(x < -w, 0.0, np.where(x < w, (x + w) ** 2 / (4 * w), x))
    return np.where(lo > 1 + w, 1.0, np.where(lo > 1 - w, 1 - (1 + w - lo) ** 2 / (4 * w), lo))


def soft_flat(p: np.ndarray) -> np.ndarray:
    """Pitches within +-FLAT_DEG become exactly 0 (flat foot), continuously."""
    t = np.deg2rad(FLAT_DEG)
    return np.sign(p) * np.maximum(np.abs(p) - t, 0.0)


def soft_excess(x: np.ndarray, w: float) -> np.ndarray:
    """max(x, 0) rounded over ``[0, 2 w]`` (C1): 0 for x <= 0, x - w for x >= 2 w."""
    x = np.maximum(x, 0.0)
    return np.where(x < 2 * w, x * x / (4 * w), x - w)
