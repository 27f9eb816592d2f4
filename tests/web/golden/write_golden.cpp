// prt_web_golden DIR: writes DIR/golden.json (and the files it names: a bake, light files) —
// inputs and what the C++ library computes from them, wherever the browser viewer must compute
// the same thing in JS. tests/web/golden_check.mjs feeds the same inputs to the page's
// functions (web/src) and compares (ctest web.GoldenVectors; docs/web.md, "Tests"):
//
//   rotation     sh::Rotation(rotationEulerXYZ) of random lights, several rotations and bands
//                (sh.js rotationEulerXYZ + rotateLight); rotationAxisAngle (sh.js axisAngle)
//   evalSh       sh::eval at random directions (sh.js evalSh: the SH background)
//   clusters     the per-frame cluster table (relight::projectClusters of the transfer cut to
//                the shown bands, packClusterTable) and the per-vertex texels (packShaderRows)
//                of small CPCA transfers — vectors and matrices, scalar and RGB, b = B and b < B
//                (compressed.js projectClusters, packWeights)
//   bake         a bake file of four transfers (dense and compressed, vectors and a matrix) on a
//                7-part mesh: the library's pick order (transferPreference), every transfer's
//                shader path and packed rows (shaderPath, packShaderRows) and the default
//                framing and camera (meshFraming, frameCamera) (bake.js parseBake, camera.js)
//   lights       light files with fewer and more bands than the transfer: io::loadLighting's
//                warnings and io::padded's coefficients (lights.js)
//   messages     bands::bandLimitMessage (messages.js, filled from the generated template)
//   encodings    sh::encodeIrradiance and sh::evaluate of every irradiance encoding, on lights
//                of 1..4 bands (the sky, turned; random ones; one whose mean is negative; a
//                sun) at random normals (irradiance_encoding.js encode, evaluate); and
//                relight::encodedDiffuse of small dense and CPCA matrix transfers, with and
//                without the material's kd (encoded_diffuse.js incidentRows, shadeEncoded)

#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "prt/core/band_limits.hpp"
#include "prt/core/vec.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/io/light_file.hpp"
#include "prt/io/lighting.hpp"
#include "prt/relight/cluster_projection.hpp"
#include "prt/relight/encoded_diffuse.hpp"
#include "prt/relight/relight.hpp"
#include "prt/relight/shader_transfer.hpp"
#include "prt/render/camera.hpp"
#include "prt/sh/encode_irradiance.hpp"
#include "prt/sh/project.hpp"
#include "prt/sh/rotate.hpp"
#include "prt/sh/sh.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using namespace prt;

std::mt19937 rng(20240521);

float uniform(float lo, float hi) {
  return std::uniform_real_distribution<float>(lo, hi)(rng);
}
std::vector<float> randoms(std::size_t n, float lo = -1.0f, float hi = 1.0f) {
  std::vector<float> v(n);
  for (float& x : v) x = uniform(lo, hi);
  return v;
}
json array(const float* p, std::size_t n) {
  json a = json::array();
  for (std::size_t i = 0; i < n; ++i) a.push_back(p[i]);
  return a;
}
json array(const std::vector<float>& v) {
  return array(v.data(), v.size());
}
json vec(const Vec3f& v) {
  return {v.x, v.y, v.z};
}
json rgbArray(std::span<const Rgb> c) {
  json a = json::array();
  for (const Rgb& x : c) a.push_back(x.x), a.push_back(x.y), a.push_back(x.z);
  return a;
}

json rotations() {
  json cases = json::array();
  for (int bands : {1, 2, 3, 5, 9})
    for (int k = 0; k < 4; ++k) {
      double euler[3] = {0, 0, 0};
      if (k == 1) euler[1] = uniform(-180, 180);  // about +Y only
      if (k >= 2)
        for (double& e : euler) e = uniform(-180, 180);
      const std::vector<float> light = randoms(std::size_t(bands) * bands * 3);
      sh::RgbSh l(bands);
      for (int i = 0; i < bands * bands; ++i) l.c[i] = {light[3 * i], light[3 * i + 1], light[3 * i + 2]};
      const sh::RgbSh out = sh::Rotation(bands, rotationEulerXYZ(euler[0], euler[1], euler[2])).apply(l);
      cases.push_back({{"bands", bands}, {"euler", {euler[0], euler[1], euler[2]}},
                       {"light", array(light)}, {"rotated", rgbArray(out.c)}});
    }
  return cases;
}

