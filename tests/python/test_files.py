"""Files through Python, against the command line: bake files both ways, SH light (JSON and the
course's light.txt), the course's cube faces and transport.txt, images."""

import json
import re

import numpy as np
import pytest

import prtkit
from conftest import SCENE


def test_project_environment_is_prt_light(tmp_path, prt_cli):
    for bands in (3, 5):
        out = tmp_path / f"sky{bands}.json"
        prt_cli("light", "builtin:sky", "--bands", bands, "-o", out)
        assert np.array_equal(prtkit.project_environment("builtin:sky", bands),
                              prtkit.read_light(out))


def test_an_image_file_and_its_array_project_alike(tmp_path, prt_cli):
    rng = np.random.default_rng(2)
    img = rng.random((16, 32, 3), dtype=np.float32) * 4
    path = tmp_path / "env.exr"
    prtkit.write_image(path, img)
    assert np.array_equal(prtkit.read_image(path), img)  # float EXR: exact
    from_file = prtkit.project_environment(path, 4)
    assert np.array_equal(from_file, prtkit.project_environment(img, 4))
    out = tmp_path / "env.json"
    prt_cli("light", path, "--bands", "4", "-o", out)
    assert np.array_equal(from_file, prtkit.read_light(out))
    # Probe layout by aspect ratio, or as told.
    square = rng.random((16, 16, 3), dtype=np.float32)
    assert prtkit.load_environment(square).layout == "probe"
    with pytest.raises(ValueError, match="2:1"):
        prtkit.load_environment(square, layout="latlong")


def test_games202_cube_faces(tmp_path, prt_cli):
    faces = tmp_path / "Skybox"
    faces.mkdir()
    rng = np.random.default_rng(3)
    for name in ("posx", "negx", "posy", "negy", "posz", "negz"):
        prtkit.write_image(faces / f"{name}.png", rng.random((8, 8, 3), dtype=np.float32),
                           tonemap="clamp")
    ours = prtkit.project_environment(faces, 3, compat="games202")
    txt = tmp_path / "light.txt"
    prt_cli("light", faces, "--compat", "games202", "--format", "games202", "-o", txt)
    # light.txt holds 9 significant digits: exact float round trip.
    assert np.array_equal(ours, prtkit.read_light(txt))
    # Our own convention differs from the course's (its posy/posz quirk).
    assert not np.allclose(ours, prtkit.project_environment(faces, 3))
    # Six faces as an array: +X -X +Y -Y +Z -Z.
    stack = np.stack([prtkit.read_image(faces / f"{n}.png")
                      for n in ("posx", "negx", "posy", "negy", "posz", "negz")])
    assert np.array_equal(prtkit.project_environment(stack, 3),
                          prtkit.project_environment(faces, 3))


def test_light_files_round_trip(tmp_path, prt_cli):
    L = prtkit.window_light(prtkit.project_environment("builtin:studio", 4), "hanning")
    js, txt = tmp_path / "l.json", tmp_path / "l.txt"
    prtkit.write_light(js, L, source="builtin:studio", window="hanning", rotation=(0, 30, 0))
    prtkit.write_light(txt, L)
    assert np.array_equal(prtkit.read_light(js), L)
    assert np.array_equal(prtkit.read_light(txt), L)
    meta = prtkit.read_light_file(js)
    assert meta["window"] == "hanning" and meta["rotation"] == (0, 30, 0)
    assert re.search(r"bands\s+4 \(16 coefficients\)", prt_cli("info", js).stdout)
    # The CLI's own windowed, rotated light equals the Python operations.
    cli = tmp_path / "cli.json"
    prt_cli("light", "builtin:studio", "--bands", "4", "--window", "hanning", "--rotate",
            "0,30,0", "-o", cli)
    ours = prtkit.rotate_light(L, (0, 30, 0))
    assert np.array_equal(ours, prtkit.read_light(cli))


