"""Probe grids from Python (issue 32): bake_probes is prt probes bit for bit, relight_probes is the
matrix product per probe that the test writes out in numpy, and shade_probes lights a moving
object's normals through the grid (numpy's own trilinear blend and clamped-cosine convolution)."""

import math

import numpy as np
import pytest

import prtkit
from conftest import SCENE


def test_bake_probes_is_bit_identical_to_prt_probes(tmp_path, prt_cli, scene):
    glb = tmp_path / "probes.glb"
    prt_cli("probes", SCENE, "--grid", "4x3x2", "--samples", "64", "--bounces", "1", "-o", glb)
    ours = prtkit.bake_probes(scene, grid=(4, 3, 2), samples=64)
    theirs = prtkit.read_bake(glb)
    assert ours.domain == "probes" and ours.layout == "matrix"
    assert ours.probe_grid["count"] == (4, 3, 2)
    a, b = np.asarray(ours), np.asarray(theirs)
    assert a.shape == b.shape == (24, 9, 9, 1) or a.shape == b.shape == (24, 9, 9)
    assert a.tobytes() == b.tobytes()


def test_relight_probes_is_the_matrix_times_the_light_per_probe(scene):
    t = prtkit.bake_probes(scene, grid=(3, 2, 2), mode="shadowed", samples=64)
    m = np.asarray(t)  # (12, 9, 9): row i arriving, column j source
    rng = np.random.default_rng(3)
    light = rng.uniform(-1, 1, (9, 3)).astype(np.float32)
    lit = prtkit.relight_probes(t, light)
    assert lit.shape == (2, 2, 3, 9, 3)
    want = np.einsum("pij,jc->pic", m.astype(np.float64), light.astype(np.float64))
    assert np.allclose(lit.reshape(12, 9, 3), want, atol=1e-5)


def test_shade_probes_blends_the_eight_probes_and_convolves(scene):
    t = prtkit.bake_probes(scene, grid=(3, 3, 3), mode="shadowed", samples=64)
    g = t.probe_grid
    light = np.zeros((9, 3), np.float32)
    light[0] = math.sqrt(4 * math.pi)
    light[2] = (0.5, 0.2, 0.1)  # a vertical gradient
    lit = prtkit.relight_probes(t, light).astype(np.float64)  # (z, y, x, 9, 3)
    origin, spacing = np.array(g["origin"]), np.array(g["spacing"])
    point = origin + spacing * np.array([1.3, 0.6, 1.7])
    normal = np.array([0.0, 1.0, 0.0])
    # numpy's trilinear blend of the probes at `point`
    u = (point - origin) / spacing
    lo = np.floor(u).astype(int)
    f = u - lo
    sh = np.zeros((9, 3))
    for dz in (0, 1):
        for dy in (0, 1):
            for dx in (0, 1):
                w = (f[0] if dx else 1 - f[0]) * (f[1] if dy else 1 - f[1]) * (f[2] if dz else 1 - f[2])
                sh += w * lit[lo[2] + dz, lo[1] + dy, lo[0] + dx]
    # E(n) = sum_l A_l sum_m L_lm Y_lm(n): the basis is prtkit's (its convention), the kernel the
    # test's own.
    y = prtkit.sh_eval(3, normal[None].astype(np.float32))[0]
    a = np.array([math.pi] + [2 * math.pi / 3] * 3 + [math.pi / 4] * 5)
    want = 0.7 * (a[:, None] * np.asarray(y)[:, None] * sh).sum(0) / math.pi
    got = prtkit.shade_probes(t, light, point[None].astype(np.float32),
                              normal[None].astype(np.float32), albedo=0.7)
    assert np.allclose(got[0], want, atol=1e-4)


def test_probes_refuse_what_is_not_theirs(scene):
    t = prtkit.bake_probes(scene, grid=(2, 2, 2), mode="shadowed", samples=16)
    with pytest.raises(ValueError, match="probe grid"):
        prtkit.relight(t, np.zeros((9, 3), np.float32))
    with pytest.raises(ValueError, match="grid"):
        prtkit.bake_probes(scene, grid=(0, 2, 2))
    surface = prtkit.bake_transfer(scene, mode="shadowed", samples=16)
    with pytest.raises(ValueError, match="not probes"):
        prtkit.relight_probes(surface, np.zeros((9, 3), np.float32))


def test_validate_compares_a_probe_grid_with_the_reference_at_six_normals(scene):
    # As prt validate: each validated probe seen by white diffuse surfaces facing +x, -x, +y,
    # -y, +z, -z (rows 6 p + a), the SH-free reference against the relit SH shaded there.
    t = prtkit.bake_probes(scene, grid=(3, 2, 3), mode="shadowed", samples=256)
    rep = prtkit.validate(scene, t, "builtin:sky", samples=64, vertices=4)
    rows = np.asarray(rep["vertices"])
    assert rows.shape == (24,)
    probes = rows // 6
    assert len(set(probes.tolist())) == 4 and (probes < 18).all()
    assert (rows % 6 == np.tile(np.arange(6), 4)).all()
    assert [r["bands"] for r in rep["rows"]] == [1, 2, 3]
    assert all(0 < r["explained"] <= 1.5 for r in rep["rows"])
