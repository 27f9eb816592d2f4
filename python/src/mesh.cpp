// prtkit.Mesh, load_mesh, and ray queries against a mesh (occluded, intersect): the same
// loaders and the same Embree BVH as `prt bake`.

#include <cmath>
#include <cstring>
#include <limits>
#include <span>

#include "common.hpp"
#include "objects.hpp"
#include "prt/core/limits.hpp"
#include "prt/core/parallel.hpp"
#include "prt/geometry/load.hpp"
#include "prt/geometry/normals.hpp"

namespace prtpy {

const prt::Occluder& PyMesh::occluder() const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!occluder_) occluder_ = prt::makeEmbreeOccluder(mesh_);
  return *occluder_;
}

namespace {

/// Keeps unit normals bit for bit, normalises the others, and replaces zero ones by the
/// angle-weighted normals of the faces around the vertex (as the loaders do).
void setNormals(prt::Mesh& mesh, const float* n) {
  const std::size_t count = mesh.vertexCount();
  mesh.normals.resize(count);
  bool zero = false;
  for (std::size_t v = 0; v < count; ++v) {
    prt::Vec3f x(n[3 * v], n[3 * v + 1], n[3 * v + 2]);
    const float len = length(x);
    if (!(len > 1e-20f)) {
      zero = true;
    } else if (std::abs(len - 1.0f) > 1e-6f) {
      x = x / len;
    }
    mesh.normals[v] = x;
  }
  if (!zero) return;
  prt::Mesh computed;
  computed.positions = mesh.positions;
  computed.triangles = mesh.triangles;
  prt::computeVertexNormals(computed);
  for (std::size_t v = 0; v < count; ++v)
    if (!(length(mesh.normals[v]) > 1e-20f)) mesh.normals[v] = computed.normals[v];
}

py::array meshArray(py::handle self, const void* data, const Shape& shape, py::dtype dtype) {
  return view(dtype, shape, data, self, false);
}

py::object meshUvs(py::handle self) {
  const prt::Mesh& m = self.cast<const PyMesh&>().mesh();
  if (m.uvs.empty()) return py::none();
  return meshArray(self, m.uvs.data(), {static_cast<py::ssize_t>(m.uvs.size()), 2},
                   py::dtype::of<float>());
}

py::object meshLightmapUvs(py::handle self) {
  const prt::Mesh& m = self.cast<const PyMesh&>().mesh();
  if (m.lightmapUvs.empty()) return py::none();
  return meshArray(self, m.lightmapUvs.data(), {static_cast<py::ssize_t>(m.lightmapUvs.size()), 2},
                   py::dtype::of<float>());
}

py::object meshAlbedo(py::handle self) {
  const prt::Mesh& m = self.cast<const PyMesh&>().mesh();
  if (m.albedo.empty()) return py::none();
  return meshArray(self, m.albedo.data(), {static_cast<py::ssize_t>(m.albedo.size()), 3},
                   py::dtype::of<float>());
}

py::object meshGloss(const PyMesh& pm) {
  const auto& g = pm.mesh().gloss;
  if (!g) return py::none();
  py::dict d;
  d["model"] = g->model == prt::SurfaceGloss::Model::Phong ? "phong" : "metallic-roughness";
  d["specular"] = py::make_tuple(g->specular.x, g->specular.y, g->specular.z);
  d["exponent"] = g->exponent;
  d["roughness"] = g->roughness;
  d["metallic"] = g->metallic;
  d["material"] = g->material;
  return d;
}

/// Rays from (M, 3) or (3,) origins and directions (one of them may be a single row).
struct RayBatch {
  py::array_t<float, py::array::c_style> origins, directions;
  std::size_t count = 0;
  bool originRows = true, directionRows = true;
  float tnear = 0, tfar = std::numeric_limits<float>::infinity();

