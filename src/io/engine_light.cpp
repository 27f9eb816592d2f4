#include "prt/io/engine_light.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>

#include <nlohmann/json.hpp>

#include "prt/core/error.hpp"
#include "prt/core/hash.hpp"
#include "prt/core/version.hpp"
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
      Json light;
      light["name"] = source;
      light["intensity"] = 1.0;
      light["rotation"] = {0, 0, 0, 1};
      light["irradianceCoefficients"] = rgbRows(f);
      Json j;
      j["asset"] = {{"generator", generator}};
      j["extensions"]["EXT_lights_image_based"]["lights"] = Json::array({light});
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
