#include "prt/io/bake_file.hpp"

// The bake file, written and read with tinygltf (GLB container, JSON, buffers) while every
// size, bound and type is checked here, so that a truncated or hand-edited file gives one clear
// line instead of a crash. Layout: docs/formats-bake.md.

#include <tiny_gltf.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <sstream>

#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/core/limits.hpp"
#include "prt/geometry/load.hpp"
#include "prt/gltf/accessor.hpp"

namespace prt {

namespace {

using tinygltf::Value;

constexpr int kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT;
constexpr int kUint = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
constexpr int kUshort = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
constexpr int kMaxBands = 32;  // sanity bound on files; bakes use far fewer

// ---------------------------------------------------------------------------------------------
// JSON values (tinygltf::Value holds 32-bit ints only: larger integers are written as doubles,
// exact below 2^53, and seeds beyond that as decimal strings).

Value num(double x) {
  return Value(x);
}
Value count(std::uint64_t n) {
  return n <= static_cast<std::uint64_t>(std::numeric_limits<int>::max())
             ? Value(static_cast<int>(n))
             : Value(static_cast<double>(n));
}
Value seedValue(std::uint64_t s) {
  return s < (std::uint64_t(1) << 53) ? count(s) : Value(std::to_string(s));
}
Value str(const std::string& s) {
  return Value(s);
}

struct Reader {
  const std::string& name;
  [[noreturn]] void fail(const std::string& msg) const { throw Error(name, msg); }

  const Value& member(const Value& obj, const std::string& key, const std::string& where) const {
    if (!obj.IsObject() || !obj.Has(key)) fail(where + " lacks '" + key + "'");
    return obj.Get(key);
  }
  double number(const Value& obj, const std::string& key, const std::string& where) const {
    const Value& v = member(obj, key, where);
    if (!v.IsNumber()) fail(where + "." + key + " is not a number");
    return v.GetNumberAsDouble();
  }
  double numberOr(const Value& obj, const std::string& key, double fallback,
                  const std::string& where) const {
    return obj.IsObject() && obj.Has(key) ? number(obj, key, where) : fallback;
  }
  std::uint64_t integer(const Value& obj, const std::string& key, const std::string& where,
                        double lo = 0, double hi = 9007199254740992.0) const {
    const Value& v = member(obj, key, where);
    if (v.IsString()) {  // large seeds
      const std::string& s = v.Get<std::string>();
      if (s.empty() || s.size() > 20 ||
          !std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); }))
        fail(where + "." + key + " is not an integer");
      if (s.size() == 20 && s > "18446744073709551615")  // std::stoull would throw "stoull"
        fail(where + "." + key + " = " + s + " is larger than 2^64 - 1");
      return std::stoull(s);
    }
    const double x = number(obj, key, where);
    if (!(x == std::floor(x)) || x < lo || x > hi)
      fail(where + "." + key + " = " + std::to_string(x) + " is not an integer in range");
    return static_cast<std::uint64_t>(x);
  }
  std::string string(const Value& obj, const std::string& key, const std::string& where) const {
    const Value& v = member(obj, key, where);
    if (!v.IsString()) fail(where + "." + key + " is not a string");
    return v.Get<std::string>();
  }
};

// ---------------------------------------------------------------------------------------------
// Writing.

// The binary chunk is described, not assembled: each bufferView is a segment that writes its
// bytes straight from the mesh and transfer arrays when the file is streamed out, so writing a
// bake needs no second copy of the transfer (nor the several that assembling a GLB in memory
// costs: the buffer, tinygltf's chunk copy, the string stream and its result).
struct Segment {
  std::size_t offset = 0, size = 0;
  std::function<void(std::ostream&)> write;
};

struct BufferBuilder {
  tinygltf::Model& model;
  std::vector<Segment> segments;
  std::size_t length = 0;  ///< bytes of the binary chunk so far

  /// A new bufferView of `size` bytes (16-byte aligned) whose content `write` produces.
  int view(std::size_t size, int stride, int target, const std::string& name,
           std::function<void(std::ostream&)> write) {
    length = (length + 15) / 16 * 16;
    tinygltf::BufferView v;
    v.buffer = 0;
    v.byteOffset = length;
    v.byteLength = size;
    v.byteStride = static_cast<size_t>(stride);
    v.target = target;
    v.name = name;
    segments.push_back({length, size, std::move(write)});
    length += size;
    model.bufferViews.push_back(std::move(v));
    return static_cast<int>(model.bufferViews.size() - 1);
  }
  /// A bufferView of bytes that stay alive (and unchanged) until the file is written.
  int view(const void* data, std::size_t size, int stride, int target, const std::string& name) {
    const char* p = static_cast<const char*>(data);
    return view(size, stride, target, name,
                [p, size](std::ostream& os) { os.write(p, static_cast<std::streamsize>(size)); });
  }

  /// Streams the binary chunk: the segments in order, zero padding between and after them.
  void writeBinary(std::ostream& os, std::size_t paddedLength) const {
    static const char zeros[16] = {};
    std::size_t at = 0;
    for (const Segment& seg : segments) {
      os.write(zeros, static_cast<std::streamsize>(seg.offset - at));
      seg.write(os);
      at = seg.offset + seg.size;
    }
    os.write(zeros, static_cast<std::streamsize>(paddedLength - at));
  }

  int accessor(int view, std::size_t byteOffset, std::size_t n, int type, int componentType) {
    tinygltf::Accessor a;
    a.bufferView = view;
    a.byteOffset = byteOffset;
    a.count = n;
    a.type = type;
    a.componentType = componentType;
    model.accessors.push_back(std::move(a));
    return static_cast<int>(model.accessors.size() - 1);
  }
};

std::vector<MeshPart> partsOf(const Mesh& mesh) {
  if (!mesh.parts.empty()) return mesh.parts;
  MeshPart p;
  p.name = "mesh";
  p.vertexCount = static_cast<std::uint32_t>(mesh.vertexCount());
  p.triangleCount = static_cast<std::uint32_t>(mesh.triangleCount());
  return {p};
}

