"""The ``WalkPath``: a planned root trajectory over the floor, with its steps and footprints."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from mjwalk._io import check_header, load_npz, save_npz

WALKPATH_FORMAT = "mjwalk.walkpath"
WALKPATH_VERSION = 1


@dataclass
class PathStep:
    """One step of a walk in world coordinates.

    Attributes:
        side: the swing foot, "left" or "right"; it lands at ``foot`` at the end of the step.
        start, end: indices into the path samples where the step begins and ends (inclusive).
        foot: (3,) landing footprint x, y (metres) and yaw (radians from +x, CCW).
        stance: (3,) the other (supporting) foot's x, y, yaw during the step.
    """

    side: str
    start: int
    end: int
    foot: np.ndarray
    stance: np.ndarray


@dataclass
class WalkPath:
    """A root (pelvis) trajectory on the floor, world frame: metres, seconds, yaw from +x CCW.

    Attributes:
        t: (N,) sample times in seconds, starting at 0.
        xy: (N, 2) pelvis position on the floor, metres.
        yaw: (N,) pelvis heading, radians from +x, counter-clockwise (unwrapped).
        steps: the steps, in order (empty for the grid-A* baseline, which has no gait).
        meta: provenance (planner, seed, expansions, planning time...).
    """

    t: np.ndarray
    xy: np.ndarray
    yaw: np.ndarray
    steps: list[PathStep] = field(default_factory=list)
    meta: dict = field(default_factory=dict)

    @property
    def points(self) -> np.ndarray:
        """(N, 2) the path's points (alias of ``xy``)."""
        return self.xy

    @property
    def length(self) -> float:
        """Walked length along the samples, metres."""
        return float(np.linalg.norm(np.diff(self.xy, axis=0), axis=1).sum())

    @property
    def duration(self) -> float:
        """Duration in seconds."""
        return float(self.t[-1] - self.t[0]) if len(self.t) else 0.0

    @property
    def start(self) -> np.ndarray:
        return self.xy[0]

    @property
    def end(self) -> np.ndarray:
        return self.xy[-1]

    def footprints(self) -> np.ndarray:
        """(S, 4) per step: side (0 left, 1 right), x, y, yaw of the landing foot."""
        if not self.steps:
            return np.zeros((0, 4))
        return np.array([[s.side == "right", *s.foot] for s in self.steps], dtype=float)

    def stamp_scene(self, workplace) -> WalkPath:
        """Record the scene this walk was planned in (its name and
        :attr:`~mjwalk.world.workplace.Workplace.fingerprint`) in ``meta``; returns self."""
        self.meta["scene"] = workplace.name
        self.meta["scene_fingerprint"] = workplace.fingerprint
        return self

    def check_scene(self, workplace, force: bool = False) -> None:
        """Raise SceneError when the walk was planned in a scene whose obstacle geometry
        differs from ``workplace``'s (played there it would pass through obstacles or leave
        the floor), unless ``force``. Walks without a recorded scene pass."""
        from mjwalk.errors import SceneError

        planned = self.meta.get("scene_fingerprint")
        if force or planned is None or planned == workplace.fingerprint:
            return
        raise SceneError(
            f"the walk was planned in scene {self.meta.get('scene', '?')!r} (obstacle "
            f"fingerprint {planned}), not in {workplace.name!r} (fingerprint "
            f"{workplace.fingerprint}): its obstacles or floor differ, so the walk would pass "
            "through obstacles or off the floor; use the scene it was planned in (or force it: "
            "--force on the command line, force=True in Python)"
        )

    def save(self, path: str | Path) -> None:
        """Write the path to one ``.npz`` file (atomically)."""
        steps = self.steps
        arrays = {
            "t": self.t,
            "xy": self.xy,
            "yaw": self.yaw,
            "step_side": np.array([s.side == "right" for s in steps], dtype=bool),
            "step_range": np.array([[s.start, s.end] for s in steps], dtype=np.int64).reshape(
                -1, 2
            ),
            "step_foot": np.array([s.foot for s in steps], dtype=float).reshape(-1, 3),
            "step_stance": np.array([s.stance for s in steps], dtype=float).reshape(-1, 3),
        }
        header = {"format": WALKPATH_FORMAT, "version": WALKPATH_VERSION, "meta": self.meta}
        save_npz(path, header, arrays)

    @classmethod
    def load(cls, path: str | Path) -> WalkPath:
        """Read a path written by :meth:`save`; a foreign or corrupt file raises ModelFileError."""
        header, data = load_npz(path, "walk-path")
        check_header(header, path, "walk-path", WALKPATH_FORMAT, WALKPATH_VERSION)
        steps = [
            PathStep(
                side="right" if side else "left",
                start=int(r[0]),
                end=int(r[1]),
                foot=foot,
                stance=stance,
            )
            for side, r, foot, stance in zip(
                data["step_side"],
                data["step_range"],
                data["step_foot"],
                data["step_stance"],
                strict=True,
            )
        ]
        return cls(t=data["t"], xy=data["xy"], yaw=data["yaw"], steps=steps, meta=header["meta"])
