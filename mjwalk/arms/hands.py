"""The hand: a one-parameter grip synergy of the humanoid's fingers and the thumb-index
aperture it makes (forward kinematics of :mod:`mjwalk.body.humanoid` in MuJoCo).

Angles in radians, apertures in metres.
"""

from __future__ import annotations

import threading

import mujoco
import numpy as np
from scipy.optimize import brentq

from mjwalk.body.humanoid import humanoid_model
from mjwalk.conventions import DEFAULT_STATURE, Side, side_prefix
from mjwalk.errors import MjwalkError

_FINGERS = ("index", "middle", "ring", "little")
#: Joint angles (rad) of the one-parameter grip synergy at closure g = 0 (open) and g = 1.
_OPEN_CMC, _CLOSED_FLEX = 1.1, 1.0


#: Hand models kept per thread and stature (each thread its own MjData: the forward
#: kinematics write into it, and threads may ask at once).
_HAND_MODELS = threading.local()
_HAND_MODELS_KEPT = 4


def _hand_model(stature: float):
    kept = _HAND_MODELS.__dict__.setdefault("kept", {})
    if stature not in kept:
        if len(kept) >= _HAND_MODELS_KEPT:
            kept.pop(next(iter(kept)))  # the one made first
        model, jmap = humanoid_model(stature)
        kept[stature] = (model, jmap, mujoco.MjData(model))
    return kept[stature]


def grip_synergy(closure: float, side: Side = "left") -> dict[str, float]:
    """Finger joint angles (rad) of the grip synergy at ``closure`` in [0, 1]: the thumb's
    opposition (CMC) closes from 63 deg to 0 while the four fingers flex (MCP = PIP = phi,
    DIP = 0.7 phi, phi up to 57 deg) and the thumb MCP/IP flex to half that.

    Args:
        closure: grip closure, clipped to [0, 1] (0 open).
        side: "left" or "right".

    Returns:
        ``{joint name: angle}``, radians.
    """
    g = float(np.clip(closure, 0.0, 1.0))
    phi = _CLOSED_FLEX * g
    p = side_prefix(side)  # joint names: "thumb_l_cmc"
    q = {f"thumb_{p}_cmc": _OPEN_CMC * (1 - g)}
    q[f"thumb_{p}_mcp"] = 0.5 * phi * 0.8
    q[f"thumb_{p}_ip"] = 0.5 * phi
    for f in _FINGERS:
        q[f"{f}_{p}_mcp"] = phi
        q[f"{f}_{p}_pip"] = phi
        q[f"{f}_{p}_dip"] = 0.7 * phi
    return q


def pinch_aperture(
    finger_q: dict[str, float], side: Side = "left", stature: float = DEFAULT_STATURE
) -> float:
    """Distance (m) between the thumb tip and the index fingertip of the humanoid hand for the
    given finger joint angles (forward kinematics of mjwalk.body.humanoid in MuJoCo).

    Args:
        finger_q: ``{joint name: angle}`` in radians (other joints neutral).
        side: "left" or "right".
        stature: body height, metres.

    Returns:
        the aperture, metres.
    """
    model, jmap, data = _hand_model(round(float(stature), 4))
    p = side_prefix(side)
    q = jmap.neutral_qpos(model, stature)
    for name, v in finger_q.items():
        q[jmap.adr(name)] = v
    data.qpos[:] = q
    mujoco.mj_kinematics(model, data)

    def tip(body, length):
        b = model.body(body).id
        return data.xpos[b] + data.xmat[b].reshape(3, 3) @ np.array([0.0, 0.0, -length * stature])

    return float(np.linalg.norm(tip(f"index_{p}_dip_seg", 0.011) - tip(f"thumb_{p}_tip", 0.015)))


def fingers_for_aperture(
    aperture: float, side: Side = "left", stature: float = DEFAULT_STATURE
) -> dict:
    """Finger joint angles (rad) whose thumb-index distance equals ``aperture`` metres (to
    0.1 mm) along the grip synergy; apertures outside the hand's range raise MjwalkError.

    Args:
        aperture: thumb-index distance, metres.
        side: "left" or "right".
        stature: body height, metres.

    Returns:
        ``{joint name: angle}``, radians.
    """
    lo = pinch_aperture(grip_synergy(1.0, side), side, stature)
    hi = pinch_aperture(grip_synergy(0.0, side), side, stature)
    if not lo <= aperture <= hi:
        raise MjwalkError(
            f"grip aperture {aperture * 100:.1f} cm outside the hand's range "
            f"{lo * 100:.1f}-{hi * 100:.1f} cm (stature {stature} m)"
        )
    g = brentq(
        lambda c: pinch_aperture(grip_synergy(c, side), side, stature) - aperture,
        0.0,
        1.0,
        xtol=1e-6,
    )
    return grip_synergy(g, side)


def finger_trajectory(
    apertures: np.ndarray, side: Side = "left", stature: float = DEFAULT_STATURE
) -> dict:
    """Finger joint angles over time: {joint name: (n,) radians} for grip ``apertures`` (n,)
    metres (clipped to the hand's range).

    Args:
        apertures: (n,) grip apertures, metres.
        side: "left" or "right".
        stature: body height, metres.

    Returns:
        ``{joint name: (n,) angles}``, radians.
    """
    lo = pinch_aperture(grip_synergy(0.95, side), side, stature)
    hi = pinch_aperture(grip_synergy(0.0, side), side, stature)
    frames = [fingers_for_aperture(float(np.clip(a, lo, hi)), side, stature) for a in apertures]
    return {k: np.array([f[k] for f in frames]) for k in frames[0]}
