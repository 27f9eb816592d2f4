#pragma once
// The GLB container (glTF 2.0 §4.4), read and written here and nowhere else; private to src/io.
// A 12-byte header (magic "glTF", version 2, total length), a JSON chunk padded with spaces and
// an optional BIN chunk padded with zeros; every length a multiple of 4, the whole below 2³²
// bytes. The binary chunk is described, not assembled: each bufferView is a segment that writes
// its bytes straight from the caller's arrays when the file is streamed out, so writing a bake
// needs no second copy of its transfer.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace prt::io::glb {

/// The chunks of a GLB, checked (header, chunk table, lengths) but not parsed.
struct Chunks {
  std::string_view json;
  std::span<const unsigned char> bin;  ///< empty when the file has no BIN chunk
};
/// Throws prt::Error(name, "...") with the first problem (bad magic, truncation, ...).
Chunks split(std::span<const unsigned char> bytes, const std::string& name);

/// The binary chunk being described, and the bufferViews and accessors that point into it.
class BinaryChunk {
 public:
  using Writer = std::function<void(std::ostream&)>;
  /// A new bufferView of `size` bytes (16-byte aligned) whose content `write` produces; its
  /// index. byteStride 0 and target 0 are left out of the JSON.
  int view(std::size_t size, int byteStride, int target, const std::string& name, Writer write);
  /// A bufferView of bytes that stay alive and unchanged until the file is written.
  int view(const void* data, std::size_t size, int byteStride, int target, const std::string& name);
  /// A new accessor; its index. `name` and min/max are left out when empty.
  int accessor(int view, std::size_t byteOffset, std::size_t count, const char* type,
               int componentType, const std::string& name = {}, std::vector<double> min = {},
               std::vector<double> max = {});
  /// Bytes of the chunk (padded to 4).
  std::size_t length() const { return (length_ + 3) / 4 * 4; }
  const nlohmann::json& views() const { return views_; }
  const nlohmann::json& accessors() const { return accessors_; }
  /// Streams the chunk's bytes: the segments in order, zero padding between and after them.
  void write(std::ostream& os) const;

 private:
  struct Segment {
    std::size_t offset = 0, size = 0;
    Writer write;
  };
  std::vector<Segment> segments_;
  std::size_t length_ = 0;
  nlohmann::json views_ = nlohmann::json::array();
  nlohmann::json accessors_ = nlohmann::json::array();
};

/// Total bytes of a GLB with this JSON text and binary chunk.
std::uint64_t fileBytes(std::string_view json, const BinaryChunk& bin);
/// Writes header, JSON chunk (padded) and BIN chunk. The caller has checked fileBytes.
void write(std::ostream& os, std::string json, const BinaryChunk& bin);

}  // namespace prt::io::glb
