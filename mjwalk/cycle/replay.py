"""Runs of a batch simulated again with their timelines, for ``mjwalk simulate``'s video and
motion exports: run ``k`` of the batch of ``seed`` draws from the same generator as in the batch
(:func:`mjwalk.cycle.seeding.run_generator`), so it is the same cycle."""

from __future__ import annotations

from collections.abc import Iterable, Iterator, MutableMapping, Sequence
from pathlib import Path

from mjwalk.cycle.context import CycleContext
from mjwalk.cycle.seeding import run_generator
from mjwalk.cycle.simulate import simulate_cycle
from mjwalk.cycle.types import CycleResult
from mjwalk.ergonomics.export import write_angles_csv, write_bvh

#: The motion files :func:`export_runs` writes, by kind: file name of run ``k`` in the folder.
EXPORT_NAMES = {"bvh": "run_{:03d}.bvh", "csv": "run_{:03d}_angles.csv"}


def replay_run(ctx: CycleContext, seed: int, run: int) -> CycleResult:
    """Run ``run`` of the batch of ``seed`` again, keeping its timeline.

    The video and the exports need the motion only: no collision check, no scoring.

    Args:
        ctx: the batch's cycle context (:func:`mjwalk.cycle.context.context_of`).
        seed: the batch's root seed.
        run: the run's index in the batch.

    Returns:
        The run's result with its ``timeline`` (frames at 30 fps).
    """
    rng = run_generator(seed, run)
    return simulate_cycle(ctx, rng, run=run, keep_timeline=True, collisions=False, ergonomics=False)


def export_runs(
    ctx: CycleContext,
    seed: int,
    results: Sequence[CycleResult],
    out: Path,
    kinds: Iterable[str],
    replayed: MutableMapping[int, CycleResult] | None = None,
) -> Iterator[tuple[str, Path]]:
    """Write each successful run's humanoid motion into ``out``, replaying the runs.

    Files are named as in :data:`EXPORT_NAMES` (:mod:`mjwalk.ergonomics.export`); each run
    is replayed once (:func:`replay_run`) unless ``replayed`` already holds it.

    Args:
        ctx: the batch's cycle context.
        seed: the batch's root seed.
        results: the batch's results (failed runs are skipped).
        out: the folder to write into.
        kinds: ``"bvh"`` and/or ``"csv"`` (joint angles), repeats ignored.
        replayed: runs already simulated again with their timelines, by run index, or None.

    Yields:
        ``(kind, path)`` for each file as soon as it is written.
    """
    replayed = {} if replayed is None else replayed
    for r in results:
        if r.error is not None:
            continue
        run = replayed.get(r.run) or replay_run(ctx, seed, r.run)
        for kind in dict.fromkeys(kinds):
            if kind == "bvh":
                path = write_bvh(run.timeline, out / EXPORT_NAMES["bvh"].format(r.run))
            else:
                path = write_angles_csv(run.timeline, out / EXPORT_NAMES["csv"].format(r.run))
            yield kind, path
