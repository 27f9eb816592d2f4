#include "prt/io/probe_grid_export.hpp"

#include "glb.hpp"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cstdint>
#include <cstdlib>

#include "prt/core/base64.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/core/json.hpp"
#include "prt/core/version.hpp"
#include "prt/image/data_texture.hpp"

namespace prt::io {

namespace {

constexpr const char* kConventions = "prtkit, threejs, unity or gltf-ibl";

/// A point or offset of glTF's frame in the convention's world: Unity's negates x (as glTF
/// importers do, and as the unity light's coefficients are turned: engine_light.hpp).
Vec3f toWorld(const ProbeGridConvention& c, Vec3f v) {
  if (c.engine == EngineLight::Unity) v.x = -v.x;
  return v;
}

/// A float as the shortest decimal that reads back to it (not its 17-digit double expansion).
double shortest(float f) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text - 1, f).ptr;
  *end = '\0';
  return std::strtod(text, nullptr);
}

Json triple(const Vec3f& v) { return Json::array({shortest(v.x), shortest(v.y), shortest(v.z)}); }

}  // namespace

std::vector<float> lightProbeGridAtlas(const ProbeGrid& grid, std::span<const Rgb> threeJs) {
  const int nx = grid.count[0], ny = grid.count[1], nz = grid.count[2];
  const int block = nz + 2 * kLightProbeGridPadding;
  PRT_CHECK(threeJs.size() == grid.probes() * 9, "nine coefficients per probe");
  std::vector<float> atlas(std::size_t(nx) * ny * 7 * block * 4, 0.0f);
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x) {
        // The 27 floats c0.r c0.g c0.b c1.r ... c8.b, then a 0: seven texels of four.
        float flat[28] = {};
        const Rgb* c = threeJs.data() + grid.row(x, y, z) * 9;
        for (int k = 0; k < 9; ++k)
          for (int ch = 0; ch < 3; ++ch) flat[3 * k + ch] = c[k][ch];
        for (int t = 0; t < 7; ++t) {
          // Layer z's slice, and the padding slice beside it at either end.
          const int base = t * block;
          for (int slice : {base + kLightProbeGridPadding + z, z == 0 ? base : -1,
                            z == nz - 1 ? base + kLightProbeGridPadding + nz : -1}) {
            if (slice < 0) continue;
            float* texel = atlas.data() + ((std::size_t(slice) * ny + y) * nx + x) * 4;
            std::copy_n(flat + 4 * t, 4, texel);
          }
        }
      }
  return atlas;
}

ProbeGridConvention parseProbeGridConvention(std::string_view name) {
  if (name == "prtkit") return {};
  if (name == "cmgen")
    throw Error("--engine cmgen: cmgen's text holds one light, not a grid (expected " +
                std::string(kConventions) + ")");
  try {
    return {parseEngineLight(name)};
  } catch (const Error&) {
    throw Error("--engine " + std::string(name) + ": unknown (expected " + kConventions + ")");
  }
}

const char* probeGridConventionName(const ProbeGridConvention& c) {
  return c.engine ? engineLightName(*c.engine) : "prtkit";
}

