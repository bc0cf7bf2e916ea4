"""The reach action: a ``pick``, ``place`` or ``fasten`` task reaches a hand to its site."""

from __future__ import annotations

from mjwalk.cycle.actions.base import Action, CycleRun, CycleState, Performed
from mjwalk.cycle.handling import RETURN_CASE, reach_duration, task_factor
from mjwalk.cycle.reaching import ReachPace
from mjwalk.cycle.reachspot import ReachStart, reach_task
from mjwalk.cycle.types import ArmRecord


class Reach(Action):
    """Turn towards the site and reach for it from where the operator stands, hold, and
    return (:func:`~mjwalk.cycle.reachspot.reach_task`: the reach model, a step back or in
    when the arm needs room); the reach, hold and return times follow the kind's MTM-1 case
    and the operator's pace, times a lognormal task factor (:mod:`mjwalk.cycle.handling`). A
    two-handed take leaves the part in the hands (the state's ``grip``); a put frees them."""

    def plan(self, run: CycleRun, state: CycleState) -> tuple[float, float]:
        """The reach's hold time and its task-time factor: the factor drawn from the run's handling
        stream (lognormal, median 1); the hold is the task's ``duration`` (else the kind's
        default) times the factor over the operator's pace.

        Args:
            run: what stays the same through the run (its handling stream is drawn from).
            state: where the operator is (unused: the draw does not depend on it).

        Returns:
            (hold seconds, task-time factor).
        """
        kind, task = self.kind, self.task
        assert kind.default_hold is not None
        hold = task.duration if task.duration is not None else kind.default_hold
        factor = task_factor(run.handling)  # lognormal, median 1 (mjwalk.cycle.handling)
        hold *= factor / run.pace  # the hold, like the reach, at the operator's pace
        return hold, factor

    def perform(self, run: CycleRun, state: CycleState, plan: tuple[float, float]) -> Performed:
        """The turn (with any step) and the reach, hold and return (its two pieces), at the
        operator's MTM-1 reach and return times times the plan's factor.

        Args:
            run: what stays the same through the run.
            state: where the operator stands and what the hands hold.
            plan: (hold seconds, task-time factor) from :meth:`plan`.

        Returns:
            The two pieces (turn, reach), the state after (where the operator stands, the
            two-handed grip held or released) and the :class:`~mjwalk.cycle.types.ArmRecord`.
        """
        hold, factor = plan
        case, walker, task = self.kind.reach_case, run.walker, self.task
        assert case is not None and task.site is not None  # reach kinds have both

        def timing(dist, case=case, factor=factor):
            return (
                reach_duration(dist, walker, case) * factor,
                reach_duration(dist, walker, RETURN_CASE) * factor,
            )

        ctx, fps = run.ctx, run.fps
        facing = ctx.workplace.station(state.here).yaw
        start = ReachStart(state.x, state.y, state.yaw, facing, state.grip, state.home)
        r = reach_task(ctx, task, start, ReachPace(hold, fps, timing))
        grip = state.grip
        if task.hand == "both":
            grip = r.width if self.kind.part == "take" else None  # released when put down
        after = state.moved(x=r.x, y=r.y, yaw=r.yaw, grip=grip)
        record = ArmRecord(
            task=self.index,
            kind=task.kind,
            site=task.site,
            hand=task.hand,
            duration=len(r.frames) / fps,
            hand_error=r.error,
            outside=bool(r.result.outside),
            warnings=list(r.result.warnings),
            step_back=r.step_back,
        )
        return Performed(((r.turn, r.turn_time), (r.frames, len(r.frames) / fps)), after, record)