void validateForWriting(const BakeFile& bake, const std::vector<MeshPart>& parts) {
  const Mesh& m = bake.mesh;
  const std::size_t V = m.vertexCount(), T = m.triangleCount();
  if (V == 0 || T == 0) throw Error("bake file: the mesh is empty (no vertices or no triangles)");
  if (V > std::numeric_limits<std::uint32_t>::max()) throw Error("bake file: too many vertices");
  if (m.normals.size() != V) throw Error("bake file: mesh has no normal per vertex");
  if (!m.albedo.empty() && m.albedo.size() != V)
    throw Error("bake file: mesh albedo is not per vertex");
  if (!m.uvs.empty() && m.uvs.size() != V) throw Error("bake file: mesh uvs are not per vertex");
  std::uint32_t nextV = 0, nextT = 0;
  for (const MeshPart& p : parts) {
    if (p.firstVertex != nextV || p.firstTriangle != nextT || p.vertexCount == 0 ||
        p.triangleCount == 0)
      throw Error("bake file: mesh part '" + p.name +
                  "' does not continue the previous part or is empty");
    nextV += p.vertexCount;
    nextT += p.triangleCount;
    if (nextV > V || nextT > T)
      throw Error("bake file: mesh part '" + p.name + "' overruns the mesh");
    for (std::uint32_t t = p.firstTriangle; t < nextT; ++t)
      for (std::uint32_t i : m.triangles[t])
        if (i < p.firstVertex || i >= nextV)
          throw Error("bake file: triangle " + std::to_string(t) + " of part '" + p.name +
                      "' uses a vertex outside the part");
  }
  if (nextV != V || nextT != T) throw Error("bake file: mesh parts do not cover the mesh");
  if (bake.vertexCount == 0 || bake.firstVertex + bake.vertexCount > V)
    throw Error("bake file: vertex range " + std::to_string(bake.firstVertex) + "+" +
                std::to_string(bake.vertexCount) + " is outside the mesh (" + std::to_string(V) +
                " vertices)");
  for (std::size_t i = 0; i < bake.transfers.size(); ++i) {
    const auto& t = bake.transfers[i];
    const TransferField& f = t.field;
    for (std::size_t j = 0; j < i; ++j)
      if (bake.transfers[j].settings.mode == t.settings.mode &&
          bake.transfers[j].field.layout == f.layout)
        throw Error(std::string("bake file: two ") + toString(f.layout) + " transfers of mode " +
                    toString(t.settings.mode));
    if (f.bands < 1 || f.bands > kMaxBands || (f.channels != 1 && f.channels != 3))
      throw Error("bake file: transfer has " + std::to_string(f.bands) + " bands and " +
                  std::to_string(f.channels) + " channels");
    if (t.compressed) {
      const CompressedTransfer& c = *t.compressed;
      if (c.layout != f.layout || c.bands != f.bands || c.channels != f.channels ||
          c.vertexCount != bake.vertexCount || f.vertexCount != bake.vertexCount)
        throw Error("bake file: compressed transfer does not match its shape or the vertex range");
      c.check("bake file");
      continue;
    }
    if (f.vertexCount != bake.vertexCount || f.data.size() != f.vertexCount * f.stride())
      throw Error("bake file: transfer rows do not match the vertex range");
  }
}

Value settingsJson(const BakedTransfer& t) {
  const BakeSettings& s = t.settings;
  Value::Object o;
  o["mode"] = str(toString(s.mode));
  o["bands"] = Value(t.field.bands);
  o["channels"] = Value(t.field.channels);
  o["samples"] = Value(s.samples);
  o["bounces"] = Value(s.bounces);
  o["seed"] = seedValue(s.seed);
  o["sampling"] = str(toString(s.sampling));
  o["layout"] = str(toString(t.field.layout));
  o["material"] = str(s.material.spec());
  if (s.material.diffuse)
    o["albedo"] = Value(Value::Array{num(s.material.diffuse->x), num(s.material.diffuse->y),
                                     num(s.material.diffuse->z)});
  return Value(std::move(o));
}

Value statsJson(const BakeStats& s) {
  Value::Object o;
  o["rays"] = count(s.rays);
  o["raysPerSecond"] = num(s.raysPerSecond);
  o["secondsTotal"] = num(s.secondsTotal);
  o["secondsDirect"] = num(s.secondsDirect);
  Value::Array sb, rb;
  for (double x : s.secondsBounce) sb.push_back(num(x));
  for (auto r : s.raysBounce) rb.push_back(count(r));
  if (!sb.empty()) o["secondsBounce"] = Value(std::move(sb));
  if (!rb.empty()) o["raysBounce"] = Value(std::move(rb));
  o["threads"] = Value(s.threads);
  o["vertices"] = count(s.vertices);
  o["stdErrT0Mean"] = num(s.stdErrT0Mean);
  o["stdErrT0Max"] = num(s.stdErrT0Max);
  o["stdErrConstMean"] = num(s.stdErrConstMean);
  o["stdErrConstMax"] = num(s.stdErrConstMax);
  return Value(std::move(o));
}

// ---------------------------------------------------------------------------------------------
// Reading.

/// Checks the GLB container (header, chunk table) before tinygltf sees it, so that truncation
/// is reported as such.
void checkGlbContainer(std::span<const unsigned char> b, const Reader& r) {
  auto u32 = [&](std::size_t at) {
    std::uint32_t x;
    std::memcpy(&x, b.data() + at, 4);
    return x;  // GLB is little-endian, as is every platform we build for
  };
  if (b.size() < 12 || std::memcmp(b.data(), "glTF", 4) != 0)
    r.fail("not a glTF binary (.glb) file (bad magic)");
  if (u32(4) != 2)
    r.fail("glTF binary container version " + std::to_string(u32(4)) + ", expected 2");
  const std::uint64_t length = u32(8);
  if (length > b.size())
    r.fail("truncated: the header says " + std::to_string(length) + " bytes, the file has " +
           std::to_string(b.size()));
  if (length < 20) r.fail("truncated: no JSON chunk");
  const std::uint64_t jsonLen = u32(12);
  if (u32(16) != 0x4E4F534Au) r.fail("first chunk is not JSON");
  if (20 + jsonLen > length) r.fail("truncated: the JSON chunk runs past the end of the file");
  const std::uint64_t binAt = 20 + jsonLen;
  if (binAt < length) {
    if (binAt + 8 > length) r.fail("truncated: incomplete binary chunk header");
    if (binAt + 8 + u32(binAt) > length) r.fail("truncated: the binary chunk runs past the end");
  }
}

void requireFinite(const std::vector<float>& x, const std::string& what, const Reader& r) {
  for (std::size_t i = 0; i < x.size(); ++i)
    if (!std::isfinite(x[i]))
      r.fail(what + " holds a non-finite value at element " + std::to_string(i));
}

BakeSettings parseSettings(const Value& o, const std::string& where, const Reader& r) {
  BakeSettings s;
  try {
    s.mode = parseTransferMode(r.string(o, "mode", where));
    s.sampling = parseSampling(r.string(o, "sampling", where));
  } catch (const Error& e) {
    if (std::string(e.what()).rfind(r.name, 0) == 0) throw;
    r.fail(where + ": " + e.what());
  }
  s.samples = static_cast<int>(r.integer(o, "samples", where, 0, 2147483647.0));
  s.bounces = static_cast<int>(r.integer(o, "bounces", where, 0, 2147483647.0));
  s.seed = r.integer(o, "seed", where);
  if (o.Has("layout")) {
    try {
      s.layout = parseTransferLayout(r.string(o, "layout", where));
    } catch (const Error& e) {
      if (std::string(e.what()).rfind(r.name, 0) == 0) throw;
      r.fail(where + ": " + e.what());
    }
  }
  if (o.Has("material")) {
    try {
      s.material = parseMaterial(r.string(o, "material", where));
    } catch (const Error& e) {
      if (std::string(e.what()).rfind(r.name, 0) == 0) throw;
      r.fail(where + ".material: " + e.what());
    }
  }
  if (o.Has("albedo")) {
    const Value& a = o.Get("albedo");
    if (!a.IsArray() || a.ArrayLen() != 3 || !a.Get(0).IsNumber() || !a.Get(1).IsNumber() ||
        !a.Get(2).IsNumber())
      r.fail(where + ".albedo is not three numbers");
    s.material.diffuse = Rgb(static_cast<float>(a.Get(0).GetNumberAsDouble()),
                             static_cast<float>(a.Get(1).GetNumberAsDouble()),
                             static_cast<float>(a.Get(2).GetNumberAsDouble()));
  }
  return s;
}