json axisAngles() {
  json cases = json::array();
  for (int k = 0; k < 4; ++k) {
    const Vec3d axis = normalize(Vec3d{uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)});
    const double angle = uniform(-3, 3);
    const Mat3d r = rotationAxisAngle(axis, angle);
    json m = json::array();
    for (int i = 0; i < 3; ++i) m.push_back({r.m[i][0], r.m[i][1], r.m[i][2]});
    cases.push_back({{"axis", {axis.x, axis.y, axis.z}}, {"angle", angle}, {"matrix", m}});
  }
  return cases;
}

json evalShCases() {
  json cases = json::array();
  for (int bands : {1, 4, 9})
    for (int k = 0; k < 4; ++k) {
      const Vec3d d = k == 0 ? Vec3d{0, 1, 0}
                             : normalize(Vec3d{uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)});
      std::vector<double> y(std::size_t(bands) * bands);
      sh::eval(bands, d, y.data());
      cases.push_back({{"bands", bands}, {"dir", {d.x, d.y, d.z}}, {"values", y}});
    }
  return cases;
}

/// A CPCA transfer of `rows` rows with random ids, weights, means and basis vectors.
Transfer randomCpca(TransferLayout layout, int bands, int channels, std::size_t rows, int K,
                    int N) {
  TransferShape shape;
  shape.layout = layout;
  shape.bands = bands;
  shape.channels = channels;
  shape.rows = {0, rows};
  CpcaRows c;
  c.clusters = K;
  c.basisCount = N;
  for (std::size_t r = 0; r < rows; ++r)
    c.cluster.push_back(r < std::size_t(K) ? std::uint32_t(r) : std::uint32_t(rng() % K));
  c.weights = FloatArray(randoms(rows * N));
  c.means = FloatArray(randoms(std::size_t(K) * shape.stride()));
  c.basis = FloatArray(randoms(std::size_t(K) * N * shape.stride(), -0.5f, 0.5f));
  return Transfer::cpca(shape, c);
}

json cpcaJson(const Transfer& t) {
  const CpcaRows& c = t.cpca();
  json ids = json::array();
  for (std::uint32_t k : c.cluster) ids.push_back(k);
  return {{"layout", toString(t.layout())}, {"bands", t.bands()},   {"channels", t.channels()},
          {"rows", t.rowCount()},           {"clusters", c.clusters}, {"basisCount", c.basisCount},
          {"cluster", ids},                 {"weights", array(c.weights.data(), c.weights.size())},
          {"means", array(c.means.data(), c.means.size())},
          {"basis", array(c.basis.data(), c.basis.size())}};
}

json clusterCases() {
  struct Case {
    TransferLayout layout;
    int bands, channels, K, N;
  };
  json cases = json::array();
  for (const Case& c : {Case{TransferLayout::Vector, 3, 1, 5, 3}, Case{TransferLayout::Vector, 4, 3, 4, 5},
                        Case{TransferLayout::Matrix, 3, 1, 3, 2}, Case{TransferLayout::Matrix, 2, 3, 2, 4},
                        Case{TransferLayout::Vector, 2, 1, 3, 0}}) {
    const Transfer t = randomCpca(c.layout, c.bands, c.channels, 11, c.K, c.N);
    const relight::ShaderPath path = relight::shaderPath(t, true);
    const relight::ShaderRows rows = relight::packShaderRows(t, path);
    json tables = json::array();
    for (int b = c.bands; b >= std::max(1, c.bands - 1); --b) {
      const std::vector<float> light = randoms(std::size_t(b) * b * 3);
      std::vector<Rgb> rotated(std::size_t(b) * b);
      for (std::size_t i = 0; i < rotated.size(); ++i)
        rotated[i] = {light[3 * i], light[3 * i + 1], light[3 * i + 2]};
      std::vector<float> table;
      relight::packClusterTable(relight::projectClusters(t.cut(b), relight::prepareLight(rotated, b)),
                                table);
      tables.push_back({{"bands", b}, {"light", array(light)}, {"table", array(table)}});
    }
    json j = cpcaJson(t);
    j["texelsPerRow"] = rows.texelsPerRow;
    j["packedRows"] = array(rows.rgba);
    j["frames"] = tables;
    cases.push_back(j);
  }
  return cases;
}

