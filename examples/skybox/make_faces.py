#!/usr/bin/env python3
"""Writes this folder's six cube faces (posx.png ... negz.png, 64x64, sRGB) from Poly Haven's
courtyard (CC0; Debian's blender-data ships it as studiolights/world/courtyard.exr), resampled
with prtkit itself in prtkit's cube convention (OpenGL's: include/prt/envmap/layout.hpp) and
tone mapped to 8 bits, as the cube-map folders of the GAMES202 course are.

    PYTHONPATH=build/python python3 examples/skybox/make_faces.py
"""
import os
import numpy as np
import prtkit

SOURCE = "/usr/share/blender/datafiles/studiolights/world/courtyard.exr"
N = 64
here = os.path.dirname(os.path.abspath(__file__))
env = prtkit.load_environment(SOURCE)

# Texel centres s, t in [-1, 1] (row 0 at the top), directions per face as layout.hpp gives them.
c = (np.arange(N) + 0.5) * 2 / N - 1
s, t = np.meshgrid(c, c)
one = np.ones_like(s)
faces = {
    "posx": (one, -t, -s), "negx": (-one, -t, s),
    "posy": (s, one, t), "negy": (s, -one, -t),
    "posz": (s, -t, one), "negz": (-s, -t, -one),
}
for name, (x, y, z) in faces.items():
    d = np.stack([x, y, z], axis=-1).reshape(-1, 3).astype(np.float32)
    radiance = env.lookup(d).reshape(N, N, 3)
    # Box-filter 4x4 supersamples would be nicer; the faces are an example, bilinear is enough.
    prtkit.write_image(os.path.join(here, name + ".png"), radiance, tonemap="aces", exposure=-1.0)
print("wrote", ", ".join(n + ".png" for n in faces), "in", here)
