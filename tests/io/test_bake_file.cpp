// The bake file: exact round trip, partial ranges and merging, version and corruption handling,
// and the glTF rules a viewer relies on, checked on the raw JSON independently of our reader.

#include <gtest/gtest.h>
#include <tiny_gltf.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <random>
#include <tuple>

#include "common/error_text.hpp"
#include "common/glb_reader.hpp"
#include "common/random_data.hpp"
#include "common/scratch.hpp"
#include "prt/compress/cpca.hpp"
#include "prt/core/error.hpp"
#include "prt/geometry/load.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/io/bake_merge.hpp"

namespace prt {
namespace {

/// The bake's object in a file of the current format: the PRTKIT_radiance_transfer extension.
nlohmann::json& prtObject(nlohmann::json& doc) {
  return doc["extensions"][kBakeExtension];
}
const nlohmann::json& prtObject(const nlohmann::json& doc) {
  return doc.at("extensions").at(kBakeExtension);
}
/// `doc` as a file of format `version` (1-4) would hold it: the object in the root's
/// extras.prtkit, no extension.
void asVersion(nlohmann::json& doc, int version) {
  nlohmann::json object = prtObject(doc);
  object["formatVersion"] = version;
  doc.erase("extensions");
  doc.erase("extensionsUsed");
  doc["extras"]["prtkit"] = std::move(object);
}

// Two parts: a quad (4 vertices, 2 triangles) and a tetrahedron-like fan (5 vertices, 3 tris).
Mesh twoPartMesh() {
  Mesh m;
  m.source = "test-mesh";
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1},           {2, 1, 2},
                 {3, 1, 2}, {3, 2, 2}, {2, 2, 3}, {2.5f, 1.5f, -1e-3f}};
  for (std::size_t i = 0; i < m.positions.size(); ++i)
    m.normals.push_back(normalize(Vec3f(0.1f * float(i), 1.0f, -0.2f * float(i))));
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    m.albedo.push_back(Rgb(0.1f * float(i), 0.5f, 0.9f - 0.05f * float(i)));
    m.uvs.push_back({0.125f * float(i), 1.0f - 0.1f * float(i)});
  }
  m.triangles = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {4, 7, 8}};
  m.parts = {{"quad", 0, 4, 0, 2}, {"fan", 4, 5, 2, 3}};
  return m;
}

Transfer randomField(int bands, int channels, std::size_t first, std::size_t n, unsigned seed) {
  TransferShape shape = testdata::shapeOf(TransferLayout::Vector, bands, channels, n);
  shape.rows.first = first;
  Transfer f = Transfer::zeros(shape);
  float* x = f.mutableValues();
  const std::size_t size = f.values().size();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-2.0f, 2.0f);
  for (std::size_t i = 0; i < size; ++i) x[i] = u(rng);
  // Values that a lossy text path would alter.
  x[0] = 1.0f / 3.0f;
  if (size > 2) x[1] = -0.0f, x[2] = 1e-40f;  // negative zero, subnormal
  return f;
}

BakedTransfer transfer(TransferMode mode, int bands, int channels, std::size_t first, std::size_t n,
                       unsigned seed) {
  BakedTransfer t;
  t.recipe.mode = mode;
  t.recipe.samples = 4096;
  t.recipe.bounces = mode == TransferMode::Interreflected ? 2 : 0;
  t.recipe.seed = (std::uint64_t(1) << 60) + 12345;  // beyond 2^53: stored as a string
  t.recipe.sampling = Sampling::UniformRandom;
  t.recipe.material.diffuse = Rgb(0.25f, 0.5f, 0.75f);
  t.stats.rays = (std::uint64_t(1) << 40) + 7;  // beyond 32 bits
  t.stats.raysPerSecond = 1.5e8;
  t.stats.secondsTotal = 12.5;
  t.stats.secondsDirect = 3.25;
  t.stats.secondsBounce = {4.0, 5.25};
  t.stats.raysBounce = {100, 200};
  t.stats.threads = 2;
  t.stats.vertices = n;
  t.stats.stdErrT0Mean = 1e-3;
  t.stats.stdErrT0Max = 4e-3;
  t.stats.stdErrConstMean = 2e-3;
  t.stats.stdErrConstMax = 8e-3;
  t.transfer = randomField(bands, channels, first, n, seed);
  return t;
}

BakeFile sampleBake() {
  BakeFile b;
  b.mesh = twoPartMesh();
  b.generator = "prtkit test";
  // Scalar 3 bands (9 floats: 3 VEC4 columns, the last padded), RGB 4 bands (48: 12 columns).
  const std::size_t V = b.mesh.vertexCount();
  b.transfers.push_back(transfer(TransferMode::Shadowed, 3, 1, 0, V, 1));
  b.transfers.push_back(transfer(TransferMode::Interreflected, 4, 3, 0, V, 2));
  return b;
}

std::span<const unsigned char> asBytes(const std::string& s) {
  return {reinterpret_cast<const unsigned char*>(s.data()), s.size()};
}

bool sameBits(const FloatArray& a, const FloatArray& b) {
  // (memcmp of two empty arrays may be handed null pointers: undefined, so not asked.)
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
}

/// Same shape and representation, and every number the same bits.
bool sameTransfer(const Transfer& a, const Transfer& b) {
  if (!(a.shape() == b.shape()) || a.representation() != b.representation()) return false;
  if (!a.compressed()) return sameBits(a.values(), b.values());
  const CpcaRows &x = a.cpca(), &y = b.cpca();
  return x.clusters == y.clusters && x.basisCount == y.basisCount && x.cluster == y.cluster &&
         sameBits(x.weights, y.weights) && sameBits(x.means, y.means) && sameBits(x.basis, y.basis);
}

void expectSameBake(const BakeFile& a, const BakeFile& b) {
  EXPECT_EQ(a.mesh.positions, b.mesh.positions);
  EXPECT_EQ(a.mesh.normals, b.mesh.normals);
  EXPECT_EQ(a.mesh.albedo, b.mesh.albedo);
  ASSERT_EQ(a.mesh.uvs.size(), b.mesh.uvs.size());
  for (std::size_t i = 0; i < a.mesh.uvs.size(); ++i) {
    EXPECT_EQ(a.mesh.uvs[i].x, b.mesh.uvs[i].x);
    EXPECT_EQ(a.mesh.uvs[i].y, b.mesh.uvs[i].y);
  }
  EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
  ASSERT_EQ(a.mesh.parts.size(), b.mesh.parts.size());
  for (std::size_t i = 0; i < a.mesh.parts.size(); ++i) {
    EXPECT_EQ(a.mesh.parts[i].name, b.mesh.parts[i].name);
    EXPECT_EQ(a.mesh.parts[i].firstVertex, b.mesh.parts[i].firstVertex);
    EXPECT_EQ(a.mesh.parts[i].vertexCount, b.mesh.parts[i].vertexCount);
    EXPECT_EQ(a.mesh.parts[i].firstTriangle, b.mesh.parts[i].firstTriangle);
    EXPECT_EQ(a.mesh.parts[i].triangleCount, b.mesh.parts[i].triangleCount);
  }
  EXPECT_EQ(a.rows(), b.rows());
  ASSERT_EQ(a.transfers.size(), b.transfers.size());
  for (std::size_t i = 0; i < a.transfers.size(); ++i) {
    const auto &x = a.transfers[i], &y = b.transfers[i];
    EXPECT_EQ(x.recipe.mode, y.recipe.mode);
    EXPECT_EQ(x.recipe.samples, y.recipe.samples);
    EXPECT_EQ(x.recipe.bounces, y.recipe.bounces);
    EXPECT_EQ(x.recipe.seed, y.recipe.seed);
    EXPECT_EQ(x.recipe.sampling, y.recipe.sampling);
    EXPECT_EQ(x.recipe.material, y.recipe.material);
    EXPECT_EQ(x.recipe, y.recipe);
    EXPECT_EQ(x.stats.rays, y.stats.rays);
    EXPECT_EQ(x.stats.raysPerSecond, y.stats.raysPerSecond);
    EXPECT_EQ(x.stats.secondsTotal, y.stats.secondsTotal);
    EXPECT_EQ(x.stats.secondsBounce, y.stats.secondsBounce);
    EXPECT_EQ(x.stats.raysBounce, y.stats.raysBounce);
    EXPECT_EQ(x.stats.stdErrT0Mean, y.stats.stdErrT0Mean);
    EXPECT_EQ(x.stats.stdErrConstMax, y.stats.stdErrConstMax);
    EXPECT_EQ(x.transfer.shape(), y.transfer.shape());
    EXPECT_TRUE(sameTransfer(x.transfer, y.transfer)) << "transfer " << i << " floats differ";
  }
}

