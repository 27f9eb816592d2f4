#pragma once
// Where per-texel transfer is evaluated (the lightmap domain, issue 18): one sample per texel of
// a W × H lightmap that a triangle covers in UV space, made by geometry/texel_sampling.hpp.
//
// Texel (x, y) is the square u ∈ [x/W, (x+1)/W), v ∈ [y/H, (y+1)/H) of the UV set, its centre at
// ((x + ½)/W, (y + ½)/H); row 0 is v = 0, the image's top row as glTF reads its textures. A
// texel whose centre lies in a triangle is sampled there; one a triangle only partly covers is
// sampled at the point of that triangle nearest to the centre (conservative coverage: a thin
// chart still gets every texel it touches).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "prt/core/vec.hpp"

namespace prt {

struct TexelSample {
  std::uint32_t texel = 0;     ///< y·W + x
  std::uint32_t triangle = 0;  ///< of the mesh
  Vec3f barycentric{0.0f};     ///< weights of the triangle's three vertices at the sample point
  bool centreInside = false;   ///< the texel's centre lies in the triangle (else its nearest point)
};

struct TexelSamples {
  int width = 0, height = 0;
  std::vector<TexelSample> samples;         ///< in texel order, one per covered texel
  std::vector<std::int32_t> sampleOfTexel;  ///< W·H entries: index into samples, −1 if uncovered

  std::size_t texelCount() const { return static_cast<std::size_t>(width) * height; }
  bool covered(std::size_t texel) const { return sampleOfTexel[texel] >= 0; }
};

/// The four texels a bilinear fetch of a W × H lightmap at `uv` blends, and their weights (they
/// sum to 1): between the texel centres around (u, v), clamped to the edge texels, as a GPU
/// samples a texture with clamp-to-edge. The one fetch every reader of a lightmap shares (the
/// bake's bounces, the renderer, the seam metric). Taps in the order (x0, y0), (x1, y0),
/// (x0, y1), (x1, y1).
struct TexelTaps {
  std::array<std::size_t, 4> texel;
  std::array<float, 4> weight;
};
inline TexelTaps bilinearTaps(Vec2f uv, int width, int height) {
  const float x = uv.x * float(width) - 0.5f, y = uv.y * float(height) - 0.5f;
  const float fx = std::floor(x), fy = std::floor(y);
  const float wx = x - fx, wy = y - fy;
  const auto clampTo = [](int i, int n) { return std::min(std::max(i, 0), n - 1); };
  const int x0 = clampTo(int(fx), width), x1 = clampTo(int(fx) + 1, width);
  const int y0 = clampTo(int(fy), height), y1 = clampTo(int(fy) + 1, height);
  const std::size_t w = std::size_t(width);
  return {{std::size_t(y0) * w + x0, std::size_t(y0) * w + x1, std::size_t(y1) * w + x0,
           std::size_t(y1) * w + x1},
          {(1 - wx) * (1 - wy), wx * (1 - wy), (1 - wx) * wy, wx * wy}};
}

}  // namespace prt