BakeStats parseStats(const Value& o, const std::string& where, const Reader& r) {
  BakeStats s;
  if (!o.IsObject()) return s;  // statistics are informative: absent means unknown
  s.rays = o.Has("rays") ? r.integer(o, "rays", where) : 0;
  s.raysPerSecond = r.numberOr(o, "raysPerSecond", 0, where);
  s.secondsTotal = r.numberOr(o, "secondsTotal", 0, where);
  s.secondsDirect = r.numberOr(o, "secondsDirect", 0, where);
  if (o.Has("secondsBounce") && o.Get("secondsBounce").IsArray())
    for (std::size_t i = 0; i < o.Get("secondsBounce").ArrayLen(); ++i)
      s.secondsBounce.push_back(
          o.Get("secondsBounce").Get(static_cast<int>(i)).GetNumberAsDouble());
  if (o.Has("raysBounce") && o.Get("raysBounce").IsArray())
    for (std::size_t i = 0; i < o.Get("raysBounce").ArrayLen(); ++i)
      s.raysBounce.push_back(static_cast<std::uint64_t>(
          o.Get("raysBounce").Get(static_cast<int>(i)).GetNumberAsDouble()));
  s.threads = static_cast<int>(r.numberOr(o, "threads", 0, where));
  s.vertices = o.Has("vertices") ? r.integer(o, "vertices", where) : 0;
  s.stdErrT0Mean = r.numberOr(o, "stdErrT0Mean", 0, where);
  s.stdErrT0Max = r.numberOr(o, "stdErrT0Max", 0, where);
  s.stdErrConstMean = r.numberOr(o, "stdErrConstMean", 0, where);
  s.stdErrConstMax = r.numberOr(o, "stdErrConstMax", 0, where);
  return s;
}

/// The compressed rows of `bt` (shape already in bt.field) from extras ".compressed" and the
/// transfer's accessor list [cluster, weights?, means, basis?].
void readCompressed(const gltf::AccessorReader& ar, const Value& z, const Value& acc,
                    const std::string& tw, BakedTransfer& bt, const Reader& r) {
  const std::string zw = tw + ".compressed";
  if (!z.IsObject() || r.string(z, "method", zw) != "cpca") r.fail(zw + ".method must be \"cpca\"");
  const TransferField& f = bt.field;
  const std::size_t n = f.vertexCount, S = f.stride();
  CompressedTransfer c;
  c.layout = f.layout;
  c.bands = f.bands;
  c.channels = f.channels;
  c.vertexCount = n;
  c.clusters = static_cast<int>(r.integer(z, "clusters", zw, 1, std::min<double>(n, 2147483647.0)));
  c.basisCount = static_cast<int>(r.integer(z, "basisCount", zw, 0, static_cast<double>(S)));
  bt.compression.clusters = c.clusters;
  bt.compression.basisCount = c.basisCount;
  bt.compression.seed = z.Has("seed") ? r.integer(z, "seed", zw) : 0;
  bt.compression.maxIterations =
      static_cast<int>(r.numberOr(z, "maxIterations", bt.compression.maxIterations, zw));
  bt.compression.tolerance = r.numberOr(z, "tolerance", bt.compression.tolerance, zw);
  const std::size_t K = static_cast<std::size_t>(c.clusters),
                    N = static_cast<std::size_t>(c.basisCount);
  const std::size_t want = N > 0 ? 4 : 2;
  if (!acc.IsArray() || acc.ArrayLen() != want)
    r.fail(tw + ".accessors must list " + std::to_string(want) +
           " accessors for compressed transfer with " + std::to_string(N) + " basis vectors");
  for (std::size_t i = 0; i < want; ++i)
    if (!acc.Get(static_cast<int>(i)).IsInt())
      r.fail(tw + ".accessors[" + std::to_string(i) + "] is not an index");
  auto index = [&](std::size_t i) { return acc.Get(static_cast<int>(i)).Get<int>(); };
  const std::string what = std::string(toString(bt.settings.mode)) + " compressed transfer";
  if (K <= 65536) {
    const auto ids = ar.exact<std::uint16_t>(index(0), 1, kUshort, n, what + " cluster ids");
    c.cluster.assign(ids.begin(), ids.end());
  } else {
    c.cluster = ar.exact<std::uint32_t>(index(0), 1, kUint, n, what + " cluster ids");
  }
  std::size_t next = 1;
  if (N > 0) c.weights = ar.exact<float>(index(next++), 1, kFloat, n * N, what + " weights");
  c.means = ar.exact<float>(index(next++), 1, kFloat, K * S, what + " means");
  if (N > 0) c.basis = ar.exact<float>(index(next++), 1, kFloat, K * N * S, what + " basis");
  try {
    c.check(zw);
  } catch (const Error& e) {
    r.fail(e.what());
  }
  if (z.Has("stats") && z.Get("stats").IsObject()) {
    const Value& st = z.Get("stats");
    const std::string sw = zw + ".stats";
    CpcaStats& s = bt.compressionStats;
    s.squaredError = r.numberOr(st, "squaredError", 0, sw);
    s.signalEnergy = r.numberOr(st, "signalEnergy", 0, sw);
    s.relativeRms = r.numberOr(st, "relativeRms", 0, sw);
    s.snrDb = r.numberOr(st, "snrDb", std::numeric_limits<double>::infinity(), sw);
    s.maxRowError = r.numberOr(st, "maxRowError", 0, sw);
    s.compressionRatio = r.numberOr(st, "compressionRatio", 0, sw);
    s.seconds = r.numberOr(st, "seconds", 0, sw);
    s.iterations = static_cast<int>(r.numberOr(st, "iterations", 0, sw));
  }
  bt.compressed = std::move(c);
}

}  // namespace

std::string transferAttributePrefix(TransferMode mode) {
  std::string m = toString(mode);
  for (char& c : m) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return "_PRT_" + m + "_T";
}

std::string transferMatrixName(TransferMode mode) {
  std::string m = toString(mode);
  for (char& c : m) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return "_PRT_" + m + "_M";
}

