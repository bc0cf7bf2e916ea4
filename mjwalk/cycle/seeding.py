"""The seeding scheme of a batch of cycles, in one place: run ``k`` of the batch of ``seed``
draws from ``SeedSequence([seed, k])`` (:func:`run_generator`), whether it runs in the batch
(:func:`mjwalk.cycle.simulate.simulate_cycles`), alone (``--only-run``) or again for its video
and exports (``mjwalk simulate``); inside a run, the walks draw from the run's generator and
the operator, the task-time factors and the standing spots from three streams spawned from it
(:func:`run_streams`), so each draws the same numbers whatever the others draw."""

from __future__ import annotations

from typing import TYPE_CHECKING, NamedTuple

import numpy as np

if TYPE_CHECKING:
    from mjwalk.cycle.types import CycleSpec
    from mjwalk.gait.walker import Walker


class RunStreams(NamedTuple):
    """The side streams of a run, spawned from its generator (in this order)."""

    operator: np.random.Generator  # who operates (Population.draw)
    handling: np.random.Generator  # the task-time factors (handling.task_factor)
    standing: np.random.Generator  # where the operator stands (the start, each walk's spot)


def run_generator(seed: int, run: int) -> np.random.Generator:
    """The generator of run ``run`` of the batch of root seed ``seed``:
    ``default_rng(SeedSequence([seed, run]))``.

    Args:
        seed: the batch's root seed.
        run: the run's index in the batch.

    Returns:
        The run's generator.
    """
    return np.random.default_rng(np.random.SeedSequence([seed, run]))


def run_streams(rng: np.random.Generator) -> RunStreams:
    """The run's side streams, spawned from its generator ``rng`` (which the walks then draw
    from, unchanged by the spawn).

    Args:
        rng: the run's generator.

    Returns:
        The :class:`RunStreams` (operator, handling, standing).
    """
    return RunStreams(*rng.spawn(3))


def draw_operator(spec: CycleSpec, streams: RunStreams) -> Walker | None:
    """The run's operator, drawn from ``spec.population`` with the operator stream.

    Args:
        spec: the cycle.
        streams: the run's side streams.

    Returns:
        The operator, or None without a population (the reference adult).
    """
    return spec.population.draw(streams.operator) if spec.population is not None else None


def batch_operator(spec: CycleSpec, seed: int, run: int) -> Walker | None:
    """The operator run ``run`` of the batch of ``seed`` draws (as the run itself does).

    Args:
        spec: the cycle.
        seed: the batch's root seed.
        run: the run's index in the batch.

    Returns:
        The operator, or None without a population.
    """
    return draw_operator(spec, run_streams(run_generator(seed, run)))


def rng_entropy(rng: np.random.Generator) -> int | list[int] | None:
    """The entropy of the SeedSequence behind ``rng``: ``default_rng(SeedSequence(entropy))``
    draws the same numbers (``[seed, run]`` for a run of a batch, the seed for
    ``default_rng(seed)``, the OS's draw for ``default_rng()``).

    Args:
        rng: a generator.

    Returns:
        The entropy (an int or a list of ints), or None for a generator built from a spawned
        sequence or without one (it cannot be recreated from an entropy alone).
    """
    seq = getattr(rng.bit_generator, "seed_seq", None)
    if not isinstance(seq, np.random.SeedSequence) or seq.spawn_key:
        return None
    ent = seq.entropy
    if isinstance(ent, list | tuple | np.ndarray):
        return [int(v) for v in ent]
    return None if ent is None else int(ent)  # type: ignore[arg-type]
