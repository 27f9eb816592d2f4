# Type stubs of the prtkit extension (python/src/*.cpp), for editors and type checkers.
# tests/python/test_stubs.py checks that every public name is here with the binding's parameters.

import os
from typing import Any, Callable, Dict, List, Literal, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

PathLike = Union[str, os.PathLike[str]]
#: None, True (a tqdm bar when tqdm is installed) or a callable taking the fraction done that may
#: return False to cancel.
Progress = Union[None, bool, Callable[[float], Optional[bool]]]
#: A 3x3 rotation matrix or Euler angles in degrees about X, then Y, then Z (R = Rz Ry Rx).
Rotation = Union[None, npt.ArrayLike]
#: A prtkit.Mesh or any object with .vertices and .faces (trimesh) or .triangles (Open3D).
MeshLike = Any
#: A path or builtin:NAME, an (H, W, 3) or (6, N, N, 3) linear float array, or an Environment.
EnvironmentLike = Union[PathLike, npt.ArrayLike, "Environment"]
#: A prtkit.Transfer, or dense rows in a float32 C-contiguous array.
TransferLike = Union["Transfer", npt.NDArray[np.float32]]
Mode = Literal["unshadowed", "shadowed", "interreflected"]
Layout = Literal["vector", "matrix"]

class Error(RuntimeError):
    """An error of the library, with its one-line message (naming the file)."""

class Cancelled(Error):
    """A long operation was cancelled (its progress callback returned False)."""

class Mesh:
    """A triangle mesh (copied from arrays; its Embree BVH built on first use and kept)."""

    def __init__(self, vertices: npt.ArrayLike, faces: npt.ArrayLike,
                 normals: Optional[npt.ArrayLike] = None, uvs: Optional[npt.ArrayLike] = None,
                 albedo: Optional[npt.ArrayLike] = None) -> None: ...
    @property
    def vertices(self) -> npt.NDArray[np.float32]: ...
    @property
    def normals(self) -> npt.NDArray[np.float32]: ...
    @property
    def faces(self) -> npt.NDArray[np.uint32]: ...
    @property
    def uvs(self) -> Optional[npt.NDArray[np.float32]]: ...
    @property
    def lightmap_uvs(self) -> Optional[npt.NDArray[np.float32]]: ...
    @property
    def albedo(self) -> Optional[npt.NDArray[np.float32]]: ...
    @property
    def vertex_count(self) -> int: ...
    @property
    def triangle_count(self) -> int: ...
    @property
    def source(self) -> str: ...
    @property
    def parts(self) -> List[Dict[str, Any]]: ...
    @property
    def gloss(self) -> Optional[Dict[str, Any]]: ...
    def occluded(self, origins: npt.ArrayLike, directions: npt.ArrayLike, tnear: float = 0.0,
                 tfar: float = ...) -> npt.NDArray[np.bool_]: ...
    def intersect(self, origins: npt.ArrayLike, directions: npt.ArrayLike, tnear: float = 0.0,
                  tfar: float = ...) -> Dict[str, np.ndarray]: ...

class Transfer:
    """A transfer (dense or CPCA-compressed) with how it was baked."""

    def __init__(self, values: npt.NDArray[np.float32], *, layout: Optional[Layout] = None,
                 first_row: int = 0, mode: Optional[Mode] = None, samples: Optional[int] = None,
                 bounces: Optional[int] = None, seed: Optional[int] = None,
                 sampling: Optional[str] = None, material: Optional[str] = None) -> None: ...
    @property
    def layout(self) -> str: ...
    @property
    def domain(self) -> str: ...
    @property
    def lightmap(self) -> Optional[Dict[str, int]]: ...
    @property
    def probe_grid(self) -> Optional[Dict[str, Tuple[float, float, float]]]: ...
    @property
    def bands(self) -> int: ...
    @property
    def haar(self) -> Optional[Dict[str, int]]: ...
    @property
    def haar_kinds(self) -> npt.NDArray[np.uint8]: ...
    @property
    def haar_indices(self) -> npt.NDArray[np.uint32]: ...
    @property
    def haar_values(self) -> npt.NDArray[np.float32]: ...
    @property
    def haar_bounce(self) -> npt.NDArray[np.float32]: ...
    @property
    def channels(self) -> int: ...
    @property
    def first_row(self) -> int: ...
    @property
    def row_count(self) -> int: ...
    def __len__(self) -> int: ...
    @property
    def representation(self) -> str: ...
    @property
    def compressed(self) -> bool: ...
    @property
    def shape(self) -> Tuple[int, ...]: ...
    @property
    def nbytes(self) -> int: ...
    @property
    def values(self) -> npt.NDArray[np.float32]: ...
    def __array__(self, dtype: Any = None, copy: Any = None) -> np.ndarray: ...
    @property
    def clusters(self) -> int: ...
    @property
    def basis_count(self) -> int: ...
    @property
    def cluster_ids(self) -> Optional[npt.NDArray[np.uint32]]: ...
    @property
    def weights(self) -> Optional[npt.NDArray[np.float32]]: ...
    @property
    def means(self) -> Optional[npt.NDArray[np.float32]]: ...
    @property
    def basis(self) -> Optional[npt.NDArray[np.float32]]: ...
    @property
    def mode(self) -> Optional[str]: ...
    @property
    def recipe(self) -> Optional[Dict[str, Any]]: ...
    @property
    def stats(self) -> Optional[Dict[str, Any]]: ...
    @property
    def compression(self) -> Optional[Dict[str, Any]]: ...
    def cut(self, bands: int) -> "Transfer": ...
    def to_dense(self) -> "Transfer": ...

