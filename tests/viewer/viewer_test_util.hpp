#pragma once
// Shared pieces of the viewer tests: running the prt binary, fixtures baked once per program,
// and comparing PNGs as displayed (sRGB codes / 255).

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "cli/cli_harness.hpp"
#include "common/scratch.hpp"
#include "context.hpp"
#include "prt/image/color.hpp"
#include "prt/image/image_io.hpp"
#include "prt/render/metrics.hpp"

namespace prt::viewer::test {

namespace fs = std::filesystem;

using prt::testing::Result;
using prt::testing::slurp;

/// A per-program scratch folder holding the fixtures below, removed when the tests are done.
inline const fs::path& scratch() {
  return prt::testing::programScratch("viewer");
}
inline const bool kScratchCleanupRegistered = prt::testing::registerProgramScratchCleanup("viewer");

/// Runs `[prefix] prt ARGS` in the scratch folder.
inline Result prt(const std::string& args, const std::string& prefix = "") {
  return prt::testing::runPrt(scratch(), args, prefix);
}

inline std::string path(const std::string& name) {
  return (scratch() / name).string();
}

/// Fixtures, baked once: a Cornell box with RGB (inter-reflected) and scalar (shadowed)
/// transfer at 4 bands, and a sphere over a plane, shadowed, 3 bands.
inline const std::string& cornellBake() {
  static const std::string p = [] {
    const Result r =
        prt("-q bake 'builtin:cornell?grid=12' --mode interreflected --mode shadowed "
            "--bands 4 --samples 64 -o cornell.glb");
    EXPECT_EQ(r.rc, 0) << r.err;
    return path("cornell.glb");
  }();
  return p;
}
inline const std::string& spherePlaneBake() {
  static const std::string p = [] {
    const Result r =
        prt("-q bake 'builtin:sphere-plane?size=1.5&grid=40&subdiv=3' --mode "
            "shadowed --bands 3 --samples 64 -o sphere.glb");
    EXPECT_EQ(r.rc, 0) << r.err;
    return path("sphere.glb");
  }();
  return p;
}

/// Glossy (matrix) transfer of the sphere over the plane, shadowed, 4 bands, a Phong lobe.
inline const std::string& glossyBake() {
  static const std::string p = [] {
    const Result r =
        prt("-q bake 'builtin:sphere-plane?size=1.5&grid=40&subdiv=3' --mode shadowed "
            "--transfer matrix --bands 4 --samples 64 "
            "--material 'phong?exponent=8&ks=0.6&kd=0.4' -o glossy.glb");
    EXPECT_EQ(r.rc, 0) << r.err;
    return path("glossy.glb");
  }();
  return p;
}

/// CPCA-compressed copies (prt compress, bake version 3), coarse enough that the compressed
/// frame differs visibly from the dense source's: the sphere over the plane (scalar, K 16,
/// N 4: one texel of id + weights per vertex), the Cornell box's RGB inter-reflected transfer
/// (K 24, N 5: two texels; its shadowed transfer stays dense in the same file) and the glossy
/// matrices (K 8, N 3).
inline std::string compressedCopy(const std::string& source, const std::string& name,
                                  const std::string& args) {
  const Result r = prt("-q compress '" + source + "' " + args + " -o " + name);
  EXPECT_EQ(r.rc, 0) << r.err;
  return path(name);
}
inline const std::string& compressedSphereBake() {
  static const std::string p =
      compressedCopy(spherePlaneBake(), "sphere-cpca.glb", "--clusters 16 --pca 4");
  return p;
}
inline const std::string& compressedCornellBake() {
  static const std::string p = compressedCopy(cornellBake(), "cornell-cpca.glb",
                                              "--mode interreflected --clusters 24 --pca 5");
  return p;
}
inline const std::string& compressedGlossyBake() {
  static const std::string p =
      compressedCopy(glossyBake(), "glossy-cpca.glb", "--clusters 8 --pca 3");
  return p;
}

/// Per-texel transfer (prt bake --domain texels) of a Cornell box over a 64 × 64 lightmap, RGB
/// inter-reflected and scalar shadowed, 4 bands; and a CPCA copy of its inter-reflected rows
/// (K 8, N 3: one texel of id + weights per lightmap texel). 256 samples: the viewer shades a
/// pixel once at its centre (MSAA multiplies coverage only) where prt render fetches at each of
/// its 4 samples, and across a noisy lightmap (32 samples) that alone costs ~0.01 of RMSE.
inline const std::string& texelBake() {
  static const std::string p = [] {
    const Result r =
        prt("-q bake 'builtin:cornell?grid=8' --mode interreflected --mode shadowed --bands 4 "
            "--domain texels --resolution 64 --samples 256 -o texels.glb");
    EXPECT_EQ(r.rc, 0) << r.err;
    return path("texels.glb");
  }();
  return p;
}
inline const std::string& compressedTexelBake() {
  static const std::string p =
      compressedCopy(texelBake(), "texels-cpca.glb", "--mode interreflected --clusters 8 --pca 3");
  return p;
}

/// Glossy matrices per texel (a Phong lobe), RGB inter-reflected with glossy bounces, over a
/// 64 × 64 lightmap of the Cornell box, 3 bands, CPCA-compressed (K 16, N 6): what prt view draws
/// per pixel (dense per-texel matrices it refuses).
inline const std::string& compressedGlossyTexelBake() {
  static const std::string p = [] {
    const Result r = prt(
        "-q bake 'builtin:cornell?grid=8' --mode interreflected --bounces 1 --transfer matrix "
        "--bands 3 --domain texels --resolution 64 --samples 256 "
        "--material 'phong?ks=0.4&exponent=6' -o glossy-texels.glb");
    EXPECT_EQ(r.rc, 0) << r.err;
    return compressedCopy(path("glossy-texels.glb"), "glossy-texels-cpca.glb",
                          "--clusters 16 --pca 6");
  }();
  return p;
}

/// A PNG as displayed: sRGB-encoded values in [0, 1].
inline image::Image readDisplayed(const std::string& file) {
  image::Image img = image::readImage(file);
  for (Rgb& p : img.pixels)
    p = {image::linearToSrgb(p.x), image::linearToSrgb(p.y), image::linearToSrgb(p.z)};
  return img;
}

/// RMSE of two PNGs as displayed (0 = identical, 1 = black against white).
inline double displayedRmse(const std::string& a, const std::string& b) {
  return render::rmse(readDisplayed(a), readDisplayed(b));
}

/// The q-quantile (0..1) of the per-pixel displayed error sqrt(Σ_c (a_c − b_c)² / 3).
inline double displayedErrorQuantile(const std::string& a, const std::string& b, double q) {
  const image::Image x = readDisplayed(a), y = readDisplayed(b);
  EXPECT_EQ(x.pixels.size(), y.pixels.size());
  std::vector<double> e;
  for (std::size_t i = 0; i < std::min(x.size(), y.size()); ++i) {
    const Rgb d = x.pixels[i] - y.pixels[i];
    e.push_back(std::sqrt(dot(d, d) / 3.0));
  }
  if (e.empty()) return 1.0;
  std::sort(e.begin(), e.end());
  return e[std::min(e.size() - 1, std::size_t(q * e.size()))];
}

}  // namespace prt::viewer::test

/// Skips the current test when no offscreen OpenGL context can be created here.
#define PRT_REQUIRE_HEADLESS_GL()                                                 \
  do {                                                                            \
    static std::string why_;                                                      \
    static const bool ok_ = ::prt::viewer::headlessAvailable(&why_);              \
    if (!ok_) GTEST_SKIP() << "no headless OpenGL (EGL/llvmpipe) here: " << why_; \
  } while (0)