namespace {

/// Every probe's coefficients in the convention (probes × K), K per probe.
struct Converted {
  std::vector<Rgb> coefficients;
  std::size_t perProbe = 0;
};

Converted convert(const ProbeGridExport& g, const ProbeGridConvention& convention) {
  checkProbeGrid(g.grid, "probe grid");
  const std::size_t b2 = std::size_t(g.bands) * std::size_t(g.bands);
  if (g.bands < 1 || g.radiance.size() != g.grid.probes() * b2)
    throw Error("probe grid: " + std::to_string(g.radiance.size()) + " coefficients for " +
                std::to_string(g.grid.probes()) + " probes of " + std::to_string(g.bands) +
                " bands");
  Converted out;
  sh::RgbSh probe(g.bands);
  for (std::size_t p = 0; p < g.grid.probes(); ++p) {
    std::copy_n(g.radiance.begin() + std::ptrdiff_t(p * b2), b2, probe.c.begin());
    const sh::RgbSh c = convention.engine ? toEngineConvention(*convention.engine, probe) : probe;
    out.perProbe = c.c.size();
    out.coefficients.insert(out.coefficients.end(), c.c.begin(), c.c.end());
  }
  return out;
}

/// What the JSON file and the glTF extension share: provenance, the convention, the grid in the
/// engine's world, three.js LightProbeGrid's parameters (the atlas' shape; its data is the
/// caller's) and the coefficients' layout.
Json describe(const ProbeGridExport& g, const ProbeGridConvention& convention,
              std::size_t perProbe) {
  // Unity's world negates x: the grid's first probe is then its largest x, stepped by −sx.
  const Vec3f origin = toWorld(convention, g.grid.origin);
  Vec3f spacing = g.grid.spacing;
  if (convention.engine == EngineLight::Unity) spacing.x = -spacing.x;
  const Vec3f n(float(g.grid.count[0] - 1), float(g.grid.count[1] - 1),
                float(g.grid.count[2] - 1));
  const Vec3f centre = toWorld(convention, g.grid.origin + g.grid.spacing * n * 0.5f);
  // three.js r187's LightProbeGrid puts its probes at the centres of the cells of its box, as
  // ours are: the box is a cell per probe (r184–r186 put them on the box's corners, (n − 1)·s).
  const Vec3f extent =
      g.grid.spacing * Vec3f(float(g.grid.count[0]), float(g.grid.count[1]), float(g.grid.count[2]));
  Json j;
  j["source"] = g.source;
  j["light"] = g.light;
  j["rotateDegrees"] = g.rotateDegrees;
  j["exposureStops"] = g.exposureStops;
  j["engine"] = probeGridConventionName(convention);
  j["grid"] = {{"origin", triple(origin)},
               {"spacing", triple(spacing)},
               {"count", g.grid.count},
               {"order", "x + nx (y + ny z)"}};
  if (convention.engine != EngineLight::Unity)
    j["lightProbeGrid"] = {{"position", triple(centre)},
                           {"width", shortest(extent.x)},
                           {"height", shortest(extent.y)},
                           {"depth", shortest(extent.z)},
                           {"resolution", g.grid.count}};
  if (convention.engine == EngineLight::ThreeJs)
    j["lightProbeGrid"]["atlas"] = {
        {"size",
         {g.grid.count[0], g.grid.count[1],
          7 * (g.grid.count[2] + 2 * kLightProbeGridPadding)}},
        {"padding", kLightProbeGridPadding},
        {"format", "RGBA, float32 little-endian, texel (x, y, slice) at ((slice ny + y) nx + x) 4"}};
  j["coefficients"] = {{"count", perProbe},
                       {"bands", perProbe == 9 ? 3 : g.bands},
                       {"layout", "probe-major, then coefficient, then r g b"}};
  return j;
}

std::string generator() { return std::string("prtkit ") + kVersion + " (prt export)"; }

}  // namespace

std::string formatProbeGrid(const ProbeGridExport& g, const ProbeGridConvention& convention) {
  const Converted c = convert(g, convention);
  Json j;
  j["asset"] = {{"generator", generator()}, {"format", "prtkit probe grid"}, {"version", 1}};
  const Json shared = describe(g, convention, c.perProbe);
  for (const auto& [key, value] : shared.items()) j[key] = value;
  if (convention.engine == EngineLight::ThreeJs) {
    const std::vector<float> atlas = lightProbeGridAtlas(g.grid, c.coefficients);
    std::string bytes(atlas.size() * sizeof(float), '\0');
    for (std::size_t i = 0; i < atlas.size(); ++i) {
      const std::uint32_t u = std::bit_cast<std::uint32_t>(atlas[i]);
      for (int b = 0; b < 4; ++b) bytes[4 * i + b] = char((u >> (8 * b)) & 0xff);
    }
    j["lightProbeGrid"]["atlas"]["data"] = base64(bytes);
  }
  Json flat = Json::array();
  for (const Rgb& v : c.coefficients)
    for (int ch = 0; ch < 3; ++ch) flat.push_back(shortest(v[ch]));
  j["probes"] = std::move(flat);
  return formatJson(j, 1) + "\n";
}

