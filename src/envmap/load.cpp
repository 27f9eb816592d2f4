#include <cstdio>
#include "prt/envmap/load.hpp"

#include <filesystem>

#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/envmap/builtin.hpp"

namespace prt::envmap {

namespace fs = std::filesystem;

std::array<image::Image, 6> readFaceFolder(const std::string& dir,
                                           const std::array<const char*, 6>& names,
                                           image::LdrDecode decode, std::vector<std::string>* files,
                                           std::vector<image::ReadStats>* stats) {
  std::array<image::Image, 6> faces;
  std::string first;
  for (int i = 0; i < 6; ++i) {
    std::string found;
    for (const char* ext :
         {"hdr", "exr", "png", "jpg", "jpeg", "HDR", "EXR", "PNG", "JPG", "JPEG"}) {
      const fs::path p = fs::path(dir) / (std::string(names[i]) + "." + ext);
      std::error_code ec;
      if (fs::exists(p, ec)) {
        found = p.string();
        break;
      }
    }
    if (found.empty())
      throw Error(dir, std::string("missing cube face '") + names[i] +
                           "' (expected posx negx posy negy posz negz .hdr/.exr/.png/.jpg)");
    image::ReadStats s;
    faces[i] = image::readImage(found, {decode}, &s);
    if (faces[i].width != faces[i].height)
      throw Error(found, "cube face is " + std::to_string(faces[i].width) + "x" +
                             std::to_string(faces[i].height) + ", faces must be square");
    if (i > 0 && faces[i].width != faces[0].width)
      throw Error(found, "cube face is " + std::to_string(faces[i].width) + "x" +
                             std::to_string(faces[i].height) + " but " +
                             fs::path(first).filename().string() + " is " +
                             std::to_string(faces[0].width) + "x" +
                             std::to_string(faces[0].height));
    if (i == 0) first = found;
    if (files) files->push_back(found);
    if (stats) stats->push_back(s);
  }
  return faces;
}

Environment environmentFromImage(image::Image img, std::optional<Layout> given,
                                 const std::string& name, Layout* used) {
  const Layout layout = given ? *given : detectLayout(img.width, img.height, name);
  if (used) *used = layout;
  const std::string dims = std::to_string(img.width) + "x" + std::to_string(img.height);
  switch (layout) {
    case Layout::LatLong:
      if (img.width != 2 * img.height)
        throw Error(name, "is " + dims + ", a lat-long image must be 2:1");
      return Environment::latLong(std::move(img));
    case Layout::Probe:
      if (img.width != img.height)
        throw Error(name, "is " + dims + ", a light probe must be square");
      return Environment::probe(std::move(img));
    case Layout::VCross:
      if (4 * img.width != 3 * img.height || img.width % 3 != 0)
        throw Error(name, "is " + dims + ", a vertical cross must be 3N x 4N");
      return Environment::cross(img, layout);
    case Layout::HCross:
      if (3 * img.width != 4 * img.height || img.width % 4 != 0)
        throw Error(name, "is " + dims + ", a horizontal cross must be 4N x 3N");
      return Environment::cross(img, layout);
    case Layout::Faces:
      break;
  }
  throw Error(name, "the 'faces' layout needs a folder of six images");
}

namespace {

LoadedEnvironment loadUnchecked(const std::string& input, const LoadOptions& options) {
  LoadedEnvironment out;
  if (isBuiltin(input)) {
    if (options.layout) throw Error(input, "a layout does not apply to builtin environments");
    out.env = builtinEnvironment(input, options.builtinTexelWidth);
    out.layout = "builtin";
    return out;
  }
  std::error_code ec;
  if (fs::is_directory(input, ec)) {
    if (options.layout && *options.layout != Layout::Faces)
      throw Error(input, std::string("is a folder, which only the 'faces' layout reads (got '") +
                             layoutName(*options.layout) + "')");
    std::array<image::Image, 6> faces =
        readFaceFolder(input, kFaceNames, options.ldrDecode, &out.files, &out.stats);
    out.env = Environment::cube(std::move(faces));
    out.layout = layoutName(Layout::Faces);
    return out;
  }
  if (!fs::exists(input, ec)) throw Error(input, "no such file or folder");
  image::ReadStats s;
  image::Image img = image::readImage(input, {options.ldrDecode}, &s);
  out.files.push_back(input);
  out.stats.push_back(s);
  Layout layout;
  out.env = environmentFromImage(std::move(img), options.layout, input, &layout);
  out.layout = layoutName(layout);
  return out;
}

}  // namespace

LoadedEnvironment loadEnvironment(const std::string& input, const LoadOptions& options) {
  LoadedEnvironment out = loadUnchecked(input, options);
  out.env.setSource(input);
  // The pixel policy zeroes NaN and inf pixels; when that is every pixel there is no light left
  // to project, render or validate against (an all-NaN EXR would relight to black and validate
  // at 0 %), so refuse rather than go on with a black environment.
  std::size_t pixels = 0, nonFinite = 0;
  for (const image::ReadStats& s : out.stats) {
    pixels += s.pixels;
    nonFinite += s.nonFinitePixels;
  }
  if (pixels > 0 && nonFinite == pixels)
    throw Error(input, "every pixel (" + std::to_string(pixels) +
                           ") is NaN or infinite: the environment holds no light");
  return out;
}

std::vector<std::string> repairWarnings(const LoadedEnvironment& loaded) {
  std::vector<std::string> out;
  for (std::size_t k = 0; k < loaded.stats.size() && k < loaded.files.size(); ++k) {
    const image::ReadStats& s = loaded.stats[k];
    const double light = s.positiveSum + s.negativeSum;
    const double share = light > 0 ? s.negativeSum / light : (s.negativePixels ? 1.0 : 0.0);
    const bool negatives = s.negativePixels > 0 && share > kNegativeLightWarning;
    if (!s.nonFinitePixels && !negatives) continue;
    std::string line = loaded.files[k] + ":";
    if (s.nonFinitePixels)
      line += " " + std::to_string(s.nonFinitePixels) + " pixels with NaN/Inf set to 0";
    if (s.nonFinitePixels && negatives) line += ",";
    if (negatives) {
      char pct[32];
      std::snprintf(pct, sizeof pct, "%.3g%%", 100 * share);
      line += " " + std::to_string(s.negativePixels) +
              " pixels with negative values clamped to 0 (" + pct + " of its light)";
    }
    out.push_back(std::move(line));
  }
  return out;
}

bool anyPixelRepaired(const LoadedEnvironment& loaded) {
  for (const image::ReadStats& s : loaded.stats)
    if (s.nonFinitePixels + s.negativePixels > 0) return true;
  return false;
}

}  // namespace prt::envmap
