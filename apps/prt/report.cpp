#include "report.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "cli.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/core/units.hpp"
#include "prt/core/version.hpp"
#include "prt/image/color.hpp"
#include "prt/sh/encode_irradiance.hpp"

namespace prt::cli {

Report::Report(std::string verb, std::string path) : path_(std::move(path)) {
  root_["verb"] = std::move(verb);
  root_["prtkitVersion"] = kVersion;
  root_["inputs"] = Json::array();
  root_["outputs"] = Json::array();
}

bool Report::toStandardOutput() const {
  return isStandardOutput(path_);
}

void Report::check(const std::vector<NamedPath>& outputs,
                   const std::vector<NamedPath>& inputs) const {
  if (!wanted()) return;
  if (toStandardOutput()) {
    for (const NamedPath& o : outputs)
      if (isStandardOutput(o.path))
        throw Error("--json - and " + o.option +
                    " - both name standard output; name a file for one of them");
    return;
  }
  std::vector<NamedPath> all = outputs;
  all.insert(all.begin(), {"--json", path_});
  checkOutputs(all, inputs);
  if (fileExtension(path_) != "json") throw Error(path_, "--json writes JSON: name a .json file");
  checkWritable(path_);
}

void Report::checkOutsideFolder(const NamedPath& folder) const {
  if (wanted() && !toStandardOutput() && detail::inside(path_, folder.path))
    throw Error(path_, "--json is inside the " + folder.option +
                           " folder, which is replaced as a whole; name a file outside it");
}

void Report::outputFolder(const Json& folder) {
  const std::filesystem::path root = folder.at("path").get<std::string>();
  for (const Json& f : folder.at("files"))
    output((root / f.at("path").get<std::string>()).string());
}

void Report::write() const {
  if (wanted()) writeFileAtomically(path_, formatJson(root_));
}

void addJsonOption(CLI::App* cmd, std::string& path) {
  cmd->add_option("--json", path,
                  "Also write what this run reports as JSON (- for standard output; "
                  "docs/formats-report.md)");
}

Json fileJson(const std::string& path) {
  // Standard output, a FIFO or a device (written directly, guard.hpp) has no size to report.
  std::error_code ec;
  if (isStandardOutput(path) || !std::filesystem::is_regular_file(path, ec))
    return {{"path", path}, {"bytes", nullptr}};
  const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
  return {{"path", path}, {"bytes", ec ? Json(nullptr) : Json(bytes)}};
}

Json folderJson(const std::string& folder, const std::string& shown) {
  namespace fs = std::filesystem;
  std::vector<std::pair<std::string, std::uintmax_t>> found;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(folder)) {
    if (!e.is_regular_file() || e.path().filename() == FolderOutput::kMarkName) continue;
    found.emplace_back(e.path().lexically_relative(folder).generic_string(), e.file_size());
  }
  std::sort(found.begin(), found.end());
  Json files = Json::array();
  std::uintmax_t total = 0;
  for (const auto& [name, bytes] : found) {
    files.push_back({{"path", name}, {"bytes", bytes}});
    total += bytes;
  }
  return {{"path", shown.empty() ? folder : shown}, {"files", std::move(files)}, {"bytes", total}};
}

std::vector<std::string> meshAttributes(const Mesh& m) {
  std::vector<std::string> a = {"normals"};
  if (!m.uvs.empty()) a.push_back("uvs");
  if (!m.lightmapUvs.empty()) a.push_back("lightmapUvs");
  if (!m.albedo.empty()) a.push_back("albedo");
  if (m.baseColour) a.push_back("baseColourTexture");
  return a;
}

Json meshJson(const Mesh& m) {
  Json parts = Json::array();
  for (const MeshPart& p : m.parts)
    parts.push_back(
        {{"name", p.name}, {"vertices", p.vertexCount}, {"triangles", p.triangleCount}});
  const Json attributes = meshAttributes(m);
  const Bounds b = computeBounds(m);
  return {{"source", m.source},
          {"vertices", m.vertexCount()},
          {"bounds", {{"min", {b.lo.x, b.lo.y, b.lo.z}}, {"max", {b.hi.x, b.hi.y, b.hi.z}}}},
          {"triangles", m.triangleCount()},
          {"parts", std::move(parts)},
          {"attributes", std::move(attributes)}};
}

