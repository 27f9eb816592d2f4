#pragma once
// One codec per representation × layout of a transfer in a bake file (docs/formats-bake.md):
//
//   dense vectors    K = ⌈B²C/4⌉ VEC4 float columns, column k of row r = values 4k..4k+3 of the
//                    row, zero-padded; in a complete bake also the primitives' attributes
//                    _PRT_<MODE>_T<k> (any glTF viewer sees them as vertex data)
//   dense matrices   one tightly packed SCALAR float accessor _PRT_<MODE>_M of the rows as
//                    Transfer holds them (B⁴·C floats per row are far past the 16 vertex
//                    attributes a GPU guarantees)
//   CPCA             cluster ids (uint16 when K ≤ 65536, else uint32), N weights per row, K
//                    means and K·N basis vectors of D floats: SCALAR accessors
//                    _PRT_<MODE>_CPCA_{CLUSTER,WEIGHTS,MEANS,BASIS} (weights and basis absent
//                    when N = 0)
//
// Each codec describes its rows in the binary chunk and names them in the transfer's JSON
// entry, and reads them back with every count checked against the shape before allocating.
// Private to src/io.

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "bake_schema.hpp"
#include "glb.hpp"
#include "prt/gltf/accessor.hpp"
#include "prt/io/bake_file.hpp"

namespace prt::io {

/// Where a decoded transfer's rows may point instead of being copied: the bytes of the file,
/// kept alive by `keeper` (null: copy everything). `checkRows` false — a mapped file whose reader
/// reads a few rows (mapBake) — leaves the rows' own values (dense rows, CPCA weights) unchecked
/// for finiteness, since checking would read them all; the reader checks those it reads. Cluster
/// ids, means and basis vectors are checked either way.
struct ByteKeeper {
  std::shared_ptr<const void> keeper;
  bool checkRows = true;
};

class TransferCodec {
 public:
  virtual ~TransferCodec() = default;
  /// Describes t's rows in `bin` and names them in `entry` (its "accessors" and the codec's own
  /// members). Returns the vertex attributes a complete bake's primitives carry: (name, view of
  /// VEC4 columns) pairs, empty for codecs without attributes.
  virtual std::vector<std::pair<std::string, int>> encode(const BakedTransfer& t,
                                                          glb::BinaryChunk& bin,
                                                          nlohmann::json& entry) const = 0;
  /// Reads the rows of `shape` named by `entry`.
  virtual Transfer decode(const nlohmann::json& entry, const std::string& where,
                          const TransferShape& shape, TransferMode mode,
                          const gltf::AccessorReader& accessors, const schema::Reader& r,
                          const ByteKeeper& bytes) const = 0;
};

/// The codec that writes `t`.
const TransferCodec& codecFor(const Transfer& t);
/// The codec a file's transfer entry was written by (its members say; version checked).
const TransferCodec& codecFor(const nlohmann::json& entry, const TransferShape& shape, int version,
                              const std::string& where, const schema::Reader& r);

}  // namespace prt::io
