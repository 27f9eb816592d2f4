#pragma once
// The bake file: a glTF 2.0 binary (.glb) that any glTF viewer opens as a plain mesh, and that
// carries one or more transfers (each a prt::Transfer with how it was baked) in
// application-specific accessors described in the PRTKIT_radiance_transfer extension. The layout is
// specified byte by byte in docs/formats-bake.md; in short:
//
//   * one glTF mesh + node per MeshPart, one triangle primitive each (POSITION, NORMAL,
//     TEXCOORD_0 if any, COLOR_0 = linear albedo if any, uint32 indices), all parts viewing one
//     shared vertex buffer in the scene's global vertex order; the mesh's base-colour texture,
//     if any, as material 0's baseColorTexture on TEXCOORD_0 (one embedded PNG);
//   * each transfer through the codec of its representation and layout: dense vectors as
//     ⌈B²C/4⌉ VEC4 float vertex attributes _PRT_<MODE>_T0.., dense matrices as one SCALAR
//     float accessor _PRT_<MODE>_M, CPCA-compressed rows as four accessors _PRT_<MODE>_CPCA_*;
//   * extensions.PRTKIT_radiance_transfer: formatVersion, generator, vertex range, and per transfer
//   its shape, how it
//     was baked (BakeRecipe, the material as structured fields), its statistics, and the
//     accessors that hold its rows.
//
// A bake may cover a vertex range [first, first + count) of the scene (split bakes): the file
// then holds the whole mesh but only the range's transfer rows (in accessors listed in the
// extension, not as primitive attributes, since glTF attributes must cover every vertex).
// mergeBakes() (bake_merge.hpp) concatenates ranges exactly, because a vertex's transfer depends
// only on the inputs, the seed and its global index (see prt/transport/bake.hpp).
//
// A bake's transfers share one domain: the mesh's vertices (vertexRange), or the texels of one
// lightmap over the mesh's lightmap UVs (texelRange and lightmap {width, height, padding}; the
// rows as one float accessor per transfer, _PRT_<MODE>_TEXELS, or CPCA's four). A texel range
// splits and merges as a vertex range does.
//
// Versions: 1 vector transfer, 2 adds matrices, 3 adds CPCA-compressed transfer, 4 stores the
// material as structured fields (type, exponent or roughness, ks, kd as numbers that read back
// exactly), 5 moves the object from the root's extras.prtkit into the vendor extension
// PRTKIT_radiance_transfer (declared in extensionsUsed, not required: any glTF viewer still
// shows the mesh; docs/extensions/PRTKIT_radiance_transfer/), 6 adds per-texel transfer, 7 probe
// grids, 8 Haar-wavelet transfer (settings.basis "haar" and settings.haar {resolution, terms};
// its quantised rows in accessors _PRT_<MODE>_HAAR_{KIND,SCALE,INDEX,VALUE}), 9 inter-reflected
// Haar transfer (settings.haar.bounceBands, settings.channels the bounce's, and a fifth
// accessor _PRT_<MODE>_HAAR_BOUNCE: each row's bounce in SH, float32). This prtkit writes 9 and
// reads 1–9.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "prt/core/version.hpp"
#include "prt/geometry/mesh.hpp"
#include "prt/transfer/bake_settings.hpp"
#include "prt/transfer/cpca_settings.hpp"
#include "prt/transfer/transfer.hpp"

namespace prt {

/// The bake-file format version this prtkit writes and the newest it reads.
inline constexpr int kBakeFormatVersion = 9;
/// The first version that holds probe grids (issue 32).
inline constexpr int kFirstProbeVersion = 7;
/// The first version that holds Haar-wavelet transfer (issue 33).
inline constexpr int kFirstHaarVersion = 8;
/// The first version that holds inter-reflected Haar transfer (a bounce in each row).
inline constexpr int kFirstHaarBounceVersion = 9;
/// The largest |value| a probe grid's origin and spacing may hold in a file (a float's range,
/// with room to add them).
inline constexpr double kMaxProbeGridNumber = 1e30;
/// The glTF extension that holds a bake's object from version 5 (earlier: extras.prtkit).
inline constexpr const char* kBakeExtension = "PRTKIT_radiance_transfer";
/// The first version written as the extension.
inline constexpr int kFirstExtensionVersion = 5;
/// The largest bake file, written or read: a GLB's lengths are 32 bits. The one limit for both,
/// so nothing is written that cannot be read (reading holds the file once, the transfer's rows
/// viewing it where they can).
inline constexpr std::uint64_t kMaxBakeFileBytes = (std::uint64_t(1) << 32) - 1;

/// One transfer stored in a bake file, with how it was made. The transfer's shape (layout,
/// bands, channels, rows) is the transfer's own; (mode, layout) is unique in a file.
struct BakedTransfer {
  BakeRecipe recipe;
  BakeStats stats;
  Transfer transfer;
  /// How a compressed transfer was fitted, and its error against the dense rows (meaningful
  /// only when transfer.compressed()).
  CpcaRecord compression;

  TransferMode mode() const { return recipe.mode; }
  /// The settings that would bake this transfer again (the recipe and the shape).
  BakeSettings settings() const;
  /// "shadowed vector (compressed)" — how the CLI names it.
  std::string describe() const;
};

struct BakeFile {
  Mesh mesh;                               ///< the whole scene, all vertices
  std::vector<BakedTransfer> transfers;    ///< distinct (mode, layout), all over rows()
  int formatVersion = kBakeFormatVersion;  ///< as read (writing writes kBakeFormatVersion)
  std::string generator = kGenerator;      ///< "prtkit 0.1.0"; written to asset.generator too