using prt::testing::Glb;
using prt::testing::splitGlb;

TEST(BakeFile, RoundTripIsBitExact) {
  const BakeFile b = sampleBake();
  const std::string bytes = encodeBake(b);
  const BakeFile r = decodeBake(asBytes(bytes), "mem.glb");
  EXPECT_EQ(r.formatVersion, kBakeFormatVersion);
  EXPECT_EQ(r.generator, "prtkit test");
  EXPECT_EQ(r.mesh.source, "test-mesh");
  EXPECT_TRUE(r.complete());
  expectSameBake(b, r);
  // Encoding is a pure function of the bake: the same bytes again.
  EXPECT_EQ(encodeBake(r), bytes);
}

/// The GLB `bytes` with its JSON chunk replaced by `doc` (the BIN chunk kept).
std::string withJson(const std::string& bytes, const nlohmann::json& doc) {
  std::string json = doc.dump();
  while (json.size() % 4) json.push_back(' ');
  std::string edited = bytes.substr(0, 12);
  const auto put = [&](std::uint32_t v) { edited.append(reinterpret_cast<const char*>(&v), 4); };
  put(static_cast<std::uint32_t>(json.size()));
  put(0x4E4F534Au);
  edited += json;
  std::uint32_t oldJson;
  std::memcpy(&oldJson, bytes.data() + 12, 4);
  edited += bytes.substr(20 + oldJson);
  const std::uint32_t total = static_cast<std::uint32_t>(edited.size());
  std::memcpy(edited.data() + 8, &total, 4);
  return edited;
}

TEST(BakeFile, ExternalFilesAreNeverOpened) {
  const std::string bytes = encodeBake(sampleBake());
  nlohmann::json doc = splitGlb(bytes).json;
  doc["buffers"].push_back({{"byteLength", 16}, {"uri", "/etc/hostname"}});
  try {
    decodeBake(asBytes(withJson(bytes, doc)), "ext.glb");
    FAIL() << "a bake naming an external file was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("external file"), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "one line";
  }
}

BakedTransfer matrixTransfer(TransferMode mode, int bands, int channels, std::size_t n) {
  BakedTransfer t = transfer(mode, bands, channels, 0, n, 9);
  t.recipe.material = parseMaterial("ggx?roughness=0.35&ks=0.25,0.5,0.75&kd=0.5");
  Transfer f = Transfer::zeros(testdata::shapeOf(TransferLayout::Matrix, bands, channels, n));
  float* x = f.mutableValues();
  for (std::size_t k = 0; k < f.values().size(); ++k)
    x[k] = static_cast<float>(std::sin(0.37 * double(k)) / 3.0);
  t.transfer = std::move(f);
  return t;
}

TEST(BakeFile, MatricesRoundTripBitExact) {
  BakeFile b = sampleBake();
  const std::size_t V = b.mesh.vertexCount();
  // A shadowed matrix beside the shadowed vector: (mode, layout) pairs are unique.
  b.transfers.push_back(matrixTransfer(TransferMode::Shadowed, 3, 1, V));
  b.transfers.push_back(matrixTransfer(TransferMode::Interreflected, 2, 3, V));
  const std::string bytes = encodeBake(b);
  const BakeFile r = decodeBake(asBytes(bytes), "mem.glb");
  EXPECT_EQ(r.formatVersion, kBakeFormatVersion);
  expectSameBake(b, r);
  EXPECT_EQ(encodeBake(r), bytes);
  ASSERT_NE(r.find(TransferMode::Shadowed, TransferLayout::Matrix), nullptr);
  ASSERT_NE(r.find(TransferMode::Shadowed, TransferLayout::Vector), nullptr);
  // The policy: the richest mode, a matrix before a vector.
  EXPECT_EQ(&pickTransfer(r, std::nullopt, std::nullopt, "x"),
            r.find(TransferMode::Interreflected, TransferLayout::Matrix));
  EXPECT_EQ(&pickTransfer(r, TransferMode::Shadowed, TransferLayout::Vector, "x"),
            r.find(TransferMode::Shadowed, TransferLayout::Vector));
  EXPECT_THROW(pickTransfer(r, TransferMode::Unshadowed, std::nullopt, "x"), Error);
  // Matrices are not vertex attributes (a GPU guarantees only 16): an accessor named in extras.
  const Glb g = splitGlb(bytes);
  for (const auto& mesh : g.json["meshes"])
    for (const auto& [name, index] : mesh["primitives"][0]["attributes"].items())
      EXPECT_EQ(name.find("_M"), std::string::npos) << name;
  const auto& t2 = prtObject(g.json)["transfers"][2];
  EXPECT_EQ(t2["matrixAccessor"], "_PRT_SHADOWED_M");
  EXPECT_EQ(t2["settings"]["layout"], "matrix");
  // A file that claims version 1 but holds a matrix is refused, naming the problem.
  nlohmann::json doc = g.json;
  asVersion(doc, 1);
  const std::string edited = withJson(bytes, doc);
  try {
    decodeBake(asBytes(edited), "old.glb");
    FAIL() << "a matrix in a version-1 file was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("version 1"), std::string::npos) << e.what();
  }
}

TEST(BakeFile, WriteAndReadThroughDisk) {
  const prt::testing::ScratchDir scratch;
  const std::filesystem::path& dir = scratch.path();
  const std::string path = (dir / "b.glb").string();
  const BakeFile b = sampleBake();
  writeBake(path, b);
  expectSameBake(b, readBake(path));
  // A failed write leaves nothing behind.
  BakeFile bad = b;
  bad.transfers[1].transfer = bad.transfers[1].transfer.withFirstRow(1);  // ranges differ
  const std::string badPath = (dir / "bad.glb").string();
  EXPECT_THROW(writeBake(badPath, bad), Error);
  EXPECT_FALSE(std::filesystem::exists(badPath));
}