class Environment:
    """Distant light as a function of direction (an image or an analytic sky)."""

    @property
    def layout(self) -> str: ...
    @property
    def source(self) -> str: ...
    @property
    def texel_count(self) -> int: ...
    @property
    def images(self) -> List[npt.NDArray[np.float32]]: ...
    def lookup(self, directions: npt.ArrayLike) -> npt.NDArray[np.float32]: ...
    def project(self, bands: int, progress: Progress = None) -> npt.NDArray[np.float32]: ...

class Camera:
    """A pinhole camera (+Y up, gluLookAt's frame); fov is the full vertical angle in degrees."""

    eye: Tuple[float, float, float]
    target: Tuple[float, float, float]
    up: Tuple[float, float, float]
    fov: float
    def __init__(self, eye: npt.ArrayLike = (0, 0, 3), target: npt.ArrayLike = (0, 0, 0),
                 up: npt.ArrayLike = (0, 1, 0), fov: float = 40.0) -> None: ...

class BakeFile:
    """A bake file as read: its mesh and transfers."""

    @property
    def mesh(self) -> Mesh: ...
    @property
    def transfers(self) -> List[Transfer]: ...
    @property
    def format_version(self) -> int: ...
    @property
    def generator(self) -> str: ...
    @property
    def rows(self) -> Tuple[int, int]: ...
    @property
    def complete(self) -> bool: ...
    def pick(self, mode: Optional[Mode] = None, transfer: Optional[Layout] = None) -> Transfer: ...

# --- meshes and rays ----------------------------------------------------------------------------

def load_mesh(path: Union[PathLike, Sequence[PathLike]]) -> Mesh:
    """Loads OBJ, PLY, OFF, glTF/GLB (optionally .gz) or builtin:NAME; a list is one scene."""

def as_mesh(mesh: MeshLike) -> Mesh: ...
def occluded(mesh: MeshLike, origins: npt.ArrayLike, directions: npt.ArrayLike,
             tnear: float = 0.0, tfar: float = ...) -> npt.NDArray[np.bool_]:
    """(M,) bool: anything on each ray within (tnear, tfar), through the bake's Embree BVH."""

def intersect(mesh: MeshLike, origins: npt.ArrayLike, directions: npt.ArrayLike,
              tnear: float = 0.0, tfar: float = ...) -> Dict[str, np.ndarray]:
    """Closest hits: dict of (M,) arrays hit, t, triangle, u, v."""

# --- baking ---------------------------------------------------------------------------------------

def bake(mesh: MeshLike, mode: Mode = "shadowed", bands: int = 3, samples: Optional[int] = None,
         seed: int = 0, bounces: int = 1, transfer: Layout = "vector",
         material: Optional[str] = None, albedo: Optional[npt.ArrayLike] = None,
         sampling: str = "cosine", range: Union[None, Tuple[int, int], range] = None,
         domain: str = "vertices", resolution: int = 512, uv: str = "auto", padding: int = 2,
         seam_fix: bool = False, denoise: bool = False,
         progress: Progress = None, target_error: float = 0.0, basis: str = "sh",
         cube_resolution: int = 32, terms: int = 64) -> npt.NDArray[np.float32]:
    """SH transfer per vertex (or per texel, domain='texels': row y*resolution + x) as a numpy
    array owning the C++ buffer: (N, B²), (N, B², 3), (N, B², B²) or (N, B², B², 3);
    bit-identical to `prt bake` with the same settings."""

