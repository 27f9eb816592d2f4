#pragma once
// prt web's work as a function, for prt demo (which puts the live viewer on its index.html).

#include <string>
#include <vector>

namespace prt::cli {

struct WebOptions {
  std::string bake;               ///< bake file (.glb)
  std::vector<std::string> envs;  ///< environments or SH light files; empty: builtin:sky
  std::string output;             ///< folder to write
  std::string rotate;             ///< initial light rotation "X,Y,Z" degrees
  std::string camera;             ///< initial camera, prt render's --camera syntax ("" = framed)
  std::string mode;               ///< initial transfer mode ("" = the richest)
  std::string material;           ///< glossy matrices' material ("" = the bake's)
  std::string toneMap = "aces";
  float exposure = 0.0f;
  int bands = 0;  ///< initial band count (0 = the bake's)
  int backgroundWidth = 512;
};

/// True when the page's built assets (index.html, prt-web.js) can be found.
bool webAssetsAvailable(std::string* why = nullptr);
/// Writes the browser viewer folder (docs/web.md). Throws prt::Error with one line.
void writeWebViewer(const WebOptions& options);

}  // namespace prt::cli
