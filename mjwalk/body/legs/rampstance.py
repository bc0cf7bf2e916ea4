"""The stance leg walking up a ramp (issue 47, deliverable 4: the body on ramps): the stance
ankle dorsiflexes by only part of the slope; the leg above it takes up the rest.

On a ramp the flat leg synthesis's tracks are carried onto the slope
(:func:`~mjwalk.body.legs.legheights.lift_to_levels`): the grounded foot is pitched to the
slope and the pelvis follows the ground, so the stance ankle would dorsiflex by the whole
slope beyond its level angle. People walking uphill do not: their peak stance dorsiflexion
rises from 10.1 deg on the level to 21.0 deg on a 20 deg slope, about half the slope
(:data:`RAMP_STANCE_DORSI_GAIN`). Here the stance ankle of a single support on an uphill ramp
is held to its level angle plus that share of the slope by raising the pelvis (the stance
knee extends), at most :data:`~mjwalk.body.legs.stance.REACH_DROP_MAX`, eased in and out over
the samples around (:func:`~mjwalk.body.legs.curves.spread`). Downhill and level ground are
left as they are. World frame, metres, radians; a pitch is + toes up.
"""

from __future__ import annotations

import numpy as np

from mjwalk.body.humanoid import LegGeometry
from mjwalk.body.legs.curves import spread
from mjwalk.body.legs.edgeswing import FLAT_PITCH
from mjwalk.body.legs.ik import leg_ik_world
from mjwalk.body.legs.stance import REACH_DROP_MAX
from mjwalk.body.legs.steps import FootTracks

#: Peak stance ankle dorsiflexion gained per unit of uphill slope (deg per deg): 10.1 deg on
#: the level to 21.0 deg on a 20 deg treadmill incline, healthy adults with a normal
#: dorsiflexion range (passive 46.4 +- 4.2 deg; nine participants; the group with a limited
#: range 9.6 to 19.0 deg): Kwon & Shin, "Foot kinematics and leg muscle activation patterns
#: are altered in those with limited ankle dorsiflexion range of motion during incline
#: walking", Gait Posture (2022), doi 10.1016/j.gaitpost.2021.12.002 (abstract verified
#: here; the angles at 5-15 deg are not in it, so the gain is the end points' slope). Applied
#: here to every sample of an uphill single support, not to the peak alone (an assumption).
RAMP_STANCE_DORSI_GAIN = (21.0 - 10.1) / 20.0
#: Passes of the pelvis raise's secant solve (the dorsiflexion left over falls under 0.05 deg
#: by the third on a 5.5 deg ramp).
RAISE_PASSES = 3
#: Step (m) of the finite difference by which the solve measures the ankle's response.
RAISE_PROBE = 0.005


def _dorsi(feet: FootTracks, s: str, j: np.ndarray, root: np.ndarray, yaw: np.ndarray,
           geom: LegGeometry, ankle=None, pitch=None) -> np.ndarray:  # fmt: skip
    """The ``s`` leg's unclipped ankle flexion (radians, + dorsiflexion) at samples ``j`` for
    the pelvis ``root`` (len(j), 3) and the feet's tracks (or the given ankles and pitches)."""
    a = feet.ankle[s][j] if ankle is None else ankle[j]
    p = feet.pitch[s][j] if pitch is None else pitch[j]
    raw = leg_ik_world(a, feet.fyaw[s][j], p, root, yaw[j], s, geom)
    return raw[f"ankle_{s}_flex"]


def _stance_peaks(feet: FootTracks, s: str, air: np.ndarray, flat: tuple[dict, dict, np.ndarray],
                  yaw: np.ndarray, geom: LegGeometry) -> np.ndarray:  # fmt: skip
    """(n,) per grounded sample of the ``s`` foot the peak ankle dorsiflexion of the flat
    synthesis over that stance (its run of grounded samples; radians; 0 in the air)."""
    flat_ankle, flat_pitch, flat_root = flat
    g = np.flatnonzero(~air)
    out = np.zeros(len(air))
    if not len(g):
        return out
    d = _dorsi(feet, s, g, flat_root[g], yaw, geom, flat_ankle[s], flat_pitch[s])
    run = np.cumsum(np.r_[True, np.diff(g) > 1]) - 1  # stance number per grounded sample
    peak = np.full(run[-1] + 1, -np.inf)
    np.maximum.at(peak, run, d)
    out[g] = peak[run]
    return out


def uphill_stance_raise(feet: FootTracks, flat: tuple[dict, dict, np.ndarray], root: np.ndarray,
                        yaw: np.ndarray, air: dict, surface: dict, geom: LegGeometry,
                        win: int) -> np.ndarray:  # fmt: skip
    """How far to raise the pelvis so that a stance ankle on an uphill ramp dorsiflexes no more
    than its level angle plus :data:`RAMP_STANCE_DORSI_GAIN` times the slope.

    Args:
        feet: the foot tracks on their surfaces (grounded feet pitched to the slope).
        flat: the flat synthesis's ankles and pitches (side -> (n, 3) / (n,)) and pelvis
            positions (n, 3), metres and radians: the level angles.
        root: (n, 3) the pelvis on the levels, metres.
        yaw: (n,) the pelvis yaw, radians from +x CCW.
        air: per side (n,) whether the foot is in the air.
        surface: per side (n,) the slope under the foot, radians (+ uphill along it).
        geom: the leg geometry.
        win: half-width (samples) over which a raise eases in and out.

    Returns:
        (n,) the raise, metres (>= 0; 0 off uphill ramps and in double support).
    """
    need = np.zeros(len(root))
    for s, o in (("l", "r"), ("r", "l")):
        j = np.flatnonzero(~air[s] & air[o] & (surface[s] > FLAT_PITCH))
        if not len(j):
            continue
        goal = _stance_peaks(feet, s, air[s], flat, yaw, geom)[j]
        goal = goal + RAMP_STANCE_DORSI_GAIN * surface[s][j]
        up = np.zeros(len(j))
        for _ in range(RAISE_PASSES):
            r = root[j].copy()
            r[:, 2] += up
            d0 = _dorsi(feet, s, j, r, yaw, geom)
            r[:, 2] += RAISE_PROBE
            rate = (d0 - _dorsi(feet, s, j, r, yaw, geom)) / RAISE_PROBE  # rad per metre up
            step = np.where(rate > 1e-6, (d0 - goal) / np.maximum(rate, 1e-6), 0.0)
            up = np.clip(up + step, 0.0, REACH_DROP_MAX)
        need[j] = up
    if not need.any():
        return need
    return np.minimum(spread(need, win), REACH_DROP_MAX)
