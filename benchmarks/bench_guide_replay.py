"""CPU cost of a station cycle's walk guides alone (``walk_guide``: the minimum-jerk path, the
obstacle in the way or within the berth, the side and the path round it), a baseline commit
against this tree in one process, and whether both give the same bytes (issue 50).

Run: PYTHONPATH=. python3 benchmarks/bench_guide_replay.py --baseline fc03651 [--cycles 10]
     [--rounds 6] [--reps 5]

This tree records the arguments of every :func:`mjwalk.plan.detour.walk_guide` call the
hybrid planner makes in ``--cycles`` animated station cycles (``simulate_cycle`` with
``keep_timeline=True`` on seeds 0.., after one warm-up cycle), each with a copy of its random
stream as it was at the call. The baseline's ``plan/guide.py``, ``plan/sides.py`` and
``plan/detour.py`` (exported as ``bench_cycle.py`` exports a baseline) are loaded beside this
tree's as a second set of modules (the rest of the package is this tree's), and every recorded
call is replayed with each set, alternating the sets round by round (``--rounds``), each round
``--reps`` passes on the CPU clock (``time.process_time``). Prints the median CPU ms a cycle of
each round per set, the medians over the rounds, the ratio, and whether every guide (its
bytes) and every random stream's state after the call are equal between the sets.
"""

from __future__ import annotations

import argparse
import copy
import hashlib
import importlib.util
import os
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
_MODULES = ("guide", "sides", "detour")  # in import order: each imports the ones before


def _record(cycles: int) -> list[tuple]:
    """The (args, kwargs) of every walk_guide call in ``cycles`` station cycles, each call's
    random stream copied as it was when called."""
    import mjwalk.cycle.simulate as sim
    import mjwalk.plan.hybrid as hybrid
    from mjwalk.cycle.spec import load_cycle_spec

    ctx = sim.prepare(load_cycle_spec(ROOT / "scenes" / "assembly_station.toml"))
    sim.simulate_cycle(ctx, 99, keep_timeline=True)  # warm-up: models, compiled code
    calls: list[tuple] = []
    real = hybrid.walk_guide

    def spy(*a, **k):
        calls.append(((a[0], *copy.deepcopy(a[1:])), k))  # the workplace itself: its caches
        return real(*a, **k)

    hybrid.walk_guide = spy  # type: ignore[assignment]
    try:
        for seed in range(cycles):
            sim.simulate_cycle(ctx, seed, keep_timeline=True)
    finally:
        hybrid.walk_guide = real  # type: ignore[assignment]
    return calls


def _load_baseline(tree: Path):
    """The baseline's walk_guide: its guide, sides and detour modules loaded under their own
    names, each importing the baseline's modules before it."""
    saved = {m: sys.modules[f"mjwalk.plan.{m}"] for m in _MODULES}
    loaded = {}
    try:
        for m in _MODULES:
            name = f"mjwalk.plan.{m}"
            spec = importlib.util.spec_from_file_location(
                name, tree / "mjwalk" / "plan" / f"{m}.py"
            )
            assert spec is not None and spec.loader is not None
            mod = importlib.util.module_from_spec(spec)
            sys.modules[name] = mod  # the next baseline module imports this one
            spec.loader.exec_module(mod)
            loaded[m] = mod
    finally:
        sys.modules.update({f"mjwalk.plan.{m}": mod for m, mod in saved.items()})
    return loaded["detour"].walk_guide


def _replay(fn, calls) -> tuple[list, float]:
    """Every recorded call through ``fn`` (fresh copies of the random streams): the results
    with each stream's state after, and the CPU seconds."""
    rngs = [copy.deepcopy(a[-1]) for a, _ in calls]
    t0 = time.process_time()
    out = [fn(*a[:-1], rng, **k) for (a, k), rng in zip(calls, rngs, strict=True)]
    cpu = time.process_time() - t0
    return [(o, r.bit_generator.state) for o, r in zip(out, rngs, strict=True)], cpu


def _digest(results) -> str:
    h = hashlib.sha256()
    for path, state in results:
        h.update(b"none" if path is None else path.tobytes())
        h.update(repr(state).encode())
    return h.hexdigest()


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--baseline", default="fc03651", help="commit timed as the old code")
    ap.add_argument("--cycles", type=int, default=10)
    ap.add_argument("--rounds", type=int, default=6)
    ap.add_argument("--reps", type=int, default=5)
    args = ap.parse_args()
    sys.path.insert(0, str(ROOT / "benchmarks"))
    from bench_cycle import baseline_tree

    from mjwalk.plan.detour import walk_guide

    calls = _record(args.cycles)
    sets = {"old": _load_baseline(baseline_tree(args.baseline)), "new": walk_guide}
    digests = {name: _digest(_replay(fn, calls)[0]) for name, fn in sets.items()}  # + compile
    ms: dict[str, list[float]] = {name: [] for name in sets}
    for r in range(args.rounds):
        for name in ("old", "new") if r % 2 == 0 else ("new", "old"):
            reps = [_replay(sets[name], calls)[1] for _ in range(args.reps)]
            ms[name].append(1e3 * statistics.median(reps) / args.cycles)
    print(
        f"walk_guide of {len(calls)} calls ({args.cycles} station cycles), CPU ms a cycle, "
        f"median of {args.reps} passes per round: baseline {args.baseline} (old) vs this tree "
        f"(new), one process; load {os.getloadavg()[0]:.1f}"
    )
    med = {}
    for name in sets:
        med[name] = statistics.median(ms[name])
        rounds = ", ".join(f"{v:.3f}" for v in ms[name])
        print(f"  {name}: rounds {rounds}; median {med[name]:.3f}")
    same = digests["old"] == digests["new"]
    print(f"  new/old {med['new'] / med['old']:.3f}; same guides and streams: {same}")


if __name__ == "__main__":
    main()
