"""Arrays cross between C++ and numpy without copies: results are owned by a capsule holding the
C++ buffer; inputs read in place (a transfer) are viewed, not converted."""

import ctypes
import subprocess
import sys

import numpy as np
import pytest

import prtkit


def capsule_name(capsule):
    get = ctypes.pythonapi.PyCapsule_GetName
    get.restype, get.argtypes = ctypes.c_char_p, [ctypes.py_object]
    return get(capsule).decode()


def test_bake_returns_the_cpp_buffer_through_a_capsule(scene):
    T = prtkit.bake(scene, samples=16)
    base = T.base
    assert type(base).__name__ == "PyCapsule" and capsule_name(base) == "prtkit.buffer"
    assert not T.flags.owndata and T.flags.c_contiguous and T.flags.writeable
    # The array starts where the C++ transfer's storage starts: nothing was copied on the way out.
    assert prtkit._prtkit._buffer_address(base) == T.ctypes.data


def test_writes_to_a_baked_array_are_seen_by_the_library(scene):
    T = prtkit.bake(scene, mode="unshadowed", samples=16)
    L = np.zeros((9, 3), np.float32)
    L[0] = 1.0
    before = prtkit.relight(T, L)
    T[:, 0] *= 2.0  # in place: the library reads this very memory
    after = prtkit.relight(T, L)
    assert np.allclose(after, 2.0 * before, rtol=1e-6)
    wrapped = prtkit.Transfer(T)  # a view, no copy
    assert np.shares_memory(wrapped.values, T)
    T[0, 0] = 123.0
    assert wrapped.values[0, 0] == 123.0


def test_the_capsule_keeps_the_buffer_alive(scene):
    T = prtkit.bake(scene, samples=16)
    view = T[5:10]
    expected = view.copy()
    del T
    assert np.array_equal(view, expected)
    assert sys.getrefcount(view.base) >= 2


def test_read_bake_views_matrices_in_the_file(tmp_path, prt_cli):
    glb = tmp_path / "m.glb"
    prt_cli("bake", "builtin:sphere?subdiv=1", "--mode", "shadowed", "--transfer", "matrix",
            "--bands", "2", "--samples", "8", "-o", glb)
    M = prtkit.read_bake(glb)
    assert M.shape[1:] == (4, 4) and type(M.base).__name__ == "PyCapsule"
    assert not M.flags.writeable  # it views the file's bytes, which are not ours to change
    with pytest.raises(ValueError):
        M[0, 0, 0] = 1.0


def test_mesh_arrays_are_read_only_views(scene):
    v = scene.vertices
    assert v.base is scene and not v.flags.writeable and v.dtype == np.float32
    assert np.shares_memory(v, scene.vertices)
    assert scene.faces.dtype == np.uint32 and scene.faces.base is scene


def test_lightmap_uvs_are_a_view_of_the_packed_charts():
    box = prtkit.load_mesh("builtin:cornell?grid=4")
    uv = box.lightmap_uvs
    assert uv is not None and uv.shape == (len(box.vertices), 2) and uv.base is box
    assert not uv.flags.writeable and uv.min() > 0 and uv.max() < 1  # inside, with a gutter
    assert box.uvs is None
    assert prtkit.load_mesh("builtin:sphere?subdiv=1").lightmap_uvs is None


def test_transfer_views_its_compressed_arrays(scene):
    t = prtkit.compress(prtkit.bake_transfer(scene, samples=16), clusters=4, pca=2)
    for name in ("cluster_ids", "weights", "means", "basis"):
        a = getattr(t, name)
        assert a.base is t and not a.flags.writeable
    assert t.weights.shape == (scene.vertex_count, 2)
    assert t.means.shape == (4, 9) and t.basis.shape == (4, 2, 9)
    # row r = M_k + Σ_j w_rj B_kj: the arrays are the model, exactly as relighting reads it.
    k = t.cluster_ids
    rec = t.means[k] + np.einsum("rj,rjd->rd", t.weights, t.basis[k])
    assert np.allclose(rec, t.to_dense().values, atol=1e-6)


def test_no_copy_is_made_of_a_large_bake():
    # In a fresh process: the peak memory grows by the transfer once (about 100 MB of matrices),
    # not twice, as a copy on the way out would make it.
    script = """
import resource, sys
import prtkit
mesh = prtkit.load_mesh("builtin:sphere?subdiv=6")
prtkit.bake(mesh, samples=1, bands=1)
before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
T = prtkit.bake(mesh, mode="unshadowed", transfer="matrix", bands=5, samples=1)
after = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
print(T.nbytes, (after - before) * 1024)
"""
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                         check=True).stdout.split()
    size, grown = int(out[0]), int(out[1])
    assert size > 90e6
    assert grown < 1.5 * size, f"peak memory grew by {grown / size:.2f}x the transfer"
