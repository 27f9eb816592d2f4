// Environments and SH lighting: prtkit.Environment, load_environment, project_environment,
// and the operations on SH light (rotation, windows, zonal convolution, irradiance).

#include <cmath>
#include <cstring>
#include <filesystem>

#include "common.hpp"
#include "objects.hpp"
#include "prt/core/band_limits.hpp"
#include "prt/core/options.hpp"
#include "prt/core/parallel.hpp"
#include "prt/envmap/load.hpp"
#include "prt/envmap/project.hpp"
#include "prt/image/image_io.hpp"
#include "prt/sh/convolve.hpp"
#include "prt/sh/rotate.hpp"

namespace prtpy {

namespace {

prt::image::Image imageFrom(const float* p, py::ssize_t h, py::ssize_t w) {
  prt::image::Image img(static_cast<int>(w), static_cast<int>(h));
  std::memcpy(static_cast<void*>(img.pixels.data()), p, img.pixels.size() * sizeof(prt::Rgb));
  return img;
}

/// The policy of the image readers (negative radiance clamped to 0), said as a warning.
void clampNegative(prt::image::Image& img, const char* what) {
  const prt::image::ReadStats s = prt::image::sanitize(img);
  if (s.negativePixels)
    warn(std::string(what) + ": " + std::to_string(s.negativePixels) +
         " pixels with negative values clamped to 0");
}

EnvironmentPtr environmentFromArray(py::handle obj, const std::optional<std::string>& layout) {
  const py::array any = py::array::ensure(obj);
  auto out = std::make_shared<PyEnvironment>();
  std::optional<prt::envmap::Layout> given;
  if (layout) given = asValueError([&] { return prt::envmap::parseLayout(*layout); });
  if (any && any.ndim() == 4) {
    const auto a = floats(obj, "environment", {6, kAny, kAny, 3});
    const py::ssize_t n = a.shape(1);
    if (a.shape(2) != n || n == 0)
      throw py::value_error("environment: cube faces must be square, non-empty");
    if (given && *given != prt::envmap::Layout::Faces)
      throw py::value_error("environment: a (6, N, N, 3) array holds cube faces, not " + *layout);
    std::array<prt::image::Image, 6> faces;
    for (int f = 0; f < 6; ++f) {
      faces[f] = imageFrom(a.data() + f * n * n * 3, n, n);
      clampNegative(faces[f], "environment");
    }
    out->env = prt::envmap::Environment::cube(std::move(faces));
    out->layout = "faces";
  } else {
    const auto a = floats(obj, "environment", {kAny, kAny, 3});
    if (a.shape(0) == 0 || a.shape(1) == 0) throw py::value_error("environment is empty");
    if (a.shape(0) > prt::image::kMaxImageSide || a.shape(1) > prt::image::kMaxImageSide)
      throw py::value_error("environment: sides must be at most " +
                            std::to_string(prt::image::kMaxImageSide));
    prt::image::Image img = imageFrom(a.data(), a.shape(0), a.shape(1));
    clampNegative(img, "environment");
    prt::envmap::Layout used;
    out->env = asValueError([&] {
      return prt::envmap::environmentFromImage(std::move(img), given, "environment", &used);
    });
    out->layout = prt::envmap::layoutName(used);
  }
  out->env.setSource("array");
  return out;
}

const char* kSourceDoc =
    "source: a file (.hdr, .exr, .png, .jpg: lat-long 2:1, light probe 1:1, crosses 3:4 and "
    "4:3), a folder of six cube faces (posx ... negz), builtin:sky|studio|constant (with "
    "parameters), an (H, W, 3) linear float array (the layout detected from its aspect ratio "
    "unless given), a (6, N, N, 3) array of cube faces (+X -X +Y -Y +Z -Z), or an Environment.";

py::array directionsOut(const std::vector<prt::Rgb>& v) {
  return adoptVector(v, {static_cast<py::ssize_t>(v.size()), 3});
}

py::array project(py::handle source, int bands, const std::optional<std::string>& layout,
                  const std::optional<std::string>& compat, py::handle progress) {
  asValueError([&] {
    prt::checkOptionRange(prt::OptionSpelling::Python, "bands", bands, 1, prt::bands::kMaxLibrary);
    return 0;
  });
  if (compat) {
    if (*compat != "games202")
      throw py::value_error("compat accepts only 'games202', got '" + *compat + "'");
    if (!isPath(source)) throw py::value_error("compat='games202' reads a folder of six faces");
    const std::string dir = pathString(source);
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec))
      throw prt::Error(dir, "compat='games202' needs a folder of six cube faces (posx.jpg ...)");
    std::array<prt::image::Image, 6> faces;
    {
      py::gil_scoped_release nogil;
      faces = prt::envmap::readFaceFolder(dir, prt::envmap::kGames202FaceOrder,
                                          prt::image::LdrDecode::Gamma22);
    }
    return lightArray(runLong("projecting", progress, [&](const prt::ProgressFn& fn) {
      return prt::envmap::projectGames202Faces(faces, bands, fn);
    }));
  }
  const EnvironmentPtr env = toEnvironment(source, layout);
  return lightArray(runLong("projecting", progress, [&](const prt::ProgressFn& fn) {
    return prt::envmap::projectEnvironment(env->env, bands, fn);
  }));
}

}  // namespace

