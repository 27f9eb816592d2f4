#include "glb.hpp"

#include <cstring>
#include <ostream>

#include "prt/core/error.hpp"

namespace prt::io::glb {

namespace {

constexpr std::uint32_t kMagic = 0x46546C67, kChunkJson = 0x4E4F534A, kChunkBin = 0x004E4942;

std::uint32_t u32(std::span<const unsigned char> b, std::size_t at) {
  std::uint32_t x;
  std::memcpy(&x, b.data() + at, 4);
  return x;  // GLB is little-endian, as is every platform we build for
}

void putU32(std::ostream& os, std::uint32_t v) {
  const unsigned char b[4] = {static_cast<unsigned char>(v), static_cast<unsigned char>(v >> 8),
                              static_cast<unsigned char>(v >> 16),
                              static_cast<unsigned char>(v >> 24)};
  os.write(reinterpret_cast<const char*>(b), 4);
}

}  // namespace

Chunks split(std::span<const unsigned char> b, const std::string& name) {
  const auto fail = [&](const std::string& msg) { throw Error(name, msg); };
  if (b.size() < 12 || std::memcmp(b.data(), "glTF", 4) != 0)
    fail("not a glTF binary (.glb) file (bad magic)");
  if (u32(b, 4) != 2)
    fail("glTF binary container version " + std::to_string(u32(b, 4)) + ", expected 2");
  const std::uint64_t length = u32(b, 8);
  if (length > b.size())
    fail("truncated: the header says " + std::to_string(length) + " bytes, the file has " +
         std::to_string(b.size()));
  if (length < 20) fail("truncated: no JSON chunk");
  const std::uint64_t jsonLen = u32(b, 12);
  if (u32(b, 16) != kChunkJson) fail("first chunk is not JSON");
  if (20 + jsonLen > length) fail("truncated: the JSON chunk runs past the end of the file");
  Chunks c;
  c.json = std::string_view(reinterpret_cast<const char*>(b.data()) + 20, jsonLen);
  const std::uint64_t binAt = 20 + jsonLen;
  if (binAt < length) {
    if (binAt + 8 > length) fail("truncated: incomplete binary chunk header");
    const std::uint64_t binLen = u32(b, binAt);
    if (binAt + 8 + binLen > length) fail("truncated: the binary chunk runs past the end");
    if (u32(b, binAt + 4) != kChunkBin) fail("second chunk is not BIN");
    c.bin = b.subspan(binAt + 8, binLen);
  }
  return c;
}

int BinaryChunk::view(std::size_t size, int byteStride, int target, const std::string& name,
                      Writer write) {
  length_ = (length_ + 15) / 16 * 16;
  nlohmann::json v = {{"buffer", 0}, {"byteLength", size}};
  if (length_) v["byteOffset"] = length_;
  if (byteStride) v["byteStride"] = byteStride;
  if (target) v["target"] = target;
  if (!name.empty()) v["name"] = name;
  views_.push_back(std::move(v));
  segments_.push_back({length_, size, std::move(write)});
  length_ += size;
  return static_cast<int>(views_.size() - 1);
}

int BinaryChunk::view(const void* data, std::size_t size, int byteStride, int target,
                      const std::string& name) {
  const char* p = static_cast<const char*>(data);
  return view(size, byteStride, target, name,
              [p, size](std::ostream& os) { os.write(p, static_cast<std::streamsize>(size)); });
}

int BinaryChunk::accessor(int view, std::size_t byteOffset, std::size_t count, const char* type,
                          int componentType, const std::string& name, std::vector<double> min,
                          std::vector<double> max) {
  nlohmann::json a = {
      {"bufferView", view}, {"componentType", componentType}, {"count", count}, {"type", type}};
  if (byteOffset) a["byteOffset"] = byteOffset;
  if (!name.empty()) a["name"] = name;
  if (!min.empty()) a["min"] = std::move(min);
  if (!max.empty()) a["max"] = std::move(max);
  accessors_.push_back(std::move(a));
  return static_cast<int>(accessors_.size() - 1);
}

void BinaryChunk::write(std::ostream& os) const {
  static const char zeros[16] = {};
  std::size_t at = 0;
  for (const Segment& seg : segments_) {
    os.write(zeros, static_cast<std::streamsize>(seg.offset - at));
    seg.write(os);
    at = seg.offset + seg.size;
  }
  os.write(zeros, static_cast<std::streamsize>(length() - at));
}

std::uint64_t fileBytes(std::string_view json, const BinaryChunk& bin) {
  return 12 + 8 + (json.size() + 3) / 4 * 4 + 8 + bin.length();
}

void write(std::ostream& os, std::string json, const BinaryChunk& bin) {
  while (json.size() % 4) json.push_back(' ');
  const std::uint64_t total = fileBytes(json, bin);
  putU32(os, kMagic);
  putU32(os, 2);
  putU32(os, static_cast<std::uint32_t>(total));
  putU32(os, static_cast<std::uint32_t>(json.size()));
  putU32(os, kChunkJson);
  os.write(json.data(), static_cast<std::streamsize>(json.size()));
  putU32(os, static_cast<std::uint32_t>(bin.length()));
  putU32(os, kChunkBin);
  bin.write(os);
}

}  // namespace prt::io::glb
