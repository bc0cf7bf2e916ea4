"""mjwalk.ergonomics.anglejit: the compiled angles equal the NumPy code they replace bit for bit
(that code, as it was before the kernels, is kept below as the reference)."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.body.humanoid import humanoid_model, pelvis_height
from mjwalk.ergonomics.anglejit import KERNEL_POINTS
from mjwalk.ergonomics.angles import (
    ABDUCTION_PLANE_DEG,
    FOOT_UP,
    OUT_TO_SIDE_SHARE,
    BodyAngles,
    angles_from_points,
    angles_from_qpos,
    body_frames,
)
from mjwalk.timeline.geomposes import geom_table

# --- the NumPy reference (mjwalk/ergonomics/angles.py at a88f200) ---
_BODY_POINTS = {
    "pelvis": "pelvis", "neck": "neck", "upper_arm_l": "shoulder_l", "upper_arm_r": "shoulder_r",
    "forearm_l": "elbow_l", "forearm_r": "elbow_r", "hand_l": "wrist_l", "hand_r": "wrist_r",
    "thigh_l": "hip_l", "thigh_r": "hip_r", "shin_l": "knee_l", "shin_r": "knee_r",
    "foot_l": "ankle_l", "foot_r": "ankle_r",
}  # fmt: skip


def _unit(v: np.ndarray) -> np.ndarray:
    n = np.sqrt(_dot(v, v))[..., None]
    return v / np.where(n > 1e-12, n, 1.0)


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1] + a[..., 2] * b[..., 2]


def _deg(x: np.ndarray) -> np.ndarray:
    return np.degrees(x)


def _trunk_angles(p: dict[str, np.ndarray]) -> tuple[np.ndarray, ...]:
    """The pelvis' left and forward axes and the trunk's flexion, side bend, inclination and
    twist (degrees) of joint positions ``p``, with the trunk axis and the shoulder line."""
    z = np.array([0.0, 0.0, 1.0])
    hip_left = p["hip_l"] - p["hip_r"]
    hip_left[:, 2] = 0.0
    hip_left = _unit(hip_left)
    fwd = np.cross(hip_left, z)  # x = y cross z
    trunk = _unit(p["neck"] - p["pelvis"])
    t_flex = _deg(np.arctan2(_dot(trunk, fwd), trunk[:, 2]))
    t_side = _deg(np.arctan2(_dot(trunk, hip_left), trunk[:, 2]))
    t_incl = _deg(np.arccos(np.clip(trunk[:, 2], -1.0, 1.0)))
    sh = p["shoulder_l"] - p["shoulder_r"]
    twist = np.arctan2(sh[:, 1], sh[:, 0]) - np.arctan2(hip_left[:, 1], hip_left[:, 0])
    t_twist = _deg((twist + np.pi) % (2 * np.pi) - np.pi)
    return fwd, trunk, sh, t_flex, t_side, t_incl, t_twist


def _arm_angles(
    p: dict[str, np.ndarray], up: np.ndarray, left: np.ndarray, front: np.ndarray
) -> tuple[np.ndarray, ...]:
    """(F, 2) upper-arm angle, elevation and plane, elbow flexion (degrees) and the
    lower-arm-out flag of both arms in the trunk's frame (``up``, ``left``, ``front``)."""
    n = len(up)
    ua_angle = np.zeros((n, 2))
    ua_elev = np.zeros((n, 2))
    ua_plane = np.zeros((n, 2))
    elbow = np.zeros((n, 2))
    out = np.zeros((n, 2), dtype=bool)
    centre = 0.5 * (p["shoulder_l"] + p["shoulder_r"])
    for s, tag in enumerate(("l", "r")):
        outward = left if s == 0 else -left
        u = p[f"elbow_{tag}"] - p[f"shoulder_{tag}"]
        f = p[f"wrist_{tag}"] - p[f"elbow_{tag}"]
        uu = _unit(u)
        down_c, fwd_c, out_c = -_dot(uu, up), _dot(uu, front), _dot(uu, outward)
        elev = _deg(np.arccos(np.clip(down_c, -1.0, 1.0)))
        plane = _deg(np.arctan2(np.abs(out_c), np.abs(fwd_c)))
        behind = (fwd_c < 0) & (plane <= ABDUCTION_PLANE_DEG)  # raised mainly backwards
        ua_angle[:, s] = np.where(behind, -elev, elev)
        ua_plane[:, s] = plane
        ua_elev[:, s] = _deg(np.arccos(np.clip(-uu[:, 2], -1.0, 1.0)))
        elbow[:, s] = _deg(np.arccos(np.clip(_dot(uu, _unit(f)), -1.0, 1.0)))
        lat = _dot(p[f"wrist_{tag}"] - centre, outward)  # outward of the trunk's midline
        sh_lat = _dot(p[f"shoulder_{tag}"] - centre, outward)
        u_len = np.linalg.norm(u, axis=-1)
        out[:, s] = (lat < 0.0) | (lat - sh_lat > OUT_TO_SIDE_SHARE * u_len)
    return ua_angle, ua_elev, ua_plane, elbow, out


