"""A capture's units, up axis and frame troubles, read from the captured body itself.

:func:`body_frame` finds the up axis (the pelvis stands above the feet, and the feet's contact
points lie in a plane across it) and the length unit (the leg length and the pelvis height
must give a human stature), and checks them against what the skeleton map declares;
:func:`repair_frames` interpolates frozen (repeated) frames, as trackers write them when they
drop frames, cuts a pose outlier at either end (a T-pose or bind pose first frame) and levels
a floor that drifts linearly over the take (a root drifting in height, as inertial suits'
do).

Proportions: hip joint centre to ankle (thigh + shank) is 0.491 of stature, hip joint centre
height 0.530 and ankle height 0.039 of it (Winter 2009, Fig. 4.1, in
:data:`mjwalk.anthropometry.SEG`), so the pelvis stands about one leg length above the ankles.
The leg length (95th percentile of the hip-ankle distance: the stance leg is nearly straight)
gives the stature, hence the unit; the pelvis height checks that the body stands on its feet.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Literal

import numpy as np

from mjwalk.anthropometry import SEG
from mjwalk.errors import CaptureError
from mjwalk.mocap.skeletons import SkeletonMap, from_z_up, to_z_up

#: Statures a capture may show, metres: mjwalk's walker bounds (``gait.walker.STATURE_RANGE``),
#: which hold the 1st percentile of women to the 99th of men of DIN 33402-2 (about 1.50-1.95 m;
#: quoted from memory) with room for tall people and children over about 7 years.
STATURE_RANGE = (1.2, 2.2)
#: Leg length (hip joint centre to ankle) per stature: thigh + shank (Winter 2009, Fig. 4.1).
LEG_PER_STATURE = SEG["thigh"] + SEG["shank"]
#: The contact samples span a plane when their second spread (RMS) is at least this share of
#: the pelvis height (about 4.5 cm for an adult) and five times the third: a standing take's
#: sway does not define a floor.
MIN_SPREAD = 0.05
#: Lowest frame rate read, Hz (film rate, the lowest common capture rate): below it a double
#: support (about 0.1 s, some 10 % of a 1.1 s stride; Perry 1992, quoted from memory) spans
#: fewer than three frames and the contacts the step segmentation cuts at are not resolved.
MIN_FPS = 24.0
#: Pelvis height above the ankles per leg length a capture may show: 1.0 standing (Winter 2009:
#: 0.491 H both), lower in walking's flexed stance (0.93 median over the shared Bandai walks),
#: with room for crouched gait; outside it the pelvis or hip joints are named wrongly.
PELVIS_PER_LEG = (0.7, 1.2)
#: Length units tried when the map gives none, metres per unit.
UNIT_CANDIDATES: dict[str, float] = {"m": 1.0, "cm": 0.01, "mm": 0.001, "in": 0.0254}
#: The contact plane's normal may lie this far from the pelvis-over-feet axis, degrees: the
#: floor of a level lab against a body leaning at most this much on average.
MAX_TILT_DEG = 20.0
#: Longest run of frozen frames interpolated, seconds: about a third of a step (step duration
#: about 0.55 s at 1.3 m/s, agethen2018 / Winter 2009 cadence ~110 steps/min).
MAX_FROZEN_S = 0.2
#: An end frame is a pose outlier when its joints jump more than this (metres) to the next
#: frame and more than ``OUTLIER_FACTOR`` times the median frame-to-frame motion of the
#: quarter second beside it (a walking foot moves smoothly; a swapped-in pose jumps).
OUTLIER_MIN_JUMP = 0.05
OUTLIER_FACTOR = 8.0
#: Window over which the floor is the lowest foot joint, seconds: about one stride (1.1 s at
#: ~110 steps/min, Winter 2009), so each window holds a stance of each foot.
FLOOR_WINDOW_S = 1.2
#: A floor drifting less than this over the take is left alone, metres (a capture system's
#: calibration, a few millimetres, is well under it; segmentation's contact height offset is
#: larger, ``gait.segment.ContactOptions``).
MIN_FLOOR_DRIFT = 0.02


def _role_positions(positions: np.ndarray, names: list[str], skel: SkeletonMap) -> dict:
    """Role -> (T, 3) file-frame positions of the seven joints the map names."""
    index = {n: i for i, n in enumerate(names)}
    return {r: positions[:, index[j]] for r, j in skel.required_joints().items()}


def _up_from_body(p: dict, path: object) -> tuple[int, float]:
    """(axis index, pelvis height above the ankles in file units) from the body's stance."""
    ankles = 0.5 * (p["ankle_l"] + p["ankle_r"])
    v = np.median(p["pelvis"] - ankles, axis=0)
    axis = int(np.argmax(np.abs(v)))
    others = np.delete(np.abs(v), axis)
    if v[axis] <= 0 or np.abs(v[axis]) < 2.0 * others.max():
        raise CaptureError(
            f"{path}: cannot tell the up axis: the pelvis stands "
            f"({v[0]:.3g}, {v[1]:.3g}, {v[2]:.3g}) file units from the ankles; give up = 'y' or "
            "'z' in a skeleton map (--skeleton map.toml)"
        )
    return axis, float(v[axis])


