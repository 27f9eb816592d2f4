"""Bad input is a clear Python exception, never a crash: ValueError for bad arrays and arguments,
prtkit.Error (a RuntimeError) with the library's one-line message for files and work."""

import numpy as np
import pytest

import prtkit

V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], np.float32)
F = np.array([[0, 1, 2]], np.int32)


@pytest.mark.parametrize("vertices,faces,match", [
    (V.astype(np.complex64), F, "real numbers"),
    (V.astype(bool), F, "real numbers"),
    (np.array(["a", "b", "c"]), F, "real numbers"),
    (V[:, :2], F, r"shape \(N, 3\), got \(3, 2\)"),
    (V.reshape(-1), F, r"shape \(N, 3\)"),
    (np.where(V == 1, np.nan, V), F, r"NaN at \[1, 0\]"),
    (np.where(V == 1, np.inf, V), F, "an infinity"),
    (V, F.astype(np.float32), "integer vertex indices"),
    (V, np.array([[0, 1, 3]]), r"faces\[0\] references vertex 3 \(the mesh has 3"),
    (V, np.array([[0, -1, 2]]), "references vertex -1"),
    (V, np.zeros((0, 3), np.int32), "faces is empty"),
])
def test_bad_mesh_arrays(vertices, faces, match):
    with pytest.raises(ValueError, match=match):
        prtkit.Mesh(vertices, faces)


def test_mesh_inputs_are_converted_when_that_is_safe():
    m = prtkit.Mesh(V.astype(np.float64)[::1], F.astype(np.uint64), albedo=0.5)
    assert m.vertices.dtype == np.float32 and np.allclose(m.albedo, 0.5)
    strided = np.zeros((3, 6), np.float64)[:, ::2]
    strided[:] = V
    assert np.array_equal(prtkit.Mesh(strided, F).vertices, V)
    with pytest.raises(ValueError, match=r"normals must have shape \(3, 3\)"):
        prtkit.Mesh(V, F, normals=np.ones((2, 3)))
    with pytest.raises(ValueError, match="albedo must not be negative"):
        prtkit.Mesh(V, F, albedo=(-1, 0, 0))


def test_bad_transfer_arrays(scene):
    T = prtkit.bake(scene, samples=8)
    L = prtkit.project_environment("builtin:sky", 3)
    with pytest.raises(ValueError, match="must be float32, got float64"):
        prtkit.relight(T.astype(np.float64), L)
    with pytest.raises(ValueError, match="C-contiguous"):
        prtkit.relight(np.asfortranarray(T), L)
    with pytest.raises(ValueError, match="C-contiguous"):
        prtkit.relight(np.zeros((10, 18), np.float32)[:, ::2], L)
    with pytest.raises(ValueError, match=r"\(N, B²\)"):
        prtkit.relight(np.zeros((10, 8), np.float32), L)
    with pytest.raises(ValueError, match="must be a numpy array"):
        prtkit.relight(T.tolist(), L)
    bad = T.copy()
    bad[3, 4] = np.nan
    with pytest.raises(ValueError, match=r"NaN at \[3, 4\]"):
        prtkit.relight(bad, L)
    with pytest.raises(ValueError, match="B² rows"):
        prtkit.relight(T, L[:5])
    with pytest.raises(ValueError, match="not a rotation"):
        prtkit.relight(T, L, rotation=np.eye(3) * 2)
    with pytest.raises(ValueError, match="albedo must have shape"):
        prtkit.relight(T, L, albedo=np.ones((3, 3)))


