#include "capture.hpp"

#include <algorithm>
#include <cstdio>

#include "prt/core/file.hpp"
#include "prt/image/color.hpp"
#include "prt/image/image_io.hpp"

namespace prt::viewer {

void writeScreenshot(const std::string& path, const image::Image& encoded,
                     const image::Image& linear) {
  if (fileExtension(path) != "png") {
    image::writeImage(path, linear);
    return;
  }
  // Decode the codes to linear so the PNG writer's clamp + sRGB encode gives them back exactly
  // (linearToSrgb(srgbToLinear(c/255)) rounds to c).
  image::Image shown = encoded;
  for (Rgb& p : shown.pixels)
    p = {image::srgbToLinear(p.x), image::srgbToLinear(p.y), image::srgbToLinear(p.z)};
  image::WriteOptions w;
  w.toneMap = image::ToneMap::Clamp;
  image::writeImage(path, shown, w);
}

namespace {
double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}
std::vector<double> steady(const std::vector<double>& v) {
  return v.size() > 1 ? std::vector<double>(v.begin() + 1, v.end()) : v;
}
}  // namespace

FrameSummary FrameStats::summary() const {
  FrameSummary s;
  s.frames = frameMs.size();
  if (frameMs.empty()) return s;
  s.firstMs = frameMs.front();
  s.medianMs = median(steady(frameMs));
  s.minMs = *std::min_element(frameMs.begin(), frameMs.end());
  s.cpuMedianMs = median(steady(cpuMs));
  s.uploadMedianUs = median(steady(uploadUs));
  // Only the frames that relit (light, eye, bands or material changed).
  std::vector<double> relit;
  for (double g : steady(relightMs))
    if (g > 0) relit.push_back(g);
  s.relightMedianMs = median(relit);
  s.relitFrames = relit.size();
  return s;
}

void FrameStats::print(const std::string& renderer, const Scene& scene, int width, int height,
                       std::size_t lightBytes, const std::string& upload, std::FILE* to) const {
  if (frameMs.empty()) return;
  using relight::ShaderPath;
  const FrameSummary s = summary();
  std::fprintf(to, "renderer: %s\n", renderer.c_str());
  const Transfer& t = scene.transfer().transfer;
  std::fprintf(to, "scene: %zu triangles, %zu vertices, %s, %s transfer (%s), %s\n",
               scene.bake().mesh.triangleCount(), scene.bake().mesh.vertexCount(),
               scene.basisText().c_str(), scene.transfer().describe().c_str(),
               t.channels() == 3 ? "RGB" : "scalar", scene.material().spec().c_str());
  std::fprintf(to, "transfer upload: %s\n", upload.c_str());
  std::fprintf(to, "frames: %zu at %dx%d; first frame %.2f ms (uploads)\n", s.frames, width, height,
               s.firstMs);
  std::fprintf(to, "frame time (draw + glFinish): median %.3f ms, min %.3f ms\n", s.medianMs,
               s.minMs);
  const bool table = path == ShaderPath::CpcaVector || path == ShaderPath::CpcaMatrix;
  const bool perPixel = relight::drawnPerPixel(t);
  // Relit on the CPU: glossy matrices, a probe grid, Haar transfer (per texel drawn through the
  // dense per-pixel path, its relit lightmap uploaded as the rows).
  const bool cpuRelit = path == ShaderPath::CpuRadiance || t.isHaar();
  std::fprintf(to, "CPU per frame (light rotation + packing%s): median %.4f ms\n",
               table      ? " + cluster projections"
               : cpuRelit ? " + CPU relighting"
                          : "",
               s.cpuMedianMs);
  if (path == ShaderPath::CpcaMatrix && perPixel) {
    std::fprintf(
        to,
        "glossy relighting: per pixel in the fragment shader (four texels a pixel), inside the "
        "frame time\n");
  } else if (path == ShaderPath::DenseMatrix || path == ShaderPath::CpcaMatrix) {
    std::fprintf(
        to, "glossy relighting: in the vertex shader (--glossy-on gpu), inside the frame time\n");
  } else if (cpuRelit) {
    const char* what = t.isHaar()          ? "Haar relighting (CPU haar::turnedLight + "
                                             "relight::relightHaar + radiance upload)"
                       : scene.probeBake() ? "probe relighting (CPU relight::relightProbes + "
                                             "shading + radiance upload)"
                                           : "glossy relighting (CPU relight::Relighter + "
                                             "radiance upload)";
    std::fprintf(to, "%s: median %.3f ms over %zu relit frames\n", what, s.relightMedianMs,
                 s.relitFrames);
  }
  std::fprintf(to, "light upload (%s, %zu bytes): median %.2f us\n",
               table ? "cluster table, glBufferData" : "glBufferSubData", lightBytes,
               s.uploadMedianUs);
}

}  // namespace prt::viewer
