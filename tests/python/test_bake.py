"""bake and read_bake against `prt bake`: the same settings give the same transfer, bit for bit."""

import numpy as np
import pytest

import prtkit
from conftest import SCENE

# (CLI options, bake keywords): every mode, both layouts, RGB inter-reflection, sampling,
# material, seed, bands, range.
CASES = [
    (["--mode", "unshadowed"], dict(mode="unshadowed")),
    (["--mode", "shadowed", "--samples", "64", "--seed", "7"],
     dict(mode="shadowed", samples=64, seed=7)),
    (["--mode", "shadowed", "--bands", "4", "--samples", "32", "--sampling", "uniform"],
     dict(mode="shadowed", bands=4, samples=32, sampling="uniform")),
    (["--mode", "interreflected", "--bounces", "2", "--samples", "32", "--albedo", "0.9,0.5,0.2"],
     dict(mode="interreflected", bounces=2, samples=32, albedo=(0.9, 0.5, 0.2))),
    (["--mode", "shadowed", "--transfer", "matrix", "--samples", "32"],
     dict(mode="shadowed", transfer="matrix", samples=32)),
    (["--mode", "interreflected", "--transfer", "matrix", "--samples", "16",
      "--material", "phong?exponent=8&ks=0.4&kd=0.6,0.5,0.4"],
     dict(mode="interreflected", transfer="matrix", samples=16,
          material="phong?exponent=8&ks=0.4&kd=0.6,0.5,0.4")),
    (["--mode", "shadowed", "--samples", "32", "--range", "100:250"],
     dict(mode="shadowed", samples=32, range=(100, 250))),
    (["--mode", "interreflected", "--samples", "512", "--target-error", "0.02"],
     dict(mode="interreflected", samples=512, target_error=0.02)),
]


@pytest.mark.parametrize("cli,kwargs", CASES, ids=[" ".join(c) for c, _ in CASES])
def test_bake_is_bit_identical_to_prt_bake(tmp_path, prt_cli, scene, cli, kwargs):
    glb = tmp_path / "cli.glb"
    prt_cli("bake", SCENE, *cli, "-o", glb)
    mode = kwargs["mode"]
    ours = prtkit.bake(scene, **kwargs)
    theirs = prtkit.read_bake(glb, mode=mode)
    assert ours.dtype == np.float32 and ours.shape == theirs.shape
    assert np.array_equal(ours, theirs)  # bit for bit (no NaN in a bake)
    assert ours.tobytes() == theirs.tobytes()


def test_shapes_of_every_layout(scene):
    n = scene.vertex_count
    assert prtkit.bake(scene, mode="unshadowed", bands=3).shape == (n, 9)
    rgb = prtkit.bake(scene, mode="interreflected", bands=2, samples=16, albedo=(1, 0.5, 0.25))
    assert rgb.shape == (n, 4, 3)
    assert prtkit.bake(scene, mode="shadowed", bands=2, samples=16,
                       transfer="matrix").shape == (n, 4, 4)
    m = prtkit.bake(scene, mode="interreflected", bands=2, samples=8, transfer="matrix",
                    albedo=(1, 0.5, 0.25))
    assert m.shape == (n, 4, 4, 3)


def test_a_mesh_made_of_arrays_bakes_as_the_loaded_mesh(scene):
    copy = prtkit.Mesh(scene.vertices.copy(), scene.faces.astype(np.int64), scene.normals.copy(),
                       albedo=scene.albedo)
    a = prtkit.bake(scene, samples=32)
    b = prtkit.bake(copy, samples=32)
    assert np.array_equal(a, b)


def test_any_object_with_vertices_and_faces_is_a_mesh(scene):
    class TrimeshLike:  # what trimesh and Open3D meshes look like to us
        vertices = scene.vertices.astype(np.float64)
        faces = scene.faces.astype(np.int64)
        vertex_normals = scene.normals.astype(np.float64)

    class Open3dLike:
        vertices = scene.vertices.tolist()
        triangles = scene.faces.tolist()

    a = prtkit.bake(scene, samples=16)
    assert np.array_equal(prtkit.bake(TrimeshLike(), samples=16), a)
    # Without normals they are computed as the loader computes them (angle-weighted).
    assert prtkit.bake(Open3dLike(), samples=16).shape == a.shape


