"""Stress harness on workplaces nobody has seen (issue 47): seeded multi-level halls
(:mod:`mjwalk.world.levelgen`), each planned, animated and scanned, outcomes counted by kind.

For each seed: the hall is generated and loaded; walks are planned (``mjwalk plan``'s API,
:func:`mjwalk.plan.walks.plan_walk`) from a floor site to a site on every other level, and to a
pedestal's site when the hall has one (a walk that cannot exist: it must be refused); a walker
with no step-up at all (``max_riser`` 0: ramps only) is sent to the mezzanine (reached by a
stair only: refused too); a short cycle (a generated .toml: walks to 2-3 sites on different
levels) is simulated ``--runs 3 --jobs 1`` and its contacts counted; a synthetic scan of the hall
(:func:`mjwalk.scan.raycast.synthetic_scan` from the hall's scanner spots, 0.4 deg rays, 5 mm
noise) becomes a scene (:func:`mjwalk.scan.scene.build_scene`) whose levels and links are
compared with the true ones (heights within 2 cm; every stair's risers, every step and ramp),
and the scene written from it (:func:`mjwalk.scan.scene.write_scene`) is loaded as any scene and
its level graph compared with the hall's (:func:`_written`: levels, links' kinds and levels,
openings' areas), since the scan's own level list can be right while the written scene is not.

The seeds run in a child process (restarted after a seed past ``--timeout`` wall seconds) and
every stage under a CPU-time alarm (:data:`ALARM`): a hang is a "timeout", never a stuck
harness. Outcomes:

- ``planned``: a walk found, its start and end on the sites' levels (within 2 cm) and no jump in
  its surface height above the highest cited riser; ``heights off`` otherwise;
- ``no route``: a :class:`~mjwalk.errors.PlanningError` (one line), its reason counted;
  expected for the pedestal and the ramp-only walker's stair walk (``refused as expected``);
- ``MjwalkError``: any other error of mjwalk's own (message);
- ``other exception``: a bug (traceback kept in the seed's record);
- cycles: runs without error, contacts (any humanoid-scene contact);
- scan: levels within 2 cm, extra levels, stairs / steps / ramps recognised; ``written scene
  differs`` (stage ``scan:written``) when the written scene's levels, links or openings are not
  the hall's.

Run: ``PYTHONPATH=. python3 benchmarks/bench_unseen.py --seeds 0-29`` (``--json FILE`` keeps the
records; ``--many SEEDS`` is the child's entry).
"""

from __future__ import annotations

import argparse
import collections
import json
import select
import signal
import subprocess
import sys
import tempfile
import time
import traceback
from pathlib import Path

import numpy as np

#: Stage alarms, seconds of this process's CPU time (``ITIMER_PROF``: a loaded machine does
#: not trip them); the kernels are compiled before the first seed (:func:`warm_up`).
ALARM = {"load": 60, "plan": 60, "cycle": 300, "scan": 120}
#: Level heights match within this, metres (issue 47's target for scans).
HEIGHT_TOL = 0.02


class StageTimeout(Exception):
    """A stage ran past its alarm."""


def _alarm(signum, frame):
    raise StageTimeout("stage timed out")


def _stage(rec: dict, name: str, fn, *args):
    """Run one stage under its alarm; errors are recorded as outcomes, never raised."""
    from mjwalk.errors import MjwalkError, PlanningError

    signal.signal(signal.SIGPROF, _alarm)
    signal.setitimer(signal.ITIMER_PROF, ALARM[name.split(":")[0]])
    t = time.process_time()
    try:
        out = fn(*args)
        return out
    except StageTimeout:
        rec.setdefault("outcomes", []).append({"stage": name, "kind": "timeout"})
    except PlanningError as e:
        rec.setdefault("outcomes", []).append({"stage": name, "kind": "no route", "msg": str(e)})
    except MjwalkError as e:
        kind = "MjwalkError"
        rec.setdefault("outcomes", []).append({"stage": name, "kind": kind, "msg": str(e)})
    except Exception as e:  # a bug
        rec.setdefault("outcomes", []).append(
            {
                "stage": name,
                "kind": "other exception",
                "msg": f"{type(e).__name__}: {e}",
                "tb": traceback.format_exc(limit=6),
            }
        )
    finally:
        signal.setitimer(signal.ITIMER_PROF, 0)
        rec.setdefault("cpu", {})[name] = round(time.process_time() - t, 2)
    return None