namespace {

Json statsJson(const BakeStats& st) {
  return {{"rays", st.rays},
          {"raysPerSecond", st.raysPerSecond},
          {"threads", st.threads},
          {"totalSeconds", st.secondsTotal},
          {"directSeconds", st.secondsDirect},
          {"bounceSeconds", st.secondsBounce},
          {"bounceRays", st.raysBounce},
          {"stdErrT00Mean", st.stdErrT0Mean},
          {"stdErrT00Max", st.stdErrT0Max},
          {"stdErrWhiteSkyMean", st.stdErrConstMean},
          {"stdErrWhiteSkyMax", st.stdErrConstMax},
          {"raysPerRowAndPass", st.raysPerRowAndPass()}};
}

Json recipeJson(const BakeRecipe& r) {
  Json j = {{"samples", r.samples},
            {"bounces", r.effectiveBounces()},
            {"seed", r.seed},
            {"sampling", toString(r.sampling)},
            {"material", r.material.spec()}};
  if (r.adaptive()) j["targetError"] = r.targetError;
  return j;
}

}  // namespace

Json transferJson(const BakedTransfer& t) {
  const Transfer& x = t.transfer;
  Json j = {{"mode", toString(t.mode())},
            {"layout", toString(x.layout())},
            {"domain", toString(x.domain())},
            {"bands", x.bands()},
            {"coefficients", x.coeffs()},
            {"channels", x.channels()},
            {"rows", {{"first", x.rows().first}, {"end", x.rows().end()}}},
            {"denseBytes", x.shape().denseBytes()},
            {"bytes", x.bytes()},
            {"representation", x.compressed() ? "cpca" : "dense"}};
  if (x.domain() == TransferDomain::Texels) {
    const TransferShape::LightmapSize& lm = x.shape().lightmap;
    j["lightmap"] = {{"width", lm.width}, {"height", lm.height}, {"padding", lm.padding}};
  }
  if (x.compressed()) {
    const CpcaStats& s = t.compression.stats;
    j["compression"] = {{"clusters", x.cpca().clusters},
                        {"components", x.cpca().basisCount},
                        {"seed", t.compression.fit.seed},
                        {"ratio", s.compressionRatio},
                        {"relativeRms", s.relativeRms},
                        {"snrDb", std::isfinite(s.snrDb) ? Json(s.snrDb) : Json(nullptr)},
                        {"squaredError", s.squaredError},
                        {"maxRowError", s.maxRowError},
                        {"iterations", s.iterations},
                        {"seconds", s.seconds}};
  }
  j["recipe"] = recipeJson(t.recipe);
  j["stats"] = statsJson(t.stats);
  return j;
}

Json cameraJson(const render::Camera& c) {
  return {{"eye", {c.eye.x, c.eye.y, c.eye.z}},
          {"target", {c.target.x, c.target.y, c.target.z}},
          {"up", {c.up.x, c.up.y, c.up.z}},
          {"fovYDegrees", c.fovY}};
}

ShSummary summarizeSh(const sh::RgbSh& c) {
  ShSummary s;
  const double k = 1.0 / std::sqrt(4 * kPi);
  s.meanRadiance = Vec3d(c.c[0]) * k;
  for (int l = 0; l < c.bands; ++l) {
    double e = 0;
    for (int m = -l; m <= l; ++m) {
      const double y = image::luminance(c.c[l * (l + 1) + m]);
      e += y * y;
    }
    s.bandEnergy.push_back(e);
  }
  // With Y1,-1 = −c y, Y1,0 = c z, Y1,1 = −c x (docs/conventions.md), the linear band of a lobe
  // along d is ∝ (−d_y, d_z, −d_x).
  if (c.bands >= 2) {
    const Vec3d d(-image::luminance(c.c[3]), -image::luminance(c.c[1]), image::luminance(c.c[2]));
    const double n = length(d);
    if (n > 0) {
      s.hasDirection = true;
      s.dominantDirection = d * (1.0 / n);
    }
  }
  return s;
}

Json shLightJson(const sh::RgbSh& c) {
  Json rows = Json::array();
  for (const Rgb& v : c.c) rows.push_back(jsonFloats(&v.x, 3));
  const ShSummary s = summarizeSh(c);
  return {{"bands", c.bands},
          {"coefficients", std::move(rows)},
          {"meanRadiance", {s.meanRadiance.x, s.meanRadiance.y, s.meanRadiance.z}},
          {"bandEnergy", s.bandEnergy},
          {"dominantDirection", s.hasDirection ? Json{s.dominantDirection.x, s.dominantDirection.y,
                                                      s.dominantDirection.z}
                                               : Json(nullptr)}};
}

Json irradianceEncodingsJson(const sh::RgbSh& radiance, const sh::RgbSh& reference) {
  Json out = Json::array();
  for (sh::IrradianceEncoding e : sh::kIrradianceEncodings) {
    const sh::EncodingError err = sh::encodingError(reference, sh::encodeIrradiance(radiance, e));
    out.push_back({{"encoding", sh::toString(e)},
                   {"numbers", sh::storedNumbers(e)},
                   {"relativeRms", err.relativeRms},
                   {"negativeShare", err.negativeShare}});
  }
  return out;
}

}  // namespace prt::cli
