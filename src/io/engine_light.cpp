#include "prt/io/engine_light.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <vector>

#include <nlohmann/json.hpp>

#include "prt/core/base64.hpp"
#include "prt/core/error.hpp"
#include "prt/core/hash.hpp"
#include "prt/core/version.hpp"
#include "prt/envmap/layout.hpp"
#include "prt/image/data_texture.hpp"
#include "prt/sh/convolve.hpp"
#include "prt/sh/rotate.hpp"

namespace prt::io {

namespace {

using Json = nlohmann::ordered_json;

/// The first three bands, zero-padded: what the 9-coefficient engines hold.
sh::RgbSh threeBands(const sh::RgbSh& f) {
  sh::RgbSh out(3);
  for (std::size_t k = 0; k < out.c.size() && k < f.c.size(); ++k) out.c[k] = f.c[k];
  return out;
}

/// |constant| of each of the first nine basis functions (sh.hpp's table).
constexpr std::array<double, 9> kBasisConstant = {
    0.28209479177387814, 0.48860251190291992, 0.48860251190291992,
    0.48860251190291992, 1.09254843059207907, 1.09254843059207907,
    0.31539156525252001, 1.09254843059207907, 0.54627421529603954};

/// The sign that turns our Condon–Shortley basis into the unsigned one (three.js): −1 where the
/// CS phase (−1)^m with m odd puts a minus on the polynomial.
constexpr std::array<float, 9> kCondonShortley = {1, -1, 1, -1, 1, -1, 1, -1, 1};

/// Unity: our basis at d = (−x_u, y_u, z_u) written in Unity's polynomials 1, y, z, x, xy, yz,
/// 3z²−1, xz, x²−y² of its own axes (the header derives it: the CS signs and the x flip).
constexpr std::array<float, 9> kUnitySign = {1, -1, 1, 1, -1, -1, 1, 1, 1};

/// Filament cmgen's cube frame against ours (checked against cmgen's own output in the tests).
Mat3d cmgenFrame() {
  return rotationEulerXYZ(0, -90, 0);
}

Json rgbRows(const sh::RgbSh& f) {
  Json rows = Json::array();
  for (const Rgb& c : f.c) rows.push_back({c[0], c[1], c[2]});
  return rows;
}

/// A fixed UUID (RFC 4122 layout, version 5 style bits) from the text it identifies, so that the
/// same light always writes the same file.
std::string stableUuid(const std::string& text) {
  Fnv1a first;
  first.add(text.data(), text.size());
  const std::uint64_t a = first.value();
  std::uint64_t b = 1099511628211ull * 7;  // a second, differently mixed pass for 128 bits
  for (unsigned char ch : text) b = (b ^ ch) * 0x100000001b3ull + 0x9e3779b97f4a7c15ull;
  char hex[40];
  std::snprintf(hex, sizeof hex, "%016llx%016llx", static_cast<unsigned long long>(a),
                static_cast<unsigned long long>(b));
  const std::string h = hex;
  return h.substr(0, 8) + "-" + h.substr(8, 4) + "-5" + h.substr(13, 3) + "-" +
         "89ab"[static_cast<unsigned char>(h[16]) % 4] + h.substr(17, 3) + "-" + h.substr(20, 12);
}

/// EXT_lights_image_based's prefiltered specular cube: 64² at mip 0, halved per mip down to the
/// 16² the extension suggests for roughness 1: three mips, roughness 0, ½, 1.
constexpr int kSpecularSize = 64;
constexpr int kSpecularMips = 3;

/// Per band l, the factor by which the GGX prefilter (Karis's split sum with n = v = r: each
/// direction l weighted by D(h) (n·l), h halfway between the mirror direction and l, normalised)
/// of roughness r (α = r²) scales the light's band l: by Funk–Hecke, the lobe's Legendre moment
/// ∫ w P_l / ∫ w over the hemisphere about the mirror direction. Roughness 0 keeps every band.
std::vector<double> ggxBandFactors(int bands, double roughness) {
  std::vector<double> g(static_cast<std::size_t>(bands), 1.0);
  if (roughness <= 0) return g;
  const double a2 = std::pow(roughness, 4);
  constexpr int n = 20000;
  std::vector<double> sum(g.size(), 0.0);
  double total = 0;
  for (int i = 0; i < n; ++i) {
    const double theta = (i + 0.5) * (std::numbers::pi / 2) / n, t = std::cos(theta);
    const double q = (1 + t) / 2 * (a2 - 1) + 1;  // (n·h)² (α² − 1) + 1, (n·h)² = (1 + n·l)/2
    const double w = a2 / (q * q) * t * std::sin(theta);
    total += w;
    double p0 = 1, p1 = t;
    sum[0] += w;
    if (bands > 1) sum[1] += w * t;
    for (int l = 2; l < bands; ++l) {
      const double p2 = ((2 * l - 1) * t * p1 - (l - 1) * p0) / l;
      sum[static_cast<std::size_t>(l)] += w * p2;
      p0 = p1;
      p1 = p2;
    }
  }
  for (std::size_t l = 0; l < g.size(); ++l) g[l] = sum[l] / total;
  return g;
}

/// Babylon.js's RGBD packing (its toRGBD, which EXT_lights_image_based's 4-channel PNGs hold):
/// D = ⌊max(255 / max(r, g, b), 1)⌋ ∈ 1..255 in alpha, (rgb · D / 255)^(1/2.2) in colour; a
/// reader takes rgb^2.2 / alpha. Negative radiance (SH ringing) is written as 0; above 255 it is
/// clamped.
std::array<std::uint8_t, 4> rgbd(const Rgb& c) {
  const double v[3] = {std::max(0.0, double(c.x)), std::max(0.0, double(c.y)),
                       std::max(0.0, double(c.z))};
  const double peak = std::max({v[0], v[1], v[2], 1e-6});
  const double d = std::clamp(std::floor(std::max(255.0 / peak, 1.0)), 1.0, 255.0);
  std::array<std::uint8_t, 4> out{};
  for (int ch = 0; ch < 3; ++ch)
    out[static_cast<std::size_t>(ch)] = static_cast<std::uint8_t>(
        std::lround(std::pow(std::min(v[ch] * d / 255.0, 1.0), 1 / 2.2) * 255.0));
  out[3] = static_cast<std::uint8_t>(d);
  return out;
}

/// The specular cube of the light itself (the radiance its coefficients hold, every band),
/// prefiltered per mip: `images` gets one data-URI PNG (RGBD) per face and mip, the result is
/// the extension's specularImages (mip by mip, faces +X −X +Y −Y +Z −Z, in the standard cube-map
/// orientation prtkit reads face folders in: row 0 at the top).
Json specularImages(const sh::RgbSh& radiance, Json& images) {
  Json mips = Json::array();
  for (int k = 0; k < kSpecularMips; ++k) {
    const int size = kSpecularSize >> k;
    const std::vector<double> g = ggxBandFactors(radiance.bands, k / double(kSpecularMips - 1));
    sh::RgbSh f = radiance;
    for (int l = 0; l < f.bands; ++l)
      for (int m = -l; m <= l; ++m) {
        Rgb& c = f.c[static_cast<std::size_t>(sh::index(l, m))];
        c = c * static_cast<float>(g[static_cast<std::size_t>(l)]);
      }
    Json faces = Json::array();
    for (int face = 0; face < 6; ++face) {
      std::vector<std::uint8_t> px(static_cast<std::size_t>(size * size * 4));
      for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
          const Vec3d d = envmap::cubeFaceDirection(face, 2 * (x + 0.5) / size - 1,
                                                    2 * (y + 0.5) / size - 1);
          const double len = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
          const Vec3f dir(static_cast<float>(d.x / len), static_cast<float>(d.y / len),
                          static_cast<float>(d.z / len));
          const auto p = rgbd(sh::reconstruct(f, dir));
          std::copy(p.begin(), p.end(), px.begin() + 4 * (std::ptrdiff_t(y) * size + x));
        }
      faces.push_back(images.size());
      images.push_back({{"name", std::string(envmap::kFaceNames[static_cast<std::size_t>(face)]) +
                                     "-mip" + std::to_string(k)},
                        {"uri", "data:image/png;base64," +
                                    base64(image::encodePng8(size, size, 4, px, "specular cube"))}});
    }
    mips.push_back(faces);
  }
  return mips;
}

}  // namespace

