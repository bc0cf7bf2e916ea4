"""``ReachModel``: constraint -> DCS -> PCA coefficients -> arm trajectory (Al-Zubi & Sommer).

Pipeline of :meth:`ReachModel.predict`:

1. the constraint vector (start/end hand position; obstacle ratio B/A; object size and
   orientation...) goes through a :class:`~mjwalk.body.dcs.DCSNetwork` that returns the PCA
   coefficients ``b`` and the alignment pose of the movement;
2. eq. 1 rebuilds the aligned segment directions, the pose maps them back to the body frame;
3. when the actual start and end hand positions are given, the pose (rotation + angular scale)
   is refit so the hand starts and ends there (the paper's "fitted to a start and end
   position"), then a final analytic IK correction, blended over the movement with a
   minimum-jerk profile, moves the hand onto both points exactly (well within 1 cm);
4. :func:`arm_joint_angles` turns directions (+ forearm roll) into the humanoid's joint angles.

Frames: the body frame at the shoulder of the moving arm, metres, x forward, y left, z up
(the humanoid's thorax frame in its neutral pose). A constraint outside the trained range is
never used silently: the result carries its distance to the training data and a warning, or
``strict=True`` raises :class:`~mjwalk.errors.MjwalkError`.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from scipy.optimize import least_squares
from scipy.spatial.transform import Rotation

from mjwalk._io import check_header, load_npz, save_npz
from mjwalk.arms.armrep import ArmRepresentation, apply_pose
from mjwalk.arms.dcs import DCSNetwork
from mjwalk.conventions import DEFAULT_STATURE
from mjwalk.errors import MjwalkError, ModelFileError

REACH_FORMAT = "mjwalk.reach"
REACH_VERSION = 1

#: Anthropometric segment lengths as shares of stature H (Winter): upper arm, forearm, hand.
ARM_SEGMENT_SHARES = (0.186, 0.146, 0.108)


#: Relaxed hand position (m, left shoulder frame, x fwd, y left, z up) where reaches start.
REST_HAND = (0.15, 0.02, -0.60)


def arm_segment_lengths(stature: float = DEFAULT_STATURE, with_hand: bool = True) -> np.ndarray:
    """Upper arm, forearm (and hand) lengths in metres for a person of ``stature`` metres."""
    shares = ARM_SEGMENT_SHARES if with_hand else ARM_SEGMENT_SHARES[:2]
    return stature * np.asarray(shares)


def chain_points(directions: np.ndarray, lengths: np.ndarray) -> np.ndarray:
    """Joint positions (..., S+1, 3) from the shoulder (origin) along unit segment
    ``directions`` (..., S, 3) with ``lengths`` (S,) metres."""
    seg = directions * np.asarray(lengths)[:, None]
    zero = np.zeros((*directions.shape[:-2], 1, 3))
    return np.concatenate([zero, np.cumsum(seg, axis=-2)], axis=-2)


def end_effector(directions: np.ndarray, lengths: np.ndarray) -> np.ndarray:
    """Hand (end of the chain) position (..., 3), metres from the shoulder."""
    return np.einsum("...sj,s->...j", directions, np.asarray(lengths))


def min_jerk(tau: np.ndarray) -> np.ndarray:
    """Minimum-jerk profile 10 t^3 - 15 t^4 + 6 t^5 on t in [0, 1]."""
    tau = np.clip(tau, 0.0, 1.0)
    return tau**3 * (10 - 15 * tau + 6 * tau**2)


def two_link_ik(
    target: np.ndarray, l1: float, l2: float, elbow_hint: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Unit directions (upper arm, forearm) putting the wrist at ``target`` (3,) from the
    shoulder, with the elbow in the plane of the shoulder-wrist axis and ``elbow_hint`` (the
    swivel angle of the hint is kept). Unreachable targets are clamped to the workspace."""
    d = float(np.linalg.norm(target))
    d = float(np.clip(d, abs(l1 - l2) + 1e-6, l1 + l2 - 1e-6))
    axis = target / max(np.linalg.norm(target), 1e-9)
    perp = elbow_hint - (elbow_hint @ axis) * axis
    if np.linalg.norm(perp) < 1e-9:
        perp = np.cross(axis, [0.0, 1.0, 0.0])
        if np.linalg.norm(perp) < 1e-9:
            perp = np.cross(axis, [1.0, 0.0, 0.0])
    perp /= np.linalg.norm(perp)
    a = (l1**2 - l2**2 + d**2) / (2 * d)
    h = np.sqrt(max(l1**2 - a**2, 0.0))
    elbow = a * axis + h * perp
    wrist = d * axis
    return elbow / l1, (wrist - elbow) / l2


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


