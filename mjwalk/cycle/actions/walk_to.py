"""The walk action: a ``walk`` or ``carry`` task walks the operator to its site."""

from __future__ import annotations

import numpy as np

from mjwalk.cycle.actions.base import Action, CycleRun, CycleState, Performed
from mjwalk.cycle.poses import carry_pose, turn_frames, walk_frames, walk_ground
from mjwalk.cycle.turnclear import turn_clear
from mjwalk.cycle.types import WalkRecord
from mjwalk.cycle.walking import plan_task_walk
from mjwalk.plan.walkpath import WalkPath


class Walk(Action):
    """Walk to the task's site (a planned hybrid-A* walk, :func:`~mjwalk.cycle.walking.
    plan_task_walk`): turn on the spot towards the walk's first heading, walk, and turn into
    the facing of the site's work (a turn that would sweep an arm into the scene turning the
    trunk clear, :mod:`~mjwalk.cycle.turnclear`); a two-handed part stays in the hands in
    the carrying posture, turns included. Its record is the walk with its grid-A* route for
    the report."""

    def plan(self, run: CycleRun, state: CycleState) -> WalkPath:
        """The walk from where the operator stands, in the heading they face, to a spot in the
        site's stand zone (drawn from the run's generator and standing stream).

        Args:
            run: what stays the same through the run (its generators and walker).
            state: where the operator stands and faces.

        Returns:
            The planned walk (world frame, m, s).
        """
        ctx, goal = run.ctx, self.goal
        face = ctx.workplace.station(goal).yaw
        xy = (state.x, state.y)
        return plan_task_walk(
            ctx, self.index, xy, run.rng, run.walker, run.standing, yaw=state.yaw, face=face
        )

    @property
    def goal(self) -> str:
        """The site walked to."""
        assert self.task.site is not None  # the spec loader requires a site for walks
        return self.task.site

    def perform(self, run: CycleRun, state: CycleState, plan: WalkPath) -> Performed:
        """Turn, walk ``plan`` and turn into the site's facing (its three pieces); the last turn
        settles from the walk's last step into standing.

        Args:
            run: what stays the same through the run.
            state: where the operator stands before the walk (and any two-handed grip).
            plan: the walk from :meth:`plan`.

        Returns:
            The three pieces, the state at the site (facing its yaw, ``home`` the walk's end),
            the :class:`~mjwalk.cycle.types.WalkRecord` and the ground under every frame.
        """
        ctx, fps, path, width = run.ctx, run.fps, plan, state.grip
        face = ctx.workplace.station(self.goal).yaw
        pose = None if width is None else carry_pose(ctx, run.first_pose, width)
        turn, dt = turn_frames(
            ctx, (state.x, state.y), state.yaw, float(path.yaw[0]), fps, pose=pose
        )
        carry = self.task.hand if self.kind.carries else None
        if width is not None:
            carry = "both"
        wf = walk_frames(ctx, path, fps, carry, width)
        x, y = (float(v) for v in path.xy[-1])
        # the last step lands knee flexed, pelvis low: the turn settles into standing
        end, dt2 = turn_frames(
            ctx, (x, y), float(path.yaw[-1]), face, fps, pose=pose, settle=wf[-1]
        )
        # a turn that sweeps an arm into the scene turns the trunk clear, into the walk
        turn, wf, end = turn_clear(ctx, [turn, wf, end], (0, 2), fps)
        after = state.moved(x=x, y=y, yaw=face, home=(x, y), here=self.goal)
        pieces = ((turn, dt), (wf, len(wf) / fps), (end, dt2))
        ground = np.concatenate([  # the surface stood on: where the walk starts, under it, its end
            np.full(len(turn), ctx.ground((state.x, state.y))),
            walk_ground(ctx, path, fps),
            np.full(len(end), ctx.ground((x, y))),
        ])  # fmt: skip
        return Performed(pieces, after, self.record(run, state.here, path), ground)

    def record(self, run: CycleRun, start: str, path: WalkPath) -> WalkRecord:
        """The walk from site ``start`` with the grid-A* route between the walk's own ends (not the
        sites' marks: the walk starts and ends where the operator stands; over levels: the
        grid routes on each level through the crossings, :mod:`mjwalk.plan.levelgrid`).

        Args:
            run: what stays the same through the run (its context plans the grid route).
            start: the site the walk leaves.
            path: the walk.

        Returns:
            The :class:`~mjwalk.cycle.types.WalkRecord` (``baseline_length`` NaN when the grid
            planner finds no route).
        """
        if path.z is None:
            base = run.ctx.baseline_route(path.xy[0], path.xy[-1])
        else:  # a walk over levels: the grid routes on its levels, through the crossings
            base = run.ctx.baseline_over_levels(path, run.walker)
        return WalkRecord(
            task=self.index,
            route=self.task.route or f"{start}->{self.goal}",
            start_site=start,
            goal_site=self.goal,
            path=path,
            baseline_length=float("nan") if base is None else base.length,
            baseline=base,
        )
