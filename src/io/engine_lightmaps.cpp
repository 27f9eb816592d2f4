// Relit lightmaps in engines' layouts (engine_lightmaps.hpp gives every layout, its decode and
// where it comes from; docs/lightmaps.md the same for users).

#include "prt/io/engine_lightmaps.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "bake_mesh.hpp"
#include "prt/core/error.hpp"
#include "prt/core/luminance.hpp"
#include "prt/core/parallel.hpp"
#include "prt/core/version.hpp"
#include "prt/image/color.hpp"
#include "prt/image/data_texture.hpp"
#include "prt/sh/encode_irradiance.hpp"

namespace prt::io {

namespace {

constexpr double kY00 = 0.28209479177387814;  // 1/√(4π)
constexpr double kY1 = 0.48860251190291992;   // √(3/4π)
constexpr double kY20 = 0.31539156525252005;  // √(5/16π)
// Godot 4.0–4.3's decode constants, as its shader writes them (Y₀₀, and Y₁ · 2/3).
constexpr double kGodot43L0 = 0.282095, kGodot43L1 = 0.32573;

struct EngineName {
  LightmapEngine e;
  const char* name;
};
constexpr EngineName kEngines[] = {{LightmapEngine::Godot, "godot"},
                                   {LightmapEngine::Godot43, "godot-4.3"},
                                   {LightmapEngine::Bakery, "bakery"}};

/// One texel's encoded irradiance as the layouts store it, already over π and scaled: the L1
/// part f ≈ a + c·n per channel (glTF axes), the zonal term and axis (the L2 layers, E_i / π,
/// apart: only l2 and l2-deringed have them).
struct TexelValues {
  Rgbd a{0, 0, 0};
  std::array<Vec3d, 3> c{};  ///< per channel
  Rgbd k{0, 0, 0};           ///< the zh3 forms: f += k (3 (a·n)² − 1)
  Vec3d axis{0, 0, 1};       ///< the zh3 forms' axis (stored by zh3-shared and zh3-optimal)
};

/// Planes of an RGB float texture of `layers` W × H layers stacked down the image.
struct Stack {
  int width = 0, height = 0, layers = 0;
  std::array<std::vector<float>, 3> planes;
  Stack(int w, int h, int n) : width(w), height(h), layers(n) {
    for (auto& p : planes) p.assign(std::size_t(w) * std::size_t(h) * std::size_t(n), 0.0f);
  }
  void set(int layer, std::size_t texel, const Rgbd& v) {
    const std::size_t at = std::size_t(layer) * std::size_t(width) * std::size_t(height) + texel;
    for (int ch = 0; ch < 3; ++ch) planes[ch][at] = float(v[ch]);
  }
  std::string exr(const std::string& label) const {
    image::DataTexture t;
    t.width = width;
    t.height = height * layers;
    t.channelNames = {"R", "G", "B"};
    t.planes = {planes[0], planes[1], planes[2]};
    return image::encodeExrData(t, label);
  }
};

/// One channel's band-1 vector c made to fit a packed layout that holds |c_k| ≤ room·a (Godot
/// 4.4+: 4, Bakery: 2): scaled down as a whole when it does not (its direction kept, as
/// l1-windowed keeps it), dropped when a ≤ 0 (a ringing light: no L0 to pack it against).
/// Sets `changed` when that loses something.
Vec3d fitted(const Vec3d& c, double a, double room, bool& changed) {
  const double m = std::max({std::abs(c.x), std::abs(c.y), std::abs(c.z)});
  if (!(a > 0)) {
    if (m > 0 || a < 0) changed = true;
    return Vec3d(0.0);
  }
  if (m <= room * a) return c;
  changed = true;
  return c * (room * a / m);
}

/// A fitted value c packed against L0 = a as c / (d·a) + ½, in [0, 1] (d = 8: Godot, 4: Bakery).
double pack(double c, double a, double d) {
  return a > 0 ? std::clamp(c / (d * a) + 0.5, 0.0, 1.0) : 0.5;
}

/// Godot's .import beside a layered atlas, as LightmapGI writes it (scene/3d/lightmap_gi.cpp,
/// _save_and_reimport_atlas_textures): a Texture2DArray of `layers` slices stacked vertically,
/// no mipmaps; "VRAM Uncompressed" (3) so the floats reach the shader as written (LightmapGI's
/// default, 2, compresses them to BC6H).
std::string godotImport(int layers) {
  return "[remap]\n\nimporter=\"2d_array_texture\"\ntype=\"CompressedTexture2DArray\"\n\n"
         "[params]\n\ncompress/mode=3\ncompress/channel_pack=1\nmipmaps/generate=false\n"
         "slices/horizontal=1\nslices/vertical=" +
         std::to_string(layers) + "\n";
}

nlohmann::json lightmapJson(const Mesh& mesh, const LightmapDescription& d) {
  return {{"width", d.lightmap.width},
          {"height", d.lightmap.height},
          {"padding", d.lightmap.padding},
          {"texCoord", lightmapTexCoord(mesh)},
          {"rowZero",
           "v = 0 (the image's top row, as glTF, Godot and Unity's glTF importers "
           "read textures)"}};
}

nlohmann::json baseManifest(const char* format, const Mesh& mesh, const LightmapDescription& d) {
  return {{"format", "prtkit-engine-lightmap"},
          {"version", 1},
          {"generator", kGenerator},
          {"kind", format},
          {"source", d.source},
          {"transfer", d.transfer},
          {"light", d.light},
          {"exposure",
           {{"stops", d.exposureStops},
            {"scale", std::exp2(d.exposureStops)},
            {"rule",
             "every value is multiplied by scale = 2^stops; the files are linear, "
             "scene-referred (no tone map): the engine's own exposure applies on top"}}},
          {"quantity",
           "f = E/pi: the exit radiance of a white Lambertian surface (E the irradiance of the "
           "light arriving at the texel); the albedo is not applied - engines multiply it"},
          {"lightmap", lightmapJson(mesh, d)}};
}

void checkTexels(std::size_t values, std::size_t perTexel, const LightmapDescription& d) {
  if (d.lightmap.width < 1 || d.lightmap.height < 1 || values != d.lightmap.texels() * perTexel)
    throw Error(d.source, "engine lightmap: " + std::to_string(values) + " values do not fill a " +
                              std::to_string(d.lightmap.width) + " x " +
                              std::to_string(d.lightmap.height) + " lightmap");
}

/// Every texel's encoding, once (zh3-optimal's and zh3-shared's axis search is the costly part),
/// already over π and scaled by 2^stops: what every layout below is made from.
struct EncodedTexels {
  std::vector<TexelValues> values;
  std::vector<std::array<Rgbd, 9>> l2;  ///< E_i / π per texel, for l2 and l2-deringed only
};
EncodedTexels encodeTexels(std::span<const Rgb> incident, int bands,
                           sh::IrradianceEncoding encoding, const LightmapDescription& d) {
  sh::checkBands(bands);
  const std::size_t n = std::size_t(bands) * std::size_t(bands);
  checkTexels(incident.size(), n, d);
  const double scale = std::exp2(d.exposureStops) / kPi;
  const std::size_t texels = d.lightmap.texels();
  EncodedTexels out;
  out.values.resize(texels);
  out.l2.resize(shRows(encoding) == 9 ? texels : 0);
  parallelFor(texels, 16, [&](std::size_t begin, std::size_t end) {
    sh::RgbSh light(bands);
    for (std::size_t t = begin; t < end; ++t) {
      std::copy_n(incident.data() + t * n, n, light.c.begin());
      const sh::EncodedIrradiance e = sh::encodeIrradiance(light, encoding);
      TexelValues& v = out.values[t];
      for (int ch = 0; ch < 3; ++ch) {
        v.a[ch] = e.sh[0][ch] * kY00 * scale;
        v.c[ch] = sh::bandOneVector(e.sh[1][ch], e.sh[2][ch], e.sh[3][ch]) * (kY1 * scale);
      }
      v.k = e.zonal * (kY20 * scale);
      v.axis = e.axis;
      if (!out.l2.empty())
        for (std::size_t i = 0; i < 9; ++i) out.l2[t][i] = e.sh[i] * scale;
    }
  });
  return out;
}

/// How the layers beyond L1 decode (the manifest's "decode"); `storedAxis` says where
/// zh3-optimal's and zh3-shared's axis is.
nlohmann::json decodeJson(sh::IrradianceEncoding encoding, const char* storedAxis) {
  nlohmann::json decode = {{"A", "the L1 layers' constant term L0 (f ~ A + c.n)"}};
  if (sh::isZonal(encoding)) {
    decode["axis"] = sh::storesAxis(encoding)
                         ? storedAxis
                         : "a = normalize(0.2126 c_r + 0.7152 c_g + 0.0722 c_b), +Z when zero";
    if (encoding == sh::IrradianceEncoding::ZH3Hallucinated)
      decode["zonal"] =
          "k = A (sqrt(5)/8) (0.08 r + 0.6 r^2), r = (sqrt(3)/2) |c.a| / A (A > 0; "
          "else k = 0); f = A + c.n + k (3 (a.n)^2 - 1)";
    if (encoding == sh::IrradianceEncoding::ZH3Shared)
      decode["zonal"] =
          "k = s A per channel, one number s per texel (k / A is the same in every channel): "
          "an engine stores s alone, 15 numbers with the octahedral axis";
  }
  if (encoding == sh::IrradianceEncoding::L1Geomerics)
    decode["nonLinear"] =
        "per channel: s = min(|c| / 2A, 1), p = 1 + 2s, alpha = (1 - s)/(1 + s), q = (1 + "
        "c.n/|c|)/2, f = A (alpha + (1 - alpha)(p + 1) q^p) (Hazel, Geomerics 2014); A + c.n "
        "where A <= 0 or c = 0";
  return decode;
}

}  // namespace

const char* toString(LightmapEngine e) {
  for (const EngineName& n : kEngines)
    if (n.e == e) return n.name;
  return "?";
}

std::vector<LightmapEngine> parseLightmapEngines(const std::string& list) {
  std::vector<LightmapEngine> out;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    const std::string name = list.substr(start, comma - start);
    const EngineName* found = nullptr;
    for (const EngineName& n : kEngines)
      if (name == n.name) found = &n;
    if (!found)
      throw Error("--engine '" + name.substr(0, 40) +
                  "': expected godot, godot-4.3 or bakery (or a comma-separated list of them)");
    if (std::find(out.begin(), out.end(), found->e) != out.end())
      throw Error("--engine names " + name + " twice");
    out.push_back(found->e);
    start = comma + 1;
  }
  return out;
}

