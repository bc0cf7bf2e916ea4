"""Build step: ship the top-level ``scenes/`` folder as package data ``mjwalk/scenes``.

Everything else is in ``pyproject.toml``. The scenes stay in ``scenes/`` (where the README and
the cycle files point); a wheel carries a copy of them in ``mjwalk/scenes/``, where
:func:`mjwalk.shipped.scene_dir` finds them. A source tree or an editable install reads the
top-level folder itself.
"""

import shutil
from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py

SCENE_PATTERNS = ("*.xml", "*.toml", "*.obj", "*.stl", "*.png")


class BuildPyWithScenes(build_py):
    """``build_py`` that also copies ``scenes/`` into the built package as ``mjwalk/scenes``."""

    def run(self):
        super().run()
        src = Path(__file__).resolve().parent / "scenes"
        dst = Path(self.build_lib) / "mjwalk" / "scenes"
        dst.mkdir(parents=True, exist_ok=True)
        for pattern in SCENE_PATTERNS:
            for f in sorted(src.glob(pattern)):
                shutil.copy2(f, dst / f.name)

    def get_outputs(self, include_bytecode=True):
        src = Path(__file__).resolve().parent / "scenes"
        dst = Path(self.build_lib) / "mjwalk" / "scenes"
        extra = [str(dst / f.name) for p in SCENE_PATTERNS for f in sorted(src.glob(p))]
        return super().get_outputs(include_bytecode) + extra


setup(cmdclass={"build_py": BuildPyWithScenes})