def test_engine_light_files_equal_prt_lights(tmp_path, prt_cli):
    # The same light, from Python and from the CLI, in every engine's convention: byte for byte.
    L = prtkit.project_environment("builtin:sky", 3)
    for fmt, ext in (("threejs", "json"), ("gltf-ibl", "json"), ("cmgen", "txt"), ("unity", "json")):
        ours, cli = tmp_path / f"py.{fmt}.{ext}", tmp_path / f"cli.{fmt}.{ext}"
        prtkit.write_light(ours, L, format=fmt, source="builtin:sky")
        prt_cli("light", "builtin:sky", "--format", fmt, "-o", cli)
        assert ours.read_bytes() == cli.read_bytes(), fmt
    # three.js's basis has no Condon-Shortley phase: coefficients 1, 3, 5, 7 change sign.
    sh = np.array(json.loads((tmp_path / "py.threejs.json").read_text())["object"]["sh"]).reshape(9, 3)
    signs = np.array([1, -1, 1, -1, 1, -1, 1, -1, 1], dtype=np.float32)[:, None]
    assert np.allclose(sh, L * signs, rtol=1e-6, atol=0)
    with pytest.raises(ValueError, match="format must be"):
        prtkit.write_light(tmp_path / "x.json", L, format="unreal")


def test_write_bake_is_read_by_prt(tmp_path, prt_cli, scene):
    t = prtkit.bake_transfer(scene, mode="shadowed", samples=32)
    glb = tmp_path / "py.glb"
    prtkit.write_bake(glb, scene, t)
    info = prt_cli("info", glb).stdout
    assert "shadowed" in info and str(scene.vertex_count) in info
    back = prtkit.read_bake_file(glb).pick()
    assert back.recipe == t.recipe and np.array_equal(back.values, t.values)
    # prt renders it as it renders its own bake of the same settings.
    cli = tmp_path / "cli.glb"
    prt_cli("bake", SCENE, "--mode", "shadowed", "--samples", "32", "-o", cli)
    a, b = tmp_path / "a.exr", tmp_path / "b.exr"
    for src, out in ((glb, a), (cli, b)):
        prt_cli("render", src, "--size", "24x18", "--spp", "1", "-o", out)
    assert np.array_equal(prtkit.read_image(a), prtkit.read_image(b))


def test_write_bake_of_arrays_and_compressed_rows(tmp_path, prt_cli, scene):
    T = prtkit.bake(scene, mode="unshadowed")
    glb = tmp_path / "arr.glb"
    with pytest.raises(ValueError, match="give mode="):
        prtkit.write_bake(glb, scene, T)
    c = prtkit.compress(prtkit.bake_transfer(scene, mode="shadowed", samples=16), clusters=4, pca=2)
    prtkit.write_bake(glb, scene, [T, c], mode="unshadowed")
    f = prtkit.read_bake_file(glb)
    assert [(x.mode, x.compressed) for x in f.transfers] == [("unshadowed", False),
                                                             ("shadowed", True)]
    assert np.array_equal(f.transfers[1].weights, c.weights)
    assert np.array_equal(prtkit.read_bake(glb, mode="unshadowed"), T)


def test_games202_transport_is_prt_export(tmp_path, prt_cli):
    glb = tmp_path / "b.glb"
    prt_cli("bake", SCENE, "--mode", "shadowed", "--samples", "16", "-o", glb)
    ours, theirs = tmp_path / "py.txt", tmp_path / "cli.txt"
    f = prtkit.read_bake_file(glb)
    prtkit.write_games202_transport(ours, f.pick(), f.mesh)
    prt_cli("export", glb, "--format", "games202", "-o", theirs)
    assert ours.read_bytes() == theirs.read_bytes()
    parsed = prtkit.read_games202_transport(ours)
    assert parsed["layout"] == "faces" and parsed["bands"] == 3
    assert parsed["rows"].shape == (3 * f.mesh.triangle_count, 9)
    tri = f.mesh.faces.reshape(-1)
    assert np.array_equal(parsed["rows"], f.pick().values[tri])


def test_reference_is_prt_reference(tmp_path, prt_cli):
    glb, out = tmp_path / "b.glb", tmp_path / "ref.json"
    prt_cli("bake", SCENE, "--mode", "shadowed", "--samples", "16", "-o", glb)
    prt_cli("reference", glb, "--light", "builtin:sky", "--samples", "32", "--vertices", "40",
            "--seed", "5", "-o", out)
    cli = json.loads(out.read_text())
    f = prtkit.read_bake_file(glb)
    ours = prtkit.reference(f.mesh, "builtin:sky", mode="shadowed", samples=32, vertices=40,
                            seed=5)
    assert ours["vertices"].tolist() == cli["vertices"]
    assert np.array_equal(ours["radiance"], np.array(cli["radiance"], np.float32))
    assert np.array_equal(ours["std_error"], np.array(cli["stdError"], np.float32))


