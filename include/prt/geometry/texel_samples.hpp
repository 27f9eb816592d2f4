#pragma once
// Where per-texel transfer is evaluated (the lightmap domain, issue 18): one sample per texel of
// a W × H lightmap that a triangle covers in UV space, made by geometry/texel_sampling.hpp.
//
// Texel (x, y) is the square u ∈ [x/W, (x+1)/W), v ∈ [y/H, (y+1)/H) of the UV set, its centre at
// ((x + ½)/W, (y + ½)/H); row 0 is v = 0, the image's top row as glTF reads its textures. A
// texel whose centre lies in a triangle is sampled there; one a triangle only partly covers is
// sampled at the point of that triangle nearest to the centre (conservative coverage: a thin
// chart still gets every texel it touches).

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

}  // namespace prt