EngineLight parseEngineLight(std::string_view name) {
  if (name == "threejs") return EngineLight::ThreeJs;
  if (name == "gltf-ibl") return EngineLight::GltfIbl;
  if (name == "cmgen") return EngineLight::Cmgen;
  if (name == "unity") return EngineLight::Unity;
  throw Error("unknown engine light format '" + std::string(name) +
              "' (threejs, gltf-ibl, cmgen or unity)");
}

const char* engineLightName(EngineLight format) {
  switch (format) {
    case EngineLight::ThreeJs: return "threejs";
    case EngineLight::GltfIbl: return "gltf-ibl";
    case EngineLight::Cmgen: return "cmgen";
    case EngineLight::Unity: return "unity";
  }
  return "?";
}

const char* engineLightExtension(EngineLight format) {
  return format == EngineLight::Cmgen ? "txt" : "json";
}

sh::RgbSh toEngineConvention(EngineLight format, const sh::RgbSh& radiance) {
  switch (format) {
    case EngineLight::ThreeJs: {
      sh::RgbSh f = threeBands(radiance);
      for (std::size_t k = 0; k < 9; ++k) f.c[k] = f.c[k] * kCondonShortley[k];
      return f;
    }
    case EngineLight::GltfIbl:
      return sh::irradiance(threeBands(radiance));
    case EngineLight::Cmgen:
      return sh::Rotation(radiance.bands, cmgenFrame()).apply(radiance);
    case EngineLight::Unity: {
      sh::RgbSh f = sh::irradiance(threeBands(radiance));
      for (std::size_t k = 0; k < 9; ++k)
        f.c[k] = f.c[k] * static_cast<float>(kUnitySign[k] * kBasisConstant[k] / std::numbers::pi);
      return f;
    }
  }
  PRT_CHECK(false, "every engine light format is handled");
  return radiance;
}

