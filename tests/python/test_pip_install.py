"""`pip install --no-build-isolation .` offline: the package pip makes imports and bakes what the
build tree's module bakes.

pip runs setup.py, which here builds the module's target in this build (PRTKIT_BUILD_DIR, already
configured and built, so the test takes seconds instead of a second full build), packages it with
the stubs, and installs it into a temporary --target with no package index.
"""

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

import prtkit

ROOT = Path(__file__).resolve().parents[2]
BUILD = Path(os.environ.get("PRT_BUILD_DIR", "/nonexistent"))  # set by CTest


def _pip_available():
    return subprocess.run([sys.executable, "-m", "pip", "--version"],
                          capture_output=True).returncode == 0


@pytest.mark.skipif(not _pip_available(), reason="pip is not installed (Debian: python3-pip)")
@pytest.mark.skipif(not (BUILD / "CMakeCache.txt").exists(),
                    reason=f"no configured CMake build of prtkit at PRT_BUILD_DIR ({BUILD})")
def test_pip_install_offline_gives_the_same_module(tmp_path):
    target = tmp_path / "site"
    env = dict(os.environ, PRTKIT_BUILD_DIR=str(BUILD), PIP_NO_INDEX="1",
               PIP_DISABLE_PIP_VERSION_CHECK="1", PYTHONDONTWRITEBYTECODE="1")
    env.pop("PYTHONPATH", None)
    run = subprocess.run([sys.executable, "-m", "pip", "install", "--no-build-isolation",
                          "--no-deps", "--no-index", "--target", str(target), str(ROOT)],
                         capture_output=True, text=True, env=env, timeout=300)
    assert run.returncode == 0, run.stdout[-2000:] + run.stderr[-2000:]
    installed = target / "prtkit"
    assert (installed / "_prtkit.pyi").exists() and (installed / "py.typed").exists()

    script = textwrap.dedent("""
        import sys, numpy as np, prtkit
        assert prtkit.__file__.startswith(sys.argv[1]), prtkit.__file__
        mesh = prtkit.Mesh(np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], np.float32),
                           np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], np.int32))
        np.save(sys.argv[2], prtkit.bake(mesh, mode="shadowed", bands=3, samples=64, seed=5))
    """)
    out = tmp_path / "t.npy"
    env["PYTHONPATH"] = str(target)
    run = subprocess.run([sys.executable, "-c", script, str(target), str(out)],
                         capture_output=True, text=True, env=env, cwd=tmp_path, timeout=120)
    assert run.returncode == 0, run.stderr[-2000:]

    mesh = prtkit.Mesh(np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], np.float32),
                       np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], np.int32))
    ours = np.asarray(prtkit.bake(mesh, mode="shadowed", bands=3, samples=64, seed=5))
    theirs = np.load(out)
    assert theirs.shape == ours.shape and np.array_equal(theirs, ours)
