"""Score one cycle's timeline task by task: what a run keeps of its ergonomics (no timeline).

:func:`assess_cycle` takes the humanoid's poses (a Timeline), the cycle's tasks as frame spans
(:class:`TaskSpan`: hand, the part's mass and coupling, the site's position, and what the task
kind does: a reach, taking or putting down a part, a lift) and the cycle
time, and returns a :class:`RunErgonomics`: per task the peak RULA, REBA and OWAS scores and the
body part that drives each peak; per lift of a part with a mass the revised NIOSH equation's
H, V, D, A, F, C, RWL and LI; ISO 11226's static holdings of the trunk and the upper arms; and
the frame-by-frame RULA and REBA scores (small ints) for plots.

Force and activity terms from the task: the load in a hand is the mass of the part it holds
(from its pick to its place or fasten, both included); muscle use (RULA) and activity (REBA)
count a hand repeating reaches 4 times a minute or more over the cycle, and a posture held
longer than a minute in one task (a long fasten) as static.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Literal

import numpy as np

from mjwalk.ergonomics import iso11226, niosh, owas, reba, rula
from mjwalk.ergonomics.angles import BodyAngles

#: Reaches per minute from which a hand's work counts as repeated (RULA muscle use; REBA
#: activity "repeated small range actions, more than 4 times a minute").
REPEATED_PER_MIN = 4.0
#: A task whose hold lasts longer than this (s) is a static posture (RULA, REBA: > 1 min).
STATIC_S = 60.0
#: Lifting duration category of a line's shift (Applications Manual 1.3.5.2: 2-8 h of work with
#: the usual breaks).
LIFT_DURATION = "long"
#: The RULA parts, each with its largest score (to name the part that drives a peak).
RULA_PARTS = {"upper_arm": 6, "lower_arm": 3, "wrist": 4, "neck": 6, "trunk": 6, "legs": 2}
REBA_PARTS = {"trunk": 5, "neck": 3, "legs": 4, "upper_arm": 6, "lower_arm": 2, "wrist": 3}


@dataclass
class TaskSpan:
    """One task of a cycle on its timeline: frames [start, end), the hand ("left", "right",
    "both"; None for walks), the mass (kg) and coupling of the part it handles, and for a
    reach the site's world position (m).

    What the task's kind does comes with it (the cycle's task kinds table,
    :data:`mjwalk.cycle.types.TASK_KINDS`, says it; ``kind`` is only its name for the report):
    ``reach`` a hand to the site and back; ``part`` "take" (the hand holds the part from this
    task on) or "put" (it puts down the part it took first), else None; ``lifts`` the reach
    lifts the part from the site or lowers it onto it (a NIOSH lift).
    """

    index: int
    kind: str
    start: int
    end: int
    hand: str | None = None
    site: str | None = None
    mass: float = 0.0
    coupling: str = "poor"
    site_pos: np.ndarray | None = None
    reach: bool = False
    part: Literal["take", "put"] | None = None
    lifts: bool = False


@dataclass
class TaskErgonomics:
    """The peaks of one task: RULA 1-7, REBA 1-15, OWAS action category 1-4, the time of the
    RULA peak (s from the cycle's start), the body parts that drive the RULA and REBA peaks,
    the RULA peak's arm ("left"/"right") and the task's highest RULA upper-arm score;
    ``reach``: the task is a reach (:attr:`TaskSpan.reach`; left out of
    :meth:`RunErgonomics.summary`)."""

    index: int
    kind: str
    site: str | None
    rula: int
    reba: int
    owas: int
    rula_time: float
    rula_driver: str
    reba_driver: str
    side: str
    upper_arm: int
    reach: bool = False


@dataclass
class RunErgonomics:
    """The ergonomics of one simulated cycle (kept by every run; no timeline).

    Attributes:
        tasks: per task peaks (:class:`TaskErgonomics`).
        lifts: the NIOSH lifts (:class:`~mjwalk.ergonomics.niosh.Lift`) of parts with a mass.
        holdings: ISO 11226's worst static holding of the trunk and of each upper arm.
        rula, reba: (F,) per-frame scores (int8) at ``fps``.
    """

    tasks: list[TaskErgonomics]
    lifts: list[niosh.Lift]
    holdings: list[iso11226.Holding]
    fps: float
    rula: np.ndarray = field(repr=False)
    reba: np.ndarray = field(repr=False)

    @property
    def rula_peak(self) -> int:
        return int(self.rula.max(initial=1))

    @property
    def reba_peak(self) -> int:
        return int(self.reba.max(initial=1))

    @property
    def owas_peak(self) -> int:
        return max((t.owas for t in self.tasks), default=1)

    @property
    def max_li(self) -> float | None:
        """The highest lifting index of the lifts that have one (0.0 without lifts; None when
        no lift has one: see :attr:`~mjwalk.ergonomics.niosh.Lift.reason`)."""
        lis = [lf.li for lf in self.lifts if lf.li is not None]
        return max(lis) if lis else (None if self.lifts else 0.0)

    @property
    def lifts_without_li(self) -> list[niosh.Lift]:
        """The lifts the NIOSH equation gives no index (RWL 0; each says why)."""
        return [lf for lf in self.lifts if lf.li is None]

    def summary(self) -> dict:
        """Plain data (JSON-ready) without the per-frame scores."""
        return {
            "rula_peak": self.rula_peak,
            "rula_action_level": int(rula.action_level(self.rula_peak)),
            "reba_peak": self.reba_peak,
            "reba_risk_level": int(reba.risk_level(self.reba_peak)),
            "owas_peak": self.owas_peak,
            "max_lifting_index": self.max_li,
            "tasks": [{k: v for k, v in vars(t).items() if k != "reach"} for t in self.tasks],
            "lifts": [vars(lf) for lf in self.lifts],
            "iso11226": [vars(h) for h in self.holdings],
        }


def _loads(spans: list[TaskSpan], n: int) -> np.ndarray:
    """(F, 2) the mass (kg) in each hand, frame by frame."""
    load = np.zeros((n, 2))
    held = [0.0, 0.0]
    for sp in spans:
        sides = [0, 1] if sp.hand == "both" else [0] if sp.hand == "left" else [1]
        if sp.part == "take" and sp.hand:
            for s in sides:
                held[s] += sp.mass / len(sides)
        for s in (0, 1):
            load[sp.start : sp.end, s] = held[s]
        if sp.part == "put" and sp.hand:
            for s in sides:
                held[s] = max(held[s] - sp.mass / len(sides), 0.0)
    return load


def _driver(parts, maxima: dict[str, int], k: int, side: int | None = None) -> str:
    best, name = -1.0, ""
    for p, m in maxima.items():
        v = getattr(parts[side] if side is not None else parts, p)[k] / m
        if v > best:
            best, name = v, p
    return name


def _rula_frames(ang: BodyAngles, load: np.ndarray, muscle: np.ndarray):
    """(F, 2) per-arm RULA grand scores, and the part scores of each arm."""
    out = np.zeros((ang.n_frames, 2), dtype=int)
    parts = []
    for s in (0, 1):
        p = rula.part_scores(ang, s)
        parts.append(p)
        force = rula.force_score(load[:, s], muscle[:, s] > 0)
        out[:, s] = rula.parts_score(p, muscle[:, s], force)
    return out, parts


def _reba_frames(ang: BodyAngles, load: np.ndarray, coupling: np.ndarray, activity: np.ndarray):
    out = np.zeros((ang.n_frames, 2), dtype=int)
    parts = []
    for s in (0, 1):
        p = reba.part_scores(ang, s)
        parts.append(p)
        load_s = reba.load_score(load[:, s])
        out[:, s] = reba.parts_score(p, load_s, coupling[:, s], activity[:, s])
    return out, parts


def assess_cycle(
    ang: BodyAngles, spans: list[TaskSpan], cycle_time: float, fps: float
) -> RunErgonomics:
    """Score a cycle: ``ang`` the body angles of all its frames, ``spans`` its tasks (in order,
    covering the frames), ``cycle_time`` seconds, ``fps`` the timeline's frame rate."""
    n = ang.n_frames
    load = _loads(spans, n)
    minutes = max(cycle_time, 1e-9) / 60.0
    reps = [
        sum(1 for s in spans if s.reach and s.hand in (side, "both")) for side in ("left", "right")
    ]
    repeated = np.array([r / minutes >= REPEATED_PER_MIN for r in reps])
    muscle = np.zeros((n, 2), dtype=int)
    muscle[:] = repeated
    coupling = np.zeros((n, 2), dtype=int)
    for sp in spans:
        if (sp.end - sp.start) / fps > STATIC_S and sp.reach:
            muscle[sp.start : sp.end] = 1
        if sp.mass > 0 and sp.hand:
            sides = [0, 1] if sp.hand == "both" else [0] if sp.hand == "left" else [1]
            for s in sides:
                coupling[sp.start : sp.end, s] = reba.COUPLING.get(sp.coupling, 2)
    r_arm, r_parts = _rula_frames(ang, load, muscle)
    b_arm, b_parts = _reba_frames(ang, load, coupling, muscle)
    ocodes = owas.codes(ang)
    ocodes[:, 3] = [owas.load_code(x) for x in load.sum(axis=1)]
    o = owas.action_category(*ocodes.T)
    r_frame = r_arm.max(axis=1)
    b_frame = b_arm.max(axis=1)
    tasks = []
    for sp in spans:
        if sp.end <= sp.start:
            continue
        sl = slice(sp.start, sp.end)
        k = sp.start + int(np.argmax(r_frame[sl]))
        side = int(np.argmax(r_arm[k]))
        kb = sp.start + int(np.argmax(b_frame[sl]))
        sb = int(np.argmax(b_arm[kb]))
        tasks.append(
            TaskErgonomics(
                index=sp.index,
                kind=sp.kind,
                site=sp.site,
                rula=int(r_frame[k]),
                reba=int(b_frame[kb]),
                owas=int(o[sl].max()),
                rula_time=k / fps,
                rula_driver=_driver(r_parts, RULA_PARTS, k, side),
                reba_driver=_driver(b_parts, REBA_PARTS, kb, sb),
                side=("left", "right")[side],
                upper_arm=int(max(r_parts[0].upper_arm[sl].max(), r_parts[1].upper_arm[sl].max())),
                reach=sp.reach,
            )
        )
    lifts = _lifts(ang, spans, cycle_time)
    holdings = [iso11226.holding(ang.trunk_inclination, fps, "trunk", iso11226.TRUNK_HOLD)]
    for s, tag in enumerate(("left", "right")):
        holdings.append(
            iso11226.holding(
                ang.upper_arm_elevation[:, s], fps, f"upper_arm_{tag}", iso11226.ARM_HOLD
            )
        )
    return RunErgonomics(
        tasks, lifts, holdings, fps, r_frame.astype(np.int8), b_frame.astype(np.int8)
    )


def _lift_geometry(ang: BodyAngles, k: int, hand: str) -> tuple[float, float, float]:
    """(H cm, V cm, A deg) of the grip at frame ``k`` (NIOSH: from the ankles' mid-point)."""
    g = ang.hands[k].mean(axis=0) if hand == "both" else ang.hands[k, 0 if hand == "left" else 1]
    rel = g[:2] - ang.ankles[k, :2]
    h = float(np.hypot(*rel)) * 100.0
    v = float(g[2]) * 100.0
    fwd = ang.forward[k, :2]
    cosang = np.dot(rel, fwd) / max(np.hypot(*rel) * np.hypot(*fwd), 1e-12)
    a = float(np.degrees(np.arccos(np.clip(cosang, -1.0, 1.0))))
    return h, max(v, 0.0), a


def _lifts(ang: BodyAngles, spans: list[TaskSpan], cycle_time: float) -> list[niosh.Lift]:
    lifting = [s for s in spans if s.lifts and s.mass > 0 and s.hand]
    if not lifting:
        return []
    f = len(lifting) / (max(cycle_time, 1e-9) / 60.0)
    out = []
    for sp in lifting:
        assert sp.hand is not None
        fr = np.arange(sp.start, sp.end)
        if sp.site_pos is not None:
            g = (
                ang.hands[fr].mean(axis=1)
                if sp.hand == "both"
                else ang.hands[fr, 0 if sp.hand == "left" else 1]
            )
            at = int(fr[np.argmin(np.linalg.norm(g - sp.site_pos, axis=1))])
        else:
            at = int(fr[len(fr) // 2])
        # taking the part lifts it from the site to where the return ends; putting it down
        # lowers it from where the task starts onto the site
        ends = (at, int(fr[-1])) if sp.part == "take" else (int(fr[0]), at)
        geo = [_lift_geometry(ang, k, sp.hand) for k in ends]
        out.append(
            niosh.lift(
                sp.index,
                sp.kind,
                sp.hand,
                sp.mass,
                (geo[0][0], geo[1][0]),
                (geo[0][1], geo[1][1]),
                (geo[0][2], geo[1][2]),
                f,
                sp.coupling,
                LIFT_DURATION,
                control_at_destination=sp.part == "put",
            )
        )
    return out