def _contact_normal(p: dict, pelvis: float) -> np.ndarray | None:
    """Unit normal of the plane the feet's slow (contact) samples span, each foot joint about
    its own mean, or None when they do not span a plane (a straight walk's contacts lie near a
    line, a standing take's in spots: their second spread is under :data:`MIN_SPREAD` of the
    pelvis height ``pelvis``)."""
    pts = []
    for r in ("ankle_l", "ankle_r", "toe_l", "toe_r"):
        x = p[r]
        if x.shape[0] < 3:
            return None
        speed = np.linalg.norm(np.diff(x, axis=0), axis=1)
        c = x[1:][speed <= np.percentile(speed, 20)]
        pts.append(c - c.mean(axis=0))  # each joint about its own mean: ankle above toe
    q = np.concatenate(pts)
    s, vt = np.linalg.svd(q, full_matrices=False)[1:]
    if s[1] < 5.0 * s[2] or s[1] / np.sqrt(q.shape[0]) < MIN_SPREAD * pelvis:
        return None
    return vt[2]


def _stature(leg: float, scale: float) -> float:
    """The stature (m) a leg length of ``leg`` file units gives at ``scale`` m per unit."""
    return leg * scale / LEG_PER_STATURE


def _fits(leg: float, scale: float) -> bool:
    return STATURE_RANGE[0] <= _stature(leg, scale) <= STATURE_RANGE[1]


def _scale(skel: SkeletonMap, leg: float, path: object) -> float:
    """The file's metres per unit: the declared one checked, or the one candidate that fits."""
    fitting = [(u, s) for u, s in UNIT_CANDIDATES.items() if _fits(leg, s)]
    if not skel.guess_scale:
        if _fits(leg, skel.scale):
            return skel.scale
        hint = f"the data fit units = '{fitting[0][0]}'" if fitting else "no length unit fits"
        raise CaptureError(
            f"{path}: skeleton {skel.name!r} declares {skel.scale:g} m per unit, which makes a "
            f"leg of {leg * skel.scale:.3g} m, a stature of {_stature(leg, skel.scale):.3g} m "
            f"outside {STATURE_RANGE[0]}-{STATURE_RANGE[1]} m; {hint} (--skeleton map.toml)"
        )
    if len(fitting) == 1:
        return fitting[0][1]
    raise CaptureError(
        f"{path}: cannot tell the length unit: a leg of {leg:.4g} file units gives a stature in "
        f"{STATURE_RANGE[0]}-{STATURE_RANGE[1]} m for {', '.join(u for u, _ in fitting) or 'none'}"
        f" of {', '.join(UNIT_CANDIDATES)}; give units in a skeleton map (--skeleton map.toml)"
    )