class ReachModel:
    """PCA + DCS model of arm trajectories conditioned on a constraint vector.

    Args:
        lengths: (S,) segment lengths in metres (see :func:`arm_segment_lengths`).
        variance: PCA variance share (or number of modes) for :class:`ArmRepresentation`.
        dcs: keyword arguments of :class:`DCSNetwork`.
        regressor: any object with ``fit(X, Y)``/``predict(X)`` used instead of the DCS (for
            baselines: sklearn KNeighborsRegressor, GaussianProcessRegressor); not saved.
    """

    def __init__(
        self,
        lengths: np.ndarray | None = None,
        variance: float | int = 0.98,
        dcs: dict | None = None,
        regressor=None,
    ):
        self.lengths = np.asarray(lengths if lengths is not None else arm_segment_lengths())
        self.variance = variance
        self.dcs = dict(dcs or {})
        self.regressor = regressor

    def fit(
        self,
        constraints: np.ndarray,
        directions: np.ndarray,
        extras: np.ndarray | None = None,
        rep: ArmRepresentation | None = None,
    ) -> ReachModel:
        """Fit on constraints (p, d) and direction trajectories (p, n, S, 3) [+ extras];
        ``rep`` reuses an ArmRepresentation already fitted on the same trajectories."""
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
        target = np.hstack([b, poses])
        self.net_ = self.regressor if self.regressor is not None else DCSNetwork(**self.dcs)
        self.net_.fit(C, target)
        if not hasattr(self.net_, "distance_to_training"):
            self._scale = C.std(axis=0) + 1e-12
            self._train = C / self._scale
        return self

    @property
    def n_neurons(self) -> int | None:
        return getattr(self.net_, "n_neurons_", None)

    def _distance(self, c: np.ndarray) -> tuple[float, bool]:
        if hasattr(self.net_, "distance_to_training"):
            d = float(self.net_.distance_to_training(c[None])[0])
            return d, d > self.net_.range_radius_
        d = float(np.min(np.linalg.norm(self._train - c / self._scale, axis=1)))
        return d, False

    def predict(
        self,
        constraint: np.ndarray,
        start: np.ndarray | None = None,
        end: np.ndarray | None = None,
        strict: bool = False,
        object_size: float | None = None,
    ) -> ReachResult:
        """Synthesize the movement for one ``constraint`` (d,); with ``start``/``end`` (3,)
        hand positions (metres, shoulder frame) the movement is fitted to them exactly; with
        ``object_size`` (m) the grip aperture (extras channel 0) is blended, with a
        minimum-jerk profile, to close exactly on the object at the end."""
        if not hasattr(self, "net_"):
            raise MjwalkError("ReachModel is not fitted; call fit() or load() first")
        c = np.atleast_1d(np.asarray(constraint, dtype=float))
        dist, outside = self._distance(c)
        warnings = []
        if outside:
            msg = (
                f"constraint {np.round(c, 4).tolist()} lies outside the trained range: "
                f"{dist:.2f} sd from the nearest training constraint "
                f"(limit {self.net_.range_radius_:.2f})"
            )
            if strict:
                raise MjwalkError(msg)
            warnings.append(msg)
        out = np.asarray(self.net_.predict(c[None]))[0]
        b, pose = out[: self.n_modes_], out[self.n_modes_ :]
        A, E = self.rep_.inverse_transform(b[None])
        A, E = A[0], (None if E is None else E[0])
        if object_size is not None:
            if E is None:
                raise MjwalkError("ReachModel.predict: object_size needs a grasp model (extras)")
            E = E.copy()
            E[:, 0] += min_jerk(np.linspace(0, 1, len(E))) * (object_size - E[-1, 0])
        if start is not None or end is not None:
            pose = self._fit_endpoints(A, pose, start, end)
        U = apply_pose(self.rep_.center_, A, pose)
        if start is not None or end is not None:
            U, note = self._ik_correct(U, start, end)
            warnings += note
        return ReachResult(
            directions=U,
            hand=end_effector(U, self.lengths),
            extras=E,
            coefficients=b,
            distance=dist,
            outside=outside,
            warnings=warnings,
        )

    def _fit_endpoints(self, A, pose0, start, end):
        idx, tgt = [], []
        if start is not None:
            idx.append(0)
            tgt.append(np.asarray(start, dtype=float))
        if end is not None:
            idx.append(len(A) - 1)
            tgt.append(np.asarray(end, dtype=float))
        tgt = np.array(tgt)
        Asub = A[idx]

        def resid(x):
            return (
                end_effector(apply_pose(self.rep_.center_, Asub, x), self.lengths) - tgt
            ).ravel()

        lb = np.r_[-np.inf, -np.inf, -np.inf, -1.0]
        ub = np.r_[np.inf, np.inf, np.inf, 1.0]
        x0 = np.clip(pose0, lb + 1e-9, ub - 1e-9)
        return least_squares(resid, x0, bounds=(lb, ub)).x

    def _ik_correct(self, U, start, end):
        """Blend the start/end hand errors out with a minimum-jerk profile (analytic IK)."""
        n = len(U)
        hand = end_effector(U, self.lengths)
        e0 = np.zeros(3) if start is None else np.asarray(start) - hand[0]
        e1 = np.zeros(3) if end is None else np.asarray(end) - hand[-1]
        w = min_jerk(np.linspace(0, 1, n))[:, None]
        delta = (1 - w) * e0 + w * e1
        l1, l2 = self.lengths[:2]
        out = U.copy()
        notes = []
        for t in range(n):
            wrist_target = hand[t] + delta[t]
            if len(self.lengths) > 2:
                wrist_target = wrist_target - end_effector(U[t, 2:], self.lengths[2:])
            if np.linalg.norm(wrist_target) > l1 + l2 - 1e-6:
                notes.append(f"frame {t}: hand target out of reach, clamped")
            elbow_hint = U[t, 0] * l1
            out[t, 0], out[t, 1] = two_link_ik(wrist_target, l1, l2, elbow_hint)
        return out, notes[:1]

    # ------------------------------------------------------------ persistence
    def save(self, path: str | Path) -> None:
        """Write the model (representation + DCS) to one versioned ``.npz`` (atomically)."""
        if not isinstance(getattr(self, "net_", None), DCSNetwork):
            raise MjwalkError("ReachModel.save: only a fitted DCS-based model can be saved")
        arrays = dict(self.rep_.to_arrays())
        arrays.update({f"dcs_{k}": v for k, v in self.net_._arrays().items()})
        arrays["lengths"] = self.lengths
        header = {
            "format": REACH_FORMAT,
            "version": REACH_VERSION,
            "n_modes": int(self.n_modes_),
            "variance": self.variance,
            "dcs_header": self.net_._header(),
        }
        save_npz(path, header, arrays)

    @classmethod
    def load(cls, path: str | Path) -> ReachModel:
        """Read a model written by :meth:`save`; corrupt/foreign files raise ModelFileError."""
        header, data = load_npz(path, "reach-model")
        check_header(header, path, "reach-model", REACH_FORMAT, REACH_VERSION)
        try:
            model = cls(lengths=data["lengths"], variance=header["variance"])
            model.rep_ = ArmRepresentation.from_arrays(data)
            model.n_modes_ = int(header["n_modes"])
            dcs_data = {k[4:]: v for k, v in data.items() if k.startswith("dcs_")}
            model.net_ = DCSNetwork.from_arrays(header["dcs_header"], dcs_data, source=str(path))
        except (KeyError, ValueError, TypeError) as exc:
            raise ModelFileError(f"{path}: corrupt reach model ({exc})") from exc
        return model