TEST(BakeFile, GltfRulesHold) {
  const BakeFile b = sampleBake();
  const std::string bytes = encodeBake(b);
  // GLB container: 12-byte header with the total length, 4-byte aligned chunks.
  std::uint32_t length;
  std::memcpy(&length, bytes.data() + 8, 4);
  EXPECT_EQ(length, bytes.size());
  EXPECT_EQ(bytes.size() % 4, 0u);
  const Glb g = splitGlb(bytes);
  const auto& j = g.json;
  EXPECT_EQ(j["asset"]["version"], "2.0");
  EXPECT_EQ(prtObject(j)["formatVersion"], kBakeFormatVersion);
  // The vendor extension is declared as used, never as required: any viewer shows the mesh.
  EXPECT_EQ(j["extensionsUsed"], nlohmann::json::array({kBakeExtension}));
  EXPECT_FALSE(j.contains("extensionsRequired"));
  EXPECT_FALSE(j.contains("extras"));
  ASSERT_EQ(j["buffers"].size(), 1u);
  EXPECT_FALSE(j["buffers"][0].contains("uri"));
  const std::size_t bufLen = j["buffers"][0]["byteLength"];
  EXPECT_LE(bufLen, g.bin.size());
  EXPECT_GE(bufLen + 3, g.bin.size());  // the chunk pads to 4 bytes at most

  // Which accessors are vertex attributes, and how many use each bufferView.
  std::map<int, int> attributeUsers;
  for (const auto& mesh : j["meshes"])
    for (const auto& prim : mesh["primitives"]) {
      std::size_t count = 0;
      for (auto it = prim["attributes"].begin(); it != prim["attributes"].end(); ++it) {
        const std::string name = it.key();
        const auto& acc = j["accessors"][it.value().get<int>()];
        if (count == 0) count = acc["count"];
        EXPECT_EQ(acc["count"], count) << name << ": attributes of a primitive differ in count";
        const bool standard =
            name == "POSITION" || name == "NORMAL" || name == "TEXCOORD_0" || name == "COLOR_0";
        EXPECT_TRUE(standard || name.rfind("_PRT_", 0) == 0) << name;
        EXPECT_EQ(acc["componentType"], 5126) << name;  // float (never unsigned int for _ attrs)
        attributeUsers[acc["bufferView"]]++;
      }
      // POSITION carries exact min/max (required by the spec).
      const auto& pos = j["accessors"][prim["attributes"]["POSITION"].get<int>()];
      ASSERT_TRUE(pos.contains("min") && pos.contains("max"));
      const int first = pos.value("byteOffset", 0) / 12;
      const int n = pos["count"];
      for (int c = 0; c < 3; ++c) {
        float lo = 1e30f, hi = -1e30f;
        for (int v = first; v < first + n; ++v) {
          lo = std::min(lo, b.mesh.positions[v][c]);
          hi = std::max(hi, b.mesh.positions[v][c]);
        }
        EXPECT_EQ(pos["min"][c].get<double>(), lo);
        EXPECT_EQ(pos["max"][c].get<double>(), hi);
      }
      EXPECT_EQ(prim.value("mode", 4), 4);
      EXPECT_EQ(j["accessors"][prim["indices"].get<int>()]["componentType"], 5125);
    }
  for (std::size_t v = 0; v < j["bufferViews"].size(); ++v) {
    const auto& bv = j["bufferViews"][v];
    const std::size_t off = bv.value("byteOffset", 0), len = bv["byteLength"];
    EXPECT_EQ(off % 4, 0u);
    EXPECT_LE(off + len, bufLen);
    if (bv.contains("byteStride")) {
      const int s = bv["byteStride"];
      EXPECT_TRUE(s >= 4 && s <= 252 && s % 4 == 0) << "byteStride " << s;
      EXPECT_NE(bv.value("target", 0), 34963) << "index views must not have a stride";
    }
    if (attributeUsers[static_cast<int>(v)] > 1) {
      EXPECT_TRUE(bv.contains("byteStride")) << "shared vertex view " << v << " needs byteStride";
    }
  }
  for (const auto& acc : j["accessors"]) {
    const std::size_t off = acc.value("byteOffset", 0);
    EXPECT_EQ(off % 4, 0u);
  }
}

// Reads a primitive's _PRT attributes through tinygltf alone (not our reader) and compares them
// with the transfer rows: the packing documented in docs/formats-bake.md.
TEST(BakeFile, AttributePackingMatchesDocumentation) {
  const BakeFile b = sampleBake();
  const std::string bytes = encodeBake(b);
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromMemory(&model, &err, &warn,
                                          reinterpret_cast<const unsigned char*>(bytes.data()),
                                          static_cast<unsigned>(bytes.size())))
      << err;
  ASSERT_EQ(model.meshes.size(), 2u);
  for (const auto& t : b.transfers) {
    const std::size_t S = t.transfer.stride(), K = (S + 3) / 4;
    const std::string prefix = transferAttributePrefix(t.mode());
    for (std::size_t part = 0; part < 2; ++part) {
      const auto& prim = model.meshes[part].primitives[0];
      const MeshPart& mp = b.mesh.parts[part];
      EXPECT_EQ(prim.attributes.count(prefix + std::to_string(K)), 0u);
      for (std::size_t k = 0; k < K; ++k) {
        const auto it = prim.attributes.find(prefix + std::to_string(k));
        ASSERT_NE(it, prim.attributes.end()) << prefix << k;
        const auto& acc = model.accessors[it->second];
        const auto& view = model.bufferViews[acc.bufferView];
        const int stride = acc.ByteStride(view);
        ASSERT_EQ(acc.count, mp.vertexCount);
        for (std::size_t v = 0; v < mp.vertexCount; ++v) {
          float q[4];
          std::memcpy(
              q, model.buffers[0].data.data() + view.byteOffset + acc.byteOffset + v * stride, 16);
          for (std::size_t c = 0; c < 4; ++c) {
            const std::size_t idx = 4 * k + c;
            const float expect = idx < S ? t.transfer.row(mp.firstVertex + v)[idx] : 0.0f;
            ASSERT_EQ(std::memcmp(&q[c], &expect, 4), 0) << "vertex " << v << " float " << idx;
          }
        }
      }
    }
  }
  EXPECT_EQ(transferAttributePrefix(TransferMode::Unshadowed), "_PRT_UNSHADOWED_T");
}

