"""Unseen floor as a policy (issue 40, deliverable 2): --voids blocked|fill|free, the floor
cover report and the top-view picture."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk import cli
from mjwalk.scan import ScanOptions, build_scene
from mjwalk.scan.voids import FILL_RADIUS, cover


def _hall(holes, seed: int = 0) -> np.ndarray:
    """A 12 x 9 m hall (floor every 4 cm, 2.5 m walls) with the floor left unscanned in the
    discs ``holes`` [(x, y, radius)], and a 1 x 1 x 1 m crate at (2, 2). Metres, z up."""
    rng = np.random.default_rng(seed)
    gx, gy = np.meshgrid(np.arange(0, 12, 0.04), np.arange(0, 9, 0.04))
    fl = np.column_stack([gx.ravel(), gy.ravel()])
    keep = np.ones(len(fl), bool)
    for x, y, r in holes:
        keep &= np.hypot(fl[:, 0] - x, fl[:, 1] - y) > r
    keep &= ~((np.abs(fl[:, 0] - 2) < 0.5) & (np.abs(fl[:, 1] - 2) < 0.5))
    parts = [np.column_stack([fl[keep], np.zeros(int(keep.sum()))])]
    h = np.arange(0, 2.5, 0.05)
    for x in (0.0, 12.0):
        yy, zz = np.meshgrid(np.arange(0, 9, 0.05), h)
        parts.append(np.column_stack([np.full(yy.size, x), yy.ravel(), zz.ravel()]))
    for y in (0.0, 9.0):
        xx, zz = np.meshgrid(np.arange(0, 12, 0.05), h)
        parts.append(np.column_stack([xx.ravel(), np.full(xx.size, y), zz.ravel()]))
    cx, cy = np.meshgrid(np.arange(1.5, 2.5, 0.04), np.arange(1.5, 2.5, 0.04))
    parts.append(np.column_stack([cx.ravel(), cy.ravel(), np.full(cx.size, 1.0)]))
    for x in (1.5, 2.5):
        yy, zz = np.meshgrid(np.arange(1.5, 2.5, 0.04), np.arange(0, 1, 0.04))
        parts.append(np.column_stack([np.full(yy.size, x), yy.ravel(), zz.ravel()]))
    pts = np.vstack(parts)
    return pts + rng.normal(0, 0.003, pts.shape)


def _walkable(scene, x, y) -> bool:
    p = scene.plan
    return bool(p.floor[int((y - p.y0) / p.resolution), int((x - p.x0) / p.resolution)])


def test_policies_on_enclosed_voids():
    """Unseen discs of radius 1.5 m (above the 1 m holes always filled, below FILL_RADIUS) and
    3 m (above it): blocked keeps both void, fill opens the small one, free both."""
    assert 1.0 < 1.5 < FILL_RADIUS < 3.0
    pts = _hall([(8.5, 2.5, 1.5), (5.0, 5.5, 3.0)])
    got = {p: build_scene(pts, ScanOptions(voids=p), source=p) for p in ("blocked", "fill", "free")}
    assert not _walkable(got["blocked"], 8.5, 2.5) and not _walkable(got["blocked"], 5.0, 5.5)
    assert _walkable(got["fill"], 8.5, 2.5) and not _walkable(got["fill"], 5.0, 5.5)
    assert _walkable(got["free"], 8.5, 2.5) and _walkable(got["free"], 5.0, 5.5)
    areas = {p: cover(s.plan) for p, s in got.items()}
    assert areas["blocked"].blocked > areas["fill"].blocked > areas["free"].blocked == 0
    # the void areas are the discs' (less the closing of sparse floor over their rims)
    assert areas["blocked"].blocked == pytest.approx(np.pi * (1.5**2 + 3.0**2), rel=0.15)
    for c in areas.values():  # what was seen and the obstacles do not depend on the policy
        assert c.seen == areas["blocked"].seen
        assert c.obstacles == areas["blocked"].obstacles
    assert got["fill"].n_void_boxes < got["blocked"].n_void_boxes


def test_cli_reports_cover_and_writes_the_top_view(tmp_path, capsys):
    src = tmp_path / "hall.xyz"
    np.savetxt(src, _hall([(8.5, 2.5, 1.5)])[::2], fmt="%.4f")
    png = tmp_path / "top.png"
    code = cli.main(
        ["scan", str(src), "-o", str(tmp_path / "h.xml"), "--voids", "fill", "--png", str(png)]
    )
    out = capsys.readouterr().out
    assert code == 0
    assert "--voids fill: floor seen" in out and "unseen and blocked (void boxes) 0.0 m²" in out
    assert png.stat().st_size > 5_000


def test_bad_voids_and_png_are_refused_before_work(tmp_path, capsys, monkeypatch):
    def fail(*args, **kwargs):
        raise AssertionError("the scan was read before the bad option was refused")

    monkeypatch.setattr("mjwalk.scan.merge.read_scan", fail)
    src = tmp_path / "a.xyz"
    src.write_text("0 0 0\n")
    for extra, match in (
        (["--voids", "open"], "invalid choice: 'open'"),
        (["--png", str(tmp_path / "top.docx")], "unsupported file type"),
    ):
        try:
            code = cli.main(["scan", str(src), "-o", str(tmp_path / "s.xml"), *extra])
        except SystemExit as exc:
            code = exc.code
        err = capsys.readouterr().err
        assert code == 2 and match in err and "Traceback" not in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.xyz"]


def test_a_pit_level_is_drawn_with_its_stair_not_as_a_gap(tmp_path):
    """Seeded stair-pit scan of tests/scan/test_scanpits.py (bottom x in [-0.44, 1], treads at
    x -1..-0.72 and -0.72..-0.44): the top view draws the arrow from the pit's bottom up to the
    tread next to the floor, and the pit in the level colour, not as an obstacle gap."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from test_scanpits import STAIR, STAIR_SCANNERS, _pits, _scan

    from mjwalk.scan.voids import draw_pit_link, save_top_view

    plan, (pit,) = _pits(_scan(STAIR, STAIR_SCANNERS))
    fig, ax = plt.subplots()
    draw_pit_link(ax, pit, plan)
    (arrow,) = [t for t in ax.texts if t.arrow_patch is not None]
    (qx, qy), (px, py) = arrow.xy, arrow.xyann
    assert -0.44 < px < 1.0 and py == pytest.approx(0.5, abs=0.1)  # the bottom's seen part
    assert qx == pytest.approx(-0.86, abs=0.1) and qy == pytest.approx(0.5, abs=0.1)
    plt.close(fig)
    shown = []
    real = plt.Axes.legend

    def legend(self, *args, handles=(), **kw):
        shown.extend(h.get_label() for h in handles)
        return real(self, *args, handles=handles, **kw)

    plt.Axes.legend = legend
    try:
        save_top_view(plan, tmp_path / "top.png", pits=[pit])
    finally:
        plt.Axes.legend = real
    assert "pit level (below the floor)" in shown
    assert "gap (floor missing): obstacle" not in shown
