"""The mjwalk humanoid: an adult digital human model built as a ``mujoco.MjSpec``.

Frames and units: metres, radians, z up. In its own frame the humanoid faces **+x**, its left is
**+y**; the free root joint sits at the pelvis (hip-joint-centre height), so a root quaternion
that is a pure rotation about z by ``yaw`` makes the humanoid face ``yaw`` (from +x, CCW). In the
neutral pose (all joint angles 0, root z = :func:`pelvis_height`) the soles rest on z = 0.

Joint sign convention (anatomical): positive = flexion / abduction / internal rotation /
dorsiflexion / inversion / pronation / ulnar deviation, for both sides.

Collision filtering (documented choice). Scene geoms keep MuJoCo's default
``contype = conaffinity = 1``. Every humanoid geom has ``contype = 2, conaffinity = 1`` and
``group = 5``. MuJoCo collides two geoms when ``(c1.contype & c2.conaffinity) or
(c2.contype & c1.conaffinity)`` is non-zero:

* human vs human: ``2 & 1 = 0`` both ways -> never (no self-collision);
* human vs scene: ``scene.contype (1) & human.conaffinity (1) = 1`` -> collides.

The group (5) and the name prefix (``human/``) let the world module leave the humanoid out of the
obstacles.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from pathlib import Path

import mujoco
import numpy as np

from mjwalk._io import atomic_path

# The humanoid's body figures live in mjwalk.anthropometry (lower stages need them too).
from mjwalk.anthropometry import (  # noqa: F401  re-exported
    FINGERS,
    ROM_DEG,
    SEG,
    SHIN_RADIUS,
    UPPER_ARM_RADIUS,
    LegGeometry,
    leg_geometry,
    pelvis_height,
    shoulder_geometry,
)
from mjwalk.conventions import DEFAULT_STATURE
from mjwalk.errors import SceneError

#: Geom group of every humanoid geom (scene obstacles use groups 0-4).
HUMAN_GROUP = 5
#: Collision bits of every humanoid geom (see the module docstring).
HUMAN_CONTYPE = 2
HUMAN_CONAFFINITY = 1
#: Name prefix of the attached humanoid.
HUMAN_PREFIX = "human/"


#: The palm's share of the hand's length (wrist to fingertip): the fingers' MCP joints (the
#: knuckles) lie this far along the hand from the wrist.
PALM_SHARE = 0.45


def _rad(name: str) -> list[float]:
    """The range of joint ``name`` (side stripped) in radians, from :data:`ROM_DEG`."""
    return list(_rad_kept(name))


@functools.cache
def _rad_kept(name: str) -> tuple[float, float]:
    """:func:`_rad`, worked out once per name (a humanoid asks for 67 ranges; each operator's
    stature builds one)."""
    key = name
    if key not in ROM_DEG:
        for suffix in ("_mcp", "_pip", "_dip"):
            if name.endswith(suffix):
                key = "finger" + suffix
    lo, hi = ROM_DEG[key]
    return float(np.deg2rad(lo)), float(np.deg2rad(hi))


#: Colours (RGBA) of the humanoid's skin, shirt, trousers and shoes.
_SKIN = (0.85, 0.7, 0.55, 1)
_CLOTH = (0.25, 0.35, 0.6, 1)
_TROUSERS = (0.2, 0.2, 0.25, 1)
_SHOES = (0.15, 0.1, 0.1, 1)


def _geom(body, kind, size, pos=None, fromto=None, rgba=_SKIN, name=None):
    """Add a humanoid geom (collision bits and group of the module docstring) to ``body``."""
    if not name:  # every humanoid geom is named so reports can say which part touched
        name = f"{body.name}_{sum(1 for _ in body.geoms)}"
    gm = body.add_geom(name=name)
    gm.type = kind
    gm.size = list(size) + [0.0] * (3 - len(size))
    if fromto is not None:
        gm.fromto = list(fromto)
    if pos is not None:
        gm.pos = list(pos)
    gm.rgba = list(rgba)
    gm.contype = HUMAN_CONTYPE
    gm.conaffinity = HUMAN_CONAFFINITY
    gm.group = HUMAN_GROUP
    return gm


def _hinge(body, name, axis):
    """Add a limited hinge ``name`` about ``axis`` (body frame), its range from ROM_DEG."""
    j = body.add_joint(name=name)
    j.type = mujoco.mjtJoint.mjJNT_HINGE
    j.axis = list(axis)
    j.range = _rad(_strip_side(name))
    j.limited = mujoco.mjtLimited.mjLIMITED_TRUE
    return j


def _body(parent, name, pos):
    """Add a child body ``name`` at ``pos`` (metres, parent frame)."""
    b = parent.add_body(name=name)
    b.pos = list(pos)
    return b


def build_humanoid(stature: float = DEFAULT_STATURE) -> mujoco.MjSpec:
    """Build the adult humanoid for ``stature`` metres as an MjSpec.

    The model holds one body tree rooted at ``pelvis`` (free joint ``root``), 3-DOF lumbar,
    thoracic and neck joints, 3-DOF shoulders, elbows, forearm pronation, 2-DOF wrists, a thumb
    with 3 joints and four fingers with 3 joints each, 3-DOF hips (rotation, flexion,
    abduction, applied in that order), knees, 2-DOF ankles and toes. Joint names are stable,
    e.g. ``hip_l_flex``, ``knee_l``, ``ankle_r_flex``, ``index_l_mcp``.

    Args:
        stature: the humanoid's stature in metres, 1.0-2.3 (else SceneError).

    Returns:
        the uncompiled spec (model name ``mjwalk_humanoid``, angles in radians), the pelvis at
        :func:`pelvis_height` above the world origin, facing +x.
    """
    if not (1.0 <= stature <= 2.3):
        raise SceneError(f"humanoid: stature {stature!r} m outside the adult range 1.0-2.3 m")
    H = stature
    g = leg_geometry(H)
    spec = mujoco.MjSpec()
    spec.modelname = "mjwalk_humanoid"
    spec.compiler.degree = False
    pelvis = _body(spec.worldbody, "pelvis", [0, 0, pelvis_height(H)])
    pelvis.add_freejoint(name="root")
    _geom(
        pelvis,
        mujoco.mjtGeom.mjGEOM_CAPSULE,
        [0.06 * H / DEFAULT_STATURE],
        fromto=[0, -g.hip_y, 0.02, 0, g.hip_y, 0.02],
        rgba=_TROUSERS,
        name="pelvis",
    )
    thorax, sh_z = _add_spine(pelvis, H)
    # ---- arms, hanging along -z in the neutral pose
    for side, s in (("l", 1.0), ("r", -1.0)):
        _add_arm(thorax, side, s, H, sh_z)
    # ---- legs: hip (rot, flex, abd) -> knee -> ankle (flex, inv) -> toes
    for side, s in (("l", 1.0), ("r", -1.0)):
        _add_leg(pelvis, side, s, H, g)
    # inertia from the geoms at the density of water: a kinematic playback model, masses only
    # matter for display; scale with mujoco.mj_setTotalmass on the compiled model if needed.
    spec.compiler.inertiafromgeom = mujoco.mjtInertiaFromGeom.mjINERTIAFROMGEOM_TRUE
    return spec


def _add_spine(pelvis, H: float):
    """Lumbar (L3 level) -> thorax (T12) -> neck (C7) -> head on ``pelvis`` for stature ``H``;
    returns the thorax body and the shoulders' height above it (m)."""
    lumbar_z = 0.05 * H
    lumbar = _body(pelvis, "lumbar", [0, 0, lumbar_z])
    for n, ax in (
        ("lumbar_flex", [0, 1, 0]),
        ("lumbar_bend", [1, 0, 0]),
        ("lumbar_rot", [0, 0, 1]),
    ):
        _hinge(lumbar, n, ax)
    _geom(
        lumbar,
        mujoco.mjtGeom.mjGEOM_CAPSULE,
        [0.075 * H / DEFAULT_STATURE],
        fromto=[0, -0.04 * H, 0.04 * H, 0, 0.04 * H, 0.04 * H],
        rgba=_CLOTH,
        name="abdomen",
    )
    thorax_z = 0.11 * H
    thorax = _body(lumbar, "thorax", [0, 0, thorax_z])
    for n, ax in (
        ("thoracic_flex", [0, 1, 0]),
        ("thoracic_bend", [1, 0, 0]),
        ("thoracic_rot", [0, 0, 1]),
    ):
        _hinge(thorax, n, ax)
    sh_z = (SEG["shoulder_height"] - SEG["hip_height"]) * H - lumbar_z - thorax_z
    _geom(
        thorax,
        mujoco.mjtGeom.mjGEOM_CAPSULE,
        [0.085 * H / DEFAULT_STATURE],
        fromto=[0, -0.05 * H, 0.5 * sh_z, 0, 0.05 * H, 0.5 * sh_z],
        rgba=_CLOTH,
        name="chest",
    )
    neck = _body(thorax, "neck", [0, 0, sh_z + 0.01 * H])
    for n, ax in (("neck_flex", [0, 1, 0]), ("neck_bend", [1, 0, 0]), ("neck_rot", [0, 0, 1])):
        _hinge(neck, n, ax)
    head_r = 0.5 * (SEG["head_top"] - SEG["chin_height"]) * H * 1.25
    _geom(
        neck,
        mujoco.mjtGeom.mjGEOM_CAPSULE,
        [0.025 * H],
        fromto=[0, 0, 0, 0, 0, 0.03 * H],
        rgba=_SKIN,
        name="neck",
    )
    _geom(
        neck,
        mujoco.mjtGeom.mjGEOM_SPHERE,
        [head_r],
        pos=[0.01 * H, 0, (SEG["head_top"] - SEG["shoulder_height"] - 0.01) * H - head_r],
        rgba=_SKIN,
        name="head",
    )
    return thorax, sh_z