def test_bake_transfer_carries_recipe_and_stats(scene):
    t = prtkit.bake_transfer(scene, mode="shadowed", samples=64, seed=3)
    assert t.layout == "vector" and t.bands == 3 and t.channels == 1
    assert t.row_count == scene.vertex_count and t.mode == "shadowed"
    assert t.recipe["samples"] == 64 and t.recipe["seed"] == 3
    assert t.stats["rays"] > 0 and t.stats["vertices"] == scene.vertex_count
    assert np.array_equal(t.values, prtkit.bake(scene, mode="shadowed", samples=64, seed=3))


def test_domains_and_what_texels_need(scene):
    assert prtkit.bake(scene, samples=8, domain="vertices").shape[0] == scene.vertex_count
    # The sphere-plane has no UV set a lightmap could lie in: said, with why each set failed.
    with pytest.raises(ValueError, match="no UV set can hold a 512 x 512 lightmap"):
        prtkit.bake(scene, samples=8, domain="texels")
    with pytest.raises(ValueError, match="unknown transfer domain 'voxels'"):
        prtkit.bake(scene, samples=8, domain="voxels")
    # A probe holds a matrix (prtkit.bake_probes): a vector bake over probes is refused by name.
    with pytest.raises(ValueError, match="layout='matrix'"):
        prtkit.bake(scene, samples=8, domain="probes")
    box = prtkit.load_mesh("builtin:cornell?grid=4")
    assert prtkit.bake(box, samples=8, domain="texels", transfer="matrix", bands=2,
                       resolution=8).shape[0] == 64
    with pytest.raises(ValueError, match="resolution=0"):
        prtkit.bake(box, samples=8, domain="texels", resolution=0)
    assert prtkit.bake(box, samples=8, domain="texels", resolution=16).shape == (256, 9)


def test_read_bake_picks_as_every_verb(tmp_path, prt_cli):
    glb = tmp_path / "two.glb"
    prt_cli("bake", SCENE, "--mode", "unshadowed", "--mode", "shadowed", "--samples", "16",
            "-o", glb)
    richest = prtkit.read_bake(glb)
    assert np.array_equal(richest, prtkit.read_bake(glb, mode="shadowed"))
    assert not np.array_equal(richest, prtkit.read_bake(glb, mode="unshadowed"))
    with pytest.raises(prtkit.Error, match="no interreflected"):
        prtkit.read_bake(glb, mode="interreflected")
    f = prtkit.read_bake_file(glb)
    assert [t.mode for t in f.transfers] == ["unshadowed", "shadowed"]
    assert f.complete and f.rows == (0, f.mesh.vertex_count)


def two_chart_plane_obj(path):
    """Two quads x in [-2, 0] and [0, 2] facing +Y, each its own chart in the texture UVs (the
    right one turned a quarter, at half the density): one UV seam at x = 0; a box above the
    seam (no UV area) casts a shadow across it."""
    v, vt, f = [], [], []
    for side in (0, 1):
        x0 = -2.0 if side == 0 else 0.0
        base = len(v)
        for dx, z in ((0, -2), (2, -2), (2, 2), (0, 2)):
            v.append((x0 + dx, 0.0, z))
            vt.append((0.05 + 0.2 * dx, 0.05 + 0.9 * (z + 2) / 4) if side == 0
                      else (0.55 + 0.1 * (z + 2), 0.05 + 0.1 * dx))
        f += [(base, base + 3, base + 2), (base, base + 2, base + 1)]
    base = len(v)
    for x in (-0.4, 0.4):
        for y in (0.6, 1.2):
            for z in (0.6, 1.4):
                v.append((x, y, z))
                vt.append((0.0, 0.0))
    for a, b, c, d in ((0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4),
                       (1, 5, 7, 3)):
        f += [(base + a, base + b, base + c), (base + a, base + c, base + d)]
    lines = [f"v {x} {y} {z}" for x, y, z in v] + [f"vt {s} {t}" for s, t in vt]
    lines += ["f " + " ".join(f"{i + 1}/{i + 1}" for i in tri) for tri in f]
    path.write_text("\n".join(lines) + "\n")