def _pairs(hall) -> list[tuple[str, str, float | None, bool]]:
    """(start, goal, max_riser, expect_refusal): a floor site to each site on another level and
    back from the mezzanine, the pedestal, and the ramp-only walker to the mezzanine."""
    floor = [s for s in hall.sites if s.level == "floor"]
    others = [s for s in hall.sites if s.level != "floor"]
    out = []
    for i, s in enumerate(others):
        a = floor[i % len(floor)].name
        out.append((a, s.name, None, not s.reachable))
        if s.level == "mezz":
            out.append((s.name, floor[(i + 1) % len(floor)].name, None, False))
            out.append((a, s.name, 0.0, True))
    return out


def _check_walk(workplace, hall, walk, start: str, goal: str) -> str | None:
    """Why a planned walk is wrong (heights off), or None."""
    from mjwalk.world.norms import MAX_RISER

    z = walk.z
    za, zb = hall.site(start).pos[2], hall.site(goal).pos[2]
    if z is None:  # a walk on one level: both ends on the floor plan
        return None if abs(za - zb) <= HEIGHT_TOL else f"flat walk between {za:.2f} and {zb:.2f}"
    z = np.asarray(z) - workplace.floor_z
    if abs(z[0] - za) > HEIGHT_TOL or abs(z[-1] - zb) > HEIGHT_TOL:
        return f"ends at {z[0]:.3f} / {z[-1]:.3f} m, sites at {za:.3f} / {zb:.3f} m"
    jump = float(np.max(np.abs(np.diff(z)))) if len(z) > 1 else 0.0
    if jump > MAX_RISER + 0.005:
        return f"surface height jumps {jump:.3f} m in one sample"
    return None


def _plan_one(workplace, hall, pair, seed: int) -> dict:
    from mjwalk.gait.default import default_model
    from mjwalk.plan.levelplan import plan_level_walk
    from mjwalk.plan.walks import plan_walk

    a, b, riser, refuse = pair
    rng = np.random.default_rng(seed)
    if riser is None:
        walk = plan_walk(workplace, a, b, rng=rng)
    else:
        walk = plan_level_walk(workplace, a, b, default_model(), rng, max_riser=riser)
    bad = _check_walk(workplace, hall, walk, a, b)
    if refuse:
        return {"kind": "planned (should be refused)", "msg": f"{a} -> {b} max_riser={riser}"}
    if bad:
        return {"kind": "heights off", "msg": f"{a} -> {b}: {bad}"}
    return {"kind": "planned", "length": round(float(walk.length), 2)}


def _cycle_toml(hall, path: Path, xml: Path) -> Path | None:
    """A cycle of walks from a floor site to 2-3 sites on different levels and back."""
    reach = [s for s in hall.sites if s.reachable and s.level != "floor"]
    levels, picks = set(), []
    for s in reach:
        if s.level not in levels:
            levels.add(s.level)
            picks.append(s.name)
    if not picks:
        return None
    floor = [s.name for s in hall.sites if s.level == "floor"]
    tasks = [*picks[:3], floor[1]]
    lines = [
        f'name = "generated levels {hall.seed}"',
        f'scene = "{xml.name}"',
        f'start = "{floor[0]}"',
        "",
        "[humanoid]",
        "stature = 1.75",
        "",
        "[models]",
        'step = "default"',
        'reach = "default"',
    ]
    for i, site in enumerate(tasks):
        lines += ["", "[[task]]", 'kind = "walk"', f'site = "{site}"', f'route = "R{i}"']
    path.write_text("\n".join(lines) + "\n")
    return path