EngineLightmaps encodeRadianceLightmap(std::span<const Rgb> radiance, const Mesh& mesh,
                                       const LightmapDescription& d) {
  checkTexels(radiance.size(), 1, d);
  const double scale = std::exp2(d.exposureStops);
  const std::size_t texels = radiance.size();
  Stack lm(d.lightmap.width, d.lightmap.height, 1);
  std::vector<std::uint8_t> preview(texels * 3);
  for (std::size_t t = 0; t < texels; ++t) {
    const Rgbd v = Rgbd(radiance[t]) * scale;
    lm.set(0, t, v);
    for (int ch = 0; ch < 3; ++ch)
      preview[3 * t + ch] = static_cast<std::uint8_t>(
          std::lround(255.0 * image::linearToSrgb(float(std::clamp(v[ch], 0.0, 1.0)))));
  }
  EngineLightmaps out;
  out.files.emplace_back("lightmap.exr", lm.exr(d.source + " (lightmap.exr)"));
  out.files.emplace_back("lightmap.png", image::encodePng8(d.lightmap.width, d.lightmap.height, 3,
                                                           preview, d.source + " (lightmap.png)"));
  out.manifest = baseManifest("lightmap", mesh, d);
  out.manifest["files"] = nlohmann::json::array(
      {{{"file", "lightmap.exr"},
        {"holds",
         "f (RGB float, linear): Godot's non-directional LightmapGI layer and Unity's "
         "unity_Lightmap both decode it as the sample itself"},
        {"decode", "f = sample"}},
       {{"file", "lightmap.png"},
        {"holds", "a preview: f clamped to [0, 1] and sRGB-encoded, 8 bits"},
        {"decode", "f = srgbToLinear(sample / 255) where f < 1"}}});
  out.files.emplace_back("lightmap.json", out.manifest.dump(2) + "\n");
  return out;
}

