"""Cycle sites on a scene's levels (issue 47): which level a standing site stands on, the ground
height under the operator, and the walk room there.

A cycle of a flat scene never builds the levels: every standing site lies within
:data:`STAND_MAX_Z` of the floor, :func:`spec_on_levels` is False, the ground is the floor
(0 m) and the walk room is the workplace's own. A cycle with a standing site on a platform or a
mezzanine (:attr:`Workplace.levels <mjwalk.world.workplace.Workplace.levels>`) stands the
operator on the level's height (root z = level height + the pelvis height), and the walk room
is the level's own (:func:`mjwalk.world.levelview.level_view`: its surfaces' extent, its edges as
walls). World frame: metres above the floor, z up.
"""

from __future__ import annotations

import numpy as np

from mjwalk.plan.lowtops import stand_top
from mjwalk.world.clearance import ClearanceField
from mjwalk.world.levelview import level_at, level_view
from mjwalk.world.norms import LEVEL_TOLERANCE
from mjwalk.world.workplace import Workplace

#: Highest a standing site may lie above the surface it stands on, metres (a site on the floor
#: within it is on the floor without looking at the levels).
STAND_MAX_Z = 0.05
#: A standing spot keeps this much more than the body radius from obstacles (m): a walk sets
#: off with a first step that sways the pelvis sideways (the default model's first steps: 1.3
#: cm median, 3.6 cm 99th percentile, 6.1 cm the largest), so from a spot on the radius itself
#: the planner may find no first step (docs/decisions/005-standing-spots.md). A walk over
#: levels sets off without turning on the spot first (:mod:`mjwalk.plan.levelplan`), so in a
#: cycle over levels a spot a reach steps to keeps this margin too (:func:`reach_room`).
START_MARGIN = 0.04


def site_level(workplace: Workplace, name: str) -> int | None:
    """The level a standing site stands on.

    Args:
        workplace: the scene.
        name: the site's name (one of ``workplace.stations``).

    Returns:
        0 for a site within :data:`STAND_MAX_Z` of the floor (the levels are not built); else
        the index in ``workplace.levels.levels`` of the level whose height lies within
        :data:`STAND_MAX_Z` below the site or at most ``norms.LEVEL_TOLERANCE`` above it (a site
        written a tenth of a millimetre under a deck's top stands on the deck, as the floor
        check takes either side) (a platform above the floor, or a pit below a floor
        with openings, :mod:`mjwalk.world.floorholes`); None when the site stands on no level.
    """
    st = workplace.stations[name]
    height = float(st.pos[2] - workplace.floor_z)
    if abs(height) <= STAND_MAX_Z:
        return 0
    lv = level_at(workplace, np.asarray(st.xy, dtype=float), float(st.pos[2]))
    if lv is None:
        return None
    if not -LEVEL_TOLERANCE <= float(st.pos[2]) - workplace.levels.levels[lv].height <= STAND_MAX_Z:
        return None
    return int(lv)


def level_workplace(workplace: Workplace, level: int) -> Workplace:
    """The workplace a walker stands in on a level.

    Args:
        workplace: the scene.
        level: the level's index (0: the floor).

    Returns:
        ``workplace`` itself for the floor, else the level's view (its surfaces' extent, its
        edges as walls, its obstacles; ``floor_z`` the level's height).
    """
    return workplace if level == 0 else level_view(workplace, level)


def spec_on_levels(workplace: Workplace, sites) -> bool:
    """Whether any of a cycle's standing sites stands above the floor.

    Args:
        workplace: the scene.
        sites: the standing sites' names (the start site and every walk's goal).

    Returns:
        True when a site stands on a raised level (a cycle over levels).
    """
    return any(site_level(workplace, s) not in (0, None) for s in sites)


def ground_height(workplace: Workplace, xy, on_levels: bool) -> float:
    """The height above the floor of the surface a standing operator's pelvis is over: the
    level's, or the top of a mat, cable bridge or floor plate lying on it under the operator
    (:func:`mjwalk.plan.lowtops.stand_top`: the walk that brought the operator there stood
    the feet on it too).

    Args:
        workplace: the scene.
        xy: (x, y) world, metres.
        on_levels: whether the cycle stands on levels (:func:`spec_on_levels`); False: the
            floor's.

    Returns:
        Metres above the floor (0 on the floor, on no level or off the levels' surfaces,
        without a low top there).
    """
    if not on_levels:
        return stand_top(workplace, xy, 0.0)
    lv = level_at(workplace, np.asarray(xy, dtype=float)[:2])
    if lv in (0, None):
        return stand_top(workplace, xy, 0.0)
    level = float(workplace.levels.levels[int(lv)].height - workplace.floor_z)
    return stand_top(workplace, xy, level)


def level_field(workplace: Workplace, xy, on_levels: bool) -> ClearanceField:
    """The walk-room field (:meth:`Workplace.walk_field`) of the level under a point.

    Args:
        workplace: the scene.
        xy: (x, y) world, metres (a site or where the operator stands).
        on_levels: whether the cycle stands on levels; False: the workplace's own field.

    Returns:
        The level's walk field, metres to the nearest obstacle or edge of the level.
    """
    if not on_levels:
        return workplace.walk_field()
    lv = level_at(workplace, np.asarray(xy, dtype=float)[:2])
    return level_workplace(workplace, 0 if lv is None else int(lv)).walk_field()


def level_room(workplace: Workplace, xy, on_levels: bool, home=None) -> float:
    """Room to walk at a point on its level (:meth:`Workplace.walk_clearance` of its view).

    Args:
        workplace: the scene.
        xy: (x, y) world, metres.
        on_levels: whether the cycle stands on levels; False: the workplace's own room.
        home: (x, y) world, metres, where the operator stands: the level is the one there (a step
            back off a platform's edge has no room); None: the level under ``xy``.

    Returns:
        Metres to the nearest obstacle or edge of the level there.
    """
    p = np.asarray(xy, dtype=float)[:2]
    if not on_levels:
        return float(workplace.walk_clearance(p)[()])
    lv = level_at(workplace, p if home is None else np.asarray(home, dtype=float)[:2])
    view = level_workplace(workplace, 0 if lv is None else int(lv))
    return float(view.walk_clearance(p)[()])


def reach_room(radius: float, on_levels: bool, here: float) -> float:
    """The least room (:func:`level_room`) a spot the operator steps to for a reach keeps, so
    that the next walk can set off from it.

    A flat cycle's walks turn on the spot before their first step, so a spot there keeps the
    body radius (today's rule). A walk over levels sets off without that turn, like a walk from
    a drawn standing spot, so in a cycle over levels the spot keeps the radius plus
    :data:`START_MARGIN` (issue 47: a step in of 0.14 m towards a fastening left the operator
    0.252 m from the platform's edge and the next walk found no first step). Neither asks more
    than the room where the operator already stands.

    Args:
        radius: the cycle's body radius, metres.
        on_levels: whether the cycle stands on levels (:func:`spec_on_levels`).
        here: the room where the operator stands before the step, metres.

    Returns:
        Metres to the nearest obstacle or edge of the level the spot must keep at least.
    """
    need = radius + START_MARGIN if on_levels else radius
    return min(need, here)
