#pragma once
// A verb's machine-readable report: `--json PATH` (`-` for standard output) on every verb that
// reports something — info, bake, light, compress, validate, reference, render, unwrap, merge,
// export, web, demo, and view's headless runs (--headless; a window's session reports nothing).
// One schema style for all of them (docs/formats-report.md): one JSON object per run whose first
// members are
//
//   "verb": "bake", "prtkitVersion": "0.1.0", "inputs": ["bunny.obj"], "outputs": ["b.glb"]
//
// followed by the verb's own. Keys are camelCase; times are seconds and sizes bytes, named so
// (…Seconds, …Bytes); counts are integers; colours [r, g, b]; directions [x, y, z]. The same
// thing is the same object in every verb: a transfer as `bake` reports it is what `info` says
// of it in the file, a light as `light` writes it is what `info` says of the file.
//
// The report is written last, atomically, once everything else was written: a failed run
// leaves none. With `--json -` the verb prints nothing else on standard output.

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "guard.hpp"
#include "prt/core/json.hpp"
#include "prt/core/vec.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/render/camera.hpp"
#include "prt/sh/sh.hpp"

namespace prt::cli {

class Report {
 public:
  /// `path` is what --json gave ("" for no report).
  Report(std::string verb, std::string path);

  bool wanted() const { return !path_.empty(); }
  /// True when the report goes to standard output (--json -): the verb's text must not.
  bool toStandardOutput() const;
  /// Refuses a report path that is an input or another output (checkOutputs), or standard
  /// output when another output already is; checks it can be written. Call before any work.
  void check(const std::vector<NamedPath>& outputs, const std::vector<NamedPath>& inputs) const;
  /// Refuses a report path inside `folder`, an output folder written as a whole (FolderOutput).
  void checkOutsideFolder(const NamedPath& folder) const;

  void input(const std::string& path) { root_["inputs"].push_back(path); }
  void output(const std::string& path) { root_["outputs"].push_back(path); }
  /// Every file of a folder as folderJson lists it, as outputs (FOLDER/RELATIVE).
  void outputFolder(const Json& folder);
  /// The verb's own members.
  Json& operator[](const char* key) { return root_[key]; }

  /// Writes the report (atomically; nothing when not wanted).
  void write() const;

 private:
  std::string path_;
  Json root_;
};

/// Adds --json to `cmd`.
void addJsonOption(CLI::App* cmd, std::string& path);

/// A file as written: {"path", "bytes"} (its size on disk; null for standard output, a FIFO
/// or a device).
Json fileJson(const std::string& path);
/// A folder as written: {"path", "files": [{"path", "bytes"}], "bytes"}: every regular file in
/// it (paths relative to it, '/'-separated, sorted; a made folder's mark left out) and their
/// total. `shown` is the path the report names it by (default `folder`).
Json folderJson(const std::string& folder, const std::string& shown = "");

/// What a scene is: {"source", "vertices", "triangles", "parts": [{"name", "vertices",
/// "triangles"}], "attributes": ["normals", "uvs", "albedo"]}.
/// The mesh's attributes besides positions, as reports and prt info name them: normals, uvs,
/// lightmapUvs, albedo.
std::vector<std::string> meshAttributes(const Mesh& m);
Json meshJson(const Mesh& mesh);
/// One transfer of a bake: {"mode", "layout", "bands", "coefficients", "channels", "rows":
/// {"first", "end"}, "bytes", "representation": "dense"|"cpca", "compression" (CPCA only),
/// "recipe": {...}, "stats": {...}}.
Json transferJson(const BakedTransfer& t);
/// A camera: {"eye", "target", "up", "fovYDegrees"}.
Json cameraJson(const render::Camera& c);
/// SH lighting: {"bands", "coefficients": [[r, g, b], …], "meanRadiance", "bandEnergy",
/// "dominantDirection" (null below 2 bands or for a zero band 1)}.
Json shLightJson(const sh::RgbSh& c);
/// Every irradiance encoding of `radiance` (sh/irradiance_encoding.hpp) and what it loses
/// against the irradiance of `reference`: [{"encoding", "numbers", "relativeRms",
/// "negativeShare"}], in kIrradianceEncodings' order.
Json irradianceEncodingsJson(const sh::RgbSh& radiance, const sh::RgbSh& reference);

/// The summary of SH lighting both the text and the report of `prt info` print.
struct ShSummary {
  Vec3d meanRadiance{0.0};         ///< L00 / √(4π): radiance averaged over the sphere
  std::vector<double> bandEnergy;  ///< Σ_m (luminance of L_lm)² per band
  bool hasDirection = false;
  Vec3d dominantDirection{0.0};  ///< from band 1 (unit), when hasDirection
};
ShSummary summarizeSh(const sh::RgbSh& c);

}  // namespace prt::cli
