#pragma once
// The per-frame CPU work of a GPU relighting viewer (prt view; the same layout the web page
// builds in JS): rotate the light's SH coefficients and lay them out for a shader. Header-only
// so bench/viewer_frame.cpp measures exactly this code without the GL stack.
//
// Rotating the environment by R (a lobe along d moves to R d) acts on the coefficients band by
// band, L'_l = M_l(R) L_l (sh::Rotation, see prt/sh/rotate.hpp); the vertex shader then forms
//   R(p) = albedo(p) ⊙ Σ_{i < b²} T_i(p) L'_i
// with b the live band count. Rotation is block-diagonal over bands, so rotating the first b
// bands of a B-band light equals cutting the rotated light to b bands: we rotate only b bands,
// O(b³) work (9 bands: 81 coefficients, a few hundred multiply-adds per channel).
//
// Layout (std140 uniform block `Light { vec4 L[kMaxCoeffs]; }`): coefficient i at floats
// 4i..4i+2 as (r, g, b), 4i+3 unused. The shader reads scalar transfer four coefficients per
// texel fetch, so coefficients b² .. roundUp4(b²) − 1 are written as zeros: the padding of the
// transfer rows then meets zero light. Only the first roundUp4(b²) vec4s are uploaded.

#include <algorithm>
#include <array>
#include <cstddef>

#include "prt/core/error.hpp"
#include "prt/sh/rotate.hpp"
#include "prt/sh/sh.hpp"

namespace prt::relight {

/// Largest band count a packed light holds: the library's limit, 32² vec4 = 16 KiB, the
/// smallest GL_MAX_UNIFORM_BLOCK_SIZE OpenGL 3.3 allows.
inline constexpr int kMaxPackedBands = sh::kMaxBands;
inline constexpr int kMaxPackedCoeffs = kMaxPackedBands * kMaxPackedBands;

/// b² rounded up to a multiple of 4: the coefficients the shader reads at b bands.
constexpr int paddedCoeffs(int bands) {
  return (bands * bands + 3) / 4 * 4;
}

class LightPacker {
 public:
  LightPacker() : rotation_(1) {}

  /// The light to draw with (its bands: the most the viewer can use with it).
  void setLight(const sh::RgbSh& light) {
    PRT_CHECK(light.bands >= 1 && light.bands <= kMaxPackedBands, "light bands out of range");
    light_ = light;
  }
  const sh::RgbSh& light() const { return light_; }

  /// Rotates the first `bands` bands (1..light bands) by `r` and packs them; O(bands³), no
  /// allocation once the rotation has been built for this band count.
  void pack(const Mat3d& r, int bands) {
    PRT_CHECK(bands >= 1 && bands <= light_.bands, "bands out of range for the light");
    if (rotation_.bands() != bands)
      rotation_ = sh::Rotation(bands, r);
    else
      rotation_.set(r);
    rotation_.apply(light_.c.data(), rotated_.data());
    const int n = bands * bands, padded = paddedCoeffs(bands);
    for (int i = 0; i < n; ++i) {
      float* dst = data_.data() + 4 * i;
      dst[0] = rotated_[i].x, dst[1] = rotated_[i].y, dst[2] = rotated_[i].z, dst[3] = 0.0f;
    }
    std::fill(data_.begin() + 4 * n, data_.begin() + 4 * padded, 0.0f);
    bands_ = bands;
  }

  int bands() const { return bands_; }
  /// The packed block: 4 · paddedCoeffs(bands) floats.
  const float* data() const { return data_.data(); }
  std::size_t bytes() const { return sizeof(float) * 4 * std::size_t(paddedCoeffs(bands_)); }
  /// The rotated coefficient i (i < bands²) after the last pack.
  Rgb coefficient(int i) const { return {data_[4 * i], data_[4 * i + 1], data_[4 * i + 2]}; }

 private:
  sh::RgbSh light_;
  sh::Rotation rotation_;
  int bands_ = 0;
  std::array<Rgb, kMaxPackedCoeffs> rotated_{};
  alignas(16) std::array<float, 4 * kMaxPackedCoeffs> data_{};
};

}  // namespace prt::relight
