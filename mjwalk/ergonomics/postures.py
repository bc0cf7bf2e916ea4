"""The posture methods as :class:`~mjwalk.ergonomics.score.Score` s: RULA, REBA and OWAS frame by
frame with each task's peak and the body part that drives it, and ISO 11226's static holdings.

Force and activity terms come from the cycle's :class:`~mjwalk.ergonomics.score.ScoreContext`:
the load in a hand is the mass of the part it holds; RULA's muscle use and REBA's activity are
its ``muscle``; REBA's coupling its ``coupling``; OWAS's load the mass in both hands.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from mjwalk.ergonomics import iso11226, owas, reba, rula
from mjwalk.ergonomics.angles import BodyAngles
from mjwalk.ergonomics.posturejit import (
    ANGLE_THRESHOLDS,
    KNEE_BENT_DEG,
    owas_kernel,
    posture_inputs,
    reba_kernel,
    rula_kernel,
    twist_end,
)
from mjwalk.ergonomics.results import RunErgonomics
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

#: The RULA parts, each with its largest score (to name the part that drives a peak).
RULA_PARTS = {"upper_arm": 6, "lower_arm": 3, "wrist": 4, "neck": 6, "trunk": 6, "legs": 2}
REBA_PARTS = {"trunk": 5, "neck": 3, "legs": 4, "upper_arm": 6, "lower_arm": 2, "wrist": 3}
#: The arms, by index of the (F, 2) per-arm arrays.
ARMS = ("left", "right")


@dataclass(frozen=True)
class ArmFrames:
    """A per-arm method's frames: ``arm`` (F, 2) the grand score of each arm's side,
    ``parts`` each side's part scores, ``frame`` (F,) the higher of the two."""

    arm: np.ndarray
    parts: list
    frame: np.ndarray


def _driver(parts, maxima: dict[str, int], k: int, side: int) -> str:
    """The body part with the highest score relative to its largest at frame ``k``."""
    best, name = -1.0, ""
    for p, m in maxima.items():
        v = getattr(parts[side], p)[k] / m
        if v > best:
            best, name = v, p
    return name


def _peak(f: ArmFrames, span: TaskSpan) -> tuple[int, int]:
    """(frame, arm) of the task's peak: the first frame of its highest score, the higher arm."""
    k = span.start + int(np.argmax(f.frame[span.start : span.end]))
    return k, int(np.argmax(f.arm[k]))


def _levels(values: Sequence[int]) -> dict:
    """The share of ``values`` at each level 1-4 or above."""
    return {str(lv): share(sum(a >= lv for a in values), len(values)) for lv in (1, 2, 3, 4)}


class RulaScore(Score):
    """RULA (:mod:`mjwalk.ergonomics.rula`): the grand score 1-7 per frame (the higher arm);
    per task its peak, the peak's time, arm and driving part, and the highest upper-arm score."""

    name = "rula"
    source = "McAtamney & Corlett 1993; action levels 1 (1-2) 2 (3-4) 3 (5-6) 4 (7)"
    columns = (
        Column("rula_peak", lambda run, t: t.rula),
        Column("rula_action_level", lambda run, t: int(rula.action_level(t.rula))),
        Column("rula_time_s", lambda run, t: f"{t.rula_time:.3f}"),
        Column("rula_driver", lambda run, t: t.rula_driver),
        Column("arm", lambda run, t: t.side),
        Column("upper_arm_score", lambda run, t: t.upper_arm),
    )
    table = (
        Column("RULA P50", lambda s: fmt(s["rula_peak"]["p50"])),
        Column("RULA P95", lambda s: fmt(s["rula_peak"]["p95"])),
        Column("RULA AL>=3", lambda s: fmt_share(s["rula_action_level"]["3"])),
        Column("RULA AL 4", lambda s: fmt_share(s["rula_action_level"]["4"])),
    )

    def per_frame(self, ang: BodyAngles, ctx: ScoreContext) -> ArmFrames:
        """Each arm's RULA grand score per frame, with the load in that hand (force score) and
        its muscle use in both groups.

        Args:
            ang: the body angles of the cycle's F frames.
            ctx: the cycle's loads (per hand), couplings and muscle use.

        Returns:
            :class:`ArmFrames`: (F, 2) scores, each side's part scores, (F,) the higher arm's.
        """
        body, arms, flags = posture_inputs(ang)
        n = ang.n_frames
        p, out = np.empty((2, 7, n), dtype=np.int64), np.empty((n, 2), dtype=np.int64)
        loads = np.stack([ctx.load, ctx.muscle]).astype(float)
        limits = (*ANGLE_THRESHOLDS, twist_end(ang), *rula.FORCE_KG)
        tables = (rula.TABLE_A, rula.TABLE_B, rula.TABLE_C)
        rula_kernel(body, arms, flags, loads, limits, tables, p, out)
        parts = [rula.RulaParts(*p[s]) for s in (0, 1)]
        return ArmFrames(out, parts, out.max(axis=1))

    def per_task(self, frames: ArmFrames, span: TaskSpan, ctx: ScoreContext) -> dict[str, Any]:
        """The task's RULA peak: its first frame of the highest score and the higher arm there.

        Args:
            frames: what :meth:`per_frame` returned.
            span: the task and its frames ``[span.start, span.end)``.
            ctx: the cycle's task context (its frame rate).

        Returns:
            ``rula`` (1-7), ``rula_time`` (s from the cycle's start), ``rula_driver`` (the part
            scoring highest against its largest score), ``side`` ("left"/"right") and
            ``upper_arm`` (the highest upper-arm score of either arm over the task).
        """
        k, side = _peak(frames, span)
        sl = slice(span.start, span.end)
        upper = max(frames.parts[0].upper_arm[sl].max(), frames.parts[1].upper_arm[sl].max())
        return {
            "rula": int(frames.frame[k]),
            "rula_time": k / ctx.fps,
            "rula_driver": _driver(frames.parts, RULA_PARTS, k, side),
            "side": ARMS[side],
            "upper_arm": int(upper),
        }

    def per_run(self, frames: ArmFrames, ang: BodyAngles, ctx: ScoreContext) -> dict[str, Any]:
        """The cycle's per-frame RULA scores.

        Args:
            frames: what :meth:`per_frame` returned.
            ang: the body angles of the cycle's F frames.
            ctx: the cycle's task context.

        Returns:
            ``rula``: (F,) int8 scores (the higher arm).
        """
        return {"rula": frames.frame.astype(np.int8)}

    def stats(self, runs: Sequence[RunErgonomics]) -> dict[str, Any]:
        """The RULA figures of a group of runs.

        Args:
            runs: the group's scored cycles.

        Returns:
            ``rula_peak`` (percentiles of the runs' peaks) and ``rula_action_level`` (the share of
            runs at each action level 1-4 or above).
        """
        peaks = [r.rula_peak for r in runs]
        return {
            "rula_peak": percentiles(peaks),
            "rula_action_level": _levels([int(rula.action_level(x)) for x in peaks]),
        }


