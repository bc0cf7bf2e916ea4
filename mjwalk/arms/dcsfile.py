"""The file form of a DCS network (:class:`~mjwalk.arms.dcs.DCSNetwork`): its arrays and
header for one versioned ``.npz`` (:func:`mjwalk._io.save_npz`), and the network rebuilt from
them. The trend network and the averaged networks nest under ``fallback.`` and ``member<j>.``
prefixes; only the first network keeps the standardized training inputs.

The file form knows a network by the fields it stores, :class:`DCSFields`, not by its class:
the network's ``save`` and ``load`` call this module, and this module needs nothing of the
network but those fields."""

from __future__ import annotations

from collections.abc import Callable
from typing import Protocol, Self, TypeVar

import numpy as np

from mjwalk._io import check_header
from mjwalk.errors import ModelFileError


class DCSFields(Protocol):
    """The fields of a fitted DCS network the file stores, and the two methods it needs.

    Arrays are in standardized input units (see :mod:`mjwalk.arms.dcs`): ``centers_`` (K, d),
    ``outputs_`` (K, m), ``widths_`` (K,), ``edges_`` (K, K) bool, ``x_mean_``/``x_scale_``
    (d,), ``train_z_`` (N, d) the standardized training inputs, ``slopes_`` (K, d, m) or None,
    ``trend_`` (d, m) or None. ``fallback_`` and ``members_`` are networks of the same kind.
    """

    centers_: np.ndarray
    outputs_: np.ndarray
    widths_: np.ndarray
    edges_: np.ndarray
    x_mean_: np.ndarray
    x_scale_: np.ndarray
    train_z_: np.ndarray
    slopes_: np.ndarray | None
    trend_: np.ndarray | None
    y_1d_: bool
    train_rmse_: float
    width_factor_: float
    ridge_: float
    local_linear_: bool
    global_linear_: bool
    slope_ridge_: float
    scaling_: str
    history_: list[tuple[int, float, float]]
    n_pruned_: int
    n_neurons_: int
    fallback_: Self | None
    members_: list[Self]

    def params(self) -> dict:
        """The constructor arguments, as the header stores them.

        Returns:
            the constructor arguments.
        """
        ...

    def set_training_points(self, Z: np.ndarray) -> None:
        """Keep the standardized training inputs ``Z`` (N, d) and the trained range.

        Args:
            Z: (N, d) standardized training inputs.
        """
        ...


#: A network type the file form rebuilds (whatever class satisfies :class:`DCSFields`).
NetworkT = TypeVar("NetworkT", bound=DCSFields)

DCS_FORMAT = "mjwalk.dcs"
#: 2: optional global linear term (``trend``) and slope ridge; 3: dead-unit pruning and the
#: trend fallback network. Version 1 and 2 files still load (no fallback).
DCS_VERSION = 3


def network_arrays(net: DCSFields, with_training: bool = True) -> dict:
    """The arrays :meth:`DCSNetwork.save` writes. The trend network and the averaged networks were
    fitted on the same inputs, so only the first network keeps the training inputs
    (``with_training``); they borrow them on load.

    Args:
        net: the fitted network.
        with_training: include the standardized training inputs ``train_z``.

    Returns:
        ``{name: array}``, nested networks under ``fallback.`` and ``member<j>.``.
    """
    fallback = getattr(net, "fallback_", None)
    return {
        "centers": net.centers_,
        "outputs": net.outputs_,
        "widths": net.widths_,
        "edges": net.edges_,
        "x_mean": net.x_mean_,
        "x_scale": net.x_scale_,
        **({"train_z": net.train_z_} if with_training else {}),
        **({} if net.slopes_ is None else {"slopes": net.slopes_}),
        **({} if net.trend_ is None else {"trend": net.trend_}),
        **(
            {}
            if fallback is None
            else {f"fallback.{k}": v for k, v in network_arrays(fallback, False).items()}
        ),
        **{
            f"member{j}.{k}": v
            for j, m in enumerate(getattr(net, "members_", []))
            for k, v in network_arrays(m, False).items()
        },
    }


