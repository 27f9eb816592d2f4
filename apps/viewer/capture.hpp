#pragma once
// Screenshots and frame statistics, shared by the headless runner and the window.

#include <string>
#include <vector>

#include "prt/image/image.hpp"
#include "scene.hpp"

namespace prt::viewer {

/// Writes what is shown: `encoded` holds display codes / 255 (the tone-mapped sRGB frame) and
/// goes to a .png as it is; .exr/.hdr get the linear frame `linear` instead.
void writeScreenshot(const std::string& path, const image::Image& encoded,
                     const image::Image& linear);

/// Per-frame timings in milliseconds; the first frame (uploads) is reported apart.
struct FrameStats {
  std::vector<double> frameMs, cpuMs, uploadUs, relightMs;
  relight::ShaderPath path = relight::ShaderPath::DenseVector;  ///< how the transfer was drawn
  /// `relight`: the CPU relighting this frame (0 when none ran).
  void add(double frame, double cpu, double upload, double relight = 0.0) {
    frameMs.push_back(frame), cpuMs.push_back(cpu), uploadUs.push_back(upload);
    relightMs.push_back(relight);
  }
  /// Prints the summary on stdout.
  /// `upload`: SceneView::uploadSummary.
  void print(const std::string& renderer, const Scene& scene, int width, int height,
             std::size_t lightBytes, const std::string& upload) const;
};

}  // namespace prt::viewer
