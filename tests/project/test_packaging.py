"""Packaging: the wheel and an editable install both carry the shipped
scenes and run from any folder; one version source; a licence file."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

import mjwalk
from mjwalk.shipped import CYCLES, SCENES, cycle_file, scene_dir, scene_file

ROOT = Path(__file__).resolve().parents[2]


def test_version_comes_from_pyproject():
    version = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["version"]
    assert mjwalk.__version__ == version
    assert 'version = "' not in (ROOT / "mjwalk" / "__init__.py").read_text()


def test_license_file_is_apache():
    text = (ROOT / "LICENSE").read_text()
    assert "Apache License" in text and "Version 2.0, January 2004" in text
    meta = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    assert meta["license"] == "Apache-2.0"


def test_shipped_names_resolve_in_a_checkout():
    assert scene_dir() == ROOT / "scenes"  # the top-level folder itself, no copy
    for name, file in SCENES.items():
        assert scene_file(name) == ROOT / "scenes" / file
    for name, file in CYCLES.items():
        assert cycle_file(name) == ROOT / "scenes" / file
    # an existing file or anything that looks like a path is taken as given
    assert scene_file(ROOT / "scenes" / "corridor.xml") == ROOT / "scenes" / "corridor.xml"
    assert scene_file("elsewhere/station.xml") == Path("elsewhere/station.xml")


def _run(cmd, cwd, env=None, timeout=900):
    res = subprocess.run(
        [str(c) for c in cmd], cwd=cwd, env=env, capture_output=True, text=True, timeout=timeout
    )
    assert res.returncode == 0, f"{cmd}\n{res.stdout}\n{res.stderr}"
    return res.stdout


def _check_install(venv: Path, work: Path, expect_in: Path) -> None:
    """From a folder outside the checkout: mjwalk imports from ``expect_in``, plans in the
    shipped station by name and checks the shipped cycle."""
    py = venv / "bin" / "python"
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    where = _run([py, "-c", "import mjwalk; print(mjwalk.__file__, mjwalk.__version__)"], work, env)
    assert where.split()[0].startswith(str(expect_in)), where
    assert where.split()[1] == mjwalk.__version__
    out = _run(
        [venv / "bin" / "mjwalk", "plan", "station", "--from", "stand_rack2", "--to"]
        + ["stand_car1", "--n", "0", "--png", "plan.png"],
        work,
        env,
    )
    assert "grid A*  stand_rack2 -> stand_car1: length 2.29" in out
    assert (work / "plan.png").stat().st_size > 0
    out = _run([venv / "bin" / "mjwalk", "simulate", "station", "--dry-run"], work, env)
    assert "assembly_station.toml and --out out checked" in out


def _venv_seeing_these_packages(venv: Path, cwd: Path) -> Path:
    """A fresh virtual environment that sees the packages of the interpreter running the tests
    (its site-packages, through a ``.pth`` file, after the new environment's own), so that
    nothing is downloaded. ``--system-site-packages`` would not do: run from a virtual
    environment it shows the base interpreter's packages, not this environment's."""
    _run([sys.executable, "-m", "venv", "--without-pip", venv], cwd)
    py = venv / "bin" / "python"
    own = _run([py, "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"], cwd)
    ours = [p for p in sys.path if Path(p).name in ("site-packages", "dist-packages")]
    # plain path lines: the parent's own .pth files (its editable mjwalk among them) stay unread
    (Path(own.strip()) / "_parent_packages.pth").write_text("\n".join(ours) + "\n")
    return py


@pytest.mark.slow
def test_wheel_and_editable_install_run_from_any_folder(tmp_path):
    """Build the wheel, install it into a fresh virtual environment (the test interpreter's
    packages visible, so nothing is downloaded), run a plan from a temporary folder; then the
    same for an editable install of this checkout."""
    src = tmp_path / "src"  # a clean copy: the build must not rely on files outside git
    shutil.copytree(
        ROOT,
        src,
        ignore=shutil.ignore_patterns(".git", "build", "*.egg-info", "__pycache__", "out"),
    )
    pip = [sys.executable, "-m", "pip"]
    _run([*pip, "wheel", "--no-deps", "-q", "-w", tmp_path / "dist", src], tmp_path)
    wheels = list((tmp_path / "dist").glob("mjwalk-*.whl"))
    assert len(wheels) == 1
    import zipfile

    names = zipfile.ZipFile(wheels[0]).namelist()
    for file in set(SCENES.values()) | set(CYCLES.values()):
        assert f"mjwalk/scenes/{file}" in names
    assert any(n.endswith("licenses/LICENSE") for n in names)

    venv = tmp_path / "venv"
    py = _venv_seeing_these_packages(venv, tmp_path)
    install = [*pip, "--python", py, "install", "--no-index", "--no-deps", "--ignore-installed"]
    _run([*install, "-q", wheels[0]], tmp_path)
    _run([*pip, "--python", py, "check"], tmp_path)  # its declared dependencies are all there
    work = tmp_path / "work"
    work.mkdir()
    _check_install(venv, work, venv)

    # a second fresh environment: uninstalling the wheel would leave the numba cache files the
    # plan wrote beside its modules (not in the wheel's RECORD), and that leftover folder would
    # shadow the editable install as a namespace package
    venv2 = tmp_path / "venv2"
    py2 = _venv_seeing_these_packages(venv2, tmp_path)
    _run(
        [*pip, "--python", py2, "install", "--no-deps", "--ignore-installed", "-q", "-e", src],
        tmp_path,
    )
    work2 = tmp_path / "work2"
    work2.mkdir()
    _check_install(venv2, work2, src)