void BakeFile::requireComplete(const std::string& file) const {
  if (complete()) return;
  throw Error(file, "is a partial bake: it holds transfer for vertices " +
                        std::to_string(firstVertex) + ".." +
                        std::to_string(firstVertex + vertexCount - 1) + " of " +
                        std::to_string(mesh.vertexCount()) +
                        " only (merge the pieces with prt merge first)");
}

std::string transferCompressedPrefix(TransferMode mode) {
  std::string m = toString(mode);
  for (char& c : m) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return "_PRT_" + m + "_CPCA_";
}

int BakeFile::requiredVersion() const {
  int v = 1;
  for (const auto& t : transfers) {
    if (t.compressed) return 3;
    if (t.field.isMatrix()) v = 2;
  }
  return v;
}

void BakeFile::expandCompressed() {
  for (auto& t : transfers)
    if (t.compressed) {
      t.field = t.compressed->reconstruct();
      t.compressed.reset();
    }
}

const BakedTransfer* BakeFile::find(TransferMode mode) const {
  for (const auto& t : transfers)
    if (t.settings.mode == mode) return &t;
  return nullptr;
}

const BakedTransfer* BakeFile::find(TransferMode mode, TransferLayout layout) const {
  for (const auto& t : transfers)
    if (t.settings.mode == mode && t.field.layout == layout) return &t;
  return nullptr;
}