# ---------------------------------------------------------------- joint angles
#: Joint names of one arm of the mjwalk humanoid (mjwalk.body.humanoid), in output order.
ARM_JOINTS = (
    "shoulder_flex",
    "shoulder_abd",
    "shoulder_rot",
    "elbow",
    "forearm_pron",
    "wrist_flex",
    "wrist_dev",
)


def arm_joint_angles(
    directions: np.ndarray, side: str = "l", roll: np.ndarray | None = None
) -> np.ndarray:
    """Humanoid arm joint angles (n, 7) in radians, order :data:`ARM_JOINTS`, from segment
    directions (n, S, 3) in the thorax frame (x forward, y left, z up; S = 2 or 3) and an
    optional forearm roll (n,) (pronation, radians).

    The humanoid's chain (mjwalk.body.humanoid) is R_sh = Ry(-flex) Rx(s abd) Rz(-s rot) with
    the arm along -z, elbow Ry(-elbow), pronation Rz(-s pron), wrist Ry(-flex) Rx(s dev), with
    s = +1 for the left and -1 for the right arm. The upper arm's twist is the one that puts
    the forearm in the elbow's flexion plane; when the elbow is straight it is carried over
    from the previous frame.
    """
    s = 1.0 if side == "l" else -1.0
    U = np.asarray(directions, dtype=float)
    n = len(U)
    q = np.zeros((n, 7))
    prev_x = None
    for t in range(n):
        u1, u2 = U[t, 0], U[t, 1]
        z = -u1
        x = u2 - (u2 @ u1) * u1
        if np.linalg.norm(x) < 1e-3:
            x = prev_x if prev_x is not None else np.array([1.0, 0.0, 0.0])
            x = x - (x @ z) * z
        x /= np.linalg.norm(x)
        prev_x = x
        y = np.cross(z, x)
        r_sh = Rotation.from_matrix(np.column_stack([x, y, z]))
        a, b, c = r_sh.as_euler("YXZ")
        elbow = float(np.arccos(np.clip(u1 @ u2, -1, 1)))
        pron = 0.0 if roll is None else float(roll[t])
        q[t, :5] = [-a, s * b, -s * c, elbow, pron]
        if U.shape[1] > 2:
            r_fa = r_sh * Rotation.from_euler("YZ", [-elbow, -s * pron])
            h = r_fa.inv().apply(U[t, 2])
            beta = np.arcsin(np.clip(h[1], -1, 1))
            q[t, 5] = np.arctan2(h[0], -h[2])
            q[t, 6] = s * beta
    q[:, 0] = np.unwrap(q[:, 0])
    q[:, 2] = np.unwrap(q[:, 2])
    return q


