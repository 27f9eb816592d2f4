#include "prt/transfer/shape.hpp"

#include <limits>

#include "prt/core/band_limits.hpp"
#include "prt/core/error.hpp"

namespace prt {

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
    case TransferDomain::Texels:
      return "texels";
    case TransferDomain::Probes:
      return "probes";
  }
  return "?";
}

const char* rowName(TransferDomain domain) {
  switch (domain) {
    case TransferDomain::Vertices:
      return "vertex";
    case TransferDomain::Texels:
      return "texel";
    case TransferDomain::Probes:
      return "probe";
  }
  return "?";
}

TransferDomain parseTransferDomain(const std::string& s) {
  if (s == "vertices") return TransferDomain::Vertices;
  if (s == "texels") return TransferDomain::Texels;
  if (s == "probes") return TransferDomain::Probes;
  throw Error("unknown transfer domain '" + s + "' (expected vertices, texels or probes)");
}

std::size_t TransferShape::rowSize() const {
  const std::size_t n = static_cast<std::size_t>(bands) * static_cast<std::size_t>(bands);
  return layout == TransferLayout::Matrix ? n * n : n;
}

std::size_t TransferShape::denseBytes() const {
  const std::size_t perRow = stride() * sizeof(float);
  if (perRow != 0 && rows.count > std::numeric_limits<std::size_t>::max() / perRow)
    return std::numeric_limits<std::size_t>::max();
  return perRow * rows.count;
}

TransferShape TransferShape::withBands(int b) const {
  TransferShape s = *this;
  s.bands = b;
  return s;
}

void TransferShape::check(const std::string& what) const {
  if (bands < 1 || bands > bands::kMaxLibrary)
    throw Error(what, bands::bandLimitMessage("the transfer", bands, "prtkit", bands::kMaxLibrary));
  if (channels != 1 && channels != 3)
    throw Error(what,
                "the transfer has " + std::to_string(channels) + " channels (expected 1 or 3)");
  if (domain == TransferDomain::Probes) {
    if (layout != TransferLayout::Matrix)
      throw Error(what, "a probe's transfer is a matrix (the light arriving from every direction)");
    checkProbeGrid(probes, what);
  }
}

std::string TransferShape::describe() const {
  return std::string(toString(layout)) + ", " + std::to_string(bands) + " bands, " +
         (channels == 3 ? "RGB" : "scalar") + ", " + std::to_string(rows.count) + " " +
         toString(domain);
}

}  // namespace prt
