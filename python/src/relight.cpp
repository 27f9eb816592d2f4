// Relighting and images: relight (every layout and representation, through the library's one
// entry point), Camera, render, and the Monte Carlo reference and validation.

#include <algorithm>
#include <cstring>

#include "common.hpp"
#include "objects.hpp"
#include "prt/envmap/project.hpp"
#include "prt/io/lighting.hpp"
#include "prt/relight/relight.hpp"
#include "prt/image/image_io.hpp"
#include "prt/render/camera.hpp"
#include "prt/render/exposure.hpp"
#include "prt/render/primary.hpp"
#include "prt/render/reference.hpp"
#include "prt/render/render.hpp"
#include "prt/render/texel_points.hpp"
#include "prt/render/validate.hpp"
#include "prt/sh/irradiance_encoding.hpp"

namespace prtpy {

namespace {

py::array rgbArray(std::vector<prt::Rgb> v) {
  const auto n = static_cast<py::ssize_t>(v.size());
  return adoptVector(std::move(v), {n, 3});
}

py::array relightFn(py::handle transferObj, py::handle lightObj, py::handle albedo, py::handle rot,
                    py::handle meshObj, py::handle eyeObj, py::handle spec) {
  const TransferPtr t = toTransfer(transferObj);
  const prt::Transfer& tr = t->transfer;
  const MeshPtr mesh = meshObj.is_none() ? nullptr : toMesh(meshObj);
  if (tr.isHaar() || isHaarLight(lightObj)) {
    if (!eyeObj.is_none() || !spec.is_none())
      throw py::value_error("Haar transfer is diffuse: relight it without eye= or material=");
    return relightHaar(*t, lightObj, albedo, rot, mesh);
  }
  if (tr.domain() == prt::TransferDomain::Probes)
    throw py::value_error(
        "the transfer is a probe grid (the light arriving at points in space): relight it with "
        "relight_probes, or shade an object in it with shade_probes");
  prt::sh::RgbSh light;
  if (isPath(lightObj)) {
    // An environment projected to the transfer's bands, or a light file: prt render's rules.
    const std::string path = pathString(lightObj);
    prt::io::Lighting lighting;
    {
      py::gil_scoped_release nogil;
      lighting = prt::io::loadLighting(path, tr.bands());
    }
    for (const std::string& w : lighting.warnings) warn(w);
    light = std::move(lighting.coefficients);
  } else {
    light = prtpy::light(lightObj);
  }
  const prt::Mat3d r = rotation(rot);
  const prt::Material mat = material(spec, t->recipe ? t->recipe->material : prt::Material{});
  if (mat.glossy() && !tr.isMatrix())
    warn(
        "the transfer is a vector (diffuse only): the material's glossy lobe needs a matrix "
        "bake (bake(..., transfer='matrix'))");

  const std::size_t first = tr.rows().first, rows = tr.rowCount();
  prt::relight::Surface surface;
  std::vector<prt::Rgb> albedoStore;
  const bool texels = tr.domain() == prt::TransferDomain::Texels;
  if (mesh && texels && !tr.isMatrix())
    throw py::value_error(
        "the transfer is per texel: relight it without mesh= (white, one radiance per texel) "
        "and render it as a lightmap (render(mesh, radiance.reshape(h, w, 3)) multiplies the "
        "albedo per pixel)");
  // Per-texel matrices: relit at the texels' sample points with their albedo (render::
  // texelRelight, as prt render does), so the lightmap is shown without the albedo again.
  prt::render::TexelRelight texelPoints;
  if (mesh && texels) {
    if (tr.rows().first != 0 || tr.rowCount() != tr.shape().lightmap.texels())
      throw py::value_error("relighting per-texel matrices needs every texel (a complete bake)");
    texelPoints = asValueError([&] {
      return prt::render::texelRelight(mesh->mesh(), mesh->occluder(), tr, prt::Material{});
    });
    surface = texelPoints.surface();
  } else if (mesh) {
    const prt::Mesh& mm = mesh->mesh();
    if (mm.vertexCount() < first + rows)
      throw py::value_error("mesh has " + std::to_string(mm.vertexCount()) +
                            " vertices; the transfer's rows are vertices " + std::to_string(first) +
                            ".." + std::to_string(first + rows - 1));
    surface.positions = std::span<const prt::Vec3f>(mm.positions).subspan(first, rows);
    surface.normals = std::span<const prt::Vec3f>(mm.normals).subspan(first, rows);
    if (!mm.albedo.empty())
      surface.albedo = std::span<const prt::Rgb>(mm.albedo).subspan(first, rows);
  }
  if (!albedo.is_none()) {
    albedoStore = albedoOf(albedo, rows);
    surface.albedo = albedoStore;
  }
  prt::Vec3f eye(0.0f);
  if (tr.isMatrix()) {
    if (!mesh)
      throw py::value_error(
          "relighting matrices (glossy transfer) needs mesh= (the rows' positions and normals)");
    if (eyeObj.is_none())
      throw py::value_error(
          "relighting matrices (glossy transfer) needs eye= (where it is seen from)");
  }
  if (!eyeObj.is_none()) eye = vec3(eyeObj, "eye");
  std::vector<prt::Rgb> out(rows);
  prt::relight::RelightInfo info;
  {
    py::gil_scoped_release nogil;
    info = prt::relight::relight(tr, light, mat, surface, eye, out, r);
  }
  if (!info.warning().empty()) warn(info.warning());
  return rgbArray(std::move(out));
}

prt::render::Camera cameraOf(py::handle obj, const prt::Mesh& mesh, int w, int h) {
  const prt::render::Camera framed = prt::render::frameMesh(mesh, w, h);
  if (obj.is_none()) return framed;
  const prt::render::Camera c =
      py::isinstance<py::str>(obj)
          ? asValueError([&] { return prt::render::parseCamera(obj.cast<std::string>(), framed); })
          : obj.cast<prt::render::Camera>();
  // A camera with no frame would trace NaN rays.
  const prt::Vec3f forward = c.target - c.eye;
  if (!(length(forward) > 0) ||
      !(length(cross(forward, c.up)) > 1e-6f * length(forward) * length(c.up)))
    throw py::value_error(
        "camera: the eye must differ from the target, and up must not be parallel "
        "to the view direction");
  if (!(c.fovY > 0 && c.fovY < 180))
    throw py::value_error("camera: fov must be in (0, 180) degrees");
  return c;
}

prt::render::MisHeuristic heuristicOf(const std::string& s) {
  if (s == "power") return prt::render::MisHeuristic::Power;
  if (s == "balance") return prt::render::MisHeuristic::Balance;
  throw py::value_error("heuristic must be power or balance, got '" + s + "'");
}

// Radiance given to render / auto_exposure: (V, 3) per vertex, or (H, W, 3) a lightmap of
// per-texel radiance over the mesh's lightmap UVs; checked finite.
struct RowRadiance {
  std::vector<prt::Rgb> values;
  int width = 0, height = 0;  ///< a lightmap's; 0 per vertex
  prt::render::ShadeFn shader(const prt::Mesh& mesh) const {
    if (width > 0) return prt::render::texelRadianceShader(mesh, values, width, height, mesh.albedo);
    return prt::render::vertexRadianceShader(mesh, values);
  }
};

RowRadiance rowRadiance(const prt::Mesh& mm, py::handle radiance) {
  // (V, 3): per vertex; (H, W, 3): a lightmap of per-texel radiance over the lightmap UVs.
  const py::array given = py::array::ensure(radiance);
  const bool lightmap = given && given.ndim() == 3;
  if (lightmap && mm.lightmapUvs.size() != mm.vertexCount())
    throw py::value_error(
        "radiance of shape (H, W, 3) is a lightmap: the mesh has no lightmap UVs");
  const py::ssize_t H = lightmap ? given.shape(0) : 0, W = lightmap ? given.shape(1) : 0;
  const auto rad =
      lightmap ? floats(radiance, "radiance", {H, W, 3})
               : floats(radiance, "radiance", {static_cast<py::ssize_t>(mm.vertexCount()), 3});
  RowRadiance out;
  out.values.resize(lightmap ? std::size_t(H * W) : mm.vertexCount());
  std::memcpy(static_cast<void*>(out.values.data()), rad.data(),
              out.values.size() * sizeof(prt::Rgb));
  out.width = int(W);
  out.height = int(H);
  asValueError([&] {
    prt::render::checkFiniteRadiance(out.values, "radiance", lightmap ? "texel" : "vertex");
    return 0;
  });
  return out;
}

py::array renderFn(py::handle meshObj, py::handle radiance, py::handle cameraObj, py::handle size,
                   int spp, std::uint32_t seed, py::handle background, py::handle environment,
                   py::handle lightObj, py::handle rot, py::handle progress) {
  const MeshPtr mesh = toMesh(meshObj);
  const prt::Mesh& mm = mesh->mesh();
  prt::render::FrameSettings frame;
  const auto wh = size.cast<std::vector<int>>();
  if (wh.size() != 2) throw py::value_error("size must be (width, height)");
  frame.width = wh[0];
  frame.height = wh[1];
  frame.spp = spp;
  frame.seed = seed;
  asValueError([&] {
    prt::render::checkFrameSettings(frame);
    return 0;
  });
  const RowRadiance rows = rowRadiance(mm, radiance);
  const prt::render::Camera camera = cameraOf(cameraObj, mm, frame.width, frame.height);
  const prt::Mat3d r = rotation(rot);

  EnvironmentPtr env;
  if (!environment.is_none()) env = toEnvironment(environment);
  prt::sh::RgbSh light;
  if (!lightObj.is_none()) light = prtpy::light(lightObj);
  std::string kind = background.is_none() ? (env ? "env" : lightObj.is_none() ? "none" : "sh") : "";
  prt::Rgb colour(0.0f);
  prt::render::Background bg = prt::render::Background::Colour;
  if (kind.empty() && !py::isinstance<py::str>(background)) {
    colour = rgb(background, "background");
    if (!isFinite(colour) || colour.x < 0 || colour.y < 0 || colour.z < 0)
      throw py::value_error("background colour must be finite and non-negative");
  } else {
    if (kind.empty()) kind = background.cast<std::string>();
    bg = asValueError([&] { return prt::render::parseBackground(kind, &colour); });
  }
  if (bg == prt::render::Background::Env && !env)
    throw py::value_error("background='env' needs environment=");
  if (bg == prt::render::Background::Sh && lightObj.is_none())
    throw py::value_error("background='sh' needs light=");
  const prt::render::BackgroundFn bgFn = prt::render::background(
      bg, colour, env ? &env->env : nullptr, lightObj.is_none() ? nullptr : &light, r);
  prt::image::Image img = runLong("rendering", progress, [&](const prt::ProgressFn& fn) {
    return prt::render::tracePrimary(camera, frame, mesh->occluder(), rows.shader(mm), bgFn, fn);
  });
  const auto h = static_cast<py::ssize_t>(img.height), w = static_cast<py::ssize_t>(img.width);
  return adoptVector(std::move(img.pixels), {h, w, 3});
}

float autoExposureFn(py::handle meshObj, py::handle radiance, py::handle cameraObj, py::handle size,
                     const std::string& tonemap) {
  const MeshPtr mesh = toMesh(meshObj);
  const prt::Mesh& mm = mesh->mesh();
  const auto wh = size.cast<std::vector<int>>();
  if (wh.size() != 2 || wh[0] < 1 || wh[1] < 1)
    throw py::value_error("size must be (width, height), both positive");
  const RowRadiance rows = rowRadiance(mm, radiance);
  const prt::render::Camera camera = cameraOf(cameraObj, mm, wh[0], wh[1]);
  const prt::image::ToneMap op = asValueError([&] { return prt::image::parseToneMap(tonemap); });
  py::gil_scoped_release nogil;
  return prt::render::autoExposure(mesh->occluder(), rows.shader(mm), camera, wh[0], wh[1], op);
}

py::dict referenceFn(py::handle meshObj, py::handle environment, const std::string& mode,
                     int samples, int bounces, py::handle spec, py::handle eyeObj,
                     std::uint64_t seed, py::handle rot, py::handle vertices,
                     const std::string& heuristic, py::handle progress) {
  const MeshPtr mesh = toMesh(meshObj);
  const prt::Mesh& mm = mesh->mesh();
  const EnvironmentPtr env = toEnvironment(environment);
  prt::render::ReferenceSettings rs;
  rs.samples = samples;
  rs.mode = asValueError([&] { return prt::parseTransferMode(mode); });
  rs.bounces = prt::effectiveBounces(rs.mode, bounces);
  rs.material = material(spec);
  // The default view: the eye of render's (and prt render's) default 640x480 camera.
  rs.eye = eyeObj.is_none() ? prt::render::frameMesh(mm, 640, 480).eye : vec3(eyeObj, "eye");
  rs.seed = seed;
  rs.rotation = rotation(rot);
  rs.heuristic = heuristicOf(heuristic);
  if (!vertices.is_none()) {
    if (py::isinstance<py::int_>(vertices))
      rs.vertices = prt::render::vertexSubset(mm.vertexCount(), vertices.cast<std::size_t>(), seed);
    else
      rs.vertices = indices(vertices, "vertices", mm.vertexCount());
  }
  const prt::render::ReferenceResult r =
      runLong("reference", progress, [&](const prt::ProgressFn& fn) {
        return prt::render::renderReference(mm, mesh->occluder(), env->env, rs, fn);
      });
  py::dict d;
  const auto n = static_cast<py::ssize_t>(r.vertices.size());
  d["vertices"] = py::array_t<std::uint32_t>(n, r.vertices.data());
  d["radiance"] = rgbArray(r.radiance);
  d["std_error"] = rgbArray(r.stdError);
  d["rays"] = r.rays;
  d["seconds"] = r.seconds;
  return d;
}

py::dict validateFn(py::handle meshObj, py::handle transferObj, py::handle environment, int samples,
                    py::handle bandsList, std::size_t vertices, std::size_t floorVertices,
                    const std::string& window, std::uint64_t seed, py::handle rot,
                    const std::string& heuristic, py::handle modeObj, py::handle bouncesObj,
                    py::handle spec, py::handle encodings, py::handle progress) {
  const MeshPtr mesh = toMesh(meshObj);
  const prt::Mesh& mm = mesh->mesh();
  const TransferPtr t = toTransfer(transferObj);
  requireShTransfer(*t, "validate() checks SH transfer; `prt validate` checks Haar bakes");
  const prt::Transfer& tr = t->transfer;
  asValueError([&] {
    prt::render::requireWholeDomain(mm, tr, "validate");
    return 0;
  });
  if (!t->recipe && modeObj.is_none())
    throw py::value_error("the transfer records no recipe: give mode= (and bounces=, material=)");
  prt::BakeRecipe recipe = t->recipe ? *t->recipe : prt::BakeRecipe{};
  if (!modeObj.is_none())
    recipe.mode = asValueError([&] { return prt::parseTransferMode(modeObj.cast<std::string>()); });
  if (!bouncesObj.is_none()) recipe.bounces = bouncesObj.cast<int>();
  recipe.material = material(spec, recipe.material);
  recipe.bounces = recipe.effectiveBounces();
  const EnvironmentPtr env = toEnvironment(environment);

  prt::render::ValidateSettings vs;
  vs.reference.samples = samples;
  vs.reference.seed = seed;
  vs.reference.rotation = rotation(rot);
  vs.reference.heuristic = heuristicOf(heuristic);
  vs.reference.eye = prt::render::frameMesh(mm, 640, 480).eye;
  if (!bandsList.is_none()) vs.bandsList = bandsList.cast<std::vector<int>>();
  vs.maxVertices = vertices;
  vs.floorVertices = floorVertices;
  vs.window = asValueError([&] { return prt::sh::parseWindow(window); });
  vs.bakeName = "transfer";
  // encodings=: 'all', or a sequence of names (prt validate --encoding).
  if (!encodings.is_none()) {
    if (py::isinstance<py::str>(encodings) && encodings.cast<std::string>() == "all") {
      vs.encodings.assign(prt::sh::kIrradianceEncodings.begin(),
                          prt::sh::kIrradianceEncodings.end());
    } else {
      for (py::handle e : encodings) {
        const auto enc = asValueError(
            [&] { return prt::sh::parseIrradianceEncoding(py::str(e).cast<std::string>()); });
        if (std::find(vs.encodings.begin(), vs.encodings.end(), enc) != vs.encodings.end())
          throw py::value_error(std::string("encodings= names ") + prt::sh::toString(enc) +
                                " twice");
        vs.encodings.push_back(enc);
      }
    }
  }
  // Per texel: a subset of the valid texels is validated, at their sample points (placed by
  // validate itself, as for prt validate).
  prt::render::ValidationReport rep =
      runLong("validating", progress, [&](const prt::ProgressFn& fn) {
        const prt::sh::RgbSh light = prt::envmap::projectEnvironment(env->env, tr.bands());
        return prt::render::validate(mm, mesh->occluder(), tr, recipe, env->env, light, vs, fn);
      });
  for (const std::string& w : rep.warnings) warn(w);
  py::dict d = py::module_::import("json").attr("loads")(prt::render::reportJson(rep));
  d["table"] = prt::render::formatTable(rep);
  d["vertex_error"] = adoptVector(std::move(rep.vertexError),
                                  {static_cast<py::ssize_t>(rep.reference.vertices.size())});
  d["vertices"] = py::array_t<std::uint32_t>(
      static_cast<py::ssize_t>(rep.reference.vertices.size()), rep.reference.vertices.data());
  return d;
}

py::tuple vecTuple(const prt::Vec3f& v) {
  return py::make_tuple(v.x, v.y, v.z);
}

}  // namespace

void bindRelight(py::module_& m) {
  m.def("relight", &relightFn, py::arg("transfer"), py::arg("light"),
        py::arg("albedo") = py::none(), py::arg("rotation") = py::none(), py::kw_only(),
        py::arg("mesh") = py::none(), py::arg("eye") = py::none(), py::arg("material") = py::none(),
        R"(Exit radiance per row of a transfer under SH light: an (N, 3) float32 array.

transfer: a prtkit.Transfer (dense or CPCA-compressed, vectors or matrices) or a numpy array
    of dense rows (float32, C-contiguous, as bake returns; checked for NaN on every call —
    wrap it in prtkit.Transfer once to check it once).
light: SH lighting (B², 3) (project_environment), or a path: an environment projected to the
    transfer's bands, or a light file (.json, the course's light.txt), as `prt render --light`.
albedo: (N, 3) per row or one colour; default the mesh's albedo, else white. A material
    that sets kd replaces it.
rotation: of the environment, a 3x3 matrix or Euler degrees (X, Y, Z): a lobe along d moves
    to R d, exactly (SH rotation, no re-projection).
mesh: where the rows are (positions, normals; its albedo): needed for matrices.
eye: the viewer's position (3,): needed for matrices (glossy transfer is view-dependent).
material: a spec (glossy lobes need matrices); default the transfer's recipe's, else lambert.
The GIL is released (the kernels are the library's: AVX2 where the CPU has it).)");

  py::class_<prt::render::Camera>(
      m, "Camera",
      R"(A pinhole camera: eye, target, up, fov (full vertical angle, degrees); +Y up, the
frame of gluLookAt. frame_mesh(mesh, width, height) gives prt render's default view.)")
      .def(py::init([](py::handle eye, py::handle target, py::handle up, float fov) {
             prt::render::Camera c;
             c.eye = vec3(eye, "eye");
             c.target = vec3(target, "target");
             c.up = vec3(up, "up");
             if (!(fov > 0 && fov < 180)) throw py::value_error("fov must be in (0, 180) degrees");
             c.fovY = fov;
             return c;
           }),
           py::arg("eye") = py::make_tuple(0, 0, 3), py::arg("target") = py::make_tuple(0, 0, 0),
           py::arg("up") = py::make_tuple(0, 1, 0), py::arg("fov") = 40.0f)
      .def_property(
          "eye", [](const prt::render::Camera& c) { return vecTuple(c.eye); },
          [](prt::render::Camera& c, py::handle v) { c.eye = vec3(v, "eye"); })
      .def_property(
          "target", [](const prt::render::Camera& c) { return vecTuple(c.target); },
          [](prt::render::Camera& c, py::handle v) { c.target = vec3(v, "target"); })
      .def_property(
          "up", [](const prt::render::Camera& c) { return vecTuple(c.up); },
          [](prt::render::Camera& c, py::handle v) { c.up = vec3(v, "up"); })
      .def_readwrite("fov", &prt::render::Camera::fovY)
      .def("__repr__", [](const prt::render::Camera& c) {
        const auto f = [](const prt::Vec3f& v) {
          return "(" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " +
                 std::to_string(v.z) + ")";
        };
        return "<prtkit.Camera eye=" + f(c.eye) + " target=" + f(c.target) + " up=" + f(c.up) +
               " fov=" + std::to_string(c.fovY) + ">";
      });

  m.def(
      "frame_mesh",
      [](py::handle mesh, int width, int height) {
        if (width < 1 || height < 1) throw py::value_error("width and height must be positive");
        return prt::render::frameMesh(toMesh(mesh)->mesh(), width, height);
      },
      py::arg("mesh"), py::arg("width") = 640, py::arg("height") = 480,
      "The camera prt render frames a mesh with by default (its bounding sphere from "
      "above-front).");

  m.def("render", &renderFn, py::arg("mesh"), py::arg("radiance"), py::arg("camera") = py::none(),
        py::arg("size") = py::make_tuple(640, 480), py::arg("spp") = 4, py::arg("seed") = 0,
        py::arg("background") = py::none(), py::arg("environment") = py::none(),
        py::arg("light") = py::none(), py::arg("rotation") = py::none(),
        py::arg("progress") = py::none(),
        R"(Renders the mesh shaded with per-vertex radiance (relight's output): an (H, W, 3) linear
float32 image, as `prt render` draws it (Embree primary rays, stratified samples per pixel).
radiance: (V, 3) per vertex, or (h, w, 3) a lightmap over the mesh's lightmap UVs (a per-texel
    transfer relit without mesh=, reshaped: relight(t, L).reshape(h, w, 3)), fetched
    bilinearly per pixel and multiplied by the mesh's albedo, as `prt render` does.

camera: a prtkit.Camera, a spec 'eye=x,y,z;target=x,y,z;up=x,y,z;fov=deg' (missing keys from
    the default), or None: frame_mesh(mesh, width, height).
size: (width, height). spp: samples per pixel; seed of the sub-pixel jitter.
background: 'env' (environment=, rotated by rotation=), 'sh' (the SH reconstruction of
    light=, rotated), 'none' (black), or a linear colour (r, g, b) / 'r,g,b' / '#rrggbb';
    default env when environment= is given, else sh when light= is, else none.)");

  m.def("auto_exposure", &autoExposureFn, py::arg("mesh"), py::arg("radiance"),
        py::arg("camera") = py::none(), py::arg("size") = py::make_tuple(640, 480),
        py::arg("tonemap") = "aces",
        R"(The exposure in stops prt render picks (--exposure auto) for this radiance seen through
camera at size: the one auto exposure rule (image/exposure.hpp) over the pixels that show the
mesh. Pass it to write_image(..., exposure=) for a render with a background.)");

  m.def("reference", &referenceFn, py::arg("mesh"), py::arg("environment"), py::kw_only(),
        py::arg("mode") = "shadowed", py::arg("samples") = 1024, py::arg("bounces") = 1,
        py::arg("material") = py::none(), py::arg("eye") = py::none(), py::arg("seed") = 0,
        py::arg("rotation") = py::none(), py::arg("vertices") = py::none(),
        py::arg("heuristic") = "power", py::arg("progress") = py::none(),
        R"(Brute-force Monte Carlo exit radiance per vertex, no SH anywhere (as `prt reference`).

environment: anything load_environment takes. mode, bounces, material: the transport and
surface to estimate (bounces count for interreflected only). eye: where glossy materials are
seen from (default: render's default camera's eye). vertices: None (all), a count (a
deterministic random subset) or indices. Returns a dict: vertices (M,), radiance (M, 3),
std_error (M, 3) per channel, rays, seconds. GIL released; progress as for bake.)");

  m.def(
      "validate", &validateFn, py::arg("mesh"), py::arg("transfer"), py::arg("environment"),
      py::kw_only(), py::arg("samples") = 1024, py::arg("bands") = py::none(),
      py::arg("vertices") = 0, py::arg("floor_vertices") = 1024, py::arg("window") = "none",
      py::arg("seed") = 0, py::arg("rotation") = py::none(), py::arg("heuristic") = "power",
      py::arg("mode") = py::none(), py::arg("bounces") = py::none(),
      py::arg("material") = py::none(), py::arg("encodings") = py::none(),
      py::arg("progress") = py::none(),
      R"(Validates a transfer against the Monte Carlo reference per band count (as `prt validate`).

transfer: every vertex of mesh; its recipe (bake_transfer, read_bake_file) gives mode,
bounces and material unless given. The environment is projected to the transfer's bands.
samples: reference samples per vertex; bands: band counts to tabulate (default 1..B);
vertices: 0 (all) or a subset size; window: none | hanning | lanczos | dering.
encodings: 'all' or names of irradiance encodings ('l1', 'zh3-shared', ...; a diffuse matrix
transfer only): the report's 'encodings' then lists each one's shading against the reference
and the transfer's own relighting (prt validate --encoding).
Returns the report as a dict (the JSON of `prt validate --json`: rows per band count with
relRmse, floor, refStdErr, ...), plus 'table' (the text table), 'vertex_error' (M,) and
'vertices' (M,).)");
}

}  // namespace prtpy