  RayBatch(py::handle o, py::handle d, double near, double far) {
    const auto rows = [](py::handle h) {
      const py::array a = py::array::ensure(h);
      return a && a.ndim() == 1;
    };
    originRows = !rows(o);
    directionRows = !rows(d);
    origins = floats(o, "origins", originRows ? Shape{kAny, 3} : Shape{3});
    directions = floats(d, "directions", directionRows ? Shape{kAny, 3} : Shape{3});
    const std::size_t no = originRows ? static_cast<std::size_t>(origins.shape(0)) : 1;
    const std::size_t nd = directionRows ? static_cast<std::size_t>(directions.shape(0)) : 1;
    if (originRows && directionRows && no != nd)
      throw py::value_error("origins and directions differ in length (" + std::to_string(no) +
                            " and " + std::to_string(nd) + ")");
    count = originRows ? no : nd;
    if (!(near >= 0) || !(far > near))
      throw py::value_error("tnear and tfar must satisfy 0 <= tnear < tfar");
    tnear = static_cast<float>(near);
    tfar = static_cast<float>(far);
    // Embree aborts on coordinates past 1.8e18; refuse them here with a message.
    const auto check = [](const py::array_t<float, py::array::c_style>& a, const char* what) {
      const float* p = a.data();
      for (py::ssize_t i = 0; i < a.size(); ++i)
        if (std::abs(p[i]) > prt::kMaxTraceableCoordinate)
          throw py::value_error(std::string(what) + " has a coordinate beyond " +
                                std::to_string(prt::kMaxTraceableCoordinate) +
                                ", more than the ray tracer handles");
    };
    check(origins, "origins");
    check(directions, "directions");
    const float* dp = directions.data();
    for (py::ssize_t i = 0; i < directions.size() / 3; ++i)
      if (dp[3 * i] == 0 && dp[3 * i + 1] == 0 && dp[3 * i + 2] == 0)
        throw py::value_error("directions[" + std::to_string(i) + "] is zero");
  }
  prt::Ray ray(std::size_t k) const {
    const float* o = origins.data() + (originRows ? 3 * k : 0);
    const float* d = directions.data() + (directionRows ? 3 * k : 0);
    return prt::Ray{{o[0], o[1], o[2]}, {d[0], d[1], d[2]}, tnear, tfar};
  }
};

py::array occludedRays(const MeshPtr& mesh, py::handle origins, py::handle directions, double tnear,
                       double tfar) {
  const RayBatch rays(origins, directions, tnear, tfar);
  py::array_t<bool> out(static_cast<py::ssize_t>(rays.count));
  auto* hit = reinterpret_cast<std::uint8_t*>(out.mutable_data());
  {
    py::gil_scoped_release nogil;
    const prt::Occluder& occ = mesh->occluder();
    constexpr std::size_t kChunk = 4096;
    const std::size_t chunks = (rays.count + kChunk - 1) / kChunk;
    prt::parallelFor(chunks, 1, [&](std::size_t b, std::size_t e) {
      std::vector<prt::Ray> buf(kChunk);
      for (std::size_t c = b; c < e; ++c) {
        const std::size_t lo = c * kChunk, n = std::min(kChunk, rays.count - lo);
        for (std::size_t k = 0; k < n; ++k) buf[k] = rays.ray(lo + k);
        occ.occluded(std::span<const prt::Ray>(buf.data(), n),
                     std::span<std::uint8_t>(hit + lo, n));
      }
    });
  }
  return out;
}

py::dict intersectRays(const MeshPtr& mesh, py::handle origins, py::handle directions, double tnear,
                       double tfar) {
  const RayBatch rays(origins, directions, tnear, tfar);
  const auto n = static_cast<py::ssize_t>(rays.count);
  py::array_t<bool> hit(n);
  py::array_t<float> t(n), u(n), v(n);
  py::array_t<std::int64_t> tri(n);
  auto* ph = reinterpret_cast<std::uint8_t*>(hit.mutable_data());
  float *pt = t.mutable_data(), *pu = u.mutable_data(), *pv = v.mutable_data();
  std::int64_t* ptri = tri.mutable_data();
  {
    py::gil_scoped_release nogil;
    const prt::Occluder& occ = mesh->occluder();
    prt::parallelFor(rays.count, 1024, [&](std::size_t b, std::size_t e) {
      for (std::size_t k = b; k < e; ++k) {
        const prt::Hit h = occ.intersect(rays.ray(k));
        ph[k] = h.hit ? 1 : 0;
        pt[k] = h.hit ? h.t : std::numeric_limits<float>::infinity();
        ptri[k] = h.hit ? static_cast<std::int64_t>(h.triangle) : -1;
        pu[k] = h.hit ? h.u : 0.0f;
        pv[k] = h.hit ? h.v : 0.0f;
      }
    });
  }
  py::dict d;
  d["hit"] = hit;
  d["t"] = t;
  d["triangle"] = tri;
  d["u"] = u;
  d["v"] = v;
  return d;
}

const char* kOccludedDoc =
    R"(Occlusion of rays against the mesh, through its Embree BVH (the one bake uses).

origins, directions: (M, 3) arrays (either may be a single (3,) row, used for every ray),
any real dtype. Directions need not be unit: tnear and tfar are in units of their length.
Returns a bool array (M,): True where anything lies on the ray within (tnear, tfar).
The GIL is released and the rays are traced on all cores (in streams of 64).)";