namespace {

// GLB container (glTF 2.0 §4.4): 12-byte header, JSON chunk (padded with spaces), BIN chunk
// (padded with zeros), every length a multiple of 4 and the whole below 2^32 bytes.
constexpr std::uint32_t kGlbMagic = 0x46546C67, kChunkJson = 0x4E4F534A, kChunkBin = 0x004E4942;

void putU32(std::ostream& os, std::uint32_t v) {
  const unsigned char b[4] = {static_cast<unsigned char>(v), static_cast<unsigned char>(v >> 8),
                              static_cast<unsigned char>(v >> 16),
                              static_cast<unsigned char>(v >> 24)};
  os.write(reinterpret_cast<const char*>(b), 4);
}

/// Streams the bake as GLB to `os`.
void streamBake(const BakeFile& bake, std::ostream& os) {
  const std::vector<MeshPart> parts = partsOf(bake.mesh);
  validateForWriting(bake, parts);
  const Mesh& mesh = bake.mesh;
  const std::size_t V = mesh.vertexCount();

  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = bake.generator;
  model.buffers.resize(1);
  BufferBuilder bb{model, {}, 0};

  // Shared vertex data in the scene's global order (parts view slices of it).
  const int posView =
      bb.view(mesh.positions.data(), V * 12, 12, TINYGLTF_TARGET_ARRAY_BUFFER, "positions");
  const int nrmView =
      bb.view(mesh.normals.data(), V * 12, 12, TINYGLTF_TARGET_ARRAY_BUFFER, "normals");
  const int uvView = mesh.uvs.empty() ? -1
                                      : bb.view(mesh.uvs.data(), V * 8, 8,
                                                TINYGLTF_TARGET_ARRAY_BUFFER, "texcoords");
  const int colView = mesh.albedo.empty() ? -1
                                          : bb.view(mesh.albedo.data(), V * 12, 12,
                                                    TINYGLTF_TARGET_ARRAY_BUFFER, "albedo");
  // Indices, local to each part (each part's attributes start at its first vertex), made while
  // streaming in blocks.
  const int idxView =
      bb.view(mesh.triangleCount() * 12, 0, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER, "indices",
              [&mesh, &parts](std::ostream& os) {
                std::vector<std::uint32_t> block;
                for (const MeshPart& p : parts)
                  for (std::uint32_t t = p.firstTriangle; t < p.firstTriangle + p.triangleCount;) {
                    const std::uint32_t end = std::min(p.firstTriangle + p.triangleCount, t + 4096);
                    block.clear();
                    for (; t < end; ++t)
                      for (int k = 0; k < 3; ++k)
                        block.push_back(mesh.triangles[t][k] - p.firstVertex);
                    os.write(reinterpret_cast<const char*>(block.data()),
                             static_cast<std::streamsize>(block.size() * 4));
                  }
              });

  // Transfer: K = ceil(B²C/4) VEC4 columns per mode, each its own tightly packed view over the
  // vertex range; column k of vertex v = row floats 4k..4k+3, zero-padded. Written column by
  // column in blocks of vertices while streaming.
  struct Columns {
    std::vector<int> views, rangeAccessors;
  };
  std::vector<Columns> columns(bake.transfers.size());
  for (std::size_t ti = 0; ti < bake.transfers.size(); ++ti) {
    const TransferField& f = bake.transfers[ti].field;
    const std::size_t S = f.stride(), K = (S + 3) / 4, n = f.vertexCount;
    if (const auto& c = bake.transfers[ti].compressed) {
      // Compressed (version 3): cluster ids (uint16 when K ≤ 65536, else uint32), N weights per
      // row, K means and K·N basis vectors of S floats, each one tightly packed SCALAR accessor
      // named from extras, in this order (weights and basis absent when N = 0).
      const std::string prefix = transferCompressedPrefix(bake.transfers[ti].settings.mode);
      auto named = [&](int view, std::size_t count, int type, const std::string& name) {
        columns[ti].rangeAccessors.push_back(
            bb.accessor(view, 0, count, TINYGLTF_TYPE_SCALAR, type));
        model.accessors.back().name = name;
      };
      if (c->clusters <= 65536) {
        const auto* ids = &c->cluster;
        const int view = bb.view(n * 2, 0, 0, prefix + "CLUSTER", [ids](std::ostream& os) {
          std::vector<std::uint16_t> block;
          for (std::size_t v0 = 0; v0 < ids->size(); v0 += 4096) {
            block.assign(ids->begin() + v0, ids->begin() + std::min(ids->size(), v0 + 4096));
            os.write(reinterpret_cast<const char*>(block.data()),
                     static_cast<std::streamsize>(block.size() * 2));
          }
        });
        named(view, n, kUshort, prefix + "CLUSTER");
      } else {
        named(bb.view(c->cluster.data(), n * 4, 0, 0, prefix + "CLUSTER"), n, kUint,
              prefix + "CLUSTER");
      }
      if (c->basisCount > 0)
        named(bb.view(c->weights.data(), c->weights.size() * 4, 0, 0, prefix + "WEIGHTS"),
              c->weights.size(), kFloat, prefix + "WEIGHTS");
      named(bb.view(c->means.data(), c->means.size() * 4, 0, 0, prefix + "MEANS"), c->means.size(),
            kFloat, prefix + "MEANS");
      if (c->basisCount > 0)
        named(bb.view(c->basis.data(), c->basis.size() * 4, 0, 0, prefix + "BASIS"),
              c->basis.size(), kFloat, prefix + "BASIS");
      continue;
    }
    if (f.isMatrix()) {
      // Matrices (version 2): B⁴·C floats per vertex are far past the 16 vertex attributes a
      // GPU guarantees, so they are one tightly packed SCALAR float accessor of the rows as
      // TransferField holds them, named from extras (not a primitive attribute).
      const std::string name = transferMatrixName(bake.transfers[ti].settings.mode);
      const int view = bb.view(f.data.data(), f.data.size() * sizeof(float), 0, 0, name);
      columns[ti].rangeAccessors.push_back(
          bb.accessor(view, 0, f.data.size(), TINYGLTF_TYPE_SCALAR, kFloat));
      model.accessors.back().name = name;
      continue;
    }
    const std::string prefix = transferAttributePrefix(bake.transfers[ti].settings.mode);
    for (std::size_t k = 0; k < K; ++k) {
      const auto writeColumn = [&f, S, n, k](std::ostream& os) {
        constexpr std::size_t kBlock = 4096;
        std::vector<float> col(kBlock * 4);
        for (std::size_t v0 = 0; v0 < n; v0 += kBlock) {
          const std::size_t m = std::min(kBlock, n - v0);
          std::fill(col.begin(), col.end(), 0.0f);
          for (std::size_t v = 0; v < m; ++v)
            for (std::size_t j = 0; j < 4 && 4 * k + j < S; ++j)
              col[v * 4 + j] = f.vertex(v0 + v)[4 * k + j];
          os.write(reinterpret_cast<const char*>(col.data()), static_cast<std::streamsize>(m * 16));
        }
      };
      columns[ti].views.push_back(bb.view(n * 16, 16, TINYGLTF_TARGET_ARRAY_BUFFER,
                                          prefix + std::to_string(k), writeColumn));
      columns[ti].rangeAccessors.push_back(
          bb.accessor(columns[ti].views.back(), 0, n, TINYGLTF_TYPE_VEC4, kFloat));
      model.accessors.back().name = prefix + std::to_string(k) + " (vertex range)";
    }
  }

  tinygltf::Material mat;
  mat.name = "prtkit default";
  const BakedTransfer* withAlbedo = nullptr;
  for (const auto& t : bake.transfers)
    if (t.settings.material.diffuse) withAlbedo = &t;
  if (withAlbedo && mesh.albedo.empty()) {
    const Rgb a = *withAlbedo->settings.material.diffuse;
    mat.pbrMetallicRoughness.baseColorFactor = {a.x, a.y, a.z, 1.0};
  }
  mat.pbrMetallicRoughness.metallicFactor = 0.0;
  mat.pbrMetallicRoughness.roughnessFactor = 1.0;
  model.materials.push_back(mat);

  tinygltf::Scene scene;
  scene.name = mesh.source;
  for (const MeshPart& p : parts) {
    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    prim.material = 0;
    const std::size_t n = p.vertexCount;
    prim.attributes["POSITION"] =
        bb.accessor(posView, p.firstVertex * 12u, n, TINYGLTF_TYPE_VEC3, kFloat);
    Vec3f lo = mesh.positions[p.firstVertex], hi = lo;
    for (std::size_t v = p.firstVertex; v < p.firstVertex + n; ++v) {
      lo = min(lo, mesh.positions[v]);
      hi = max(hi, mesh.positions[v]);
    }
    model.accessors.back().minValues = {lo.x, lo.y, lo.z};
    model.accessors.back().maxValues = {hi.x, hi.y, hi.z};
    prim.attributes["NORMAL"] =
        bb.accessor(nrmView, p.firstVertex * 12u, n, TINYGLTF_TYPE_VEC3, kFloat);
    if (uvView >= 0)
      prim.attributes["TEXCOORD_0"] =
          bb.accessor(uvView, p.firstVertex * 8u, n, TINYGLTF_TYPE_VEC2, kFloat);
    if (colView >= 0)
      prim.attributes["COLOR_0"] =
          bb.accessor(colView, p.firstVertex * 12u, n, TINYGLTF_TYPE_VEC3, kFloat);
    if (bake.complete())
      for (std::size_t ti = 0; ti < bake.transfers.size(); ++ti) {
        if (bake.transfers[ti].field.isMatrix() || bake.transfers[ti].compressed) continue;
        const std::string prefix = transferAttributePrefix(bake.transfers[ti].settings.mode);
        for (std::size_t k = 0; k < columns[ti].views.size(); ++k)
          prim.attributes[prefix + std::to_string(k)] =
              bb.accessor(columns[ti].views[k], p.firstVertex * 16u, n, TINYGLTF_TYPE_VEC4, kFloat);
      }
    prim.indices = bb.accessor(idxView, p.firstTriangle * 12u, p.triangleCount * 3u,
                               TINYGLTF_TYPE_SCALAR, kUint);
    tinygltf::Mesh gm;
    gm.name = p.name;
    gm.primitives.push_back(std::move(prim));
    model.meshes.push_back(std::move(gm));
    tinygltf::Node node;
    node.name = p.name;
    node.mesh = static_cast<int>(model.meshes.size() - 1);
    model.nodes.push_back(std::move(node));
    scene.nodes.push_back(static_cast<int>(model.nodes.size() - 1));
  }
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  const std::size_t binLength = (bb.length + 3) / 4 * 4;

  // extras.prtkit
  Value::Object prt;
  prt["formatVersion"] = Value(bake.requiredVersion());
  prt["generator"] = str(bake.generator);
  prt["source"] = str(mesh.source);
  prt["vertexCount"] = count(V);
  prt["triangleCount"] = count(mesh.triangleCount());
  prt["vertexRange"] =
      Value(Value::Object{{"first", count(bake.firstVertex)}, {"count", count(bake.vertexCount)}});
  Value::Array transfers;
  for (std::size_t ti = 0; ti < bake.transfers.size(); ++ti) {
    const BakedTransfer& t = bake.transfers[ti];
    Value::Object o;
    o["settings"] = settingsJson(t);
    o["stats"] = statsJson(t.stats);
    if (t.compressed) {
      const CompressedTransfer& c = *t.compressed;
      const CpcaStats& cs = t.compressionStats;
      Value::Object z;
      z["method"] = str("cpca");
      z["clusters"] = Value(c.clusters);
      z["basisCount"] = Value(c.basisCount);
      z["seed"] = seedValue(t.compression.seed);
      z["maxIterations"] = Value(t.compression.maxIterations);
      z["tolerance"] = num(t.compression.tolerance);
      z["accessorPrefix"] = str(transferCompressedPrefix(t.settings.mode));
      Value::Object st;
      st["squaredError"] = num(cs.squaredError);
      st["signalEnergy"] = num(cs.signalEnergy);
      st["relativeRms"] = num(cs.relativeRms);
      if (std::isfinite(cs.snrDb)) st["snrDb"] = num(cs.snrDb);  // absent: exact (infinite)
      st["maxRowError"] = num(cs.maxRowError);
      st["compressionRatio"] = num(cs.compressionRatio);
      st["seconds"] = num(cs.seconds);
      st["iterations"] = Value(cs.iterations);
      z["stats"] = Value(std::move(st));
      o["compressed"] = Value(std::move(z));
    } else if (t.field.isMatrix())
      o["matrixAccessor"] = str(transferMatrixName(t.settings.mode));
    else
      o["attributePrefix"] = str(transferAttributePrefix(t.settings.mode));
    Value::Array acc;
    for (int a : columns[ti].rangeAccessors) acc.push_back(Value(a));
    o["accessors"] = Value(std::move(acc));
    transfers.push_back(Value(std::move(o)));
  }
  if (!transfers.empty()) prt["transfers"] = Value(std::move(transfers));
  model.extras = Value(Value::Object{{"prtkit", Value(std::move(prt))}});

  // The JSON by tinygltf from the model with an empty buffer, then the buffer declared as the
  // GLB's BIN chunk (no uri, its real length).
  std::ostringstream text;
  tinygltf::TinyGLTF gltf;
  if (!gltf.WriteGltfSceneToStream(&model, text, false, false))
    throw Error("bake file: glTF serialisation failed");
  nlohmann::json doc = nlohmann::json::parse(text.str());
  doc["buffers"] = nlohmann::json::array({nlohmann::json{{"byteLength", binLength}}});
  std::string json = doc.dump();
  while (json.size() % 4) json.push_back(' ');
  const std::uint64_t total = 12 + 8 + json.size() + 8 + binLength;
  if (total >= (std::uint64_t(1) << 32))
    throw Error("bake file: " + std::to_string(total >> 20) +
                " MiB exceeds the 4 GiB a GLB file can hold (bake fewer bands, or split the "
                "bake into vertex ranges)");

  putU32(os, kGlbMagic);
  putU32(os, 2);
  putU32(os, static_cast<std::uint32_t>(total));
  putU32(os, static_cast<std::uint32_t>(json.size()));
  putU32(os, kChunkJson);
  os.write(json.data(), static_cast<std::streamsize>(json.size()));
  putU32(os, static_cast<std::uint32_t>(binLength));
  putU32(os, kChunkBin);
  bb.writeBinary(os, binLength);
}

}  // namespace

