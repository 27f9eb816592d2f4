#include "web_report.hpp"

#include <array>
#include <optional>

#include "args.hpp"
#include "prt/render/camera.hpp"
#include "report.hpp"
#include "transfer_options.hpp"

namespace prt::cli {

namespace {

/// What the page opens on (report, not page data): the transfer it picks, the first
/// environment, the bands, rotation, exposure, tone map and camera (null: framed for its canvas).
Json initialViewJson(const WebOptions& a, const BakeFile& bake, const WebEnvironment& env,
                     int bands, float exposure) {
  std::optional<TransferMode> mode;
  if (!a.mode.empty()) mode = parseTransferMode(a.mode);
  const BakedTransfer& t = prt::pickTransfer(bake, mode, {}, a.bake);
  const std::array<double, 3> euler = parseEulerDegrees(a.rotate);
  Json camera = nullptr;
  if (!a.camera.empty())
    camera = cameraJson(render::parseCamera(
        a.camera, render::frameCamera(render::meshFraming(bake.mesh), 640, 480)));
  return {{"transfer",
           {{"mode", toString(t.mode())},
            {"layout", toString(t.transfer.layout())},
            {"representation", t.transfer.compressed() ? "cpca" : "dense"}}},
          {"encoding", a.encoding.empty() ? "none" : a.encoding},
          {"environment", env.name},
          {"bands", a.bands > 0 ? a.bands : bands},
          {"rotationDegrees", {euler[0], euler[1], euler[2]}},
          {"exposureStops", exposure},
          {"exposureAuto", !a.exposure.has_value()},
          {"toneMap", a.toneMap},
          {"camera", std::move(camera)}};
}

}  // namespace

Json webReport(const WebOptions& a, const BakeFile& bake, const std::vector<WebEnvironment>& envs,
               const WebPageFacts& f) {
  Json report;
  report["folder"] = folderJson(a.output, f.shown);
  report["bake"] = {{"path", a.bake},
                    {"bytes", f.bakeBytes},
                    {"embedded", f.embedded},
                    {"file", f.embedded ? Json(nullptr) : Json(kBakeFileName)},
                    {"texelPointsBytes", f.texelPointsBytes}};
  report["mesh"] = meshJson(bake.mesh);
  report["transfers"] = Json::array();
  for (const BakedTransfer& t : bake.transfers) {
    Json tj = transferJson(t);
    // Glossy matrices: the material the page shades them with (--material or the bake's).
    if (f.glossy.is_object() && f.glossy.contains(toString(t.mode())))
      tj["pageMaterial"] = f.glossy[toString(t.mode())]["material"];
    report["transfers"].push_back(std::move(tj));
  }
  report["bands"] = f.bands;
  report["environments"] = Json::array();
  for (const WebEnvironment& e : envs)
    report["environments"].push_back(
        {{"source", e.spec},
         {"name", e.name},
         {"light", shLightJson(e.light)},
         {"background", {{"width", e.background.width}, {"height", e.background.height}}}});
  report["view"] = initialViewJson(a, bake, envs.front(), f.bands, f.exposureStops);
  return report;
}

}  // namespace prt::cli