json bakeCase(const fs::path& dir) {
  BakeFile b;
  b.mesh = builtinScene("cornell?grid=3");
  const std::size_t V = b.mesh.vertexCount();
  const auto dense = [&](TransferMode mode, int bands, int channels) {
    BakedTransfer t;
    t.recipe.mode = mode;
    TransferShape shape;
    shape.bands = bands;
    shape.channels = channels;
    shape.rows = {0, V};
    t.transfer = Transfer::dense(shape, FloatArray(randoms(V * shape.stride())));
    return t;
  };
  const auto compressed = [&](TransferMode mode, TransferLayout layout, int bands, int channels, int K,
                              int N) {
    BakedTransfer t;
    t.recipe.mode = mode;
    t.transfer = randomCpca(layout, bands, channels, V, K, N);
    return t;
  };
  // Stored in an order unlike the preference, so that the page has to sort.
  b.transfers.push_back(dense(TransferMode::Unshadowed, 3, 1));
  b.transfers.push_back(compressed(TransferMode::Shadowed, TransferLayout::Vector, 3, 1, 6, 3));
  b.transfers.push_back(dense(TransferMode::Interreflected, 3, 3));
  b.transfers.push_back(compressed(TransferMode::Shadowed, TransferLayout::Matrix, 3, 1, 4, 2));
  const std::string file = (dir / "golden.glb").string();
  writeBake(file, b);
  const BakeFile read = readBake(file);

  json order = json::array();
  for (std::size_t i : transferPreference(read)) {
    const Transfer& t = read.transfers[i].transfer;
    const relight::ShaderPath path = relight::shaderPath(t, true);
    const relight::ShaderRows rows = relight::packShaderRows(t, path);
    order.push_back({{"mode", toString(read.transfers[i].mode())}, {"layout", toString(t.layout())},
                     {"compressed", t.compressed()}, {"texelsPerRow", rows.texelsPerRow},
                     {"packedRows", array(rows.rgba)}});
  }
  json parts = json::array();
  for (const MeshPart& p : read.mesh.parts)
    parts.push_back({{"name", p.name}, {"first", p.firstVertex}, {"vertices", p.vertexCount}});
  const render::Framing f = render::meshFraming(read.mesh);
  const int w = 320, h = 240;
  const render::Camera c = render::frameCamera(f, w, h);
  return {{"file", "golden.glb"},
          {"vertices", V},
          {"parts", parts},
          {"transfers", order},
          {"framing", {{"centre", vec(f.centre)}, {"radius", f.radius}, {"direction", vec(f.direction)},
                       {"up", vec(f.up)}, {"fov", f.fovY}, {"margin", f.margin}}},
          {"width", w},
          {"height", h},
          {"camera", {{"eye", vec(c.eye)}, {"target", vec(c.target)}, {"up", vec(c.up)}, {"fov", c.fovY}}}};
}

/// A per-texel bake (format 6): a 6 × 5 lightmap over the Cornell box's parts, dense RGB
/// inter-reflected rows and CPCA-compressed scalar shadowed rows; the library's packing of each
/// (packShaderRows: rows by texel, y·W + x), which the page packs once for every part.
json texelBakeCase(const fs::path& dir) {
  BakeFile b;
  b.mesh = builtinScene("cornell?grid=3");
  b.mesh.lightmapUvs.clear();
  for (std::size_t v = 0; v < b.mesh.vertexCount(); ++v) {
    const std::vector<float> uv = randoms(2, 0.0f, 1.0f);
    b.mesh.lightmapUvs.push_back({uv[0], uv[1]});
  }
  const int W = 6, H = 5;
  const std::size_t rows = std::size_t(W) * H;
  const auto texels = [&](TransferShape s) {
    s.domain = TransferDomain::Texels;
    s.lightmap = {W, H, 1};
    return s;
  };
  BakedTransfer dense;
  dense.recipe.mode = TransferMode::Interreflected;
  TransferShape shape;
  shape.bands = 3;
  shape.channels = 3;
  shape.rows = {0, rows};
  shape = texels(shape);
  dense.transfer = Transfer::dense(shape, FloatArray(randoms(rows * shape.stride())));
  BakedTransfer compressed;
  compressed.recipe.mode = TransferMode::Shadowed;
  const Transfer c = randomCpca(TransferLayout::Vector, 3, 1, rows, 4, 2);
  compressed.transfer = Transfer::cpca(texels(c.shape()), c.cpca());
  b.transfers = {compressed, dense};
  const std::string file = (dir / "golden-texels.glb").string();
  writeBake(file, b);
  const BakeFile read = readBake(file);
  json order = json::array();
  for (std::size_t i : transferPreference(read)) {
    const Transfer& t = read.transfers[i].transfer;
    const relight::ShaderRows r = relight::packShaderRows(t, relight::shaderPath(t, true));
    order.push_back({{"mode", toString(read.transfers[i].mode())}, {"compressed", t.compressed()},
                     {"perPixel", r.perPixel}, {"texelsPerRow", r.texelsPerRow},
                     {"packedRows", array(r.rgba)}});
  }
  return {{"file", "golden-texels.glb"}, {"width", W}, {"height", H}, {"transfers", order}};
}

