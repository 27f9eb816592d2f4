#include "transfer_codecs.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>

#include "prt/core/error.hpp"
#include "prt/haar/resolution.hpp"
#include "prt/transfer/haar_rows.hpp"

namespace prt::io {

namespace {

using nlohmann::json;
constexpr int kFloat = gltf::kFloat, kUint = gltf::kUnsignedInt, kUshort = gltf::kUnsignedShort;
constexpr int kShort = gltf::kShort, kUbyte = gltf::kUnsignedByte;
constexpr int kArrayBuffer = 34962;

/// The accessor indices an entry lists, each checked to be an integer.
std::vector<int> accessorList(const json& entry, std::size_t want, const std::string& what,
                              const std::string& where, const schema::Reader& r) {
  const json& acc = r.member(entry, "accessors", where);
  if (!acc.is_array() || acc.size() != want)
    r.fail(where + ".accessors must list " + std::to_string(want) + " accessors for " + what);
  std::vector<int> out;
  for (std::size_t i = 0; i < want; ++i) {
    if (!acc[i].is_number_integer() || acc[i].get<std::int64_t>() < 0 ||
        acc[i].get<std::int64_t>() > 2147483647)
      r.fail(where + ".accessors[" + std::to_string(i) + "] is not an index");
    out.push_back(acc[i].get<int>());
  }
  return out;
}

void requireFinite(const float* x, std::size_t n, const std::string& what,
                   const schema::Reader& r) {
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isfinite(x[i]))
      r.fail(what + " holds a non-finite value at element " + std::to_string(i));
}

/// Exactly `count` floats of accessor `index`: a view of the file's bytes when they are tightly
/// packed and aligned and a keeper holds them, else a copy. Every value checked finite, unless
/// they are `rows` of a file read without (ByteKeeper::checkRows).
FloatArray floats(const gltf::AccessorReader& a, int index, std::size_t count,
                  const std::string& what, const schema::Reader& r, const ByteKeeper& bytes,
                  bool rows) {
  const gltf::AccessorSpan s = a.spanExact(index, 1, kFloat, count, what, sizeof(float));
  FloatArray out;
  if (bytes.keeper && s.stride == sizeof(float) &&
      reinterpret_cast<std::uintptr_t>(s.data) % alignof(float) == 0) {
    out = FloatArray::view(bytes.keeper, reinterpret_cast<const float*>(s.data), count);
  } else {
    std::vector<float> copy(count);
    for (std::size_t i = 0; i < count; ++i) std::memcpy(&copy[i], s.element(i), sizeof(float));
    out = FloatArray(std::move(copy));
  }
  if (!rows || bytes.checkRows) requireFinite(out.data(), out.size(), what, r);
  return out;
}

// ---- dense vectors ----------------------------------------------------------------------------

class DenseVectorCodec final : public TransferCodec {
 public:
  std::vector<std::pair<std::string, int>> encode(const BakedTransfer& bt, glb::BinaryChunk& bin,
                                                  json& entry) const override {
    const Transfer& t = bt.transfer;
    const std::size_t S = t.stride(), K = (S + 3) / 4, n = t.rowCount();
    const std::string prefix = transferAttributePrefix(bt.mode());
    std::vector<std::pair<std::string, int>> attributes;
    json acc = json::array();
    for (std::size_t k = 0; k < K; ++k) {
      // Column k of every row, written in blocks of rows while streaming.
      const auto writeColumn = [&t, S, n, k](std::ostream& os) {
        constexpr std::size_t kBlock = 4096;
        std::vector<float> col(kBlock * 4);
        for (std::size_t v0 = 0; v0 < n; v0 += kBlock) {
          const std::size_t m = std::min(kBlock, n - v0);
          std::fill(col.begin(), col.end(), 0.0f);
          for (std::size_t v = 0; v < m; ++v)
            for (std::size_t j = 0; j < 4 && 4 * k + j < S; ++j)
              col[v * 4 + j] = t.row(v0 + v)[4 * k + j];
          os.write(reinterpret_cast<const char*>(col.data()), static_cast<std::streamsize>(m * 16));
        }
      };
      const std::string name = prefix + std::to_string(k);
      const int view = bin.view(n * 16, 16, kArrayBuffer, name, writeColumn);
      attributes.emplace_back(name, view);
      acc.push_back(bin.accessor(view, 0, n, "VEC4", kFloat, name + " (vertex range)"));
    }
    entry["attributePrefix"] = prefix;
    entry["accessors"] = std::move(acc);
    return attributes;
  }