std::string encodeBake(const BakeFile& bake) {
  std::ostringstream out;
  streamBake(bake, out);
  return out.str();
}

void writeBake(const std::string& path, const BakeFile& bake) {
  try {
    writeFileAtomically(path, [&](std::ostream& os) { streamBake(bake, os); });
  } catch (const Error& e) {
    const std::string what = e.what();
    throw Error(what.rfind(path, 0) == 0 ? what : path + ": " + what);
  }
}

namespace {

// A bake file is one self-contained GLB: tinygltf must never open another file on its behalf
// (a `uri` naming /dev/zero or a FIFO would otherwise be read or block).
bool noFileExists(const std::string&, void*) {
  return true;  // so that tinygltf asks to read it, and noFileRead says why it may not
}
std::string noFileExpand(const std::string& path, void*) {
  return path;
}
bool noFileRead(std::vector<unsigned char>*, std::string* err, const std::string& path, void*) {
  if (err) *err += "refers to an external file (" + path.substr(0, 80) + "); a bake is one .glb\n";
  return false;
}
bool noFileWrite(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "writing is not allowed\n";
  return false;
}

}  // namespace

BakeFile decodeBake(std::span<const unsigned char> bytes, const std::string& name) {
  const Reader r{name};
  checkGlbContainer(bytes, r);
  checkGltfNesting(name, bytes);  // tinygltf recurses into extras: refuse deep JSON first
  tinygltf::Model model;
  {
    tinygltf::TinyGLTF gltf;
    gltf.SetFsCallbacks(
        tinygltf::FsCallbacks{&noFileExists, &noFileExpand, &noFileRead, &noFileWrite, nullptr});
    std::string err, warn;
    if (bytes.size() > std::numeric_limits<unsigned int>::max()) r.fail("file too large (> 4 GiB)");
    if (!gltf.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(),
                                   static_cast<unsigned int>(bytes.size()))) {
      std::string first = err.substr(0, err.find('\n'));
      r.fail("invalid glTF: " + (first.empty() ? std::string("parse error") : first));
    }
  }
  const gltf::AccessorReader ar(name, model);
  if (!model.extras.IsObject() || !model.extras.Has("prtkit") ||
      !model.extras.Get("prtkit").IsObject())
    r.fail("not a prtkit bake file (a glTF without extras.prtkit)");
  const Value& prt = model.extras.Get("prtkit");
  const std::string where = "extras.prtkit";
  const auto version = r.integer(prt, "formatVersion", where, 0, 1e9);
  if (version > static_cast<std::uint64_t>(kBakeFormatVersion))
    r.fail("bake format version " + std::to_string(version) +
           " is newer than this prtkit understands (" + std::to_string(kBakeFormatVersion) + ")");
  if (version < 1) r.fail("bake format version " + std::to_string(version) + " is invalid");

  BakeFile bake;
  bake.formatVersion = static_cast<int>(version);
  bake.generator = prt.Has("generator") && prt.Get("generator").IsString()
                       ? prt.Get("generator").Get<std::string>()
                       : model.asset.generator;
  Mesh& mesh = bake.mesh;
  mesh.source = prt.Has("source") && prt.Get("source").IsString()
                    ? prt.Get("source").Get<std::string>()
                    : name;
  const std::size_t V = r.integer(prt, "vertexCount", where, 1, 4294967295.0);
  const std::size_t T = r.integer(prt, "triangleCount", where, 1, 4294967295.0);
  checkLimit(name, "vertex count", V, limits().maxVertices, "PRT_MAX_VERTICES");
  checkLimit(name, "triangle count", T, limits().maxTriangles, "PRT_MAX_TRIANGLES");
  if (model.meshes.empty()) r.fail("holds no mesh");

  // The parts: glTF meshes in order, one triangle primitive each, concatenated.
  bool anyUv = false, anyColor = false;
  for (std::size_t mi = 0; mi < model.meshes.size(); ++mi) {
    const tinygltf::Mesh& gm = model.meshes[mi];
    const std::string what = "mesh " + std::to_string(mi) + " ('" + gm.name + "')";
    if (gm.primitives.size() != 1)
      r.fail(what + " has " + std::to_string(gm.primitives.size()) + " primitives, expected 1");
    const tinygltf::Primitive& p = gm.primitives[0];
    if (p.mode != TINYGLTF_MODE_TRIANGLES && p.mode != -1) r.fail(what + " is not a triangle list");
    auto attr = [&](const char* key) {
      auto it = p.attributes.find(key);
      return it == p.attributes.end() ? -1 : it->second;
    };
    const int pa = attr("POSITION");
    if (pa < 0 || static_cast<std::size_t>(pa) >= model.accessors.size())
      r.fail(what + " has no POSITION");
    const std::size_t n = model.accessors[static_cast<std::size_t>(pa)].count;
    if (n == 0 || mesh.positions.size() + n > V)
      r.fail(what + " has more vertices than extras.prtkit.vertexCount");
    MeshPart part;
    part.name = gm.name;
    part.firstVertex = static_cast<std::uint32_t>(mesh.positions.size());
    part.vertexCount = static_cast<std::uint32_t>(n);
    part.firstTriangle = static_cast<std::uint32_t>(mesh.triangles.size());

    auto pos = ar.exact<float>(pa, 3, kFloat, n, what + " POSITION");
    auto nrm = ar.exact<float>(attr("NORMAL"), 3, kFloat, n, what + " NORMAL");
    requireFinite(pos, what + " POSITION", r);
    requireFinite(nrm, what + " NORMAL", r);
    for (std::size_t v = 0; v < n; ++v) {
      mesh.positions.emplace_back(pos[3 * v], pos[3 * v + 1], pos[3 * v + 2]);
      mesh.normals.emplace_back(nrm[3 * v], nrm[3 * v + 1], nrm[3 * v + 2]);
    }
    const bool hasUv = attr("TEXCOORD_0") >= 0, hasColor = attr("COLOR_0") >= 0;
    if (mi > 0 && (hasUv != anyUv || hasColor != anyColor))
      r.fail(what + " differs from the first part in TEXCOORD_0/COLOR_0");
    anyUv = hasUv;
    anyColor = hasColor;
    if (hasUv) {
      auto uv = ar.exact<float>(attr("TEXCOORD_0"), 2, kFloat, n, what + " TEXCOORD_0");
      for (std::size_t v = 0; v < n; ++v) mesh.uvs.push_back({uv[2 * v], uv[2 * v + 1]});
    }
    if (hasColor) {
      auto c = ar.exact<float>(attr("COLOR_0"), 3, kFloat, n, what + " COLOR_0");
      requireFinite(c, what + " COLOR_0", r);
      for (std::size_t v = 0; v < n; ++v)
        mesh.albedo.emplace_back(c[3 * v], c[3 * v + 1], c[3 * v + 2]);
    }
    if (p.indices < 0 || static_cast<std::size_t>(p.indices) >= model.accessors.size())
      r.fail(what + " has no indices");
    const std::size_t ni = model.accessors[static_cast<std::size_t>(p.indices)].count;
    if (ni == 0 || ni % 3 != 0)
      r.fail(what + ": index count " + std::to_string(ni) + " is not a positive multiple of 3");
    if (mesh.triangles.size() + ni / 3 > T)
      r.fail(what + " has more triangles than extras.prtkit.triangleCount");
    auto idx = ar.exact<std::uint32_t>(p.indices, 1, kUint, ni, what + " indices");
    for (std::size_t t = 0; t < ni / 3; ++t) {
      std::array<std::uint32_t, 3> tri;
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t i = idx[3 * t + k];
        if (i >= n)
          r.fail(what + ": triangle " + std::to_string(t) + " references vertex " +
                 std::to_string(i) + " (part has " + std::to_string(n) + ")");
        tri[k] = i + part.firstVertex;
      }
      mesh.triangles.push_back(tri);
    }
    part.triangleCount = static_cast<std::uint32_t>(ni / 3);
    mesh.parts.push_back(part);
  }
  if (mesh.positions.size() != V || mesh.triangles.size() != T)
    r.fail("the meshes hold " + std::to_string(mesh.positions.size()) + " vertices and " +
           std::to_string(mesh.triangles.size()) + " triangles, extras.prtkit says " +
           std::to_string(V) + " and " + std::to_string(T));
  checkMeshExtent(mesh, name);  // named as given here, not as the bake's recorded source

  const Value& range = r.member(prt, "vertexRange", where);
  bake.firstVertex = r.integer(range, "first", where + ".vertexRange", 0, 4294967295.0);
  bake.vertexCount = r.integer(range, "count", where + ".vertexRange", 1, 4294967295.0);
  if (bake.firstVertex + bake.vertexCount > V)
    r.fail("vertex range " + std::to_string(bake.firstVertex) + "+" +
           std::to_string(bake.vertexCount) + " is outside the mesh (" + std::to_string(V) +
           " vertices)");

  if (prt.Has("transfers")) {
    const Value& ts = prt.Get("transfers");
    if (!ts.IsArray()) r.fail(where + ".transfers is not an array");
    for (std::size_t ti = 0; ti < ts.ArrayLen(); ++ti) {
      const std::string tw = where + ".transfers[" + std::to_string(ti) + "]";
      const Value& t = ts.Get(static_cast<int>(ti));
      const Value& so = r.member(t, "settings", tw);
      BakedTransfer bt;
      bt.settings = parseSettings(so, tw + ".settings", r);
      bt.settings.firstVertex = bake.firstVertex;
      bt.settings.vertexCount = bake.vertexCount;
      if (bake.find(bt.settings.mode, bt.settings.layout))
        r.fail(std::string("two ") + toString(bt.settings.layout) + " transfers of mode " +
               toString(bt.settings.mode));
      if (bt.settings.layout == TransferLayout::Matrix && bake.formatVersion < 2)
        r.fail(tw + " is a matrix transfer in a version " + std::to_string(bake.formatVersion) +
               " file (matrices need version 2)");
      const auto bands = r.integer(so, "bands", tw + ".settings", 1, kMaxBands);
      const auto channels = r.integer(so, "channels", tw + ".settings", 1, 3);
      if (channels == 2) r.fail(tw + ".settings.channels must be 1 or 3");
      bt.settings.bands = static_cast<int>(bands);
      bt.stats = t.Has("stats") ? parseStats(t.Get("stats"), tw + ".stats", r) : BakeStats{};
      TransferField& f = bt.field;
      f.bands = static_cast<int>(bands);
      f.channels = static_cast<int>(channels);
      f.vertexCount = bake.vertexCount;
      f.layout = bt.settings.layout;
      const std::size_t S = f.stride(), K = f.isMatrix() ? 1 : (S + 3) / 4;
      const Value& acc = r.member(t, "accessors", tw);
      if (t.Has("compressed")) {
        if (bake.formatVersion < 3)
          r.fail(tw + " is compressed transfer in a version " + std::to_string(bake.formatVersion) +
                 " file (compression needs version 3)");
        readCompressed(ar, t.Get("compressed"), acc, tw, bt, r);
        bake.transfers.push_back(std::move(bt));
        continue;
      }
      if (f.isMatrix()) {
        if (!acc.IsArray() || acc.ArrayLen() != 1 || !acc.Get(0).IsInt())
          r.fail(tw + ".accessors must list the one accessor of the matrices");
        // The reader checks the declared count against the bytes present before allocating.
        f.data = ar.exact<float>(acc.Get(0).Get<int>(), 1, kFloat, f.vertexCount * S,
                                 std::string(toString(bt.settings.mode)) + " matrices");
        requireFinite(f.data, std::string(toString(bt.settings.mode)) + " matrices", r);
        bake.transfers.push_back(std::move(bt));
        continue;
      }
      if (!acc.IsArray() || acc.ArrayLen() != K)
        r.fail(tw + ".accessors must list " + std::to_string(K) + " accessors for " +
               std::to_string(bands) + " bands x " + std::to_string(channels) + " channels");
      f.data.assign(f.vertexCount * S, 0.0f);
      for (std::size_t k = 0; k < K; ++k) {
        const Value& a = acc.Get(static_cast<int>(k));
        if (!a.IsInt()) r.fail(tw + ".accessors[" + std::to_string(k) + "] is not an index");
        auto col = ar.exact<float>(
            a.Get<int>(), 4, kFloat, f.vertexCount,
            std::string(toString(bt.settings.mode)) + " transfer column " + std::to_string(k));
        requireFinite(col, std::string(toString(bt.settings.mode)) + " transfer", r);
        for (std::size_t v = 0; v < f.vertexCount; ++v)
          for (std::size_t j = 0; j < 4 && 4 * k + j < S; ++j)
            f.vertex(v)[4 * k + j] = col[v * 4 + j];
      }
      bake.transfers.push_back(std::move(bt));
    }
  }
  return bake;
}

