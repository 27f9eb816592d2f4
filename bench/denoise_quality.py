#!/usr/bin/env python3
"""What prt denoise gains (issue 35, docs/validation.md "Denoising per-texel transfer").

For each scene and sample count N: bakes per texel at N and 4N samples and a converged
reference, denoises the N bake (prt denoise, its defaults), and prints the relative RMS error
of the relit radiance of each against the reference's, under builtin:sky and builtin:studio at
3 bands, over the texels the reference covers:

    bench/denoise_quality.py build/prt [--quick]

Scenes: the builtin Cornell box at 128² (shadowed and inter-reflected) and the Stanford bunny
(glmark2-data) over prt unwrap's atlas at 256² (shadowed). The reference is 8,192 samples
(Cornell) and 4,096 (bunny); N = 64 and 256.
"""
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "build", "python"))
import prtkit  # noqa: E402


def run(prt, *args):
    subprocess.run([prt, "-q", *map(str, args)], check=True)


def relit(path, light):
    t = np.asarray(prtkit.read_bake(path), dtype=np.float64)
    t = t.reshape(t.shape[0], -1)
    if t.shape[1] == 3 * light.shape[0]:  # RGB rows: coefficient-major, then r g b
        return (t.reshape(t.shape[0], -1, 3) * light[None]).sum(1)
    return t @ light[:, 1:2]


def main():
    prt = sys.argv[1] if len(sys.argv) > 1 else "build/prt"
    quick = "--quick" in sys.argv
    work = tempfile.mkdtemp(prefix="prt-denoise-")
    lights = {}
    for name in ("sky", "studio"):
        f = os.path.join(work, name + ".json")
        run(prt, "light", "builtin:" + name, "--bands", 3, "-o", f)
        lights[name] = np.array(json.load(open(f))["coefficients"])
    bunny = "/usr/share/glmark2/models/bunny.obj"
    scenes = [("cornell", "builtin:cornell", "shadowed", 128, 8192),
              ("cornell", "builtin:cornell", "interreflected", 128, 8192)]
    if os.path.exists(bunny) and not quick:
        atlas = os.path.join(work, "bunny-atlas.glb")
        run(prt, "unwrap", bunny, "-o", atlas)
        scenes.append(("bunny", atlas, "shadowed", 256, 4096))
    print(f"{'scene':8} {'mode':15} {'N':>5} | {'light':7} {'N':>8} {'N denoised':>11} {'4N':>8} | denoised / 4N")
    for label, scene, mode, res, ref_samples in scenes:
        def bake(n):
            out = os.path.join(work, f"{label}-{mode}-{n}.glb")
            if not os.path.exists(out):
                run(prt, "bake", scene, "--mode", mode, "--domain", "texels", "--resolution", res,
                    "--samples", n, "-o", out)
            return out
        ref = bake(ref_samples)
        for n in (64,) if quick else (64, 256):
            noisy, four = bake(n), bake(4 * n)
            den = noisy.replace(".glb", "-denoised.glb")
            run(prt, "denoise", noisy, "-o", den)
            for name, L in lights.items():
                r = relit(ref, L)
                mask = np.abs(r).sum(1) > 0
                err = lambda f: np.sqrt(np.mean((relit(f, L) - r)[mask] ** 2)) / np.sqrt(np.mean(r[mask] ** 2))
                a, b, c = err(noisy), err(den), err(four)
                print(f"{label:8} {mode:15} {n:5} | {name:7} {a:8.4f} {b:11.4f} {c:8.4f} | {b / c:5.2f}")


if __name__ == "__main__":
    main()
