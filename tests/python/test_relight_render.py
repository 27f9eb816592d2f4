"""relight and render against `prt render`: a rotated light relit and drawn in Python gives the
image the command line writes, for vectors, matrices seen from the camera, and CPCA."""

import json

import numpy as np
import pytest

import prtkit
from conftest import SCENE

SIZE = (48, 36)
pytestmark = pytest.mark.filterwarnings("ignore:.*negative pixels set to 0")


def python_render(glb, light_spec, rotate, material=None, spp=2):
    f = prtkit.read_bake_file(glb)
    t = f.pick()
    L = prtkit.project_environment(light_spec, t.bands)  # what prt render's --light projects
    camera = prtkit.frame_mesh(f.mesh, *SIZE)
    radiance = prtkit.relight(t, L, rotation=rotate, mesh=f.mesh, eye=camera.eye,
                              material=material)
    return prtkit.render(f.mesh, radiance, camera=camera, size=SIZE, spp=spp, background="none")


def cli_render(prt_cli, tmp_path, glb, light_spec, rotate, material=None, spp=2):
    """prt render's EXR, as read back: the image reader clamps negative pixels (SH ringing) to 0
    and says so, so the comparisons clamp ours too."""
    out = tmp_path / "cli.exr"
    extra = ["--material", material] if material else []
    prt_cli("render", glb, "--light", light_spec, "--rotate", ",".join(map(str, rotate)),
            "--size", f"{SIZE[0]}x{SIZE[1]}", "--spp", spp, "--background", "none", *extra,
            "-o", out)
    return prtkit.read_image(out)


BAKES = {
    "vector": ["--mode", "shadowed", "--samples", "64"],
    "rgb": ["--mode", "interreflected", "--samples", "32", "--albedo", "0.8,0.4,0.2"],
    "matrix": ["--mode", "shadowed", "--transfer", "matrix", "--samples", "32",
               "--material", "phong?exponent=12&ks=0.5&kd=0.5"],
}


@pytest.mark.parametrize("kind", list(BAKES))
def test_relit_rotated_light_renders_as_prt_render(tmp_path, prt_cli, kind):
    glb = tmp_path / f"{kind}.glb"
    prt_cli("bake", SCENE, *BAKES[kind], "-o", glb)
    rotate = (20, 75, -10)
    ours = python_render(glb, "builtin:sky", rotate)
    theirs = cli_render(prt_cli, tmp_path, glb, "builtin:sky", rotate)
    assert ours.shape == (SIZE[1], SIZE[0], 3) and ours.dtype == np.float32
    assert ours.max() > 0.05  # the scene is lit and on screen
    assert np.array_equal(np.maximum(ours, 0), theirs)


def test_auto_exposure_is_prt_renders(tmp_path, prt_cli):
    """auto_exposure picks prt render's --exposure auto for the same radiance and camera, and
    write_image's default ('auto') writes the picture prt render writes (not exposure 0: a sky
    of radiance ~3 burns out)."""
    glb = tmp_path / "e.glb"
    prt_cli("bake", SCENE, *BAKES["vector"], "-o", glb)
    report, png = tmp_path / "r.json", tmp_path / "cli.png"
    prt_cli("render", glb, "--light", "builtin:sky", "--size", f"{SIZE[0]}x{SIZE[1]}", "--spp", 2,
            "--background", "none", "--json", report, "-o", png)
    stops = json.loads(report.read_text())["exposureStops"]
    f = prtkit.read_bake_file(glb)
    L = prtkit.project_environment("builtin:sky", f.pick().bands)
    camera = prtkit.frame_mesh(f.mesh, *SIZE)
    radiance = prtkit.relight(f.pick(), L, mesh=f.mesh)
    assert prtkit.auto_exposure(f.mesh, radiance, camera=camera, size=SIZE) == pytest.approx(
        stops, abs=1e-6)
    assert abs(stops) > 0.5  # the default of old (0 stops) would be visibly wrong
    image = prtkit.render(f.mesh, radiance, camera=camera, size=SIZE, spp=2, background="none")
    ours, zero = tmp_path / "py.png", tmp_path / "zero.png"
    prtkit.write_image(ours, image)
    prtkit.write_image(zero, image, exposure=0)
    cli = prtkit.read_image(png)
    assert np.abs(prtkit.read_image(ours) - cli).mean() < 0.01
    assert np.abs(prtkit.read_image(zero) - cli).mean() > 0.03
    with pytest.raises(ValueError, match="'auto'"):
        prtkit.write_image(ours, image, exposure="bright")


