"""Builds the prtkit extension for `pip install --no-build-isolation .` with the project's CMake.

The libraries and the module only (no tests, benchmarks or command line), Release, for the
interpreter pip runs, in build-pip/cmake (or PRTKIT_BUILD_DIR: an already configured build of
this project, whose target prt_python is then built as it is configured). PRTKIT_CMAKE_ARGS
adds configure options; CMAKE_BUILD_PARALLEL_LEVEL sets the build's jobs.

pip shows a build backend's output only with -v (without it, a spinner that moves when a line
comes, or in a log "still running..." at most once a minute), and all of it when the build fails.
So the build says little: a line for the configure, one per tenth of the build's steps (and every
30 s without one) with the time so far, and the compiler's errors when it fails. No time-left
estimate: the steps are not equal (the module's pybind11 sources, built last, take 4x the
average), so one from the steps done was 3-4x short. The whole CMake and compiler output goes to
build-pip/build.log.
"""

import os
import queue
import re
import shlex
import shutil
import subprocess
import sys
import threading
import time
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent
PIP_BUILD = ROOT / "build-pip"  # beside build/, never inside it (CMake's)

# A build step: Ninja's "[12/345] ..." or Make's "[ 45%] ...".
STEP = re.compile(r"\[\s*(?:(\d+)/(\d+)|(\d+)%)\]")
# Build tool chatter that says nothing the progress line does not.
CHATTER = re.compile(r"(ninja: no work to do|-- |Scanning dependencies|Consolidate compiler"
                     r"|make(\[\d+\])?: (Entering|Leaving) directory)")


def version():
    text = (ROOT / "CMakeLists.txt").read_text()
    return re.search(r"project\(prtkit VERSION ([0-9.]+)", text).group(1)


def note(text):
    print(f"prtkit: {text}", file=sys.stderr, flush=True)


def cache_entries(cache):
    """The NAME -> value entries of a CMakeCache.txt."""
    entries = {}
    for line in cache.read_text(errors="replace").splitlines():
        m = re.match(r"([A-Za-z_][A-Za-z0-9_.+-]*):[A-Z]+=(.*)", line)
        if m:
            entries[m.group(1)] = m.group(2)
    return entries


def stale_reason(build, source):
    """Why the CMake cache in build cannot configure source (it was made for another path, as a
    moved or copied checkout leaves it: CMake refuses it), or None when there is none or it can."""
    cache = build / "CMakeCache.txt"
    if not cache.is_file():
        return None
    entries = cache_entries(cache)
    home, made_in = entries.get("CMAKE_HOME_DIRECTORY"), entries.get("CMAKE_CACHEFILE_DIR")
    if home and Path(home).resolve() != Path(source).resolve():
        return f"configured for the sources in {home}, not {source}"
    if made_in and Path(made_in).resolve() != Path(build).resolve():
        return f"made in {made_in}, not here"
    return None


def pip_build_dir(source=ROOT, build=None):
    """build-pip/cmake of source, emptied first (with a note) where a moved or copied checkout left
    a cache for another path; a cache that is not prtkit's is left alone and stops the build."""
    build = Path(build) if build else Path(source) / "build-pip" / "cmake"
    why = stale_reason(build, source)
    if why:
        project = cache_entries(build / "CMakeCache.txt").get("CMAKE_PROJECT_NAME")
        if project != "prtkit" or build.is_symlink():
            sys.exit(f"{build}: {why}, and not a build of prtkit that setup.py made; "
                     "remove it or set PRTKIT_BUILD_DIR")
        note(f"{build} was {why}: starting a fresh build there")
        shutil.rmtree(build)
    return build


def duration(seconds):
    seconds = int(round(seconds))
    return f"{seconds // 60}m{seconds % 60:02d}s" if seconds >= 60 else f"{seconds}s"


def progress_line(fraction, elapsed, done=None, total=None):
    """'build 40% (51/126), 49s': the share of the build's steps done and the time so far."""
    text = f"build {int(fraction * 100)}%"
    if total:
        text += f" ({done}/{total})"
    return text + f", {duration(elapsed)}"


def run_logged(command, log, on_line=None, tick=None, every=30.0):
    """Runs command, its stdout and stderr appended to log; on_line(line) for each line as it
    comes, tick() every `every` seconds without one. Returns the exit status and the lines."""
    proc = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            stdin=subprocess.DEVNULL, text=True, errors="replace")
    lines = queue.Queue()

    def read():
        for line in proc.stdout:
            lines.put(line)
        lines.put(None)

    threading.Thread(target=read, daemon=True).start()
    output = []
    with open(log, "a") as f:
        f.write(f"$ {shlex.join(command)}\n")
        while True:
            try:
                line = lines.get(timeout=every)
            except queue.Empty:
                if tick:
                    tick()
                continue
            if line is None:
                break
            f.write(line)
            f.flush()
            output.append(line)
            if on_line:
                on_line(line.rstrip("\n"))
    return proc.wait(), output