void writeProbeGridGltf(const std::string& path, const ProbeGridExport& g,
                        const ProbeGridConvention& convention) {
  const Converted c = convert(g, convention);
  Json ext = describe(g, convention, c.perProbe);
  glb::BinaryChunk bin;
  // Rgb is three packed floats: the coefficients are the accessor's VEC3 elements as they lie.
  static_assert(sizeof(Rgb) == 3 * sizeof(float));
  const int probes = bin.view(c.coefficients.data(), c.coefficients.size() * sizeof(Rgb), 0, 0,
                              "probes");
  ext["probes"] = bin.accessor(probes, 0, c.coefficients.size(), "VEC3", 5126, "probes");
  std::vector<float> atlas;
  if (convention.engine == EngineLight::ThreeJs) {
    atlas = lightProbeGridAtlas(g.grid, c.coefficients);
    const int view = bin.view(atlas.data(), atlas.size() * sizeof(float), 0, 0,
                              "LightProbeGrid atlas");
    ext["lightProbeGrid"]["atlas"]["accessor"] =
        bin.accessor(view, 0, atlas.size() / 4, "VEC4", 5126, "LightProbeGrid atlas");
  }
  Json gltf;
  gltf["asset"] = {{"generator", generator()}, {"version", "2.0"}};
  gltf["extensionsUsed"] = Json::array({kProbeGridExtension});
  gltf["extensions"][kProbeGridExtension] = std::move(ext);
  gltf["accessors"] = bin.accessors();
  gltf["bufferViews"] = bin.views();
  gltf["buffers"] = Json::array({{{"byteLength", bin.length()}}});
  std::string text = gltf.dump();
  if (glb::fileBytes(text, bin) > std::uint64_t(0xffffffffu))
    throw Error(path, "the grid exceeds the 4 GiB a GLB file can hold");
  writeFileAtomically(path, [&](std::ostream& os) { glb::write(os, std::move(text), bin); });
}

std::string encodeProbeGridExr(const ProbeGridExport& g, const ProbeGridConvention& convention,
                               const std::string& name) {
  const Converted c = convert(g, convention);
  const int nx = g.grid.count[0], ny = g.grid.count[1], nz = g.grid.count[2];
  if (std::int64_t(ny) * nz > 65535)
    throw Error(name, "an EXR volume stacks the grid's " + std::to_string(nz) + " z slices of " +
                          std::to_string(ny) + " rows: " + std::to_string(ny * nz) +
                          " rows, more than the 65,535 it holds (write .json or .glb)");
  image::DataTexture volume;
  volume.width = nx;
  volume.height = ny * nz;
  const std::size_t K = c.perProbe;
  const char* channel[3] = {"R", "G", "B"};
  for (std::size_t k = 0; k < K; ++k)
    for (int ch = 0; ch < 3; ++ch) {
      volume.channelNames.push_back("sh" + std::to_string(k) + "." + channel[ch]);
      std::vector<float> plane(g.grid.probes());
      // Probe (x, y, z) is row x + nx (y + ny z) of the grid and texel (x, z·ny + y): the same
      // order, so plane element p is probe p.
      for (std::size_t p = 0; p < g.grid.probes(); ++p) plane[p] = c.coefficients[p * K + k][ch];
      volume.planes.push_back(std::move(plane));
    }
  Json j;
  j["asset"] = {{"generator", generator()}, {"format", "prtkit probe grid"}, {"version", 1}};
  const Json shared = describe(g, convention, K);  // (items() of a temporary would dangle)
  for (const auto& [key, value] : shared.items()) j[key] = value;
  j["volume"] = {{"width", nx},
                 {"height", ny * nz},
                 {"texel", "probe (x, y, z) at column x, row z ny + y (row 0 the top)"},
                 {"channels", "shK.R, shK.G, shK.B: coefficient K of the convention"}};
  volume.attributes.emplace_back("prtkit", formatJson(j, 1));
  return image::encodeExrData(volume, name);
}

}  // namespace prt::io
