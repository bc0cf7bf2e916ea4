"""mjwalk.scan.scanoptions: how a scan becomes a scene, one checked record."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import mjwalk
from mjwalk.cli import build_parser
from mjwalk.cli.scenes import scan_options
from mjwalk.errors import InputError, ScanError
from mjwalk.scan import ScanOptions
from mjwalk.scan.scanoptions import DEFAULT_RESOLUTION, ScanOptionsError


def test_defaults_and_their_exports():
    opts = ScanOptions()
    assert (opts.units, opts.up, opts.drop_invalid) == ("m", "+z", False)
    assert opts.resolution == DEFAULT_RESOLUTION == 0.02
    assert (opts.offset, opts.voids, opts.register) == (None, "blocked", False)
    assert opts.gaps == "obstacle"
    assert mjwalk.ScanOptions is ScanOptions
    with pytest.raises(dataclasses.FrozenInstanceError):
        opts.units = "mm"  # type: ignore[misc]


def test_values_are_normalised():
    opts = ScanOptions(resolution="0.05", offset=np.array([1.0, -2.0, 3.5]))  # type: ignore[arg-type]
    assert opts.resolution == 0.05 and isinstance(opts.resolution, float)
    assert opts.offset == (1.0, -2.0, 3.5) and all(type(v) is float for v in opts.offset)
    assert ScanOptions(offset=(1, 2, 3)) == ScanOptions(offset=(1.0, 2.0, 3.0))


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"resolution": 0}, "resolution 0 m is outside 0.005-0.1 m"),
        ({"voids": "open"}, "unknown --voids 'open' (one of blocked, fill, free)"),
        ({"gaps": "fence"}, "unknown gaps 'fence' (one of obstacle, floor)"),
        ({"units": "furlong"}, "scan options: unknown units 'furlong'"),
        ({"up": "w"}, "scan options: unknown up axis 'w'"),
        ({"offset": (1.0, 2.0)}, "offset must be 3 finite numbers (file units), got (1.0, 2.0)"),
        ({"offset": (1.0, np.nan, 2.0)}, "offset must be 3 finite numbers"),
    ],
)
def test_bad_values_are_one_line_errors(kwargs, message):
    with pytest.raises(ScanOptionsError) as info:
        ScanOptions(**kwargs)
    assert message in str(info.value) and "\n" not in str(info.value)
    assert isinstance(info.value, ScanError) and isinstance(info.value, InputError)


def test_the_scan_command_builds_its_options_in_one_place():
    args = build_parser().parse_args(
        [
            "scan",
            "a.ply",
            "-o",
            "a.xml",
            "--units",
            "mm",
            "--up=-y",
            "--resolution",
            "0.05",
            "--offset=1,2,3",
            "--voids",
            "fill",
            "--register",
            "--drop-invalid",
            "--gaps",
            "floor",
        ]
    )
    assert scan_options(args) == ScanOptions(
        units="mm",
        up="-y",
        drop_invalid=True,
        resolution=0.05,
        offset=(1.0, 2.0, 3.0),
        voids="fill",
        register=True,
        gaps="floor",
    )
    defaults = build_parser().parse_args(["scan", "a.ply", "-o", "a.xml"])
    assert scan_options(defaults) == ScanOptions()
