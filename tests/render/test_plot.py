"""Top views and the report's charts (mjwalk.render.plot)."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "report"))
from test_figures import SCENE, _line, _results

import mjwalk.render.plot as plot
from mjwalk.world import load_workplace


@pytest.fixture(scope="module")
def workplace():
    return load_workplace(SCENE)


def test_spaghetti_draws_at_most_a_cap_of_walks_per_route_each_as_one_artist(
    tmp_path, workplace, monkeypatch
):
    """A long batch's floor plan draws a capped, evenly spread sample of each route's walks
    (the statistics and CSVs keep every walk): each route's walks as one line collection and
    their own grid-A* routes as another, dashed, not a line each (issue 50: thousands of
    lines were most of the report's time over a few hundred runs)."""
    from matplotlib.collections import LineCollection

    from mjwalk.report import report_dict

    results = _results(workplace, runs=12)
    figures: list = []
    close = plot.plt.close
    monkeypatch.setattr(plot.plt, "close", figures.append)  # kept to be looked at
    monkeypatch.setattr(plot, "MAX_DRAWN_PER_ROUTE", 5)
    rep = report_dict(results)
    plot.spaghetti_png(tmp_path / "s.png", results, workplace, None, rep)
    (fig,) = figures
    ax = fig.axes[0]
    lines = [c for c in ax.collections if isinstance(c, LineCollection)]
    solid = [c for c in lines if c.get_linestyle()[0][1] is None]
    dashed = [c for c in lines if c.get_linestyle()[0][1] is not None]
    routes = list(rep["routes"])
    # 12 runs, each route walked 12+ times: 5 of each drawn, in the route's colour
    assert len(solid) == len(routes) and all(len(c.get_paths()) == 5 for c in solid)
    colors = plot.route_colors(routes)
    assert [tuple(c.get_colors()[0][:3]) for c in solid] == [colors[r][:3] for r in routes]
    assert sum(len(c.get_paths()) for c in dashed) <= 5 * len(routes)  # with their walks
    assert len(ax.lines) < 40  # sites, each route's first start and end, legend entries
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    assert legend[: len(routes)] == routes
    close(fig)
    assert (tmp_path / "s.png").stat().st_size > 0


def test_route_colors_are_tab10_in_order():
    colors = plot.route_colors([f"T{k}" for k in range(12)])
    assert list(colors) == [f"T{k}" for k in range(12)]
    assert colors["T0"] == colors["T10"] != colors["T1"]  # ten colours, then round again
    assert len(colors["T3"]) == 4 and all(0.0 <= c <= 1.0 for c in colors["T3"])


def test_save_plan_png_writes_a_top_view(tmp_path, workplace):
    walk = _line(workplace.stations["stand_rack2"].xy, (1.0, 0.0), 1.0, 1.0)
    out = tmp_path / "plan.png"
    plot.save_plan_png(out, workplace, [walk], baseline=walk, title="one walk")
    assert out.stat().st_size > 1000
    assert not list(tmp_path.glob("*.tmp*"))  # written atomically