EngineLightmaps encodeIrradianceLightmaps(std::span<const Rgb> incident, int bands,
                                          sh::IrradianceEncoding encoding,
                                          std::span<const LightmapEngine> engines, const Mesh& mesh,
                                          const LightmapDescription& d) {
  if (engines.empty()) throw Error("engine lightmap: no engine layout asked for");
  const std::size_t texels = d.lightmap.texels();
  const int W = d.lightmap.width, H = d.lightmap.height;

  const EncodedTexels enc = encodeTexels(incident, bands, encoding, d);
  const std::vector<TexelValues>& values = enc.values;

  EngineLightmaps out;
  out.manifest = baseManifest("lightmap-sh", mesh, d);
  out.manifest["encoding"] = sh::toString(encoding);
  nlohmann::json files = nlohmann::json::array(), clamped = nlohmann::json::object();
  const char* l1Note = encoding == sh::IrradianceEncoding::L1Windowed
                           ? "band 1 windowed per channel to stay non-negative (l1-windowed)"
                       : encoding == sh::IrradianceEncoding::L2Deringed
                           ? "bands 0-1 of the deringed l2"
                           : "bands 0-1 of the irradiance";
  for (const LightmapEngine engine : engines) {
    std::size_t clampCount = 0;
    if (engine == LightmapEngine::Godot || engine == LightmapEngine::Godot43) {
      const bool packed = engine == LightmapEngine::Godot;
      Stack s(W, H, 4);
      for (std::size_t t = 0; t < texels; ++t) {
        const TexelValues& v = values[t];
        bool hit = false;
        Rgbd layer[4];
        for (int ch = 0; ch < 3; ++ch) {
          const Vec3d c = packed ? fitted(v.c[ch], v.a[ch], 4, hit) : v.c[ch];
          // Godot's layers 1..3: L1n1 (with n.y), L1_0 (n.z), L1p1 (n.x).
          const double l1[3] = {c.y, c.z, c.x};
          layer[0][ch] = packed ? v.a[ch] : v.a[ch] / kGodot43L0;
          for (int k = 0; k < 3; ++k)
            layer[k + 1][ch] = packed ? pack(l1[k], v.a[ch], 8) : l1[k] / kGodot43L1;
        }
        for (int k = 0; k < 4; ++k) s.set(k, t, layer[k]);
        clampCount += hit;
      }
      const std::string file = packed ? "godot.exr" : "godot-4.3.exr";
      out.files.emplace_back(file, s.exr(d.source + " (" + file + ")"));
      out.files.emplace_back(file + ".import", godotImport(4));
      files.push_back(
          {{"file", file},
           {"engine", packed ? "Godot 4.4+ LightmapGI, directional (SH L1, packed L1: godot "
                               "PR #96114)"
                             : "Godot 4.0-4.3 LightmapGI, directional (SH L1, unpacked)"},
           {"layout",
            "RGB float, W x 4H: layers L0, L1n1, L1_0, L1p1 stacked down the image "
            "(a Texture2DArray of 4 slices, slices/vertical = 4 in " +
                file + ".import)"},
           {"holds", l1Note},
           {"frame",
            "glTF axes: Godot imports glTF without changing them; the SH is in the "
            "LightmapGI node's space (keep it at the identity)"},
           {"decode",
            packed ? "f = L0 + 4 L0 ((L1n1 - 0.5) 2 n.y + (L1_0 - 0.5) 2 n.z + (L1p1 - 0.5) 2 n.x)"
                   : "f = 0.282095 L0 + 0.32573 (L1n1 n.y + L1_0 n.z + L1p1 n.x)"},
           {"source",
            packed ? "servers/rendering/renderer_rd/shaders/forward_clustered/"
                     "scene_forward_clustered.glsl (USE_LIGHTMAP, uses_sh); "
                     "modules/lightmapper_rd/lm_compute.glsl (MODE_PACK_L1_COEFFS)"
                   : "servers/rendering/renderer_rd/shaders/forward_clustered/"
                     "scene_forward_clustered.glsl of Godot 4.0-4.3 (USE_LIGHTMAP, uses_sh)"}});
    } else {
      Stack l0(W, H, 1), l1[3] = {Stack(W, H, 1), Stack(W, H, 1), Stack(W, H, 1)};
      for (std::size_t t = 0; t < texels; ++t) {
        const TexelValues& v = values[t];
        bool hit = false;
        Rgbd x, y, z;
        for (int ch = 0; ch < 3; ++ch) {
          // Unity's axes: x mirrored (left-handed; UnityGLTF's import negates x).
          const Vec3d c = fitted(Vec3d(-v.c[ch].x, v.c[ch].y, v.c[ch].z), v.a[ch], 2, hit);
          x[ch] = pack(c.x, v.a[ch], 4);
          y[ch] = pack(c.y, v.a[ch], 4);
          z[ch] = pack(c.z, v.a[ch], 4);
        }
        l0.set(0, t, v.a);
        l1[0].set(0, t, x);
        l1[1].set(0, t, y);
        l1[2].set(0, t, z);
        clampCount += hit;
      }
      out.files.emplace_back("bakery-L0.exr", l0.exr(d.source + " (bakery-L0.exr)"));
      const char* names[3] = {"bakery-L1x.exr", "bakery-L1y.exr", "bakery-L1z.exr"};
      for (int k = 0; k < 3; ++k)
        out.files.emplace_back(names[k], l1[k].exr(d.source + " (" + names[k] + ")"));
      files.push_back(
          {{"file", "bakery-L0.exr, bakery-L1x.exr, bakery-L1y.exr, bakery-L1z.exr"},
           {"engine",
            "Unity with Bakery's SH directional mode (L0 = unity_Lightmap; L1x, L1y, "
            "L1z = _RNM0, _RNM1, _RNM2)"},
           {"layout", "RGB float, W x H each; the L1 textures linear (sRGB off in Unity)"},
           {"holds", l1Note},
           {"frame",
            "Unity axes: x negated (Unity is left-handed; UnityGLTF's glTF import "
            "negates x)"},
           {"decode",
            "f = L0 + n.x (2 L1x - 1) 2 L0 + n.y (2 L1y - 1) 2 L0 + n.z (2 L1z - 1) 2 L0"},
           {"source",
            "Bakery.cginc, BakerySH (BAKERY_SHNONLINEAR_OFF; its non-linear option "
            "rescales by a Geomerics fit of the summed channels)"}});
    }
    clamped[toString(engine)] = clampCount;
    out.clampedTexels = std::max(out.clampedTexels, clampCount);
  }

  // What the encoding holds beyond L1, in prtkit's own layouts.
  if (sh::storesZonal(encoding)) {
    Stack zh(W, H, 1);
    for (std::size_t t = 0; t < texels; ++t) zh.set(0, t, values[t].k);
    out.files.emplace_back("zh3.exr", zh.exr(d.source + " (zh3.exr)"));
    const char* paper = "Roughton, Sloan et al., ZH3: Quadratic Zonal Harmonics, I3D 2024";
    const std::string source =
        encoding == sh::IrradianceEncoding::ZH3Shared
            ? std::string("prtkit's zh3-shared, a variant of ") + paper +
                  ": one zonal number shared in proportion to L0, about a searched axis"
            : std::string(paper);
    files.push_back({{"file", "zh3.exr"},
                     {"engine", "prtkit's ZH3 layout (no engine ships ZH3 lightmaps)"},
                     {"layout", "RGB float, W x H: k per channel"},
                     {"decode",
                      "f = A + c.n + k (3 (a.n)^2 - 1), A and c the L1 part "
                      "(f ~ A + c.n) of any layout above, in glTF axes"},
                     {"source", source}});
  }
  if (sh::storesAxis(encoding)) {
    Stack ax(W, H, 1);
    for (std::size_t t = 0; t < texels; ++t) ax.set(0, t, values[t].axis);
    out.files.emplace_back("zh3-axis.exr", ax.exr(d.source + " (zh3-axis.exr)"));
    files.push_back({{"file", "zh3-axis.exr"},
                     {"engine", "prtkit's ZH3 layout"},
                     {"layout", "RGB float, W x H: the zonal axis a (unit, glTF axes)"}});
  }
  if (shRows(encoding) == 9) {
    Stack l2(W, H, 9);
    for (std::size_t t = 0; t < texels; ++t)
      for (int i = 0; i < 9; ++i) l2.set(i, t, enc.l2[t][std::size_t(i)]);
    out.files.emplace_back("l2.exr", l2.exr(d.source + " (l2.exr)"));
    files.push_back({{"file", "l2.exr"},
                     {"engine", "prtkit's L2 layout (no engine ships L2 lightmaps)"},
                     {"layout",
                      "RGB float, W x 9H: layer i = E_i / pi, i = l(l+1)+m, stacked "
                      "down the image"},
                     {"decode",
                      "f = sum_i layer_i Y_i(n), prtkit's real SH with the "
                      "Condon-Shortley phase (docs/conventions.md), glTF axes"}});
  }
  out.manifest["decode"] = decodeJson(encoding, "a = zh3-axis.exr");
  out.manifest["files"] = std::move(files);
  out.manifest["clampedTexels"] = std::move(clamped);
  out.files.emplace_back("lightmap.json", out.manifest.dump(2) + "\n");
  return out;
}

