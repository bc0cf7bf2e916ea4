"""The revised NIOSH lifting equation as a :class:`~mjwalk.ergonomics.score.Score`: which reaches
of a cycle lift a part, the lift's geometry from the body's frames, its index, and the
workforce's lifting figures (the lifts the equation gives no index reported apart).

A lift is a reach that lifts a part with a mass from its site or lowers it onto it
(:attr:`~mjwalk.ergonomics.score.TaskSpan.lifts`); its frequency is the cycle's lifts over its
cycle time (cycles back to back), its duration category :data:`LIFT_DURATION`.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Sequence
from typing import Any

import numpy as np

from mjwalk.ergonomics import niosh
from mjwalk.ergonomics.angles import BodyAngles
from mjwalk.ergonomics.results import RunErgonomics, TaskErgonomics
from mjwalk.ergonomics.score import (
    Column,
    Score,
    ScoreContext,
    TaskSpan,
    fmt,
    fmt_share,
    percentiles,
    share,
)

#: Lifting duration category of a line's shift (Applications Manual 1.3.5.2: 2-8 h of work with
#: the usual breaks).
LIFT_DURATION = "long"


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


def cycle_lifts(ang: BodyAngles, spans: Sequence[TaskSpan], cycle_time: float) -> list[niosh.Lift]:
    """The NIOSH lifts of a cycle's tasks.

    The grip is at the frame where the hand comes closest to the site (the task's middle frame
    without a site): taking a part lifts it from there to where the task ends; putting it down
    lowers it from where the task starts onto the site.

    Args:
        ang: the body angles of the cycle's frames.
        spans: its tasks.
        cycle_time: the cycle's duration, s (the lifting frequency is lifts / minutes).

    Returns:
        One :class:`~mjwalk.ergonomics.niosh.Lift` per lifting task with a mass and a hand.
    """
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
        ends = (at, int(fr[-1])) if sp.part == "take" else (int(fr[0]), at)
        geo = [_lift_geometry(ang, k, sp.hand) for k in ends]
        out.append(
            niosh.lift(
                sp.index,
                sp.kind,
                sp.hand,
                sp.mass,
                niosh.LiftEnds(
                    (geo[0][0], geo[1][0]), (geo[0][1], geo[1][1]), (geo[0][2], geo[1][2])
                ),
                niosh.LiftConditions(f, LIFT_DURATION, sp.coupling),
                control_at_destination=sp.part == "put",
            )
        )
    return out


def _task_lift(run: RunErgonomics, task: TaskErgonomics) -> niosh.Lift | None:
    """The lift of a task (the last one named after it), None without one."""
    # a search from the end, not a dict of the run's lifts per call: ergonomics.csv asks for
    # each row's lift five times, over 10 000 runs a million calls (issue 50)
    return next((lf for lf in reversed(run.lifts) if lf.task == task.index), None)


def _li_cell(run: RunErgonomics, task: TaskErgonomics) -> str:
    lf = _task_lift(run, task)
    return "" if lf is None or lf.li is None else f"{lf.li:.3f}"


def _note_cell(run: RunErgonomics, task: TaskErgonomics) -> str:
    lf = _task_lift(run, task)
    return "" if lf is None or lf.li is not None else f"no lifting index: {lf.reason}"


def _lift_cell(attr: str, digits: int):
    """A cell of the task's lift's ``attr`` to ``digits`` places (empty without a lift)."""

    def cell(run: RunErgonomics, task: TaskErgonomics) -> str:
        lf = _task_lift(run, task)
        return "" if lf is None else f"{getattr(lf, attr):.{digits}f}"

    return cell


def _li_over_1(with_lifts: Sequence[RunErgonomics]) -> dict:
    """The share of cycles with a lift index above 1, of the cycles where that is known: a lift
    with an index above 1, or every lift with an index (a cycle whose other lifts have none is
    left out, and counted by :func:`_without_li`)."""
    over = [any(lf.li is not None and lf.li > 1.0 for lf in r.lifts) for r in with_lifts]
    known = [o or not r.lifts_without_li for o, r in zip(over, with_lifts, strict=True)]
    return share(sum(over), sum(known))


def _without_li(with_lifts: Sequence[RunErgonomics]) -> dict:
    """The lifts the NIOSH equation gives no index: how many of all, the share of cycles with
    one, their lifting frequencies (lifts/min) and the limits they crossed (limit: lifts)."""
    lifts = [lf for r in with_lifts for lf in r.lifts]
    none = [lf for lf in lifts if lf.li is None]
    f = [lf.f for lf in none]
    return {
        "lifts": len(none),
        "of_lifts": len(lifts),
        "cycles": share(sum(bool(r.lifts_without_li) for r in with_lifts), len(with_lifts)),
        "lifts_per_min": [float(min(f)), float(max(f))] if f else None,
        "limits": dict(Counter(lf.limit for lf in none).most_common()),
    }


class NioshScore(Score):
    """The revised NIOSH lifting equation (:mod:`mjwalk.ergonomics.niosh`): per lift H, V, D,
    A, F, C, RWL and LI; over runs the index's P50/P95, the share of cycles with an index above
    1, and the lifts without an index apart."""

    name = "niosh"
    source = "revised NIOSH lifting equation, Waters et al. 1993 / 1994"
    columns = (
        Column("lifting_index", _li_cell),
        Column("rwl_kg", _lift_cell("rwl", 3)),
        Column("mass_kg", _lift_cell("mass", 3)),
        Column("lifts_per_min", _lift_cell("f", 2)),
        Column("lifting_index_note", _note_cell),
    )
    table = (
        Column("LI P50", lambda s: fmt(s["lifting_index"]["p50"], 2)),
        Column("LI P95", lambda s: fmt(s["lifting_index"]["p95"], 2)),
        Column("cycles LI>1", lambda s: fmt_share(s["cycles_li_over_1"])),
        Column("cycles without LI", lambda s: fmt_share(s["lifting_index_not_computed"]["cycles"])),
    )

    def per_run(self, frames: None, ang: BodyAngles, ctx: ScoreContext) -> dict[str, Any]:
        """The cycle's NIOSH lifts (:func:`cycle_lifts`).

        Args:
            frames: what :meth:`per_frame` returned.
            ang: the body angles of the cycle's F frames.
            ctx: the cycle's task context.

        Returns:
            ``lifts``: one :class:`~mjwalk.ergonomics.niosh.Lift` per lifting task.
        """
        return {"lifts": cycle_lifts(ang, ctx.spans, ctx.cycle_time)}

    def stats(self, runs: Sequence[RunErgonomics]) -> dict[str, Any]:
        """The NIOSH figures of a group of runs.

        Args:
            runs: the group's scored cycles.

        Returns:
            ``lifting_index`` (percentiles of the indices computed), ``lifts_per_cycle``
            (lifts with an index per run), ``cycles_li_over_1`` (the share of the cycles with
            lifts where an index is above 1, of those where that is known) and
            ``lifting_index_not_computed`` (the lifts without an index: counts, share of
            cycles, frequencies, limits crossed).
        """
        lis = [lf.li for r in runs for lf in r.lifts if lf.li is not None]
        with_lifts = [r for r in runs if r.lifts]
        return {
            "lifting_index": percentiles(lis),
            "lifts_per_cycle": len(lis) / len(runs) if runs else 0.0,
            "cycles_li_over_1": _li_over_1(with_lifts),
            "lifting_index_not_computed": _without_li(with_lifts),
        }

    def notes(self, stats: dict[str, Any]) -> list[str]:
        """The paragraph on the lifts without a lifting index.

        Args:
            stats: all operators' figures (with this method's :meth:`stats`).

        Returns:
            Markdown lines; none when every lift has an index.
        """
        w = stats["lifting_index_not_computed"]
        if not w["lifts"]:
            return []
        lo, hi = w["lifts_per_min"]
        freq = f"{lo:.1f}" if round(lo, 1) == round(hi, 1) else f"{lo:.1f}-{hi:.1f}"
        limits = "; ".join(f"{k} ({v} lifts)" for k, v in w["limits"].items())
        return [
            f"No NIOSH lifting index for {w['lifts']} of {w['of_lifts']} lifts "
            f"({w['cycles']['k']} of {w['cycles']['n']} cycles with lifts; left out of LI P50, "
            f"LI P95 and cycles LI>1): their recommended weight limit is 0 at {freq} lifts/min "
            f"(a cycle's lifts over its cycle time, cycles back to back). Limits crossed: "
            f"{limits}. ergonomics.csv gives the reason per lift.",
            "",
        ]
