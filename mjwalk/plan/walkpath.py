"""The ``WalkPath``: a planned root trajectory over the floor, with its steps and footprints."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from mjwalk._io import check_header, load_npz, save_npz
from mjwalk.errors import InputError, ModelFileError, SceneError

WALKPATH_FORMAT = "mjwalk.walkpath"
WALKPATH_VERSION = 1
#: Longest walk mjwalk plays, seconds: a cycle lasts at most an hour
#: (:data:`mjwalk.cycle.specfile.MAX_CYCLE_SECONDS`), and an hour at 240 fps is 864 000 frames.
MAX_WALK_SECONDS = 3600.0


@dataclass
class PathStep:
    """One step of a walk in world coordinates.

    Attributes:
        side: the swing foot, "left" or "right"; it lands at ``foot`` at the end of the step.
        start, end: indices into the path samples where the step begins and ends (inclusive).
        foot: (3,) landing footprint x, y (metres) and yaw (radians from +x, CCW).
        stance: (3,) the other (supporting) foot's x, y, yaw during the step.
        foot_z: height of the walk surface the swing foot lands on, metres above the floor
            (0 on the floor; a platform's, tread's or ramp's height where it lands there).
        stance_z: height of the walk surface under the stance foot, metres.
    """

    side: str
    start: int
    end: int
    foot: np.ndarray
    stance: np.ndarray
    foot_z: float = 0.0
    stance_z: float = 0.0


@dataclass
class WalkPath:
    """A root (pelvis) trajectory on the floor, world frame: metres, seconds, yaw from +x CCW.

    Attributes:
        t: (N,) sample times in seconds, starting at 0.
        xy: (N, 2) pelvis position on the floor, metres.
        yaw: (N,) pelvis heading, radians from +x, counter-clockwise (unwrapped).
        steps: the steps, in order (empty for the grid-A* baseline, which has no gait).
        meta: provenance (planner, seed, expansions, planning time...).
        z: (N,) height of the walk surface under the pelvis at each sample, metres above the
            floor; None on one level (the floor: every height 0). A walk over platforms,
            ramps and stairs carries it (issue 47).
    """

    t: np.ndarray
    xy: np.ndarray
    yaw: np.ndarray
    steps: list[PathStep] = field(default_factory=list)
    meta: dict = field(default_factory=dict)
    z: np.ndarray | None = None

    @property
    def ground(self) -> np.ndarray:
        """(N,) height of the walk surface under the pelvis, metres (zeros on the floor)."""
        return np.zeros(len(self.t)) if self.z is None else np.asarray(self.z, dtype=float)

    @property
    def is_flat(self) -> bool:
        """Whether the whole walk stays on the floor (no height anywhere)."""
        heights = [s.foot_z for s in self.steps] + [s.stance_z for s in self.steps]
        return (self.z is None or not np.any(self.z)) and not any(heights)

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
        """(S, 4) per step: side (0 left, 1 right), x, y, yaw of the landing foot.

        Returns:
            (S, 4) side, x, y (metres, world frame), yaw (radians from +x CCW).
        """
        if not self.steps:
            return np.zeros((0, 4))
        return np.array([[s.side == "right", *s.foot] for s in self.steps], dtype=float)

    def validate(self, what: str = "walk") -> None:
        """Raise InputError naming ``what`` and the array unless the walk is consistent: ``t``
        (N,) finite, from 0 and never decreasing, at most :data:`MAX_WALK_SECONDS` long;
        ``xy`` (N, 2) and ``yaw`` (N,) finite; each step's sample range inside 0..N-1 and in
        order, its side "left" or "right", its footprints (3,) finite. An edited walk file
        otherwise failed deep in playback (a ValueError, a MemoryError, an IndexError).

        Args:
            what: the walk's name in the message (e.g. its file).
        """

        def bad(msg: str) -> InputError:
            return InputError(f"{what}: {msg}")

        t, xy, yaw = (np.asarray(a) for a in (self.t, self.xy, self.yaw))
        if t.ndim != 1 or len(t) < 1:
            raise bad(f"t must be a 1-D array of sample times (seconds), got shape {t.shape}")
        n = len(t)
        if xy.shape != (n, 2):
            raise bad(f"xy must have shape ({n}, 2) (one x, y per time in t), got {xy.shape}")
        if yaw.shape != (n,):
            raise bad(f"yaw must have shape ({n},) (one heading per time in t), got {yaw.shape}")
        for name, a in (("t", t), ("xy", xy), ("yaw", yaw)):
            if not np.issubdtype(a.dtype, np.number) or not np.all(np.isfinite(a)):
                raise bad(f"{name} must hold finite numbers")
        if self.z is not None:
            z = np.asarray(self.z)
            if z.shape != (n,) or not np.issubdtype(z.dtype, np.number):
                raise bad(f"z must have shape ({n},) (one height per time in t), got {z.shape}")
            if not np.all(np.isfinite(z)):
                raise bad("z must hold finite numbers")
        if abs(float(t[0])) > 1e-9:
            raise bad(f"t must start at 0 s, starts at {float(t[0]):g} s")
        dt = np.diff(t)
        if np.any(dt < 0):  # equal times pass: a grid route may repeat a point
            k = int(np.flatnonzero(dt < 0)[0])
            raise bad(
                f"t must increase: sample {k + 1} at {float(t[k + 1]):g} s comes before "
                f"sample {k} at {float(t[k]):g} s"
            )
        if float(t[-1]) > MAX_WALK_SECONDS:
            raise bad(f"lasts {float(t[-1]):g} s, longer than {MAX_WALK_SECONDS:g} s")
        prev_end = 0
        for k, s in enumerate(self.steps):
            if s.side not in ("left", "right"):
                raise bad(f"step {k}: side must be 'left' or 'right', got {s.side!r}")
            if not (0 <= s.start <= s.end < n) or s.start < prev_end:
                raise bad(
                    f"step {k}: samples {s.start}..{s.end} are not an in-order range of the "
                    f"walk's samples 0..{n - 1}"
                )
            prev_end = s.start
            for name, a in (("foot", s.foot), ("stance", s.stance)):
                a = np.asarray(a)
                if a.shape != (3,) or not np.all(np.isfinite(a)):
                    raise bad(f"step {k}: {name} must be 3 finite numbers (x, y, yaw)")
            if not (np.isfinite(s.foot_z) and np.isfinite(s.stance_z)):
                raise bad(f"step {k}: foot_z and stance_z must be finite heights (metres)")

    def stamp_scene(self, workplace) -> WalkPath:
        """Record the scene this walk was planned in (its name and
        :attr:`~mjwalk.world.workplace.Workplace.fingerprint`) in ``meta``; returns self.

        Args:
            workplace: the scene the walk was planned in.

        Returns:
            This walk.
        """
        self.meta["scene"] = workplace.name
        self.meta["scene_fingerprint"] = workplace.fingerprint
        return self

    def check_scene(self, workplace, force: bool = False) -> None:
        """Raise SceneError when the walk was planned in a scene whose obstacle geometry
        differs from ``workplace``'s (played there it would pass through obstacles or leave
        the floor), unless ``force``. Walks without a recorded scene pass.

        Args:
            workplace: the scene the walk is to be played in.
            force: play it anyway (no check).
        """
        planned = self.meta.get("scene_fingerprint")
        if force:
            return
        if planned is None or planned == workplace.fingerprint:
            off = ~np.asarray(workplace.on_floor(np.asarray(self.xy, dtype=float)))
            if off.any():
                k = int(np.flatnonzero(off)[0])
                x, y = (float(v) for v in self.xy[k])
                b = workplace.floor_bounds
                raise SceneError(
                    f"the walk leaves the floor of {workplace.name!r}: sample {k} at "
                    f"({x:.6g}, {y:.6g}) m is outside x [{b[0]:g}, {b[2]:g}], y [{b[1]:g}, "
                    f"{b[3]:g}] (an edited walk file, or another scene's)"
                )
            return
        raise SceneError(
            f"the walk was planned in scene {self.meta.get('scene', '?')!r} (obstacle "
            f"fingerprint {planned}), not in {workplace.name!r} (fingerprint "
            f"{workplace.fingerprint}): its obstacles or floor differ, so the walk would pass "
            "through obstacles or off the floor; use the scene it was planned in (or force it: "
            "--force on the command line, force=True in Python)"
        )

    def save(self, path: str | Path) -> None:
        """Write the path to one ``.npz`` file (atomically).

        Args:
            path: the ``.npz`` file to write.
        """
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
        if not self.is_flat:  # a flat walk's file stays as it was before levels existed
            arrays["z"] = self.ground
            arrays["step_z"] = np.array(
                [[s.foot_z, s.stance_z] for s in steps], dtype=float
            ).reshape(-1, 2)
        header = {"format": WALKPATH_FORMAT, "version": WALKPATH_VERSION, "meta": self.meta}
        save_npz(path, header, arrays)

    @classmethod
    def load(cls, path: str | Path) -> WalkPath:
        """Read a path written by :meth:`save`; a foreign or corrupt file raises ModelFileError.

        Args:
            path: the ``.npz`` file.

        Returns:
            The walk.
        """
        header, data = load_npz(path, "walk-path")
        check_header(header, path, "walk-path", WALKPATH_FORMAT, WALKPATH_VERSION)
        names = ("t", "xy", "yaw", "step_side", "step_range", "step_foot", "step_stance")
        missing = [k for k in names if k not in data]
        if missing:
            raise ModelFileError(f"{path}: not a complete walk-path file (no {missing[0]!r})")
        counts = {k: len(data[k]) if data[k].ndim else -1 for k in names[3:]}
        if len(set(counts.values())) != 1 or data["step_range"].shape[1:] != (2,):
            raise ModelFileError(
                f"{path}: the step arrays disagree (entries: "
                + ", ".join(f"{k} {v}" for k, v in counts.items())
                + f"; step_range shape {data['step_range'].shape})"
            )
        if not isinstance(header.get("meta"), dict):
            raise ModelFileError(f"{path}: the walk-path header has no meta table")
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
        if "step_z" in data:
            if data["step_z"].shape != (len(steps), 2):
                raise ModelFileError(f"{path}: step_z has shape {data['step_z'].shape}")
            for s, (fz, sz) in zip(steps, data["step_z"], strict=True):
                s.foot_z, s.stance_z = float(fz), float(sz)
        walk = cls(
            t=data["t"],
            xy=data["xy"],
            yaw=data["yaw"],
            steps=steps,
            meta=header["meta"],
            z=data["z"] if "z" in data else None,
        )
        try:
            walk.validate(str(path))
        except InputError as exc:
            raise ModelFileError(str(exc)) from None
        return walk
