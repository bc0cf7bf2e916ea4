"""The hybrid A*'s found chain of steps as a walk: its 120 Hz pelvis track, headings and
footfalls in the world (:func:`assemble_walk`).
"""

from __future__ import annotations

import numpy as np

from mjwalk.conventions import SAMPLE_RATE_HZ
from mjwalk.gait.features import spline_basis
from mjwalk.plan.walkpath import PathStep, WalkPath

FPS = SAMPLE_RATE_HZ


def to_world(px, py, heading, local: np.ndarray) -> np.ndarray:
    """Local step coordinates (x right, y forward) -> world, for a frame at (px, py) heading
    ``heading`` (radians from +x). ``local`` (..., 2); px, py, heading broadcast against it."""
    s, c = np.sin(heading), np.cos(heading)
    x, y = local[..., 0], local[..., 1]
    return np.stack([px + x * s + y * c, py - x * c + y * s], axis=-1)


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
    """
    parent, rows, pos, frames, lefts = nodes
    ids = []
    while nid > 0:
        ids.append(nid)
        nid = parent[nid]
    chain = np.array(ids[::-1])
    left = lefts[chain]
    batch = model.decode(feats[rows[chain]], np.where(left, "left", "right"))
    ox = pos[parent[chain]].real
    oy = pos[parent[chain]].imag
    fr = frames[chain]
    # the steps at 120 Hz (sample 0 of each is the previous step's last), one frame each
    # (StepBatch.trajectory: K = round(duration·fps) + 1 samples, at least 2, its spline
    # basis looked up once per sample count)
    n = len(chain)
    sizes = np.maximum(np.round(batch.duration * FPS).astype(np.int64) + 1, 2).tolist()
    local_parts, yaw_parts = [], []
    for row, k in enumerate(sizes):
        basis = spline_basis(k)
        local_parts.append((basis @ batch.landmarks[row])[1:])
        yaw_parts.append(basis @ batch.yaw_landmarks[row])
    counts = [k - 1 for k in sizes]
    # every sample's step, then the landing and the stance foot of every step: one turn
    # into the world for all of them
    of = np.concatenate([np.repeat(np.arange(n), counts), np.arange(n), np.arange(n)])
    local = np.concatenate([*local_parts, batch.footprint[:, :2], batch.stance[:, :2]])
    world = to_world(ox[of], oy[of], fr[of], local)
    k = len(world) - 2 * n
    xy = np.empty((1 + k, 2))
    xy[0] = pos[0].real, pos[0].imag
    xy[1:] = world[:k]
    # sample 0 faces the first step's frame: a starter's turn on the spot (free start
    # heading) is not part of the walk (a cycle turns the operator before it), so the
    # pelvis yaw does not jump between samples 0 and 1
    yaw = np.empty(len(xy))
    yaw[0] = fr[0] + yaw_parts[0][0]
    yaw[1:] = fr[of[:k]] + np.concatenate([y[1:] for y in yaw_parts])
    # world poses (x, y, yaw) of every step's landing foot and of its own estimate of the
    # stance foot
    feet = np.column_stack([world[k : k + n], fr + batch.footprint[:, 2]])
    own_stance = np.column_stack([world[k + n :], fr + batch.stance[:, 2]])
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