def body_frame(
    positions: np.ndarray, names: list[str], skel: SkeletonMap, path: object = ""
) -> SkeletonMap:
    """The map with the file's scale and up axis read from (or checked against) the body.

    Args:
        positions: (T, J, 3) joint positions in file units and the file's frame.
        names: the J joint names (the map's seven are present).
        skel: the map; ``guess_scale``/``guess_up`` say what to read, ``verify`` or either
            guess that the declared values are checked.
        path: the file, for messages.

    Returns:
        ``skel`` with ``scale`` and ``up`` from the data, its guess flags cleared, and
        ``verify`` set.

    Raises:
        CaptureError: one line when the up axis is not y or z, the feet's contact plane is
            tilted from it, no (or more than one) unit gives a human stature, or the declared
            unit or axis contradicts the data, naming the map-file fix.
    """
    p = _role_positions(np.asarray(positions, float), names, skel)
    axis, pelvis = _up_from_body(p, path)
    normal = _contact_normal(p, pelvis)
    if normal is not None and abs(normal[axis]) < np.cos(np.radians(MAX_TILT_DEG)):
        tilt = np.degrees(np.arccos(min(1.0, abs(normal[axis]))))
        raise CaptureError(
            f"{path}: the feet's contact plane is tilted {tilt:.0f} deg from the pelvis-over-"
            f"feet axis {'xyz'[axis]}: not a level walk, or joints named wrongly in the map"
        )
    if axis == 0:
        raise CaptureError(
            f"{path}: the body stands along x; only y or z up is supported: rotate the file"
        )
    found = "xyz"[axis]
    if not skel.guess_up and found != skel.up:
        raise CaptureError(
            f"{path}: skeleton {skel.name!r} declares {skel.up} up but the pelvis stands above "
            f"the feet along {found}; use up = '{found}' (--skeleton map.toml)"
        )
    legs = [np.linalg.norm(p["hip" + s] - p["ankle" + s], axis=1) for s in ("_l", "_r")]
    leg = float(np.percentile(np.concatenate(legs), 95))
    lo, hi = PELVIS_PER_LEG
    if not lo <= pelvis / leg <= hi:
        raise CaptureError(
            f"{path}: the pelvis joint {skel.pelvis!r} stands {pelvis / leg:.2f} leg lengths "
            f"above the ankles (a standing or walking body: {lo}-{hi}); map the hip-centre joint "
            "as pelvis and the thigh's first joint as hip (--skeleton map.toml)"
        )
    scale = _scale(skel, leg, path)
    up: Literal["y", "z"] = "y" if found == "y" else "z"
    return replace(skel, scale=scale, up=up, guess_scale=False, guess_up=False, verify=True)


def _frozen_runs(world: np.ndarray) -> list[tuple[int, int]]:
    """[a, b) runs of frames that repeat frame a - 1 exactly (every joint)."""
    same = np.all(world[1:] == world[:-1], axis=(1, 2))
    runs, t = [], 0
    n = same.shape[0]
    while t < n:
        if same[t]:
            u = t
            while u < n and same[u]:
                u += 1
            runs.append((t + 1, u + 1))
            t = u
        else:
            t += 1
    return runs


def _fill_frozen(world: np.ndarray, fps: float, path: object) -> tuple[np.ndarray, int]:
    """Frozen runs between two moving frames replaced by linear interpolation."""
    out = world.copy()
    filled = 0
    for a, b in _frozen_runs(world):
        if b >= world.shape[0]:
            continue  # frozen to the end: the body stands still, or the take ends there
        moved = float(np.max(np.linalg.norm(world[b] - world[a - 1], axis=-1)))
        if moved < 1e-6:
            continue  # a still body repeats itself
        if (b - a) / fps > MAX_FROZEN_S:
            raise CaptureError(
                f"{path}: frames {a + 1}-{b} repeat one pose for {(b - a) / fps:.2f} s while "
                f"the body moves {moved:.2f} m: tracking was lost there; cut the file at that gap"
            )
        w = (np.arange(a, b) - (a - 1)) / (b - (a - 1))
        out[a:b] = world[a - 1] + w[:, None, None] * (world[b] - world[a - 1])
        filled += b - a
    return out, filled


