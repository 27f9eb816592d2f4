#pragma once
// A GLB read back by the tests independently of prtkit's writer and reader (glTF 2.0 §4.4): its
// JSON and BIN chunks, and a FLOAT accessor's values.

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace prt::testing {

/// A GLB's JSON and the payload of its BIN chunk (empty without one).
struct Glb {
  nlohmann::json json;
  std::string bin;
};

inline Glb splitGlb(const std::string& bytes) {
  const auto u32 = [&](std::size_t at) {
    std::uint32_t v;
    std::memcpy(&v, bytes.data() + at, 4);
    return v;
  };
  Glb g;
  EXPECT_EQ(bytes.substr(0, 4), "glTF");
  EXPECT_EQ(u32(8), bytes.size());
  const std::uint32_t jsonLength = u32(12);
  g.json = nlohmann::json::parse(bytes.substr(20, jsonLength));
  const std::size_t bin = 20 + std::size_t(jsonLength);
  if (bin < bytes.size()) g.bin = bytes.substr(bin + 8, u32(bin));
  return g;
}

/// Accessor `index` of a GLB as floats (FLOAT components, SCALAR/VEC2/VEC3/VEC4, tightly
/// packed).
inline std::vector<float> accessorFloats(const Glb& g, int index) {
  const nlohmann::json& a = g.json["accessors"][index];
  const nlohmann::json& v = g.json["bufferViews"][a["bufferView"].get<int>()];
  EXPECT_EQ(a["componentType"], 5126);
  const std::string type = a["type"];
  const std::size_t width = type == "VEC4" ? 4 : type == "VEC3" ? 3 : type == "VEC2" ? 2 : 1;
  std::vector<float> out(a["count"].get<std::size_t>() * width);
  const std::size_t at = v.value("byteOffset", std::size_t(0)) + a.value("byteOffset", std::size_t(0));
  EXPECT_LE(at + out.size() * 4, g.bin.size());
  if (at + out.size() * 4 <= g.bin.size()) std::memcpy(out.data(), g.bin.data() + at, out.size() * 4);
  return out;
}

}  // namespace prt::testing