def _cycle(toml: Path) -> dict:
    from mjwalk.cycle.simulate import simulate_cycles

    results = simulate_cycles(toml, 3, seed=0, n_jobs=1, on_error="record")
    errors = [r.error for r in results if r.error]
    contacts = sum(len(r.collisions) for r in results)
    deepest = max((c.depth for r in results for c in r.collisions), default=0.0)
    parts = sorted({f"{c.body_part}/{c.scene_geom}" for r in results for c in r.collisions})
    return {"runs": len(results), "errors": errors, "contacts": contacts,
            "deepest": round(float(deepest), 4), "parts": parts[:6]}  # fmt: skip


def _scan(model, hall, seed: int, true_graph) -> dict:
    from mjwalk.scan.raycast import synthetic_scan
    from mjwalk.scan.scene import build_scene

    scan = synthetic_scan(model, list(hall.scanners), step_deg=0.4, noise=0.005, seed=seed)
    scene = build_scene(scan.points, source=f"levels_{seed}")
    to_written = scene.matrix @ np.linalg.inv(scan.to_scene)  # the hall's frame to the scene's
    lp = scene.levels
    found = [] if lp is None else [float(h) for h in lp.heights]
    pit_links = []
    for pit in scene.pits:  # the levels below the floor a stair or a ramp reaches
        if pit.bottom is not None:
            found.append(float(pit.bottom.height))
        if pit.link is not None:
            k, lv = pit.link, pit.levels
            pit_links.append((k.kind, lv[k.lower].height, lv[k.upper].height, k))
    true_all = sorted({*hall.heights, *hall.treads})
    missed = [h for h in hall.heights if not any(abs(h - f) <= HEIGHT_TOL for f in found)]
    extra = [f for f in found if not any(abs(h - f) <= HEIGHT_TOL for h in true_all)]
    links = [] if lp is None else list(lp.links)
    heights = [] if lp is None else list(lp.heights)
    got = []
    for k in links:
        lo, hi = heights[k.lower], heights[k.upper]
        got.append((k.kind, lo, hi, len(k.risers), float(np.mean(k.risers)) if k.risers else 0))
    for kind, lo, hi, k in pit_links:
        got.append((kind, lo, hi, len(k.risers), float(np.mean(k.risers)) if k.risers else 0))
    rec = {"levels": len(found), "missed": missed, "extra": [round(x, 3) for x in extra]}
    rec["links"] = _match_links(hall, got)
    rec["written"] = _written(true_graph, scene, to_written)
    return rec