def test_compressed_relighting_renders_as_prt_render(tmp_path, prt_cli):
    glb, cglb = tmp_path / "d.glb", tmp_path / "c.glb"
    prt_cli("bake", SCENE, "--mode", "shadowed", "--samples", "64", "-o", glb)
    prt_cli("compress", glb, "--clusters", "8", "--pca", "3", "-o", cglb)
    # Our compression of the same rows is the command line's, bit for bit...
    ours = prtkit.compress(prtkit.read_bake_file(glb).pick(), clusters=8, pca=3)
    theirs = prtkit.read_bake_file(cglb).pick()
    assert theirs.compressed and ours.compressed
    for name in ("cluster_ids", "weights", "means", "basis"):
        assert np.array_equal(getattr(ours, name), getattr(theirs, name)), name
    # ... and relit in the compressed space, it draws the same image.
    rotate = (0, 120, 0)
    assert np.array_equal(np.maximum(python_render(cglb, "builtin:sky", rotate), 0),
                          cli_render(prt_cli, tmp_path, cglb, "builtin:sky", rotate))


def test_relight_takes_arrays_light_files_and_materials(tmp_path, prt_cli, scene):
    T = prtkit.bake(scene, mode="shadowed", samples=32)
    L = prtkit.project_environment("builtin:sky", 3)
    light_file = tmp_path / "sky.json"
    prt_cli("light", "builtin:sky", "--bands", "3", "-o", light_file)
    a = prtkit.relight(T, L, albedo=scene.albedo)
    assert np.array_equal(a, prtkit.relight(T, light_file, albedo=scene.albedo))
    assert np.array_equal(a, prtkit.relight(T, "builtin:sky", mesh=scene))
    grey = prtkit.relight(T, L, albedo=0.5)
    assert np.allclose(grey, 0.5 * prtkit.relight(T, L), rtol=1e-6)
    # A rotation as a matrix equals the same rotation as Euler degrees.
    assert np.array_equal(prtkit.relight(T, L, rotation=(10, 20, 30)),
                          prtkit.relight(T, L, rotation=prtkit.rotation_matrix(10, 20, 30)))
    with pytest.warns(UserWarning, match="glossy lobe needs a matrix"):
        prtkit.relight(T, L, material="phong?exponent=8&ks=0.5")


def test_matrices_need_a_mesh_and_an_eye(scene):
    M = prtkit.bake(scene, transfer="matrix", bands=2, samples=8)
    L = prtkit.project_environment("builtin:sky", 2)
    with pytest.raises(ValueError, match="needs mesh="):
        prtkit.relight(M, L, eye=(0, 1, 3))
    with pytest.raises(ValueError, match="needs eye="):
        prtkit.relight(M, L, mesh=scene)
    assert prtkit.relight(M, L, mesh=scene, eye=(0, 1, 3)).shape == (scene.vertex_count, 3)


def test_render_backgrounds(scene):
    R = np.full((scene.vertex_count, 3), 0.5, np.float32)
    img = prtkit.render(scene, R, size=(16, 12), spp=1, background=(0.0, 0.25, 1.0))
    corner = img[0, 0]
    assert np.allclose(corner, (0.0, 0.25, 1.0))
    env = prtkit.render(scene, R, size=(16, 12), spp=1, environment="builtin:sky")
    assert env[0, 0].sum() > 0
    sh = prtkit.render(scene, R, size=(16, 12), spp=1,
                       light=prtkit.project_environment("builtin:sky", 3))
    assert sh[0, 0].sum() > 0


def test_texel_transfer_bakes_relights_and_renders_as_prt_render(tmp_path, prt_cli):
    """Per-texel transfer (domain='texels'): the bake equals `prt bake --domain texels` bit for
    bit, a range is the whole bake's rows, and relit without a mesh and rendered as a lightmap
    it draws prt render's image; a mesh given to relight is refused (the albedo is per pixel)."""
    box = "builtin:cornell?grid=6"
    mesh = prtkit.load_mesh(box)
    t = prtkit.bake_transfer(mesh, mode="shadowed", domain="texels", resolution=24, samples=32)
    assert t.domain == "texels" and t.lightmap == {"width": 24, "height": 24, "padding": 2,
                                                    "seams_fixed": False, "denoised": False}
    glb = tmp_path / "t.glb"
    prt_cli("bake", box, "--mode", "shadowed", "--domain", "texels", "--resolution", 24,
            "--samples", 32, "-o", glb)
    f = prtkit.read_bake_file(glb)
    cli = f.pick()
    assert cli.domain == "texels"
    assert np.array_equal(np.asarray(cli.values), np.asarray(t.values))
    part = prtkit.bake(mesh, mode="shadowed", domain="texels", resolution=24, samples=32,
                       range=(100, 350))
    assert np.array_equal(part, np.asarray(t.values)[100:350])
    L = prtkit.project_environment("builtin:sky", 3)
    radiance = prtkit.relight(t, L)
    assert radiance.shape == (24 * 24, 3)
    with pytest.raises(ValueError, match="per texel"):
        prtkit.relight(t, L, mesh=mesh)
    camera = prtkit.frame_mesh(f.mesh, *SIZE)
    ours = prtkit.render(f.mesh, radiance.reshape(24, 24, 3), camera=camera, size=SIZE, spp=2,
                         background="none")
    theirs = cli_render(prt_cli, tmp_path, glb, "builtin:sky", (0, 0, 0))
    assert np.abs(np.maximum(ours, 0) - theirs).max() < 1e-4 * max(theirs.max(), 1)
    # Read upside down it is another image: the fetch really follows the lightmap.
    flipped = prtkit.render(f.mesh, radiance.reshape(24, 24, 3)[::-1].copy(), camera=camera,
                            size=SIZE, spp=2, background="none")
    assert np.abs(flipped - theirs).mean() > 10 * np.abs(np.maximum(ours, 0) - theirs).mean()
    with pytest.raises(ValueError, match="texel count"):
        prtkit.bake(mesh, domain="texels", resolution=8, range=(0, 100))