def test_bad_settings_are_value_errors_with_the_library_message(scene):
    with pytest.raises(ValueError, match="unknown transfer mode 'soft'"):
        prtkit.bake(scene, mode="soft")
    with pytest.raises(ValueError, match="unknown transfer layout"):
        prtkit.bake(scene, transfer="tensor")
    with pytest.raises(ValueError, match="bands=40: must be 1..16"):
        prtkit.bake(scene, bands=40)
    with pytest.raises(ValueError, match="samples=0"):
        prtkit.bake(scene, samples=0)
    with pytest.raises(ValueError, match=r"range \(5, 5\)"):
        prtkit.bake(scene, range=(5, 5))
    with pytest.raises(ValueError, match="phong"):
        prtkit.bake(scene, material="phong?exponent=-3")
    with pytest.raises(ValueError, match=r"albedo: components must lie in \[0, 1\]"):
        prtkit.bake(scene, albedo=2)
    with pytest.raises(TypeError, match="prtkit.Mesh or have .vertices"):
        prtkit.bake(42)
    with pytest.raises(TypeError, match="progress must be"):
        prtkit.bake(scene, samples=8, progress="yes")


def test_file_errors_carry_the_library_line(tmp_path):
    with pytest.raises(prtkit.Error, match="nope.obj: cannot open"):
        prtkit.load_mesh(tmp_path / "nope.obj")
    bad = tmp_path / "bad.glb"
    bad.write_bytes(b"glTF" + b"\0" * 8)
    with pytest.raises(prtkit.Error) as e:
        prtkit.read_bake(bad)
    assert str(e.value).startswith(str(bad)) and "\n" not in str(e.value)
    assert isinstance(e.value, RuntimeError)
    broken = tmp_path / "broken.obj"
    broken.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n")
    with pytest.raises(prtkit.Error, match="broken.obj"):
        prtkit.load_mesh(broken)
    with pytest.raises(prtkit.Error, match="builtin:nosuch"):
        prtkit.load_environment("builtin:nosuch")


def test_environment_arrays(tmp_path):
    with pytest.raises(ValueError, match="NaN"):
        prtkit.project_environment(np.full((8, 16, 3), np.nan, np.float32), 3)
    with pytest.raises(ValueError, match=r"shape \(N, M, 3\)"):
        prtkit.project_environment(np.ones((8, 16)), 3)
    with pytest.raises(ValueError, match="16x7 fits no layout"):
        prtkit.project_environment(np.ones((7, 16, 3)), 3)
    with pytest.warns(UserWarning, match="1 pixels with negative values clamped"):
        prtkit.load_environment(np.where(np.arange(8 * 16 * 3).reshape(8, 16, 3) == 5, -1.0, 1.0))
    with pytest.raises(ValueError, match="bands=0"):
        prtkit.project_environment("builtin:sky", 0)


def test_ray_queries_refuse_what_embree_cannot_take(scene):
    with pytest.raises(ValueError, match="differ in length"):
        prtkit.occluded(scene, np.zeros((3, 3)), np.ones((4, 3)))
    with pytest.raises(ValueError, match=r"directions\[1\] is zero"):
        prtkit.occluded(scene, np.zeros((2, 3)), np.array([[0, 1, 0], [0, 0, 0]]))
    with pytest.raises(ValueError, match="beyond"):
        prtkit.occluded(scene, np.full((1, 3), 1e30), np.ones((1, 3)))
    with pytest.raises(ValueError, match="NaN"):
        prtkit.occluded(scene, np.full((1, 3), np.nan), np.ones((1, 3)))


def test_cameras_and_directions_that_trace_nothing(scene):
    R = np.ones((scene.vertex_count, 3), np.float32)
    with pytest.raises(ValueError, match="eye must differ from the target"):
        prtkit.render(scene, R, camera=prtkit.Camera(eye=(0, 0, 0), target=(0, 0, 0)))
    with pytest.raises(ValueError, match="up must not be parallel"):
        prtkit.render(scene, R, camera=prtkit.Camera(eye=(0, 5, 0), target=(0, 0, 0)))
    with pytest.raises(ValueError, match="fov"):
        prtkit.Camera(fov=0)
    with pytest.raises(ValueError, match=r"directions\[0\] is zero"):
        prtkit.load_environment("builtin:sky").lookup(np.zeros((1, 3)))
    with pytest.raises(ValueError, match="not unit length"):
        prtkit.sh_eval(3, np.array([[0, 2.0, 0]]))
    with pytest.raises(ValueError, match=r"radiance must have shape"):
        prtkit.render(scene, R[:-1])