def test_validate_reports_per_band(scene):
    t = prtkit.bake_transfer(scene, mode="shadowed", samples=64)
    rep = prtkit.validate(scene, t, "builtin:sky", samples=32, vertices=60, floor_vertices=30)
    assert [r["bands"] for r in rep["rows"]] == [1, 2, 3]
    assert rep["vertex_error"].shape == (60,) and "rel" in rep["table"].lower()
    assert rep["rows"][-1]["relRmse"] < rep["rows"][0]["relRmse"]
    with pytest.raises(ValueError, match="give mode="):
        prtkit.validate(scene, t.values, "builtin:sky", samples=8, vertices=10)


def test_validate_measures_encodings_as_the_cli(scene):
    # A diffuse matrix bake: each encoding's shading against the reference and the transfer's
    # own relighting; at 3 bands l2 is that relighting, l1 is not.
    m = prtkit.bake_transfer(scene, mode="shadowed", samples=64, transfer="matrix")
    rep = prtkit.validate(scene, m, "builtin:sky", samples=32, vertices=40, floor_vertices=20,
                          encodings="all")
    enc = {e["encoding"]: e for e in rep["encodings"]}
    assert len(rep["encodings"]) == 9 and rep["encodings"][0]["encoding"] == "l1"
    assert enc["l2"]["vsBake"] < 1e-5 < enc["l1"]["vsBake"]
    assert "vs the bake's" in rep["table"]
    two = prtkit.validate(scene, m, "builtin:sky", samples=16, vertices=10, floor_vertices=10,
                          encodings=["zh3-shared", "l1"])
    assert [e["encoding"] for e in two["encodings"]] == ["zh3-shared", "l1"]
    with pytest.raises(ValueError, match="encoding must be"):
        prtkit.validate(scene, m, "builtin:sky", samples=8, vertices=10, encodings=["l3"])
    with pytest.raises(ValueError, match="twice"):
        prtkit.validate(scene, m, "builtin:sky", samples=8, vertices=10, encodings=["l1", "l1"])
    v = prtkit.bake_transfer(scene, mode="shadowed", samples=16)
    with pytest.raises(prtkit.Error, match="--encoding measures"):
        prtkit.validate(scene, v, "builtin:sky", samples=8, vertices=10, encodings="all")


