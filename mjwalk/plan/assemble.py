"""The hybrid A*'s found chain of steps as a walk: its 120 Hz pelvis track, headings and
footfalls in the world (:func:`assemble_walk`).
"""

from __future__ import annotations

import math

import numpy as np

from mjwalk._jit import njit
from mjwalk.conventions import SAMPLE_RATE_HZ
from mjwalk.gait.features import spline_pieces
from mjwalk.plan.walkpath import PathStep, WalkPath

FPS = SAMPLE_RATE_HZ


def to_world(px, py, heading, local: np.ndarray) -> np.ndarray:
    """Local step coordinates (x right, y forward) -> world, for a frame at (px, py) heading
    ``heading`` (radians from +x). ``local`` (..., 2); px, py, heading broadcast against it.

    Args:
        px: the frame's origin x, metres, world frame (scalar or broadcasting array).
        py: the frame's origin y, metres.
        heading: the frame's heading, radians from +x CCW.
        local: (..., 2) points in the step frame (x right, y forward), metres.

    Returns:
        (..., 2) the points in the world frame: (px + x·sin h + y·cos h, py - x·cos h + y·sin h).
    """
    s, c = np.sin(heading), np.cos(heading)
    x, y = local[..., 0], local[..., 1]
    return np.stack([px + x * s + y * c, py - x * c + y * s], axis=-1)


@njit
def _turned(px, py, s, c, x, y):
    """:func:`to_world` of one local point (x, y) for a frame at (px, py) whose heading has
    sine ``s`` and cosine ``c``."""
    return px + x * s + y * c, py - x * c + y * s


@njit
def _basis_at(u, starts, coef, out):
    """The landmark spline's basis (6,) at normalized time ``u`` into ``out``
    (:func:`~mjwalk.gait.features.spline_pieces`)."""
    j = 0
    while j + 1 < starts.shape[0] and u >= starts[j + 1]:
        j += 1
    d = u - starts[j]
    for c in range(out.shape[0]):
        out[c] = ((coef[0, j, c] * d + coef[1, j, c]) * d + coef[2, j, c]) * d + coef[3, j, c]


@njit
def _walk_samples(landmarks, yaw_lm, sizes, fr, ox, oy, foot, stance, starts, coef, x0, y0):
    """The walk's pelvis samples (1 + sum(sizes - 1), 2) and yaws, and every step's landing
    and stance foot as world poses (n, 3): step r's samples 1 .. sizes[r] - 1 of its spline
    (:func:`~mjwalk.gait.features.spline_basis`: its first and last rows the first and last
    landmark exactly) in its frame at (ox[r], oy[r]) heading fr[r] (:func:`to_world`);
    sample 0 the walk's start (x0, y0) facing the first step's first yaw."""
    n = sizes.shape[0]
    total = 1
    for r in range(n):
        total += sizes[r] - 1
    xy = np.empty((total, 2))
    yaw = np.empty(total)
    xy[0, 0], xy[0, 1] = x0, y0
    basis = np.empty(landmarks.shape[1])
    last = landmarks.shape[1] - 1
    idx = 1
    for r in range(n):
        k = sizes[r]
        s, c = math.sin(fr[r]), math.cos(fr[r])
        for i in range(0 if r == 0 else 1, k):
            if i == 0 or i == k - 1:
                basis[:] = 0.0
                basis[0 if i == 0 else last] = 1.0
            else:
                _basis_at(i / (k - 1), starts, coef, basis)
            lx = ly = yw = 0.0
            for b in range(basis.shape[0]):
                lx += basis[b] * landmarks[r, b, 0]
                ly += basis[b] * landmarks[r, b, 1]
                yw += basis[b] * yaw_lm[r, b]
            if i == 0:
                yaw[0] = fr[0] + yw
                continue
            xy[idx, 0], xy[idx, 1] = _turned(ox[r], oy[r], s, c, lx, ly)
            yaw[idx] = fr[r] + yw
            idx += 1
    feet = np.empty((n, 3))
    own = np.empty((n, 3))
    for r in range(n):
        s, c = math.sin(fr[r]), math.cos(fr[r])
        feet[r, 0], feet[r, 1] = _turned(ox[r], oy[r], s, c, foot[r, 0], foot[r, 1])
        feet[r, 2] = fr[r] + foot[r, 2]
        own[r, 0], own[r, 1] = _turned(ox[r], oy[r], s, c, stance[r, 0], stance[r, 1])
        own[r, 2] = fr[r] + stance[r, 2]
    return xy, yaw, feet, own


def assemble_walk(model, nid: int, nodes, feats: np.ndarray, meta: dict) -> WalkPath:
    """The walk that ends at search node ``nid``: its steps decoded by ``model`` from their
    features ``feats`` (rows ``nodes[1]``) and turned into the world at their nodes' frames.

    Args:
        model: the step model the steps were drawn from.
        nid: the goal node (node 0 is the start).
        nodes: the search's (parent, rows, pos, frames, lefts) per node: predecessor, feature
            row, end point (world x + iy, metres), step-frame heading (radians) and whether
            the step's swing foot is the left one.
        feats: the sampled features (rows, d).
        meta: the walk's ``meta``.

    Returns:
        The walk sampled at :data:`FPS` (world frame, metres, radians) with its steps and
        ``meta``.
    """
    parent, rows, pos, frames, lefts = nodes
    ids = []
    while nid > 0:
        ids.append(nid)
        nid = parent[nid]
    chain = np.array(ids[::-1])
    left = lefts[chain]
    # the sides as booleans (True: right; batch_from_raw makes the same strings once)
    batch = model.decode(feats[rows[chain]], ~left)
    ox = pos[parent[chain]].real
    oy = pos[parent[chain]].imag
    fr = frames[chain]
    # the steps at 120 Hz (sample 0 of each is the previous step's last), one frame each
    # (StepBatch.trajectory: K = round(duration·fps) + 1 samples, at least 2), and every
    # step's landing and stance foot, turned into the world in one compiled pass
    sizes = np.maximum(np.round(batch.duration * FPS).astype(np.int64) + 1, 2)
    starts, coef = spline_pieces()
    xy, yaw, feet, own_stance = _walk_samples(
        batch.landmarks, batch.yaw_landmarks, sizes, fr, ox, oy, batch.footprint,
        batch.stance, starts, coef, pos[0].real, pos[0].imag,
    )  # fmt: skip
    counts = (sizes - 1).tolist()
    steps: list[PathStep] = []
    landed: dict[bool, np.ndarray] = {}
    ends = np.cumsum(counts).tolist()
    index = 0
    for row, is_left in enumerate(left.tolist()):
        # A foot stays where it landed: the stance foot of a step is where that foot landed
        # in the step before (each sampled step also carries its own estimate of it, a few
        # centimetres off its predecessor's landing, which would make the foot jump).
        stance_w = landed.get(not is_left, own_stance[row])
        landed[is_left] = feet[row]
        side = "left" if is_left else "right"
        steps.append(
            PathStep(side=side, start=index, end=ends[row], foot=feet[row], stance=stance_w)
        )
        index = ends[row]
    return WalkPath(
        t=np.arange(len(xy)) / FPS,
        xy=xy,
        yaw=yaw,
        steps=steps,
        meta=meta,
    )