  Transfer decode(const json& entry, const std::string& where, const TransferShape& shape,
                  TransferMode mode, const gltf::AccessorReader& a, const schema::Reader& r,
                  const ByteKeeper&) const override {
    const std::size_t S = shape.stride(), K = (S + 3) / 4, n = shape.rows.count;
    const std::vector<int> acc = accessorList(
        entry, K,
        std::to_string(shape.bands) + " bands x " + std::to_string(shape.channels) + " channels",
        where, r);
    std::vector<float> values(n * S, 0.0f);
    for (std::size_t k = 0; k < K; ++k) {
      const std::string what =
          std::string(toString(mode)) + " transfer column " + std::to_string(k);
      const std::vector<float> col = a.exact<float>(acc[k], 4, kFloat, n, what);
      requireFinite(col.data(), col.size(), std::string(toString(mode)) + " transfer", r);
      for (std::size_t v = 0; v < n; ++v)
        for (std::size_t j = 0; j < 4 && 4 * k + j < S; ++j)
          values[v * S + 4 * k + j] = col[v * 4 + j];
    }
    return Transfer::dense(shape, FloatArray(std::move(values)));
  }
};

// ---- dense rows in one accessor: matrices (either domain), per-texel vectors ------------------

class DenseRowsCodec final : public TransferCodec {
 public:
  std::vector<std::pair<std::string, int>> encode(const BakedTransfer& bt, glb::BinaryChunk& bin,
                                                  json& entry) const override {
    const Transfer& t = bt.transfer;
    const bool matrix = t.isMatrix();
    const std::string name = matrix ? transferMatrixName(bt.mode()) : transferTexelName(bt.mode());
    const FloatArray& v = t.values();
    const int view = bin.view(v.data(), v.size() * sizeof(float), 0, 0, name);
    entry[matrix ? "matrixAccessor" : "texelAccessor"] = name;
    entry["accessors"] = json::array({bin.accessor(view, 0, v.size(), "SCALAR", kFloat, name)});
    return {};
  }

