#include "prt/transfer/shape.hpp"

#include <algorithm>
#include <limits>

#include "prt/core/band_limits.hpp"
#include "prt/core/error.hpp"
#include "prt/haar/haar_light.hpp"
#include "prt/haar/resolution.hpp"
#include "prt/transfer/haar_rows.hpp"

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

const char* toString(TransferBasis basis) {
  return basis == TransferBasis::Haar ? "haar" : "sh";
}

TransferBasis parseTransferBasis(const std::string& s) {
  if (s == "sh") return TransferBasis::SphericalHarmonics;
  if (s == "haar") return TransferBasis::Haar;
  throw Error("unknown basis '" + s + "' (expected sh or haar)");
}

int TransferShape::coeffs() const {
  return isHaar() ? static_cast<int>(haar::coefficientCount(haar.resolution)) : bands * bands;
}

std::size_t TransferShape::rowSize() const {
  if (isHaar()) return haarBounceOffset() + haarBounceFloats();
  const std::size_t n = static_cast<std::size_t>(bands) * static_cast<std::size_t>(bands);
  return layout == TransferLayout::Matrix ? n * n : n;
}

std::size_t TransferShape::haarBounceOffset() const {
  return haar::haarRowFloats(haar.terms);
}

std::size_t TransferShape::haarBounceFloats() const {
  const auto b = static_cast<std::size_t>(haar.bounceBands < 0 ? 0 : haar.bounceBands);
  return b * b * static_cast<std::size_t>(channels < 1 ? 1 : channels);
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
  if (isHaar()) {
    if (!haar::validResolution(haar.resolution))
      throw Error(what, "the Haar cube's resolution must be a power of two from " +
                            std::to_string(haar::kMinResolution) + " to " +
                            std::to_string(haar::kMaxResolution) + ", got " +
                            std::to_string(haar.resolution));
    const auto count = haar::coefficientCount(haar.resolution);
    if (haar.terms < 1 || static_cast<std::size_t>(haar.terms) > count)
      throw Error(what, "a Haar row keeps 1 to " + std::to_string(count) + " terms, got " +
                            std::to_string(haar.terms));
    if (bands != 0) throw Error(what, "a Haar transfer has no bands");
    if (layout != TransferLayout::Vector || domain == TransferDomain::Probes)
      throw Error(what, "Haar transfer is diffuse (vector rows) over vertices or texels");
    if (haar.bounceBands < 0 || haar.bounceBands > haar::kUnshadowedBands)
      throw Error(what, "a Haar row's bounce has 0 to " + std::to_string(haar::kUnshadowedBands) +
                            " SH bands, got " + std::to_string(haar.bounceBands));
    if (channels != 1 && (channels != 3 || haar.bounceBands == 0))
      throw Error(what,
                  "Haar transfer is scalar, and RGB only in its inter-reflected bounce, got " +
                      std::to_string(channels) + " channels");
    return;
  }
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
  if (isHaar())
    return std::string(toString(layout)) + ", Haar " + std::to_string(haar.resolution) +
           "² cube, " + std::to_string(haar.terms) + " terms, " +
           (haar.bounceBands > 0 ? "bounce in " + std::to_string(haar.bounceBands) + " SH bands, "
                                 : std::string()) +
           (channels == 3 ? "RGB" : "scalar") + ", " + std::to_string(rows.count) + " " +
           toString(domain);
  return std::string(toString(layout)) + ", " + std::to_string(bands) + " bands, " +
         (channels == 3 ? "RGB" : "scalar") + ", " + std::to_string(rows.count) + " " +
         toString(domain);
}

}  // namespace prt