def _add_arm(thorax, side: str, s: float, H: float, sh_z: float) -> None:
    """Upper arm, forearm and hand of ``side`` ("l"/"r", ``s`` +1/-1) on ``thorax``, the
    shoulder ``sh_z`` metres above it."""
    sh = _body(thorax, f"upper_arm_{side}", [0, s * 0.5 * SEG["shoulder_width"] * H, sh_z])
    # flexion: arm forward (rotation about -y); abduction: arm sideways (about +-x);
    # internal rotation about the arm's long axis (-z for left, +z for right).
    _hinge(sh, f"shoulder_{side}_flex", [0, -1, 0])
    _hinge(sh, f"shoulder_{side}_abd", [s, 0, 0])
    _hinge(sh, f"shoulder_{side}_rot", [0, 0, -s])
    ua = SEG["upper_arm"] * H
    _geom(
        sh,
        mujoco.mjtGeom.mjGEOM_CAPSULE,
        [UPPER_ARM_RADIUS * H],
        fromto=[0, 0, 0, 0, 0, -ua],
        rgba=_CLOTH,
        name=f"upper_arm_{side}",
    )
    fa_b = _body(sh, f"forearm_{side}", [0, 0, -ua])
    _hinge(fa_b, f"elbow_{side}", [0, -1, 0])
    _hinge(fa_b, f"forearm_{side}_pron", [0, 0, -s])
    fa = SEG["forearm"] * H
    _geom(
        fa_b,
        mujoco.mjtGeom.mjGEOM_CAPSULE,
        [0.019 * H],
        fromto=[0, 0, 0, 0, 0, -fa],
        rgba=_SKIN,
        name=f"forearm_{side}",
    )
    hand = _body(fa_b, f"hand_{side}", [0, 0, -fa])
    _hinge(hand, f"wrist_{side}_flex", [0, -1, 0])
    _hinge(hand, f"wrist_{side}_dev", [s, 0, 0])
    _add_hand(hand, side, s, H)


