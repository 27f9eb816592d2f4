#pragma once
// The shape of a transfer: everything that says what its numbers mean, stored once (in
// prt::Transfer) and read by every consumer (Sloan, Kautz & Snyder, "Precomputed Radiance
// Transfer for Real-Time Rendering in Dynamic, Low-Frequency Lighting Environments",
// SIGGRAPH 2002, §5 diffuse vectors, §6 glossy matrices).
//
// A transfer is a table of one *row* per element of its domain: mesh vertices, or the texels
// of a lightmap over the mesh's lightmap UVs, or the probes of a grid in space (probe_grid.hpp:
// matrices over the whole sphere). What a row holds depends on the layout:
//
//   Vector  (diffuse transfer)  B² coefficients:  T_i(p) = (1/π) ∫ Y_i(ω) V(p,ω) max(n·ω,0) dω
//                                                 (+ inter-reflected light);
//                                                 exit radiance R(p) = albedo(p) ⊙ Σ_i T_i L_i.
//   Matrix  (glossy transfer)   B² × B² entries, row-major, row i = transferred coefficient,
//                               column j = source-light coefficient:
//                                 (M_p)_ij = ∫_{n·ω>0} Y_i(ω) V(p,ω) Y_j(ω) dω (+ bounces),
//                               so the SH of the light that arrives at p is L'_p = M_p L; the
//                               material's lobes turn L'_p into exit radiance (material.hpp).
//
// Channels: 1 (scalar, the same transfer for r, g, b) or 3 (RGB, coloured inter-reflection),
// interleaved innermost: value e of a row, channel c, is at e·channels + c. For an RGB transfer
// the bounce albedos are folded in; the albedo at p itself is not (relighting applies it).
//
// Rows: a transfer may hold a range [first, first + count) of its domain's rows (a split bake);
// row r of the transfer is element first + r of the domain.
//
// Basis: spherical harmonics of B bands (everything above), or Haar wavelets over a cube map
// of N² texels per face (prt/haar/cube_haar.hpp; Ng, Ramamoorthi & Hanrahan 2003): a Haar row
// holds the smaller half of diffuse transfer over the 6 N² texels — the occluded part
//   D_j(p) = (1/π) ∫_texel j (1 − V(p,ω)) max(n·ω,0) dω   (= U_j − T_j)
// of a mostly open row, or the visible part T_j of a mostly closed one — wavelet-transformed,
// pruned to its `terms` largest coefficients and stored as a kind and `terms` (index, value)
// float pairs (prt/transfer/haar_rows.hpp). Relighting (prt/relight/relight_haar.hpp):
//   R(p) = albedo(p) ⊙ ( U(n)·L − Σ_k D̃_k L̃_k )   or   albedo(p) ⊙ Σ_k T̃_k L̃_k,
// the unshadowed part U(n)·L from the light in closed form (prt/haar/haar_light.hpp).
// Inter-reflected Haar transfer adds to each row its bounce — the light that arrives at p
// after one or more diffuse bounces, B_i(p) = Σ_{k≥1} T^k_i(p) — in SH of `bounceBands` bands
// (the bounce is smooth; only direct light has a sun's sharp edge), stored after the pairs and
// relit against the light's SH:  R(p) += albedo(p) ⊙ Σ_i B_i(p) L_i.
// A Haar shape has no bands (0); its channels (1, or 3 for coloured inter-reflection) are the
// bounce's, and its direct part is scalar.
//
// Memory: 4·B²·C bytes per row for vectors, 4·B⁴·C for matrices (9 bands, 1M vertices, RGB
// matrices: 79 GB); denseBytes() states it before anything is allocated.

#include <cstddef>
#include <string>

#include "prt/transfer/probe_grid.hpp"

