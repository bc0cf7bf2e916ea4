"""Workplaces from MJCF: floor, obstacle footprints, clearance field, stations, 3-D checks."""

from mjwalk.world.clearance import ClearanceField, build_clearance
from mjwalk.world.footprint import Footprint, geom_footprint
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
    "Station",
    "Workplace",
    "WorkplaceOptions",
    "build_clearance",
    "geom_footprint",
    "load_model",
    "load_workplace",
    "shared_workplace",
    "workplace_from_model",
]