def _end_outliers(world: np.ndarray, joints: list[int], fps: float) -> tuple[int, int]:
    """(frames to cut at the start, at the end): up to three end frames whose joints jump to
    the next frame far more than the take moves per frame in the quarter second beside them
    (a T-pose or bind pose frame)."""
    x = world[:, joints]
    step = np.max(np.linalg.norm(np.diff(x, axis=0), axis=-1), axis=1)
    w = max(3, round(0.25 * fps))
    if step.size < 2 * w + 6:
        return 0, 0

    def count(seq: np.ndarray) -> int:
        n = 0
        while n < 3:
            limit = max(OUTLIER_MIN_JUMP, OUTLIER_FACTOR * float(np.median(seq[n + 1 : n + 1 + w])))
            if seq[n] <= limit:
                break
            n += 1
        return n

    return count(step), count(step[::-1])


def _level_floor(world: np.ndarray, feet: list[int], fps: float) -> tuple[np.ndarray, float]:
    """Remove a linear drift of the floor: the lowest foot joint's height per
    :data:`FLOOR_WINDOW_S` window, fitted by a line over time; subtracted when it drifts more
    than :data:`MIN_FLOOR_DRIFT` over the take (returns the drift removed, metres)."""
    n = max(1, round(FLOOR_WINDOW_S * fps))
    k = world.shape[0] // n
    if k < 3:
        return world, 0.0
    low = world[: k * n, feet, 2].min(axis=1).reshape(k, n).min(axis=1)
    t_mid = (np.arange(k) * n + 0.5 * (n - 1)) / fps
    slope = float(np.polyfit(t_mid, low, 1)[0])
    t = np.arange(world.shape[0]) / fps
    drift = slope * t[-1]
    if abs(drift) <= MIN_FLOOR_DRIFT:
        return world, 0.0
    out = world.copy()
    out[..., 2] -= (slope * (t - t.mean()))[:, None]
    return out, drift


def repair_frames(
    positions: np.ndarray, names: list[str], skel: SkeletonMap, fps: float, path: object = ""
) -> tuple[np.ndarray, dict]:
    """Frozen frames interpolated, pose-outlier end frames cut, a drifting floor levelled.

    Args:
        positions: (T, J, 3) joint positions in file units and the file's frame.
        names: the J joint names.
        skel: the map (its ``scale`` and ``up`` resolved, :func:`body_frame`) naming the seven
            joints whose motion decides.
        fps: the rate of ``positions``, Hz.
        path: the file, for messages.

    Returns:
        The repaired (T', J, 3) positions in file units and frame (``positions`` itself when
        nothing was done) and what was done, the non-zero ones of ``frozen_filled``,
        ``cut_start``, ``cut_end`` (frame counts) and ``floor_drift_m`` (the floor drift
        removed, metres).

    Raises:
        CaptureError: a frozen run longer than :data:`MAX_FROZEN_S` while the body moves.
    """
    world = to_z_up(np.asarray(positions, float), skel.up) * skel.scale
    index = {n: i for i, n in enumerate(names)}
    roles = [index[j] for j in skel.required_joints().values()]
    head, tail = _end_outliers(world, roles, fps)
    world = world[head : world.shape[0] - tail]
    world, filled = _fill_frozen(world, fps, path)
    feet = [index[getattr(skel, r)] for r in ("ankle_l", "ankle_r", "toe_l", "toe_r")]
    world, drift = _level_floor(world, feet, fps)
    done = {
        "frozen_filled": filled,
        "cut_start": head,
        "cut_end": tail,
        "floor_drift_m": round(drift, 4),
    }
    done = {k: v for k, v in done.items() if v}
    if not done:
        return positions, done
    return from_z_up(world / skel.scale, skel.up), done
