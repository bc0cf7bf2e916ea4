"""What the ``mjwalk`` sub-commands share: help texts."""

from __future__ import annotations

#: The shipped scenes a scene argument may name.
SCENES = "station, corridor, open_floor"
#: Help of every command's ``--quiet``.
QUIET_HELP = "no progress messages or bars (warnings and errors only)"
