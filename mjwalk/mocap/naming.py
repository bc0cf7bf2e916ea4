"""Capture skeletons by their joint names: detect the naming convention of a file, or read the
user's own map (a TOML file) when no convention fits.

A convention names the seven joints a :class:`~mjwalk.mocap.Take` needs (pelvis, hips, ankles,
toes); units and up axis are *not* part of it (the same names come in centimetres, metres or
inches, y or z up): :mod:`mjwalk.mocap.bodycheck` reads them from the data. Joint names are
compared without case and without a namespace prefix (``mixamorig:Hips``, ``mixamorig1:Hips``
and ``Hips`` are one name). The names, each checked against public files (the
``search``/``find_string`` corpora, 2026-12-05):

- ``humanik``: ``Hips/LeftUpLeg/LeftFoot/LeftToeBase`` (Autodesk HumanIK / MotionBuilder
  names): Mixamo after its ``mixamorig:`` prefix (Mixamo rigs in many public retargeting maps,
  e.g. ``'ball_l': 'mixamorig:LeftToeBase'``), the CMU BVH conversions
  (``una-dinosauria/cmu-mocap`` ``data/035/35_11.bvh``: ``LHipJoint`` at the pelvis, then
  ``LeftUpLeg, LeftLeg, LeftFoot, LeftToeBase``) and the SFU Motion Capture Database (a
  retargeting configuration for it lists ``Hips, LeftUpLeg, LeftLeg, LeftFoot, LeftToeBase``).
- ``lafan1``: ``Hips/LeftUpLeg/LeftFoot/LeftToe`` (Ubisoft LaFAN1, as used by motion-matching
  code on it: ``Hips, LeftUpLeg, LeftLeg, LeftFoot, LeftToe, RightUpLeg, ...``; one public
  channel breakdown of a LaFAN1 file names the toe ``LeftToeBase``: such a file reads as
  ``humanik``, the same joints).
- ``xsens_mvn``: ``Pelvis/LeftUpperLeg/LeftFoot/LeftToe`` (Xsens MVN segments: ``Pelvis, L5,
  L3, T12, T8, Neck, Head, ..., RightUpperLeg, RightLowerLeg, RightFoot, RightToe``).
- ``rokoko``: ``Hips/LeftThigh/LeftFoot/LeftToe`` (Rokoko Newton: ``hips, leftThigh, leftShin,
  leftFoot, leftToe, leftToeTip``).
- ``bandai``: ``Hips/UpperLeg_L/Foot_L/Toes_L`` (Bandai Namco Research Motion Dataset).

Vicon Shogun/Blade exports were not found in the corpora with their own names; the ones seen
use the HumanIK names and are detected as such; any other skeleton needs a map file.

In every convention the hip role is the joint at the head of the femur (the thigh bone starts
there; CMU's ``LHipJoint`` sits at the pelvis and is not it), the ankle the joint the foot
bone starts at, the toe the ball of the foot.

Map file (``--skeleton map.toml``)::

    pelvis = "Root"
    hip_l = "L_Hip"      # and hip_r, ankle_l, ankle_r, toe_l, toe_r
    units = "cm"         # optional: m, cm, mm, in, or a number of metres per unit
    up = "y"             # optional: y or z

Units and up axis left out are read from the data; given ones are checked against it.
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass
from pathlib import Path

from mjwalk.errors import CaptureError
from mjwalk.mocap.skeletons import SKELETONS, SkeletonMap

#: Length units a map file may name, metres per unit.
UNITS: dict[str, float] = {"m": 1.0, "cm": 0.01, "mm": 0.001, "in": 0.0254}

ROLES = ("pelvis", "hip_l", "hip_r", "ankle_l", "ankle_r", "toe_l", "toe_r")


@dataclass(frozen=True)
class Convention:
    """The joint names one capture convention gives the seven roles (any case, no prefix).

    Attributes:
        name: convention name (``Take.meta["skeleton"]``).
        joints: role -> joint name, for every role of :data:`ROLES`.
    """

    name: str
    joints: dict[str, str]


def _lr(name: str, pelvis: str, parts: tuple[str, str, str], left: str, right: str) -> Convention:
    """A convention with ``pelvis`` and hip/ankle/toe ``parts`` named by the ``left`` and
    ``right`` patterns (``{}`` stands for the part: ``"Left{}"``, ``"{}_L"``)."""
    j = {"pelvis": pelvis}
    for role, part in zip(("hip", "ankle", "toe"), parts, strict=True):
        j[role + "_l"] = left.format(part)
        j[role + "_r"] = right.format(part)
    return Convention(name, j)


#: Known conventions, tried in this order (the first with all seven names present wins).
CONVENTIONS: tuple[Convention, ...] = (
    _lr("bandai", "Hips", ("UpperLeg", "Foot", "Toes"), "{}_L", "{}_R"),
    _lr("humanik", "Hips", ("UpLeg", "Foot", "ToeBase"), "Left{}", "Right{}"),
    _lr("lafan1", "Hips", ("UpLeg", "Foot", "Toe"), "Left{}", "Right{}"),
    _lr("xsens_mvn", "Pelvis", ("UpperLeg", "Foot", "Toe"), "Left{}", "Right{}"),
    _lr("rokoko", "Hips", ("Thigh", "Foot", "Toe"), "Left{}", "Right{}"),
)


def _guessed(name: str, j: dict[str, str]) -> SkeletonMap:
    """The map of role -> joint ``j`` whose units and up axis are read from the data."""
    return SkeletonMap(
        name=name,
        pelvis=j["pelvis"],
        ankle_l=j["ankle_l"],
        ankle_r=j["ankle_r"],
        toe_l=j["toe_l"],
        toe_r=j["toe_r"],
        hip_l=j["hip_l"],
        hip_r=j["hip_r"],
        guess_scale=True,
        guess_up=True,
    )


def _key(name: str) -> str:
    """A joint name without namespace prefix and case: ``mixamorig:LeftFoot`` -> ``leftfoot``."""
    return name.rsplit(":", 1)[-1].strip().lower()


def _bind(conv: Convention, names: list[str]) -> dict[str, str] | None:
    """Role -> the file's own joint name, or None when a role's joint is missing."""
    by_key: dict[str, str] = {}
    for n in names:
        by_key.setdefault(_key(n), n)
    out = {}
    for role, joint in conv.joints.items():
        found = by_key.get(_key(joint))
        if found is None:
            return None
        out[role] = found
    return out


def detect_skeleton(names: list[str], path: object = "") -> SkeletonMap:
    """The skeleton map of a file from its joint names alone; units and up axis to be read from
    the data (``guess_scale``/``guess_up`` set, see :mod:`mjwalk.mocap.bodycheck`).

    Args:
        names: the joint names the file defines.
        path: the file, for the message.

    Returns:
        The map of the first convention of :data:`CONVENTIONS` whose seven joints are present.

    Raises:
        CaptureError: no convention fits (one line naming the map-file fix).
    """
    for conv in CONVENTIONS:
        bound = _bind(conv, names)
        if bound is not None:
            return _guessed(conv.name, bound)
    shown = ", ".join(names[:12]) + (", ..." if len(names) > 12 else "")
    known = ", ".join(c.name for c in CONVENTIONS)
    raise CaptureError(
        f"{path}: no known skeleton convention ({known}) fits the joints {shown}; name the "
        "pelvis, hips, ankles and toes in a map file: --skeleton map.toml (see the README)"
    )


def _units(value: object, path: object) -> float:
    """Metres per file unit from a map's ``units`` (a name of :data:`UNITS` or a number)."""
    if isinstance(value, str) and value.lower() in UNITS:
        return UNITS[value.lower()]
    if isinstance(value, (int, float)) and not isinstance(value, bool) and 0 < value < 1e3:
        return float(value)
    raise CaptureError(
        f"{path}: units = {value!r}: use one of {', '.join(UNITS)} or metres per unit (> 0)"
    )


