#pragma once
// Loading an environment from what a user names: an image file (lat-long, probe, cross), a folder
// of six cube faces (posx negx posy negy posz negz with any readable extension, e.g. the GAMES202
// course's Skybox/posx.jpg), or builtin:NAME. The layout is detected from the aspect ratio
// (2:1 lat-long, 1:1 probe, 3:4 vertical cross, 4:3 horizontal cross) or from the folder, unless
// given explicitly.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "prt/envmap/environment.hpp"
#include "prt/image/image_io.hpp"

namespace prt::envmap {

struct LoadOptions {
  std::optional<Layout> layout;  ///< override; detected when empty
  image::LdrDecode ldrDecode = image::LdrDecode::Srgb;
  int builtinTexelWidth = 512;
};

struct LoadedEnvironment {
  Environment env;
  std::string layout;                   ///< "latlong" … "faces", or "builtin"
  std::vector<std::string> files;       ///< the files read (one, six, or none for builtins)
  std::vector<image::ReadStats> stats;  ///< per file: what the pixel policy repaired
};

/// Reads the six faces of a folder in the order given by `names` (e.g. kFaceNames or the
/// course's order); checks they exist, are square and share one size.
std::array<image::Image, 6> readFaceFolder(const std::string& dir,
                                           const std::array<const char*, 6>& names,
                                           image::LdrDecode decode,
                                           std::vector<std::string>* files = nullptr,
                                           std::vector<image::ReadStats>* stats = nullptr);

/// An environment from an image in memory (a render, an application's array): `layout` if
/// given, else detected from the aspect ratio, and checked as loadEnvironment checks a file's
/// (`name` in messages; the layout used is written to `used`). Faces need six images
/// (Environment::cube).
Environment environmentFromImage(image::Image img, std::optional<Layout> layout,
                                 const std::string& name, Layout* used = nullptr);

/// Loads an image file, a face folder or builtin:NAME. Throws prt::Error naming the file, also
/// when every pixel read was NaN or infinite (nothing would be left but black). The
/// environment's source() is `input`.
LoadedEnvironment loadEnvironment(const std::string& input, const LoadOptions& options = {});
/// Negative pixels whose magnitudes sum to at most this fraction of an image's light are the
/// harmless residue of lossy EXR compression (Blender's studio.exr: 0.002 %) and are clamped
/// silently; more is said, as it changes the light.
inline constexpr double kNegativeLightWarning = 1e-4;
/// One line per file whose pixels the policy repaired and whose light it changed: "FILE: N
/// pixels with NaN/Inf set to 0", "FILE: M pixels with negative values clamped to 0 (x% of its
/// light)" (past kNegativeLightWarning) — what every verb that loads an environment warns.
std::vector<std::string> repairWarnings(const LoadedEnvironment& loaded);
/// True when any file of `loaded` had a pixel repaired (NaN/Inf or negative, however small):
/// what --strict refuses.
bool anyPixelRepaired(const LoadedEnvironment& loaded);

}  // namespace prt::envmap