# ---------------------------------------------------------------- fingers
_FINGERS = ("index", "middle", "ring", "little")
#: Joint angles (rad) of the one-parameter grip synergy at closure g = 0 (open) and g = 1.
_OPEN_CMC, _CLOSED_FLEX = 1.1, 1.0


@functools.lru_cache(maxsize=4)
def _hand_model(stature: float):
    import mujoco

    from mjwalk.body.humanoid import humanoid_model

    model, jmap = humanoid_model(stature)
    return model, jmap, mujoco.MjData(model)


def grip_synergy(closure: float, side: str = "l") -> dict[str, float]:
    """Finger joint angles (rad) of the grip synergy at ``closure`` in [0, 1]: the thumb's
    opposition (CMC) closes from 63 deg to 0 while the four fingers flex (MCP = PIP = phi,
    DIP = 0.7 phi, phi up to 57 deg) and the thumb MCP/IP flex to half that."""
    g = float(np.clip(closure, 0.0, 1.0))
    phi = _CLOSED_FLEX * g
    q = {f"thumb_{side}_cmc": _OPEN_CMC * (1 - g)}
    q[f"thumb_{side}_mcp"] = 0.5 * phi * 0.8
    q[f"thumb_{side}_ip"] = 0.5 * phi
    for f in _FINGERS:
        q[f"{f}_{side}_mcp"] = phi
        q[f"{f}_{side}_pip"] = phi
        q[f"{f}_{side}_dip"] = 0.7 * phi
    return q