class RebaScore(Score):
    """REBA (:mod:`mjwalk.ergonomics.reba`): the score 1-15 per frame (the higher side); per
    task its peak and the part that drives it."""

    name = "reba"
    source = "Hignett & McAtamney 2000; risk levels 0 (1) 1 (2-3) 2 (4-7) 3 (8-10) 4 (11+)"
    columns = (
        Column("reba_peak", lambda run, t: t.reba),
        Column("reba_risk_level", lambda run, t: int(reba.risk_level(t.reba))),
        Column("reba_driver", lambda run, t: t.reba_driver),
    )
    table = (
        Column("REBA P50", lambda s: fmt(s["reba_peak"]["p50"])),
        Column("REBA P95", lambda s: fmt(s["reba_peak"]["p95"])),
        Column("REBA >=3 (high)", lambda s: fmt_share(s["reba_risk_level"]["3"])),
    )

    def per_frame(self, ang: BodyAngles, ctx: ScoreContext) -> ArmFrames:
        """Each side's REBA score per frame, with the load in that hand, its grip's coupling and
        its activity (muscle use).

        Args:
            ang: the body angles of the cycle's F frames.
            ctx: the cycle's loads (per hand), couplings and muscle use.

        Returns:
            :class:`ArmFrames`: (F, 2) scores, each side's part scores, (F,) the higher side's.
        """
        body, arms, flags = posture_inputs(ang)
        n = ang.n_frames
        p, out = np.empty((2, 6, n), dtype=np.int64), np.empty((n, 2), dtype=np.int64)
        loads = np.stack([ctx.load, ctx.coupling, ctx.muscle]).astype(float)
        limits = (*ANGLE_THRESHOLDS, twist_end(ang), KNEE_BENT_DEG, *reba.LOAD_KG)
        tables = (reba.TABLE_A, reba.TABLE_B, reba.TABLE_C)
        knee = np.ascontiguousarray(ang.knee_flexion, dtype=float)
        reba_kernel(body, arms, knee, flags, loads, limits, tables, p, out)
        parts = [reba.RebaParts(*p[s]) for s in (0, 1)]
        return ArmFrames(out, parts, out.max(axis=1))

    def per_task(self, frames: ArmFrames, span: TaskSpan, ctx: ScoreContext) -> dict[str, Any]:
        """The task's REBA peak and the part that drives it.

        Args:
            frames: what :meth:`per_frame` returned.
            span: the task and its frames ``[span.start, span.end)``.
            ctx: the cycle's task context (its frame rate).

        Returns:
            ``reba`` (1-15) and ``reba_driver``.
        """
        k, side = _peak(frames, span)
        return {
            "reba": int(frames.frame[k]),
            "reba_driver": _driver(frames.parts, REBA_PARTS, k, side),
        }

    def per_run(self, frames: ArmFrames, ang: BodyAngles, ctx: ScoreContext) -> dict[str, Any]:
        """The cycle's per-frame REBA scores.

        Args:
            frames: what :meth:`per_frame` returned.
            ang: the body angles of the cycle's F frames.
            ctx: the cycle's task context.

        Returns:
            ``reba``: (F,) int8 scores (the higher side).
        """
        return {"reba": frames.frame.astype(np.int8)}

    def stats(self, runs: Sequence[RunErgonomics]) -> dict[str, Any]:
        """The REBA figures of a group of runs.

        Args:
            runs: the group's scored cycles.

        Returns:
            ``reba_peak`` (percentiles of the runs' peaks) and ``reba_risk_level`` (the share of
            runs at each risk level 1-4 or above).
        """
        peaks = [r.reba_peak for r in runs]
        return {
            "reba_peak": percentiles(peaks),
            "reba_risk_level": _levels([int(reba.risk_level(x)) for x in peaks]),
        }