namespace prt {

/// What one row holds.
enum class TransferLayout {
  Vector,  ///< B² values: diffuse transfer
  Matrix,  ///< B² × B² values: glossy transfer (transferred incident radiance)
};
const char* toString(TransferLayout layout);
/// Parses "vector" | "matrix"; throws prt::Error otherwise.
TransferLayout parseTransferLayout(const std::string& s);

/// Which functions the coefficients are of.
enum class TransferBasis {
  SphericalHarmonics,  ///< B² real SH, bands 0..B−1 (the default)
  Haar,                ///< 2D Haar wavelets over a cube map's faces, pruned per row
};
const char* toString(TransferBasis basis);  ///< "sh", "haar"
/// Parses "sh" | "haar"; throws prt::Error otherwise.
TransferBasis parseTransferBasis(const std::string& s);

/// What the rows index.
enum class TransferDomain {
  Vertices,  ///< one row per mesh vertex, interpolated across triangles
  /// One row per texel of a lightmap (TransferShape::lightmap), texel (x, y) row y·W + x, over
  /// the mesh's lightmap UVs (Mesh::lightmapUvs; transport/bake_texels.hpp), fetched bilinearly.
  Texels,
  /// One row per probe of a grid in space (TransferShape::probes; probe_grid.hpp): the matrix
  /// of the light arriving there from every direction, interpolated trilinearly.
  Probes,
};
const char* toString(TransferDomain domain);  ///< "vertices", "texels", "probes" (plural)
/// One row of a domain in messages: "vertex", "texel", "probe".
const char* rowName(TransferDomain domain);
/// Parses "vertices" | "texels" | "probes"; throws prt::Error otherwise.
TransferDomain parseTransferDomain(const std::string& s);

/// Rows [first, first + count) of a domain.
struct RowRange {
  std::size_t first = 0;
  std::size_t count = 0;
  std::size_t end() const { return first + count; }
  bool operator==(const RowRange&) const = default;
};

struct TransferShape {
  TransferDomain domain = TransferDomain::Vertices;
  TransferLayout layout = TransferLayout::Vector;
  int bands = 0;
  int channels = 1;  ///< 1 (scalar) or 3 (RGB)
  RowRange rows;     ///< which rows of the domain the transfer holds
  /// Texels: the lightmap's width and height (the domain has width · height rows) and the rings
  /// of texels around the charts that hold their covered neighbours' values (dilation: what a
  /// bilinear fetch at a chart's edge reads); texels beyond them hold zeros. seamsFixed: the
  /// least-squares seam fix (transport/lightmap_seam_fix.hpp) has been applied.
  struct LightmapSize {
    int width = 0, height = 0;
    int padding = 0;
    bool seamsFixed = false;
    bool denoised = false;  ///< transport/denoise_texels.hpp's filter was applied
    std::size_t texels() const { return static_cast<std::size_t>(width) * height; }
    bool operator==(const LightmapSize&) const = default;
  };
  LightmapSize lightmap{};
  TransferBasis basis = TransferBasis::SphericalHarmonics;
  /// Haar: the cube's resolution N (a power of two, haar/resolution.hpp), the coefficients
  /// kept per row (1 ≤ terms ≤ 6 N²) and the SH bands of the bounce each row holds after them
  /// (0: none, the direct transfer alone; inter-reflected: 1..haar::kUnshadowedBands).
  struct HaarSize {
    int resolution = 0;
    int terms = 0;
    int bounceBands = 0;
    bool operator==(const HaarSize&) const = default;
  };
  HaarSize haar{};
  /// Probes: the grid the rows are the probes of.
  ProbeGrid probes{};
  /// Rows of the whole domain: the lightmap's texels, the grid's probes, or `vertices` (the
  /// mesh's, which the shape does not hold).
  std::size_t domainRows(std::size_t vertices) const {
    return domain == TransferDomain::Texels   ? lightmap.texels()
           : domain == TransferDomain::Probes ? probes.probes()
                                              : vertices;
  }

  bool isHaar() const { return basis == TransferBasis::Haar; }
  /// Coefficients of the basis: B² (SH) or 6 N² (Haar).
  int coeffs() const;
  bool isMatrix() const { return layout == TransferLayout::Matrix; }
  /// Values per row per channel: B² (vector), B⁴ (matrix); Haar: all of a row, 1 + 2 · terms
  /// and the bounce's bounceBands² · channels.
  std::size_t rowSize() const;
  /// Floats per row, all channels.
  std::size_t stride() const {
    return isHaar() ? rowSize() : rowSize() * static_cast<std::size_t>(channels);
  }
  /// Haar: the floats of a row before its bounce (haar::haarRowFloats(terms)), and the bounce's
  /// bounceBands² · channels after them.
  std::size_t haarBounceOffset() const;
  std::size_t haarBounceFloats() const;
  std::size_t rowCount() const { return rows.count; }
  /// Bytes of the dense rows (4 · rows · stride); saturates at SIZE_MAX instead of overflowing.
  std::size_t denseBytes() const;
  /// The same shape with b bands.
  TransferShape withBands(int b) const;
  /// Throws prt::Error("WHAT: ...") unless bands are in 1..bands::kMaxLibrary (SH; Haar: 0, a
  /// valid resolution and terms, vector rows over vertices or texels) and channels 1|3.
  void check(const std::string& what) const;
  /// "interreflected"-free description: "matrix, 5 bands, RGB, 34,835 vertices"; Haar: "vector,
  /// Haar 32² cube, 64 terms, scalar, 34,835 vertices".
  std::string describe() const;
  bool operator==(const TransferShape&) const = default;
};

}  // namespace prt