def _add_hand(hand, side: str, s: float, H: float) -> None:
    """Palm, thumb (CMC, MCP, IP) and four fingers (MCP, PIP, DIP) on the ``hand`` body."""
    palm = PALM_SHARE * SEG["hand"] * H
    _geom(
        hand,
        mujoco.mjtGeom.mjGEOM_BOX,
        [0.012 * H, 0.022 * H, 0.5 * palm],
        pos=[0, 0, -0.5 * palm],
        rgba=_SKIN,
        name=f"palm_{side}",
    )
    # thumb: CMC opposition, MCP, IP (3 joints), from the palm's radial side
    th = _body(hand, f"thumb_{side}", [0.01 * H, s * 0.018 * H, -0.1 * palm])
    _hinge(th, f"thumb_{side}_cmc", [-1, 0, 0] if s > 0 else [1, 0, 0])
    _geom(
        th,
        mujoco.mjtGeom.mjGEOM_CAPSULE,
        [0.006 * H],
        fromto=[0, 0, 0, 0.008 * H, 0, -0.02 * H],
        rgba=_SKIN,
    )
    th2 = _body(th, f"thumb_{side}_distal", [0.008 * H, 0, -0.02 * H])
    _hinge(th2, f"thumb_{side}_mcp", [0, -1, 0])
    _geom(
        th2,
        mujoco.mjtGeom.mjGEOM_CAPSULE,
        [0.0055 * H],
        fromto=[0, 0, 0, 0.004 * H, 0, -0.016 * H],
        rgba=_SKIN,
    )
    th3 = _body(th2, f"thumb_{side}_tip", [0.004 * H, 0, -0.016 * H])
    _hinge(th3, f"thumb_{side}_ip", [0, -1, 0])
    _geom(
        th3,
        mujoco.mjtGeom.mjGEOM_CAPSULE,
        [0.005 * H],
        fromto=[0, 0, 0, 0, 0, -0.015 * H],
        rgba=_SKIN,
    )
    # four fingers, 3 independent joints each (MCP, PIP, DIP), flexion towards the palm (+x)
    for k, f in enumerate(FINGERS):
        y = s * (0.015 - 0.01 * k) * H
        seg = [0.024, 0.014, 0.011]
        parent = hand
        pos = [0, y, -palm]
        for jn, L in zip(("mcp", "pip", "dip"), seg, strict=True):
            name = f"{f}_{side}_{jn}" if jn != "mcp" else f"{f}_{side}"
            fb = _body(parent, name if jn == "mcp" else f"{f}_{side}_{jn}_seg", pos)
            _hinge(fb, f"{f}_{side}_{jn}", [0, -1, 0])
            _geom(
                fb,
                mujoco.mjtGeom.mjGEOM_CAPSULE,
                [0.0045 * H],
                fromto=[0, 0, 0, 0, 0, -L * H],
                rgba=_SKIN,
            )
            parent, pos = fb, [0, 0, -L * H]


