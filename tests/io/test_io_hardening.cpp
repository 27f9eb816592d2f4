// Deeply nested JSON reaches recursive code in tinygltf (extras, extensions) from every verb that
// reads a .glb or .gltf, the bake file reader included; a depth scan refuses it first.

#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "prt/core/error.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/io/light_file.hpp"

namespace prt {
namespace {

std::string glb(std::string json) {
  while (json.size() % 4) json.push_back(' ');
  std::string out = "glTF";
  const auto u32 = [&](std::uint32_t v) {
    for (int k = 0; k < 4; ++k) out.push_back(char((v >> (8 * k)) & 0xff));
  };
  u32(2);
  u32(std::uint32_t(12 + 8 + json.size()));
  u32(std::uint32_t(json.size()));
  out += "JSON";
  out += json;
  return out;
}

TEST(IoHardening, DeeplyNestedJsonIsRefusedBeforeParsing) {
  const std::string nest = std::string(50000, '[') + std::string(50000, ']');
  const std::string bytes = glb(R"({"asset":{"version":"2.0"},"extras":)" + nest + "}");
  std::string e;
  try {
    decodeBake({reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size()}, "deep.glb");
  } catch (const Error& err) {
    e = err.what();
  }
  EXPECT_EQ(e,
            "deep.glb: JSON nested deeper than 256 levels (PRT_MAX_NESTING); refusing to parse it");

  e.clear();
  try {
    io::parseLightJson(R"({"coefficients": )" + nest + "}", "deep.json");
  } catch (const Error& err) {
    e = err.what();
  }
  EXPECT_EQ(
      e, "deep.json: JSON nested deeper than 256 levels (PRT_MAX_NESTING); refusing to parse it");
  // fuzz_light_json: a number beyond double range threw nlohmann's out_of_range, not prt::Error.
  e.clear();
  try {
    io::parseLightJson("4444444444444444444444444E4444444", "big.json");
  } catch (const Error& err) {
    e = err.what();
  }
  EXPECT_EQ(e, "big.json: invalid JSON (a number out of range)");
  // A normal light file still parses from memory.
  const io::LightFile ok = io::parseLightJson(R"({"coefficients": [[1, 2, 3]]})", "ok.json");
  EXPECT_EQ(ok.coefficients.bands, 1);
  EXPECT_EQ(io::parseLightGames202("1 2 3\n", "ok.txt").bands, 1);
}

}  // namespace
}  // namespace prt
