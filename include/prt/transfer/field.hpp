#pragma once
// The transfer field: what a bake produces and what every relighting path consumes.
// (Sloan, Kautz & Snyder, "Precomputed Radiance Transfer for Real-Time Rendering in Dynamic,
// Low-Frequency Lighting Environments", SIGGRAPH 2002, §5 diffuse vectors, §6 glossy matrices.)
//
// A field is a table of one *row* per element of its domain (vertices now, texels later). What a
// row holds depends on the layout:
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
// interleaved innermost: entry e of row r, channel c is at data[(r·rowSize + e)·channels + c].
// For an RGB field the bounce albedos are folded in; the albedo at p itself is not (relighting
// applies it), for both channel counts.
//
// Memory: 4·B²·C bytes per vertex for vectors, 4·B⁴·C for matrices (9 bands, 1M vertices, RGB
// matrices: 79 GB); transferBytes() states it before anything is allocated.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace prt {

/// Which integral the transfer holds (the transport, independent of layout and material).
enum class TransferMode { Unshadowed, Shadowed, Interreflected };
const char* toString(TransferMode mode);
/// Parses "unshadowed" | "shadowed" | "interreflected"; throws prt::Error otherwise.
TransferMode parseTransferMode(const std::string& s);

/// What one row of the field holds.
enum class TransferLayout {
  Vector,  ///< B² values: diffuse transfer
  Matrix,  ///< B² × B² values: glossy transfer (transferred incident radiance)
};
const char* toString(TransferLayout layout);
/// Parses "vector" | "matrix"; throws prt::Error otherwise.
TransferLayout parseTransferLayout(const std::string& s);

/// What the rows index.
enum class TransferDomain {
  Vertices,  ///< one row per mesh vertex, interpolated across triangles
};
const char* toString(TransferDomain domain);

/// Values one row holds per channel for a layout and band count (B² or B⁴).
std::size_t transferRowSize(TransferLayout layout, int bands);
/// Bytes of a field of `rows` rows; saturates at SIZE_MAX instead of overflowing.
std::size_t transferBytes(TransferLayout layout, int bands, int channels, std::size_t rows);

struct TransferField {
  TransferLayout layout = TransferLayout::Vector;
  TransferDomain domain = TransferDomain::Vertices;
  int bands = 0;
  int channels = 1;             ///< 1 (scalar) or 3 (RGB)
  std::size_t vertexCount = 0;  ///< rows: elements of the domain
  std::vector<float> data;      ///< vertexCount × rowSize() × channels

  int coeffs() const { return bands * bands; }
  /// Values per row per channel: B² (vector) or B⁴ (matrix).
  std::size_t rowSize() const { return transferRowSize(layout, bands); }
  /// Floats per row, all channels.
  std::size_t stride() const { return rowSize() * static_cast<std::size_t>(channels); }
  float* vertex(std::size_t v) { return data.data() + v * stride(); }
  const float* vertex(std::size_t v) const { return data.data() + v * stride(); }
  bool isMatrix() const { return layout == TransferLayout::Matrix; }
  /// An empty field of the given shape with its data allocated (zeros).
  static TransferField zeros(TransferLayout layout, int bands, int channels, std::size_t rows);
  /// The first b bands of every row (a b-band bake equals the first b² coefficients; for
  /// matrices, the leading b² × b² block).
  TransferField truncated(int b) const;
  /// Throws prt::Error unless the sizes agree and every value is finite.
  void check(const std::string& what) const;
};

}  // namespace prt