def _written(true_graph, scene, to_written: np.ndarray) -> dict:
    """The scene ``mjwalk scan`` writes, loaded as any scene is, against the generated hall's:
    each hall level found on the written scene under a point of its largest surface (mapped by
    ``to_written``) within :data:`HEIGHT_TOL` of its height above the floor, each link of the
    hall's (kind, lower, upper) a link of the written scene's between the levels matched, and
    each level's openings (:func:`mjwalk.world.openings.openings_of`) of the same total area
    within :func:`_opening_tol`. The scan's own level list can be right while the scene written
    from it is not (hall 1057: its pit stair's link was lost in the written scene only)."""
    from mjwalk.scan.scene import write_scene
    from mjwalk.world.workplace import load_workplace

    with tempfile.TemporaryDirectory() as tmp:
        wp = load_workplace(write_scene(scene, Path(tmp) / "scan.xml"), cache=False)
        graph = wp.levels
    z0, w0 = true_graph.levels[0].height, graph.levels[0].height
    match: dict[int, int] = {}
    for lv in true_graph.levels:
        p = _inner_point(true_graph, lv)
        q = (to_written @ np.array([p[0], p[1], lv.height, 1.0]))[:2]
        i = graph.surface_at(q, lv.height - z0 + w0)
        j = None if i is None else graph.level_of[i]
        if j is not None and abs(graph.levels[j].height - w0 - (lv.height - z0)) <= HEIGHT_TOL:
            match[lv.index] = j
    out: dict = {"levels": [len(true_graph.levels), len(graph.levels)]}
    out["unmatched"] = [
        round(lv.height - z0, 3) for lv in true_graph.levels if lv.index not in match
    ]
    out["extra"] = [
        round(lv.height - w0, 3) for lv in graph.levels if lv.index not in match.values()
    ]
    want = {(k.kind, match.get(k.lower, -1), match.get(k.upper, -1)) for k in true_graph.links}
    have = {(k.kind, k.lower, k.upper) for k in graph.links}
    name = {j: f"{graph.levels[j].height - w0:+.2f}" for j in range(len(graph.levels))}
    name[-1] = "?"
    out["links_missing"] = sorted(f"{k} {name[a]}->{name[b]}" for k, a, b in want - have)
    out["links_extra"] = sorted(f"{k} {name[a]}->{name[b]}" for k, a, b in have - want)
    out["openings"] = []
    for i, j in match.items():
        a, b, tol = _opening_areas(true_graph, i, graph, j)
        if abs(a - b) > tol:
            out["openings"].append([round(true_graph.levels[i].height - z0, 3), a, b, tol])
    return out


def _inner_point(graph, level) -> tuple[float, float]:
    """A point where a level is walked on (world xy, metres): inside its surfaces, not under a
    higher surface (a pit's bottom is the hall's floor plane, under the floor's boxes but in the
    pit), and :data:`INNER_MARGIN` inside that region's edges when it is wide enough; where
    the hall's own graph stands a walker on that level (:meth:`LevelGraph.surface_at`: room
    above it), since an obstacle no walk surface tops (hall 1146's pedestal, whose deck is no
    level) hides the level under it in the hall and the written scene alike, and the region's
    representative point fell on it (level +0.00 m missing in a scene that has it); and, when
    such a point exists, where nothing stands in the scan's obstacle band
    (``floor.OBSTACLE_Z_RANGE``) within :data:`INNER_MARGIN` of it: the scan's floor plan writes
    what it saw in the band as boxes standing on the level, a cell or two wider than the thing
    (hall 1219's floor point lay 0.2 mm beside a beam at 1.74 m, where the hall has room to
    stand; written as a column from the floor: level +0.00 m missing and its links)."""
    import shapely  # deferred: slow to import; the scan stage alone needs it

    from mjwalk.world.floor import OBSTACLE_Z_RANGE  # deferred: as every mjwalk import here

    band_top = OBSTACLE_Z_RANGE[1]

    def poly(i):
        return shapely.Polygon(np.asarray(graph.surfaces[i].footprint.vertices, dtype=float))

    own = shapely.union_all([poly(i) for i in level.surfaces])
    above = [
        poly(i)
        for i, s in enumerate(graph.surfaces)
        if i not in level.surfaces and s.z_high > level.height + HEIGHT_TOL
    ]
    free = own.difference(shapely.union_all(above)) if above else own
    free = free if not free.is_empty else own
    inner = free.buffer(-INNER_MARGIN)
    region = inner if not inner.is_empty else free
    c = region.representative_point()
    points = [(c.x, c.y), *_grid_points(region)]
    ring = INNER_MARGIN * np.array(
        [[0.0, 0.0]] + [[np.cos(a), np.sin(a)] for a in np.arange(8) * np.pi / 4]
    )
    for q in points:  # nothing in the scan's obstacle band within INNER_MARGIN (hall 1219's beam)
        i = graph.surface_at(q, level.height)
        if i in level.surfaces and graph.surfaces[i].free_height(q + ring).min() >= band_top:
            return float(q[0]), float(q[1])
    for q in points:
        if graph.surface_at(q, level.height) in level.surfaces:
            return float(q[0]), float(q[1])
    return float(c.x), float(c.y)