const BakedTransfer& pickTransfer(const BakeFile& bake, std::optional<TransferMode> mode,
                                  std::optional<TransferLayout> layout, const std::string& file) {
  if (bake.transfers.empty()) throw Error(file, "the bake holds no transfer");
  const TransferMode order[] = {TransferMode::Interreflected, TransferMode::Shadowed,
                                TransferMode::Unshadowed};
  const TransferLayout layouts[] = {TransferLayout::Matrix, TransferLayout::Vector};
  for (TransferMode m : order) {
    if (mode && *mode != m) continue;
    for (TransferLayout l : layouts) {
      if (layout && *layout != l) continue;
      if (const BakedTransfer* t = bake.find(m, l)) return *t;
    }
  }
  const std::string want = std::string(mode ? toString(*mode) + std::string(" ") : "") +
                           (layout ? toString(*layout) + std::string(" ") : "");
  std::string have;
  for (const auto& t : bake.transfers)
    have += std::string(have.empty() ? "" : ", ") + toString(t.settings.mode) + " " +
            toString(t.field.layout);
  throw Error(file, "no " + want + "transfer in the bake (it has " + have + ")");
}

BakeFile readBake(const std::string& path) {
  const std::vector<unsigned char> bytes = readFileBytes(path);
  return decodeBake(bytes, path);
}

