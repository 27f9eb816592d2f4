#pragma once
// prt demo's results and the page that shows them (index.html): what runDemo (demo.cpp)
// measured and wrote, and the HTML around it.

#include <string>
#include <vector>

#include "demo_texels.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/render/validate.hpp"

namespace prt::cli {

/// prt demo's options.
struct HaarRow;

struct DemoArgs {
  std::string output = "demo-out";
  std::string mesh = "auto";
  std::vector<std::string> envs;
  int bands = 5;
  int samples = 512;
  int referenceSamples = 512;
  int bounces = 1;
  std::string size = "480x360";
  int frames = 12;
  std::string glossy = "phong?exponent=12&ks=0.5&kd=0.5";  ///< "none": no glossy rows
  int glossyBands = 5;
  int glossySamples = 256;
  /// Each glossy reference sample is a diffuse and a glossy one (two rays and more): half the
  /// diffuse modes' count costs about what one of them does.
  int glossyReferenceSamples = 256;
  std::string json;  ///< --json: the run's figures (docs/formats-report.md)
};

/// The demo scene: what was asked, or the bunny on a plane, or the Cornell box; and the sphere
/// the camera frames (the object, not the whole ground plane).
struct DemoScene {
  std::string path;  ///< the mesh read: --mesh, or what auto chose
  Mesh mesh;
  std::string description;
  Vec3f centre{0.0f};
  float radius = 1;
};

struct ModeResult {
  TransferMode mode;
  bool glossy = false;  ///< matrix transfer with the --glossy material
  double seconds = 0;   ///< validation, relighting and pictures
  render::ValidationReport report;
  float errorScale = 0;
  std::string prtImage, refImage, errImage;
};

struct LightResult {
  std::string spec, name, preview, turntable, comparison;
  std::vector<std::string> frames;
  float exposure = 0;
  std::vector<ModeResult> modes;
  double seconds = 0;
};

/// The glossy bake, when made.
struct GlossyBake {
  BakeFile file;
  Material material;
  double seconds = 0;
  std::size_t bytes = 0;
};

/// Writes index.html: the live viewer (unless `webWhy` says why not), the scene and bake, then
/// per environment its preview, every mode's pictures and validation table, and the turntable.
void writeDemoPage(const std::string& path, const DemoScene& scene, const BakeFile& bake,
                   const std::vector<LightResult>& lights, const DemoArgs& a, double bakeSeconds,
                   double totalSeconds, const std::string& webWhy, const GlossyBake* glossy,
                   const TexelRow* texels, const HaarRow* haar);

}  // namespace prt::cli