  /// The domain the transfers share (vertices when there are none).
  TransferDomain domain() const;
  /// Texels: the lightmap the transfers cover (zero size for vertices).
  TransferShape::LightmapSize lightmap() const;
  /// Probes: the grid the transfers cover (an empty grid otherwise).
  ProbeGrid probeGrid() const;
  /// Rows of the whole domain: the mesh's vertices, the lightmap's texels or the grid's probes.
  std::size_t domainRows() const;
  /// The row range the transfers cover (the whole mesh when there are none).
  RowRange rows() const;
  /// True if the transfers cover every row of their domain.
  bool complete() const;
  /// Throws prt::Error("FILE: is a partial bake: it holds transfer for vertices a..b of n only
  /// (merge ...)") unless complete(): the one check every consumer of a whole bake makes.
  void requireComplete(const std::string& file) const;
  /// Throws prt::Error("FILE: holds per-texel transfer (a W x H lightmap); USE ...") unless the
  /// transfers are per vertex: the one check of every consumer that reads rows as vertices.
  /// `use` says what does not take texels, e.g. "prt view relights per-vertex transfer only".
  void requireVertices(const std::string& file, const std::string& use) const;
  /// Throws prt::Error("FILE: holds a probe grid (N x N x N probes ...), not a surface's
  /// transfer; USE") for a probe bake: the one check of every consumer that draws or reads the
  /// transfer as the mesh's surface (vertices or texels).
  void requireSurface(const std::string& file, const std::string& use) const;
  /// Throws prt::Error("FILE: holds Haar-wavelet transfer (...); USE") when a transfer is in
  /// the Haar basis: the one check of every consumer that reads SH coefficients only. `use`
  /// says what does, e.g. "prt compress fits SH transfer".
  void requireSh(const std::string& file, const std::string& use) const;
  /// The transfer of `mode` and `layout` (any layout if not given), or nullptr.
  const BakedTransfer* find(TransferMode mode, std::optional<TransferLayout> layout = {}) const;
};

/// Serialises to GLB bytes. Throws prt::Error if the bake is inconsistent (row counts, bands,
/// duplicate modes, parts that do not tile the mesh, an empty mesh) or larger than
/// kMaxBakeFileBytes.
std::string encodeBake(const BakeFile& bake);
/// Writes a .glb atomically (nothing is left behind on failure).
void writeBake(const std::string& path, const BakeFile& bake);

/// Parses and validates GLB bytes (copied: the result does not refer to `bytes`); `name` is
/// used in messages. Throws prt::Error with one line ("NAME: ...") for anything malformed,
/// truncated, or newer than kBakeFormatVersion.
BakeFile decodeBake(std::span<const unsigned char> bytes, const std::string& name);
/// Reads and validates a bake file. The file is held in memory once; dense matrix and
/// compressed rows view it instead of being copied.
BakeFile readBake(const std::string& path);
/// Reads a bake file as readBake does, but maps it (core/file.hpp: mapFile) and leaves the
/// transfer's rows in the mapping unread: a row is read from disk when first touched, so a
/// consumer of a few rows (prt validate --vertices N) reads those and the mesh alone, whatever
/// the file's size. The rows' values (dense rows, CPCA weights) are not checked finite, which
/// would read them all: the consumer checks those it reads. Dense per-vertex vectors, stored as
/// columns, are copied and checked as readBake copies them.
BakeFile mapBake(const std::string& path);

/// The transfer to relight with — the one policy every verb and the viewers share: of `mode`
/// if given, else the richest the bake holds (kModesRichestFirst); of `layout` if given, else a
/// matrix (glossy) before a vector of the same mode. Throws prt::Error("FILE: no ... transfer in
/// the bake (it has ...)").
const BakedTransfer& pickTransfer(const BakeFile& bake, std::optional<TransferMode> mode,
                                  std::optional<TransferLayout> layout, const std::string& file);
/// The transfers in the order pickTransfer prefers them (indices into bake.transfers).
std::vector<std::size_t> transferPreference(const BakeFile& bake);

/// The glTF attribute name prefix of a mode's vector transfer: "_PRT_SHADOWED_T" etc.
std::string transferAttributePrefix(TransferMode mode);
/// The accessor name of a mode's matrix transfer: "_PRT_SHADOWED_M" etc.
std::string transferMatrixName(TransferMode mode);
/// The accessor name of a mode's dense per-texel vector transfer: "_PRT_SHADOWED_TEXELS" etc.
std::string transferTexelName(TransferMode mode);
/// The accessor name prefix of a mode's Haar rows: "_PRT_SHADOWED_HAAR_" (then SCALE, INDEX,
/// VALUE).
std::string transferHaarPrefix(TransferMode mode);
/// The accessor name prefix of a mode's compressed transfer: "_PRT_SHADOWED_CPCA_" etc.
/// (then CLUSTER, WEIGHTS, MEANS, BASIS).
std::string transferCompressedPrefix(TransferMode mode);
/// Where a transfer's numbers lie in the file, for prt info: "attributes _PRT_SHADOWED_T0..2",
/// "accessor _PRT_SHADOWED_M", "accessor _PRT_SHADOWED_TEXELS" or "CPCA-compressed, accessors
/// _PRT_SHADOWED_CPCA_*" — the one dispatch on its representation, layout and domain.
std::string transferStorage(const BakedTransfer& transfer);

}  // namespace prt
