#!/usr/bin/env python3
"""`prt light` against Filament's `cmgen` (the packaged peer), projecting an environment onto SH.

Both read the image, project it to 3 bands (9 RGB coefficients) and write a small text file:

    prt light ENV -b 3 -o out.json
    cmgen --sh=3 --sh-output=sh.txt -w no ENV     (-w no: no windowing, as prt light's default)

timed by wall clock and by CPU (user + system of the child), in alternating rounds so that a
change of load hits both, on a 4096 x 2048 sky (written here: a gradient and a sun) as a Radiance .hdr (flat RGBE
scanlines) and as an OpenEXR (written by prtkit.write_image, when the module is on PYTHONPATH). The
coefficients are compared too (cmgen's are irradiance-ready radiance SH in its own sign and
axis convention, so only the DC term, which no convention changes, is compared).

    PYTHONPATH=build/python /usr/bin/python3 bench/light_vs_cmgen.py [--prt build/prt] [--rounds 5]

Without cmgen (libfilament-tools) it says so and exits 0.
"""

import argparse
import json
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time

import numpy as np

def sky_image(width=4096, height=2048):
    """A latitude-longitude sky: a gradient and a small, bright sun (linear RGB, float32)."""
    y = (np.arange(height) + 0.5) / height
    x = (np.arange(width) + 0.5) / width
    th = np.pi * y[:, None]
    ph = 2 * np.pi * x[None, :]
    d = np.stack([np.sin(th) * np.cos(ph), np.cos(th) * np.ones_like(ph),
                  np.sin(th) * np.sin(ph)], -1)
    sun = np.array([0.5, 0.6, 0.62])
    sun /= np.linalg.norm(sun)
    img = np.array([0.4, 0.6, 1.0]) * np.clip(d[..., 1], 0, 1)[..., None] + 0.05
    img = img + np.array([50.0, 45.0, 40.0]) * (d @ sun > 0.9995)[..., None]
    return img.astype(np.float32)


def write_hdr(path, img):
    """Radiance RGBE with flat (uncompressed) scanlines."""
    height, width = img.shape[:2]
    m = img.max(-1)
    e = np.floor(np.log2(np.maximum(m, 1e-32))) + 1
    scale = np.where(m > 1e-32, 256.0 / np.exp2(e), 0)
    rgbe = np.zeros((height, width, 4), np.uint8)
    rgbe[..., :3] = np.clip(img * scale[..., None], 0, 255).astype(np.uint8)
    rgbe[..., 3] = np.where(m > 1e-32, e + 128, 0).astype(np.uint8)
    with open(path, "wb") as f:
        f.write(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n" % (height, width))
        f.write(rgbe.tobytes())


def timed(cmd, cwd):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run(cmd, cwd=cwd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def dc_prt(path):
    with open(path) as f:
        return json.load(f)["coefficients"][0]


def dc_cmgen(path):
    # cmgen's sh.txt: "( r, g, b); // L00" lines, first the DC term.
    with open(path) as f:
        for line in f:
            if "L00" in line:
                return [float(v) for v in line.split("(")[1].split(")")[0].split(",")]
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--prt", default=os.path.join(os.path.dirname(__file__), "..", "build", "prt"))
    ap.add_argument("--rounds", type=int, default=5)
    a = ap.parse_args()
    cmgen = shutil.which("cmgen")
    if not cmgen:
        print("skipped: cmgen is not installed (apt install libfilament-tools)")
        return 0
    prt = os.path.abspath(a.prt)
    work = tempfile.mkdtemp(prefix="prt-cmgen-")
    img = sky_image()
    inputs = [("4096x2048 .hdr", os.path.join(work, "sky4k.hdr"))]
    write_hdr(inputs[0][1], img)
    # The same sky as EXR, written by prtkit (tinyexr): cmgen cannot decode blender-data's EXRs
    # ("Unknown compression type").
    try:
        import prtkit
        inputs.append(("4096x2048 .exr", os.path.join(work, "sky4k.exr")))
        prtkit.write_image(inputs[1][1], img, exposure=0)
    except ImportError:
        print("(no prtkit module on PYTHONPATH: the EXR row is left out)")
    print(f"{'environment':<34} {'prt wall':>9} {'cmgen wall':>11} {'ratio':>12} "
          f"{'prt CPU':>8} {'cmgen CPU':>10} {'CPU ratio':>12}  DC prt / cmgen")
    for label, env in inputs:
        pw, pc, cw, cc = [], [], [], []
        for _ in range(a.rounds):
            w, c = timed([prt, "-q", "light", env, "-b", "3", "-o", "out.json"], work)
            pw.append(w)
            pc.append(c)
            w, c = timed([cmgen, "--sh=3", "--sh-output=sh.txt", "-w", "no", env], work)
            cw.append(w)
            cc.append(c)
        ratios = sorted(c / p for p, c in zip(pw, cw))
        cpu_ratios = sorted(c / p for p, c in zip(pc, cc))
        dp, dc = dc_prt(os.path.join(work, "out.json")), dc_cmgen(os.path.join(work, "sh.txt"))
        print(f"{label:<34} {min(pw):8.3f}s {min(cw):10.3f}s "
              f"{min(cw) / min(pw):5.2f}x ({ratios[0]:.2f}-{ratios[-1]:.2f}) "
              f"{min(pc):7.3f}s {min(cc):9.3f}s "
              f"{min(cc) / min(pc):5.2f}x ({cpu_ratios[0]:.2f}-{cpu_ratios[-1]:.2f})  "
              f"{dp[1]:.4g} / {dc[1] if dc else float('nan'):.4g}")
    shutil.rmtree(work)
    return 0


if __name__ == "__main__":
    sys.exit(main())