def test_seam_fix_is_the_clis(tmp_path, prt_cli):
    obj = tmp_path / "plane.obj"
    two_chart_plane_obj(obj)
    glb = tmp_path / "fixed.glb"
    prt_cli("bake", obj, "--mode", "shadowed", "--domain", "texels", "--resolution", "16",
            "--uv", "0", "--samples", "256", "--seam-fix", "-o", glb)
    mesh = prtkit.load_mesh(obj)
    kw = dict(mode="shadowed", samples=256, domain="texels", resolution=16, uv="0")
    fixed = prtkit.bake_transfer(mesh, seam_fix=True, **kw)
    plain = prtkit.bake_transfer(mesh, **kw)
    assert fixed.lightmap["seams_fixed"] and not plain.lightmap["seams_fixed"]
    cli = prtkit.read_bake_file(glb).pick()
    assert np.array_equal(np.asarray(cli.values), np.asarray(fixed.values))
    assert not np.array_equal(np.asarray(plain.values), np.asarray(fixed.values))
    # The request's one message, in Python's spelling (prt bake says --seam-fix).
    with pytest.raises(ValueError, match="seam_fix= fixes the seams of a lightmap: add domain='texels'"):
        prtkit.bake(mesh, samples=8, seam_fix=True)
    with pytest.raises(ValueError, match="needs the whole lightmap"):
        prtkit.bake(mesh, seam_fix=True, range=(0, 10), **{k: kw[k] for k in kw if k != "samples"},
                    samples=8)


def test_denoise_is_the_clis(tmp_path, prt_cli):
    obj = tmp_path / "plane.obj"
    two_chart_plane_obj(obj)
    glb = tmp_path / "denoised.glb"
    prt_cli("bake", obj, "--mode", "shadowed", "--domain", "texels", "--resolution", "16",
            "--uv", "0", "--samples", "64", "--denoise", "-o", glb)
    mesh = prtkit.load_mesh(obj)
    kw = dict(mode="shadowed", samples=64, domain="texels", resolution=16, uv="0")
    denoised = prtkit.bake_transfer(mesh, denoise=True, **kw)
    plain = prtkit.bake_transfer(mesh, **kw)
    assert denoised.lightmap["denoised"] and not plain.lightmap["denoised"]
    cli = prtkit.read_bake_file(glb).pick()
    assert np.array_equal(np.asarray(cli.values), np.asarray(denoised.values))
    assert not np.array_equal(np.asarray(plain.values), np.asarray(denoised.values))
    # The request's one message, in Python's spelling (prt bake says --denoise).
    with pytest.raises(ValueError, match="denoise= filters a lightmap: add domain='texels'"):
        prtkit.bake(mesh, samples=8, denoise=True)
    with pytest.raises(ValueError, match="needs the whole lightmap"):
        prtkit.bake(mesh, denoise=True, range=(0, 10), **{k: kw[k] for k in kw if k != "samples"},
                    samples=8)


def test_target_error_samples_adaptively_and_is_refused_where_not_made(scene):
    t = prtkit.bake_transfer(scene, mode="shadowed", samples=1024, target_error=0.03)
    assert t.recipe["target_error"] == 0.03
    assert 64 < t.stats["rays_per_row_and_pass"] < 1024
    for kwargs, match in [(dict(target_error=-1), "target_error: must be in"),
                          (dict(target_error=0.01, transfer="matrix"), "target_error samples"),
                          (dict(target_error=0.01, sampling="uniform"), "target_error needs")]:
        with pytest.raises(ValueError, match=match):
            prtkit.bake(scene, mode="shadowed", samples=64, **kwargs)
