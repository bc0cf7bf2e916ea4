"""The settings of the default and capture reach models (mjwalk.arms.reachdefault)."""

from mjwalk.arms.dcsoptions import DCSOptions
from mjwalk.arms.reach import check_endpoint_model
from mjwalk.arms.reachdefault import CAPTURE_DCS, DEFAULT_DCS, default_reach_model


def test_the_shipped_dcs_settings_are_valid_options():
    default = DCSOptions(**{k: v for k, v in DEFAULT_DCS.items() if k != "rng"})
    default.check()
    assert DEFAULT_DCS["rng"] == 0
    assert default.selection == "loo" and default.trend_fallback
    capture = DCSOptions(**CAPTURE_DCS)
    capture.check()
    assert capture.n_networks == 5 and capture.scaling == ("global", "point")
    assert capture.selection == default.selection  # both chosen by PRESS


def test_the_default_model_is_an_endpoint_model_read_once():
    model = default_reach_model(progress=False)
    check_endpoint_model(model)  # start/end hand in, upper arm, forearm and hand out
    assert len(model.lengths) == 3 and model.n_inputs == 6
    assert default_reach_model(progress=False) is model
