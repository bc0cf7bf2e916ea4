"""``ReachModel``: constraint -> DCS -> PCA coefficients -> arm trajectory (Al-Zubi & Sommer).

Pipeline of :meth:`ReachModel.predict`:

1. the constraint vector (start/end hand position; obstacle ratio B/A; object size and
   orientation...) goes through a :class:`~mjwalk.arms.dcs.DCSNetwork` that returns the PCA
   coefficients ``b`` and the alignment pose of the movement;
2. eq. 1 rebuilds the aligned segment directions, the pose maps them back to the body frame;
3. when the actual start and end hand positions are given, the pose (rotation + angular scale)
   is refit so the hand starts and ends there (the paper's "fitted to a start and end
   position"), then a final analytic IK correction, blended over the movement with a
   minimum-jerk profile, moves the hand onto both points exactly (well within 1 cm);
4. :func:`~mjwalk.arms.chain.arm_joint_angles` turns directions (+ forearm roll) into
   the humanoid's joint angles.

Frames: the body frame at the shoulder of the moving arm, metres, x forward, y left, z up
(the humanoid's thorax frame in its neutral pose). A constraint outside the trained range is
never used silently: the result carries its distance to the training data and a warning, or
``strict=True`` raises :class:`~mjwalk.errors.MjwalkError`. A DCS with a trend fallback (the
default model's and :data:`~mjwalk.arms.reachdefault.CAPTURE_DCS`) blends into its trend network
there rather than extrapolating its neurons' local maps; the warning says by how much.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import least_squares

from mjwalk._io import check_header, load_npz, save_npz
from mjwalk.arms.anglerows import min_jerk_steps
from mjwalk.arms.armpose import apply_pose
from mjwalk.arms.armrep import ArmRepresentation
from mjwalk.arms.chain import (
    MIRROR_Y,
    REST_HAND,
    arm_segment_lengths,
    end_effector,
    two_link_ik_rows,
)
from mjwalk.arms.dcs import DCSNetwork
from mjwalk.arms.posefit import fit_endpoint_pose
from mjwalk.conventions import Side
from mjwalk.errors import MjwalkError, ModelFileError

REACH_FORMAT = "mjwalk.reach"
REACH_VERSION = 1
#: Constraint of an endpoint reach model: start and end hand positions (m, shoulder frame).
ENDPOINT_INPUTS = 6
#: Segments of the humanoid arm chain a scene reach drives: upper arm, forearm, hand.
HUMANOID_ARM_SEGMENTS = 3
#: Bounds of the endpoint fit's pose (rotation vector, radians; log angular scale): the log
#: scale within +-1 (:meth:`ReachModel._fit_endpoints`). Read-only: shared by every fit.
_POSE_LB = np.array([-np.inf, -np.inf, -np.inf, -1.0])
_POSE_UB = np.array([np.inf, np.inf, np.inf, 1.0])
_POSE_LB.setflags(write=False)
_POSE_UB.setflags(write=False)


def load_endpoint_model(path: str | Path, source: str | None = None) -> ReachModel:
    """Read a reach model file and check it is an endpoint model of the humanoid's arm
    (:func:`check_endpoint_model`); ``source`` names it in the error (default: the path).

    The file is read once per content: a cycle spec checks it when it is loaded and the
    cycle uses it later, so both get the same :class:`ReachModel` object as long as the
    file's size and modification time are unchanged (treat it as read-only).

    Args:
        path: the reach model file.
        source: name in the error, or None for the path.

    Returns:
        the model (shared; treat as read-only).
    """
    file = Path(path).resolve()
    if file.is_file():
        stat = file.stat()
        model = _load_reach_file(str(file), stat.st_size, stat.st_mtime_ns)
    else:
        model = ReachModel.load(path)  # raises the loader's "no such file" error
    check_endpoint_model(model, str(path) if source is None else source)
    return model


@functools.lru_cache(maxsize=8)
def _load_reach_file(path: str, size: int, mtime_ns: int) -> ReachModel:
    """:meth:`ReachModel.load`, memoized by path, size and modification time."""
    return ReachModel.load(path)


def check_endpoint_model(model: ReachModel, source: str = "reach model") -> None:
    """Raise :class:`~mjwalk.errors.MjwalkError` unless ``model`` is what
    :func:`reach_for_side`, :func:`~mjwalk.timeline.reachscene.reach_in_scene` and the cycle ask
    of it: a start/end hand constraint (6,) mapped to the humanoid's upper arm, forearm and
    hand (3 segments), such as :func:`~mjwalk.arms.reachdefault.default_reach_model`.

    Args:
        model: the reach model.
        source: name of the model in the error.
    """
    n_in, n_seg = model.n_inputs, len(model.lengths)
    if n_in == ENDPOINT_INPUTS and n_seg == HUMANOID_ARM_SEGMENTS:
        return
    hint = ""
    if n_in == 9 and n_seg == 2:
        hint = (
            " (a model of raises from capture, mjwalk.arm_movements: its constraint is the "
            "start elbow, start hand and end hand; use it with ReachModel.predict, or train "
            "an endpoint model with mjwalk.arm_movements(..., hand=True))"
        )
    raise MjwalkError(
        f"{source}: a scene reach needs an endpoint model of the humanoid's arm (constraint: "
        f"start and end hand positions, {ENDPOINT_INPUTS} values; segments: upper arm, "
        f"forearm, hand); this one takes {n_in} inputs and has {n_seg} segments{hint}"
    )


def _point(p, what: str, error: type[MjwalkError] = MjwalkError) -> np.ndarray:
    """``p`` as a finite (3,) float array, or ``error`` naming ``what``."""
    a = np.asarray(p, dtype=float)
    if a.shape != (3,) or not np.isfinite(a).all():
        raise error(f"ReachModel: {what} must be three finite numbers (m), got {a.tolist()}")
    return a


@dataclass
class ReachResult:
    """One synthesized arm movement in the shoulder body frame (metres, x fwd, y left, z up).

    Attributes:
        directions: (n, S, 3) unit segment directions (upper arm, forearm[, hand]) over time.
        hand: (n, 3) end-of-chain position over time, metres from the shoulder.
        extras: (n, C) extra channels (e.g. grip aperture m, forearm roll rad) or None.
        coefficients: (q,) PCA coefficients the DCS returned.
        distance: distance of the constraint to the nearest training constraint, in training
            standard deviations.
        outside: True when ``distance`` exceeds the network's trained-range radius.
        warnings: human-readable notes (extrapolation, clamped targets).
    """

    directions: np.ndarray
    hand: np.ndarray
    extras: np.ndarray | None
    coefficients: np.ndarray
    distance: float
    outside: bool
    warnings: list[str] = field(default_factory=list)


def mirror_result(res: ReachResult) -> ReachResult:
    """The mirror image of a reach through the body's sagittal plane (y -> -y in the shoulder
    frame): a left-arm movement becomes the right arm's and back. Directions and hand path are
    reflected; the extra channels (grip aperture, forearm roll in the anatomical sign
    convention, which is the same for both sides) are kept.

    Args:
        res: a reach in one arm's shoulder frame.

    Returns:
        the reflected reach.
    """
    # (the fields spelled out: dataclasses.replace looks each one up by name at every call)
    return ReachResult(
        directions=res.directions * MIRROR_Y,
        hand=res.hand * MIRROR_Y,
        extras=res.extras,
        coefficients=res.coefficients,
        distance=res.distance,
        outside=res.outside,
        warnings=list(res.warnings),
    )


def arm_scale(model: ReachModel, stature: float) -> float:
    """The model's arm length over the arm of a humanoid of ``stature`` metres, both summed
    over the model's segments (to the hand's end for an endpoint model, whose hand end is what
    it places; Winter's shares for the humanoid; 1 at the stature the model's lengths are of).
    A scene reach is solved at the model's size: targets (m, shoulder frame) are multiplied
    by it, and segment directions, hence joint angles, are the same at every size (geometric
    similarity).

    Args:
        model: the reach model.
        stature: body height, metres.

    Returns:
        the dimensionless scale.
    """
    lengths = np.asarray(model.lengths, dtype=float)
    return float(lengths.sum() / arm_segment_lengths(stature)[: len(lengths)].sum())


def humanoid_arm(model: ReachModel, stature: float) -> tuple[float, np.ndarray]:
    """``(scale, arm_lengths)`` of a humanoid of ``stature`` metres reaching with ``model``:
    :func:`arm_scale`, and its upper arm, forearm and hand at the model's size (Winter's
    shares times the scale): the segments the endpoint fit puts the humanoid's hand on the
    target with, where the model's clips had arms of other proportions.

    Args:
        model: the reach model.
        stature: body height, metres.

    Returns:
        ``(scale, arm_lengths (3,) metres)``.
    """
    scale = arm_scale(model, stature)
    return scale, arm_segment_lengths(stature)[: len(model.lengths)] * scale


def reach_for_side(
    model: ReachModel,
    end: np.ndarray,
    side: Side,
    start: np.ndarray | None = None,
    object_size: float | None = None,
    arm_lengths: ArrayLike | None = None,
) -> ReachResult:
    """The endpoint reach from ``start`` (default: where the model's reaches start,
    :attr:`ReachModel.rest_hand`) to ``end`` (metres, in the moving arm's shoulder frame) for
    either arm; ``start`` is a rest posture, the same for both arms (in the left arm's frame).
    The model is a left-arm model; the body is symmetric about its sagittal plane, so a
    right-arm reach is the left-arm reach to the mirrored target (:data:`MIRROR_Y`), mirrored
    back (:func:`mirror_result`). ``arm_lengths``: the moving arm's segments at the model's
    size (see :meth:`ReachModel.predict`; :func:`humanoid_arm` for a humanoid's).

    Args:
        model: a left-arm endpoint model.
        end: (3,) hand end, metres, moving arm's shoulder frame.
        side: "left" or "right".
        start: (3,) hand start, metres, left arm's frame, or None.
        object_size: grasped object size, metres, or None.
        arm_lengths: (3,) moving arm segments, metres, or None.

    Returns:
        the reach in the moving arm's shoulder frame.
    """
    check_endpoint_model(model)
    start = np.asarray(model.rest_hand if start is None else start, dtype=float)
    if arm_lengths is not None:
        # a rest hand out of this arm's reach (a straight hanging arm of other proportions
        # than the clips') comes onto its reach: a rest posture, not a target
        reach = (1.0 - 1e-6) * float(np.sum(arm_lengths))
        r = float(np.linalg.norm(start))
        if r > reach:
            start = start * (reach / r)
    end = np.asarray(end, dtype=float) * (MIRROR_Y if side == "right" else 1.0)
    res = model.predict(
        np.concatenate((start, end)),
        start=start,
        end=end,
        object_size=object_size,
        arm_lengths=arm_lengths,
    )
    return mirror_result(res) if side == "right" else res


class ReachModel:
    """PCA + DCS model of arm trajectories conditioned on a constraint vector.

    Args:
        lengths: (S,) segment lengths in metres (see :func:`arm_segment_lengths`).
        variance: PCA variance share (or number of modes) for :class:`ArmRepresentation`.
        dcs: keyword arguments of :class:`DCSNetwork`.
        regressor: any object with ``fit(X, Y)``/``predict(X)`` used instead of the DCS (for
            baselines: sklearn KNeighborsRegressor, GaussianProcessRegressor); not saved.
        rest_hand: (3,) where an endpoint model's reaches start (m, left shoulder frame; see
            :attr:`rest_hand`); default: the mean start of its training constraints.
    """

    def __init__(
        self,
        lengths: np.ndarray | None = None,
        variance: float | int = 0.98,
        dcs: dict | None = None,
        regressor=None,
        rest_hand: ArrayLike | None = None,
    ):
        self.lengths = np.asarray(lengths if lengths is not None else arm_segment_lengths())
        self.variance = variance
        self.dcs = dict(dcs or {})
        self.regressor = regressor
        self.rest_hand_ = None if rest_hand is None else _point(rest_hand, "rest_hand")

    @property
    def rest_hand(self) -> np.ndarray:
        """(3,) hand position (m, left shoulder frame; the same rest posture for a mirrored
        right arm) where the reaches of a cycle and of
        :func:`~mjwalk.timeline.reachscene.reach_in_scene` start: given to the constructor, else the
        mean start hand of an endpoint model's training constraints (a model trained on capture
        starts where the clips' reaches start), else :data:`REST_HAND` (the generated default
        model's nominal start, and models saved before this was kept)."""
        if self.rest_hand_ is not None:
            return self.rest_hand_.copy()
        return np.asarray(REST_HAND, dtype=float)

    def fit(
        self,
        constraints: np.ndarray,
        directions: np.ndarray,
        extras: np.ndarray | None = None,
        rep: ArmRepresentation | None = None,
    ) -> ReachModel:
        """Fit on constraints (p, d) and direction trajectories (p, n, S, 3) [+ extras];
        ``rep`` reuses an ArmRepresentation already fitted on the same trajectories.

        Args:
            constraints: (p, d) constraint vectors.
            directions: (p, n, S, 3) unit directions, shoulder frame.
            extras: (p, n, C) extra channels, or None.
            rep: a fitted representation to reuse, or None.

        Returns:
            this model, fitted.
        """
        C = np.asarray(constraints, dtype=float)
        if C.ndim == 1:
            C = C[:, None]
        U = np.asarray(directions, dtype=float)
        if len(C) != len(U):
            raise MjwalkError(f"ReachModel.fit: {len(C)} constraints but {len(U)} trajectories")
        if U.shape[2] != len(self.lengths):
            raise MjwalkError(
                f"ReachModel.fit: trajectories have {U.shape[2]} segments, lengths {self.lengths}"
            )
        self.rep_ = rep if rep is not None else ArmRepresentation(self.variance).fit(U, extras)
        A, poses = self.rep_.align(U)
        b = self.rep_.pca_.transform(self.rep_.to_features(A, extras))
        self.n_modes_ = b.shape[1]
        self.n_inputs_ = C.shape[1]
        if self.rest_hand_ is None and C.shape[1] == ENDPOINT_INPUTS:
            self.rest_hand_ = C[:, :3].mean(axis=0)
        target = np.hstack([b, poses])
        self.net_ = self.regressor if self.regressor is not None else DCSNetwork(**self.dcs)
        self.net_.fit(C, target)
        if not hasattr(self.net_, "distance_to_training"):
            self._scale = C.std(axis=0) + 1e-12
            self._train = C / self._scale
        return self

    @property
    def n_inputs(self) -> int:
        """Length of the constraint vector the model was fitted on."""
        if not hasattr(self, "n_inputs_"):
            raise MjwalkError("ReachModel is not fitted; call fit() or load() first")
        return self.n_inputs_

    @property
    def n_neurons(self) -> int | None:
        return getattr(self.net_, "n_neurons_", None)

    def _distance(self, c: np.ndarray) -> tuple[float, bool, np.ndarray | None]:
        """The constraint's distance to the nearest training constraint (standardized
        units), whether it lies outside the trained range, and the network's (1,) distance
        array (None for a network without one), which :meth:`predict` hands on to it."""
        if hasattr(self.net_, "distance_to_training"):
            d_arr = self.net_.distance_to_training(c[None])
            d = float(d_arr[0])
            return d, d > self.net_.range_radius_, d_arr
        d = float(np.min(np.linalg.norm(self._train - c / self._scale, axis=1)))
        return d, False, None

    def predict(
        self,
        constraint: np.ndarray,
        start: np.ndarray | None = None,
        end: np.ndarray | None = None,
        strict: bool = False,
        object_size: float | None = None,
        arm_lengths: ArrayLike | None = None,
    ) -> ReachResult:
        """Synthesize the movement for one ``constraint`` (d,); with ``start``/``end`` (3,)
        hand positions (metres, shoulder frame) the movement is fitted to them exactly; with
        ``object_size`` (m) the grip aperture (extras channel 0) is blended, with a
        minimum-jerk profile, to close exactly on the object at the end. ``arm_lengths`` (S,)
        m: the segments of the arm that makes the movement (default: the model's ``lengths``),
        for the fit to ``start``/``end`` and ``hand``: an arm of other proportions than the
        clips' (a humanoid's, at the model's size) puts its own hand on the points.

        Args:
            constraint: (d,) constraint vector.
            start: (3,) hand start, metres, shoulder frame, or None.
            end: (3,) hand end, metres, shoulder frame, or None.
            strict: raise outside the trained range instead of warning.
            object_size: object size, metres, or None.
            arm_lengths: (S,) segment lengths, metres, or None (the model's).

        Returns:
            the synthesized movement.
        """
        L = self.lengths if arm_lengths is None else np.asarray(arm_lengths, dtype=float)
        if L.shape != self.lengths.shape or not (L > 0).all():
            raise MjwalkError(
                f"ReachModel.predict: arm_lengths must be {len(self.lengths)} positive lengths "
                f"(m), got {np.asarray(arm_lengths).tolist()}"
            )
        if not hasattr(self, "net_"):
            raise MjwalkError("ReachModel is not fitted; call fit() or load() first")
        c = np.atleast_1d(np.asarray(constraint, dtype=float))
        dist, outside, d_arr = self._distance(c)
        warnings = []
        if outside:
            msg = (
                f"constraint {np.round(c, 4).tolist()} lies outside the trained range: "
                f"{dist:.2f} sd from the nearest training constraint "
                f"(limit {self.net_.range_radius_:.2f})"
            )
            if getattr(self.net_, "fallback_", None) is not None:
                g = float(self.net_.network_weight(c[None])[0])
                msg += f"; the trajectory follows the trend network ({1 - g:.0%})"
            if strict:
                raise MjwalkError(msg)
            warnings.append(msg)
        # (the network's weight reuses the distance found above: one nearest-neighbour query)
        out = np.asarray(
            self.net_.predict(c[None], d_arr)
            if isinstance(self.net_, DCSNetwork) and d_arr is not None
            else self.net_.predict(c[None])
        )[0]
        b, pose = out[: self.n_modes_], out[self.n_modes_ :]
        A, E = self.rep_.inverse_transform(b[None])
        A, E = A[0], (None if E is None else E[0])
        if object_size is not None:
            if E is None:
                raise MjwalkError("ReachModel.predict: object_size needs a grasp model (extras)")
            E = E.copy()
            E[:, 0] += min_jerk_steps(len(E)) * (object_size - E[-1, 0])
        if start is not None or end is not None:
            pose = self._fit_endpoints(A, pose, start, end, L)
        U = apply_pose(self.rep_.center_, A, pose)
        if start is not None or end is not None:
            U, note = self._ik_correct(U, start, end, L)
            warnings += note
        return ReachResult(
            directions=U,
            hand=end_effector(U, L),
            extras=E,
            coefficients=b,
            distance=dist,
            outside=outside,
            warnings=warnings,
        )

    def _fit_endpoints(self, A, pose0, start, end, lengths):
        idx, points = [], []
        if start is not None:
            idx.append(0)
            points.append(np.asarray(start, dtype=float))
        if end is not None:
            idx.append(len(A) - 1)
            points.append(np.asarray(end, dtype=float))
        tgt = np.array(points)
        Asub = A[idx]

        def resid(x):
            return (end_effector(apply_pose(self.rep_.center_, Asub, x), lengths) - tgt).ravel()

        lb, ub = _POSE_LB.copy(), _POSE_UB.copy()
        x0 = np.clip(pose0, _POSE_LB + 1e-9, _POSE_UB - 1e-9)
        # compiled Levenberg-Marquardt (the same residual); scipy's bounded solver where it
        # does not converge or the scale ends on its bound
        x, ok = fit_endpoint_pose(self.rep_.center_, Asub, lengths, tgt, x0, (-1.0, 1.0))
        if ok:
            return x
        return least_squares(resid, x0, bounds=(lb, ub)).x

    def _ik_correct(self, U, start, end, lengths):
        """Blend the start/end hand errors out with a minimum-jerk profile (analytic IK)."""
        n = len(U)
        hand = end_effector(U, lengths)
        e0 = np.zeros(3) if start is None else np.asarray(start) - hand[0]
        e1 = np.zeros(3) if end is None else np.asarray(end) - hand[-1]
        w = min_jerk_steps(n)[:, None]
        delta = (1 - w) * e0 + w * e1
        l1, l2 = lengths[:2]
        out = U.copy()
        wrist_target = hand + delta
        if len(lengths) > 2:
            wrist_target = wrist_target - end_effector(U[:, 2:], lengths[2:])
        far = np.flatnonzero(np.linalg.norm(wrist_target, axis=1) > l1 + l2 - 1e-6)
        notes = [f"frame {far[0]}: hand target out of reach, clamped"] if len(far) else []
        out[:, 0], out[:, 1] = two_link_ik_rows(wrist_target, l1, l2, U[:, 0] * l1)
        return out, notes

    # ------------------------------------------------------------ persistence
    def save(self, path: str | Path) -> None:
        """Write the model (representation + DCS) to one versioned ``.npz`` (atomically).

        Args:
            path: the ``.npz`` file to write.
        """
        if not isinstance(getattr(self, "net_", None), DCSNetwork):
            raise MjwalkError("ReachModel.save: only a fitted DCS-based model can be saved")
        arrays = dict(self.rep_.to_arrays())
        arrays.update({f"dcs_{k}": v for k, v in self.net_.to_arrays().items()})
        arrays["lengths"] = self.lengths
        if self.rest_hand_ is not None:
            arrays["rest_hand"] = self.rest_hand_
        header = {
            "format": REACH_FORMAT,
            "version": REACH_VERSION,
            "n_modes": int(self.n_modes_),
            "variance": self.variance,
            "dcs_header": self.net_.header(),
        }
        save_npz(path, header, arrays)

    @classmethod
    def load(cls, path: str | Path) -> ReachModel:
        """Read a model written by :meth:`save`; corrupt/foreign files raise ModelFileError.

        Args:
            path: the ``.npz`` file.

        Returns:
            the fitted model.
        """
        header, data = load_npz(path, "reach-model")
        check_header(header, path, "reach-model", REACH_FORMAT, REACH_VERSION)
        try:
            model = cls(lengths=data["lengths"], variance=header["variance"])
            model.rep_ = ArmRepresentation.from_arrays(data)
            model.n_modes_ = int(header["n_modes"])
            dcs_data = {k[4:]: v for k, v in data.items() if k.startswith("dcs_")}
            model.net_ = DCSNetwork.from_arrays(header["dcs_header"], dcs_data, source=str(path))
            model.n_inputs_ = len(model.net_.x_mean_)
            if "rest_hand" in data:
                model.rest_hand_ = _point(data["rest_hand"], f"{path}: rest_hand", ModelFileError)
        except (KeyError, ValueError, TypeError) as exc:
            raise ModelFileError(f"{path}: corrupt reach model ({exc})") from exc
        return model