TEST(BakeFile, PartialRangesMergeExactly) {
  const BakeFile full = sampleBake();
  const std::size_t V = full.mesh.vertexCount();
  auto piece = [&](std::size_t first, std::size_t n) {
    BakeFile p = full;
    for (auto& t : p.transfers) {
      const std::size_t S = t.transfer.stride();
      const float* all = full.find(t.mode())->transfer.values().data();
      TransferShape shape = t.transfer.shape();
      shape.rows = {first, n};
      t.transfer = Transfer::dense(
          shape, FloatArray(std::vector<float>(all + first * S, all + (first + n) * S)));
      t.stats.vertices = n;
    }
    // Through the file format: a partial file has no per-primitive transfer attributes.
    const std::string bytes = encodeBake(p);
    const auto glb = splitGlb(bytes);  // (a temporary's member would die before the loop runs)
    for (const auto& mesh : glb.json["meshes"])
      for (auto it = mesh["primitives"][0]["attributes"].begin();
           it != mesh["primitives"][0]["attributes"].end(); ++it)
        EXPECT_NE(it.key().rfind("_PRT", 0), 0u) << it.key();
    BakeFile r = decodeBake(asBytes(bytes), "piece.glb");
    EXPECT_FALSE(r.complete());
    return r;
  };
  std::vector<BakeFile> pieces = {piece(6, 3), piece(0, 2), piece(2, 4)};
  const BakeFile merged = mergeBakes(pieces);
  EXPECT_TRUE(merged.complete());
  for (const auto& t : full.transfers) {
    const BakedTransfer* m = merged.find(t.mode());
    ASSERT_NE(m, nullptr);
    EXPECT_TRUE(sameTransfer(m->transfer, t.transfer));
    EXPECT_EQ(m->stats.rays, 3 * t.stats.rays);
    EXPECT_EQ(m->stats.vertices, V);
    EXPECT_DOUBLE_EQ(m->stats.stdErrT0Mean, t.stats.stdErrT0Mean);  // equal means stay equal
    EXPECT_DOUBLE_EQ(m->stats.secondsTotal, 3 * t.stats.secondsTotal);
  }
  // And the merged file is a complete bake that round-trips.
  expectSameBake(merged, decodeBake(asBytes(encodeBake(merged)), "merged.glb"));

  EXPECT_THROW(mergeBakes({piece(0, 2), piece(3, 6)}), Error);  // gap at vertex 2
  EXPECT_THROW(mergeBakes({piece(0, 3), piece(2, 7)}), Error);  // overlap
  BakeFile otherSeed = piece(2, 7);
  otherSeed.transfers[0].recipe.seed = 1;
  EXPECT_THROW(mergeBakes({piece(0, 2), otherSeed}), Error);
  BakeFile otherMesh = piece(2, 7);
  otherMesh.mesh.positions[0].x += 1.0f;
  EXPECT_THROW(mergeBakes({piece(0, 2), otherMesh}), Error);
}

TEST(BakeFile, NewerFormatVersionIsRejectedWithOneLine) {
  std::string bytes = encodeBake(sampleBake());
  const std::string key = "\"formatVersion\":" + std::to_string(kBakeFormatVersion);
  const auto at = bytes.find(key);
  ASSERT_NE(at, std::string::npos);
  // The next version, the generator's name shortened to match: the container stays valid.
  const std::string newer = std::to_string(kBakeFormatVersion + 1);
  const std::size_t longer = newer.size() - std::to_string(kBakeFormatVersion).size();
  bytes.replace(at + key.size() - newer.size() + longer, newer.size() - longer, newer);
  const auto generator = bytes.find("\"generator\":\"");
  ASSERT_NE(generator, std::string::npos);
  bytes.erase(generator + 13, longer);
  try {
    decodeBake(asBytes(bytes), "new.glb");
    FAIL() << "accepted a newer format";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "new.glb: bake format version " + newer +
                                         " is newer than this prtkit understands (" +
                                         std::to_string(kBakeFormatVersion) + ")");
  }
}

TEST(BakeFile, ForeignGltfIsRejected) {
  std::string bytes = encodeBake(sampleBake());
  // The extension's object renamed: a glTF that only says it uses the extension.
  const auto at = bytes.find(std::string("\"") + kBakeExtension + "\":{");
  ASSERT_NE(at, std::string::npos);
  bytes[at + 1] = 'X';
  try {
    decodeBake(asBytes(bytes), "other.glb");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not a prtkit bake file"), std::string::npos) << e.what();
  }
}

// A seed string past 2^64 - 1 is our one-line error, not std::stoull's bare "stoull".
TEST(BakeFile, SeedPastTwoToTheSixtyFourIsRejectedByName) {
  BakeFile b = sampleBake();
  b.transfers[0].recipe.seed = UINT64_MAX;
  std::string bytes = encodeBake(b);
  const auto at = bytes.find("\"18446744073709551615\"");
  ASSERT_NE(at, std::string::npos);
  bytes[at + 1] = '9';  // same length: the container stays valid
  try {
    decodeBake(asBytes(bytes), "big.glb");
    FAIL() << "accepted a seed past 2^64";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("big.glb: "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("larger than 2^64 - 1"), std::string::npos) << e.what();
  }
}

TEST(BakeFile, InconsistentMetadataIsRejected) {
  // Claim 4 bands where 3 are stored: the accessor list no longer matches B²·C.
  std::string bytes = encodeBake(sampleBake());
  const auto at = bytes.find("\"bands\":3");
  ASSERT_NE(at, std::string::npos);
  bytes[at + 8] = '4';
  EXPECT_THROW(decodeBake(asBytes(bytes), "x.glb"), Error);
  // Claim one more vertex than the meshes hold.
  bytes = encodeBake(sampleBake());
  const auto at2 = bytes.find("\"vertexCount\":9");
  ASSERT_NE(at2, std::string::npos);
  bytes[at2 + 14] = '8';
  EXPECT_THROW(decodeBake(asBytes(bytes), "x.glb"), Error);
}

TEST(BakeFile, TruncatedOrCorruptFilesThrowNeverCrash) {
  const std::string bytes = encodeBake(sampleBake());
  // Every truncation must be reported (the GLB length field no longer matches).
  for (std::size_t n = 0; n < bytes.size(); n += (n < 64 ? 1 : 7)) {
    const std::string cut = bytes.substr(0, n);
    EXPECT_THROW(decodeBake(asBytes(cut), "cut.glb"), Error) << "length " << n;
  }
  // Random byte corruption anywhere: either a clean Error or a successfully parsed bake.
  std::mt19937 rng(7);
  for (int trial = 0; trial < 300; ++trial) {
    std::string bad = bytes;
    const int flips = 1 + static_cast<int>(rng() % 4);
    for (int f = 0; f < flips; ++f) bad[rng() % bad.size()] = static_cast<char>(rng());
    try {
      const BakeFile r = decodeBake(asBytes(bad), "bad.glb");
      for (const auto& t : r.transfers) {
        EXPECT_EQ(t.transfer.rows(), r.rows());
        if (!t.transfer.compressed()) {
          EXPECT_EQ(t.transfer.values().size(), r.rows().count * t.transfer.stride());
        }
      }
    } catch (const Error&) {
    }
  }
  EXPECT_THROW(decodeBake(asBytes(std::string("not a glb at all")), "t.glb"), Error);
}

TEST(BakeFile, WriterRejectsInconsistentBakes) {
  BakeFile b = sampleBake();
  b.transfers.push_back(b.transfers[0]);  // duplicate mode
  EXPECT_THROW(encodeBake(b), Error);
  b = sampleBake();
  b.mesh.parts[1].firstVertex = 3;  // parts overlap
  EXPECT_THROW(encodeBake(b), Error);
  b = sampleBake();
  for (BakedTransfer& t : b.transfers) t.transfer = t.transfer.withFirstRow(100);
  EXPECT_THROW(encodeBake(b), Error);  // outside the mesh
  b = sampleBake();
  b.mesh.triangles.clear();
  b.mesh.parts.clear();
  EXPECT_THROW(encodeBake(b), Error);
  // A mesh without parts is written as one part.
  b = sampleBake();
  b.mesh.parts.clear();
  const BakeFile r = decodeBake(asBytes(encodeBake(b)), "one.glb");
  ASSERT_EQ(r.mesh.parts.size(), 1u);
  EXPECT_EQ(r.mesh.parts[0].vertexCount, b.mesh.vertexCount());
  EXPECT_EQ(r.mesh.triangles, b.mesh.triangles);
}

