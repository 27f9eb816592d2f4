// All-frequency lighting and relighting (issue 33; docs/haar.md): prtkit.HaarLight,
// project_haar, read_haar_light, and relight() of a Haar bake — what `prt light --basis haar`
// and `prt render` of a Haar bake do, from Python.

#include <array>
#include <cstring>
#include <vector>

#include "common.hpp"
#include "objects.hpp"
#include "prt/haar/cube_haar.hpp"
#include "prt/haar/project_light.hpp"
#include "prt/haar/resolution.hpp"
#include "prt/io/haar_light_file.hpp"
#include "prt/relight/relight_haar.hpp"
#include "prt/render/texel_points.hpp"
#include "prt/transfer/haar_rows.hpp"

namespace prtpy {

namespace {

/// prtkit.HaarLight: a Haar light file's content (the K terms, the unshadowed part, where it
/// came from).
struct PyHaarLight {
  prt::io::HaarLightFile file;
};
using HaarLightPtr = std::shared_ptr<PyHaarLight>;

HaarLightPtr project(py::handle source, int resolution, std::size_t terms, py::handle rot,
                     const std::string& selection, std::optional<std::string> layout) {
  asValueError([&] {
    prt::haar::checkResolution(resolution, "resolution");
    return 0;
  });
  if (terms < 1 || terms > prt::haar::coefficientCount(resolution))
    throw py::value_error("terms must be 1.." +
                          std::to_string(prt::haar::coefficientCount(resolution)) +
                          " (6 N² coefficients of an N = " + std::to_string(resolution) +
                          " cube), got " + std::to_string(terms));
  const prt::haar::Selection sel =
      asValueError([&] { return prt::haar::parseSelection(selection); });
  const EnvironmentPtr env = toEnvironment(source, layout);
  const prt::Mat3d r = rotation(rot);
  auto out = std::make_shared<PyHaarLight>();
  {
    py::gil_scoped_release nogil;
    out->file.light = prt::haar::projectLight(env->env, resolution, terms, r, sel);
  }
  out->file.selection = prt::haar::toString(sel);
  out->file.source = env->env.source();
  out->file.layout = env->layout;
  // Euler degrees when given so (the file's `rotation`); a matrix is kept in the terms only.
  if (!rot.is_none()) {
    try {
      out->file.rotationDeg = rot.cast<std::array<double, 3>>();
    } catch (const py::cast_error&) {
    }
  }
  return out;
}

py::array termIndices(const prt::haar::HaarLight& l) {
  py::array_t<std::uint32_t> a(static_cast<py::ssize_t>(l.index.size()));
  if (!l.index.empty())
    std::memcpy(a.mutable_data(), l.index.data(), l.index.size() * sizeof(std::uint32_t));
  return a;
}

py::array termValues(const prt::haar::HaarLight& l) {
  py::array_t<float> a({static_cast<py::ssize_t>(l.value.size()), py::ssize_t(3)});
  if (!l.value.empty())
    std::memcpy(a.mutable_data(), l.value.data(), l.value.size() * sizeof(prt::Rgb));
  return a;
}

}  // namespace

bool isHaarLight(py::handle obj) {
  return py::isinstance<PyHaarLight>(obj);
}

py::array relightHaar(const PyTransfer& t, py::handle lightObj, py::handle albedo, py::handle rot,
                      const std::shared_ptr<PyMesh>& mesh) {
  const prt::Transfer& tr = t.transfer;
  if (!tr.isHaar())
    throw py::value_error(
        "a HaarLight relights Haar transfer (bake --basis haar); this transfer is SH: give it SH "
        "light (project_environment, or an environment path)");
  if (!rot.is_none())
    throw py::value_error(
        "a Haar light is rotated by projecting it again: project_haar(..., rotation=R)");
  if (!mesh)
    throw py::value_error(
        "relighting Haar transfer needs mesh= (each row's normal: a row that stores its "
        "occluded part adds the unshadowed light at that normal)");
  const int n = tr.shape().haar.resolution;
  HaarLightPtr light;
  if (isHaarLight(lightObj)) {
    light = lightObj.cast<HaarLightPtr>();
  } else if (isPath(lightObj) && prt::io::isHaarLightFile(pathString(lightObj))) {
    light = std::make_shared<PyHaarLight>();
    const std::string path = pathString(lightObj);
    light->file = asValueError([&] { return prt::io::readHaarLightJson(path); });
  } else if (py::isinstance<py::array>(lightObj) &&
             py::array(lightObj.cast<py::array>()).ndim() == 2) {
    throw py::value_error(
        "the light is SH ((B², 3)) and the transfer Haar: give a prtkit.HaarLight "
        "(project_haar), a Haar light file or an environment");
  } else {
    // An environment: its largest terms over the transfer's cube (prt render's default count).
    light = project(lightObj, n,
                    std::min(prt::haar::kDefaultLightTerms, prt::haar::coefficientCount(n)),
                    py::none(), "area", std::nullopt);
  }
  const prt::Mesh& mm = mesh->mesh();
  const std::size_t first = tr.rows().first, rows = tr.rowCount();
  std::vector<prt::Rgb> albedoStore;
  std::span<const prt::Rgb> kd;
  std::span<const prt::Vec3f> normals;
  prt::render::TexelRelight texels;
  if (tr.domain() == prt::TransferDomain::Texels) {
    // Per texel: relit white (render(mesh, radiance.reshape(h, w, 3)) multiplies the albedo per
    // pixel) at each texel's normal, as prt render relights it (render::texelRelight).
    if (first != 0 || rows != tr.shape().lightmap.texels())
      throw py::value_error(
          "relighting per-texel Haar transfer needs every texel (a complete "
          "bake)");
    texels = asValueError(
        [&] { return prt::render::texelRelight(mm, mesh->occluder(), tr, prt::Material{}); });
    normals = texels.points.normals;
  } else {
    if (mm.vertexCount() < first + rows)
      throw py::value_error("mesh has " + std::to_string(mm.vertexCount()) +
                            " vertices; the transfer's rows are vertices " + std::to_string(first) +
                            ".." + std::to_string(first + rows - 1));
    normals = std::span<const prt::Vec3f>(mm.normals).subspan(first, rows);
    if (!mm.albedo.empty()) kd = std::span<const prt::Rgb>(mm.albedo).subspan(first, rows);
  }
  if (!albedo.is_none()) {
    albedoStore = albedoOf(albedo, rows);
    kd = albedoStore;
  }
  std::vector<prt::Rgb> out(rows);
  asValueError([&] {
    py::gil_scoped_release nogil;
    prt::relight::relightHaar(tr, light->file.light, normals, kd, out);
    return 0;
  });
  return adoptVector(std::move(out), {static_cast<py::ssize_t>(rows), 3});
}

void bindHaar(py::module_& m) {
  py::class_<PyHaarLight, HaarLightPtr>(
      m, "HaarLight",
      R"(All-frequency light (docs/haar.md): an environment's K largest area-weighted Haar
wavelet terms over an N² cube map, with its unshadowed part (the brightest texels exactly, the
rest in 5-band SH) — what `prt light --basis haar` writes. Made by project_haar or
read_haar_light; relights a Haar bake with relight(transfer, light, mesh=...).)")
      .def_property_readonly("resolution",
                             [](const PyHaarLight& l) { return l.file.light.resolution; })
      .def_property_readonly(
          "terms", [](const PyHaarLight& l) { return l.file.light.terms(); },
          "K, the wavelet terms kept.")
      .def_property_readonly(
          "energy_kept", [](const PyHaarLight& l) { return l.file.light.energyKept; },
          "Σ|c|² of the kept terms over that of all 6 N² (RGB summed).")
      .def_property_readonly(
          "indices", [](const PyHaarLight& l) { return termIndices(l.file.light); },
          "(K,) uint32: the kept coefficients (face·N² + y·N + x of the pyramid), ascending.")
      .def_property_readonly(
          "values", [](const PyHaarLight& l) { return termValues(l.file.light); },
          "(K, 3) float32: their RGB values.")
      .def_property_readonly("selection", [](const PyHaarLight& l) { return l.file.selection; })
      .def_property_readonly("source", [](const PyHaarLight& l) { return l.file.source; })
      .def(
          "write",
          [](const PyHaarLight& l, py::handle path) {
            const std::string p = pathString(path);
            asValueError([&] {
              py::gil_scoped_release nogil;
              prt::io::writeHaarLightJson(p, l.file);
              return 0;
            });
          },
          py::arg("path"), "Writes the light as `prt light --basis haar` does (a .json file).")
      .def("__repr__", [](const PyHaarLight& l) {
        return "<prtkit.HaarLight " + std::to_string(l.file.light.terms()) + " terms of a " +
               std::to_string(l.file.light.resolution) + "² cube" +
               (l.file.source.empty() ? "" : ", " + l.file.source) + ">";
      });

  m.def("project_haar", &project, py::arg("source"), py::arg("resolution") = 32,
        py::arg("terms") = prt::haar::kDefaultLightTerms, py::arg("rotation") = py::none(),
        py::arg("selection") = "area", py::arg("layout") = py::none(),
        "An environment's all-frequency light, as `prt light ENV --basis haar --resolution N "
        "--terms K` makes it: the K largest wavelet terms of its N² cube map (selection 'area': "
        "area-weighted, Ng et al. 2003; 'magnitude'), rotated by resampling the environment "
        "(rotation: a 3x3 matrix or Euler degrees X, Y, Z). source: a path, builtin:NAME, a "
        "prtkit.Environment or an (H, W, 3) image.");
  m.def(
      "read_haar_light",
      [](py::handle path) {
        auto l = std::make_shared<PyHaarLight>();
        const std::string p = pathString(path);
        l->file = asValueError([&] { return prt::io::readHaarLightJson(p); });
        return l;
      },
      py::arg("path"), "A Haar light file (`prt light --basis haar`) as a prtkit.HaarLight.");
}

}  // namespace prtpy
