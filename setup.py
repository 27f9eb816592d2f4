"""Builds the prtkit extension for `pip install --no-build-isolation .` with the project's CMake.

The libraries and the module only (no tests, benchmarks or command line), Release, for the
interpreter pip runs, in build-pip/cmake (or PRTKIT_BUILD_DIR: an already configured build of
this project, whose target prt_python is then built as it is configured). PRTKIT_CMAKE_ARGS
adds configure options; CMAKE_BUILD_PARALLEL_LEVEL sets the build's jobs.
"""

import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent
PIP_BUILD = ROOT / "build-pip"  # beside build/, never inside it (CMake's)


def version():
    text = (ROOT / "CMakeLists.txt").read_text()
    return re.search(r"project\(prtkit VERSION ([0-9.]+)", text).group(1)


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        target = Path(self.get_ext_fullpath(ext.name)).resolve()
        given = os.environ.get("PRTKIT_BUILD_DIR")
        build = Path(given).resolve() if given else PIP_BUILD / "cmake"
        if given:
            if not (build / "CMakeCache.txt").exists():
                sys.exit(f"PRTKIT_BUILD_DIR={given}: not a configured CMake build of prtkit")
        else:
            configure = ["cmake", "-S", str(ROOT), "-B", str(build),
                         "-DCMAKE_BUILD_TYPE=Release", f"-DPython3_EXECUTABLE={sys.executable}",
                         "-DPRT_BUILD_TESTS=OFF", "-DPRT_BUILD_BENCH=OFF", "-DPRT_BUILD_APPS=OFF",
                         "-DPRT_BUILD_PYTHON=ON"]
            if shutil.which("ninja") and not (build / "CMakeCache.txt").exists():
                configure += ["-G", "Ninja"]
            configure += shlex.split(os.environ.get("PRTKIT_CMAKE_ARGS", ""))
            subprocess.check_call(configure)
        subprocess.check_call(["cmake", "--build", str(build), "--target", "prt_python"])
        built = build / "python" / "prtkit" / target.name
        if not built.exists():
            sys.exit(f"{built}: not built (is the interpreter {sys.executable} the one CMake "
                     "found? see the configure output)")
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)


PIP_BUILD.mkdir(exist_ok=True)
setup(
    version=version(),
    ext_modules=[CMakeExtension("prtkit._prtkit")],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": str(PIP_BUILD / "setuptools")},
             "egg_info": {"egg_base": str(PIP_BUILD)}},
    zip_safe=False,
)
