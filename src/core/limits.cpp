#include "prt/core/limits.hpp"

#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <mutex>
#include <optional>

#include "prt/core/error.hpp"

namespace prt {

namespace {

std::mutex gMutex;
std::optional<Limits> gLimits;

void fromEnv(const char* name, std::uint64_t& out) {
  const char* v = std::getenv(name);
  if (!v || !*v) return;
  std::uint64_t x = 0;
  const char* end = v + std::strlen(v);
  const auto [ptr, ec] = std::from_chars(v, end, x);
  if (ec != std::errc() || ptr != end || x == 0)
    throw Error(
        name, std::string("'") + std::string(v).substr(0, 40) + "' is not a positive whole number");
  out = x;
}

void fromEnv(const char* name, double& out) {
  const char* v = std::getenv(name);
  if (!v || !*v) return;
  char* end = nullptr;
  const double x = std::strtod(v, &end);
  if (end != v + std::strlen(v) || !std::isfinite(x) || x <= 0)
    throw Error(name, std::string("'") + std::string(v).substr(0, 40) +
                          "' is not a positive finite number");
  out = x;
}

std::string coordinateCapMessage(double v) {
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "%g is beyond the ray tracer's range (at most %g: Embree refuses rays that start "
                "past 1.8e18)",
                v, kMaxTraceableCoordinate);
  return buf;
}

}  // namespace

Limits limitsFromEnvironment() {
  Limits l;
  fromEnv("PRT_MAX_FILE_BYTES", l.maxFileBytes);
  fromEnv("PRT_MAX_DECOMPRESSED_BYTES", l.maxDecompressedBytes);
  fromEnv("PRT_MAX_IMAGE_SIDE", l.maxImageSide);
  fromEnv("PRT_MAX_IMAGE_PIXELS", l.maxImagePixels);
  fromEnv("PRT_MAX_VERTICES", l.maxVertices);
  fromEnv("PRT_MAX_TRIANGLES", l.maxTriangles);
  fromEnv("PRT_MAX_NESTING", l.maxNesting);
  fromEnv("PRT_MAX_COORDINATE", l.maxCoordinate);
  if (l.maxCoordinate > kMaxTraceableCoordinate)
    throw Error("PRT_MAX_COORDINATE", coordinateCapMessage(l.maxCoordinate));
  return l;
}

Limits limits() {
  std::lock_guard<std::mutex> lock(gMutex);
  if (!gLimits) gLimits = limitsFromEnvironment();
  return *gLimits;
}

void setLimits(const Limits& l) {
  if (!(l.maxCoordinate > 0 && l.maxCoordinate <= kMaxTraceableCoordinate))
    throw Error("Limits::maxCoordinate", coordinateCapMessage(l.maxCoordinate));
  std::lock_guard<std::mutex> lock(gMutex);
  gLimits = l;
}

std::size_t physicalMemoryBytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page <= 0) return std::numeric_limits<std::size_t>::max();
  return static_cast<std::size_t>(pages) * static_cast<std::size_t>(page);
}

bool fitsInMemory(std::uint64_t bytes) {
  return bytes <= physicalMemoryBytes() / 10 * 9;
}

void checkLimit(const std::string& label, const std::string& what, std::uint64_t count,
                std::uint64_t cap, const char* envName) {
  if (count > cap)
    throw Error(label, what + " " + std::to_string(count) + " exceeds the limit of " +
                           std::to_string(cap) + " (" + envName + ")");
}

void checkImageSize(const std::string& label, std::uint64_t width, std::uint64_t height) {
  const Limits l = limits();
  if (width > l.maxImageSide || height > l.maxImageSide)
    throw Error(label, "image size " + std::to_string(width) + "x" + std::to_string(height) +
                           " exceeds the limit of " + std::to_string(l.maxImageSide) +
                           " pixels a side (PRT_MAX_IMAGE_SIDE)");
  // Both factors are at most maxImageSide (< 2^32 in any sane setting), so no overflow below
  // 2^64; guard anyway.
  if (width != 0 && height > l.maxImagePixels / width)
    throw Error(label, "image size " + std::to_string(width) + "x" + std::to_string(height) +
                           " exceeds the limit of " + std::to_string(l.maxImagePixels) +
                           " pixels (PRT_MAX_IMAGE_PIXELS)");
}

std::uint64_t jsonNestingDepth(std::string_view s, std::uint64_t stopAt) {
  std::uint64_t depth = 0, deepest = 0;
  bool inString = false;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (inString) {
      if (c == '\\')
        ++i;  // skip the escaped character (a quote or a backslash)
      else if (c == '"')
        inString = false;
      continue;
    }
    if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      if (++depth > deepest) {
        deepest = depth;
        if (deepest > stopAt) return deepest;
      }
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return deepest;
}

void checkJsonNesting(const std::string& label, std::string_view text) {
  const std::uint64_t cap = limits().maxNesting;
  if (jsonNestingDepth(text, cap) > cap)
    throw Error(label, "JSON nested deeper than " + std::to_string(cap) +
                           " levels (PRT_MAX_NESTING); refusing to parse it");
}

void checkGltfNesting(const std::string& label, std::span<const unsigned char> bytes) {
  std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  // GLB: magic "glTF", version, length, then the JSON chunk (length, type "JSON", data).
  if (bytes.size() >= 20 && std::memcmp(bytes.data(), "glTF", 4) == 0) {
    std::uint32_t len = 0;
    std::memcpy(&len, bytes.data() + 12, 4);  // little endian on every platform we build for
    text = text.substr(20, std::min<std::size_t>(len, bytes.size() - 20));
  }
  checkJsonNesting(label, text);
}

}  // namespace prt
