#pragma once
// prt web's work as a function, for prt demo (which puts the live viewer on its index.html).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "prt/core/json.hpp"

namespace prt::cli {

/// The largest bake prt-data.js carries inside itself (base64, 4/3 of the bytes): the page then
/// opens from disk. A larger one goes beside it as kBakeFileName, fetched by the page over http
/// (a browser refuses file:// fetches), without the 4/3 and the decoding of a script that size.
inline constexpr std::uint64_t kMaxEmbeddedBakeBytes = std::uint64_t(32) << 20;
inline constexpr const char* kBakeFileName = "bake.glb";
/// Beside it, per-texel glossy matrices' points (little-endian float32, render::packTexelPoints).
inline constexpr const char* kTexelPointsFileName = "texel-points.bin";
/// The largest bake the page takes: its transfer is uploaded as float textures, and Chromium
/// holds the file, the parsed glTF and the textures at once (docs/web.md, "Large bakes").
inline constexpr std::uint64_t kMaxPageBakeBytes = std::uint64_t(1) << 30;

struct WebOptions {
  std::string bake;               ///< bake file (.glb)
  std::vector<std::string> envs;  ///< environments or SH light files; empty: builtin:sky
  std::string output;             ///< folder to write
  std::string rotate;             ///< initial light rotation "X,Y,Z" degrees
  std::string camera;             ///< initial camera, prt render's --camera syntax ("" = framed)
  std::string mode;               ///< initial transfer mode ("" = the richest)
  std::string material;           ///< glossy matrices' material ("" = the bake's)
  /// The irradiance encoding a per-vertex matrix transfer opens drawn through ("" or "none" =
  /// PRT's own radiance; dense matrices are drawn through l2 then: docs/web.md).
  std::string encoding;
  std::string toneMap = "aces";
  /// Initial exposure in stops; nullopt: auto (render::relitSurvey of the initial transfer and
  /// environment, relit on the CPU through the initial camera).
  std::optional<float> exposure;
  int bands = 0;  ///< initial band count (0 = the bake's)
  int terms = 0;  ///< a Haar bake's initial light terms (0 = haar::kDefaultLightTerms)
  int backgroundWidth = 512;
  std::string embed = "auto";  ///< auto | always | never: the bake inside prt-data.js or beside
  std::string reportAs;        ///< the folder's name in the closing line ("" = output)
  std::string json;            ///< prt web --json (the verb's; writeWebViewer ignores it)
};

/// True when the page's built assets (index.html, prt-web.js) can be found.
bool webAssetsAvailable(std::string* why = nullptr);
/// Writes the browser viewer folder (docs/web.md). Throws prt::Error with one line. Returns
/// what prt web --json reports after the envelope (docs/formats-report.md): `folder`
/// (folderJson, named as reportAs), `bake`, `mesh`, `transfers`, `bands`, `environments`,
/// `view`.
Json writeWebViewer(const WebOptions& options);

}  // namespace prt::cli