LightmapLayers radianceLayers(std::span<const Rgb> radiance, const Mesh& mesh,
                              const LightmapDescription& d) {
  checkTexels(radiance.size(), 1, d);
  const float scale = float(std::exp2(d.exposureStops));
  LightmapLayers out;
  LightmapLayer f{"f", "f (RGB, linear): the lightmap itself", {}};
  f.texels.reserve(radiance.size());
  for (const Rgb& v : radiance) f.texels.push_back(v * scale);
  out.layers.push_back(std::move(f));
  out.manifest = baseManifest("lightmap", mesh, d);
  out.manifest["decode"] = {{"f", "f = f"}};
  return out;
}

LightmapLayers irradianceLayers(std::span<const Rgb> incident, int bands,
                                sh::IrradianceEncoding encoding, const Mesh& mesh,
                                const LightmapDescription& d) {
  const EncodedTexels enc = encodeTexels(incident, bands, encoding, d);
  const std::size_t texels = enc.values.size();
  LightmapLayers out;
  auto layer = [&](std::string name, std::string holds, auto value) {
    LightmapLayer l{std::move(name), std::move(holds), std::vector<Rgb>(texels)};
    for (std::size_t t = 0; t < texels; ++t) l.texels[t] = Rgb(value(t));
    out.layers.push_back(std::move(l));
  };
  nlohmann::json decode;
  if (shRows(encoding) == 9) {
    for (int i = 0; i < 9; ++i)
      layer("sh" + std::to_string(i), "E_" + std::to_string(i) + " / pi (i = l(l+1)+m)",
            [&](std::size_t t) { return enc.l2[t][std::size_t(i)]; });
    decode["f"] =
        "f = sum_i sh_i Y_i(n), prtkit's real SH with the Condon-Shortley phase "
        "(docs/conventions.md), glTF axes";
  } else {
    const auto& v = enc.values;
    layer("L0", "A: f's mean over normals (its constant term)", [&](std::size_t t) { return v[t].a; });
    const char* axes[3] = {"L1x", "L1y", "L1z"};
    for (int k = 0; k < 3; ++k)
      layer(axes[k], std::string("the ") + "xyz"[k] + " component of c per channel (glTF axes)",
            [&](std::size_t t) { return Rgbd(v[t].c[0][k], v[t].c[1][k], v[t].c[2][k]); });
    if (sh::storesZonal(encoding))
      layer("zonal", "k per channel: f += k (3 (a.n)^2 - 1)", [&](std::size_t t) { return v[t].k; });
    if (sh::storesAxis(encoding))
      layer("axis", "the zonal axis a (unit, glTF axes)", [&](std::size_t t) {
        return Rgbd(v[t].axis.x, v[t].axis.y, v[t].axis.z);
      });
    decode = decodeJson(encoding, "a = the axis layer");
    decode["f"] = sh::isZonal(encoding) ? "f = L0 + L1x n.x + L1y n.y + L1z n.z + k (3 (a.n)^2 - 1)"
                                        : "f = L0 + L1x n.x + L1y n.y + L1z n.z";
  }
  out.manifest = baseManifest("lightmap-sh", mesh, d);
  out.manifest["encoding"] = sh::toString(encoding);
  out.manifest["decode"] = std::move(decode);
  return out;
}

}  // namespace prt::io