json lightCases(const fs::path& dir) {
  json cases = json::array();
  for (const auto& [lightBands, transferBands] : {std::pair{2, 4}, std::pair{3, 4}, std::pair{5, 3}, std::pair{3, 3}}) {
    const std::string name =
        "light" + std::to_string(lightBands) + "_for" + std::to_string(transferBands) + ".json";
    io::LightFile lf;
    lf.coefficients = sh::RgbSh(lightBands);
    for (Rgb& x : lf.coefficients.c) x = {uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
    io::writeLightJson((dir / name).string(), lf);
    const io::Lighting l = io::loadLighting((dir / name).string(), transferBands);
    const sh::RgbSh padded = io::padded(l.coefficients, transferBands);
    cases.push_back({{"file", name},
                     {"path", (dir / name).string()},
                     {"transferBands", transferBands},
                     {"warnings", l.warnings},
                     {"coefficients", rgbArray(padded.c)}});
  }
  return cases;
}

/// The lights the encodings are checked on: the sky (3 bands, and turned), random lights of 1..4
/// bands, one whose mean is negative in red, and a sun (a narrow cap, 3 bands: it rings).
std::vector<std::pair<std::string, sh::RgbSh>> encodingLights() {
  std::vector<std::pair<std::string, sh::RgbSh>> out;
  const sh::RgbSh sky = io::loadLighting("builtin:sky", 3).coefficients;
  out.push_back({"builtin:sky", sky});
  out.push_back({"builtin:sky turned", sh::Rotation(3, rotationEulerXYZ(30, -50, 20)).apply(sky)});
  for (int bands : {1, 2, 3, 4}) {
    sh::RgbSh l(bands);
    for (Rgb& x : l.c) x = {uniform(-0.5f, 0.5f), uniform(-0.5f, 0.5f), uniform(-0.5f, 0.5f)};
    l.c[0] = {uniform(0.5f, 2), uniform(0.5f, 2), uniform(0.5f, 2)};
    out.push_back({"random, " + std::to_string(bands) + " bands", l});
  }
  sh::RgbSh negative(3);
  for (Rgb& x : negative.c) x = {uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
  negative.c[0].x = -0.3f;
  out.push_back({"negative mean", negative});
  const Vec3d sun = normalize(Vec3d{0.3, 0.8, -0.5});
  const sh::RgbSh cap = sh::projectFunctionRgb(
      3,
      [&](const Vec3d& d) {
        return dot(d, sun) > 0.97 ? Rgbd(20, 18, 15) : Rgbd(0.01, 0.015, 0.03);
      },
      64);
  out.push_back({"sun", cap});
  return out;
}

json encodingCases() {
  std::vector<Vec3d> normals = {{0, 1, 0}, {0, -1, 0}, {1, 0, 0}, {0, 0, -1}};
  for (int k = 0; k < 12; ++k)
    normals.push_back(normalize(Vec3d{uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)}));
  json dirs = json::array();
  for (const Vec3d& n : normals) dirs.push_back({n.x, n.y, n.z});
  json cases = json::array();
  for (const auto& [name, light] : encodingLights()) {
    json encoded = json::array();
    for (sh::IrradianceEncoding e : sh::kIrradianceEncodings) {
      const sh::EncodedIrradiance x = sh::encodeIrradiance(light, e);
      json values = json::array(), coeffs = json::array();
      for (const Vec3d& n : normals) {
        const Rgbd v = sh::evaluate(x, n);
        values.push_back(v.x), values.push_back(v.y), values.push_back(v.z);
      }
      for (const Rgbd& c : x.sh)
        coeffs.push_back(c.x), coeffs.push_back(c.y), coeffs.push_back(c.z);
      encoded.push_back({{"encoding", sh::toString(e)},
                         {"sh", coeffs},
                         {"axis", {x.axis.x, x.axis.y, x.axis.z}},
                         {"zonal", {x.zonal.x, x.zonal.y, x.zonal.z}},
                         {"values", values}});
    }
    cases.push_back({{"light", name},
                     {"bands", light.bands},
                     {"coefficients", rgbArray(light.c)},
                     {"encoded", encoded}});
  }
  return {{"normals", dirs}, {"lights", cases}};
}

/// relight::encodedDiffuse of small matrix transfers (dense RGB, dense scalar and CPCA RGB, 3
/// and 4 bands, shown at all or fewer bands), with the rows' albedo or the material's kd.
json encodedDiffuseCases() {
  json cases = json::array();
  const std::size_t rows = 9;
  struct Case {
    bool compressed;
    int bands, channels, shown;
    bool kd;
  };
  int k = 0;
  for (const Case& c : {Case{false, 3, 3, 3, false}, Case{false, 4, 1, 4, true},
                        Case{true, 3, 3, 3, false}, Case{false, 4, 3, 2, false}}) {
    const sh::IrradianceEncoding encoding =
        sh::kIrradianceEncodings[std::size_t(k++) * 5 % sh::kIrradianceEncodings.size()];
    TransferShape shape;
    shape.layout = TransferLayout::Matrix;
    shape.bands = c.bands;
    shape.channels = c.channels;
    shape.rows = {0, rows};
    Transfer t = c.compressed ? randomCpca(TransferLayout::Matrix, c.bands, c.channels, rows, 3, 2)
                              : Transfer::dense(
                                    shape, FloatArray(randoms(rows * shape.stride(), -0.3f, 0.6f)));
    const Transfer shown = c.shown < c.bands ? t.cut(c.shown) : t;
    std::vector<Vec3f> normals;
    std::vector<Rgb> albedo;
    for (std::size_t r = 0; r < rows; ++r) {
      const Vec3d n = normalize(Vec3d{uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)});
      normals.push_back(Vec3f(n));
      albedo.push_back({uniform(0, 1), uniform(0, 1), uniform(0, 1)});
    }
    sh::RgbSh light(c.shown);
    for (Rgb& x : light.c) x = {uniform(-0.5f, 0.5f), uniform(-0.5f, 0.5f), uniform(-0.5f, 0.5f)};
    light.c[0] = {2, 1.8f, 1.5f};
    Material material;
    if (c.kd) material.diffuse = Rgb{0.7f, 0.5f, 0.3f};
    const relight::Surface surface{{}, normals, albedo};
    const std::vector<Rgb> out = relight::encodedDiffuse(shown, light, encoding, material, surface);
    json n = json::array(), a = json::array();
    for (const Vec3f& x : normals) n.push_back(x.x), n.push_back(x.y), n.push_back(x.z);
    json j = c.compressed ? cpcaJson(t)
                          : json{{"layout", "matrix"},
                                 {"bands", c.bands},
                                 {"channels", c.channels},
                                 {"rows", rows},
                                 {"matrices", array(t.values().data(), t.values().size())}};
    j["compressed"] = c.compressed;
    j["shown"] = c.shown;
    j["encoding"] = sh::toString(encoding);
    j["light"] = rgbArray(light.c);
    j["normals"] = n;
    j["albedo"] = rgbArray(albedo);
    j["kd"] = c.kd ? json{0.7f, 0.5f, 0.3f} : json(nullptr);
    j["radiance"] = rgbArray(out);
    cases.push_back(j);
  }
  return cases;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: prt_web_golden DIR\n");
    return 2;
  }
  try {
    const fs::path dir = argv[1];
    fs::create_directories(dir);
    json g;
    g["rotation"] = rotations();
    g["axisAngle"] = axisAngles();
    g["evalSh"] = evalShCases();
    g["clusters"] = clusterCases();
    g["bake"] = bakeCase(dir);
    g["texelBake"] = texelBakeCase(dir);
    g["lights"] = lightCases(dir);
    g["encodings"] = encodingCases();
    g["encodedDiffuse"] = encodedDiffuseCases();
    g["messages"] = json::array();
    for (const auto& [what, b, who, max] :
         {std::tuple{"the shadowed vector transfer", 20, "this page's light", 15},
          std::tuple{"a light {with} braces", 33, "the library", bands::kMaxLibrary}})
      g["messages"].push_back({{"what", what}, {"bands", b}, {"who", who}, {"max", max},
                               {"message", bands::bandLimitMessage(what, b, who, max)}});
    std::ofstream(dir / "golden.json") << g.dump() << "\n";
    std::printf("wrote %s\n", (dir / "golden.json").string().c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "prt_web_golden: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
