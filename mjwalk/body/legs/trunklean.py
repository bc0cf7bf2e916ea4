"""The trunk leaned forward in stair ascent (issue 47): how far, over which samples, and how
the spine's two flexion joints share it.

People climbing a stair lean the trunk forward: healthy adults ascending a 17 cm stair hold it
13.7 deg forward of the vertical on average, against 1.3 deg in level walking (the table cited
at :data:`STAIR_ASCENT_TRUNK_LEAN`). That table gives the trunk's (thorax's) tilt to the
vertical, not the pelvis's, so the lean is built in the spine: the pelvis keeps its posterior
tilt (:mod:`mjwalk.body.legs.pelvistilt`), the hips their flexion to it, and the lumbar and
thoracic joints flex by the lean (:func:`lean_spine`, applied by
:func:`mjwalk.timeline.frames.frames_from_legs` after the lumbar joint has taken the pelvic
tilt back). :func:`ascent_lean` gives a walk's lean per sample, held over each run of
ascending steps and eased in and out at its ends as the pelvic tilt is
(:func:`~mjwalk.body.legs.pelvistilt.ascent_share`). No descent lean: no citable figure of a
forward trunk lean in stair descent was found (a 10 cm step down is met with the trunk rotated
backward: Aminiaghdam et al., PLOS ONE 12(12) 2017, e0190135, abstract), and none per operator
group (older or fatigued adults).

World frame: radians; lean + = the trunk's top forward (about the pelvis's +y axis).
"""

from __future__ import annotations

import math

import numpy as np

from mjwalk.anthropometry import ROM_DEG
from mjwalk.body.legs.pelvistilt import ascent_share

#: Forward trunk lean held over a stair ascent beyond the level walk's, radians. The table of
#: Int J Phys Med Rehabil 2:231 (2014), Table 3 (https://www.omicsonline.org/JPMRimages/
#: 2329-9096-2-231-t003.html; the table verified here, the article's title and authors not):
#: healthy controls (n = 20) walking level at 1.06 m/s hold a mean anterior trunk tilt of 1.3
#: deg (SD 3.8; maximum 2.1, range over stance 2.4) and ascending a 17 cm stair at 0.46 m/s
#: 13.7 deg (SD 6.6; maximum 16.5, range over stance 4.6). The stair's mean less the level
#: walk's, 12.4 deg, is added to the model's level-walk trunk: the riser (17 cm) is this
#: model's stairs' (scenes/multilevel_station.xml, benchmarks/bench_levels.py). ASSUMPTION:
#: held at that mean through the flight (the table's 4.6 deg range over stance is the
#: oscillation about it; where in the step it peaks is not given), not scaled with the riser
#: (one riser height measured).
STAIR_ASCENT_TRUNK_LEAN = math.radians(13.7 - 1.3)
#: The lumbar joint's share of the lean, the thoracic joint taking the rest. ASSUMPTION: the
#: two joints flex in proportion to their flexion ranges (Kapandji: lumbar 60, thoracic 45
#: deg; :data:`mjwalk.anthropometry.ROM_DEG`), as the cycle's forward bends share a bend
#: (:func:`mjwalk.cycle.crouch.bend_trunk`); the cited table measures the thorax to the
#: vertical, not the split.
LUMBAR_LEAN_SHARE = ROM_DEG["lumbar_flex"][1] / (
    ROM_DEG["lumbar_flex"][1] + ROM_DEG["thoracic_flex"][1]
)


def ascent_lean(walk, n: int, lean: float = STAIR_ASCENT_TRUNK_LEAN) -> np.ndarray:
    """The trunk's forward lean at every sample of a walk: ``lean`` held over each run of
    ascending steps, eased in over its first step and out over the step off it
    (:func:`~mjwalk.body.legs.pelvistilt.ascent_share`), zero elsewhere.

    Args:
        walk: a :class:`~mjwalk.plan.walkpath.WalkPath` (its steps' ``foot_z``/``stance_z``).
        n: the number of samples.
        lean: the held lean, radians (+ forward).

    Returns:
        (n,) lean, radians (+ forward).
    """
    return lean * ascent_share(walk, n)


def lean_spine(
    lumbar: np.ndarray, thoracic: np.ndarray, lean: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """The lumbar and thoracic flexion with the trunk leaned forward by ``lean``: the two
    flexions add :data:`LUMBAR_LEAN_SHARE` and the rest of it, so the thorax turns forward by
    ``lean`` about the pelvis's y axis (the joints' ranges are applied by the caller).

    Args:
        lumbar: (n,) lumbar flexion, radians.
        thoracic: (n,) thoracic flexion, radians.
        lean: (n,) the lean, radians (+ forward).

    Returns:
        ``(lumbar, thoracic)``: (n,) each, radians.
    """
    lean = np.asarray(lean, float)
    return lumbar + LUMBAR_LEAN_SHARE * lean, thoracic + (1.0 - LUMBAR_LEAN_SHARE) * lean
