#!/usr/bin/env python3
"""Haar against SH at equal bytes per vertex (issue 33, docs/haar.md "Measured").

Bakes the Stanford bunny (glmark2-data) on a ground plane, shadowed, in SH at several band
counts and in the Haar basis (32² cube) at several budgets of terms, and validates each with
prt validate against the same Monte Carlo reference vertices under builtin:sky (a sun) and
Poly Haven's courtyard (blender-data, when installed). Prints, per environment, bytes per vertex
as stored (SH: 4 B² float coefficients; Haar: 5 + 4 K, its quantised terms) against the rel.
RMSE and the energy-weighted error:

    bench/haar_quality.py build/prt [--quick]

--quick: fewer budgets and 1,000 vertices.
"""
import json
import os
import subprocess
import sys
import tempfile

BUNNY = "/usr/share/glmark2/models/bunny.obj"
COURTYARD = "/usr/share/blender/datafiles/studiolights/world/courtyard.exr"


def run(prt, *args):
    subprocess.run([prt, "-q", *map(str, args)], check=True)


def validate(prt, bake, env, vertices, extra):
    with tempfile.NamedTemporaryFile(suffix=".json") as report:
        subprocess.run([prt, "-q", "validate", bake, "--light", env, "--vertices", str(vertices),
                        "--json", report.name, *map(str, extra)], check=True,
                       stdout=subprocess.DEVNULL)
        return json.load(open(report.name))


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    prt = os.path.abspath(sys.argv[1])
    quick = "--quick" in sys.argv
    if not os.path.exists(BUNNY):
        sys.exit(f"{BUNNY} not found (Debian's glmark2-data)")
    envs = ["builtin:sky"] + ([COURTYARD] if os.path.exists(COURTYARD) else [])
    vertices = 1000 if quick else 2000
    bands = [3, 5, 8] if quick else [3, 5, 8, 11, 16]
    # Each budget at the bytes of a band count: 5 + 4 K ≤ 4 B² (transfer/haar_rows.hpp).
    terms = [(4 * b * b - 5) // 4 for b in bands] + ([] if quick else [1023])
    scene = [BUNNY, "builtin:plane?y=-1"]
    rows = {env: [] for env in envs}
    with tempfile.TemporaryDirectory() as tmp:
        for b in bands:
            out = os.path.join(tmp, f"sh{b}.glb")
            run(prt, "bake", *scene, "--mode", "shadowed", "--bands", b, "--samples", 1024,
                "-o", out)
            for env in envs:
                r = validate(prt, out, env, vertices, ["--bands-list", b])
                row = r["rows"][-1]
                rows[env].append((4 * b * b, f"SH {b} bands", row["relRmse"],
                                  row["energyWeightedRelErr"]))
        for k in terms:
            out = os.path.join(tmp, f"haar{k}.glb")
            run(prt, "bake", *scene, "--mode", "shadowed", "--basis", "haar", "--terms", k,
                "-o", out)
            for env in envs:
                r = validate(prt, out, env, vertices, ["--terms", 200])
                row = r["rows"][0]
                rows[env].append((5 + 4 * k, f"Haar {k} terms", row["relRmse"],
                                  row["energyWeightedRelErr"]))
    for env in envs:
        print(f"\n{env} (bunny on a plane, shadowed, {vertices} vertices)")
        print(f"{'bytes/vertex':>12}  {'storage':<16} {'rel RMSE':>9} {'energy-weighted':>16}")
        for bytes_, label, rel, energy in sorted(rows[env]):
            print(f"{bytes_:>12}  {label:<16} {100 * rel:>8.2f}% {100 * energy:>15.2f}%")


if __name__ == "__main__":
    main()