def network_header(net: DCSFields) -> dict:
    """The header :meth:`DCSNetwork.save` writes: format, version, parameters, the values the
    grids chose and the growth history, and those of the trend and averaged networks.

    Args:
        net: the fitted network.

    Returns:
        the header dict (JSON-serializable).
    """
    params = net.params()
    fallback = getattr(net, "fallback_", None)
    return {
        "format": DCS_FORMAT,
        "version": DCS_VERSION,
        "params": params,
        "y_1d": bool(net.y_1d_),
        "train_rmse": net.train_rmse_,
        "width_factor_": getattr(net, "width_factor_", None),
        "ridge_": getattr(net, "ridge_", None),
        "local_linear_": net.slopes_ is not None,
        "global_linear_": net.trend_ is not None,
        "slope_ridge_": getattr(net, "slope_ridge_", None),
        "scaling_": getattr(net, "scaling_", None),
        "history": [[int(a), float(b), float(c)] for a, b, c in net.history_],
        "n_pruned_": int(getattr(net, "n_pruned_", 0)),
        **({} if fallback is None else {"fallback": network_header(fallback)}),
        "members": [network_header(m) for m in getattr(net, "members_", [])],
    }


def network_from_arrays(
    cls: Callable[..., NetworkT],
    header: dict,
    data: dict,
    source: str = "<arrays>",
    train_z: np.ndarray | None = None,
) -> NetworkT:
    """Rebuild a network of class ``cls`` (called with the header's parameters) from
    :meth:`DCSNetwork.save`'s header and arrays; ``train_z``: the training inputs of the
    network this one belongs to (its trend network or an averaged network), used when ``data``
    has none.

    Args:
        cls: the network class (or factory) called with the header's ``params``.
        header: the header :func:`network_header` wrote.
        data: the arrays :func:`network_arrays` wrote.
        source: name of the source in errors.
        train_z: (N, d) standardized training inputs, or None.

    Returns:
        the fitted network; a corrupt header or arrays raise :class:`~mjwalk.errors.ModelFileError`.
    """
    version = header.get("version")  # version 1-2 files (no trend/fallback) read the same
    check_header(
        header, source, "DCS network", DCS_FORMAT, version if version in (1, 2) else DCS_VERSION
    )
    try:
        params = dict(header["params"])
        if "random_state" in params:  # files written before the rng/seed convention
            params["rng"] = params.pop("random_state")
        net = cls(**params)
        net.centers_ = np.asarray(data["centers"], dtype=float)
        net.outputs_ = np.asarray(data["outputs"], dtype=float)
        net.widths_ = np.asarray(data["widths"], dtype=float)
        net.edges_ = np.asarray(data["edges"], dtype=bool)
        net.x_mean_ = np.asarray(data["x_mean"], dtype=float)
        net.x_scale_ = np.asarray(data["x_scale"], dtype=float)
        net.y_1d_ = bool(header["y_1d"])
        net.train_rmse_ = float(header["train_rmse"])
        net.width_factor_ = header.get("width_factor_")  # type: ignore[assignment]
        net.ridge_ = header.get("ridge_")  # type: ignore[assignment]
        net.local_linear_ = bool(header.get("local_linear_", False))
        net.slopes_ = np.asarray(data["slopes"], dtype=float) if net.local_linear_ else None
        net.global_linear_ = bool(header.get("global_linear_", False))
        net.slope_ridge_ = header.get("slope_ridge_")  # type: ignore[assignment]
        net.trend_ = np.asarray(data["trend"], dtype=float) if net.global_linear_ else None
        net.scaling_ = header.get("scaling_") or params.get("scaling", "column")
        net.history_ = [tuple(h) for h in header.get("history", [])]
        net.n_pruned_ = int(header.get("n_pruned_", 0))
        own = np.asarray(data["train_z"] if "train_z" in data else train_z, dtype=float)
        if own.ndim != 2:
            raise ValueError("no training inputs")
        net.fallback_ = None
        if "fallback" in header:
            sub = {k[9:]: v for k, v in data.items() if k.startswith("fallback.")}
            net.fallback_ = network_from_arrays(cls, header["fallback"], sub, source, own)
        net.members_ = []
        for j, sub_header in enumerate(header.get("members", [])):
            pre = f"member{j}."
            sub = {k[len(pre) :]: v for k, v in data.items() if k.startswith(pre)}
            net.members_.append(network_from_arrays(cls, sub_header, sub, source, own))
        k = len(net.centers_)
        if (
            net.outputs_.shape[0] != k
            or net.widths_.shape != (k,)
            or net.edges_.shape != (k, k)
            or net.centers_.shape[1] != len(net.x_mean_)
            or (
                net.slopes_ is not None
                and net.slopes_.shape != (k, len(net.x_mean_), net.outputs_.shape[1])
            )
            or (
                net.trend_ is not None
                and net.trend_.shape != (len(net.x_mean_), net.outputs_.shape[1])
            )
        ):
            raise ValueError("array shapes are inconsistent")
        net.n_neurons_ = k
        net.set_training_points(own)
    except (KeyError, TypeError, ValueError, IndexError) as exc:
        raise ModelFileError(f"{source}: corrupt DCS network ({exc})") from exc
    return net