def _add_leg(pelvis, side: str, s: float, H: float, g: LegGeometry) -> None:
    """Thigh, shin, foot (with its ``sole_*`` site) and toes of ``side`` on ``pelvis``."""
    th = _body(pelvis, f"thigh_{side}", [0, s * g.hip_y, 0])
    _hinge(th, f"hip_{side}_rot", [0, 0, -s])
    _hinge(th, f"hip_{side}_flex", [0, -1, 0])
    _hinge(th, f"hip_{side}_abd", [s, 0, 0])
    _geom(
        th,
        mujoco.mjtGeom.mjGEOM_CAPSULE,
        [0.035 * H],
        fromto=[0, 0, 0, 0, 0, -g.thigh],
        rgba=_TROUSERS,
        name=f"thigh_{side}",
    )
    sk = _body(th, f"shin_{side}", [0, 0, -g.thigh])
    _hinge(sk, f"knee_{side}", [0, 1, 0])
    _geom(
        sk,
        mujoco.mjtGeom.mjGEOM_CAPSULE,
        [SHIN_RADIUS * H],
        fromto=[0, 0, 0, 0, 0, -g.shank],
        rgba=_TROUSERS,
        name=f"shin_{side}",
    )
    ft = _body(sk, f"foot_{side}", [0, 0, -g.shank])
    _hinge(ft, f"ankle_{side}_flex", [0, -1, 0])
    _hinge(ft, f"ankle_{side}_inv", [-s, 0, 0])
    ah = g.ankle_height
    ball = g.foot_front - 0.2 * SEG["foot_length"] * H
    hw = 0.5 * SEG["foot_width"] * H
    _geom(
        ft,
        mujoco.mjtGeom.mjGEOM_BOX,
        [0.5 * (ball + g.foot_back), hw, 0.5 * ah * 0.8],
        pos=[0.5 * (ball - g.foot_back), 0, -ah + 0.4 * ah],
        rgba=_SHOES,
        name=f"foot_{side}",
    )
    to = _body(ft, f"toes_{side}", [ball, 0, -ah])
    _hinge(to, f"toe_{side}", [0, -1, 0])
    tl = g.foot_front - ball
    _geom(
        to,
        mujoco.mjtGeom.mjGEOM_BOX,
        [0.5 * tl, hw, 0.2 * ah],
        pos=[0.5 * tl, 0, 0.2 * ah],
        rgba=_SHOES,
        name=f"toes_{side}",
    )
    site = ft.add_site(name=f"sole_{side}")
    site.pos = [0, 0, -ah]


