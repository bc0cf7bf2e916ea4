"""Zones, excursions and verdicts of a continuous posture angle over time: EN 1005-4:2005+A1:2008
(Safety of machinery -- Evaluation of working postures and movements in relation to machinery)
for upper-arm elevation and trunk flexion, and ISO 11226:2000's holding-time step for the same
angles (:mod:`mjwalk.ergonomics.iso11226` holds its curves).

Both standards split the angle into three zones at 20 and 60 deg (:data:`ZONES`). EN 1005-4
judges a zone by whether the posture in it is static (held at least :data:`STATIC_S`) and, for
movements, by their frequency (excursions a minute into the zone, below or from
:data:`HIGH_FREQ_PER_MIN`); without a support for the arm or the trunk (the humanoid has none):

=============  ==============  =============================  =============================
zone           static          movement < freq limit          movement >= freq limit
=============  ==============  =============================  =============================
0-20 deg       acceptable      acceptable                     acceptable
20-60 deg      conditionally   acceptable                     conditionally acceptable
> 60 deg       not acceptable  conditionally acceptable       not acceptable
=============  ==============  =============================  =============================

Provenance: no primary text of EN 1005-4 or ISO 11226 is reachable here (searched 2026-12-02:
only catalogue pages). The zone limits 20 and 60 deg and the three verdicts are those Delleman &
Dul (2007, "International standards on working postures and movements ISO 11226 and EN 1005-4",
Ergonomics 50(11):1809-1819) describe for both standards; the table above is transcribed from a
vendor's secondary transcription of EN 1005-4 (Dassault Systemes DELMIA "Fault Monitor" help
page, help-3dexperience: upper arm 0-20 acceptable, 20-60 acceptable below 2/min and
conditionally acceptable from 2/min, > 60 not acceptable; trunk side bend and twist beyond
10 deg conditionally acceptable below 2/min, not acceptable from 2/min). That page gives 2/min
for the upper arm too; a limit of 10/min for the upper arm's 20-60 deg zone is widely quoted
from the standard but could NOT be verified here, so mjwalk uses the transcribed 2/min for
both body parts (the stricter reading). "Conditionally acceptable" for a static posture in
20-60 deg means: acceptable only as long as ISO 11226's maximum holding time
(:func:`iso11226_verdict`).

What the frequency counts (checked 2026-12-04): movements into the zone, not all movements of
the arm: for > 60 deg the excursions beyond 60 deg, for 20-60 deg those beyond 20 deg (a raise
above 60 deg passes through it), per minute of the cycle, a dip back across the limit by less
than :data:`HYSTERESIS_DEG` not ending the excursion. The 10/min was searched for again (web
pages, documentation and code stores: DELMIA's page still gives 2/min; a copy of DIN EN
1005-4:2009 shows only its front matter) and is still not verified, so 2/min stays. It would
not tell short from tall on the shipped scenes/shelving_station.toml either (40 runs, seed 0):
the right arm goes above 60 deg exactly 3 times in every cycle (twice into the low
compartment, once onto the top shelf), 8.2-17.8 times a minute (median 12.1); the rate follows
the cycle time (r = -0.97), hardly stature (r = +0.24: the taller walk a little faster). At
2/min every cycle is not acceptable; at 10/min only the 4 slowest (under 10 a minute) would be
acceptable.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mjwalk.ergonomics import iso11226

#: The zones' limits, degrees (EN 1005-4 and ISO 11226 alike: 20 and 60 deg; Delleman & Dul 2007).
ZONES = ((0.0, 20.0), (20.0, 60.0), (60.0, 180.0))
#: Zone names, in the order of :data:`ZONES`.
ZONE_NAMES = ("0-20", "20-60", ">60")
#: A posture held at least this long (s) is static (ISO 11226 scope: 4 s; EN 1005-4 uses the
#: same 4 s per Delleman & Dul 2007).
STATIC_S = iso11226.STATIC_S
#: Excursions per minute from which movements into a zone are "high frequency" (EN 1005-4 as
#: transcribed by DELMIA's help page: 2/min; see the module docstring for the unverified 10/min).
HIGH_FREQ_PER_MIN = 2.0
#: How far (deg) an angle must fall below a zone's lower limit for the excursion into the zone
#: to end, so that a dip across the limit and back (a hand settling on a grasp, the humanoid's
#: frame-to-frame jitter) is not counted as a second movement into the zone. ASSUMED: neither
#: standard's reachable transcription says how movements are counted, and no published
#: hysteresis for counting zone entries was found (searched 2026-12-04); 5 deg is half the
#: finest band the standards use (EN 1005-4's 10 deg for trunk side bend and twist), so no
#: move from one zone to another is merged. Measured, 8 cycles of scenes/shelving_station.toml:
#: the excursions above 60 deg are the same with 0, 5 and 10 deg (no double counts there);
#: above 20 deg the left arm's 4 become 2 in 4 of the 8 cycles (dips of 1-3 frames to
#: 17-20 deg around the place at the 1.06 m part; dips to 13-14 deg still count).
HYSTERESIS_DEG = 5.0
#: The verdicts, from best to worst.
VERDICTS = ("acceptable", "conditionally acceptable", "not acceptable")


def worst(*verdicts: str) -> str:
    """The worst of some verdicts.

    Args:
        verdicts: names from :data:`VERDICTS` (none: "acceptable").

    Returns:
        The worst of them.
    """
    return VERDICTS[max((VERDICTS.index(v) for v in verdicts), default=0)]


def runs_above(
    angle: np.ndarray, limit: float, hysteresis: float = HYSTERESIS_DEG
) -> list[tuple[int, int]]:
    """The excursions of an angle above a limit: [start, end) frame runs where it exceeds it,
    two runs counting as one excursion (from the first's start to the second's end) when the
    angle between them stays above ``limit - hysteresis`` (a dip, not a return: a Schmitt
    trigger, :data:`HYSTERESIS_DEG`).

    Args:
        angle: (F,) degrees.
        limit: degrees.
        hysteresis: degrees (0: every crossing counts).

    Returns:
        The runs, in order.
    """
    a = np.asarray(angle)
    m = np.concatenate([[0], (a > limit).astype(np.int8), [0]])
    d = np.diff(m)
    starts, ends = np.flatnonzero(d == 1), np.flatnonzero(d == -1)
    if len(starts) > 1 and hysteresis > 0:
        # a run joins the one before when the dip between them (the frames from the earlier
        # run's end to its own start: never empty) stays above limit - hysteresis; joining
        # keeps the earlier run's end as the dip's start, so each dip is that of two raw runs
        # in a row, and all of them are found at once (minima: the same numbers)
        gaps = np.minimum.reduceat(a, np.column_stack([ends[:-1], starts[1:]]).ravel())[::2]
        first = np.concatenate([[True], ~(gaps > limit - hysteresis)])
        last = np.concatenate([first[1:], [True]])
        starts, ends = starts[first], ends[last]
    return list(zip(starts.tolist(), ends.tolist(), strict=True))


@dataclass
class Zone:
    """An angle's exposure in one zone over some frames.

    Attributes:
        name: the zone (:data:`ZONE_NAMES`).
        time: seconds in the zone.
        share: that time's share of the frames' time (0-1).
        excursions: runs at or beyond the zone's lower limit (entries into it or above).
        per_min: excursions per minute of the frames' time.
        static: excursions held at least :data:`STATIC_S`.
        verdict: EN 1005-4's verdict of the zone (:data:`VERDICTS`).
    """

    name: str
    time: float
    share: float
    excursions: int
    per_min: float
    static: int
    verdict: str


def zone_verdict(zone: int, static: int, per_min: float, excursions: int) -> str:
    """EN 1005-4's verdict of one zone (the table of the module docstring, no support).

    Args:
        zone: 0, 1 or 2 (0-20, 20-60, > 60 deg).
        static: static excursions into the zone or above.
        per_min: excursions a minute.
        excursions: how many.

    Returns:
        A verdict of :data:`VERDICTS`.
    """
    if zone == 0 or excursions == 0:
        return VERDICTS[0]
    high = per_min >= HIGH_FREQ_PER_MIN
    if zone == 1:
        return VERDICTS[1] if static or high else VERDICTS[0]
    return VERDICTS[2] if static or high else VERDICTS[1]


def zones(angle: np.ndarray, fps: float) -> list[Zone]:
    """An angle's time, excursions and EN 1005-4 verdict in each of :data:`ZONES`.

    Args:
        angle: (F,) degrees (upper-arm elevation or trunk flexion).
        fps: frames per second.

    Returns:
        One :class:`Zone` per zone, in order.
    """
    a = np.asarray(angle, dtype=float)
    total = max(len(a) / fps, 1e-9)
    out = []
    for k, (lo, hi) in enumerate(ZONES):
        inside = (a > lo) & (a <= hi) if k else a <= hi
        runs = runs_above(a, lo) if k else []
        n_static = sum((e - s) / fps >= STATIC_S for s, e in runs)
        per_min = 60.0 * len(runs) / total
        time = float(inside.sum()) / fps
        verdict = zone_verdict(k, n_static, per_min, len(runs))
        out.append(Zone(ZONE_NAMES[k], time, time / total, len(runs), per_min, n_static, verdict))
    return out


def iso11226_verdict(angle: np.ndarray, fps: float, curve) -> tuple[str, float]:
    """ISO 11226's verdict of an angle over time, in three steps as EN 1005-4 words them:
    acceptable without a static holding beyond 20 deg; conditionally acceptable when every
    static holding in 20-60 deg lasts no longer than its maximum acceptable holding time
    (step 2, at the holding's peak angle); not acceptable when one lasts longer, or a static
    holding goes beyond 60 deg.

    Args:
        angle: (F,) degrees.
        fps: frames per second.
        curve: the holding-time curve (:data:`mjwalk.ergonomics.iso11226.TRUNK_HOLD` or
            :data:`~mjwalk.ergonomics.iso11226.ARM_HOLD`).

    Returns:
        (verdict, the worst ratio of held to acceptable time; 0 without a static holding).
    """
    a = np.asarray(angle, dtype=float)
    verdict, ratio = VERDICTS[0], 0.0
    for s, e in runs_above(a, iso11226.ACCEPTABLE_DEG):
        held = (e - s) / fps
        if held < STATIC_S:
            continue
        limit = iso11226.max_holding_time(float(a[s:e].max()), curve)
        r = held / limit if limit > 0 else float("inf")
        ratio = max(ratio, r)
        verdict = worst(verdict, VERDICTS[2] if r > 1.0 else VERDICTS[1])
    return verdict, ratio


__all__ = [
    "HIGH_FREQ_PER_MIN",
    "HYSTERESIS_DEG",
    "STATIC_S",
    "VERDICTS",
    "ZONES",
    "ZONE_NAMES",
    "Zone",
    "iso11226_verdict",
    "runs_above",
    "worst",
    "zone_verdict",
    "zones",
]
