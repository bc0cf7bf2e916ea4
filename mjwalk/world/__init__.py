"""Workplaces from MJCF: floor, obstacle footprints, clearance field, stations, 3-D checks; walk
surfaces and the levels, steps, ramps and stairs between them."""

from mjwalk.world.clearance import ClearanceField, build_clearance
from mjwalk.world.footprint import Footprint, geom_footprint
from mjwalk.world.levels import (
    Level,
    LevelGraph,
    LevelLink,
    LevelOptions,
    describe_levels,
    level_graph,
)
from mjwalk.world.surfaces import SurfaceOptions, find_walk_surfaces
from mjwalk.world.walksurface import HeadroomMap, Overhead, WalkSurface, head_fits
from mjwalk.world.workplace import (
    Station,
    Workplace,
    WorkplaceOptions,
    load_model,
    load_workplace,
    shared_workplace,
    workplace_from_model,
)

__all__ = [
    "ClearanceField",
    "Footprint",
    "HeadroomMap",
    "Level",
    "LevelGraph",
    "LevelLink",
    "LevelOptions",
    "Overhead",
    "Station",
    "SurfaceOptions",
    "WalkSurface",
    "Workplace",
    "WorkplaceOptions",
    "build_clearance",
    "describe_levels",
    "find_walk_surfaces",
    "geom_footprint",
    "head_fits",
    "level_graph",
    "load_model",
    "load_workplace",
    "shared_workplace",
    "workplace_from_model",
]
