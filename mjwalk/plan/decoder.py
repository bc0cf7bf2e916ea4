"""The step decoder of the hybrid A*: a step's features to its checked geometry as one
affine map (:class:`StepDecoder`), built once per model (:func:`decoder_of`).
"""

from __future__ import annotations

import weakref

import numpy as np

from mjwalk.errors import PlanningError
from mjwalk.gait.features import I_DUR, StepBatch


class StepDecoder:
    """What the search needs of a step, as one affine map of its standardized features z (d,).

    ``z @ matrix + offset`` is a complex row (2m + 3,) in the step's local frame (x right,
    y forward; x + iy, metres): the pelvis at m samples evenly spaced in time (sample 0 is the
    start, exactly 0; sample m-1 the end), the landing ankle, (landing foot yaw +
    i · end pelvis yaw) in radians relative to the start heading, and the pelvis yaw at the
    m samples (real parts, radians relative to the start heading; the stance-lean check
    decodes them only for the steps that reach it) and the duration (real part, seconds, not
    clipped; the energy cost's). Decoding features and
    evaluating the landmark spline are both affine (see :mod:`mjwalk.gait.features`), so the
    map is read off the model's own decoder at z = 0 and the unit vectors, then checked on
    random features: a model whose decoding is not affine is refused, not mis-planned.

    Args:
        model: the step model (its ``n_dims`` features, ``decode`` and ``features``).
        m: pelvis samples per step.

    Raises:
        PlanningError: the model's decoding is not affine in its features.
    """

    def __init__(self, model, m: int):
        self.m = m
        self._reach: dict[int, tuple[np.ndarray, np.ndarray]] = {}
        d = model.n_dims
        basis = np.vstack([np.zeros(d), np.eye(d)])
        cols = self._columns(model, basis, m)
        self.offset = cols[0]
        self.matrix = np.ascontiguousarray(cols[1:] - cols[0])
        z = np.random.default_rng(0).standard_normal((16, d)) * 3.0
        ref = self._columns(model, z, m)
        if not np.allclose(z @ self.matrix + self.offset, ref, rtol=0.0, atol=1e-9):
            raise PlanningError("the step model's decoding is not affine in its features")

    def closing_reach(self, gp) -> tuple[np.ndarray, np.ndarray]:
        """How far a draw's mean and residual move a step's decoded end (column m - 1) from
        the mean's value at an inducing input, for the closing draws of
        :func:`mjwalk.plan.search.search` (:func:`~mjwalk.plan.stepgeom.closing_ends_far`):
        within r·√(2(1 - e_j)) + spread of f_z[j] for the kernel row e_j of inducing input j
        (:meth:`~mjwalk.gait.transition.TransitionGP.mean_reach`, plus the residual pools'
        largest move and the roundings). Made once per GP.

        Args:
            gp: the :class:`~mjwalk.gait.transition.TransitionGP`.

        Returns:
            ((r, spread) metres, f_z (m_gp,) complex, step frame, metres).
        """
        hit = self._reach.get(id(gp))
        if hit is None:
            v = self.matrix[:, self.m - 1]
            r, f_z, slack = gp.mean_reach(v)
            flat = gp.kernel[7]  # the residual pools (m·k, d): real products, no complex copy
            pool = float(np.hypot(flat @ v.real, flat @ v.imag).max()) * (1.0 + 1e-9) + 1e-12
            hit = (np.array([r, slack + pool]), np.ascontiguousarray(f_z))
            self._reach[id(gp)] = hit
        return hit

    @staticmethod
    def _columns(model, z: np.ndarray, m: int) -> np.ndarray:
        batch: StepBatch = model.decode(z, "left")
        local, yaw = batch.resample(m)
        return np.column_stack(
            [
                local[..., 0] + 1j * local[..., 1],
                batch.footprint[:, 0] + 1j * batch.footprint[:, 1],
                batch.footprint[:, 2] + 1j * batch.end_yaw,
                yaw + 0j,
                # the duration before decode's clip at MIN_DURATION (the check clips it)
                model.features.decode_raw(z)[:, I_DUR] + 0j,
            ]
        )


#: Decoders already built, by model (a conditioned model: its base and walker) and samples per
#: step (:func:`decoder_of`); the model is held weakly and the oldest entries go beyond
#: :data:`_DECODERS_MAX`.
_DECODERS: dict[tuple[int, object, int], tuple[weakref.ref, StepDecoder]] = {}
_DECODERS_MAX = 16


def decoder_of(model, m: int) -> StepDecoder:
    """The :class:`StepDecoder` of ``model`` at ``m`` samples per step, built once per process.

    Building one decodes and checks 23 feature rows (about 0.15 ms, as much as a short walk's
    whole search); planners are made per goal (a cycle's walks, a benchmark's start/goal
    pairs), models per operator (:meth:`StepModel.for_walker`), so it is shared by model.

    Args:
        model: the step model (:class:`~mjwalk.gait.model.StepModel`).
        m: pelvis samples per step.

    Returns:
        The model's decoder, shared by model and ``m`` (the model held weakly).
    """
    owner, walker = getattr(model, "_base", None), getattr(model, "_walker", None)
    if owner is None or walker is None:
        owner, walker = model, None
    # a conditioned model's decoding is its base's features scaled by factors that the walker
    # sets (StepModel.for_walker): the same walker's models, made again, share a decoder
    key = (id(owner), walker, int(m))
    hit = _DECODERS.get(key)
    if hit is not None and hit[0]() is owner:
        return hit[1]
    dec = StepDecoder(model, m)
    while len(_DECODERS) >= _DECODERS_MAX:
        _DECODERS.pop(next(iter(_DECODERS)))
    _DECODERS[key] = (weakref.ref(owner), dec)
    return dec
