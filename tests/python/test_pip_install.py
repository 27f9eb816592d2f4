"""`pip install --no-build-isolation .` offline: the package pip makes imports and bakes what the
build tree's module bakes.

pip runs setup.py, which here builds the module's target in this build (PRTKIT_BUILD_DIR, already
configured and built, so the test takes seconds instead of a second full build), packages it with
the stubs, and installs it into a temporary --target with no package index. setup.py's helpers
are tested directly, in milliseconds: a moved checkout's stale build-pip/ and the build's
progress lines.
"""

import importlib.util
import os
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

import prtkit

ROOT = Path(__file__).resolve().parents[2]
BUILD = Path(os.environ.get("PRT_BUILD_DIR", "/nonexistent"))  # set by CTest


def _setup_py():
    """setup.py as a module, without running setup() (it runs only as __main__)."""
    spec = importlib.util.spec_from_file_location("prtkit_setup", ROOT / "setup.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


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


@pytest.mark.skipif(shutil.which("cmake") is None, reason="cmake is not installed")
def test_a_moved_checkout_starts_a_fresh_pip_build(tmp_path, capsys):
    # CMake refuses a cache made for another source and build directory ("does not match the
    # source ... used to generate cache"), which is what a moved or copied clone's build-pip/ holds.
    setup_py = _setup_py()
    old, new = tmp_path / "old", tmp_path / "new"
    old.mkdir()
    (old / "CMakeLists.txt").write_text("cmake_minimum_required(VERSION 3.16)\n"
                                        "project(prtkit VERSION 1.0 LANGUAGES NONE)\n")
    build = old / "build-pip" / "cmake"
    subprocess.run(["cmake", "-S", str(old), "-B", str(build)], check=True, capture_output=True)
    (old / "build-pip" / "build.log").write_text("not setup.py's to remove\n")
    assert setup_py.pip_build_dir(old) == build and (build / "CMakeCache.txt").exists()
    assert capsys.readouterr().err == ""  # a cache for this checkout is reused, silently

    old.rename(new)
    moved = new / "build-pip" / "cmake"
    refused = subprocess.run(["cmake", "-S", str(new), "-B", str(moved)], capture_output=True)
    assert refused.returncode != 0  # what pip install hit before

    assert setup_py.pip_build_dir(new) == moved
    note = capsys.readouterr().err
    assert note.count("\n") == 1 and str(old) in note and "fresh build" in note, note
    assert not moved.exists()
    assert (new / "build-pip" / "build.log").exists() and (new / "CMakeLists.txt").exists()
    subprocess.run(["cmake", "-S", str(new), "-B", str(moved)], check=True, capture_output=True)


def test_a_stale_cache_that_is_not_prtkits_is_left_alone(tmp_path):
    setup_py = _setup_py()
    build = tmp_path / "build-pip" / "cmake"
    build.mkdir(parents=True)
    cache = build / "CMakeCache.txt"
    cache.write_text("CMAKE_PROJECT_NAME:STATIC=other\n"
                     "CMAKE_HOME_DIRECTORY:INTERNAL=/elsewhere\n"
                     f"CMAKE_CACHEFILE_DIR:INTERNAL={build}\n")
    with pytest.raises(SystemExit, match="not a build of prtkit"):
        setup_py.pip_build_dir(tmp_path)
    assert cache.exists()


def test_the_pip_build_says_how_far_it_is_in_a_few_lines(tmp_path, capsys):
    # Ninja's 240 "[i/240]" lines become one line per tenth; a compiler warning is counted, not
    # shown (GCC 12's false -Wrestrict is 15 lines); the log keeps everything.
    setup_py = _setup_py()
    ticks = iter(range(0, 10_000, 2))  # a clock that advances 2 s per reading
    steps = ("print('[0/2] Re-checking globbed directories...')\n"
             "for i in range(1, 241):\n"
             "    print(f'[{i}/240] Building CXX object src/f{i}.cpp.o')\n"
             "    if i == 100: print('src/f100.cpp:3:1: warning: unused variable', flush=True)\n")
    log = tmp_path / "build.log"
    status, _, warnings, other = setup_py.build_with_progress(
        [sys.executable, "-c", steps], log, clock=lambda: next(ticks), every=1e9)
    assert status == 0 and warnings == 1 and other == ["src/f100.cpp:3:1: warning: unused variable"]
    lines = capsys.readouterr().err.splitlines()
    assert len(lines) == 11 and all(line.startswith("prtkit: build ") for line in lines), lines
    assert lines[0].startswith("prtkit: build 0% (1/240), ")
    assert lines[5].startswith("prtkit: build 50% (120/240), ")
    assert lines[-1].startswith("prtkit: build 100% (240/240), ")
    assert sum(line.startswith("[") for line in log.read_text().splitlines()) == 241


def test_a_copied_checkouts_manifest_with_absolute_paths_is_dropped(tmp_path):
    # The setup.py before this one gave setuptools an absolute egg_base, so SOURCES.txt named the
    # checkout's path; a copy still holding it failed with "setup script specifies an absolute path".
    setup_py = _setup_py()
    egg_info = tmp_path / "prtkit.egg-info"
    egg_info.mkdir()
    (egg_info / "PKG-INFO").write_text("Name: prtkit\n")
    manifest = egg_info / "SOURCES.txt"
    manifest.write_text("setup.py\nbuild-pip/prtkit.egg-info/PKG-INFO\n")
    setup_py.drop_stale_manifest(egg_info)
    assert manifest.exists()  # relative paths: kept
    manifest.write_text("setup.py\n/elsewhere/build-pip/prtkit.egg-info/PKG-INFO\n")
    setup_py.drop_stale_manifest(egg_info)
    assert not manifest.exists() and (egg_info / "PKG-INFO").exists()