EnvironmentPtr toEnvironment(py::handle obj, const std::optional<std::string>& layout) {
  if (py::isinstance<PyEnvironment>(obj)) return obj.cast<EnvironmentPtr>();
  if (!isPath(obj)) return environmentFromArray(obj, layout);
  const std::string path = pathString(obj);
  prt::envmap::LoadOptions options;
  if (layout) options.layout = asValueError([&] { return prt::envmap::parseLayout(*layout); });
  prt::envmap::LoadedEnvironment loaded;
  {
    py::gil_scoped_release nogil;
    loaded = prt::envmap::loadEnvironment(path, options);
  }
  for (const std::string& w : prt::envmap::repairWarnings(loaded)) warn(w);
  auto out = std::make_shared<PyEnvironment>();
  out->env = std::move(loaded.env);
  out->layout = loaded.layout;
  return out;
}

void bindLight(py::module_& m) {
  py::class_<PyEnvironment, EnvironmentPtr>(
      m, "Environment",
      R"(Distant light as a function of direction: an image (lat-long, probe, cross, cube faces) or
an analytic sky. load_environment makes one; project_environment, reference, validate and
render take one (or anything load_environment takes).)")
      .def_property_readonly("layout", [](const PyEnvironment& e) { return e.layout; })
      .def_property_readonly("source", [](const PyEnvironment& e) { return e.env.source(); })
      .def_property_readonly("texel_count",
                             [](const PyEnvironment& e) { return e.env.texelCount(); })
      .def_property_readonly(
          "images",
          [](py::object self) {
            const PyEnvironment& e = self.cast<const PyEnvironment&>();
            py::list out;
            for (const prt::image::Image& img : e.env.images())
              out.append(view(py::dtype::of<float>(), {img.height, img.width, 3}, img.pixels.data(),
                              self, false));
            return out;
          },
          "The images as (H, W, 3) float32 read-only views: one, or six cube faces (+X -X +Y -Y "
          "+Z -Z); for an analytic sky its lat-long texels.")
      .def(
          "lookup",
          [](const PyEnvironment& e, py::handle directions) {
            const auto d = floats(directions, "directions", {kAny, 3});
            const std::size_t n = static_cast<std::size_t>(d.shape(0));
            for (std::size_t k = 0; k < n; ++k)
              if (d.data()[3 * k] == 0 && d.data()[3 * k + 1] == 0 && d.data()[3 * k + 2] == 0)
                throw py::value_error("directions[" + std::to_string(k) + "] is zero");
            std::vector<prt::Rgb> out(n);
            {
              py::gil_scoped_release nogil;
              const float* p = d.data();
              prt::parallelFor(n, 4096, [&](std::size_t b, std::size_t en) {
                for (std::size_t k = b; k < en; ++k)
                  out[k] =
                      e.env.lookup(normalize(prt::Vec3f(p[3 * k], p[3 * k + 1], p[3 * k + 2])));
              });
            }
            return directionsOut(out);
          },
          py::arg("directions"), "Radiance (M, 3) seen along (M, 3) directions (bilinear).")
      .def(
          "project",
          [](py::object self, int bands, py::object progress) {
            return project(self, bands, std::nullopt, std::nullopt, progress);
          },
          py::arg("bands"), py::arg("progress") = py::none(),
          "project_environment(self, bands): its SH lighting, (B², 3).")
      .def("__repr__", [](const PyEnvironment& e) {
        return "<prtkit.Environment " + (e.env.source().empty() ? "" : e.env.source() + ": ") +
               e.layout + ", " + std::to_string(e.env.texelCount()) + " texels>";
      });

  m.def(
      "load_environment",
      [](py::object source, std::optional<std::string> layout) {
        return toEnvironment(source, layout);
      },
      py::arg("source"), py::arg("layout") = py::none(),
      (std::string("Loads an environment (prtkit.Environment).\n\n") + kSourceDoc +
       "\nlayout: latlong | probe | vcross | hcross | faces (default: detected). Pixels that "
       "are NaN or infinite in a file are set to 0 and negative ones clamped, with a warning; "
       "in an array NaN is a ValueError.")
          .c_str());

  m.def(
      "project_environment", &project, py::arg("source"), py::arg("bands"),
      py::arg("layout") = py::none(), py::arg("compat") = py::none(),
      py::arg("progress") = py::none(),
      (std::string(
           "SH lighting of an environment: a (B², 3) float32 array, L_i = Σ_texels L Y_i ΔΩ with\n"
           "exact texel solid angles, as `prt light` computes it (bit-identical).\n\n") +
       kSourceDoc +
       "\nbands: B, 1..32. compat='games202': a folder of the course's cube faces read and "
       "projected as the course framework does (`prt light --compat games202`).")
          .c_str());

  m.def(
      "rotation_matrix",
      [](double x, double y, double z) {
        const prt::Mat3d r = prt::rotationEulerXYZ(x, y, z);
        py::array_t<double> out({3, 3});
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) out.mutable_at(i, j) = r.m[i][j];
        return out;
      },
      py::arg("x"), py::arg("y"), py::arg("z"),
      "The rotation R = Rz Ry Rx from Euler angles in degrees (`--rotate X,Y,Z`), a (3, 3) array.");

  m.def(
      "rotate_light",
      [](py::handle light, py::handle rot) {
        const prt::sh::RgbSh l = prtpy::light(light);
        const prt::Mat3d r = rotation(rot);
        return lightArray(prt::sh::Rotation(l.bands, r).apply(l));
      },
      py::arg("light"), py::arg("rotation"),
      "SH lighting (B², 3) rotated by R (a 3x3 matrix or Euler degrees X, Y, Z): a lobe along d "
      "moves to R d. Exact per band (no re-projection).");

  m.def(
      "window_light",
      [](py::handle light, const std::string& window, std::optional<double> width) {
        prt::sh::RgbSh l = prtpy::light(light);
        const double w = width.value_or(0.0);
        if (width && !(w > 0)) throw py::value_error("width must be positive");
        asValueError(
            [&] { return prt::sh::applyWindow(l, prt::sh::parseWindow(window), w).minAfter; });
        return lightArray(l);
      },
      py::arg("light"), py::arg("window") = "hanning", py::arg("width") = py::none(),
      "SH lighting windowed against ringing, as `prt light --window`: hanning or lanczos "
      "(width W, default the band count) or dering (the least-smoothing Hanning window whose "
      "reconstruction is non-negative).");

  m.def(
      "convolve_light",
      [](py::handle light, py::handle kernel) {
        prt::sh::RgbSh l = prtpy::light(light);
        const auto k = doubles(kernel, "kernel", {l.bands});
        prt::sh::convolveZonal(
            l, std::span<const double>(k.data(), static_cast<std::size_t>(l.bands)));
        return lightArray(l);
      },
      py::arg("light"), py::arg("kernel"),
      "Zonal convolution: band l of the light (B², 3) multiplied by kernel[l] (B values; e.g. "
      "clamped_cosine_kernel(B) for irradiance).");

  m.def(
      "irradiance",
      [](py::handle light) { return lightArray(prt::sh::irradiance(prtpy::light(light))); },
      py::arg("light"),
      "Irradiance SH E_lm = Λ_l L_lm of radiance SH (B², 3) (Ramamoorthi & Hanrahan 2001).");

  m.def(
      "clamped_cosine_kernel",
      [](int bands) {
        if (bands < 1 || bands > prt::sh::kMaxBands)
          throw py::value_error("bands must be 1.." + std::to_string(prt::sh::kMaxBands));
        return py::array(py::cast(prt::sh::clampedCosineKernel(bands)));
      },
      py::arg("bands"), "Λ_l of the clamped cosine, l = 0..B-1 (π, 2π/3, π/4, 0, ...).");

  m.def(
      "sh_eval",
      [](int bands, py::handle directions) {
        if (bands < 1 || bands > prt::sh::kMaxBands)
          throw py::value_error("bands must be 1.." + std::to_string(prt::sh::kMaxBands));
        const auto d = floats(directions, "directions", {kAny, 3});
        const std::size_t n = static_cast<std::size_t>(d.shape(0));
        const float* p = d.data();
        for (std::size_t k = 0; k < n; ++k) {
          const float len2 =
              p[3 * k] * p[3 * k] + p[3 * k + 1] * p[3 * k + 1] + p[3 * k + 2] * p[3 * k + 2];
          if (std::abs(len2 - 1.0f) > 1e-4f)
            throw py::value_error("directions[" + std::to_string(k) + "] is not unit length");
        }
        std::vector<float> out(n * static_cast<std::size_t>(bands * bands));
        {
          py::gil_scoped_release nogil;
          prt::sh::evalBatch(bands,
                             std::span<const prt::Vec3f>(reinterpret_cast<const prt::Vec3f*>(p), n),
                             out.data());
        }
        return adoptVector(std::move(out), {static_cast<py::ssize_t>(n), bands * bands});
      },
      py::arg("bands"), py::arg("directions"),
      "The real SH basis Y_i (Condon-Shortley phase, index l(l+1)+m) at (M, 3) unit directions: "
      "an (M, B²) float32 array.");
}

}  // namespace prtpy
