#pragma once
// The transfer: what a bake produces and every consumer reads — one value whatever its
// representation. Its shape (domain, layout, bands, channels, rows; shape.hpp) is stored once,
// here; behind it the rows are either dense (stride() floats per row) or CPCA-compressed (a
// cluster id and N weights per row, K means and K·N basis vectors; cpca_rows.hpp).
//
// Consumers ask the transfer what it is once, at one dispatch point per module (relight's entry
// point, the bake file's codecs, the viewers' shader packing); the operations every consumer
// needs live here, defined once for both representations:
//
//   cut(b)         the first b bands (vectors: the first b² values of every row; matrices: the
//                  leading b² × b² block). Dense rows are cut; compressed rows keep their ids
//                  and weights and cut every mean and basis vector, which is exact because the
//                  reconstruction is linear: cut(b).toDense() == toDense().cut(b), bit for bit.
//   toDense()      the reconstruction (a dense transfer is returned as is, sharing its storage).
//   reconstructRow the dense values of one row, from either representation.
//   bytes()        memory as stored.
//
// Storage is shared between copies and copied on the first write (core/float_array.hpp), so a
// Transfer is cheap to pass by value and a mapped bake file is never copied to be read.

#include <cstddef>
#include <string>

#include "prt/core/float_array.hpp"
#include "prt/transfer/cpca_rows.hpp"
#include "prt/transfer/shape.hpp"

namespace prt {

class Transfer {
 public:
  enum class Representation { Dense, Cpca };

  Transfer() = default;
  /// Dense rows of `shape`, all zero.
  static Transfer zeros(const TransferShape& shape);
  /// Dense rows (rows · stride floats; throws prt::Error("transfer: ...") on another size).
  static Transfer dense(const TransferShape& shape, FloatArray values);
  /// CPCA-compressed rows (throws prt::Error("transfer: ...") when the arrays do not fit the
  /// shape; ids and finiteness are checked by check()).
  static Transfer cpca(const TransferShape& shape, CpcaRows rows);

  const TransferShape& shape() const { return shape_; }
  /// True for a default-constructed transfer (no bands, no rows).
  bool empty() const { return shape_.bands == 0 && !shape_.isHaar(); }
  bool isHaar() const { return shape_.isHaar(); }
  TransferLayout layout() const { return shape_.layout; }
  TransferDomain domain() const { return shape_.domain; }
  int bands() const { return shape_.bands; }
  int coeffs() const { return shape_.coeffs(); }
  int channels() const { return shape_.channels; }
  bool isMatrix() const { return shape_.isMatrix(); }
  std::size_t rowCount() const { return shape_.rows.count; }
  const RowRange& rows() const { return shape_.rows; }
  std::size_t stride() const { return shape_.stride(); }

  Representation representation() const { return representation_; }
  bool compressed() const { return representation_ == Representation::Cpca; }

  // Dense rows (PRT_CHECK that the transfer is dense).
  const FloatArray& values() const;
  /// Writable dense values (copies shared storage first; take it once before a parallel loop).
  float* mutableValues();
  const float* row(std::size_t r) const { return values().data() + r * stride(); }

  // Compressed rows (PRT_CHECK that the transfer is compressed).
  const CpcaRows& cpca() const;
  const float* clusterMean(std::size_t k) const;
  const float* basisVector(std::size_t k, std::size_t j) const;

  /// The dense values of row r (stride() floats) into out, from either representation.
  void reconstructRow(std::size_t r, float* out) const;
  /// The first b bands, 1 ≤ b ≤ bands(), in the same representation (see above); SH only.
  Transfer cut(int b) const;
  /// The dense transfer (the reconstruction of compressed rows; a dense one unchanged).
  Transfer toDense() const;
  /// Bytes as stored: dense 4 · rows · stride; Haar as its file holds it (transfer/haar_rows.hpp:
  /// 4 + 4 · terms a row, 6 · terms past 6·104² coefficients, and 4 bytes a float of an
  /// inter-reflected row's bounce); CPCA a uint16 (K ≤ 65536) or uint32 id and N floats per row,
  /// plus K(N + 1) vectors of stride floats.
  std::size_t bytes() const;
  /// Throws prt::Error("WHAT: ...") unless the shape is valid, the arrays fit it, every cluster
  /// id is below K and every value is finite.
  void check(const std::string& what) const;

  /// The same rows relabelled as rows [first, first + count) of the domain (the count is the
  /// transfer's own; merging split bakes places pieces with it).
  Transfer withFirstRow(std::size_t first) const;

 private:
  TransferShape shape_;
  Representation representation_ = Representation::Dense;
  FloatArray values_;  ///< dense
  CpcaRows cpca_;      ///< compressed
};

}  // namespace prt
