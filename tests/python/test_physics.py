"""Physics through Python: the white furnace, rotation against re-projection, occlusion."""

import numpy as np

import prtkit


def constant_light(bands, value=1.0):
    L = np.zeros((bands * bands, 3), np.float32)
    L[0] = value * np.sqrt(4 * np.pi)  # L00 of a constant environment
    return L


def test_white_furnace():
    # A convex object under a constant white sky relights to exactly its albedo, whatever the
    # transport: nothing shadows it and nothing bounces back.
    sphere = prtkit.load_mesh("builtin:sphere?subdiv=3&albedo=1")
    L = prtkit.project_environment("builtin:constant", 3)
    # L00 is exact (exact texel solid angles); the rest is texel quadrature error.
    assert np.allclose(L[0], constant_light(3)[0], rtol=1e-6)
    assert np.abs(L[1:]).max() < 1e-4
    for mode in ("unshadowed", "shadowed", "interreflected"):
        T = prtkit.bake(sphere, mode=mode, samples=256)
        R = prtkit.relight(T, L)
        assert np.allclose(R, 1.0, atol=2e-3), mode
    # Glossy matrices: a Lambertian surface returns 1 everywhere; a normalised lobe returns
    # ks where it lies above the horizon (views within 25° of the normal; grazing views lose
    # the part of the lobe below it).
    M = prtkit.bake_transfer(sphere, mode="shadowed", transfer="matrix", samples=1024, bands=5)
    eye = np.array([0.3, 0.5, 3.0])
    R = prtkit.relight(M, constant_light(5), mesh=sphere, eye=eye)
    assert np.allclose(R, 1.0, atol=1e-5)
    R = prtkit.relight(M, constant_light(5), mesh=sphere, eye=eye,
                       material="phong?exponent=4&ks=0.5&kd=0.5")
    v = eye - sphere.vertices
    facing = (v * sphere.normals).sum(1) / np.linalg.norm(v, axis=1) > np.cos(np.radians(25))
    assert facing.sum() >= 10 and np.allclose(R[facing], 1.0, atol=1e-2)


def test_furnace_with_an_array_environment():
    sky = np.ones((32, 64, 3), np.float32)
    L = prtkit.project_environment(sky, 3)
    assert np.allclose(L[0], constant_light(3)[0], rtol=1e-5)
    assert np.abs(L[1:]).max() < 5e-3  # a 64 x 32 image: coarse quadrature beyond band 0
    assert np.array_equal(L, prtkit.load_environment(sky).project(3))


def test_rotating_the_light_is_rotating_the_environment():
    # Projecting a rotated environment equals rotating the projection (to quadrature error).
    rng = np.random.default_rng(1)
    dirs = rng.normal(size=(20000, 3)).astype(np.float32)
    dirs /= np.linalg.norm(dirs, axis=1, keepdims=True)
    env = prtkit.load_environment("builtin:sky")
    L = env.project(4)
    R = prtkit.rotation_matrix(10, 70, -20)
    rotated = prtkit.rotate_light(L, R)
    # Reconstruct both along d: rotated light at d equals the light at Rᵀ d.
    Y = prtkit.sh_eval(4, dirs)
    Yr = prtkit.sh_eval(4, (dirs @ R).astype(np.float32))  # rows: (Rᵀ d)ᵀ = dᵀ R
    assert np.allclose(Y @ rotated, Yr @ L, atol=1e-3 * np.abs(L).max())


def test_occlusion_against_the_plane():
    plane = prtkit.load_mesh("builtin:plane?size=1&grid=4")
    o = np.array([[0, 1, 0], [0, 1, 0], [5, 1, 0], [0, -1, 0]], np.float32)
    d = np.array([[0, -1, 0], [0, 1, 0], [0, -1, 0], [0, 1, 0]], np.float32)
    assert prtkit.occluded(plane, o, d).tolist() == [True, False, False, True]
    assert plane.occluded(o, d, tfar=0.5).tolist() == [False] * 4
    hit = prtkit.intersect(plane, o, d)
    assert hit["hit"].tolist() == [True, False, False, True]
    assert np.allclose(hit["t"][[0, 3]], 1.0) and hit["triangle"][1] == -1
    # One origin broadcast against many directions.
    many = np.tile(np.array([[0, -1, 0]], np.float32), (1000, 1))
    assert prtkit.occluded(plane, np.array([0, 1, 0]), many).all()


def test_shadowed_equals_one_minus_blocked_rays(scene):
    # T00 of a shadowed bake is Y00·(visible cosine-weighted fraction): check it against
    # occluded() at one plane vertex right under the sphere.
    T = prtkit.bake(scene, mode="shadowed", samples=4096)
    U = prtkit.bake(scene, mode="unshadowed")
    v = int(np.argmin(np.linalg.norm(scene.vertices - np.array([0, 0, 0]), axis=1)))
    rng = np.random.default_rng(0)
    u1, u2 = rng.random(20000), rng.random(20000)
    r, phi = np.sqrt(u1), 2 * np.pi * u2  # cosine-weighted about +Y (the plane's normal)
    dirs = np.stack([r * np.cos(phi), np.sqrt(1 - u1), r * np.sin(phi)], 1).astype(np.float32)
    origin = scene.vertices[v] + 1e-4 * scene.normals[v]
    visible = 1.0 - prtkit.occluded(scene, origin, dirs).mean()
    assert abs(T[v, 0] / U[v, 0] - visible) < 0.02