// Compressed transfer: bit-exact round trip of ids, weights, means and bases for a vector and a
// matrix transfer, uint16 ids, stats kept; a version-2 claim is refused by name.
TEST(BakeFile, CompressedTransferRoundTripsBitExact) {
  BakeFile b = sampleBake();
  b.transfers.push_back(matrixTransfer(TransferMode::Unshadowed, 2, 3, b.mesh.vertexCount()));
  for (std::size_t i : {std::size_t(0), std::size_t(2)}) {  // shadowed vector, unshadowed matrix
    BakedTransfer& t = b.transfers[i];
    CpcaOptions o;
    o.clusters = 3;
    o.basisCount = i == 0 ? 2 : 0;  // N = 0 (no weights, no basis) for the matrix
    o.seed = 77;
    o.maxIterations = 10;
    CpcaStats stats;
    t.transfer = compressCpca(t.transfer, o, &stats);
    t.compression = {o, stats};
  }
  const std::string bytes = encodeBake(b);
  const BakeFile r = decodeBake(asBytes(bytes), "mem.glb");
  EXPECT_EQ(encodeBake(r), bytes);
  for (std::size_t i : {std::size_t(0), std::size_t(2)}) {
    const BakedTransfer &x = b.transfers[i], &y = r.transfers[i];
    ASSERT_TRUE(y.transfer.compressed());
    EXPECT_TRUE(sameTransfer(x.transfer, y.transfer));
    EXPECT_EQ(y.compression.fit.seed, 77u);
    EXPECT_EQ(y.compression.stats.squaredError, x.compression.stats.squaredError);
    EXPECT_EQ(y.compression.stats.iterations, x.compression.stats.iterations);
    EXPECT_TRUE(sameBits(y.transfer.toDense().values(), x.transfer.toDense().values()));
  }
  EXPECT_FALSE(r.transfers[1].transfer.compressed());
  const Glb g = splitGlb(bytes);
  const auto& t0 = prtObject(g.json)["transfers"][0];
  EXPECT_EQ(t0["compressed"]["clusters"], 3);
  EXPECT_EQ(t0["accessors"].size(), 4u);
  EXPECT_EQ(g.json["accessors"][t0["accessors"][0].get<int>()]["componentType"], 5123);  // uint16
  EXPECT_EQ(prtObject(g.json)["transfers"][2]["accessors"].size(), 2u);
  // No compressed accessor is a primitive attribute.
  for (const auto& mesh : g.json["meshes"])
    for (const auto& [name, index] : mesh["primitives"][0]["attributes"].items())
      EXPECT_EQ(name.find("_PRT_SHADOWED"), std::string::npos) << name;
  // A version-2 claim holding compressed transfer is refused, naming the version.
  nlohmann::json doc = g.json;
  asVersion(doc, 2);
  // (Version 2 stored the material as its spec string.)
  for (auto& t : doc["extras"]["prtkit"]["transfers"])
    t["settings"]["material"] = parseMaterial("lambert").spec();
  try {
    decodeBake(asBytes(withJson(bytes, doc)), "old.glb");
    FAIL() << "compressed transfer in a version-2 file was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("needs version 3"), std::string::npos) << e.what();
  }
  // Hand-edited shapes are refused with one line naming the file: fewer clusters than the
  // arrays hold, more basis vectors than the accessor list.
  for (const auto& [from, to] :
       {std::pair<std::string, std::string>{"\"clusters\":3", "\"clusters\":2"},
        {"\"basisCount\":2", "\"basisCount\":1"},
        {"\"basisCount\":0", "\"basisCount\":1"}}) {
    std::string bad = bytes;
    const auto pos = bad.find(from);
    ASSERT_NE(pos, std::string::npos) << from;
    bad.replace(pos, from.size(), to);
    try {
      decodeBake(asBytes(bad), "bad.glb");
      FAIL() << to << " was accepted";
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind("bad.glb: ", 0), 0u) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
  // Compressed pieces are not merged.
  EXPECT_THROW(mergeBakes({b, b}), Error);
}

// The material is stored as structured fields that read back exactly (version 4), and the
// spec string of versions 2-3 still reads.
TEST(BakeFile, MaterialIsStructuredAndReadsBackExactly) {
  BakeFile b = sampleBake();
  Material m = parseMaterial("phong?exponent=17.123456789&ks=0.1234567,0.5,0.75");
  m.diffuse = Rgb(1.0f / 3.0f, 0.2f, 0.7f);
  b.transfers[0].recipe.material = m;
  const std::string bytes = encodeBake(b);
  const BakeFile r = decodeBake(asBytes(bytes), "m.glb");
  EXPECT_EQ(r.transfers[0].recipe.material, m);
  const nlohmann::json j = prtObject(splitGlb(bytes).json)["transfers"][0]["settings"]["material"];
  EXPECT_EQ(j["type"], "phong");
  EXPECT_EQ(j["exponent"].get<double>(), 17.123456789);
  EXPECT_EQ(j["ks"][0].get<double>(), 0.1234567);  // the float's shortest decimal
  EXPECT_FALSE(prtObject(splitGlb(bytes).json)["transfers"][0]["settings"].contains("albedo"));
  // Version 3 wrote the spec string and a separate albedo: both still read.
  nlohmann::json doc = splitGlb(bytes).json;
  asVersion(doc, 3);
  doc["extras"]["prtkit"]["transfers"][0]["settings"]["material"] = "ggx?roughness=0.5&ks=0.25";
  doc["extras"]["prtkit"]["transfers"][0]["settings"]["albedo"] = {0.5, 0.25, 0.125};
  const BakeFile old = decodeBake(asBytes(withJson(bytes, doc)), "old.glb");
  const Material& om = old.transfers[0].recipe.material;
  EXPECT_EQ(om.lobe.kind, LobeKind::Ggx);
  EXPECT_EQ(om.lobe.roughness, 0.5);
  EXPECT_EQ(om.specular, Rgb(0.25f));
  EXPECT_EQ(*om.diffuse, Rgb(0.5f, 0.25f, 0.125f));
  // A structured material out of range is refused by name.
  doc = splitGlb(bytes).json;
  prtObject(doc)["transfers"][0]["settings"]["material"]["exponent"] = -1;
  try {
    decodeBake(asBytes(withJson(bytes, doc)), "bad.glb");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("material.exponent"), std::string::npos) << e.what();
  }
}