std::string formatEngineLight(EngineLight format, const sh::RgbSh& radiance,
                              const std::string& source) {
  const sh::RgbSh f = toEngineConvention(format, radiance);
  const std::string generator = std::string("prtkit ") + kVersion + " (prt light)";
  switch (format) {
    case EngineLight::ThreeJs: {
      Json flat = Json::array();
      for (const Rgb& c : f.c)
        for (int ch = 0; ch < 3; ++ch) flat.push_back(c[ch]);
      Json j;
      j["metadata"] = {{"version", 4.6}, {"type", "Object"}, {"generator", generator}};
      j["object"] = {{"uuid", stableUuid(flat.dump() + source)},
                     {"type", "LightProbe"},
                     {"name", source},
                     {"layers", 1},
                     {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}},
                     {"up", {0, 1, 0}},
                     {"intensity", 1},
                     {"sh", flat}};
      return j.dump(2) + "\n";
    }
    case EngineLight::GltfIbl: {
      // A complete glTF 2.0 asset: the light, one scene that uses it, the specular cube's images.
      Json images = Json::array();
      Json light;
      light["name"] = source;
      light["intensity"] = 1.0;
      light["rotation"] = {0, 0, 0, 1};
      light["irradianceCoefficients"] = rgbRows(f);
      light["specularImageSize"] = kSpecularSize;
      light["specularImages"] = specularImages(radiance, images);
      Json j;
      j["asset"] = {{"version", "2.0"}, {"generator", generator}};
      j["extensionsUsed"] = {"EXT_lights_image_based"};
      j["extensions"]["EXT_lights_image_based"]["lights"] = Json::array({light});
      j["scene"] = 0;
      j["scenes"] = Json::array(
          {{{"name", source}, {"extensions", {{"EXT_lights_image_based", {{"light", 0}}}}}}});
      j["images"] = images;
      return j.dump(2) + "\n";
    }
    case EngineLight::Cmgen: {
      std::string s;
      for (int l = 0; l < f.bands; ++l)
        for (int m = -l; m <= l; ++m) {
          const Rgb& c = f.c[static_cast<std::size_t>(sh::index(l, m))];
          char line[128];
          std::snprintf(line, sizeof line, "(%18.15f, %18.15f, %18.15f); // L%d%d\n",
                        static_cast<double>(c[0]), static_cast<double>(c[1]),
                        static_cast<double>(c[2]), l, m);
          s += line;
        }
      return s;
    }
    case EngineLight::Unity: {
      Json flat = Json::array();
      for (int ch = 0; ch < 3; ++ch)
        for (const Rgb& c : f.c) flat.push_back(c[ch]);
      Json j;
      j["generator"] = generator;
      j["source"] = source;
      j["convention"] =
          "UnityEngine.Rendering.SphericalHarmonicsL2: sh[channel, i] = sh[9 * channel + i], "
          "evaluated as ShadeSH9 does; Unity's axes (x negated from glTF's)";
      j["sh"] = flat;
      return j.dump(2) + "\n";
    }
  }
  PRT_CHECK(false, "every engine light format is handled");
  return {};
}

}  // namespace prt::io
