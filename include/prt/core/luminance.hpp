#pragma once
// Rec. 709 / sRGB relative luminance, the one weighting of R, G and B the project uses: the
// tone mappers' auto exposure (image/color.hpp) and the luminance axis of the ZH3 encoding
// (sh/encode_irradiance.hpp).

#include "prt/core/vec.hpp"

namespace prt {

/// 0.2126 R + 0.7152 G + 0.0722 B.
inline constexpr double kLuminanceR = 0.2126, kLuminanceG = 0.7152, kLuminanceB = 0.0722;

template <typename T>
inline T luminanceOf(const Vec3<T>& c) {
  return T(kLuminanceR) * c.x + T(kLuminanceG) * c.y + T(kLuminanceB) * c.z;
}

}  // namespace prt