def pinch_aperture(
    finger_q: dict[str, float], side: str = "l", stature: float = DEFAULT_STATURE
) -> float:
    """Distance (m) between the thumb tip and the index fingertip of the humanoid hand for the
    given finger joint angles (forward kinematics of mjwalk.body.humanoid in MuJoCo)."""
    import mujoco

    model, jmap, data = _hand_model(round(float(stature), 4))
    q = jmap.neutral_qpos(model, stature)
    for name, v in finger_q.items():
        q[jmap.adr(name)] = v
    data.qpos[:] = q
    mujoco.mj_kinematics(model, data)

    def tip(body, length):
        b = model.body(body).id
        return data.xpos[b] + data.xmat[b].reshape(3, 3) @ np.array([0.0, 0.0, -length * stature])

    return float(
        np.linalg.norm(tip(f"index_{side}_dip_seg", 0.011) - tip(f"thumb_{side}_tip", 0.015))
    )


def fingers_for_aperture(
    aperture: float, side: str = "l", stature: float = DEFAULT_STATURE
) -> dict:
    """Finger joint angles (rad) whose thumb-index distance equals ``aperture`` metres (to
    0.1 mm) along the grip synergy; apertures outside the hand's range raise MjwalkError."""
    from scipy.optimize import brentq

    lo = pinch_aperture(grip_synergy(1.0, side), side, stature)
    hi = pinch_aperture(grip_synergy(0.0, side), side, stature)
    if not lo <= aperture <= hi:
        raise MjwalkError(
            f"grip aperture {aperture * 100:.1f} cm outside the hand's range "
            f"{lo * 100:.1f}-{hi * 100:.1f} cm (stature {stature} m)"
        )
    g = brentq(
        lambda c: pinch_aperture(grip_synergy(c, side), side, stature) - aperture,
        0.0,
        1.0,
        xtol=1e-6,
    )
    return grip_synergy(g, side)


def finger_trajectory(
    apertures: np.ndarray, side: str = "l", stature: float = DEFAULT_STATURE
) -> dict:
    """Finger joint angles over time: {joint name: (n,) radians} for grip ``apertures`` (n,)
    metres (clipped to the hand's range)."""
    lo = pinch_aperture(grip_synergy(0.95, side), side, stature)
    hi = pinch_aperture(grip_synergy(0.0, side), side, stature)
    frames = [fingers_for_aperture(float(np.clip(a, lo, hi)), side, stature) for a in apertures]
    return {k: np.array([f[k] for f in frames]) for k in frames[0]}


# ---------------------------------------------------------------- in a scene
def arm_frames(
    q0: np.ndarray, jm, q: np.ndarray, side: str, times: np.ndarray
) -> tuple[np.ndarray, list[str]]:
    """Poses (len(times), nq): ``q0`` with one arm's joint angles ``q`` (n, 7), order
    :data:`ARM_JOINTS`, radians) sampled evenly over [0, 1], interpolated at ``times`` in [0, 1]
    and clipped to the humanoid's joint ranges; and the names of the joints that were clipped."""
    src = np.linspace(0.0, 1.0, len(q))
    out = np.repeat(np.asarray(q0)[None], len(times), axis=0)
    clipped = []
    for k, name in enumerate(ARM_JOINTS):
        part, *rest = name.split("_")
        jn = "_".join([part, side, *rest])  # "shoulder_flex" -> "shoulder_l_flex"
        qi = np.interp(times, src, q[:, k])
        lo, hi = jm.limits(jn)
        if (qi < lo - 1e-6).any() or (qi > hi + 1e-6).any():
            clipped.append(jn)
        out[:, jm.adr(jn)] = np.clip(qi, lo, hi)
    return out, clipped


def _site_pose(model, name: str):
    import mujoco

    sid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SITE, name)
    if sid < 0:
        raise MjwalkError(f"scene has no site {name!r}")
    return model.site_pos[sid], model.site_quat[sid], sid