def test_texel_matrices_bake_as_the_cli_and_relight_at_the_texels(tmp_path, prt_cli):
    """Glossy matrices per texel: the bake equals `prt bake --transfer matrix --domain texels`
    bit for bit; relit with mesh= (at the texels' sample points) under a diffuse material they
    give the vector bake's radiance within its error; without mesh= they are refused."""
    box = "builtin:cornell?grid=6"
    mesh = prtkit.load_mesh(box)
    t = prtkit.bake_transfer(mesh, mode="shadowed", transfer="matrix", domain="texels",
                             resolution=16, samples=256, bands=3)
    assert t.domain == "texels" and t.layout == "matrix"
    glb = tmp_path / "m.glb"
    prt_cli("bake", box, "--mode", "shadowed", "--transfer", "matrix", "--domain", "texels",
            "--resolution", 16, "--samples", 256, "--bands", 3, "-o", glb)
    assert np.array_equal(np.asarray(prtkit.read_bake_file(glb).pick().values),
                          np.asarray(t.values))
    v = prtkit.bake_transfer(mesh, mode="shadowed", domain="texels", resolution=16,
                             samples=256, bands=3)
    L = prtkit.project_environment("builtin:sky", 3)
    eye = (0.0, 1.0, 4.0)
    rm = prtkit.relight(t, L, 1.0, mesh=mesh, eye=eye, material="lambert")
    rv = prtkit.relight(v, L)
    assert rm.shape == rv.shape == (256, 3)
    lit = rv.sum(axis=1) > 0
    assert lit.sum() > 100
    # The same diffuse light from two estimators (uniform vs cosine directions) and two band
    # cuts of the cosine (in the kernel vs in the transfer): a few percent on the mean; texel by
    # texel more (measured 11.5%), as the matrices' 3-band product rings in the shadows.
    assert abs(rm[lit].mean() / rv[lit].mean() - 1) < 0.05
    assert np.abs(rm[lit] - rv[lit]).mean() < 0.15 * rv[lit].mean()
    # Texel rows relit at another texel's point are another image.
    assert np.abs(rm[lit][::-1] - rv[lit]).mean() > 2 * np.abs(rm[lit] - rv[lit]).mean()
    with pytest.raises(ValueError, match="needs mesh="):
        prtkit.relight(t, L, eye=eye)


def test_texel_transfer_validates_as_prt_validate(tmp_path, prt_cli):
    """validate of a per-texel transfer: the same subset of valid texels and the same table as
    `prt validate`, its error explained by the band limit and the reference's noise."""
    box = "builtin:cornell?grid=6"
    mesh = prtkit.load_mesh(box)
    t = prtkit.bake_transfer(mesh, mode="shadowed", domain="texels", resolution=32, samples=256)
    r = prtkit.validate(mesh, t, "builtin:sky", samples=128, vertices=300)
    assert r["rows"][-1]["explained"] > 0.8
    glb = tmp_path / "t.glb"
    prt_cli("bake", box, "--mode", "shadowed", "--domain", "texels", "--resolution", 32,
            "--samples", 256, "-o", glb)
    prt_cli("validate", glb, "--light", "builtin:sky", "--reference-samples", 128,
            "--vertices", 300, "--json", tmp_path / "v.json")
    cli = json.load(open(tmp_path / "v.json"))
    assert abs(cli["rows"][-1]["relRmse"] - r["rows"][-1]["relRmse"]) < 1e-6