def load_skeleton_map(path: str | Path) -> SkeletonMap:
    """A user's skeleton map from a TOML file (format in the module docstring).

    Args:
        path: the ``.toml`` file.

    Returns:
        The map; units and up axis the file leaves out are read from the data.

    Raises:
        CaptureError: unreadable file, bad TOML, a role missing or an unknown key (one line).
    """
    path = Path(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except OSError as exc:
        raise CaptureError(f"{path}: cannot read skeleton map ({exc.strerror or exc})") from None
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise CaptureError(f"{path}: not a TOML skeleton map ({exc})") from None
    unknown = sorted(set(data) - {*ROLES, "units", "up", "name"})
    if unknown:
        raise CaptureError(
            f"{path}: unknown key {unknown[0]!r}; keys: {', '.join(ROLES)}, units, up"
        )
    missing = [r for r in ROLES if not isinstance(data.get(r), str) or not data[r].strip()]
    if missing:
        raise CaptureError(f"{path}: the map names no joint for {', '.join(missing)}")
    up = data.get("up")
    if up is not None and up not in ("y", "z"):
        raise CaptureError(f"{path}: up = {up!r}: use 'y' or 'z'")
    return SkeletonMap(
        name=str(data.get("name", path.stem)),
        **{r: data[r] for r in ROLES},
        scale=_units(data["units"], path) if "units" in data else 1.0,
        up=up or "y",
        guess_scale="units" not in data,
        guess_up=up is None,
        verify=True,
    )


def resolve_skeleton(
    skeleton: SkeletonMap | str | None, names: list[str], path: object
) -> SkeletonMap:
    """The map to read one file with: a given map, a preset name, a map file, or detection.

    Args:
        skeleton: a :class:`SkeletonMap`; a preset name of :data:`SKELETONS`; a path ending in
            ``.toml``; or None / ``"auto"`` to detect it from ``names``.
        names: the file's joint names.
        path: the file, for messages.

    Returns:
        The skeleton map (its joints not yet checked against ``names``).

    Raises:
        CaptureError: unknown preset name, bad map file, or no convention detected.
    """
    if isinstance(skeleton, SkeletonMap):
        return skeleton
    if skeleton is None or str(skeleton).lower() == "auto":
        return detect_skeleton(names, path)
    if str(skeleton).lower().endswith(".toml"):
        return load_skeleton_map(skeleton)
    key = str(skeleton).lower()
    if key in SKELETONS:
        return SKELETONS[key]
    conv = {c.name: c for c in CONVENTIONS}.get(key)
    if conv is not None:
        bound = _bind(conv, names) or conv.joints  # missing: the joint check names it
        return _guessed(conv.name, bound)
    known = sorted({*SKELETONS, *(c.name for c in CONVENTIONS)})
    raise CaptureError(
        f"unknown skeleton {skeleton!r}; known: {', '.join(known)}, auto, or a map file .toml"
    )