// A dense matrix read from a file views the file's bytes instead of copying them.
TEST(BakeFile, ReadingViewsTheFileForMatrices) {
  const prt::testing::ScratchDir scratch;
  const std::string path = (scratch.path() / "m.glb").string();
  BakeFile b = sampleBake();
  b.transfers.push_back(matrixTransfer(TransferMode::Shadowed, 3, 1, b.mesh.vertexCount()));
  writeBake(path, b);
  const BakeFile r = readBake(path);
  const BakedTransfer* m = r.find(TransferMode::Shadowed, TransferLayout::Matrix);
  ASSERT_NE(m, nullptr);
  EXPECT_TRUE(m->transfer.values().isView());
  EXPECT_FALSE(r.find(TransferMode::Shadowed, TransferLayout::Vector)->transfer.values().isView());
  expectSameBake(b, r);
  // decodeBake of bytes the caller owns copies.
  const std::string bytes = encodeBake(b);
  EXPECT_FALSE(decodeBake(asBytes(bytes), "x")
                   .find(TransferMode::Shadowed, TransferLayout::Matrix)
                   ->transfer.values()
                   .isView());
}

// The writer writes only what its reader reads, and both hold a recipe to what bake() does
// (checkRecipe): a kd beyond 1, a sample count of 0, bounces beyond 16 are refused on the way
// out and on the way in, whatever version the file claims.
TEST(BakeFile, WriterAndReaderHoldTheRecipeToWhatABakeCouldMake) {
  BakeFile b = sampleBake();
  b.transfers[0].recipe.material.diffuse = Rgb(2.0f, 0.5f, 0.5f);
  try {
    encodeBake(b);
    ADD_FAILURE() << "a kd of 2 was written";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("kd"), std::string::npos) << e.what();
  }
  const std::string bytes = encodeBake(sampleBake());
  const Glb g = splitGlb(bytes);
  struct Edit {
    const char* what;
    std::function<void(nlohmann::json&)> apply;
    const char* expect;
  };
  const std::vector<Edit> edits = {
      {"kd 2",
       [](nlohmann::json& s) {
         s["material"]["kd"] = {2.0, 0.5, 0.5};
       },
       "kd"},
      {"old albedo 2",
       [](nlohmann::json& s) {
         s["material"] = "lambert";
         s["albedo"] = {2.0, 0.5, 0.5};
       },
       "albedo"},
      {"samples 0", [](nlohmann::json& s) { s["samples"] = 0; }, "samples"},
      {"bounces 17", [](nlohmann::json& s) { s["bounces"] = 17; }, "bounces"},
      {"target error -1", [](nlohmann::json& s) { s["targetError"] = -1.0; }, "target error"},
      {"target error 2", [](nlohmann::json& s) { s["targetError"] = 2.0; }, "target error"},
      {"target error text", [](nlohmann::json& s) { s["targetError"] = "0.01"; }, "targetError"},
  };
  for (const Edit& e : edits) {
    SCOPED_TRACE(e.what);
    nlohmann::json doc = g.json;
    const bool old = std::string(e.what) == "old albedo 2";
    if (old) asVersion(doc, 3);
    for (auto& t : (old ? doc["extras"]["prtkit"] : prtObject(doc))["transfers"]) {
      if (std::string(e.what) == "old albedo 2") t["settings"]["material"] = "lambert";
      e.apply(t["settings"]);
    }
    try {
      decodeBake(asBytes(withJson(bytes, doc)), "edited.glb");
      ADD_FAILURE() << "read";
    } catch (const Error& err) {
      const std::string m = err.what();
      EXPECT_EQ(m.rfind("edited.glb", 0), 0u) << m;
      EXPECT_NE(m.find(e.expect), std::string::npos) << m;
    }
  }
}

// Adaptive sampling's target (BakeRecipe::targetError) is part of the recipe: written only when
// set, read back exactly, and a file without it reads as 0 (every row cast `samples`).
TEST(BakeFile, TheTargetErrorRoundTripsWhenSet) {
  BakeFile b = sampleBake();
  EXPECT_EQ(
      prtObject(splitGlb(encodeBake(b)).json)["transfers"][0]["settings"].count("targetError"), 0u);
  b.transfers[0].recipe.targetError = 0.0125;
  const std::string bytes = encodeBake(b);
  EXPECT_EQ(prtObject(splitGlb(bytes).json)["transfers"][0]["settings"]["targetError"], 0.0125);
  const BakeFile back = decodeBake(asBytes(bytes), "adaptive.glb");
  EXPECT_EQ(back.transfers[0].recipe.targetError, 0.0125);
  EXPECT_EQ(back.transfers[0].recipe, b.transfers[0].recipe);
}

// A compressed transfer cut below its basis (N > values per row) cannot be stored: refused by
// the writer with what to do, rather than written and refused by the reader.
TEST(BakeFile, CompressedTransferCutBelowItsBasisIsRefusedOnTheWayOut) {
  BakeFile b = sampleBake();
  BakedTransfer& t = b.transfers[0];
  CpcaOptions o;
  o.clusters = 2;
  o.basisCount = 6;
  o.maxIterations = 5;
  t.transfer = compressCpca(t.transfer, o);
  ASSERT_GT(t.transfer.bands(), 1);
  t.transfer = t.transfer.cut(1);  // 1 value per row (x channels), 6 basis vectors
  ASSERT_GT(static_cast<std::size_t>(t.transfer.cpca().basisCount), t.transfer.stride());
  try {
    encodeBake(b);
    ADD_FAILURE() << "written";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("basis vectors"), std::string::npos) << e.what();
  }
  b.transfers[0].transfer = b.transfers[0].transfer.toDense();
  EXPECT_NO_THROW(decodeBake(asBytes(encodeBake(b)), "dense.glb"));
}

}  // namespace
}  // namespace prt

namespace prt {
namespace {

// A matrix transfer carries its material's kernels per band ("response", docs/formats-bake.md)
// for engines: against the closed forms — the clamped cosine's A_l/π = 1, 2/3, 1/4 and the
// normalised Phong lobe's Λ_l = (s+1) ∫₀¹ t^s P_l(t) dt = 1, (s+1)/(s+2), s/(s+3) — and zero
// lobe for a Lambertian one; a vector transfer carries none.
TEST(BakeFile, MatrixTransfersCarryTheirMaterialsKernels) {
  BakeFile b = sampleBake();
  const std::size_t V = b.mesh.vertexCount();
  b.transfers.push_back(matrixTransfer(TransferMode::Shadowed, 3, 1, V));
  b.transfers.push_back(matrixTransfer(TransferMode::Interreflected, 3, 3, V));
  const double s = 8;
  const std::size_t n = b.transfers.size();
  b.transfers[n - 2].recipe.material = parseMaterial("phong?exponent=8&ks=0.5");
  b.transfers[n - 1].recipe.material = parseMaterial("lambert");
  const nlohmann::json t = prtObject(splitGlb(encodeBake(b)).json)["transfers"];
  ASSERT_EQ(t.size(), n);
  for (std::size_t i = 0; i + 2 < n; ++i) EXPECT_FALSE(t[i].contains("response")) << i;
  const double diffuse[3] = {1, 2.0 / 3, 0.25}, phong[3] = {1, (s + 1) / (s + 2), s / (s + 3)};
  for (std::size_t i = n - 2; i < n; ++i) {
    ASSERT_TRUE(t[i].contains("response")) << i;
    const nlohmann::json& r = t[i]["response"];
    ASSERT_EQ(r["diffuse"].size(), 3u);
    ASSERT_EQ(r["lobe"].size(), 3u);
    for (int l = 0; l < 3; ++l) {
      EXPECT_NEAR(r["diffuse"][l].get<double>(), diffuse[l], 1e-12) << l;
      EXPECT_NEAR(r["lobe"][l].get<double>(), i == n - 2 ? phong[l] : 0.0, 1e-6) << l;
    }
  }
}

}  // namespace
}  // namespace prt

