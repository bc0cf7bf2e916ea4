"""The settings of a DCS network (:class:`~mjwalk.arms.dcs.DCSNetwork`) in one frozen record,
with where each default comes from.

A network's saved file stores these settings (and the seed) as the ``params`` of its header
(:mod:`mjwalk.arms.dcsfile`), in the order of the fields below; :meth:`DCSOptions.as_dict`
gives them in that order. The shipped models override some of them
(:data:`~mjwalk.arms.reachdefault.DEFAULT_DCS`, :data:`~mjwalk.arms.reachdefault.CAPTURE_DCS`).
A field that may be a sequence is a grid chosen while the network grows (:mod:`mjwalk.arms.dcsfit`).
"""

from __future__ import annotations

from dataclasses import dataclass, fields

from mjwalk.errors import MjwalkError


@dataclass(frozen=True)
class DCSOptions:
    """How a :class:`~mjwalk.arms.dcs.DCSNetwork` grows and chooses its outputs.

    Defaults marked "first implementation" are the values the network was written with
    (Bruske & Sommer 1995 give the algorithm, not these numbers) and were not tuned since;
    the shipped models set their own where it mattered (:mod:`mjwalk.arms.reachdefault`).

    Attributes:
        max_neurons: upper bound on the number of neurons (first implementation: 30).
        error_threshold: stop growing once the training RMSE (output units) is below this
            (0: never; growth stops by size or held-out error instead).
        max_age: lateral edges not refreshed for more than this many winning presentations of
            their endpoint are removed (first implementation: 30).
        width_factor: ``sigma_i = width_factor *`` mean distance of neuron ``i`` to its lateral
            neighbours (1: the mean edge length itself); a sequence is a grid.
        eps_winner: Kohonen learning rate of the winner (first implementation: 0.05).
        eps_neighbour: Kohonen learning rate of the winner's neighbours (first
            implementation: 0.005, a tenth of the winner's).
        n_epochs: presentations of the whole training set per growth step (first
            implementation: 3).
        validation_fraction: share of samples held out to select the network size (0
            disables; 0.2, the usual fifth held out).
        n_iter_no_change: insertions without held-out improvement before growth stops (first
            implementation: 6).
        ridge: Tikhonov regularization of the output least squares (relative to the design
            scale), towards each neuron's mean target (1e-6: just enough to keep it well
            posed); a sequence is a grid.
        scaling: input standardization, ``"column"``, ``"global"`` or ``"point"``
            (:mod:`mjwalk.arms.dcsfit`; default per column, zero mean and unit variance); a
            sequence is a grid.
        selection: ``"holdout"`` (default) or ``"loo"`` (PRESS on all samples;
            :mod:`mjwalk.arms.dcsfit`).
        local_linear: per-neuron local linear outputs (default off: eq. 2's constant
            outputs); a sequence is a grid.
        global_linear: add a global linear term ``T z`` (default off); a sequence is a grid.
            Left out, like ``local_linear``, with fewer than
            :data:`~mjwalk.arms.dcsfit.SAMPLES_PER_COEFFICIENT` samples per input column.
        slope_ridge: penalty of the local slopes relative to ``ridge`` (> 0; 1: the same);
            a sequence is a grid (used only with local linear outputs).
        min_wins: neurons winning fewer training samples after an adaptation pass are removed
            (dead units, Fritzke 1995; 1 removes neurons that win nothing, 0 keeps every one).
        trend_fallback: blend into the trend network outside the trained range
            (:mod:`mjwalk.arms.dcs`; default off).
        n_networks: networks grown from independent seeds and averaged (default 1: one).
    """

    max_neurons: int = 30
    error_threshold: float = 0.0
    max_age: int = 30
    width_factor: float | tuple[float, ...] = 1.0
    eps_winner: float = 0.05
    eps_neighbour: float = 0.005
    n_epochs: int = 3
    validation_fraction: float = 0.2
    n_iter_no_change: int = 6
    ridge: float | tuple[float, ...] = 1e-6
    scaling: str | tuple[str, ...] = "column"
    selection: str = "holdout"
    local_linear: bool | tuple[bool, ...] = False
    global_linear: bool | tuple[bool, ...] = False
    slope_ridge: float | tuple[float, ...] = 1.0
    min_wins: int = 1
    trend_fallback: bool = False
    n_networks: int = 1

    def as_dict(self) -> dict:
        """The settings as keyword arguments, in field order (the file header's order).

        Returns:
            ``{field name: value}`` for every field of :class:`DCSOptions`.
        """
        return {f.name: getattr(self, f.name) for f in fields(self)}

    def check(self) -> None:
        """Raise :class:`~mjwalk.errors.MjwalkError` on a size, dead-unit, ensemble or
        selection setting a network cannot grow with (the grids are checked as they are read,
        :func:`~mjwalk.arms.dcsfit.grid_values`)."""
        if self.max_neurons < 2:
            raise MjwalkError(f"DCSNetwork: max_neurons must be >= 2, got {self.max_neurons}")
        if int(self.min_wins) != self.min_wins or self.min_wins < 0:
            raise MjwalkError(f"DCSNetwork: min_wins must be an integer >= 0, got {self.min_wins}")
        if int(self.n_networks) != self.n_networks or self.n_networks < 1:
            raise MjwalkError(
                f"DCSNetwork: n_networks must be an integer >= 1, got {self.n_networks}"
            )
        if self.selection not in ("holdout", "loo"):
            raise MjwalkError(
                f"DCSNetwork: selection must be 'holdout' or 'loo', got {self.selection!r}"
            )
