"""The settings record of a DCS network (mjwalk.arms.dcsoptions)."""

import dataclasses

import pytest

from mjwalk.arms.dcs import DCSNetwork
from mjwalk.arms.dcsoptions import DCSOptions
from mjwalk.errors import MjwalkError


def test_options_are_frozen_and_keep_the_file_header_order():
    opts = DCSOptions()
    with pytest.raises(dataclasses.FrozenInstanceError):
        opts.max_neurons = 3  # type: ignore[misc]
    keys = list(opts.as_dict())
    assert keys[:3] == ["max_neurons", "error_threshold", "max_age"]
    assert keys[-3:] == ["min_wins", "trend_fallback", "n_networks"] and len(keys) == 18


def test_a_network_takes_a_record_keywords_over_it_and_its_seed_apart():
    net = DCSNetwork(DCSOptions(max_neurons=8, ridge=0.1), rng=3, max_neurons=9)
    assert net.options.max_neurons == 9 and net.options.ridge == 0.1 and net.rng == 3
    params = net.params()
    assert list(params) == [*DCSOptions().as_dict(), "rng"] and params["rng"] == 3
    assert DCSNetwork(**params).options == net.options
    with pytest.raises(TypeError):
        DCSNetwork(max_nerons=8)


@pytest.mark.parametrize(
    "bad, match",
    [
        ({"max_neurons": 1}, "max_neurons"),
        ({"min_wins": -1}, "min_wins"),
        ({"n_networks": 0}, "n_networks"),
        ({"selection": "kfold"}, "selection"),
    ],
)
def test_check_names_the_setting_a_network_cannot_grow_with(bad, match):
    with pytest.raises(MjwalkError, match=match):
        DCSOptions(**bad).check()
