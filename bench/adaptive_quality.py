#!/usr/bin/env python3
"""What adaptive sampling gains (issue 35; prt bake --target-error, docs/transport.md "Adaptive
sampling").

For each scene and target error E: bakes shadowed transfer adaptively (at most 4,096 rays per
row), then with every row at the adaptive bake's mean rays per row (rounded up: the same rays or
more), and prints against a converged reference (8,192 samples, another seed) the relative RMS
error over every coefficient (what prt validate reports) of both and their ratio; the same for
equal sampling at whole powers of two (where Sobol' points are whole nets: the bakes at the two
powers of two around the adaptive bake's rays, interpolated log-log); and the RMS error of the
radiance under the unit sky (what E targets), also as a share of E:

    PYTHONPATH=build/python /usr/bin/python3 bench/adaptive_quality.py [--quick]

Scenes: the builtin sphere over a plane, the builtin Cornell box per texel (128²), the Stanford
bunny (glmark2-data, when installed) and the Stanford dragon (/work/shared/data, when there).
"""
import os
import sys
import warnings

import numpy as np

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "build", "python"))
import prtkit  # noqa: E402

BUNNY = "/usr/share/glmark2/models/bunny.obj"
DRAGON = "/work/shared/data/meshes/stanford_dragon/dragon_vrip_res2.ply.gz"
SQRT_4PI = np.sqrt(4 * np.pi)


def errors(x, ref):
    x = x.reshape(x.shape[0], -1).astype(np.float64)
    ref = ref.reshape(ref.shape[0], -1).astype(np.float64)
    rel = np.sqrt(((x - ref) ** 2).sum() / (ref ** 2).sum())
    const = np.sqrt((((x[:, 0] - ref[:, 0]) * SQRT_4PI) ** 2).mean())
    return rel, const


def main():
    quick = "--quick" in sys.argv
    warnings.simplefilter("ignore")
    scenes = [("sphere-plane", "builtin:sphere-plane?grid=24&subdiv=3", {}),
              ("Cornell box, 128² texels", "builtin:cornell", dict(domain="texels",
                                                                  resolution=128))]
    if os.path.exists(BUNNY):
        scenes.append(("bunny", BUNNY, {}))
    if os.path.exists(DRAGON) and not quick:
        scenes.append(("dragon", DRAGON, {}))
    targets = (0.03, 0.01) if quick else (0.03, 0.015, 0.01, 0.005)
    print(f"{'scene':<26} {'E':>6} {'rays/row':>9} {'rel adaptive':>13} {'rel equal':>10} "
          f"{'ratio':>6} {'equal 2^k':>10} {'ratio':>6} {'sky err adaptive':>17} {'/E':>5}")
    for name, path, kw in scenes:
        mesh = prtkit.load_mesh(path)
        ref = np.asarray(prtkit.bake(mesh, mode="shadowed", samples=8192, seed=12345, **kw))
        for e in targets:
            t = prtkit.bake_transfer(mesh, mode="shadowed", samples=4096, seed=0, target_error=e,
                                     **kw)
            rays = t.stats["rays_per_row_and_pass"]
            equal = np.asarray(prtkit.bake(mesh, mode="shadowed", samples=int(np.ceil(rays)),
                                           seed=0, **kw))
            ra, ca = errors(np.asarray(t), ref)
            ru, _ = errors(equal, ref)
            # Equal sampling at the powers of two around the adaptive bake's rays (where Sobol'
            # points are whole nets), interpolated log-log at its rays.
            lo = 2 ** int(np.floor(np.log2(rays)))
            e_lo, _ = errors(np.asarray(prtkit.bake(mesh, mode="shadowed", samples=lo, seed=0,
                                                    **kw)), ref)
            e_hi, _ = errors(np.asarray(prtkit.bake(mesh, mode="shadowed", samples=2 * lo,
                                                    seed=0, **kw)), ref)
            rp = np.exp(np.interp(np.log(rays), np.log([lo, 2 * lo]), np.log([e_lo, e_hi])))
            print(f"{name:<26} {e:>6} {rays:>9.1f} {ra:>13.3e} {ru:>10.3e} {ra / ru:>6.2f} "
                  f"{rp:>10.3e} {ra / rp:>6.2f} {ca:>17.3e} {ca / e:>5.2f}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