class OwasScore(Score):
    """OWAS (:mod:`mjwalk.ergonomics.owas`): the action category 1-4 per frame, with the mass
    in both hands as its load; per task the highest."""

    name = "owas"
    source = "Karhu et al. 1977; action categories 1-4"
    columns = (Column("owas_peak", lambda run, t: t.owas),)

    def per_frame(self, ang: BodyAngles, ctx: ScoreContext) -> np.ndarray:
        """The OWAS action category per frame, the load code from the mass in both hands.

        Args:
            ang: the body angles of the cycle's F frames.
            ctx: the cycle's loads (per hand), couplings and muscle use.

        Returns:
            (F,) action categories 1-4.
        """
        body, _, flags = posture_inputs(ang)
        out = np.empty(ang.n_frames, dtype=np.int64)
        elevation = np.ascontiguousarray(ang.upper_arm_elevation, dtype=float)
        knee = np.ascontiguousarray(ang.knee_flexion, dtype=float)
        load = np.ascontiguousarray(ctx.load, dtype=float)
        limits = (owas.BACK_DEG, KNEE_BENT_DEG, *owas.LOAD_KG)
        owas_kernel(body, elevation, knee, flags, load, limits, owas.TABLE, out)
        return out

    def per_task(self, frames: np.ndarray, span: TaskSpan, ctx: ScoreContext) -> dict[str, Any]:
        """The task's highest OWAS action category.

        Args:
            frames: what :meth:`per_frame` returned.
            span: the task and its frames ``[span.start, span.end)``.
            ctx: the cycle's task context (its frame rate).

        Returns:
            ``owas`` (1-4).
        """
        return {"owas": int(frames[span.start : span.end].max())}

    def stats(self, runs: Sequence[RunErgonomics]) -> dict[str, Any]:
        """The OWAS figures of a group of runs.

        Args:
            runs: the group's scored cycles.

        Returns:
            ``owas_peak``: percentiles of the runs' highest action categories.
        """
        return {"owas_peak": percentiles([r.owas_peak for r in runs])}


class Iso11226Score(Score):
    """ISO 11226 (:mod:`mjwalk.ergonomics.iso11226`): the worst static holding of the trunk's
    inclination and of each upper arm's elevation over the cycle."""

    name = "iso11226"
    source = "ISO 11226:2000 static trunk and upper-arm postures"
    table = (Column("ISO 11226 not acc.", lambda s: fmt_share(s["iso11226_not_acceptable"])),)

    def per_run(self, frames: None, ang: BodyAngles, ctx: ScoreContext) -> dict[str, Any]:
        """The worst static holdings of the cycle: trunk inclination and each upper arm's
        elevation.

        Args:
            frames: what :meth:`per_frame` returned.
            ang: the body angles of the cycle's F frames.
            ctx: the cycle's task context.

        Returns:
            ``holdings``: the trunk's, the left and the right upper arm's
            :class:`~mjwalk.ergonomics.iso11226.Holding`.
        """
        fps = ctx.fps
        holdings = [iso11226.holding(ang.trunk_inclination, fps, "trunk", iso11226.TRUNK_HOLD)]
        for s, tag in enumerate(ARMS):
            holdings.append(
                iso11226.holding(
                    ang.upper_arm_elevation[:, s], fps, f"upper_arm_{tag}", iso11226.ARM_HOLD
                )
            )
        return {"holdings": holdings}

    def stats(self, runs: Sequence[RunErgonomics]) -> dict[str, Any]:
        """The ISO 11226 figures of a group of runs.

        Args:
            runs: the group's scored cycles.

        Returns:
            ``iso11226_not_acceptable``: the share of runs with a holding not acceptable.
        """
        bad = sum(not all(h.acceptable for h in r.holdings) for r in runs)
        return {"iso11226_not_acceptable": share(bad, len(runs))}
