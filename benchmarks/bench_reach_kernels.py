"""The reaches' compiled kernels of this tree against a baseline tree's, in one process (issue
50: changes of a few hundred microseconds a cycle, which alternating whole processes on a
shared machine cannot resolve).

Run: PYTHONPATH=. python3 benchmarks/bench_reach_kernels.py --baseline fc03651 [--cycles 10]
     [--rounds 7]

Records the arguments of every :func:`mjwalk.arms.posefit.fit_endpoint_pose` and
:func:`mjwalk.arms.chain.arm_frames` call of ``--cycles`` station cycles (seeds 0..), loads the
baseline tree's ``posefit.py`` and ``chain.py`` beside this tree's (by path, under other module
names: ``git show BASELINE:<file>`` into a temporary directory), replays each call in both,
alternating the trees ``--rounds`` times, and prints one JSON line per kernel: the CPU ms a
cycle of each tree (``time.process_time``, medians and every round), their ratio, and how many
calls give other bytes (0: bit-identical).
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

#: (kernel, module file, function name).
KERNELS = [
    ("fit_endpoint_pose", "mjwalk/arms/posefit.py", "fit_endpoint_pose"),
    ("arm_frames", "mjwalk/arms/chain.py", "arm_frames"),
]


def _record(cycles: int) -> dict[str, list]:
    """The (args, kwargs) of every call of each kernel in ``cycles`` station cycles."""
    import mjwalk
    import mjwalk.cycle.simulate as sim
    from mjwalk.cycle.spec import load_cycle_spec

    spec_path = Path(mjwalk.__file__).resolve().parents[1] / "scenes" / "assembly_station.toml"
    ctx = sim.prepare(load_cycle_spec(spec_path))
    sim.simulate_cycle(ctx, 99)  # warm-up: models, compiled code
    calls: dict[str, list] = {name: [] for name, _, _ in KERNELS}
    patched = []
    for name, path, func in KERNELS:
        module = path[: -len(".py")].replace("/", ".")
        f = getattr(importlib.import_module(module), func)

        def spy(*a, _f=f, _name=name, **k):
            calls[_name].append((a, k))
            return _f(*a, **k)

        for mod_name, mod in list(sys.modules.items()):  # wherever it is bound by name
            if mod_name.startswith("mjwalk") and mod is not None and vars(mod).get(func) is f:
                setattr(mod, func, spy)
                patched.append((mod, func, f))
    try:
        for seed in range(cycles):
            sim.simulate_cycle(ctx, seed, keep_timeline=True)
    finally:
        for mod, func, f in patched:
            setattr(mod, func, f)
    return calls


def _load(path: Path, name: str):
    """The module at ``path`` under the module name ``name``."""
    spec = importlib.util.spec_from_file_location(name, path)
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _bytes(result) -> bytes:
    """The bytes of a kernel's result (arrays, flags and name lists)."""
    parts = result if isinstance(result, tuple) else (result,)
    out = b""
    for p in parts:
        out += np.asarray(p).tobytes() if isinstance(p, np.ndarray) else repr(p).encode()
    return out


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--baseline", required=True, help="commit of the baseline tree")
    ap.add_argument("--cycles", type=int, default=10)
    ap.add_argument("--rounds", type=int, default=7)
    args = ap.parse_args()
    calls = _record(args.cycles)
    here = Path(__file__).resolve().parents[1]
    with tempfile.TemporaryDirectory() as tmp:
        for name, path, func in KERNELS:
            text = subprocess.run(
                ["git", "-C", str(here), "show", f"{args.baseline}:{path}"],
                check=True,
                capture_output=True,
                text=True,
            ).stdout
            base_file = Path(tmp) / f"base_{Path(path).name}"
            base_file.write_text(text)
            trees = {
                "baseline": getattr(_load(base_file, f"_base_{name}"), func),
                "tree": getattr(_load(here / path, f"_tree_{name}"), func),
            }
            recorded = calls[name]
            for f in trees.values():  # compile / load both before timing
                for a, k in recorded[:3]:
                    f(*a, **k)
            differ = sum(
                _bytes(trees["baseline"](*a, **k)) != _bytes(trees["tree"](*a, **k))
                for a, k in recorded
            )
            ms: dict[str, list[float]] = {t: [] for t in trees}
            for _ in range(args.rounds):
                for t, f in trees.items():
                    c0 = time.process_time()
                    for a, k in recorded:
                        f(*a, **k)
                    ms[t].append(1e3 * (time.process_time() - c0) / args.cycles)
            med = {t: float(np.median(v)) for t, v in ms.items()}
            report = {
                "kernel": name,
                "calls_per_cycle": len(recorded) / args.cycles,
                "median_ms_per_cycle": med,
                "ratio": med["tree"] / med["baseline"],
                "rounds": ms,
                "differ": differ,
            }
            print(json.dumps(report))


if __name__ == "__main__":
    main()