def _grid_points(region, n: int = 40) -> list[tuple[float, float]]:
    """Points of a region on an ``n`` x ``n`` grid over its bounds (world xy, metres), from
    its representative point outwards."""
    import shapely  # deferred: slow to import; the scan stage alone needs it

    x0, y0, x1, y1 = region.bounds
    c = region.representative_point()
    pts = [
        (float(x), float(y))
        for x in np.linspace(x0, x1, n)
        for y in np.linspace(y0, y1, n)
        if region.contains(shapely.Point(x, y))
    ]
    return sorted(pts, key=lambda q: (q[0] - c.x) ** 2 + (q[1] - c.y) ** 2)


#: Metres a level's test point keeps from its edges: five floor-plan cells (2 cm,
#: :data:`mjwalk.scan.scanoptions.DEFAULT_RESOLUTION`). ASSUMPTION: a written edge lies within
#: a cell or two of the true one; 0.1 m keeps the point on the same level either way.
INNER_MARGIN = 0.1


#: How far a written scene's opening edge may lie from the hall's, metres: one floor-plan
#: cell (:data:`mjwalk.scan.scanoptions.DEFAULT_RESOLUTION`, 2 cm). ASSUMPTION: the scan
#: writes an edge on a cell boundary, the true edge lies anywhere within that cell.
OPENING_EDGE_TOL = 0.02


def _opening_areas(true_graph, i: int, graph, j: int) -> tuple[float, float, float]:
    """Total area of level ``i``'s openings in the hall and of level ``j``'s in the written
    scene (square metres), and the difference allowed: the hall's openings' perimeter times
    :data:`OPENING_EDGE_TOL` (none when the hall's level has no opening)."""
    import shapely  # deferred: slow to import; the scan stage alone needs it

    from mjwalk.world.openings import openings_of

    def union(g, k):
        return shapely.union_all(
            [shapely.Polygon(np.asarray(f.vertices, dtype=float)) for f in openings_of(g, k)]
        )

    a, b = union(true_graph, i), union(graph, j)
    return round(a.area, 3), round(b.area, 3), round(a.length * OPENING_EDGE_TOL, 3)


def _written_faults(w: dict) -> list[str]:
    """What the written scene got wrong (:func:`_written`), one phrase each; empty when it
    matches the hall."""
    out = [f"level {h:+.2f} m missing" for h in w["unmatched"]]
    out += [f"extra level {h:+.2f} m" for h in w["extra"]]
    out += [f"link missing: {k}" for k in w["links_missing"]]
    out += [f"extra link: {k}" for k in w["links_extra"]]
    out += [
        f"openings at {h:+.2f} m: {a:.3f} vs {b:.3f} m2 (tol {t:.3f})"
        for h, a, b, t in w["openings"]
    ]
    return out


def _match_links(hall, got) -> dict:
    """Per true link kind: how many the scan recognised (stairs: the same risers within 1 cm)."""
    out: dict = collections.defaultdict(lambda: [0, 0])
    for k in hall.links:
        out[k.kind][1] += 1
        for kind, lo, hi, n, r in got:
            same = abs(lo - k.lower) <= HEIGHT_TOL and abs(hi - k.upper) <= HEIGHT_TOL
            if k.kind == "stair" and kind == "stair" and same and n == k.risers:
                ok = abs(r - k.riser) <= 0.01
            elif k.kind == "step" and k.risers == 2:  # a tread then the level: two steps
                ok = (
                    kind == "step"
                    and abs(hi - lo - k.riser) <= HEIGHT_TOL
                    and (abs(lo - k.lower) <= HEIGHT_TOL or abs(hi - k.upper) <= HEIGHT_TOL)
                )
            else:
                ok = kind == k.kind and same
            if ok:
                out[k.kind][0] += 1
                break
    return dict(out)


