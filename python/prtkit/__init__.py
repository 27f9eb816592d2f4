"""prtkit: precomputed radiance transfer from Python, numpy in and out.

The C++ library behind the ``prt`` command line, without copies in either direction:

    import prtkit
    mesh = prtkit.load_mesh("bunny.obj")                  # or prtkit.Mesh(vertices, faces)
    T = prtkit.bake(mesh, mode="shadowed", bands=3, samples=256)   # (N, 9) float32
    L = prtkit.project_environment("studio.exr", 3)       # (9, 3) SH lighting
    radiance = prtkit.relight(T, L, rotation=(0, 90, 0))  # (N, 3) per vertex

Long calls release the GIL, use every core, take ``progress=`` (a callable, or True for a tqdm
bar) and stop within a fraction of a second on Ctrl-C (KeyboardInterrupt). Library errors are
``prtkit.Error`` with the library's one-line message; bad arrays are ``ValueError``. Results are
bit-identical to the ``prt`` command line's with the same settings. See docs/python.md.
"""

from ._prtkit import (  # noqa: F401  (the public API)
    __version__,
    BakeFile,
    Camera,
    Cancelled,
    Environment,
    HaarLight,
    Error,
    Mesh,
    Transfer,
    as_mesh,
    auto_exposure,
    bake,
    bake_transfer,
    clamped_cosine_kernel,
    compress,
    convolve_light,
    frame_mesh,
    get_threads,
    intersect,
    irradiance,
    load_environment,
    load_mesh,
    occluded,
    project_environment,
    project_haar,
    read_bake,
    read_bake_file,
    read_games202_transport,
    read_haar_light,
    read_image,
    read_light,
    read_light_file,
    reference,
    relight,
    relight_probes,
    shade_probes,
    bake_probes,
    render,
    rotate_light,
    rotation_matrix,
    set_threads,
    sh_eval,
    validate,
    window_light,
    write_bake,
    write_games202_transport,
    write_image,
    write_light,
)

__all__ = [
    "BakeFile",
    "Camera",
    "Cancelled",
    "Environment",
    "Error",
    "HaarLight",
    "Mesh",
    "Transfer",
    "as_mesh",
    "auto_exposure",
    "bake",
    "bake_transfer",
    "clamped_cosine_kernel",
    "compress",
    "convolve_light",
    "frame_mesh",
    "get_threads",
    "intersect",
    "irradiance",
    "load_environment",
    "load_mesh",
    "occluded",
    "project_environment",
    "project_haar",
    "read_bake",
    "read_bake_file",
    "read_games202_transport",
    "read_haar_light",
    "read_image",
    "read_light",
    "read_light_file",
    "reference",
    "relight",
    "relight_probes",
    "shade_probes",
    "bake_probes",
    "render",
    "rotate_light",
    "rotation_matrix",
    "set_threads",
    "sh_eval",
    "validate",
    "window_light",
    "write_bake",
    "write_games202_transport",
    "write_image",
    "write_light",
]

# Classes and exceptions print as prtkit.X, where users find them.
for _cls in (BakeFile, Camera, Cancelled, Environment, Error, Mesh, Transfer):
    _cls.__module__ = "prtkit"
del _cls