def build_with_progress(command, log, step=10, every=30.0, clock=time.monotonic):
    """Runs the build command, saying one line per `step` percent of its steps (and every `every`
    seconds without one). Returns the exit status, the seconds it took, the number of compiler
    warnings and the lines that are neither steps nor chatter (the errors, when it fails)."""
    start = clock()
    state = {"shown": -1, "last": start, "fraction": 0.0, "done": None, "total": None}
    other = []

    def say():
        state["last"] = clock()
        note(progress_line(state["fraction"], state["last"] - start, state["done"], state["total"]))

    def on_line(line):
        m = STEP.match(line)
        if not m:
            if line.strip() and not CHATTER.match(line):
                other.append(line)
            return
        if m.group(2):
            done, total = int(m.group(1)), int(m.group(2))
            if done == 0:  # Ninja's "[0/2] Re-checking globbed directories..."
                return
            if total != state["total"]:  # CMake re-ran and Ninja started again
                state["shown"] = -1
            state["done"], state["total"], state["fraction"] = done, total, done / total
        else:
            state["fraction"] = int(m.group(3)) / 100
        bucket = int(state["fraction"] * 100) // step * step
        if bucket > state["shown"] or clock() - state["last"] >= every:
            state["shown"] = max(bucket, state["shown"])
            say()

    status, _ = run_logged(command, log, on_line, say, every)
    warnings = sum(bool(re.search(r": warning: ", line)) for line in other)
    return status, clock() - start, warnings, other


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        target = Path(self.get_ext_fullpath(ext.name)).resolve()
        given = os.environ.get("PRTKIT_BUILD_DIR")
        log = PIP_BUILD / "build.log"
        log.write_text("")
        if given:
            build = Path(given).resolve()
            if not (build / "CMakeCache.txt").exists():
                sys.exit(f"PRTKIT_BUILD_DIR={given}: not a configured CMake build of prtkit")
        else:
            build = pip_build_dir()
            configure = ["cmake", "-S", str(ROOT), "-B", str(build),
                         "-DCMAKE_BUILD_TYPE=Release", f"-DPython3_EXECUTABLE={sys.executable}",
                         "-DPRT_BUILD_TESTS=OFF", "-DPRT_BUILD_BENCH=OFF", "-DPRT_BUILD_APPS=OFF",
                         "-DPRT_BUILD_PYTHON=ON"]
            if shutil.which("ninja") and not (build / "CMakeCache.txt").exists():
                configure += ["-G", "Ninja"]
            configure += shlex.split(os.environ.get("PRTKIT_CMAKE_ARGS", ""))
            note(f"configuring {build} (Release, for {sys.executable}); full log: {log}")
            start = time.monotonic()
            status, output = run_logged(configure, log)
            if status != 0:
                sys.stderr.write("".join(output))
                sys.exit(f"prtkit: configure failed (exit {status}); full log: {log}")
            note(f"configured in {duration(time.monotonic() - start)}")
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL")
        note(f"building prt_python in {build}" + (f" ({jobs} jobs)" if jobs else "")
             + " (from scratch: minutes)")
        status, took, warnings, other = build_with_progress(
            ["cmake", "--build", str(build), "--target", "prt_python"], log)
        if status != 0:
            sys.stderr.write("".join(line + "\n" for line in other))
            sys.exit(f"prtkit: build failed (exit {status}); full log: {log}")
        note(f"built in {duration(took)}"
             + (f" ({warnings} compiler warnings: {log})" if warnings else ""))
        built = build / "python" / "prtkit" / target.name
        if not built.exists():
            sys.exit(f"{built}: not built (is the interpreter {sys.executable} the one CMake "
                     "found? see the configure output)")
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)


def drop_stale_manifest(egg_info):
    """Removes egg_info's SOURCES.txt where it lists absolute paths (setuptools keeps those while
    they exist, and a copied checkout's still name the original, which build_py then refuses:
    "setup script specifies an absolute path"). setuptools writes it again on every run."""
    manifest = Path(egg_info) / "SOURCES.txt"
    if manifest.is_file() and any(os.path.isabs(line)
                                  for line in manifest.read_text(errors="replace").splitlines()):
        manifest.unlink()


if __name__ == "__main__":  # pip (setuptools.build_meta) runs it so; tests import its helpers
    PIP_BUILD.mkdir(exist_ok=True)
    drop_stale_manifest(PIP_BUILD / "prtkit.egg-info")
    # Relative to setup.py's directory (pip runs it there), so that nothing setuptools records
    # under build-pip/ names this checkout's path.
    relative = os.path.relpath(PIP_BUILD)
    setup(
        version=version(),
        ext_modules=[CMakeExtension("prtkit._prtkit")],
        cmdclass={"build_ext": CMakeBuild},
        options={"build": {"build_base": os.path.join(relative, "setuptools")},
                 "egg_info": {"egg_base": relative}},
        zip_safe=False,
    )
