"""Shared fixtures of the prtkit Python tests (run by CTest, label python; docs/python.md).

Every test needs numpy and the built module: where either is missing the tests are skipped,
saying why, and the session exits with 77, which CTest reports as "skipped" (never "passed").
Tests that compare against the command line run the `prt` that CTest names in PRT_CLI.
"""

import os
import subprocess

import pytest

try:
    import numpy as np  # noqa: F401
except ImportError as e:  # pragma: no cover - depends on the machine
    NUMPY_MISSING = f"numpy is not installed ({e}); Debian: python3-numpy"
else:
    NUMPY_MISSING = None

PRTKIT_MISSING = None
if NUMPY_MISSING is None:
    try:
        import prtkit  # noqa: F401
    except ImportError as e:  # pragma: no cover
        PRTKIT_MISSING = (f"the prtkit module is not importable ({e}); build it (pybind11-dev, "
                          "python3-dev) and put build/python on PYTHONPATH")

SKIPPED_EXIT = 77


MISSING = NUMPY_MISSING or PRTKIT_MISSING
if MISSING:
    # The test files import numpy and prtkit: without them, collect nothing and say why.
    collect_ignore_glob = ["test_*.py"]


def pytest_report_header(config):
    return f"prtkit tests skipped: {MISSING}" if MISSING else None


def pytest_sessionfinish(session, exitstatus):
    # Nothing could run (numpy or the module missing), or everything was skipped: a skip, not
    # a pass.
    if MISSING:
        print(f"\nskipped: {MISSING}")
        session.exitstatus = SKIPPED_EXIT
        return
    reporter = session.config.pluginmanager.get_plugin("terminalreporter")
    if reporter is None or exitstatus != 0:
        return
    stats = reporter.stats
    ran = sum(len(stats.get(k, [])) for k in ("passed", "failed", "error", "xfailed", "xpassed"))
    if ran == 0 and stats.get("skipped"):
        session.exitstatus = SKIPPED_EXIT


def _cli():
    path = os.environ.get("PRT_CLI")
    if path and os.path.exists(path):
        return path
    here = os.path.dirname(os.path.abspath(__file__))
    guess = os.path.join(here, "..", "..", "build", "prt")
    return os.path.abspath(guess) if os.path.exists(guess) else None


@pytest.fixture(scope="session")
def prt_cli():
    """A function running `prt ARGS...` (quiet), failing the test with its stderr on error."""
    path = _cli()
    if path is None:
        pytest.skip("the prt command line is not built (PRT_CLI unset)")

    def run(*args, check=True):
        proc = subprocess.run([path, "-q", *map(str, args)], capture_output=True, text=True)
        if check and proc.returncode != 0:
            pytest.fail(f"prt {' '.join(map(str, args))} failed: {proc.stderr}")
        return proc

    return run


# A small scene with shadows (the sphere over the plane) that bakes in milliseconds.
SCENE = "builtin:sphere-plane?grid=12&subdiv=2"


@pytest.fixture(scope="session")
def scene():
    import prtkit
    return prtkit.load_mesh(SCENE)
