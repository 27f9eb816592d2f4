#!/usr/bin/env python3
"""The Python binding's overhead over the C++ bake (docs/performance.md, "Python module").

prtkit.bake on a prtkit.Mesh (BVH already built) against bench_python_overhead (prt::bake with a
prebuilt BVH, Google Benchmark) on the same mesh and settings, in alternating rounds of the same
run; reports the medians, the minima and their ratios, and, within the Python process, the time
the binding adds around prt::bake (the call's wall time less the bake's own, BakeStats).

    PYTHONPATH=build/python /usr/bin/python3 bench/python_overhead.py [--mesh PATH]
        [--samples 256] [--rounds 7] [--bench build/bench/bench_python_overhead]

The mesh defaults to the Stanford dragon (100k vertices) of /work/shared/data, else the bunny of
glmark2-data; without either the benchmark says so and exits 0.
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import time

import prtkit

MESHES = ["/work/shared/data/meshes/stanford_dragon/dragon_vrip_res2.ply.gz",
          "/usr/share/glmark2/models/bunny.obj"]
HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mesh", default=next((m for m in MESHES if os.path.exists(m)), None))
    ap.add_argument("--samples", type=int, default=256)
    ap.add_argument("--bands", type=int, default=3)
    ap.add_argument("--mode", default="shadowed")
    ap.add_argument("--rounds", type=int, default=7)
    ap.add_argument("--bench", default=os.path.join(HERE, "..", "build", "bench",
                                                    "bench_python_overhead"))
    a = ap.parse_args()
    if a.mesh is None:
        print("skipped: no mesh (neither the dragon of /work/shared/data nor glmark2-data's "
              "bunny); give --mesh")
        return 0
    if not os.path.exists(a.bench):
        print(f"skipped: {a.bench} is not built (cmake --build build --target "
              "bench_python_overhead)")
        return 0
    mesh = prtkit.load_mesh(a.mesh)
    prtkit.bake(mesh, samples=1)  # builds the BVH, as the C++ side does before timing
    settings = dict(mode=a.mode, bands=a.bands, samples=a.samples)
    print(f"{a.mesh}: {mesh.vertex_count} vertices; {a.mode}, {a.bands} bands, "
          f"{a.samples} samples, {prtkit.get_threads()} threads, {a.rounds} rounds")
    cpp, py, inside = [], [], []

    def run_cpp():
        out = subprocess.run([a.bench, a.mesh, "--samples", str(a.samples), "--bands",
                              str(a.bands), "--mode", a.mode, "--benchmark_format=json"],
                             check=True, capture_output=True, text=True).stdout
        cpp.append(json.loads(out)["benchmarks"][0]["real_time"] / 1e3)

    def run_py():
        t0 = time.perf_counter()
        t = prtkit.bake_transfer(mesh, **settings)
        py.append(time.perf_counter() - t0)
        inside.append(t.stats["seconds_total"])  # the time spent in prt::bake itself

    for r in range(a.rounds):
        # Alternate which goes first, so that a change of load does not favour one side.
        for run in ((run_cpp, run_py) if r % 2 == 0 else (run_py, run_cpp)):
            run()
        print(f"round {r + 1}: C++ {cpp[-1]:.3f} s, Python {py[-1]:.3f} s "
              f"(of which prt::bake {inside[-1]:.3f} s)")
    mc, mp = statistics.median(cpp), statistics.median(py)
    print(f"median: C++ {mc:.3f} s, Python {mp:.3f} s, overhead {100 * (mp / mc - 1):+.2f} %")
    print(f"min:    C++ {min(cpp):.3f} s, Python {min(py):.3f} s, overhead "
          f"{100 * (min(py) / min(cpp) - 1):+.2f} %")
    around = [p - i for p, i in zip(py, inside)]
    print(f"in the same process: the binding adds {1e3 * statistics.median(around):.2f} ms "
          f"(median; max {1e3 * max(around):.2f} ms) around prt::bake, "
          f"{100 * statistics.median([x / i for x, i in zip(around, inside)]):.3f} % of it")
    return 0


if __name__ == "__main__":
    sys.exit(main())