def _strip_side(name: str) -> str:
    """'hip_l_flex' -> 'hip_flex', 'index_r_pip' -> 'index_pip', 'knee_l' -> 'knee'."""
    parts = [p for p in name.split("_") if p not in ("l", "r")]
    return "_".join(parts)


@dataclass
class JointMap:
    """Where each humanoid hinge lives in ``qpos`` and its range of motion.

    Attributes:
        names: joint names without the prefix (e.g. ``"knee_l"``), in qpos order.
        qposadr: (J,) qpos address of each joint.
        range: (J, 2) lower and upper limit, radians.
        root: qpos address of the free root joint (x, y, z, qw, qx, qy, qz follow).
        prefix: the name prefix in the compiled model ("" for the bare humanoid).
    """

    names: tuple[str, ...]
    qposadr: np.ndarray
    range: np.ndarray
    root: int
    prefix: str = ""

    def __post_init__(self) -> None:
        self._index = {n: i for i, n in enumerate(self.names)}

    def __contains__(self, name: str) -> bool:
        return name in self._index

    def index(self, name: str) -> int:
        """Position of ``name`` in :attr:`names`; unknown names raise SceneError.

        Args:
            name: a joint name without the prefix, e.g. ``"knee_l"``.

        Returns:
            the index into :attr:`names`, :attr:`qposadr` and :attr:`range`.
        """
        try:
            return self._index[name]
        except KeyError:
            raise SceneError(f"humanoid has no joint {name!r}") from None

    def adr(self, name: str) -> int:
        """qpos address of joint ``name``.

        Args:
            name: a joint name without the prefix.

        Returns:
            the index into ``qpos``.
        """
        return int(self.qposadr[self.index(name)])

    def limits(self, name: str) -> tuple[float, float]:
        """Range of joint ``name``.

        Args:
            name: a joint name without the prefix.

        Returns:
            (lo, hi), radians.
        """
        lo, hi = self.range[self.index(name)]
        return float(lo), float(hi)

    @classmethod
    def from_model(cls, model: mujoco.MjModel, prefix: str = "") -> JointMap:
        """Collect the humanoid joints (names starting with ``prefix``) of a compiled model.

        Args:
            model: a compiled model holding the humanoid (alone or attached to a scene).
            prefix: the humanoid's name prefix in ``model``.

        Returns:
            the map of its hinges (free root excluded); SceneError without a root joint.
        """
        names, adrs, rows, root = [], [], [], None
        # the model's arrays read once (each attribute read of an MjModel makes a new array:
        # three a joint cost about 0.3 ms a humanoid, built once per operator's stature)
        types, qposadr = model.jnt_type.tolist(), model.jnt_qposadr.tolist()
        free = int(mujoco.mjtJoint.mjJNT_FREE)
        for j in range(model.njnt):
            full = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, j) or ""
            if not full.startswith(prefix):
                continue
            short = full[len(prefix) :]
            if types[j] == free:
                if short == "root":
                    root = qposadr[j]
                continue
            names.append(short)
            adrs.append(qposadr[j])
            rows.append(j)
        if root is None:
            raise SceneError(f"model has no humanoid root joint {prefix + 'root'!r}")
        ranges = model.jnt_range[rows] if rows else np.array([])
        return cls(tuple(names), np.array(adrs, dtype=int), ranges, root, prefix)

    def neutral_qpos(self, model: mujoco.MjModel, stature: float = DEFAULT_STATURE) -> np.ndarray:
        """``model.qpos0`` with the humanoid standing upright at the origin facing +x.

        Args:
            model: the compiled model the map was made from.
            stature: the humanoid's stature, metres (sets the pelvis height).

        Returns:
            (nq,) qpos: root at (0, 0, :func:`pelvis_height`), identity quaternion, joints at 0.
        """
        q = model.qpos0.copy()
        q[self.root : self.root + 7] = [0, 0, pelvis_height(stature), 1, 0, 0, 0]
        q[self.qposadr] = 0.0
        return q


