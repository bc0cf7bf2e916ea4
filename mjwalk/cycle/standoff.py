"""The stand-off of a reach: where the operator stands so the reaching arm clears the scene.

A walk ends anywhere in its stand zone, and the operator then turns to bring the target ahead
of the reaching shoulder. Both move the shoulder, and a shoulder close to a shelf board's front
face lifts the hand from its relaxed pose (:data:`~mjwalk.arms.chain.REST_HAND`, wrist
at about the board's height) almost straight up in front of the board, the fingers brushing its
front edge. The planner cannot see this (its clearance is 2-D, a body radius around the
pelvis); the arm can. So the cycle checks each reach with MuJoCo's collision detection, the arm
geoms inflated by :data:`REACH_CLEARANCE`, and when it is not clear steps the operator back
from the target in :data:`STEP_BACK` increments (up to :data:`MAX_STEP_BACK`) during the turn,
as a worker steps back from a shelf he stands too close to; a reach whose target is out of arm's
length from where the last one left the operator steps in first
(:mod:`mjwalk.cycle.reachspot`). The cycle's contact check (:mod:`mjwalk.timeline.collisions`)
is unchanged. How often reaches step back, and how far, is measured by
``benchmarks/bench_contacts.py`` (docs/decisions/007-reach-standoff.md).

World frame: metres, z up.
"""

from __future__ import annotations

import copy

import mujoco
import numpy as np

from mjwalk.body.humanoid import HUMAN_GROUP, JointMap
from mjwalk.cycle.memo import ScratchData
from mjwalk.timeline.collisions import candidate_frames, floor_geoms, repeats

#: Clearance (m) the reaching arm (upper arm to fingertips) keeps from every scene geom. The
#: contacts it prevents were up to 6.3 mm deep (benchmarks/bench_contacts.py, 300 cycles);
#: 1 cm is a little more than the radius of a fingertip (0.0045 H = 8 mm at H = 1.75 m), so a
#: finger passing the edge keeps about its own thickness of air.
REACH_CLEARANCE = 0.01
#: Increment (m) of the step back from a target whose reach is not clear, and the largest step
#: back: a short shuffle step (about a third of a walking step of 0.7 m).
STEP_BACK = 0.02
MAX_STEP_BACK = 0.20
#: A step back must leave the hand within this distance (m) of its target (or no farther than
#: from where the walk ended): the cycle's reaches end on their targets within 1 cm
#: (tests/cycle/test_simulate.py), the accuracy of the reach model fitted to its end points.
REACH_TOLERANCE = 0.01
#: Contacts with the floor count only deeper than this (m): the soles rest on it (as in
#: :func:`mjwalk.timeline.collisions.collision_report`).
FLOOR_TOLERANCE = 0.01
#: The clearance checks' MjData, one per model layout and thread: every operator's stature has
#: its own :class:`ArmClearance` (its own margins) but the same sizes, and making an MjData of
#: the station's humanoid (a 17.8 MB arena) cost about 0.7 ms a stature. :meth:`ArmClearance.
#: distance` sets each pose's whole qpos before MuJoCo reads it. Kept apart from the contexts'
#: scratch (:mod:`mjwalk.cycle.context`), in which the reach code computes between clearance
#: checks. 64 layouts a thread, as many as the humanoid cache holds models.
CLEARANCE_DATA = ScratchData(64)


class ArmClearance:
    """Clearance of humanoid poses from the scene by MuJoCo collision detection, the arm geoms
    (both arms, upper arm to fingertips) inflated by ``clearance`` metres.

    Args:
        model: the scene with the humanoid attached (:func:`mjwalk.body.humanoid.attach_humanoid`).
        jointmap: its joint map (for the humanoid's name prefix).
        clearance: metres the arms must keep from the scene.
    """

    def __init__(
        self, model: mujoco.MjModel, jointmap: JointMap, clearance: float = REACH_CLEARANCE
    ):
        self.clearance = float(clearance)
        self.model = copy.deepcopy(model)  # the caller's model keeps its margins
        self.data = CLEARANCE_DATA.of(self.model)  # every use sets the whole qpos
        m = self.model
        roots = {m.body(f"{jointmap.prefix}upper_arm_{s}").id for s in ("l", "r")}
        arm = np.zeros(m.ngeom, dtype=bool)
        parent = m.body_parentid.tolist()  # (each attribute read of an MjModel makes an array)
        for g, b in enumerate(m.geom_bodyid.tolist()):
            while b > 0 and b not in roots:
                b = parent[b]
            arm[g] = b in roots
        self.human = m.geom_group == HUMAN_GROUP
        self.model.geom_margin[arm & self.human] = self.clearance
        self.floor = floor_geoms(m)

    def distance(self, qpos: np.ndarray, broad_phase: bool = True) -> float:
        """The smallest distance of the humanoid to the scene over the poses ``qpos`` among the
        pairs closer than their margin (an arm geom within ``clearance``, any other humanoid geom
        overlapping, the floor deeper than :data:`FLOOR_TOLERANCE`). With ``broad_phase``
        MuJoCo's collision detection runs only on the poses where such a pair can be
        (:func:`~mjwalk.timeline.collisions.candidate_frames`, the margins included), and once for
        a run of equal poses (a reach's hold: about half a cycle's poses); the result is that of
        every pose (``broad_phase=False``).

        Args:
            qpos: (F, nq) or (nq,) the poses.
            broad_phase: skip the poses no close pair can be in.

        Returns:
            The distance, metres (negative: overlap); ``inf`` when no pair is that close (the poses
            are clear).
        """
        m, d = self.model, self.data
        best = np.inf
        poses = np.atleast_2d(qpos)
        if broad_phase:
            poses = poses[~repeats(poses)]  # a pose equal to the one before has its distance
            poses = poses[candidate_frames(m, poses, self.human, self.floor, FLOOR_TOLERANCE, d)]
        for q in poses:
            d.qpos[:] = q
            mujoco.mj_kinematics(m, d)
            mujoco.mj_collision(m, d)
            n = d.ncon
            if n == 0:
                continue
            g = np.asarray(d.contact.geom[:n]).astype(int)
            dist = np.asarray(d.contact.dist[:n])
            h1, h2 = self.human[g[:, 0]], self.human[g[:, 1]]
            scene = np.where(h1, g[:, 1], g[:, 0])
            keep = (h1 != h2) & ~(self.floor[scene] & (dist >= -FLOOR_TOLERANCE))
            if keep.any():
                best = min(best, float(dist[keep].min()))
        return best

    def clear(self, qpos: np.ndarray) -> bool:
        """Whether every pose keeps the arms ``clearance`` metres from the scene and nothing else of
        the humanoid touches it.

        Args:
            qpos: (F, nq) or (nq,) the poses.

        Returns:
            True when :meth:`distance` is ``inf``.
        """
        return self.distance(qpos) == np.inf


def step_back_offsets() -> np.ndarray:
    """The step-back distances tried in order: 0, :data:`STEP_BACK`, ... up to
    :data:`MAX_STEP_BACK`.

    Returns:
        (n,) metres.
    """
    n = round(MAX_STEP_BACK / STEP_BACK)
    return np.arange(n + 1) * STEP_BACK
