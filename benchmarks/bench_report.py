"""What ``mjwalk simulate``'s report costs as the batch grows (issue 50: 10 000 cycles with
``--jobs 2`` in 10 minutes, the report included), and that a faster tree writes the same files.

Run: python3 benchmarks/bench_report.py [--runs 40] [--scale 400 2000] [--against /work/main]

Simulates ``--runs`` station runs once (seed 0, this tree), then for each ``--scale`` N repeats
them up to N runs (deep copies numbered on) and, in a fresh process per tree (this one and
``--against``), times what the command does after the batch: ``report_dict``,
``write_report`` (report.json, the CSVs, report.md, the three PNGs) and the printed summary.
Prints CPU seconds (the machine is shared: CPU time, not wall) and whether every file and the
summary are byte-identical between the trees.
"""

from __future__ import annotations

import argparse
import filecmp
import os
import pickle
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SPEC = ROOT / "scenes" / "assembly_station.toml"

#: The timed part, run in a fresh process with the tree on PYTHONPATH: argv = results pickle,
#: runs, output folder. Trees without ``write_report(report=...)`` compute the figures twice,
#: as their ``mjwalk simulate`` did.
_TIMED = """
import copy, inspect, pickle, sys, time
import mjwalk
from pathlib import Path
from mjwalk.report import format_summary, report_dict, write_report
from mjwalk.world import shared_workplace
res = pickle.load(open(sys.argv[1], "rb"))
n, out = int(sys.argv[2]), Path(sys.argv[3])
base = list(res)
while len(res) < n:
    r = copy.deepcopy(base[len(res) % len(base)])
    r.run = len(res)
    res.append(r)
res = res[:n]
wp = shared_workplace(res[0].spec.scene)
c = time.process_time()
if "report" in inspect.signature(write_report).parameters:
    rep = report_dict(res)
    write_report(res, out, workplace=wp, report=rep)
    text = format_summary(rep)
else:
    write_report(res, out, workplace=wp)
    text = format_summary(report_dict(res))
print(mjwalk.__file__)
print(time.process_time() - c)
(out / "summary.txt").write_text(text)
"""


def _timed(tree: Path, pickled: Path, runs: int, out: Path) -> float:
    """CPU seconds of the report of ``runs`` runs in a fresh process of ``tree``."""
    out.mkdir(parents=True)
    env = {**os.environ, "PYTHONPATH": str(tree)}
    cmd = [sys.executable, "-c", _TIMED, str(pickled), str(runs), str(out)]
    # in the tree's own folder: ``python -c`` puts the working folder before PYTHONPATH
    done = subprocess.run(cmd, check=True, capture_output=True, text=True, env=env, cwd=tree)
    where, cpu = done.stdout.strip().splitlines()[-2:]
    assert where.startswith(str(tree)), f"{tree}: ran {where}"
    return float(cpu)


def _same(a: Path, b: Path) -> bool:
    """Whether folders ``a`` and ``b`` hold the same files, byte for byte."""
    names = sorted(p.name for p in a.iterdir())
    if names != sorted(p.name for p in b.iterdir()):
        return False
    return all(filecmp.cmp(a / n, b / n, shallow=False) for n in names)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=40, help="runs simulated (then repeated)")
    ap.add_argument("--scale", type=int, nargs="+", default=[400, 2000])
    ap.add_argument("--against", type=Path, default=None, help="another checkout to compare")
    args = ap.parse_args()
    from mjwalk.cycle.simulate import simulate_cycles

    with tempfile.TemporaryDirectory() as tmp:
        pickled = Path(tmp, "results.pkl")
        results = simulate_cycles(str(SPEC), args.runs, seed=0, n_jobs=2, on_error="record")
        pickled.write_bytes(pickle.dumps(results))
        trees = {"this tree": ROOT}
        if args.against is not None:
            trees["against"] = args.against.resolve()
        print(f"load average at the start: {os.getloadavg()[0]:.1f} (2 cores)")
        for j, n in enumerate(args.scale):
            cpu = {name: _timed(t, pickled, n, Path(tmp, f"{j}-{i}")) for i, (name, t) in
                   enumerate(trees.items())}  # fmt: skip
            line = f"{n:6d} runs: report CPU this tree {cpu['this tree']:.2f} s"
            if "against" in cpu:
                same = _same(Path(tmp, f"{j}-0"), Path(tmp, f"{j}-1"))
                line += (
                    f", against {cpu['against']:.2f} s ({cpu['against'] / cpu['this tree']:.2f}x)"
                    f"; files and summary {'identical' if same else 'DIFFER'}"
                )
            print(line, flush=True)


if __name__ == "__main__":
    main()
