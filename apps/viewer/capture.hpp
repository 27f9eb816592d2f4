#pragma once
// Screenshots and frame statistics, shared by the headless runner and the window.

#include <cstdio>
#include <string>
#include <vector>

#include "prt/image/image.hpp"
#include "scene.hpp"

namespace prt::viewer {

/// Writes what is shown: `encoded` holds display codes / 255 (the tone-mapped sRGB frame) and
/// goes to a .png as it is; .exr/.hdr get the linear frame `linear` instead.
void writeScreenshot(const std::string& path, const image::Image& encoded,
                     const image::Image& linear);

/// FrameStats summed up as --stats prints it: medians over the frames after the first
/// (which uploads), in milliseconds (upload: microseconds).
struct FrameSummary {
  std::size_t frames = 0;
  double firstMs = 0, medianMs = 0, minMs = 0, cpuMedianMs = 0, uploadMedianUs = 0;
  double relightMedianMs = 0;   ///< over the frames that relit on the CPU
  std::size_t relitFrames = 0;  ///< frames after the first that relit on the CPU
};

/// Per-frame timings in milliseconds; the first frame (uploads) is reported apart.
struct FrameStats {
  std::vector<double> frameMs, cpuMs, uploadUs, relightMs;
  relight::ShaderPath path = relight::ShaderPath::DenseVector;  ///< how the transfer was drawn
  /// `relight`: the CPU relighting this frame (0 when none ran).
  void add(double frame, double cpu, double upload, double relight = 0.0) {
    frameMs.push_back(frame), cpuMs.push_back(cpu), uploadUs.push_back(upload);
    relightMs.push_back(relight);
  }
  FrameSummary summary() const;
  /// Prints the summary on `to` (stdout; stderr when prt view --json - owns stdout).
  /// `upload`: SceneView::uploadSummary.
  void print(const std::string& renderer, const Scene& scene, int width, int height,
             std::size_t lightBytes, const std::string& upload, std::FILE* to = stdout) const;
};

}  // namespace prt::viewer
