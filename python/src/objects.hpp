#pragma once
// The C++ values behind the module's Python classes, shared by its files: Mesh (with its ray
// tracer, built once), Transfer (with how it was baked), Environment. Each is immutable once
// made, so the GIL can be released while the library reads it from any thread.

#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "common.hpp"
#include "prt/envmap/environment.hpp"
#include "prt/geometry/mesh.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/transfer/bake_settings.hpp"
#include "prt/transfer/cpca_settings.hpp"
#include "prt/transfer/transfer.hpp"

namespace prtpy {

/// prtkit.Mesh: a prt::Mesh and, once asked for, its Embree BVH.
class PyMesh {
 public:
  explicit PyMesh(prt::Mesh mesh) : mesh_(std::move(mesh)) {}
  const prt::Mesh& mesh() const { return mesh_; }
  /// The BVH (built on first use, thread-safe; call without the GIL: building takes time).
  const prt::Occluder& occluder() const;

 private:
  prt::Mesh mesh_;
  mutable std::mutex mutex_;
  mutable std::unique_ptr<prt::Occluder> occluder_;
};
using MeshPtr = std::shared_ptr<PyMesh>;

/// A prtkit.Mesh, or any object with `vertices` and `faces` (trimesh) or `triangles` (Open3D)
/// — and, if it has them, `vertex_normals` — as a mesh (copied; normals computed when absent).
MeshPtr toMesh(py::handle obj);
/// The mesh the arrays describe (prtkit.Mesh's constructor).
MeshPtr meshFromArrays(py::handle vertices, py::handle faces, py::handle normals, py::handle uvs,
                       py::handle albedo);

/// prtkit.Transfer: a prt::Transfer and, when it came from a bake or a bake file, its recipe
/// and statistics (and, compressed, how the CPCA was fitted).
struct PyTransfer {
  prt::Transfer transfer;
  std::optional<prt::BakeRecipe> recipe;
  std::optional<prt::BakeStats> stats;
  std::optional<prt::CpcaRecord> compression;
};
using TransferPtr = std::shared_ptr<PyTransfer>;

/// `range` ((first, end) or range(first, end); None: all) as rows of a domain of `rows` rows
/// named `what` ("vertex", "texel", "probe"); ValueError outside it.
prt::RowRange rowRange(py::handle range, std::size_t rows, const char* what = "vertex");

/// A prtkit.Transfer, or a numpy array of dense rows read in place (float32, C-contiguous,
/// shape (N, B²), (N, B², 3), (N, B², B²) or (N, B², B², 3); finite). `what` names it.
TransferPtr toTransfer(py::handle obj, const char* what = "transfer");
/// The dense transfer a numpy array holds, viewed in place (see toTransfer); the layout is
/// inferred from the shape unless given.
prt::Transfer transferFromArray(py::handle array, const std::optional<std::string>& layout,
                                std::size_t firstRow, bool checkFinite, const char* what);
/// The numpy shape of dense rows: (N, B²[, 3]) or (N, B², B²[, 3]).
Shape denseShape(const prt::TransferShape& shape);
/// The dense values of `t` as numpy, no copy: the base is a capsule owning the transfer.
/// Writable when `writable` and the storage is the transfer's own (call it only on a transfer
/// nothing else shares: a fresh bake, a file's rows once the file is gone); read-only when it
/// views other memory (a bake file's bytes).
py::array transferArray(prt::Transfer t, bool writable);

/// ValueError unless `t` is SH transfer: "the transfer is Haar ... : `use`" (transfer.cpp).
void requireShTransfer(const PyTransfer& t, const std::string& use);

/// True for a prtkit.HaarLight (haar.cpp).
bool isHaarLight(py::handle obj);
/// relight() of a Haar transfer (haar.cpp): under a HaarLight, a Haar light file or an
/// environment (its 200 largest terms over the transfer's cube), at the mesh's normals, with
/// `albedo` ((rows, 3), one colour, or None: the mesh's, else white); (rows, 3) radiance.
py::array relightHaar(const PyTransfer& t, py::handle light, py::handle albedo, py::handle rot,
                      const MeshPtr& mesh);

/// prtkit.Environment: distant light as a function of direction.
struct PyEnvironment {
  prt::envmap::Environment env;
  std::string layout;  ///< "latlong", ..., "faces", "builtin"
};
using EnvironmentPtr = std::shared_ptr<PyEnvironment>;
/// A prtkit.Environment, a path / builtin:NAME, or an (H, W, 3) linear float image.
EnvironmentPtr toEnvironment(py::handle obj, const std::optional<std::string>& layout = {});

/// A material: a spec string ("phong?exponent=32&ks=0.5", ValueError if bad) or None (→ `def`).
prt::Material material(py::handle spec, const prt::Material& def = {});

}  // namespace prtpy
