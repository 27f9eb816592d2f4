// The one glTF accessor reader (prt/gltf/accessor.hpp) that the mesh loader and the bake file
// share: every component type, normalised integers, strides, and every bound a file can lie
// about, on models built here byte by byte.

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "prt/core/error.hpp"
#include "prt/gltf/accessor.hpp"

namespace prt::gltf {
namespace {

/// A model with one buffer (the bytes given), one view over all of it and no accessors yet.
struct Fixture {
  tinygltf::Model model;

  explicit Fixture(std::vector<unsigned char> bytes, std::size_t stride = 0) {
    tinygltf::Buffer b;
    b.data = std::move(bytes);
    tinygltf::BufferView v;
    v.buffer = 0;
    v.byteOffset = 0;
    v.byteLength = b.data.size();
    v.byteStride = stride;
    model.buffers.push_back(std::move(b));
    model.bufferViews.push_back(v);
  }
  /// Adds an accessor over view 0 and returns its index.
  int add(int type, int componentType, std::size_t count, std::size_t byteOffset = 0,
          bool normalized = false) {
    tinygltf::Accessor a;
    a.bufferView = 0;
    a.byteOffset = byteOffset;
    a.type = type;
    a.componentType = componentType;
    a.count = count;
    a.normalized = normalized;
    model.accessors.push_back(a);
    return int(model.accessors.size() - 1);
  }
  /// A reader over the model as it is when a read is made (so that `f.reader().floats(f.add(..))`
  /// sees the accessor its argument adds: the reader is made after the arguments).
  struct Reader {
    const Fixture& f;
    AccessorReader now() const { return AccessorReader("f.gltf", documentOf(f.model)); }
    std::vector<float> floats(int i, int c, const std::string& w) const {
      return now().floats(i, c, w);
    }
    std::vector<std::uint32_t> indices(int i, const std::string& w) const {
      return now().indices(i, w);
    }
    std::size_t count(int i, const std::string& w) const { return now().count(i, w); }
    template <typename T>
    std::vector<T> exact(int i, int c, int type, std::size_t n, const std::string& w) const {
      return now().exact<T>(i, c, type, n, w);
    }
  };
  Reader reader() const { return Reader{*this}; }
};

template <typename T>
std::vector<unsigned char> bytesOf(const std::vector<T>& v) {
  std::vector<unsigned char> b(v.size() * sizeof(T));
  std::memcpy(b.data(), v.data(), b.size());
  return b;
}

/// The error message of f(), or "(no error)".
template <typename F>
std::string errorOf(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

/// The message names the file first, says `part`, and is one line.
void expectError(const std::string& e, const std::string& part) {
  EXPECT_EQ(e.rfind("f.gltf: ", 0), 0u) << e;
  EXPECT_NE(e.find(part), std::string::npos) << e;
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
}

TEST(GltfAccessor, EveryComponentTypeReadsAsStored) {
  {
    Fixture f(bytesOf<std::int8_t>({-128, -1, 0, 127}));
    EXPECT_EQ(f.reader().floats(f.add(TINYGLTF_TYPE_SCALAR, kByte, 4), 1, "x"),
              (std::vector<float>{-128, -1, 0, 127}));
  }
  {
    Fixture f(bytesOf<std::uint8_t>({0, 1, 200, 255}));
    EXPECT_EQ(f.reader().floats(f.add(TINYGLTF_TYPE_SCALAR, kUnsignedByte, 4), 1, "x"),
              (std::vector<float>{0, 1, 200, 255}));
  }
  {
    Fixture f(bytesOf<std::int16_t>({-32768, -7, 300, 32767}));
    EXPECT_EQ(f.reader().floats(f.add(TINYGLTF_TYPE_VEC2, kShort, 2), 2, "x"),
              (std::vector<float>{-32768, -7, 300, 32767}));
  }
  {
    Fixture f(bytesOf<std::uint16_t>({0, 9, 40000, 65535}));
    EXPECT_EQ(f.reader().floats(f.add(TINYGLTF_TYPE_VEC4, kUnsignedShort, 1), 4, "x"),
              (std::vector<float>{0, 9, 40000, 65535}));
  }
  {
    Fixture f(bytesOf<std::uint32_t>({0, 70000, 16777216}));
    EXPECT_EQ(f.reader().floats(f.add(TINYGLTF_TYPE_VEC3, kUnsignedInt, 1), 3, "x"),
              (std::vector<float>{0, 70000, 16777216}));
    EXPECT_EQ(f.reader().indices(f.add(TINYGLTF_TYPE_SCALAR, kUnsignedInt, 3), "indices"),
              (std::vector<std::uint32_t>{0, 70000, 16777216}));
  }
  {
    Fixture f(bytesOf<float>({1.5f, -2.25f, 1e30f}));
    EXPECT_EQ(f.reader().floats(f.add(TINYGLTF_TYPE_VEC3, kFloat, 1), 3, "x"),
              (std::vector<float>{1.5f, -2.25f, 1e30f}));
    // Float data stays as stored when an accessor (wrongly) says normalized.
    EXPECT_EQ(f.reader().floats(f.add(TINYGLTF_TYPE_VEC3, kFloat, 1, 0, true), 3, "x"),
              (std::vector<float>{1.5f, -2.25f, 1e30f}));
    EXPECT_EQ(f.reader().exact<float>(f.add(TINYGLTF_TYPE_SCALAR, kFloat, 3), 1, kFloat, 3, "x"),
              (std::vector<float>{1.5f, -2.25f, 1e30f}));
  }
  // Indices: the three unsigned types; signed and float ones are refused.
  {
    Fixture f(bytesOf<std::uint16_t>({3, 65535, 0, 0}));
    EXPECT_EQ(f.reader().indices(f.add(TINYGLTF_TYPE_SCALAR, kUnsignedShort, 2), "indices"),
              (std::vector<std::uint32_t>{3, 65535}));
    EXPECT_EQ(f.reader().indices(f.add(TINYGLTF_TYPE_SCALAR, kUnsignedByte, 3), "indices"),
              (std::vector<std::uint32_t>{3, 0, 255}));
    const int s = f.add(TINYGLTF_TYPE_SCALAR, kShort, 2);
    expectError(errorOf([&] { f.reader().indices(s, "indices"); }),
                "indices: SHORT is not an unsigned integer component type");
    const int v = f.add(TINYGLTF_TYPE_VEC2, kUnsignedShort, 1);
    expectError(errorOf([&] { f.reader().indices(v, "indices"); }),
                "indices: accessor " + std::to_string(v) + " is not SCALAR");
  }
  EXPECT_EQ(componentSize(kByte), 1u);
  EXPECT_EQ(componentSize(kShort), 2u);
  EXPECT_EQ(componentSize(kFloat), 4u);
  EXPECT_EQ(componentSize(5124), 0u);  // INT: not a glTF component type
}

TEST(GltfAccessor, NormalisedIntegersMapAsTheSpecSays) {
  // §3.11: unsigned x / (2ⁿ − 1); signed max(x / (2ⁿ⁻¹ − 1), −1).
  {
    Fixture f(bytesOf<std::uint8_t>({0, 51, 128, 255}));
    const auto x = f.reader().floats(f.add(TINYGLTF_TYPE_VEC4, kUnsignedByte, 1, 0, true), 4, "c");
    EXPECT_EQ(x, (std::vector<float>{0.0f, 0.2f, 128 / 255.0f, 1.0f}));
  }
  {
    Fixture f(bytesOf<std::int8_t>({-128, -127, 0, 127}));
    const auto x = f.reader().floats(f.add(TINYGLTF_TYPE_VEC4, kByte, 1, 0, true), 4, "n");
    EXPECT_EQ(x, (std::vector<float>{-1.0f, -1.0f, 0.0f, 1.0f}));  // −128 clamps to −1
  }
  {
    Fixture f(bytesOf<std::uint16_t>({0, 65535}));
    const auto x =
        f.reader().floats(f.add(TINYGLTF_TYPE_VEC2, kUnsignedShort, 1, 0, true), 2, "uv");
    EXPECT_EQ(x, (std::vector<float>{0.0f, 1.0f}));
  }
  {
    Fixture f(bytesOf<std::int16_t>({-32768, 16384, 32767, 0}));
    const auto x = f.reader().floats(f.add(TINYGLTF_TYPE_VEC4, kShort, 1, 0, true), 4, "n");
    EXPECT_EQ(x, (std::vector<float>{-1.0f, 16384 / 32767.0f, 1.0f, 0.0f}));
  }
  // exact<T> takes raw data only: a normalised accessor is the wrong type for it.
  Fixture f(bytesOf<std::uint16_t>({1, 2}));
  const int a = f.add(TINYGLTF_TYPE_SCALAR, kUnsignedShort, 2, 0, true);
  expectError(errorOf([&] { f.reader().exact<std::uint16_t>(a, 1, kUnsignedShort, 2, "ids"); }),
              "ids: accessor 0 is SCALAR of UNSIGNED_SHORT (normalized), expected SCALAR of "
              "UNSIGNED_SHORT");
}

TEST(GltfAccessor, ByteStrideInterleavesElements) {
  // Three vertices of (position, normal), 24 bytes each.
  std::vector<float> v;
  for (int i = 0; i < 3; ++i) v.insert(v.end(), {float(i), 10.0f + i, 20.0f + i, 0, 1, float(-i)});
  Fixture f(bytesOf(v), 24);
  const int pos = f.add(TINYGLTF_TYPE_VEC3, kFloat, 3, 0);
  const int nrm = f.add(TINYGLTF_TYPE_VEC3, kFloat, 3, 12);
  const AccessorReader r = f.reader().now();
  EXPECT_EQ(r.floats(pos, 3, "POSITION"), (std::vector<float>{0, 10, 20, 1, 11, 21, 2, 12, 22}));
  EXPECT_EQ(r.floats(nrm, 3, "NORMAL"), (std::vector<float>{0, 1, 0, 0, 1, -1, 0, 1, -2}));
  EXPECT_EQ(r.exact<float>(nrm, 3, kFloat, 3, "NORMAL"), r.floats(nrm, 3, "NORMAL"));
  const AccessorSpan s = r.span(nrm, "NORMAL");
  EXPECT_EQ(s.stride, 24u);
  EXPECT_EQ(s.count, 3u);
  EXPECT_EQ(s.elementSize(), 12u);
  // The last normal ends exactly at the view's end (12 + 2·24 + 12 = 72); one more overruns.
  f.model.accessors[std::size_t(nrm)].count = 4;
  expectError(errorOf([&] { f.reader().floats(nrm, 3, "NORMAL"); }),
              "runs past the end of its bufferView 0");
  // A stride smaller than an element is refused, even for one element.
  f.model.bufferViews[0].byteStride = 8;
  f.model.accessors[std::size_t(pos)].count = 1;
  expectError(errorOf([&] { f.reader().floats(pos, 3, "POSITION"); }),
              "POSITION: byteStride 8 is smaller than an element (12 bytes)");
}

TEST(GltfAccessor, AccessorOverrunningItsViewIsRefused) {
  std::vector<unsigned char> bytes(64);
  Fixture f(bytes);
  f.model.bufferViews[0].byteLength = 32;  // the buffer has 64 bytes, the view 32
  const int ok = f.add(TINYGLTF_TYPE_VEC4, kFloat, 2);
  EXPECT_EQ(f.reader().floats(ok, 4, "T").size(), 8u);
  const int over = f.add(TINYGLTF_TYPE_VEC4, kFloat, 3);  // 48 bytes in a 32-byte view
  expectError(errorOf([&] { f.reader().floats(over, 4, "T"); }),
              "T: accessor 1 (3 elements of 16 bytes, stride 16, at 0) runs past the end of its "
              "bufferView 0 (32 bytes; truncated file?)");
  const int shifted = f.add(TINYGLTF_TYPE_VEC4, kFloat, 2, 4);  // 32 bytes at offset 4
  expectError(errorOf([&] { f.reader().exact<float>(shifted, 4, kFloat, 2, "T"); }),
              "runs past the end of its bufferView 0");
  const int past = f.add(TINYGLTF_TYPE_SCALAR, kFloat, 1, 40);  // offset beyond the view
  expectError(errorOf([&] { f.reader().floats(past, 1, "T"); }), "runs past the end");
}

TEST(GltfAccessor, ViewOverrunningItsBufferIsRefused) {
  Fixture f(std::vector<unsigned char>(48));
  const int a = f.add(TINYGLTF_TYPE_VEC3, kFloat, 1);  // 12 bytes: inside either way
  f.model.bufferViews[0].byteLength = 100;
  expectError(errorOf([&] { f.reader().floats(a, 3, "POSITION"); }),
              "POSITION: bufferView 0 (100 bytes at 0) lies outside its buffer of 48 bytes");
  f.model.bufferViews[0].byteLength = 40;
  f.model.bufferViews[0].byteOffset = 16;  // 16 + 40 > 48
  expectError(errorOf([&] { f.reader().floats(a, 3, "POSITION"); }), "lies outside its buffer");
  // An offset so large that offset + length wraps around.
  f.model.bufferViews[0].byteOffset = std::numeric_limits<std::size_t>::max() - 7;
  f.model.bufferViews[0].byteLength = 16;
  expectError(errorOf([&] { f.reader().floats(a, 3, "POSITION"); }), "lies outside its buffer");
  f.model.bufferViews[0].byteOffset = 0;
  f.model.bufferViews[0].byteLength = 48;
  EXPECT_EQ(f.reader().floats(a, 3, "POSITION").size(), 3u);
  // Missing views and buffers.
  f.model.bufferViews[0].buffer = 3;
  expectError(errorOf([&] { f.reader().floats(a, 3, "POSITION"); }),
              "POSITION: bufferView 0 has no valid buffer");
  f.model.accessors[0].bufferView = -1;
  expectError(errorOf([&] { f.reader().floats(a, 3, "POSITION"); }),
              "POSITION: accessor 0 has no valid bufferView");
}

TEST(GltfAccessor, CountTimesSizeCannotOverflow) {
  Fixture f(std::vector<unsigned char>(64));
  // A count whose byte size (count × 16) wraps around 2⁶⁴ to 0: refused by the count against
  // the buffer's bytes, before anything is allocated.
  const std::size_t wraps = (std::numeric_limits<std::size_t>::max() >> 4) + 1;
  const int big = f.add(TINYGLTF_TYPE_VEC4, kFloat, wraps);
  expectError(errorOf([&] { f.reader().floats(big, 4, "T"); }),
              "T: accessor count " + std::to_string(wraps) + " exceeds the 64 bytes of its buffer");
  expectError(errorOf([&] { f.reader().exact<float>(big, 4, kFloat, wraps, "T"); }),
              "exceeds the 64 bytes");
  // A stride whose product with (count − 1) wraps to 0: 2⁶² · 4 = 2⁶⁴. Naive arithmetic would
  // see 0 + 16 bytes and read far outside the buffer.
  const int strided = f.add(TINYGLTF_TYPE_VEC4, kFloat, 5);
  f.model.bufferViews[0].byteStride = std::size_t(1) << 62;
  expectError(errorOf([&] { f.reader().floats(strided, 4, "T"); }), "runs past the end");
  // An accessor offset that wraps when the element is added.
  f.model.bufferViews[0].byteStride = 0;
  const int offset =
      f.add(TINYGLTF_TYPE_VEC4, kFloat, 1, std::numeric_limits<std::size_t>::max() - 3);
  expectError(errorOf([&] { f.reader().floats(offset, 4, "T"); }), "runs past the end");
  // count() reports the declared count without reading: callers cap totals with it first.
  EXPECT_EQ(f.reader().count(big, "T"), wraps);
}

TEST(GltfAccessor, SparseAccessorsAreRefused) {
  Fixture f(bytesOf<float>({1, 2, 3}));
  const int a = f.add(TINYGLTF_TYPE_VEC3, kFloat, 1);
  f.model.accessors[0].sparse.isSparse = true;
  f.model.accessors[0].sparse.count = 1;
  expectError(errorOf([&] { f.reader().floats(a, 3, "POSITION"); }),
              "POSITION: sparse accessors are not supported");
  expectError(errorOf([&] { f.reader().exact<float>(a, 3, kFloat, 1, "POSITION"); }),
              "sparse accessors are not supported");
  expectError(errorOf([&] { f.reader().count(a, "POSITION"); }), "sparse");
}

TEST(GltfAccessor, WrongShapesAndIndicesAreRefused) {
  Fixture f(bytesOf<float>({1, 2, 3, 4, 5, 6, 7, 8}));
  const int vec4 = f.add(TINYGLTF_TYPE_VEC4, kFloat, 2);
  const int mat2 = f.add(TINYGLTF_TYPE_MAT2, kFloat, 2);
  const AccessorReader r = f.reader().now();
  expectError(errorOf([&] { r.floats(vec4, 3, "NORMAL"); }),
              "NORMAL has 4 components (VEC4), expected 3 (VEC3)");
  // MAT2 has four components too, but is not a VEC4.
  expectError(errorOf([&] { r.floats(mat2, 4, "COLOR_0"); }), "expected 4 (VEC4)");
  EXPECT_EQ(r.components(mat2, "m"), 4);
  expectError(errorOf([&] { r.exact<float>(vec4, 4, kFloat, 3, "T"); }),
              "T: accessor 0 has 2 elements, expected 3");
  expectError(errorOf([&] { r.exact<std::uint32_t>(vec4, 4, kUnsignedInt, 2, "T"); }),
              "T: accessor 0 is VEC4 of FLOAT, expected VEC4 of UNSIGNED_INT");
  expectError(errorOf([&] { r.floats(7, 3, "POSITION"); }),
              "POSITION: accessor 7 does not exist (the file has 2)");
  expectError(errorOf([&] { r.floats(-1, 3, "NORMAL"); }), "NORMAL: accessor -1 does not exist");
  f.model.accessors[0].componentType = 5124;  // INT
  expectError(errorOf([&] { f.reader().floats(vec4, 4, "T"); }),
              "T: accessor 0 has an invalid component type 5124");
}

}  // namespace
}  // namespace prt::gltf