def test_haar_bakes_read_and_relight_all_frequency(tmp_path, prt_cli):
    # Haar-wavelet transfer (prt bake --basis haar): read_bake_file reads it, relight() relights
    # it under a HaarLight; read_bake's dense numpy rows, compress and validate refuse it by name.
    scene = "builtin:sphere-plane?grid=8&subdiv=2"
    out = tmp_path / "haar.glb"
    prt_cli("bake", scene, "--mode", "shadowed", "--basis", "haar", "--resolution", "16",
            "--terms", "96", "--samples", "4", "-o", out)
    f = prtkit.read_bake_file(str(out))
    t = f.transfers[0]
    assert t.haar == {"resolution": 16, "terms": 96, "bounce_bands": 0} and t.bands == 0
    kinds, idx, val = t.haar_kinds, t.haar_indices, t.haar_values
    assert kinds.shape == (f.mesh.vertex_count,) and set(np.unique(kinds)) <= {0, 1}
    assert idx.shape == val.shape == (f.mesh.vertex_count, 96)
    assert idx.max() < 6 * 16 * 16 and np.isfinite(val).all()

    # The constant sky: every row relights to its visible cosine-weighted share, which the SH
    # bake's √(4π)·T₀ estimates independently (its own rays).
    const = prtkit.project_haar("builtin:constant", resolution=16, terms=6 * 16 * 16)
    assert const.terms <= 6 * 16 * 16 and const.indices.shape == (const.terms,)
    assert const.values.shape == (const.terms, 3) and abs(const.energy_kept - 1) < 1e-6
    haar = prtkit.relight(t, const, albedo=(1, 1, 1), mesh=f.mesh)
    sh = prtkit.bake(f.mesh, mode="shadowed", bands=3, samples=1024)[:, 0] * np.sqrt(4 * np.pi)
    assert haar.shape == (f.mesh.vertex_count, 3)
    assert np.abs(haar[:, 0] - sh).mean() < 0.01, np.abs(haar[:, 0] - sh).mean()

    # The sun: against the Monte Carlo reference the Haar relighting is closer than 3-band SH.
    sky = prtkit.project_haar("builtin:sky", resolution=16, terms=200)
    assert sky.terms == 200 and 0 < sky.energy_kept < 1
    path = tmp_path / "sky-haar.json"
    sky.write(path)
    again = prtkit.read_haar_light(path)
    assert np.array_equal(again.indices, sky.indices) and np.array_equal(again.values, sky.values)
    lit = prtkit.relight(t, again, mesh=f.mesh)  # the mesh's albedo, as the reference's
    assert np.array_equal(lit, prtkit.relight(t, str(path), mesh=f.mesh))
    ref = prtkit.reference(f.mesh, "builtin:sky", mode="shadowed", samples=256)
    ref = np.asarray(ref["radiance"] if isinstance(ref, dict) else ref)
    shb = prtkit.bake(f.mesh, mode="shadowed", bands=3, samples=256)
    shl = prtkit.relight(shb, prtkit.project_environment("builtin:sky", 3), mesh=f.mesh)

    def rel(x):
        return np.sqrt(((x - ref) ** 2).sum() / (ref ** 2).sum())

    assert rel(lit) < 0.7 * rel(shl), (rel(lit), rel(shl))

    with pytest.raises(prtkit.Error, match="haar.glb: holds Haar-wavelet transfer"):
        prtkit.read_bake(str(out))
    for call, match in [(lambda: t.values, "sparse wavelet terms"),
                        (lambda: prtkit.compress(t), "CPCA compresses SH rows"),
                        (lambda: prtkit.relight(t, const), "needs mesh="),
                        (lambda: prtkit.relight(t, np.zeros((9, 3), np.float32), mesh=f.mesh),
                         "the light is SH"),
                        (lambda: prtkit.relight(shb, const, mesh=f.mesh), "this transfer is SH"),
                        (lambda: prtkit.project_haar("builtin:sky", resolution=12), "resolution"),
                        (lambda: prtkit.project_haar("builtin:sky", resolution=4, terms=97),
                         "terms must be 1..96")]:
        with pytest.raises(ValueError, match=match):
            call()


def test_haar_bakes_in_python_per_vertex_and_per_texel(tmp_path, prt_cli):
    # bake_transfer(basis='haar') is prt bake --basis haar, bit for bit, per vertex and per
    # texel (--cube-resolution: the cube, --resolution the lightmap); a per-texel Haar bake
    # relights white at its texels' normals, as prt render does, and render() draws it.
    scene = "builtin:sphere-plane?grid=8&subdiv=2"
    for domain, args, kw in [
            ("vertices", ["--resolution", "8"], {}),
            ("texels", ["--domain", "texels", "--resolution", "16", "--cube-resolution", "8"],
             {"domain": "texels", "resolution": 16})]:
        out = tmp_path / f"h-{domain}.glb"
        prt_cli("bake", scene, "--mode", "shadowed", "--basis", "haar", "--terms", "20",
                "--samples", "2", *args, "-o", out)
        f = prtkit.read_bake_file(str(out))  # per texel: the mesh unwrapped as prt bake did
        cli, m = f.transfers[0], f.mesh
        t = prtkit.bake_transfer(m, mode="shadowed", basis="haar", cube_resolution=8, terms=20,
                                 samples=2, **kw)
        assert t.haar == {"resolution": 8, "terms": 20, "bounce_bands": 0} and t.domain == domain
        assert t.haar_bounce.shape == (len(t.haar_kinds), 0, 1)
        assert t.recipe["samples"] == 2
        for column in ("haar_kinds", "haar_indices", "haar_values"):
            assert np.array_equal(getattr(t, column), getattr(cli, column)), (domain, column)
    # One ray per cube texel unless told.
    assert prtkit.bake_transfer(m, basis="haar", cube_resolution=4, terms=4).recipe["samples"] == 1

    # Per texel under the constant sky: each covered texel's visible share, the SH bake's √(4π)T₀.
    # Every term kept, so that what is left is the bake's noise; no gutter (padding 0), which SH
    # fills with its neighbours' mean and Haar with one neighbour's row.
    t = prtkit.bake_transfer(m, mode="shadowed", basis="haar", cube_resolution=8, terms=384,
                             samples=4, domain="texels", resolution=16, padding=0)
    const = prtkit.project_haar("builtin:constant", resolution=8, terms=6 * 8 * 8)
    lit = prtkit.relight(t, const, mesh=m)
    assert lit.shape == (16 * 16, 3)
    sh = prtkit.bake(m, mode="shadowed", bands=1, samples=1024, domain="texels", resolution=16,
                     padding=0)
    sh = sh[:, 0] * np.sqrt(4 * np.pi)
    covered = sh != 0
    assert covered.sum() > 50
    assert np.abs(lit[covered, 0] - sh[covered]).mean() < 0.015
    image = prtkit.render(m, lit.reshape(16, 16, 3), size=(32, 24))
    assert image.shape == (24, 32, 3) and np.isfinite(image).all() and image.max() > 0

    for call, match in [
            (lambda: prtkit.bake(m, basis="haar"), "use bake_transfer"),
            (lambda: prtkit.bake_transfer(m, basis="haar", cube_resolution=12), "cube_resolution"),
            (lambda: prtkit.bake_transfer(m, basis="haar", domain="texels", resolution=16,
                                          denoise=True), "denoise"),
            (lambda: prtkit.bake_transfer(m, basis="haar", mode="interreflected", bands=6),
             "bands"),
            (lambda: prtkit.bake_transfer(m, basis="wavelet"), "basis")]:
        with pytest.raises(ValueError, match=match):
            call()