  Transfer decode(const json& entry, const std::string& where, const TransferShape& shape,
                  TransferMode mode, const gltf::AccessorReader& a, const schema::Reader& r,
                  const ByteKeeper& bytes) const override {
    const char* what = shape.isMatrix() ? " matrices" : " texel rows";
    const std::vector<int> acc = accessorList(entry, 1, std::string("the") + what, where, r);
    // The reader checks the declared count against the bytes present before anything is read.
    return Transfer::dense(shape, floats(a, acc[0], shape.rows.count * shape.stride(),
                                         std::string(toString(mode)) + what, r, bytes, true));
  }
};

// ---- Haar rows: per row its scale, per term a 16-bit (or 32-bit) index and a 16-bit value -----

class HaarRowsCodec final : public TransferCodec {
 public:
  std::vector<std::pair<std::string, int>> encode(const BakedTransfer& bt, glb::BinaryChunk& bin,
                                                  json& entry) const override {
    const Transfer& t = bt.transfer;
    const std::size_t rows = t.rowCount(), terms = std::size_t(t.shape().haar.terms);
    const bool wide = haar::coefficientCount(t.shape().haar.resolution) > 65536;
    // The rows are on their grid (haar_rows.hpp): the scale is the row's largest |value| and
    // every q an integer, read back exactly.
    auto kind = std::make_shared<std::vector<std::uint8_t>>(rows, 0);
    auto scale = std::make_shared<std::vector<float>>(rows, 0.0f);
    auto index = std::make_shared<std::vector<std::uint32_t>>(rows * terms);
    auto value = std::make_shared<std::vector<std::int16_t>>(rows * terms);
    for (std::size_t r = 0; r < rows; ++r) {
      const float* p = t.row(r);
      (*kind)[r] = static_cast<std::uint8_t>(p[0]);
      float s = 0;
      for (std::size_t k = 0; k < terms; ++k) s = std::max(s, std::abs(p[2 + 2 * k]));
      (*scale)[r] = s;
      for (std::size_t k = 0; k < terms; ++k) {
        (*index)[r * terms + k] = static_cast<std::uint32_t>(p[1 + 2 * k]);
        (*value)[r * terms + k] =
            static_cast<std::int16_t>(haar::quantizeHaarValue(p[2 + 2 * k], s));
      }
    }
    const std::string prefix = transferHaarPrefix(bt.mode());
    json acc = json::array();
    const auto add = [&](const char* part, std::size_t count, int type, std::size_t size,
                         glb::BinaryChunk::Writer write) {
      acc.push_back(bin.accessor(bin.view(count * size, 0, 0, prefix + part, std::move(write)), 0,
                                 count, "SCALAR", type, prefix + part));
    };
    add("KIND", rows, kUbyte, 1, [kind](std::ostream& os) {
      os.write(reinterpret_cast<const char*>(kind->data()), std::streamsize(kind->size()));
    });
    add("SCALE", rows, kFloat, 4, [scale](std::ostream& os) {
      os.write(reinterpret_cast<const char*>(scale->data()), std::streamsize(scale->size() * 4));
    });
    add("INDEX", rows * terms, wide ? kUint : kUshort, wide ? 4 : 2,
        [index, wide](std::ostream& os) {
          if (wide) {
            os.write(reinterpret_cast<const char*>(index->data()),
                     std::streamsize(index->size() * 4));
            return;
          }
          std::vector<std::uint16_t> narrow(index->begin(), index->end());
          os.write(reinterpret_cast<const char*>(narrow.data()),
                   std::streamsize(narrow.size() * 2));
        });
    add("VALUE", rows * terms, kShort, 2, [value](std::ostream& os) {
      os.write(reinterpret_cast<const char*>(value->data()), std::streamsize(value->size() * 2));
    });
    // Inter-reflected: each row's bounce in SH, as float32, after its pairs (shape.hpp).
    const std::size_t bounceFloats = t.shape().haarBounceFloats();
    if (bounceFloats > 0) {
      auto bounce = std::make_shared<std::vector<float>>(rows * bounceFloats);
      const std::size_t offset = t.shape().haarBounceOffset();
      for (std::size_t r = 0; r < rows; ++r)
        std::copy_n(t.row(r) + offset, bounceFloats, bounce->data() + r * bounceFloats);
      add("BOUNCE", rows * bounceFloats, kFloat, 4, [bounce](std::ostream& os) {
        os.write(reinterpret_cast<const char*>(bounce->data()),
                 std::streamsize(bounce->size() * 4));
      });
    }
    entry["haarAccessorPrefix"] = prefix;
    entry["accessors"] = std::move(acc);
    return {};
  }

