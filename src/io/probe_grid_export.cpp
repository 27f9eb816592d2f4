#include "prt/io/probe_grid_export.hpp"

#include <charconv>
#include <cstdlib>

#include "prt/core/error.hpp"
#include "prt/core/json.hpp"
#include "prt/core/version.hpp"

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

std::string formatProbeGrid(const ProbeGridExport& g, const ProbeGridConvention& convention) {
  checkProbeGrid(g.grid, "probe grid");
  const std::size_t b2 = std::size_t(g.bands) * std::size_t(g.bands);
  if (g.bands < 1 || g.radiance.size() != g.grid.probes() * b2)
    throw Error("probe grid: " + std::to_string(g.radiance.size()) + " coefficients for " +
                std::to_string(g.grid.probes()) + " probes of " + std::to_string(g.bands) +
                " bands");
  // Unity's world negates x: the grid's first probe is then its largest x, stepped by −sx.
  Vec3f origin = toWorld(convention, g.grid.origin);
  Vec3f spacing = g.grid.spacing;
  if (convention.engine == EngineLight::Unity) spacing.x = -spacing.x;
  const Vec3f n(float(g.grid.count[0] - 1), float(g.grid.count[1] - 1),
                float(g.grid.count[2] - 1));
  const Vec3f extent = g.grid.spacing * n;
  const Vec3f centre = toWorld(convention, g.grid.origin + extent * 0.5f);

  Json flat = Json::array();
  std::size_t perProbe = 0;
  sh::RgbSh probe(g.bands);
  for (std::size_t p = 0; p < g.grid.probes(); ++p) {
    std::copy_n(g.radiance.begin() + std::ptrdiff_t(p * b2), b2, probe.c.begin());
    const sh::RgbSh out =
        convention.engine ? toEngineConvention(*convention.engine, probe) : probe;
    perProbe = out.c.size();
    for (const Rgb& c : out.c)
      for (int ch = 0; ch < 3; ++ch) flat.push_back(shortest(c[ch]));
  }
  Json j;
  j["asset"] = {{"generator", std::string("prtkit ") + kVersion + " (prt export)"},
                {"format", "prtkit probe grid"},
                {"version", 1}};
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
  j["coefficients"] = {{"count", perProbe},
                       {"bands", perProbe == 9 ? 3 : g.bands},
                       {"layout", "probe-major, then coefficient, then r g b"}};
  j["probes"] = std::move(flat);
  return formatJson(j, 1) + "\n";
}

}  // namespace prt::io