def warm_up() -> None:
    """Plan one walk over levels on the shipped multi-level station, unguarded: numba compiles
    (or loads) its kernels here, not under a stage's alarm (an alarm inside a compilation
    leaves the kernel unusable for the rest of the process)."""
    from mjwalk.gait.default import default_model
    from mjwalk.plan.walks import plan_walk
    from mjwalk.world.workplace import load_workplace

    root = Path(__file__).resolve().parents[1]
    wp = load_workplace(root / "scenes" / "multilevel_station.xml")
    plan_walk(wp, "stand_rack1", "stand_mezz_rack", default_model(), rng=0)


def run_one(seed: int, stages: tuple[str, ...] = ("plan", "cycle", "scan")) -> dict:
    """The ``stages`` on one seed's hall; the record of its outcomes."""
    from mjwalk.world.levelgen import generate_levels
    from mjwalk.world.workplace import load_model, load_workplace

    rec: dict = {"seed": seed}
    hall = generate_levels(seed)
    rec["features"] = list(hall.features)
    with tempfile.TemporaryDirectory() as tmp:
        xml = hall.write(Path(tmp) / f"levels_{seed}.xml")
        wp = _stage(rec, "load", lambda: load_workplace(xml, cache=False))
        if wp is None:
            return rec
        for i, pair in enumerate(_pairs(hall) if "plan" in stages else []):
            out = _stage(
                rec, f"plan:{pair[0]}->{pair[1]}", _plan_one, wp, hall, pair, seed * 100 + i
            )
            if out is not None:
                rec.setdefault("outcomes", []).append(
                    {"stage": f"plan:{pair[0]}->{pair[1]}", **out}
                )
            elif pair[3] and rec["outcomes"][-1]["kind"] == "no route":
                rec["outcomes"][-1]["kind"] = "refused as expected"
        toml = _cycle_toml(hall, Path(tmp) / "cycle.toml", xml)
        if toml is not None and "cycle" in stages:
            cyc = _stage(rec, "cycle", _cycle, toml)
            if cyc is not None:
                rec["cycle"] = cyc
        if "scan" in stages:
            scan = _stage(rec, "scan", _scan, load_model(xml), hall, seed, wp.levels)
            if scan is not None:
                rec["scan"] = scan
                faults = _written_faults(scan["written"])
                if faults:
                    rec.setdefault("outcomes", []).append(
                        {"stage": "scan:written", "kind": "written scene differs",
                         "msg": "; ".join(faults)}
                    )  # fmt: skip
    return rec


def _children(seeds: list[int], timeout: float, stages: str):
    """Yield each seed's record from child processes that run the seeds in turn (one process
    keeps its compiled kernels and models warm); a seed past ``timeout`` seconds, or a child
    that dies, is recorded as such and a new child takes the seeds after it."""
    todo = list(seeds)
    while todo:
        cmd = [sys.executable, str(Path(__file__).resolve()), "--many", ",".join(map(str, todo))]
        cmd += ["--stages", stages]
        child = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        assert child.stdout is not None
        while todo:
            t = time.perf_counter()
            ready, _, _ = select.select([child.stdout], [], [], timeout)
            line = child.stdout.readline() if ready else ""
            if line.startswith("{"):
                rec = json.loads(line)
                rec["wall"] = round(time.perf_counter() - t, 1)
                todo.remove(rec["seed"])
                yield rec
                continue
            seed = todo.pop(0)
            child.kill()
            err = "" if ready else "timeout"
            if ready:  # the child died
                child.wait()
                tail = (child.stderr.read() if child.stderr else "").strip().splitlines()[-3:]
                err = f"child exit {child.returncode}: {' | '.join(tail)}"
            kind = "timeout" if err == "timeout" else "other exception"
            yield {"seed": seed, "outcomes": [{"stage": "seed", "kind": kind, "msg": err}]}
            break
        child.kill()
        child.wait()