BakeFile mergeBakes(std::vector<BakeFile> pieces) {
  if (pieces.empty()) throw Error("merge: no bake files");
  std::sort(pieces.begin(), pieces.end(),
            [](const BakeFile& a, const BakeFile& b) { return a.firstVertex < b.firstVertex; });
  BakeFile out = pieces.front();
  const Mesh& m0 = out.mesh;
  for (std::size_t i = 1; i < pieces.size(); ++i) {
    const BakeFile& p = pieces[i];
    const std::string who = "merge: the piece starting at vertex " + std::to_string(p.firstVertex);
    const Mesh& m = p.mesh;
    if (m.positions != m0.positions || m.normals != m0.normals || m.triangles != m0.triangles ||
        m.albedo != m0.albedo)
      throw Error(who + " was baked from a different mesh");
    const std::size_t end = out.firstVertex + out.vertexCount;
    if (p.firstVertex < end)
      throw Error(who + " overlaps the previous range (which ends at " + std::to_string(end) + ")");
    if (p.firstVertex > end)
      throw Error(who + " leaves a gap: vertices " + std::to_string(end) + ".." +
                  std::to_string(p.firstVertex - 1) + " are missing");
    if (p.transfers.size() != out.transfers.size()) throw Error(who + " holds different modes");
    for (const BakeFile* b : {static_cast<const BakeFile*>(&out), &p})
      for (const auto& t : b->transfers)
        if (t.compressed)
          throw Error(who +
                      ": compressed transfer cannot be merged (merge the bakes, then compress)");
    for (std::size_t t = 0; t < out.transfers.size(); ++t) {
      BakedTransfer& a = out.transfers[t];
      const BakedTransfer* b = p.find(a.settings.mode, a.field.layout);
      if (!b)
        throw Error(who + std::string(" lacks the ") + toString(a.settings.mode) + " transfer");
      const BakeSettings &sa = a.settings, &sb = b->settings;
      if (sa.bands != sb.bands || sa.samples != sb.samples || sa.bounces != sb.bounces ||
          sa.seed != sb.seed || sa.sampling != sb.sampling || sa.material != sb.material ||
          sa.layout != sb.layout || a.field.bands != b->field.bands ||
          a.field.channels != b->field.channels)
        throw Error(who + " was baked with different settings (" + toString(sa.mode) + ")");
      a.field.data.insert(a.field.data.end(), b->field.data.begin(), b->field.data.end());
      a.field.vertexCount += b->field.vertexCount;
      // Statistics: sums, vertex-weighted means, maxima.
      BakeStats& x = a.stats;
      const BakeStats& y = b->stats;
      const double wx = static_cast<double>(out.vertexCount),
                   wy = static_cast<double>(p.vertexCount);
      auto mean = [&](double u, double v) { return (u * wx + v * wy) / (wx + wy); };
      x.stdErrT0Mean = mean(x.stdErrT0Mean, y.stdErrT0Mean);
      x.stdErrConstMean = mean(x.stdErrConstMean, y.stdErrConstMean);
      x.stdErrT0Max = std::max(x.stdErrT0Max, y.stdErrT0Max);
      x.stdErrConstMax = std::max(x.stdErrConstMax, y.stdErrConstMax);
      const double raySeconds = (x.raysPerSecond > 0 ? x.rays / x.raysPerSecond : 0) +
                                (y.raysPerSecond > 0 ? y.rays / y.raysPerSecond : 0);
      x.rays += y.rays;
      x.raysPerSecond = raySeconds > 0 ? x.rays / raySeconds : 0;
      x.secondsTotal += y.secondsTotal;
      x.secondsDirect += y.secondsDirect;
      for (std::size_t k = 0; k < y.secondsBounce.size(); ++k) {
        if (x.secondsBounce.size() <= k) x.secondsBounce.push_back(0);
        x.secondsBounce[k] += y.secondsBounce[k];
      }
      for (std::size_t k = 0; k < y.raysBounce.size(); ++k) {
        if (x.raysBounce.size() <= k) x.raysBounce.push_back(0);
        x.raysBounce[k] += y.raysBounce[k];
      }
      x.vertices += y.vertices;
      x.threads = std::max(x.threads, y.threads);
    }
    out.vertexCount += p.vertexCount;
  }
  for (auto& t : out.transfers) {
    t.settings.firstVertex = out.firstVertex;
    t.settings.vertexCount = out.vertexCount;
  }
  return out;
}

}  // namespace prt