def humanoid_model(stature: float = DEFAULT_STATURE) -> tuple[mujoco.MjModel, JointMap]:
    """Compile the bare humanoid and its JointMap.

    Args:
        stature: the humanoid's stature, metres.

    Returns:
        the compiled model and its JointMap (no prefix).
    """
    spec = build_humanoid(stature)
    model = spec.compile()
    return model, JointMap.from_model(model)


def attach_humanoid(
    scene: str | Path | mujoco.MjSpec, stature: float = DEFAULT_STATURE, prefix: str = HUMAN_PREFIX
) -> tuple[mujoco.MjModel, JointMap]:
    """Attach the humanoid to a workplace scene, without touching the scene file.

    Args:
        scene: path of an MJCF scene, or an ``MjSpec`` (it is copied, not modified).
        stature: the humanoid's stature in metres.
        prefix: prefix of every humanoid element name in the compiled model.

    Returns:
        the compiled model (scene + humanoid) and the humanoid's JointMap (names unprefixed).
    """
    if isinstance(scene, mujoco.MjSpec):
        parent = scene.copy()
        where = "<MjSpec>"
    else:
        path = Path(scene)
        where = str(path)
        if not path.is_file():
            raise SceneError(f"{path}: no such scene file")
        try:
            parent = mujoco.MjSpec.from_file(str(path))
        except Exception as exc:  # mujoco raises ValueError with the XML parser message
            raise SceneError(f"{path}: cannot parse scene ({exc})") from exc
    child = build_humanoid(stature)
    frame = parent.worldbody.add_frame()
    frame.attach_body(child.body("pelvis"), prefix, "")
    try:
        model = parent.compile()
    except Exception as exc:
        raise SceneError(f"{where}: cannot compile scene with the humanoid ({exc})") from exc
    return model, JointMap.from_model(model, prefix)


def write_humanoid_xml(path: str | Path, stature: float = DEFAULT_STATURE) -> None:
    """Write the humanoid MJCF with a floor plane and a light (the file
    ``scenes/humanoid.xml`` is produced by this), atomically, mode 0644.

    Args:
        path: the output file.
        stature: the humanoid's stature, metres.
    """
    spec = build_humanoid(stature)
    floor = spec.worldbody.add_geom(name="floor")
    floor.type = mujoco.mjtGeom.mjGEOM_PLANE
    floor.size = [5, 5, 0.1]
    floor.rgba = [0.8, 0.8, 0.8, 1]
    light = spec.worldbody.add_light()
    light.pos = [0, 0, 4]
    spec.compile()
    xml = spec.to_xml()
    with atomic_path(path) as tmp:
        tmp.write_text(
            "<!-- Generated by mjwalk.body.humanoid.write_humanoid_xml(stature="
            f"{stature}); do not edit by hand. -->\n" + xml
        )
    Path(path).chmod(0o644)
