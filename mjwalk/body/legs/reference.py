"""Reference gait tables: one gait cycle of sagittal hip, knee and foot-pitch angles (the "gait
DB" of the paper) from the literature (Winter 1991; Perry & Burnfield 2010), warped onto landmark
figures of real capture (:data:`BANDAI_LANDMARKS`).

Cycle fractions: 0 = heel strike of the leg, 1 = its next heel strike. Angles in radians
(the tables in degrees).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy.interpolate import CubicSpline

from mjwalk._jit import njit

#: Literature reference gait (:data:`DEFAULT_REFERENCE`): sagittal angles in degrees
#: every 5 % of the gait cycle, 0 % = heel strike. ``hip``: thigh flexion, ``knee``: knee
#: flexion, after D. A. Winter, "The Biomechanics and Motor Control of Human Gait: Normal,
#: Elderly and Pathological", 2nd ed. (1991), natural cadence ensemble averages (read off the
#: figures, rounded to the degree): knee ~3 deg at heel strike, ~18 deg loading response,
#: ~60-63 deg peak swing; hip +30 to -10 deg. ``pitch``: foot angle to the floor (+ toes up),
#: after the foot-floor angles in J. Perry & J. M. Burnfield, "Gait Analysis: Normal and
#: Pathological Function", 2nd ed. (2010): ~20 deg at heel strike, foot flat ~8-40 %, toe-off
#: at ~60 % with ~35-40 deg, rounded.
WINTER_GAIT: dict[str, Any] = {
    "cycle": np.arange(0, 101, 5) / 100.0,
    "hip": [30, 29, 27, 24, 20, 15, 10, 5, 0, -4, -8, -9, -5, 3, 12, 20, 26, 30, 32, 31, 30],
    "knee": [3, 10, 16, 19, 18, 15, 11, 7, 5, 6, 10, 20, 35, 50, 60, 63, 57, 42, 25, 10, 3],
    "pitch": [20, 8, 0, 0, 0, 0, 0, 0, 0, -3, -10, -22, -38, -50, -45, -30, -15, -3, 8, 17, 20],
}


@dataclass(frozen=True)
class ReferenceGait:
    """One gait cycle of sagittal reference angles (the "gait DB" of the paper).

    Attributes:
        cycle: (M,) increasing cycle fractions from 0 (heel strike) to 1 (next heel strike).
        hip: (M,) thigh flexion from the vertical in the walking plane, radians (+ knee ahead).
        knee: (M,) knee flexion, radians.
        pitch: (M,) foot angle to the floor, radians, + toes up.
        source: where the numbers come from.
    """

    cycle: np.ndarray
    hip: np.ndarray
    knee: np.ndarray
    pitch: np.ndarray
    source: str = ""
    _splines: dict[str, CubicSpline] = field(init=False, repr=False, compare=False)
    _unit: bool = field(init=False, repr=False, compare=False)
    _ppoly: dict[str, tuple[np.ndarray, np.ndarray]] = field(init=False, repr=False, compare=False)
    #: values at single cycle fractions, kept (the synthesis asks for the same few, such as
    #: the knee at heel strike, hundreds of times per cycle)
    _memo: dict[tuple[str, float, bool], Any] = field(init=False, repr=False, compare=False)
    #: what the synthesis derives from the table for one leg geometry (a walker's stature),
    #: kept by geometry (:func:`~mjwalk.body.legs.synthesis.legs_from_walk`)
    per_geom: dict[Any, Any] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        sp = {}
        for k in ("hip", "knee", "pitch"):
            v = np.asarray(getattr(self, k), float).copy()
            v[-1] = v[0]  # periodic
            sp[k] = CubicSpline(np.asarray(self.cycle, float), v, bc_type="periodic")
        object.__setattr__(self, "_splines", sp)
        cyc = np.asarray(self.cycle, float)
        object.__setattr__(self, "_unit", bool(cyc[0] == 0.0 and cyc[-1] == 1.0))
        ppoly = {k: (np.ascontiguousarray(v.c), np.ascontiguousarray(v.x)) for k, v in sp.items()}
        object.__setattr__(self, "_ppoly", ppoly)
        object.__setattr__(self, "_memo", {})
        object.__setattr__(self, "per_geom", {})

    def __call__(self, name: str, cycle, derivative: bool = False) -> np.ndarray:
        """Angle ``name`` ("hip", "knee", "pitch") in radians at cycle fraction(s) (wrapped);
        ``derivative=True`` gives radians per unit cycle."""
        # (a Python float by Python's %: NumPy's floor-mod arithmetic, fmod then shifted into
        # [0, 1), without a ufunc call per value)
        c = cycle % 1.0 if type(cycle) is float else np.mod(cycle, 1.0)
        sp = self._splines[name]
        if not self._unit:  # a table not on [0, 1]: scipy wraps onto it
            return sp(c, 1) if derivative else sp(c)
        coef, knots = self._ppoly[name]
        if isinstance(c, np.ndarray):
            out = _ppoly_eval(coef, knots, c.ravel().astype(float), 1 if derivative else 0)
            return out.reshape(c.shape)
        key = (name, float(c), bool(derivative))
        val = self._memo.get(key)
        if val is None:
            val = _ppoly_eval(coef, knots, np.array([float(c)]), 1 if derivative else 0)[0]
            if len(self._memo) < 4096:
                self._memo[key] = val
        return val


@njit
def _ppoly_eval(coef, knots, xs, nu):
    """A cubic spline's value (``nu`` = 0) or first derivative (1) at ``xs`` in [0, 1] from its
    piecewise-polynomial coefficients ``coef`` (4, m-1) on ``knots`` (m,): scipy's
    ``PPoly.__call__`` without its per-call overhead (the leg synthesis evaluates the
    reference thousands of times per walk); :func:`ppoly_at` per value."""
    out = np.empty(len(xs))
    for j in range(len(xs)):
        out[j] = ppoly_at(coef, knots, xs[j], nu)
    return out


@njit
def ppoly_at(coef, knots, x, nu):
    """One value of :func:`_ppoly_eval` (for compiled callers): scipy's ``PPoly`` arithmetic
    (interval with knots[i] <= x < knots[i+1], the last one closed; the power sum with its
    running power and derivative prefactors).

    Args:
        coef: (4, m - 1) cubic coefficients per interval, highest power first.
        knots: (m,) increasing breakpoints.
        x: the query point.
        nu: the derivative order (0 = the value).

    Returns:
        the polynomial's ``nu``-th derivative at ``x``.
    """
    m = len(knots)
    i = np.searchsorted(knots, x, side="right") - 1
    i = min(max(i, 0), m - 2)
    sx = x - knots[i]
    res = 0.0
    z = 1.0
    for kp in range(4):
        if kp < nu:
            continue
        pref = 1.0
        for k in range(kp, kp - nu, -1):
            pref *= k
        res = res + coef[3 - kp, i] * z * pref
        if kp < 3:
            z *= sx
    return res


@njit
def wrap01(c):
    """``np.mod(c, 1.0)`` of one float (the cycle fraction :meth:`ReferenceGait.__call__`
    evaluates): NumPy's floor-mod arithmetic (fmod, then shifted into [0, 1)).

    Args:
        c: a cycle fraction (any real).

    Returns:
        c mod 1, in [0, 1).
    """
    r = np.fmod(c, 1.0)
    if r != 0.0:
        if r < 0.0:
            r += 1.0
    else:
        r = 0.0
    return r


def winter_reference() -> ReferenceGait:
    """The reference gait of the table :data:`WINTER_GAIT` (literature values).

    Returns:
        a :class:`ReferenceGait` (hip, knee and foot pitch over the cycle, radians).
    """
    g = WINTER_GAIT
    return ReferenceGait(
        cycle=g["cycle"],
        hip=np.deg2rad(g["hip"]),
        knee=np.deg2rad(g["knee"]),
        pitch=np.deg2rad(g["pitch"]),
        source="Winter 1991 (hip, knee); Perry & Burnfield 2010 (foot-floor angle)",
    )


#: Landmarks of a straight-walk gait cycle calibrated on real capture, for :func:`warp_reference`:
#: per angle, pairs ((cycle %, deg) on :data:`WINTER_GAIT`, (cycle %, deg) in the calibrated gait)
#: at the gait events and extrema (heel strike, loading-response peak, mid-stance, push-off
#: minimum, toe-off, swing peak, late swing). Target figures: bandai-walk (Kobayashi et al.
#: 2023, CC BY-NC 4.0), ``dataset-2_walk_normal_001..003``, left leg, mean of 13 gait cycles
#: by :func:`gait_cycles` (heel strike = toes-up pitch peak), read off and rounded to the
#: percent and degree. This actor walks with more knee flexion in stance than Winter's
#: ensemble (34 vs 19 deg at the loading-response peak, 17 vs 5 deg at mid-stance).
BANDAI_LANDMARKS = {
    "hip": [
        ((0, 30), (0, 22)),
        ((5, 29), (11, 29)),
        ((30, 10), (30, 11)),
        ((55, -9), (57, -10)),
        ((90, 32), (85, 27)),
        ((100, 30), (100, 22)),
    ],
    "knee": [
        ((0, 3), (0, 1)),
        ((15, 19), (18, 34)),
        ((40, 5), (44, 17)),
        ((60, 35), (60, 35)),
        ((75, 63), (75, 70)),
        ((90, 25), (90, 29)),
        ((100, 3), (100, 1)),
    ],
    "pitch": [
        ((0, 20), (0, 28)),
        ((10, 0), (12, 0)),
        ((40, 0), (40, 0)),
        ((65, -50), (69, -69)),
        ((80, -15), (80, -42)),
        ((100, 20), (100, 28)),
    ],
}


def warp_reference(
    landmarks: dict, base: ReferenceGait | None = None, source: str = "", n: int = 101
) -> ReferenceGait:
    """A reference gait generated from ``base`` (default :func:`winter_reference`) warped onto
    landmark figures, so a gait can be calibrated on a few numbers rather than copied.

    Args:
        landmarks: angle name ("hip", "knee", "pitch") -> increasing list of pairs
            ``((base cycle %, base deg), (cycle %, deg))``, the first at 0 % and the last at
            100 %. Time is warped piecewise linearly between the landmarks; between two
            landmarks the base curve is scaled affinely so its landmark values map onto the
            targets (the base's shape is kept on every segment).
        base: the gait whose shapes are warped.
        source: where the landmark figures come from.
        n: samples per cycle of the result.

    Returns:
        the warped :class:`ReferenceGait` (radians).
    """
    base = base or _WINTER
    x = np.linspace(0.0, 100.0, n)
    out = {}
    for name in ("hip", "knee", "pitch"):
        lm = np.asarray(landmarks[name], float)  # (K, 2, 2)
        src, dst = lm[:, 0], lm[:, 1]
        if not (np.all(np.diff(dst[:, 0]) > 0) and np.all(np.diff(src[:, 0]) > 0)):
            raise ValueError(f"warp_reference: {name} landmarks must increase in cycle")
        v = np.degrees(base(name, np.interp(x, dst[:, 0], src[:, 0]) / 100.0))
        k = np.clip(np.searchsorted(dst[:, 0], x, side="right") - 1, 0, len(dst) - 2)
        a0, a1, b0, b1 = src[k, 1], src[k + 1, 1], dst[k, 1], dst[k + 1, 1]
        same = np.isclose(a1, a0)
        lin = (x - dst[k, 0]) / (dst[k + 1, 0] - dst[k, 0])
        scaled = b0 + (v - a0) * (b1 - b0) / np.where(same, 1.0, a1 - a0)
        out[name] = np.radians(np.where(same, b0 + (v - a0) + (b1 - b0) * lin, scaled))
    return ReferenceGait(
        cycle=x / 100.0,
        hip=out["hip"],
        knee=out["knee"],
        pitch=out["pitch"],
        source=f"{base.source} warped onto {source or 'landmarks'}",
    )


def bandai_reference() -> ReferenceGait:
    """The Winter reference warped onto :data:`BANDAI_LANDMARKS` (a generated gait calibrated
    on the figures of the bandai-walk "normal" actor; no capture samples are used).

    Returns:
        the warped :class:`ReferenceGait` (the package default, :data:`DEFAULT_REFERENCE`).
    """
    return warp_reference(
        BANDAI_LANDMARKS, source="bandai-walk normal 001-003 landmarks (BANDAI_LANDMARKS)"
    )


def heel_strike_ankle(ref: ReferenceGait) -> float:
    """The reference's own ankle flexion at heel strike (radians, + dorsiflexion): its foot
    pitch plus knee flexion minus thigh flexion at cycle 0 (the foot's angle to the shank),
    with the pitch as the landing takes it (toes up only, ``hs_pitch``). The default
    reference's is +7.0 deg (the bandai actor's 28 deg pitch and 22 deg thigh at heel
    strike, :data:`BANDAI_LANDMARKS`). A first step from standing landed at 16 deg, bounded
    by the ankle's range alone (synthetic first steps at 1.55-1.95 m, 15.3 median in the
    station's, b3507ca, ``benchmarks/bench_swing_ankle.py``), where the ankle is neutral at
    initial contact (Perry & Burnfield, "Gait Analysis", 2nd ed., 2010, quoted from memory;
    slideplayer.com/5345284 "Biomechanics foot ankle": "Initial Contact Ankle jt. is in
    neutral"); ``steps.landing_pitches`` bounds a first step's landing by this angle.

    Args:
        ref: the reference gait.

    Returns:
        the ankle angle, radians.
    """
    return max(0.0, float(ref("pitch", 0.0))) + float(ref("knee", 0.0)) - float(ref("hip", 0.0))


def reference_angle(joint: str, cycle, derivative: bool = False):
    """Default-reference angle of ``joint`` at cycle(s).

    Args:
        joint: "hip", "knee" or "pitch".
        cycle: gait-cycle fraction(s), 0 = heel strike (scalar or array; wrapped into [0, 1)).
        derivative: the derivative per unit cycle instead of the angle.

    Returns:
        the angle(s) in radians (or radians per cycle), the shape of ``cycle``.
    """
    return DEFAULT_REFERENCE(joint, cycle, derivative)


_WINTER = winter_reference()

#: The reference gait :func:`legs_from_walk` uses by default: the generated
#: :func:`bandai_reference` (the Winter table warped onto the landmark figures
#: :data:`BANDAI_LANDMARKS`; no capture samples). Its maximum difference to held-out
#: bandai-walk clips is hip 4.8 / knee 6.9 deg, the plain Winter table's 12.4 / 16.1 deg
#: (tests/body/test_analysis.py::test_knee_hip_curves_vs_bandai_capture).
DEFAULT_REFERENCE = bandai_reference()