const char* kIntersectDoc = R"(Closest hits of rays against the mesh.

Returns a dict of (M,) arrays: hit (bool), t (float32, inf where nothing is hit), triangle
(int64 index into faces, -1 where nothing is hit) and the barycentrics u, v of the hit
(p = (1-u-v) p0 + u p1 + v p2).)";

}  // namespace

MeshPtr meshFromArrays(py::handle vertices, py::handle faces, py::handle normals, py::handle uvs,
                       py::handle albedo) {
  const auto pos = floats(vertices, "vertices", {kAny, 3});
  const std::size_t n = static_cast<std::size_t>(pos.shape(0));
  if (n == 0) throw py::value_error("vertices is empty");
  if (n > std::min<std::uint64_t>(prt::limits().maxVertices, 0xffffffffull))
    throw py::value_error("vertices: " + std::to_string(n) + " vertices exceed the limit of " +
                          std::to_string(prt::limits().maxVertices) + " (PRT_MAX_VERTICES)");
  prt::Mesh mesh;
  mesh.source = "Mesh";
  mesh.positions.resize(n);
  std::memcpy(static_cast<void*>(mesh.positions.data()), pos.data(), n * sizeof(prt::Vec3f));
  mesh.triangles = triangles(faces, "faces", n);
  if (mesh.triangles.empty()) throw py::value_error("faces is empty");
  if (!normals.is_none()) {
    const auto nrm = floats(normals, "normals", {static_cast<py::ssize_t>(n), 3});
    setNormals(mesh, nrm.data());
  } else {
    prt::computeVertexNormals(mesh);
  }
  if (!uvs.is_none()) {
    const auto uv = floats(uvs, "uvs", {static_cast<py::ssize_t>(n), 2});
    mesh.uvs.resize(n);
    std::memcpy(static_cast<void*>(mesh.uvs.data()), uv.data(), n * sizeof(prt::Vec2f));
  }
  if (!albedo.is_none()) {
    const py::array a = py::array::ensure(albedo);
    if (a && a.ndim() == 2) {
      const auto al = floats(albedo, "albedo", {static_cast<py::ssize_t>(n), 3});
      mesh.albedo.resize(n);
      std::memcpy(static_cast<void*>(mesh.albedo.data()), al.data(), n * sizeof(prt::Rgb));
    } else {
      mesh.albedo.assign(n, rgb(albedo, "albedo"));
    }
    for (const prt::Rgb& c : mesh.albedo)
      if (c.x < 0 || c.y < 0 || c.z < 0) throw py::value_error("albedo must not be negative");
  }
  mesh.parts.push_back({"mesh", 0, static_cast<std::uint32_t>(n), 0,
                        static_cast<std::uint32_t>(mesh.triangles.size())});
  asValueError([&] {
    prt::checkMeshValues(mesh, "Mesh");
    return 0;
  });
  return std::make_shared<PyMesh>(std::move(mesh));
}

