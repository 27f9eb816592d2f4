#include "prt/transport/transfer.hpp"

#include <algorithm>

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

TransferField TransferField::truncated(int b) const {
  PRT_CHECK(b >= 1 && b <= bands, "truncation to more bands than the transfer holds");
  TransferField out;
  out.bands = b;
  out.channels = channels;
  out.vertexCount = vertexCount;
  const std::size_t n = static_cast<std::size_t>(b * b) * channels;
  out.data.resize(vertexCount * n);
  for (std::size_t v = 0; v < vertexCount; ++v) std::copy_n(vertex(v), n, out.data.data() + v * n);
  return out;
}

}  // namespace prt
