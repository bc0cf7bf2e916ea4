"""The timeline stage: per-frame humanoid poses of walks and reaches in a scene
(:mod:`~mjwalk.timeline.timeline`, :mod:`~mjwalk.timeline.frames`,
:mod:`~mjwalk.timeline.reachscene`), playback and humanoid-vs-scene collision checks
(:mod:`~mjwalk.timeline.collisions`)."""

from mjwalk.timeline.collisions import Contact, check_collisions, collision_report
from mjwalk.timeline.frames import frames_from_legs, timeline_from_walk
from mjwalk.timeline.parts import PartTrack, part_tracks
from mjwalk.timeline.reachscene import SceneReachOptions, reach_in_scene
from mjwalk.timeline.timeline import Event, Timeline, iter_frames

__all__ = [
    "Contact",
    "Event",
    "PartTrack",
    "SceneReachOptions",
    "Timeline",
    "check_collisions",
    "collision_report",
    "frames_from_legs",
    "iter_frames",
    "part_tracks",
    "reach_in_scene",
    "timeline_from_walk",
]
