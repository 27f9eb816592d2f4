#pragma once
// The resource policy: how large an input may be before a loader refuses it. Every loader checks
// the sizes a file *declares* (image width × height, element and accessor counts, nesting depth,
// decompressed size) against these caps and against the bytes actually present, before it
// allocates, so a 50-byte header cannot make us allocate gigabytes, a nested document cannot
// overflow the stack and a compressed bomb cannot fill memory. docs/robustness.md states the
// figures and the reasons for them.
//
// Each cap can be overridden, for one process, by an environment variable (read once, at the
// first call of limits()) or in code with setLimits():
//
//   PRT_MAX_FILE_BYTES          largest input file read whole into memory
//   PRT_MAX_DECOMPRESSED_BYTES  largest output of inflating a .gz input
//   PRT_MAX_IMAGE_SIDE          largest image width or height
//   PRT_MAX_IMAGE_PIXELS        largest width × height
//   PRT_MAX_VERTICES            largest vertex count of one mesh (after merging a scene)
//   PRT_MAX_TRIANGLES           largest triangle count of one mesh
//   PRT_MAX_NESTING             deepest JSON nesting / scene-graph depth
//   PRT_MAX_COORDINATE          largest |x|, |y| or |z| of a vertex (what the ray tracer handles)
//
// A variable that is not a positive number makes limits() throw prt::Error naming it, and so
// does a PRT_MAX_COORDINATE beyond kMaxTraceableCoordinate (what Embree can trace at all).

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace prt {

/// The largest PRT_MAX_COORDINATE (and Limits::maxCoordinate) accepted: Embree aborts
/// (`ray.valid()`) on ray origins or directions beyond FLT_LARGE = 1.844e18 in any coordinate,
/// and a camera framing a mesh stands up to about 10 of its coordinates' magnitude away
/// (bounding-sphere centre + radius / sin(fov/2) · margin), so 1e17 keeps every ray Embree sees
/// inside its range. (Renders go black long before, near 3e12: see maxCoordinate.)
inline constexpr double kMaxTraceableCoordinate = 1e17;

struct Limits {
  std::uint64_t maxFileBytes = std::uint64_t(2) << 30;          ///< 2 GiB
  std::uint64_t maxDecompressedBytes = std::uint64_t(1) << 30;  ///< 1 GiB
  std::uint64_t maxImageSide = 32768;
  std::uint64_t maxImagePixels = std::uint64_t(1) << 28;  ///< 16384², 3 GiB as float RGB
  std::uint64_t maxVertices = std::uint64_t(1) << 27;     ///< 134 M
  std::uint64_t maxTriangles = std::uint64_t(1) << 28;    ///< 268 M
  std::uint64_t maxNesting = 256;
  double maxCoordinate = 1e10;  ///< renders go black near 3e12 (cubes of the radius overflow)
};

/// The limits in force (defaults, overridden by PRT_MAX_* variables, or by setLimits()).
Limits limits();
/// Replaces the limits for the rest of the process (tests, embedding applications, fuzzers);
/// throws prt::Error for a maxCoordinate that is not in (0, kMaxTraceableCoordinate].
void setLimits(const Limits& l);
/// The defaults with the PRT_MAX_* environment variables applied; throws prt::Error for a
/// variable that is not a positive number.
Limits limitsFromEnvironment();

/// This machine's physical memory in bytes (SIZE_MAX where the system does not say).
std::size_t physicalMemoryBytes();
/// The memory policy of the verbs that estimate their footprint before the heavy work (the
/// bake, the unwrap): work needing more than 90% of the physical memory is refused up front.
bool fitsInMemory(std::uint64_t bytes);
/// Throws Error(label, "WHAT COUNT exceeds the limit of CAP (PRT_MAX_NAME)") if count > cap.
void checkLimit(const std::string& label, const std::string& what, std::uint64_t count,
                std::uint64_t cap, const char* envName);
/// Checks a declared image size against the side and pixel caps, before allocating.
void checkImageSize(const std::string& label, std::uint64_t width, std::uint64_t height);

/// The deepest nesting of JSON arrays and objects in `text` (brackets inside strings ignored),
/// scanning at most until the depth exceeds `stopAt`. Linear, no allocation, never recurses.
std::uint64_t jsonNestingDepth(std::string_view text, std::uint64_t stopAt);
/// Throws Error(label, "JSON nesting deeper than N ...") if `text` nests deeper than
/// limits().maxNesting; call before handing text to a recursive parser (nlohmann, tinygltf).
void checkJsonNesting(const std::string& label, std::string_view text);
/// The same for a glTF: the JSON chunk of a GLB (by its header) or the whole text of a .gltf.
void checkGltfNesting(const std::string& label, std::span<const unsigned char> bytes);

}  // namespace prt