def reach_in_scene(
    scene,
    model: ReachModel,
    stand_site: str,
    target_site: str,
    constraint: np.ndarray | None = None,
    side: str = "l",
    stature: float = DEFAULT_STATURE,
    duration: float = 1.2,
    fps: float = 30.0,
    target_offset: np.ndarray = (0.0, 0.0, 0.0),
    object_size: float | None = None,
):
    """A :class:`~mjwalk.playback.Timeline` of the humanoid standing at ``stand_site`` (facing
    the site's +x) and reaching its ``side`` hand to ``target_site`` (+ ``target_offset``,
    world metres): the hand starts at :data:`REST_HAND` (relaxed, elbow slightly bent; the
    start of :mod:`~mjwalk.body.reachgen` reaches) and ends on the target within
    1 cm; joint angles outside the humanoid's ranges are clipped (noted in ``meta``).

    ``constraint`` defaults to the start and end hand positions (an ``"endpoints"`` model); for
    an ``"obstacle"`` or ``"grasp"`` model pass its constraint vector. Returns
    ``(timeline, result)`` with ``result`` the :class:`ReachResult` in the shoulder frame.
    """
    import mujoco

    from mjwalk.body.humanoid import attach_humanoid, pelvis_height
    from mjwalk.timeline.frames import Timeline, yaw_quat

    if side != "l":
        raise MjwalkError("reach_in_scene: models are trained for the left arm; mirror first")
    mj, jm = attach_humanoid(scene, stature)
    _site_pose(mj, stand_site)
    data = mujoco.MjData(mj)
    mujoco.mj_kinematics(mj, data)  # site_xpos of bodies' sites need the kinematics
    sid_stand = mujoco.mj_name2id(mj, mujoco.mjtObj.mjOBJ_SITE, stand_site)
    sid_target = mujoco.mj_name2id(mj, mujoco.mjtObj.mjOBJ_SITE, target_site)
    if sid_target < 0:
        raise MjwalkError(f"scene has no site {target_site!r}")
    xmat = data.site_xmat[sid_stand].reshape(3, 3)
    yaw = float(np.arctan2(xmat[1, 0], xmat[0, 0]))
    q0 = jm.neutral_qpos(mj, stature)
    r = jm.root
    q0[r : r + 3] = [
        data.site_xpos[sid_stand][0],
        data.site_xpos[sid_stand][1],
        pelvis_height(stature),
    ]
    q0[r + 3 : r + 7] = yaw_quat(np.array([yaw]))[0]
    data.qpos[:] = q0
    mujoco.mj_kinematics(mj, data)
    prefix = jm.prefix
    ua = mj.body(f"{prefix}upper_arm_{side}").id
    shoulder = data.xpos[ua].copy()
    frame = data.xmat[ua].reshape(3, 3).copy()  # shoulder frame at zero shoulder angles
    target_w = data.site_xpos[sid_target] + np.asarray(target_offset, dtype=float)
    end = frame.T @ (target_w - shoulder)
    start = np.asarray(REST_HAND, dtype=float)
    c = np.r_[start, end] if constraint is None else np.asarray(constraint, dtype=float)
    res = model.predict(c, start=start, end=end, object_size=object_size)
    q = arm_joint_angles(res.directions, side, None if res.extras is None else res.extras[:, 1])
    n_out = max(2, round(duration * fps) + 1)
    src = np.linspace(0.0, 1.0, len(q))
    dst = np.linspace(0.0, 1.0, n_out)
    qpos, clipped = arm_frames(q0, jm, q, side, dst)
    if res.extras is not None:
        ap = np.interp(dst, src, res.extras[:, 0])
        for name, vals in finger_trajectory(ap, side, stature).items():
            qpos[:, jm.adr(name)] = vals
    tl = Timeline(
        model=mj,
        jointmap=jm,
        fps=fps,
        t=dst * duration,
        qpos=qpos,
        scene=str(scene),
        stature=stature,
    )
    tl.meta = {
        "clipped_joints": clipped,
        "target_world": target_w,
        "shoulder": shoulder,
        "frame": frame,
    }
    return tl, res
