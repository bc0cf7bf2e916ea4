"""Which walk surfaces are one level, and where ramps' ends meet those levels.

A level is the horizontal surfaces that touch (a contact, :mod:`mjwalk.world.contacts`) with no
more than a level tolerance between their heights, and every box of a floor with openings
(:mod:`mjwalk.world.floorholes`) touching or not: :func:`group_levels`. A walker stepping off a
ramp's end does not care which of a level's boxes is under the foot, so a ramp's end meets a
level along a body's width across any of its surfaces (``contacts.level_contacts``):
:func:`ramp_end_contacts` groups the surfaces and finds those contacts, for the level graph
(:mod:`mjwalk.world.levels`) and for what a walker reaches from the floor
(:mod:`mjwalk.world.surfaces`: a deck of several boxes only a ramp reaches, each box meeting
the ramp's head along less than a body's width, issue 47). Metres.
"""

from __future__ import annotations

from collections.abc import Sequence

from mjwalk.world.contacts import Contact, level_contacts
from mjwalk.world.norms import CONTACT_GAP, LEVEL_TOLERANCE, MAX_RISER
from mjwalk.world.walksurface import WalkSurface


def group_levels(
    surfaces: Sequence[WalkSurface], contacts: Sequence[Contact], tol: float = LEVEL_TOLERANCE
) -> list[list[int]]:
    """The horizontal surfaces grouped into levels (union-find over the contacts).

    Args:
        surfaces: the walk surfaces.
        contacts: the contacts between them (``contacts.surface_contacts``).
        tol: touching surfaces whose heights differ by no more than this along the whole
            contact are one level, metres (``norms.LEVEL_TOLERANCE``, 4 mm).

    Returns:
        The groups of surface indices, each in index order, by their first surface; ramps are in
        none. Every "floor" surface (the boxes of a floor with openings) is in one group.
    """
    parent = list(range(len(surfaces)))

    def root(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for c in contacts:
        if surfaces[c.a].is_ramp or surfaces[c.b].is_ramp:
            continue
        if max(abs(c.rise_range[0]), abs(c.rise_range[1])) <= tol:
            parent[root(c.a)] = root(c.b)
    floors = [i for i, s in enumerate(surfaces) if s.kind == "floor"]  # a floor's boxes
    for i in floors[1:]:  # (mjwalk.world.floorholes) are one level, touching or not
        parent[root(i)] = root(floors[0])
    groups: dict[int, list[int]] = {}
    for i, s in enumerate(surfaces):
        if not s.is_ramp:
            groups.setdefault(root(i), []).append(i)
    return list(groups.values())


def ramp_end_contacts(
    surfaces: Sequence[WalkSurface],
    contacts: Sequence[Contact],
    gap: float = CONTACT_GAP,
    max_rise: float = MAX_RISER,
    tol: float = LEVEL_TOLERANCE,
) -> list[Contact]:
    """Where the ramps' edges meet levels: the surfaces grouped by :func:`group_levels`, then
    ``contacts.level_contacts`` (consecutive stretches on any surface of one level joined, kept
    when a body wide).

    Args:
        surfaces: the walk surfaces (or the candidates for them).
        contacts: the contacts between them (``contacts.surface_contacts``).
        gap: how far beyond an edge a level is looked for, metres (> 0).
        max_rise: largest height difference across a contact, metres (>= 0).
        tol: the level tolerance of :func:`group_levels`, metres.

    Returns:
        The contacts of the ramps' edges, ``b`` the level's surface under most of each stretch.
    """
    level_of: list[int | None] = [None] * len(surfaces)
    for k, group in enumerate(group_levels(surfaces, contacts, tol)):
        for i in group:
            level_of[i] = k
    return level_contacts(surfaces, level_of, gap, max_rise)