def bake_transfer(mesh: MeshLike, mode: Mode = "shadowed", bands: int = 3,
                  samples: Optional[int] = None, seed: int = 0, bounces: int = 1,
                  transfer: Layout = "vector", material: Optional[str] = None,
                  albedo: Optional[npt.ArrayLike] = None, sampling: str = "cosine",
                  range: Union[None, Tuple[int, int], range] = None, domain: str = "vertices",
                  resolution: int = 512, uv: str = "auto", padding: int = 2,
                  seam_fix: bool = False, denoise: bool = False, progress: Progress = None,
                  target_error: float = 0.0, basis: str = "sh", cube_resolution: int = 32,
                  terms: int = 64) -> Transfer:
    """bake, returning a Transfer with its recipe and statistics; basis='haar' bakes Haar
    wavelet transfer (sparse rows: haar_kinds, haar_indices, haar_values)."""

def compress(transfer: TransferLike, clusters: int = 64, pca: int = 8, seed: int = 0,
             iterations: int = 30, tolerance: float = 1e-3, progress: Progress = None) -> Transfer:
    """CPCA compression (Sloan et al. 2003), as `prt compress`."""

# --- light ----------------------------------------------------------------------------------------

def load_environment(source: EnvironmentLike, layout: Optional[str] = None) -> Environment: ...
def project_environment(source: EnvironmentLike, bands: int, layout: Optional[str] = None,
                        compat: Optional[Literal["games202"]] = None,
                        progress: Progress = None) -> npt.NDArray[np.float32]:
    """SH lighting (B², 3) of an environment, as `prt light`."""

class HaarLight:
    """All-frequency light: an environment's K largest Haar wavelet terms over an N² cube map
    with its unshadowed part (`prt light --basis haar`; docs/haar.md)."""

    @property
    def resolution(self) -> int: ...
    @property
    def terms(self) -> int: ...
    @property
    def energy_kept(self) -> float: ...
    @property
    def indices(self) -> npt.NDArray[np.uint32]: ...
    @property
    def values(self) -> npt.NDArray[np.float32]: ...
    @property
    def selection(self) -> str: ...
    @property
    def source(self) -> str: ...
    def write(self, path: PathLike) -> None: ...

def project_haar(source: EnvironmentLike, resolution: int = 32, terms: int = 200,
                 rotation: Rotation = None, selection: str = "area",
                 layout: Optional[str] = None) -> HaarLight:
    """The K largest area-weighted wavelet terms of an environment's N² cube map, as
    `prt light --basis haar`."""

def read_haar_light(path: PathLike) -> HaarLight:
    """A Haar light file (`prt light --basis haar`)."""

def rotation_matrix(x: float, y: float, z: float) -> npt.NDArray[np.float64]: ...
def rotate_light(light: npt.ArrayLike, rotation: Rotation) -> npt.NDArray[np.float32]: ...
def window_light(light: npt.ArrayLike, window: str = "hanning",
                 width: Optional[float] = None) -> npt.NDArray[np.float32]: ...
def convolve_light(light: npt.ArrayLike, kernel: npt.ArrayLike) -> npt.NDArray[np.float32]: ...
def irradiance(light: npt.ArrayLike) -> npt.NDArray[np.float32]: ...
def clamped_cosine_kernel(bands: int) -> npt.NDArray[np.float64]: ...
def sh_eval(bands: int, directions: npt.ArrayLike) -> npt.NDArray[np.float32]: ...

# --- relighting and images ------------------------------------------------------------------------

def relight(transfer: TransferLike, light: Union[npt.ArrayLike, PathLike, HaarLight],
            albedo: Optional[npt.ArrayLike] = None, rotation: Rotation = None, *,
            mesh: Optional[MeshLike] = None, eye: Optional[npt.ArrayLike] = None,
            material: Optional[str] = None) -> npt.NDArray[np.float32]:
    """Exit radiance (N, 3) per row: vectors, matrices seen from `eye`, CPCA; a Haar transfer
    under a HaarLight, a Haar light file or an environment (mesh= for its normals)."""

def bake_probes(mesh: MeshLike, grid: Union[str, Tuple[int, int, int]] = "auto",
                bounds: Optional[npt.ArrayLike] = None, mode: str = "interreflected",
                bands: int = 3, samples: int = 1024, seed: int = 0, bounces: int = 1,
                albedo: Optional[npt.ArrayLike] = None,
                range: Union[None, Tuple[int, int], range] = None,
                progress: Progress = None) -> Transfer:
    """Relightable probes (prt probes): a B² x B² matrix per probe of a grid in the scene."""