namespace prt {
namespace {

// Lightmap UVs travel with the mesh (issue 18): the only UV set goes as TEXCOORD_0, beside a
// texture set as TEXCOORD_1, and the bake's object names which (lightmapTexCoord); both read
// back exactly, and a glTF reader sees TEXCOORD_1 as the lightmap set.
TEST(BakeFile, LightmapUvsRoundTripInTheirSet) {
  BakeFile b = sampleBake();
  b.mesh.uvs.clear();
  const std::size_t V = b.mesh.vertexCount();
  for (std::size_t v = 0; v < V; ++v) b.mesh.lightmapUvs.push_back({float(v) / V, 0.5f});
  std::string bytes = encodeBake(b);
  nlohmann::json j = splitGlb(bytes).json;
  EXPECT_EQ(prtObject(j)["lightmapTexCoord"], 0);
  EXPECT_TRUE(j["meshes"][0]["primitives"][0]["attributes"].contains("TEXCOORD_0"));
  EXPECT_FALSE(j["meshes"][0]["primitives"][0]["attributes"].contains("TEXCOORD_1"));
  BakeFile r = decodeBake(asBytes(bytes), "lm.glb");
  EXPECT_TRUE(r.mesh.uvs.empty());
  ASSERT_EQ(r.mesh.lightmapUvs.size(), V);
  for (std::size_t v = 0; v < V; ++v) EXPECT_EQ(r.mesh.lightmapUvs[v].x, b.mesh.lightmapUvs[v].x);

  for (std::size_t v = 0; v < V; ++v) b.mesh.uvs.push_back({0.25f, float(v)});
  bytes = encodeBake(b);
  j = splitGlb(bytes).json;
  EXPECT_EQ(prtObject(j)["lightmapTexCoord"], 1);
  r = decodeBake(asBytes(bytes), "lm2.glb");
  ASSERT_EQ(r.mesh.uvs.size(), V);
  ASSERT_EQ(r.mesh.lightmapUvs.size(), V);
  for (std::size_t v = 0; v < V; ++v) {
    EXPECT_EQ(r.mesh.uvs[v].y, float(v));
    EXPECT_EQ(r.mesh.lightmapUvs[v].x, b.mesh.lightmapUvs[v].x);
  }
  const testing::ScratchDir dir("lightmap");
  const Mesh loaded = loadMesh(dir.write("lm2.glb", bytes));
  ASSERT_EQ(loaded.lightmapUvs.size(), V);
  EXPECT_EQ(loaded.lightmapUvs[V - 1].x, b.mesh.lightmapUvs[V - 1].x);
  // A lightmapTexCoord naming a set the mesh lacks is refused by name.
  prtObject(j)["lightmapTexCoord"] = 1;
  j["meshes"][0]["primitives"][0]["attributes"].erase("TEXCOORD_1");
  try {
    decodeBake(asBytes(withJson(bytes, j)), "bad.glb");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("TEXCOORD_1"), std::string::npos) << e.what();
  }
}

/// A bake of per-texel transfer over the two-part mesh's lightmap UVs: a W × H lightmap, rows
/// [first, first + n), scalar 3 bands and RGB 2 bands.
BakeFile texelBake(int W, int H, std::size_t first, std::size_t n) {
  BakeFile b;
  b.mesh = twoPartMesh();
  const std::size_t V = b.mesh.vertexCount();
  for (std::size_t v = 0; v < V; ++v) b.mesh.lightmapUvs.push_back({float(v) / V, 0.25f});
  int seed = 11;
  for (const auto& [mode, bands, channels] : std::vector<std::tuple<TransferMode, int, int>>{
           {TransferMode::Shadowed, 3, 1}, {TransferMode::Interreflected, 2, 3}}) {
    BakedTransfer t = transfer(mode, bands, channels, first, n, unsigned(seed++));
    TransferShape shape = t.transfer.shape();
    shape.domain = TransferDomain::Texels;
    shape.lightmap = {W, H, 2};
    t.transfer = Transfer::dense(shape, t.transfer.values());
    b.transfers.push_back(std::move(t));
  }
  return b;
}

// mapBake reads what readBake reads, the rows viewing the mapped file (dense and compressed),
// and leaves the rows' values unread: a non-finite value that readBake refuses is read back as
// it is (its reader checks the rows it reads: render::validate), while a cluster id beyond K is
// still refused.
TEST(BakeFile, MappingLeavesTheRowsUnreadUntilTouched) {
  const prt::testing::ScratchDir scratch;
  const int W = 16, H = 8;
  BakeFile b = texelBake(W, H, 0, W * H);
  CpcaOptions cs;
  cs.clusters = 3;
  cs.basisCount = 2;
  b.transfers[1].transfer = compressCpca(b.transfers[1].transfer, cs);
  const std::string clean = (scratch.path() / "clean.glb").string();
  writeBake(clean, b);
  const BakeFile mapped = mapBake(clean);
  expectSameBake(b, mapped);
  EXPECT_TRUE(mapped.transfers[0].transfer.values().isView());
  EXPECT_TRUE(mapped.transfers[1].transfer.cpca().weights.isView());

  // One non-finite value in each transfer's rows: a dense row's (the writer takes it), a
  // compressed row's weight (patched into the file: the writer refuses it).
  BakeFile corrupt = b;
  const std::size_t row = 77;
  corrupt.transfers[0].transfer.mutableValues()[row * corrupt.transfers[0].transfer.stride()] =
      std::numeric_limits<float>::infinity();
  std::string bytes = encodeBake(corrupt);
  const float weight = b.transfers[1].transfer.cpca().weights[row * 2 + 1];
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::size_t at = bytes.find(std::string(reinterpret_cast<const char*>(&weight), 4));
  ASSERT_NE(at, std::string::npos);
  ASSERT_EQ(bytes.find(std::string(reinterpret_cast<const char*>(&weight), 4), at + 1),
            std::string::npos);
  std::memcpy(&bytes[at], &nan, 4);
  const std::string bad = scratch.write("bad.glb", bytes);
  EXPECT_NE(testing::errorOf([&] { readBake(bad); }).find("non-finite"), std::string::npos);
  const BakeFile read = mapBake(bad);
  EXPECT_TRUE(std::isinf(read.transfers[0].transfer.row(row)[0]));
  EXPECT_TRUE(std::isnan(read.transfers[1].transfer.cpca().weights[row * 2 + 1]));
  EXPECT_EQ(read.transfers[0].transfer.row(row + 1)[0], b.transfers[0].transfer.row(row + 1)[0]);
}

// Per-texel transfer in the file (format 6): each transfer's rows as one float accessor, the
// lightmap and texel range in the extension, the domain in the settings; bit-exact back, dense
// and compressed; split ranges merge exactly; and every way a file can lie about it refused
// by name.
TEST(BakeFile, TexelTransferRoundTripsAndMergesExactly) {
  const int W = 6, H = 5;
  const BakeFile b = texelBake(W, H, 0, W * H);
  const std::string bytes = encodeBake(b);
  nlohmann::json j = splitGlb(bytes).json;
  const nlohmann::json& o = prtObject(j);
  EXPECT_EQ(o["formatVersion"], kBakeFormatVersion);  // texels need 6; every file is written at the newest
  EXPECT_FALSE(o.contains("vertexRange"));
  EXPECT_EQ(o["texelRange"]["count"], W * H);
  EXPECT_EQ(o["lightmap"]["width"], W);
  EXPECT_EQ(o["lightmap"]["padding"], 2);
  EXPECT_EQ(o["transfers"][0]["settings"]["domain"], "texels");
  EXPECT_EQ(o["transfers"][0]["texelAccessor"], "_PRT_SHADOWED_TEXELS");
  // Texels are not vertex attributes: no primitive carries them.
  for (const auto& mesh : j["meshes"])
    for (auto it = mesh["primitives"][0]["attributes"].begin();
         it != mesh["primitives"][0]["attributes"].end(); ++it)
      EXPECT_NE(it.key().rfind("_PRT", 0), 0u) << it.key();
  const BakeFile r = decodeBake(asBytes(bytes), "texels.glb");
  expectSameBake(b, r);
  EXPECT_EQ(r.domain(), TransferDomain::Texels);
  EXPECT_EQ(r.domainRows(), std::size_t(W * H));
  EXPECT_TRUE(r.complete());
  EXPECT_EQ(r.transfers[1].transfer.shape().lightmap, (TransferShape::LightmapSize{W, H, 2}));
  EXPECT_NE(testing::errorOf([&] {
              r.requireVertices("texels.glb", "USE");
            }).find("texels.glb: holds per-texel transfer (a 6 x 5 lightmap); USE"),
            std::string::npos);

  // Compressed per-texel rows round-trip too.
  BakeFile c = b;
  CpcaOptions cs;
  cs.clusters = 3;
  cs.basisCount = 2;
  c.transfers[0].transfer = compressCpca(b.transfers[0].transfer, cs);
  const BakeFile rc = decodeBake(asBytes(encodeBake(c)), "cpca-texels.glb");
  EXPECT_TRUE(rc.transfers[0].transfer.compressed());
  EXPECT_EQ(rc.transfers[0].transfer.domain(), TransferDomain::Texels);
  EXPECT_TRUE(sameTransfer(rc.transfers[0].transfer, c.transfers[0].transfer));

  // Texel ranges merge exactly, and say texels when they do not fit.
  auto piece = [&](std::size_t first, std::size_t n) {
    BakeFile p = texelBake(W, H, first, n);
    for (std::size_t t = 0; t < p.transfers.size(); ++t) {
      const std::size_t S = p.transfers[t].transfer.stride();
      const float* all = b.transfers[t].transfer.values().data();
      p.transfers[t].transfer =
          Transfer::dense(p.transfers[t].transfer.shape(),
                          FloatArray(std::vector<float>(all + first * S, all + (first + n) * S)));
    }
    BakeFile back = decodeBake(asBytes(encodeBake(p)), "piece.glb");
    EXPECT_FALSE(back.complete());
    return back;
  };
  const BakeFile merged = mergeBakes({piece(13, 17), piece(0, 13)});
  EXPECT_TRUE(merged.complete());
  for (std::size_t t = 0; t < b.transfers.size(); ++t)
    EXPECT_TRUE(sameTransfer(merged.transfers[t].transfer, b.transfers[t].transfer));
  EXPECT_NE(testing::errorOf([&] {
              mergeBakes({piece(0, 10), piece(13, 17)});
            }).find("leaves a gap: texels 10..12 are missing"),
            std::string::npos);
  EXPECT_NE(testing::errorOf([&] {
              piece(0, 10).requireComplete("p.glb");
            }).find("holds transfer for texels 0..9 of 30"),
            std::string::npos);
  BakeFile otherMap = texelBake(W, H + 1, 13, 17);
  EXPECT_NE(testing::errorOf([&] {
              mergeBakes({piece(0, 13), otherMap});
            }).find("another lightmap"),
            std::string::npos);

  // The writer: one domain per file, UVs to be over.
  BakeFile mixed = b;
  mixed.transfers.push_back(transfer(TransferMode::Unshadowed, 2, 1, 0, b.mesh.vertexCount(), 5));
  EXPECT_NE(testing::errorOf([&] { encodeBake(mixed); }).find("different domains"),
            std::string::npos);
  BakeFile noUvs = b;
  noUvs.mesh.lightmapUvs.clear();
  EXPECT_NE(testing::errorOf([&] { encodeBake(noUvs); }).find("needs the mesh's lightmap UVs"),
            std::string::npos);

  // The reader: a range past the lightmap, a domain the settings contradict, texels in a
  // version-5 file, no UV set named, a lightmap beyond the limit.
  const auto refused = [&](const std::function<void(nlohmann::json&)>& edit) {
    nlohmann::json e = j;
    edit(e);
    return testing::errorOf([&] { decodeBake(asBytes(withJson(bytes, e)), "bad.glb"); });
  };
  EXPECT_NE(refused([](nlohmann::json& e) {
              prtObject(e)["texelRange"]["count"] = 31;
            }).find("texel range 0+31 is outside the lightmap (30 texels)"),
            std::string::npos);
  EXPECT_NE(refused([](nlohmann::json& e) {
              prtObject(e)["transfers"][1]["settings"]["domain"] = "vertices";
            }).find("domain is vertices in a bake over texels"),
            std::string::npos);
  EXPECT_NE(refused([](nlohmann::json& e) {
              prtObject(e)["formatVersion"] = 5;
            }).find("texels need version 6"),
            std::string::npos);
  EXPECT_NE(refused([](nlohmann::json& e) {
              prtObject(e).erase("lightmapTexCoord");
            }).find("names no lightmapTexCoord"),
            std::string::npos);
  EXPECT_NE(refused([](nlohmann::json& e) {
              prtObject(e)["lightmap"]["width"] = 9000;
            }).find("lightmap.width"),
            std::string::npos);
  EXPECT_NE(refused([](nlohmann::json& e) {
              prtObject(e)["vertexRange"] = {{"first", 0}};
            }).find("both a vertexRange and a texelRange"),
            std::string::npos);
  EXPECT_NE(refused([](nlohmann::json& e) {
              prtObject(e)["lightmap"]["seamsFixed"] = 1;
            }).find("lightmap.seamsFixed is not true or false"),
            std::string::npos);

  // The seam fix is recorded in the lightmap (absent: not applied) and read back.
  EXPECT_FALSE(o["lightmap"].contains("seamsFixed"));
  BakeFile fixed = b;
  for (BakedTransfer& t : fixed.transfers) {
    TransferShape shape = t.transfer.shape();
    shape.lightmap.seamsFixed = true;
    t.transfer = Transfer::dense(shape, t.transfer.values());
  }
  const std::string fixedBytes = encodeBake(fixed);
  EXPECT_EQ(prtObject(splitGlb(fixedBytes).json)["lightmap"]["seamsFixed"], true);
  EXPECT_TRUE(decodeBake(asBytes(fixedBytes), "fixed.glb").lightmap().seamsFixed);
}

}  // namespace
}  // namespace prt