def _leg_angles(p: dict[str, np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """(F, 2) knee flexion (degrees) and feet-on-the-floor flags of both legs."""
    n = len(p["pelvis"])
    knee = np.zeros((n, 2))
    down = np.zeros((n, 2), dtype=bool)
    for s, tag in enumerate(("l", "r")):
        th = _unit(p[f"knee_{tag}"] - p[f"hip_{tag}"])
        sn = _unit(p[f"ankle_{tag}"] - p[f"knee_{tag}"])
        knee[:, s] = _deg(np.arccos(np.clip(_dot(th, sn), -1.0, 1.0)))
        az = p[f"ankle_{tag}"][:, 2]
        down[:, s] = az <= az.min(initial=np.inf) + FOOT_UP
    return knee, down


def reference_angles(
    p: dict[str, np.ndarray],
    *,
    head_up: np.ndarray | None = None,
    hands: np.ndarray | None = None,
    wrist: np.ndarray | None = None,
    neck_twist: np.ndarray | None = None,
    twist_range: float = 80.0,
    walking: np.ndarray | None = None,
) -> BodyAngles:
    """Body angles of F frames from joint positions (frames as in the module docstring).

    Args:
        p: the joints :data:`POINTS`, each (F, 3), metres, world frame z up.
        head_up: (F, 3) the head's up direction (default: neck -> head).
        hands: (F, 2, 3) the grip points, world metres (default: the wrists).
        wrist: (F, 2, 3) wrist flexion, ulnar deviation and forearm pronation, degrees
            (default zeros: positions alone do not show them).
        neck_twist: (F,) the neck's axial rotation, degrees (default zeros).
        twist_range: the forearm rotation's half range, degrees.
        walking: (F,) frames of a walk (default none).

    Returns:
        The :class:`BodyAngles` of the F frames.
    """
    n = len(p["pelvis"])
    fwd, trunk, sh, t_flex, t_side, t_incl, t_twist = _trunk_angles(p)
    # the trunk's frame: up the trunk axis, left the shoulder line made orthogonal to it
    up = trunk
    left = _unit(sh - _dot(sh, up)[:, None] * up)
    front = np.cross(left, up)
    # neck
    hu = _unit(head_up if head_up is not None else p["head"] - p["neck"])
    n_flex = _deg(np.arctan2(_dot(hu, front), _dot(hu, up)))
    n_side = _deg(np.arctan2(_dot(hu, left), _dot(hu, up)))
    ua_angle, ua_elev, ua_plane, elbow, out = _arm_angles(p, up, left, front)
    knee, down = _leg_angles(p)
    w = np.zeros((n, 2, 3)) if wrist is None else np.asarray(wrist, dtype=float)
    return BodyAngles(
        trunk_flexion=t_flex,
        trunk_side_bend=t_side,
        trunk_twist=t_twist,
        trunk_inclination=t_incl,
        neck_flexion=n_flex,
        neck_side_bend=n_side,
        neck_twist=np.zeros(n) if neck_twist is None else np.asarray(neck_twist, dtype=float),
        upper_arm_angle=ua_angle,
        upper_arm_elevation=ua_elev,
        upper_arm_plane=ua_plane,
        elbow_flexion=elbow,
        wrist_flexion=w[:, :, 0],
        wrist_deviation=w[:, :, 1],
        wrist_twist=w[:, :, 2],
        twist_range=float(twist_range),
        knee_flexion=knee,
        feet_down=down,
        walking=np.zeros(n, dtype=bool) if walking is None else np.asarray(walking, dtype=bool),
        hands=np.stack([p["wrist_l"], p["wrist_r"]], axis=1) if hands is None else hands,
        ankles=0.5 * (p["ankle_l"] + p["ankle_r"]),
        forward=fwd,
        shoulder_raised=np.zeros((n, 2), dtype=bool),
        lower_arm_out=out,
    )


def _assert_same(a: BodyAngles, b: BodyAngles) -> None:
    for name in a.__dataclass_fields__:
        x, y = np.asarray(getattr(a, name)), np.asarray(getattr(b, name))
        assert x.shape == y.shape, name
        assert np.array_equal(x, y, equal_nan=True), name  # the same floats, not close ones


def _motion(n: int = 400, seed: int = 0):
    """A humanoid moving every hinge at random (smoothly), with its model and joint map."""
    model, jm = humanoid_model()
    q = jm.neutral_qpos(model)
    q[jm.root + 2] = pelvis_height(1.75)
    rng = np.random.default_rng(seed)
    qpos = np.tile(q, (n, 1))
    t = np.linspace(0.0, 1.0, n)
    for j in range(jm.root + 7, model.nq):
        qpos[:, j] += 0.6 * np.sin(2 * np.pi * (rng.uniform(0.5, 3.0) * t + rng.uniform()))
    qpos[:, jm.root : jm.root + 3] += rng.normal(0.0, 0.3, 3)
    return model, jm, qpos


def test_points_give_the_reference_angles_bit_for_bit():
    """Random joint positions (and near-degenerate ones: a zero-length hip line, an arm along
    the trunk) give exactly the reference's floats."""
    rng = np.random.default_rng(1)
    n = 500
    p = {k: rng.normal(0.0, 0.4, (n, 3)) for k in (*KERNEL_POINTS, "head")}
    p["hip_r"][:5] = p["hip_l"][:5]
    p["elbow_l"][5:10] = p["shoulder_l"][5:10]
    kw = dict(walking=rng.random(n) < 0.3, twist_range=75.0)
    _assert_same(angles_from_points(p, **kw), reference_angles(p, **kw))


@pytest.mark.parametrize("seed", [0, 1])
def test_humanoid_angles_equal_the_reference_bit_for_bit(seed):
    """angles_from_qpos (the geom table read in place, the compiled pass) gives what the
    reference gives on body_frames' points, with and without a shared geom table."""
    model, jm, qpos = _motion(seed=seed)
    bodies = list(_BODY_POINTS)
    pos, rot = body_frames(model, jm, qpos, bodies)
    p = {_BODY_POINTS[b]: pos[:, k] for k, b in enumerate(bodies)}
    head_up = rot[:, bodies.index("neck"), :, 2]
    p["head"] = p["neck"] + head_up
    new = angles_from_qpos(model, jm, qpos)
    hands = np.stack([new.hands[:, 0], new.hands[:, 1]], axis=1)
    q = np.degrees(qpos)
    wrist = np.stack(
        [np.stack([q[:, jm.adr(f"wrist_{t}_flex")], q[:, jm.adr(f"wrist_{t}_dev")],
                   q[:, jm.adr(f"forearm_{t}_pron")]], axis=1) for t in ("l", "r")], axis=1,
    )  # fmt: skip
    lo, hi = jm.limits("forearm_l_pron")
    ref = reference_angles(
        p, head_up=head_up, hands=hands, wrist=wrist, neck_twist=q[:, jm.adr("neck_rot")],
        twist_range=float(np.degrees(max(abs(lo), abs(hi)))),
    )  # fmt: skip
    _assert_same(new, ref)
    for k, t in enumerate(("l", "r")):  # the palms' centres: the hand's origin + R @ offset
        b = bodies.index(f"hand_{t}")
        g = model.geom(jm.prefix + f"palm_{t}").id
        assert np.array_equal(new.hands[:, k], pos[:, b] + rot[:, b] @ model.geom_pos[g])
    table = geom_table(model, qpos, np.arange(model.ngeom))
    _assert_same(angles_from_qpos(model, jm, qpos, table=table), new)
