#include "demo_report.hpp"

#include <filesystem>

#include "prt/render/validate.hpp"

namespace prt::cli {

namespace {

/// One mode under one environment: its pictures, and its validation table as prt validate
/// --json reports it (render::reportJson).
Json modeJson(const ModeResult& m) {
  return {{"mode", toString(m.mode)},
          {"glossy", m.glossy},
          {"seconds", m.seconds},
          {"errorScale", m.errorScale},
          {"images", {{"prt", m.prtImage}, {"reference", m.refImage}, {"error", m.errImage}}},
          {"validation", Json::parse(render::reportJson(m.report))}};
}

Json texelEntryJson(const TexelRowEntry& e) {
  return {{"label", e.label}, {"image", e.image},     {"rows", e.rows},
          {"bytes", e.bytes}, {"relRmse", e.relRmse}, {"relRmseFull", e.relRmseFull}};
}

/// The per-texel row as the page's paragraph gives it.
Json texelRowJson(const TexelRow& t) {
  return {{"environment", t.environment},
          {"resolution", t.resolution},
          {"bands", t.bands},
          {"referenceImage", t.referenceImage},
          {"fullReferenceImage", t.fullReferenceImage},
          {"referenceVertices", t.referenceVertices},
          {"referenceSamples", t.referenceSamples},
          {"referenceNoise", t.referenceNoise},
          {"coarse", texelEntryJson(t.coarse)},
          {"texels", texelEntryJson(t.texels)},
          {"dense", texelEntryJson(t.dense)},
          {"seconds", t.seconds}};
}

Json haarEntryJson(const HaarRowEntry& e) {
  return {{"label", e.label},
          {"image", e.image},
          {"bytesPerVertex", e.bytesPerVertex},
          {"relRmse", e.relRmse},
          {"energyRel", e.energyRel}};
}

/// The all-frequency row as the page's table gives it.
Json haarRowJson(const HaarRow& r) {
  Json lights = Json::array();
  for (const HaarRowLight& L : r.lights)
    lights.push_back({{"environment", L.environment},
                      {"sh", haarEntryJson(L.sh)},
                      {"haar", haarEntryJson(L.haar)},
                      {"refStdErr", L.refStdErr}});
  return {{"bands", r.bands},
          {"resolution", r.resolution},
          {"terms", r.terms},
          {"lightTerms", r.lightTerms},
          {"vertices", r.vertices},
          {"referenceSamples", r.referenceSamples},
          {"bakeSeconds", r.bakeSeconds},
          {"seconds", r.seconds},
          {"lights", std::move(lights)}};
}

}  // namespace

Json environmentJson(const LightResult& L, const sh::RgbSh& light) {
  Json modes = Json::array();
  for (const ModeResult& m : L.modes) modes.push_back(modeJson(m));
  return {{"source", L.spec},
          {"name", L.name},
          {"light", shLightJson(light)},
          {"lightFile", "lights/" + L.name + ".json"},
          {"preview", L.preview},
          {"exposureStops", L.exposure},
          {"modes", std::move(modes)},
          {"comparison", L.comparison},
          {"turntable", L.turntable.empty() ? Json(nullptr) : Json(L.turntable)},
          {"frames", L.frames},
          {"seconds", L.seconds}};
}

void writeDemoReport(Report& report, DemoOutcome o, const std::string& output,
                     const std::vector<std::string>& environments) {
  namespace fs = std::filesystem;
  const fs::path out = fs::absolute(output);
  report.input(o.scene.path);
  for (const std::string& e : environments) report.input(e);
  const Json written = folderJson(output);
  report.outputFolder(written);
  report["folder"] = written;
  report["scene"] = {{"description", o.scene.description}, {"mesh", meshJson(o.scene.mesh)}};
  Json transfers = Json::array();
  for (const BakedTransfer& t : o.bake.transfers) transfers.push_back(transferJson(t));
  report["bake"] = {{"file", "scene.glb"},
                    {"bytes", fs::file_size(out / "scene.glb")},
                    {"seconds", o.bakeSeconds},
                    {"transfers", std::move(transfers)}};
  report["glossy"] = nullptr;
  if (o.glossy)
    report["glossy"] = {{"file", "glossy.glb"},
                        {"bytes", o.glossy->bytes},
                        {"seconds", o.glossy->seconds},
                        {"material", o.glossy->material.spec()},
                        {"transfer", transferJson(o.glossy->file.transfers.front())}};
  report["environments"] = std::move(o.environments);
  report["texels"] = texelRowJson(o.texels);
  report["haar"] = o.haar ? haarRowJson(*o.haar) : Json(nullptr);
  report["web"] = std::move(o.web);
  report["webMissing"] = o.webMissing.empty() ? Json(nullptr) : Json(o.webMissing);
  report["totalSeconds"] = o.totalSeconds;
  report.write();
}

}  // namespace prt::cli