  Transfer decode(const json& entry, const std::string& where, const TransferShape& shape,
                  TransferMode mode, const gltf::AccessorReader& a, const schema::Reader& r,
                  const ByteKeeper&) const override {
    const std::size_t bounceFloats = shape.haarBounceFloats();
    const std::vector<int> acc =
        bounceFloats > 0
            ? accessorList(entry, 5,
                           "the inter-reflected Haar rows (kind, scale, index, value, bounce)",
                           where, r)
            : accessorList(entry, 4, "the Haar rows (kind, scale, index, value)", where, r);
    const std::size_t rows = shape.rows.count, terms = std::size_t(shape.haar.terms);
    const bool wide = haar::coefficientCount(shape.haar.resolution) > 65536;
    const std::string what = std::string(toString(mode)) + " Haar rows";
    const std::vector<std::uint8_t> kind =
        a.exact<std::uint8_t>(acc[0], 1, kUbyte, rows, what + " kinds");
    const std::vector<float> scale = a.exact<float>(acc[1], 1, kFloat, rows, what + " scales");
    std::vector<std::uint32_t> index;
    if (wide) {
      index = a.exact<std::uint32_t>(acc[2], 1, kUint, rows * terms, what + " indices");
    } else {
      const auto narrow =
          a.exact<std::uint16_t>(acc[2], 1, kUshort, rows * terms, what + " indices");
      index.assign(narrow.begin(), narrow.end());
    }
    const std::vector<std::int16_t> value =
        a.exact<std::int16_t>(acc[3], 1, kShort, rows * terms, what + " values");
    std::vector<float> bounce;
    if (bounceFloats > 0)
      bounce = a.exact<float>(acc[4], 1, kFloat, rows * bounceFloats, what + " bounces");
    const std::size_t stride = shape.stride(), offset = shape.haarBounceOffset();
    std::vector<float> out(rows * stride);
    for (std::size_t i = 0; i < rows; ++i) {
      if (!std::isfinite(scale[i]) || scale[i] < 0)
        r.fail(where + ": Haar row " + std::to_string(i) + " has scale " +
               std::to_string(scale[i]) + " (a finite number >= 0)");
      float* row = out.data() + i * stride;
      row[0] = float(kind[i]);  // 0 or 1: checked with the rest below
      for (std::size_t k = 0; k < terms; ++k) {
        const std::int16_t q = value[i * terms + k];
        if (q < -haar::kHaarValueSteps)
          r.fail(where + ": Haar row " + std::to_string(i) + ", term " + std::to_string(k) +
                 ": value " + std::to_string(q) + " is off the grid (-32767..32767)");
        row[1 + 2 * k] = float(index[i * terms + k]);
        row[2 + 2 * k] = haar::dequantizeHaarValue(scale[i], q);
      }
      std::copy_n(bounce.data() + i * bounceFloats, bounceFloats, row + offset);
    }
    // Dequantised: always a copy, always checked (index range, order, padding, kind).
    Transfer t = Transfer::dense(shape, FloatArray(std::move(out)));
    r.within(where, [&] { t.check(what); });
    return t;
  }
};

// ---- CPCA -------------------------------------------------------------------------------------

class CpcaCodec final : public TransferCodec {
 public:
  std::vector<std::pair<std::string, int>> encode(const BakedTransfer& bt, glb::BinaryChunk& bin,
                                                  json& entry) const override {
    const Transfer& t = bt.transfer;
    const CpcaRows& c = t.cpca();
    const std::size_t n = t.rowCount();
    const std::string prefix = transferCompressedPrefix(bt.mode());
    json acc = json::array();
    const auto named = [&](int view, std::size_t count, int type, const char* part) {
      acc.push_back(bin.accessor(view, 0, count, "SCALAR", type, prefix + part));
    };
    if (c.clusters <= 65536) {
      const auto* ids = &c.cluster;
      const int view = bin.view(n * 2, 0, 0, prefix + "CLUSTER", [ids](std::ostream& os) {
        std::vector<std::uint16_t> block;
        for (std::size_t v0 = 0; v0 < ids->size(); v0 += 4096) {
          block.assign(ids->begin() + v0, ids->begin() + std::min(ids->size(), v0 + 4096));
          os.write(reinterpret_cast<const char*>(block.data()),
                   static_cast<std::streamsize>(block.size() * 2));
        }
      });
      named(view, n, kUshort, "CLUSTER");
    } else {
      named(bin.view(c.cluster.data(), n * 4, 0, 0, prefix + "CLUSTER"), n, kUint, "CLUSTER");
    }
    const auto floatsView = [&](const FloatArray& x, const char* part) {
      named(bin.view(x.data(), x.size() * 4, 0, 0, prefix + part), x.size(), kFloat, part);
    };
    if (c.basisCount > 0) floatsView(c.weights, "WEIGHTS");
    floatsView(c.means, "MEANS");
    if (c.basisCount > 0) floatsView(c.basis, "BASIS");
    json z = {{"method", "cpca"},
              {"clusters", c.clusters},
              {"basisCount", c.basisCount},
              {"accessorPrefix", prefix}};
    schema::writeCpcaRecord(bt.compression, z);
    entry["compressed"] = std::move(z);
    entry["accessors"] = std::move(acc);
    return {};
  }