def test_interreflected_haar_rows_hold_their_bounce_in_sh(tmp_path, prt_cli):
    # bake_transfer(basis='haar', mode='interreflected') is prt bake's, bit for bit: each row
    # its Haar pairs and its bounce in SH of `bands` bands, RGB under a coloured albedo. The
    # pairs are the shadowed bake's own (the same rays); the bounce is what the SH bake of the
    # same bounces adds to its direct light; relit, it adds albedo ⊙ Σ B_i L_i to the rows.
    scene = "builtin:sphere-plane?grid=8&subdiv=2"
    out = tmp_path / "ir.glb"
    prt_cli("bake", scene, "--mode", "interreflected", "--bounces", "1", "--albedo",
            "0.9,0.5,0.3", "--basis", "haar", "--resolution", "8", "--terms", "20",
            "--bands", "2", "-o", out)
    f = prtkit.read_bake_file(str(out))
    cli, m = f.transfers[0], f.mesh
    kd = (0.9, 0.5, 0.3)
    t = prtkit.bake_transfer(m, mode="interreflected", bounces=1, basis="haar",
                             cube_resolution=8, terms=20, bands=2, albedo=kd)
    assert t.haar == {"resolution": 8, "terms": 20, "bounce_bands": 2} and t.channels == 3
    for column in ("haar_kinds", "haar_indices", "haar_values", "haar_bounce"):
        assert np.array_equal(getattr(t, column), getattr(cli, column)), column
    rows = len(t.haar_kinds)
    assert t.haar_bounce.shape == (rows, 4, 3) and np.abs(t.haar_bounce).max() > 0.01
    shadowed = prtkit.bake_transfer(m, mode="shadowed", basis="haar", cube_resolution=8,
                                    terms=20)
    for column in ("haar_kinds", "haar_indices", "haar_values"):
        assert np.array_equal(getattr(t, column), getattr(shadowed, column)), column
    # The SH bake's bounce: 1024 directions a row for each ray per cube texel, the same seed.
    ir = prtkit.bake(m, mode="interreflected", bounces=1, bands=2, samples=1024, albedo=kd)
    direct = prtkit.bake(m, mode="shadowed", bands=2, samples=1024)
    bounce = ir.reshape(rows, 4, 3) - direct.reshape(rows, 4, 1)
    assert np.abs(t.haar_bounce - bounce).max() < 1e-5
    # Relit: the bounce's share is albedo ⊙ Σ_i B_i L_i under the light's SH (the constant sky:
    # L_00 = √(4π), the rest 0).
    const = prtkit.project_haar("builtin:constant", resolution=8, terms=384)
    kd = np.array(kd, np.float32)
    added = prtkit.relight(t, const, mesh=m) - prtkit.relight(shadowed, const, mesh=m)
    expect = kd * t.haar_bounce[:, 0, :] * np.sqrt(4 * np.pi)
    assert np.abs(added - expect).max() < 1e-4 * max(1.0, np.abs(expect).max())