def table(records: list[dict]) -> str:
    """The outcome table: walks by outcome, reasons of refusals and errors, cycles, scans."""
    kinds: collections.Counter = collections.Counter()
    msgs: dict = collections.defaultdict(collections.Counter)
    for r in records:
        for o in r.get("outcomes", []):
            kinds[(o["stage"].split(":")[0], o["kind"])] += 1
            if o["kind"] not in ("planned",):
                msgs[o["kind"]][_short(o.get("msg", ""))] += 1
    lines = [f"seeds: {len(records)}", "", "| stage | outcome | count |", "|---|---|---|"]
    lines += [f"| {s} | {k} | {n} |" for (s, k), n in sorted(kinds.items())]
    cyc = [r["cycle"] for r in records if "cycle" in r]
    runs = sum(c["runs"] for c in cyc)
    errs = sum(len(c["errors"]) for c in cyc)
    with_contacts = sum(c["contacts"] > 0 for c in cyc)
    lines += ["", f"cycles: {len(cyc)} simulated, {runs} runs, {errs} runs failed, "
              f"{with_contacts} cycles with contacts "
              f"({sum(c['contacts'] for c in cyc)} contacts)"]  # fmt: skip
    scans = [r["scan"] for r in records if "scan" in r]
    miss = sum(bool(s["missed"]) for s in scans)
    extra = sum(bool(s["extra"]) for s in scans)
    link = collections.defaultdict(lambda: [0, 0])
    for s in scans:
        for k, (a, b) in s["links"].items():
            link[k][0] += a
            link[k][1] += b
    lines += [f"scans: {len(scans)}; levels within 2 cm in {len(scans) - miss}, "
              f"extra levels in {extra}; recognised: "
              + ", ".join(f"{k} {a}/{b}" for k, (a, b) in sorted(link.items()))]  # fmt: skip
    written = [s["written"] for s in scans if "written" in s]
    faults = [_written_faults(w) for w in written]
    lines += [f"written scenes: {len(written)}; as the hall in {sum(not f for f in faults)}; "
              f"levels off in {sum(bool(w['unmatched'] or w['extra']) for w in written)}, "
              f"links off in {sum(bool(w['links_missing'] or w['links_extra']) for w in written)}, "
              f"openings off in {sum(bool(w['openings']) for w in written)}"]  # fmt: skip
    for kind, c in sorted(msgs.items()):
        lines += ["", f"{kind}:"] + [f"  {n} x {m}" for m, n in c.most_common(8)]
    return "\n".join(lines)


def _short(msg: str) -> str:
    import re

    msg = msg.splitlines()[0] if msg else ""
    return re.sub(r"-?\d+\.\d+", "#", msg)[:150]


def _seeds(text: str) -> list[int]:
    out: list[int] = []
    for part in text.split(","):
        a, _, b = part.partition("-")
        out += list(range(int(a), int(b) + 1)) if b else [int(a)]
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", default="0-29", help="seeds, e.g. 0-29 or 3,5,8 (0-29)")
    ap.add_argument("--timeout", type=float, default=1800.0, help="seconds per seed (1800)")
    ap.add_argument("--json", type=Path, help="write the seeds' records here")
    ap.add_argument("--stages", default="plan,cycle,scan", help="stages run (plan,cycle,scan)")
    ap.add_argument("--many", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.many is not None:
        warm_up()
        for seed in _seeds(args.many):
            print(json.dumps(run_one(seed, tuple(args.stages.split(",")))), flush=True)
        return
    records = []
    for rec in _children(_seeds(args.seeds), args.timeout, args.stages):
        seed = rec["seed"]
        records.append(rec)
        bad = [o for o in rec.get("outcomes", []) if o["kind"] != "planned"]
        print(f"seed {seed}: {len(rec.get('outcomes', []))} outcomes, {len(bad)} not planned, "
              f"{rec.get('wall', '?')} s", flush=True)  # fmt: skip
        if args.json:
            args.json.write_text(json.dumps(records, indent=1))
    print(table(records))


if __name__ == "__main__":
    main()
