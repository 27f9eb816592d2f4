#include "prt/transfer/field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "prt/core/error.hpp"

namespace prt {

const char* toString(TransferMode mode) {
  switch (mode) {
    case TransferMode::Unshadowed:
      return "unshadowed";
    case TransferMode::Shadowed:
      return "shadowed";
    case TransferMode::Interreflected:
      return "interreflected";
  }
  return "?";
}

TransferMode parseTransferMode(const std::string& s) {
  if (s == "unshadowed") return TransferMode::Unshadowed;
  if (s == "shadowed") return TransferMode::Shadowed;
  if (s == "interreflected") return TransferMode::Interreflected;
  throw Error("unknown transfer mode '" + s +
              "' (expected unshadowed, shadowed or interreflected)");
}

const char* toString(TransferLayout layout) {
  switch (layout) {
    case TransferLayout::Vector:
      return "vector";
    case TransferLayout::Matrix:
      return "matrix";
  }
  return "?";
}

TransferLayout parseTransferLayout(const std::string& s) {
  if (s == "vector") return TransferLayout::Vector;
  if (s == "matrix") return TransferLayout::Matrix;
  throw Error("unknown transfer layout '" + s + "' (expected vector or matrix)");
}

const char* toString(TransferDomain domain) {
  switch (domain) {
    case TransferDomain::Vertices:
      return "vertices";
  }
  return "?";
}

std::size_t transferRowSize(TransferLayout layout, int bands) {
  const std::size_t n = static_cast<std::size_t>(bands) * static_cast<std::size_t>(bands);
  return layout == TransferLayout::Matrix ? n * n : n;
}

std::size_t transferBytes(TransferLayout layout, int bands, int channels, std::size_t rows) {
  const std::size_t perRow =
      transferRowSize(layout, bands) * static_cast<std::size_t>(channels) * sizeof(float);
  if (perRow != 0 && rows > std::numeric_limits<std::size_t>::max() / perRow)
    return std::numeric_limits<std::size_t>::max();
  return perRow * rows;
}

TransferField TransferField::zeros(TransferLayout layout, int bands, int channels,
                                   std::size_t rows) {
  TransferField f;
  f.layout = layout;
  f.bands = bands;
  f.channels = channels;
  f.vertexCount = rows;
  f.data.assign(rows * f.stride(), 0.0f);
  return f;
}

TransferField TransferField::truncated(int b) const {
  PRT_CHECK(b >= 1 && b <= bands, "truncation to more bands than the transfer holds");
  TransferField out = zeros(layout, b, channels, vertexCount);
  const std::size_t c = static_cast<std::size_t>(channels);
  if (layout == TransferLayout::Vector) {
    const std::size_t n = static_cast<std::size_t>(b * b) * c;
    for (std::size_t v = 0; v < vertexCount; ++v) std::copy_n(vertex(v), n, out.vertex(v));
    return out;
  }
  // Matrix: the leading b² × b² block of each B² × B² row.
  const std::size_t nb = static_cast<std::size_t>(b * b), nB = static_cast<std::size_t>(coeffs());
  for (std::size_t v = 0; v < vertexCount; ++v) {
    const float* src = vertex(v);
    float* dst = out.vertex(v);
    for (std::size_t i = 0; i < nb; ++i) std::copy_n(src + i * nB * c, nb * c, dst + i * nb * c);
  }
  return out;
}

void TransferField::check(const std::string& what) const {
  if (channels != 1 && channels != 3)
    throw Error(what, "transfer has " + std::to_string(channels) + " channels (expected 1 or 3)");
  if (data.size() != vertexCount * stride())
    throw Error(what, "transfer holds " + std::to_string(data.size()) + " values, expected " +
                          std::to_string(vertexCount * stride()));
  for (std::size_t k = 0; k < data.size(); ++k)
    if (!std::isfinite(data[k]))
      throw Error(what, "transfer value " + std::to_string(k) + " of row " +
                            std::to_string(k / std::max<std::size_t>(1, stride())) +
                            " is not finite");
}

}  // namespace prt
