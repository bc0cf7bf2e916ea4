"""The planner's affine step decoder (mjwalk.plan.decoder): features to checked geometry."""

from __future__ import annotations

import numpy as np

from mjwalk.gait.default import default_model
from mjwalk.gait.walker import Walker
from mjwalk.plan.decoder import StepDecoder, decoder_of


def test_decoder_matches_model_decoding():
    """The planner's affine map gives the model's decoded pelvis samples, landing foot and
    yaws (to rounding) for sampled features, including the far tails."""
    model = default_model()
    rng = np.random.default_rng(4)
    z = np.vstack(
        [
            model.sample_first(20, rng).features,
            model.sample_next_features(
                model.sample_first(2, rng, "left").features, "left", 50, rng
            ),
            3.0 * rng.standard_normal((20, model.n_dims)),
        ]
    )
    m = 16
    dec = StepDecoder(model, m)
    got = z @ dec.matrix + dec.offset
    batch = model.decode(z, "left")
    local, _ = batch.resample(m)
    np.testing.assert_allclose(got[:, :m].real, local[..., 0], atol=1e-9)
    np.testing.assert_allclose(got[:, :m].imag, local[..., 1], atol=1e-9)
    np.testing.assert_allclose(got[:, 0], 0.0, atol=1e-12)  # every step starts at its origin
    np.testing.assert_allclose(got[:, m].real, batch.footprint[:, 0], atol=1e-9)
    np.testing.assert_allclose(got[:, m].imag, batch.footprint[:, 1], atol=1e-9)
    np.testing.assert_allclose(got[:, m + 1].real, batch.footprint[:, 2], atol=1e-9)
    np.testing.assert_allclose(got[:, m + 1].imag, batch.end_yaw, atol=1e-9)


def test_decoder_of_keeps_one_decoder_per_model_and_size():
    model = default_model()
    a = decoder_of(model, 16)
    assert decoder_of(model, 16) is a
    assert a.matrix.shape == (model.n_dims, 2 * 16 + 3) and a.offset.shape == (2 * 16 + 3,)
    assert decoder_of(model, 8).matrix.shape == (model.n_dims, 2 * 8 + 3)


def test_a_walkers_models_made_again_share_its_decoder():
    base = default_model()
    walker = Walker(stature=1.81, speed=1.31, cadence=108.0)
    first = base.for_walker(walker)
    dec = decoder_of(first, 16)
    base.for_walker(Walker(stature=1.62, speed=1.1, cadence=101.0))  # for_walker keeps one
    again = base.for_walker(walker)
    assert again is not first and decoder_of(again, 16) is dec  # the walker sets the decoding
    assert decoder_of(base, 16) is not dec
    fresh = StepDecoder(again, 16)
    assert fresh.matrix.tobytes() == dec.matrix.tobytes()
    assert fresh.offset.tobytes() == dec.offset.tobytes()