MeshPtr toMesh(py::handle obj) {
  if (py::isinstance<PyMesh>(obj)) return obj.cast<MeshPtr>();
  if (py::hasattr(obj, "vertices") &&
      (py::hasattr(obj, "faces") || py::hasattr(obj, "triangles"))) {
    const py::object np = py::module_::import("numpy");
    const py::object faces = py::hasattr(obj, "faces") ? obj.attr("faces") : obj.attr("triangles");
    py::object normals = py::none();
    if (py::hasattr(obj, "vertex_normals")) {
      py::array n = np.attr("asarray")(obj.attr("vertex_normals"));
      if (n.size() > 0) normals = n;
    }
    return meshFromArrays(np.attr("asarray")(obj.attr("vertices")), np.attr("asarray")(faces),
                          normals, py::none(), py::none());
  }
  throw py::type_error("mesh must be a prtkit.Mesh or have .vertices and .faces (got " +
                       py::str(py::type::of(obj)).cast<std::string>() + ")");
}

void bindMesh(py::module_& m) {
  py::class_<PyMesh, std::shared_ptr<PyMesh>>(
      m, "Mesh", R"(A triangle mesh: what bake, relight and render take.

Mesh(vertices, faces, normals=None, uvs=None, albedo=None) makes one from arrays: vertices
(N, 3) and faces (T, 3) integer indices, counter-clockwise = front; normals (N, 3) (unit
normals are kept bit for bit, others normalised, zero ones and missing ones computed as
angle-weighted vertex normals, as the file loaders do); uvs (N, 2); albedo (N, 3) linear RGB,
or one colour for all. Inputs are copied (any real dtype); NaN, infinity or an index out of
range is a ValueError. load_mesh reads files.

The arrays it exposes (vertices, normals, faces, uvs, albedo) are read-only views of the
C++ mesh, without copies. The Embree BVH is built on first use and kept with the mesh: bake
a prtkit.Mesh rather than, say, a trimesh object to build it once.)")
      .def(py::init(&meshFromArrays), py::arg("vertices"), py::arg("faces"),
           py::arg("normals") = py::none(), py::arg("uvs") = py::none(),
           py::arg("albedo") = py::none())
      .def_property_readonly(
          "vertices",
          [](py::object self) {
            const prt::Mesh& mm = self.cast<const PyMesh&>().mesh();
            return meshArray(self, mm.positions.data(),
                             {static_cast<py::ssize_t>(mm.vertexCount()), 3},
                             py::dtype::of<float>());
          },
          "(N, 3) float32 positions (read-only view).")
      .def_property_readonly(
          "normals",
          [](py::object self) {
            const prt::Mesh& mm = self.cast<const PyMesh&>().mesh();
            return meshArray(self, mm.normals.data(),
                             {static_cast<py::ssize_t>(mm.normals.size()), 3},
                             py::dtype::of<float>());
          },
          "(N, 3) float32 unit vertex normals (read-only view).")
      .def_property_readonly(
          "faces",
          [](py::object self) {
            const prt::Mesh& mm = self.cast<const PyMesh&>().mesh();
            return meshArray(self, mm.triangles.data(),
                             {static_cast<py::ssize_t>(mm.triangleCount()), 3},
                             py::dtype::of<std::uint32_t>());
          },
          "(T, 3) uint32 vertex indices per triangle (read-only view).")
      .def_property_readonly("uvs", &meshUvs, "(N, 2) float32 texture coordinates, or None.")
      .def_property_readonly("lightmap_uvs", &meshLightmapUvs,
                             "(N, 2) float32 lightmap coordinates (glTF TEXCOORD_1; the builtin "
                             "plane's and Cornell box's packed charts), or None.")
      .def_property_readonly("albedo", &meshAlbedo,
                             "(N, 3) float32 linear albedo per vertex, or None (uniform white).")
      .def_property_readonly("vertex_count",
                             [](const PyMesh& pm) { return pm.mesh().vertexCount(); })
      .def_property_readonly("triangle_count",
                             [](const PyMesh& pm) { return pm.mesh().triangleCount(); })
      .def_property_readonly(
          "source", [](const PyMesh& pm) { return pm.mesh().source; },
          "The file (or builtin:NAME) it came from; 'Mesh' for arrays.")
      .def_property_readonly(
          "parts",
          [](const PyMesh& pm) {
            py::list out;
            for (const prt::MeshPart& p : pm.mesh().parts) {
              py::dict d;
              d["name"] = p.name;
              d["first_vertex"] = p.firstVertex;
              d["vertex_count"] = p.vertexCount;
              d["first_triangle"] = p.firstTriangle;
              d["triangle_count"] = p.triangleCount;
              out.append(d);
            }
            return out;
          },
          "The objects of a scene: a list of dicts (name, vertex and triangle ranges).")
      .def_property_readonly("gloss", &meshGloss,
                             "The file's glossy surface (MTL Ks/Ns, glTF metallic-roughness) as "
                             "a dict, or None: the material bake uses when given none.")
      .def("occluded", &occludedRays, py::arg("origins"), py::arg("directions"),
           py::arg("tnear") = 0.0, py::arg("tfar") = std::numeric_limits<double>::infinity(),
           kOccludedDoc)
      .def("intersect", &intersectRays, py::arg("origins"), py::arg("directions"),
           py::arg("tnear") = 0.0, py::arg("tfar") = std::numeric_limits<double>::infinity(),
           kIntersectDoc)
      .def("__repr__", [](const PyMesh& pm) {
        const prt::Mesh& mm = pm.mesh();
        return "<prtkit.Mesh " + mm.source + ": " + std::to_string(mm.vertexCount()) +
               " vertices, " + std::to_string(mm.triangleCount()) + " triangles>";
      });

  m.def(
      "load_mesh",
      [](py::object paths) {
        std::vector<std::string> inputs;
        if (py::isinstance<py::str>(paths) || py::hasattr(paths, "__fspath__"))
          inputs.push_back(py::str(py::module_::import("os").attr("fspath")(paths)));
        else
          for (py::handle p : paths)
            inputs.push_back(py::str(py::module_::import("os").attr("fspath")(p)));
        prt::LoadReport report;
        prt::Mesh mesh;
        {
          py::gil_scoped_release nogil;
          mesh = prt::loadScene(inputs, &report);
          // The module shades per vertex (and per texel): a base-colour texture is folded
          // into the vertices' albedo (geometry/mesh.hpp), as every per-vertex consumer sees it.
          prt::foldBaseColour(mesh);
        }
        for (const std::string& w : report.warnings) warn(w);
        return std::make_shared<PyMesh>(std::move(mesh));
      },
      py::arg("path"),
      R"(Loads a mesh: OBJ (with its MTL), PLY, OFF, glTF/GLB, optionally .gz, or builtin:NAME
(sphere, sphere-plane, plane, cornell, with parameters: 'builtin:sphere?subdiv=3').

A list of paths is merged into one scene (the objects shadow each other), as `prt bake a b`
does. The vertex order is the loader's (for OBJ, the GAMES202 course's). What the loader
repaired is issued as warnings; a file it cannot read raises prtkit.Error.)");

  m.def("as_mesh", &toMesh, py::arg("mesh"),
        "A prtkit.Mesh from a prtkit.Mesh (returned as is) or any object with .vertices and "
        ".faces (trimesh) or .triangles (Open3D), and .vertex_normals when it has them.");
  m.def(
      "occluded",
      [](py::handle mesh, py::handle origins, py::handle directions, double tnear, double tfar) {
        return occludedRays(toMesh(mesh), origins, directions, tnear, tfar);
      },
      py::arg("mesh"), py::arg("origins"), py::arg("directions"), py::arg("tnear") = 0.0,
      py::arg("tfar") = std::numeric_limits<double>::infinity(), kOccludedDoc);
  m.def(
      "intersect",
      [](py::handle mesh, py::handle origins, py::handle directions, double tnear, double tfar) {
        return intersectRays(toMesh(mesh), origins, directions, tnear, tfar);
      },
      py::arg("mesh"), py::arg("origins"), py::arg("directions"), py::arg("tnear") = 0.0,
      py::arg("tfar") = std::numeric_limits<double>::infinity(), kIntersectDoc);
}

}  // namespace prtpy
