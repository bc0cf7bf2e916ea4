"""Conventions shared by every stage: sample rate, default body size, side names.

Units everywhere in mjwalk: metres, seconds, radians; world frame z up, yaw from +x
counter-clockwise. Randomness: a function that makes one draw takes ``rng`` (a
``numpy.random.Generator`` or an int seed, passed to ``numpy.random.default_rng``); a function
that makes a batch of independent draws takes a root ``seed`` and spawns one stream per item
(``numpy.random.SeedSequence``), so an item does not depend on how many others are drawn.
"""

from __future__ import annotations

from typing import Literal

#: Sample rate (Hz) of takes, steps and planned walks: the capture and synthesis rate of
#: agethen2018 (Vicon at 120 Hz).
SAMPLE_RATE_HZ = 120.0
#: Default stature of the humanoid (m): the mean of agethen2018's subjects, N(1.75, 0.04) m.
DEFAULT_STATURE = 1.75
#: Default body radius (m) the planners keep from obstacle footprints: half the shoulder width
#: of an adult plus a margin.
BODY_RADIUS = 0.25

#: A body side in the public API.
Side = Literal["left", "right"]
SIDES: tuple[Side, Side] = ("left", "right")


def side_prefix(side: str) -> Literal["l", "r"]:
    """The one-letter side of MJCF joint and body names (``"knee_l"``).

    Args:
        side: ``"left"`` or ``"right"``.

    Returns:
        ``"l"`` or ``"r"``.

    Raises:
        ValueError: for anything but ``"left"`` / ``"right"``.
    """
    if side == "left":
        return "l"
    if side == "right":
        return "r"
    raise ValueError(f"side must be 'left' or 'right', got {side!r}")


def side_of_prefix(prefix: str) -> Side:
    """The side of a one-letter joint-name side (the inverse of :func:`side_prefix`).

    Args:
        prefix: ``"l"`` or ``"r"``.

    Returns:
        ``"left"`` or ``"right"``.

    Raises:
        ValueError: for anything but ``"l"`` / ``"r"``.
    """
    if prefix == "l":
        return "left"
    if prefix == "r":
        return "right"
    raise ValueError(f"side prefix must be 'l' or 'r', got {prefix!r}")


def other_side(side: str) -> Side:
    """The opposite side.

    Args:
        side: ``"left"`` or ``"right"``.

    Returns:
        ``"right"`` for ``"left"``; ``"left"`` for ``"right"`` (and for any other value).
    """
    return "right" if side == "left" else "left"