def relight_probes(transfer: TransferLike, light: npt.ArrayLike,
                   rotation: Rotation = None) -> npt.NDArray[np.float32]:
    """The SH of the light arriving at every probe: (nz, ny, nx, B², 3)."""

def shade_probes(transfer: TransferLike, light: npt.ArrayLike, points: npt.ArrayLike,
                 normals: npt.ArrayLike,
                 albedo: Optional[npt.ArrayLike] = None) -> npt.NDArray[np.float32]:
    """Diffuse exit radiance (N, 3) of points with normals lit through the probe grid."""

def frame_mesh(mesh: MeshLike, width: int = 640, height: int = 480) -> Camera: ...
def render(mesh: MeshLike, radiance: npt.ArrayLike, camera: Union[None, Camera, str] = None,
           size: Tuple[int, int] = (640, 480), spp: int = 4, seed: int = 0,
           background: Union[None, str, npt.ArrayLike] = None,
           environment: Optional[EnvironmentLike] = None, light: Optional[npt.ArrayLike] = None,
           rotation: Rotation = None, progress: Progress = None) -> npt.NDArray[np.float32]:
    """An (H, W, 3) linear image of the mesh shaded with per-vertex radiance, as `prt render`."""

def auto_exposure(mesh: MeshLike, radiance: npt.ArrayLike, camera: Union[None, Camera, str] = None,
                  size: Tuple[int, int] = (640, 480), tonemap: str = "aces") -> float:
    """The exposure in stops prt render picks (--exposure auto) for this radiance and camera."""

def reference(mesh: MeshLike, environment: EnvironmentLike, *, mode: Mode = "shadowed",
              samples: int = 1024, bounces: int = 1, material: Optional[str] = None,
              eye: Optional[npt.ArrayLike] = None, seed: int = 0, rotation: Rotation = None,
              vertices: Union[None, int, npt.ArrayLike] = None, heuristic: str = "power",
              progress: Progress = None) -> Dict[str, Any]:
    """Brute-force Monte Carlo radiance per vertex: vertices, radiance, std_error, rays, seconds."""

def validate(mesh: MeshLike, transfer: TransferLike, environment: EnvironmentLike, *,
             samples: int = 1024, bands: Optional[Sequence[int]] = None, vertices: int = 0,
             floor_vertices: int = 1024, window: str = "none", seed: int = 0,
             rotation: Rotation = None, heuristic: str = "power", mode: Optional[Mode] = None,
             bounces: Optional[int] = None, material: Optional[str] = None,
             encodings: Union[None, str, Sequence[str]] = None,
             progress: Progress = None) -> Dict[str, Any]:
    """The error per band count against the reference, as `prt validate --json`; with
    encodings ('all' or names), each irradiance encoding's cost too (`--encoding`)."""

# --- files ----------------------------------------------------------------------------------------

def read_bake(path: PathLike, mode: Optional[Mode] = None,
              transfer: Optional[Layout] = None) -> npt.NDArray[np.float32]: ...
def read_bake_file(path: PathLike) -> BakeFile: ...
def write_bake(path: PathLike, mesh: MeshLike,
               transfers: Union[TransferLike, Sequence[TransferLike]],
               mode: Optional[Mode] = None) -> None: ...
def read_light(path: PathLike) -> npt.NDArray[np.float32]: ...
def read_light_file(path: PathLike) -> Dict[str, Any]: ...
def write_light(path: PathLike, light: npt.ArrayLike, *, format: Optional[str] = None,  # json games202 threejs gltf-ibl cmgen unity
                source: str = "", layout: str = "", window: str = "none",
                rotation: npt.ArrayLike = (0, 0, 0)) -> None: ...
def read_games202_transport(path: PathLike) -> Dict[str, Any]: ...
def write_games202_transport(path: PathLike, transfer: TransferLike, mesh: MeshLike,
                             layout: str = "faces", channel: Optional[str] = None) -> None: ...
def read_image(path: PathLike, decode: str = "srgb") -> npt.NDArray[np.float32]: ...
def write_image(path: PathLike, image: npt.ArrayLike, tonemap: str = "aces",
                exposure: Union[float, str] = "auto") -> None: ...

# --- threads --------------------------------------------------------------------------------------

def set_threads(threads: int) -> None: ...
def get_threads() -> int: ...
def _buffer_address(capsule: Any) -> int: ...