  Transfer decode(const json& entry, const std::string& where, const TransferShape& shape,
                  TransferMode mode, const gltf::AccessorReader& a, const schema::Reader& r,
                  const ByteKeeper& bytes) const override {
    const std::string zw = where + ".compressed";
    const json& z = entry["compressed"];
    if (!z.is_object() || r.string(z, "method", zw) != "cpca")
      r.fail(zw + ".method must be \"cpca\"");
    const std::size_t n = shape.rows.count, S = shape.stride();
    CpcaRows c;
    c.clusters = static_cast<int>(
        r.integer(z, "clusters", zw, 1, std::min<double>(double(n), 2147483647.0)));
    c.basisCount = static_cast<int>(r.integer(z, "basisCount", zw, 0, static_cast<double>(S)));
    const std::size_t K = static_cast<std::size_t>(c.clusters),
                      N = static_cast<std::size_t>(c.basisCount);
    const std::vector<int> acc =
        accessorList(entry, N > 0 ? 4 : 2,
                     "compressed transfer with " + std::to_string(N) + " basis vectors", where, r);
    const std::string what = std::string(toString(mode)) + " compressed transfer";
    if (K <= 65536) {
      const auto ids = a.exact<std::uint16_t>(acc[0], 1, kUshort, n, what + " cluster ids");
      c.cluster.assign(ids.begin(), ids.end());
    } else {
      c.cluster = a.exact<std::uint32_t>(acc[0], 1, kUint, n, what + " cluster ids");
    }
    std::size_t next = 1;
    if (N > 0) c.weights = floats(a, acc[next++], n * N, what + " weights", r, bytes, true);
    c.means = floats(a, acc[next++], K * S, what + " means", r, bytes, false);
    if (N > 0) c.basis = floats(a, acc[next++], K * N * S, what + " basis", r, bytes, false);
    if (!bytes.checkRows)  // the ids alone (check() would read every weight too)
      for (std::size_t i = 0; i < n; ++i)
        if (c.cluster[i] >= K)
          r.fail(zw + ": row " + std::to_string(i) + " names cluster " +
                 std::to_string(c.cluster[i]) + " of " + std::to_string(K));
    Transfer t = Transfer::cpca(shape, std::move(c));
    if (bytes.checkRows) t.check(r.name() + ": " + zw);  // ids below K
    return t;
  }
};

const DenseVectorCodec kDenseVector;
const DenseRowsCodec kDenseRows;
const CpcaCodec kCpca;
const HaarRowsCodec kHaarRows;

/// Dense vectors over vertices are vertex attributes; every other dense transfer is its rows.
const TransferCodec& denseCodecFor(const TransferShape& shape) {
  if (shape.isHaar()) return kHaarRows;
  if (shape.isMatrix() || shape.domain == TransferDomain::Texels) return kDenseRows;
  return kDenseVector;
}

}  // namespace

const TransferCodec& codecFor(const Transfer& t) {
  if (t.compressed()) return kCpca;
  return denseCodecFor(t.shape());
}

const TransferCodec& codecFor(const json& entry, const TransferShape& shape, int version,
                              const std::string& where, const schema::Reader& r) {
  if (r.has(entry, "compressed")) {
    if (version < 3)
      r.fail(where + " is compressed transfer in a version " + std::to_string(version) +
             " file (compression needs version 3)");
    return kCpca;
  }
  return denseCodecFor(shape);
}

}  // namespace prt::io
