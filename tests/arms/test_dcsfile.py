"""The file form of a DCS network (mjwalk.arms.dcsfile): arrays, header and the rebuilt network."""

import numpy as np
import pytest

from mjwalk.arms.dcs import DCSNetwork
from mjwalk.arms.dcsfile import (
    DCS_FORMAT,
    DCS_VERSION,
    network_arrays,
    network_from_arrays,
    network_header,
)
from mjwalk.errors import ModelFileError


def _fitted():
    rng = np.random.default_rng(3)
    X = rng.uniform(-1, 1, (80, 2))
    Y = np.c_[np.sin(2 * X[:, 0]) + X[:, 1] ** 2, np.cos(X[:, 1])]
    net = DCSNetwork(max_neurons=8, trend_fallback=True, n_networks=2, rng=0).fit(X, Y)
    return net, X


def test_nested_networks_share_the_first_ones_training_inputs_and_rebuild_exactly():
    net, X = _fitted()
    arrays, header = network_arrays(net), network_header(net)
    assert (header["format"], header["version"]) == (DCS_FORMAT, DCS_VERSION)
    # only the first network keeps the training inputs; the trend and member networks nest
    assert [k for k in arrays if k.endswith("train_z")] == ["train_z"]
    assert "fallback.centers" in arrays and "member0.centers" in arrays
    assert len(header["members"]) == 1 and "fallback" in header
    back = network_from_arrays(DCSNetwork, header, arrays)
    assert type(back) is DCSNetwork
    np.testing.assert_array_equal(back.predict(X), net.predict(X))
    np.testing.assert_array_equal(back.fallback_.train_z_, net.train_z_)
    assert back.range_radius_ == net.range_radius_


def test_inconsistent_arrays_are_a_model_file_error_naming_the_source():
    net, _ = _fitted()
    arrays = network_arrays(net)
    arrays["widths"] = arrays["widths"][:-1]
    with pytest.raises(ModelFileError, match=r"net\.npz: corrupt DCS network"):
        network_from_arrays(DCSNetwork, network_header(net), arrays, source="net.npz")
