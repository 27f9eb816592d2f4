#pragma once
// The bake file: a glTF 2.0 binary (.glb) that any glTF viewer opens as a plain mesh, and that
// carries the per-vertex transfer (one or more modes) as application-specific vertex attributes
// plus the bake settings and statistics in `extras`. The layout is specified byte by byte in
// docs/formats-bake.md; in short:
//
//   * one glTF mesh + node per MeshPart, one triangle primitive each (POSITION, NORMAL,
//     TEXCOORD_0 if any, COLOR_0 = linear albedo if any, uint32 indices), all parts viewing one
//     shared vertex buffer in the scene's global vertex order;
//   * the transfer of mode M (B² coefficients × C channels per vertex, K = ceil(B²C / 4)) as K
//     VEC4 float attributes _PRT_<M>_T0 .. _PRT_<M>_T{K-1}: attribute k holds floats
//     4k .. 4k+3 of the vertex's row (row layout as TransferField: (i*C + c)), zero-padded;
//   * extras.prtkit: formatVersion, generator, vertex range, and per mode its settings, stats
//     and the accessors that hold its rows for the range.
//
// A bake may cover a vertex range [first, first + count) of the scene (split bakes): the file
// then holds the whole mesh but only the range's transfer rows (in accessors listed in extras,
// not as primitive attributes, since glTF attributes must cover every vertex). mergeBakes()
// concatenates ranges exactly, because a vertex's transfer depends only on the inputs, the seed
// and its global index (see prt/transport/bake.hpp).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "prt/compress/cpca.hpp"
#include "prt/geometry/mesh.hpp"
#include "prt/transfer/field.hpp"
#include "prt/transport/bake.hpp"

namespace prt {

/// The bake-file format version this prtkit writes and the newest it reads.
/// Version 1: vector transfer as vertex attributes. Version 2 adds matrix (glossy) transfer in
/// accessors named from extras; a bake without matrices is still written as version 1.
/// Version 3 adds CPCA-compressed transfer (cluster ids, weights, cluster means and bases in
/// accessors named from extras); only a bake that holds compressed transfer is written as 3.
inline constexpr int kBakeFormatVersion = 3;

/// One transfer stored in a bake file, with the settings and statistics that produced it.
/// settings.firstVertex / vertexCount equal the file's vertex range.
struct BakedTransfer {
  BakeSettings settings;  ///< mode and layout equal the field's; (mode, layout) unique in a file
  BakeStats stats;
  TransferField field;  ///< rows for the file's vertex range (field.vertexCount = range count)
  /// Set when the transfer is stored CPCA-compressed (prt compress): `field` then keeps the
  /// shape (layout, bands, channels, rows) with no data, and this holds the rows.
  std::optional<CompressedTransfer> compressed;
  CpcaOptions compression;     ///< the options that made `compressed`
  CpcaStats compressionStats;  ///< its error against the uncompressed transfer

  /// The rows as a dense field: `field`, or the reconstruction of `compressed`.
  TransferField dense() const { return compressed ? compressed->reconstruct() : field; }
};

struct BakeFile {
  Mesh mesh;                               ///< the whole scene, all vertices
  std::vector<BakedTransfer> transfers;    ///< distinct modes, all over the same vertex range
  std::size_t firstVertex = 0;             ///< the vertex range the transfers cover
  std::size_t vertexCount = 0;             ///< (equal to mesh.vertexCount() for a complete bake)
  int formatVersion = kBakeFormatVersion;  ///< as read (writeBake writes requiredVersion())
  std::string generator = "prtkit";        ///< "prtkit 0.1.0"; written to asset.generator too

  /// True if the transfers cover every vertex of the mesh.
  bool complete() const { return firstVertex == 0 && vertexCount == mesh.vertexCount(); }
  /// Throws prt::Error("FILE: is a partial bake: it holds transfer for vertices a..b of n only
  /// (merge ...)") unless complete(): the one check every consumer of a whole bake makes.
  void requireComplete(const std::string& file) const;
  /// The first transfer of `mode` (any layout), or nullptr.
  const BakedTransfer* find(TransferMode mode) const;
  /// The transfer of `mode` and `layout`, or nullptr.
  const BakedTransfer* find(TransferMode mode, TransferLayout layout) const;
  /// The oldest format version that holds this bake (3 if it has compressed transfer, else 2 if
  /// it has matrices, else 1).
  int requiredVersion() const;
  /// Replaces every compressed transfer by its reconstruction (for consumers of dense rows).
  void expandCompressed();
};

/// Serialises to GLB bytes. Throws prt::Error if the bake is inconsistent (row counts, bands,
/// duplicate modes, parts that do not tile the mesh, an empty mesh).
std::string encodeBake(const BakeFile& bake);
/// Writes a .glb atomically (nothing is left behind on failure).
void writeBake(const std::string& path, const BakeFile& bake);

/// Parses and validates GLB bytes; `name` is used in messages. Throws prt::Error with one line
/// ("NAME: ...") for anything malformed, truncated, or newer than kBakeFormatVersion.
BakeFile decodeBake(std::span<const unsigned char> bytes, const std::string& name);
/// Reads and validates a bake file.
BakeFile readBake(const std::string& path);

/// The transfer to relight with — the one policy every verb and the viewers share: of `mode`
/// if given, else the richest the bake holds (interreflected, then shadowed, then unshadowed);
/// of `layout` if given, else a matrix (glossy) before a vector of the same mode. Throws
/// prt::Error("FILE: no ... transfer in the bake (it has ...)").
const BakedTransfer& pickTransfer(const BakeFile& bake, std::optional<TransferMode> mode,
                                  std::optional<TransferLayout> layout, const std::string& file);

/// Concatenates bakes of disjoint, adjacent vertex ranges of the same mesh with the same modes
/// and settings (in any order) into one bake of the union range. Statistics are combined: rays
/// and times add, mean errors average weighted by vertex count, maxima take the maximum.
/// Throws prt::Error naming the first mismatch, gap or overlap.
BakeFile mergeBakes(std::vector<BakeFile> pieces);

/// The glTF attribute name prefix of a mode's vector transfer: "_PRT_SHADOWED_T" etc.
std::string transferAttributePrefix(TransferMode mode);
/// The accessor name of a mode's matrix transfer: "_PRT_SHADOWED_M" etc.
std::string transferMatrixName(TransferMode mode);
/// The accessor name prefix of a mode's compressed transfer: "_PRT_SHADOWED_CPCA_" etc.
/// (then CLUSTER, WEIGHTS, MEANS, BASIS).
std::string transferCompressedPrefix(TransferMode mode);

}  // namespace prt
