#pragma once
// The shader-ready form of a transfer: what a GPU viewer uploads once per transfer, what it
// uploads per frame, and which shader draws it — one dispatch shared by prt view (texture
// buffers) and, in JS, by the web page (2D float textures of the same texel order; web/src).
// The CPU work of a frame is here too (rotating and packing the light, projecting clusters), so
// bench/viewer_frame.cpp measures exactly what a viewer runs, without the GL stack.
//
// Paths (shaderPath picks one from the transfer's layout and representation):
//
//   DenseVector   per row, once: the coefficients — scalar: ⌈B²/4⌉ RGBA32F texels, four
//                 coefficients each, zero-padded; RGB: B² texels (r, g, b, 0). Per frame: the
//                 rotated light (LightPacker). Shader: R = albedo ⊙ Σ_{i<b²} T_i L'_i.
//   DenseMatrix   (scalar matrices, ≤ kMaxShaderGlossy bands, prt view --glossy-on gpu) per row,
//                 once: B² matrix rows of ⌈B²/4⌉ texels each. Per frame: the light and the
//                 material kernels (shaderKernel). Shader: the glossy response of relight.hpp.
//   CpcaVector    per row, once: T = ⌈(N+1)/4⌉ texels, slot 0 the cluster id as a float (exact:
//                 ids are below 2²⁴, checked), slot 1 + j the weight w_j, the rest 0 (16·T bytes
//                 against 16·⌈B²/4⌉ dense). Per frame: the cluster table (below).
//   CpcaMatrix    the same per row; per frame the cluster table of B² values per cluster vector
//                 and the material kernels.
//   CpuRadiance   dense matrices relit on the CPU (relight::Relighter): nothing per row; per
//                 relit frame the exit radiance, 12 bytes per vertex.
//
// The cluster table (relight::projectClusters, cluster_projection.hpp) as texels (r, g, b, 0):
// texel (k·(N + 1) + j)·Q + i holds value i (Q = 1 for vectors, B² for matrices) of the
// cluster's mean (j = 0) or of basis vector j − 1 projected on the rotated light:
//   vectors   c_k = M_k·L, d_kj = B_kj·L                          K(N + 1) texels
//   matrices  L'_k0 = M_k L, L'_kj = B_kj L (B² RGB values each)  K(N + 1)·B² texels
// and a shader forms, with k = k(v) and w_j read from the row's texels,
//   vectors:   e(v) = albedo(v) ⊙ (c_k + Σ_j w_vj d_kj)
//   matrices:  L'_v,i = L'_k0,i + Σ_j w_vj L'_kj,i, then the glossy response
// (shaders/prt_compressed.glsl). evalPackedRow below is that sum on the CPU, the reference the
// packing is tested against (tests/relight).
//
// The light (std140 uniform block `Light { vec4 L[kMaxPackedCoeffs]; }`): coefficient i at
// floats 4i..4i+2 as (r, g, b), 4i+3 unused. Scalar rows are read four coefficients per texel
// fetch, so coefficients b² .. roundUp4(b²) − 1 are written as zeros: the padding of the rows
// then meets zero light. Rotating the first b bands of a B-band light equals cutting the rotated
// light to b bands (rotation is block-diagonal over bands), so only b bands are rotated, O(b³).
//
// Fewer bands than baked: the shaders loop over the first b² coefficients (vectors) or rows and
// columns (matrices) — the same numbers Transfer::cut(b) keeps.
//
// Per-texel transfer (TransferDomain::Texels: a W × H lightmap over the mesh's lightmap UVs) is
// packed exactly as per-vertex transfer, row by row — row y·W + x is texel (x, y), so the data
// texture is indexed by texel row — and drawn per pixel (ShaderRows::perPixel): the vertex stage
// passes the lightmap UV and the albedo (shaders/stages/lightmap.vert), the fragment stage takes
// the four texels of render::texelRadianceShader's bilinear fetch (geometry/texel_samples.hpp,
// bilinearTaps: centres at ((x + ½)/W, (y + ½)/H), clamped to the edge), relights each — dense
// T·L', or CPCA's c_k + Σ_j w_j d_kj from the same cluster table — and blends the four results
// with the bilinear weights (relighting is linear, so this is the fetch of the relit lightmap
// prt render makes), times the interpolated albedo (shaders/prt_lightmap.glsl). CPCA-compressed
// glossy matrices per texel (CpcaMatrix, desktop viewer) take the same four taps, each forming
// its received light L' from the cluster table and shading it with the glossy response at the
// texel's own sample point, normal and albedo (a second data texture, render::packTexelPoints;
// render::texelRelight, what prt render relights at), then blend: prt render's relit lightmap
// again. Dense matrices per texel (B⁴ floats a texel) are refused by name. The browser viewers
// shade the same way from the points prt web computes and ships beside its bake (they cannot
// trace the inside-geometry probe that places them); without them they refuse by name.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <span>
#include <string>
#include <vector>

#include "prt/core/band_limits.hpp"
#include "prt/core/error.hpp"
#include "prt/core/vec.hpp"
#include "prt/relight/cluster_projection.hpp"
#include "prt/sh/rotate.hpp"
#include "prt/sh/sh.hpp"
#include "prt/transfer/transfer.hpp"

namespace prt::relight {

enum class ShaderPath { DenseVector, DenseMatrix, CpcaVector, CpcaMatrix, CpuRadiance };
const char* toString(ShaderPath path);

/// The one dispatch of the GPU viewers: how `t` is drawn (matricesOnGpu: dense matrices in the
/// vertex shader instead of relit on the CPU; compressed matrices are always drawn on the GPU
/// when matricesOnGpu, else relit on the CPU). Per-texel vectors take the same paths, relit per
/// pixel (see the top). Throws prt::Error with one line when the path cannot draw it (bands past
/// the shaders' limits, RGB matrices in the vertex shader, matrices per texel).
ShaderPath shaderPath(const Transfer& t, bool matricesOnGpu);

/// Whether the transfer's rows are drawn per pixel (lightmap texels fetched at the mesh's
/// lightmap UVs) rather than per vertex: the one place the viewers ask the domain.
bool drawnPerPixel(const Transfer& t);

/// Why a dense per-texel matrix transfer is not drawn (shaderPath's refusal).
inline constexpr const char* kPerTexelMatricesRefusal =
    "per-texel glossy matrices are drawn CPCA-compressed (prt compress), relit per pixel; dense "
    "ones (B⁴ floats a texel) by prt render only";
/// Why the browser viewers refuse per-texel matrices they have no texel points for (the page's
/// and the three.js module's, generated): the points come from prt web, beside its own bake.
inline constexpr const char* kPageTexelMatricesRefusal =
    "per-texel glossy matrices are shaded at their texels' sample points, which prt web writes "
    "beside its own bake (write a page for this file with prt web; prt view draws it "
    "CPCA-compressed, prt render any)";

/// The per-row texels of a path (uploaded once).
struct ShaderRows {
  ShaderPath path = ShaderPath::DenseVector;
  int texelsPerRow = 0;     ///< T (0 for CpuRadiance)
  int basisCount = 0;       ///< N (compressed paths)
  int channels = 1;         ///< the transfer's (1 or 3)
  std::vector<float> rgba;  ///< rows × T × 4
  /// Per-texel transfer: the rows are lightmap texels (row y·W + x), relit per pixel from the
  /// mesh's lightmap UVs; else per-vertex rows relit per vertex.
  bool perPixel = false;
  TransferShape::LightmapSize lightmap{};  ///< perPixel: W × H
  /// Bytes one row uploads (16·T).
  std::size_t bytesPerRow() const { return 16 * static_cast<std::size_t>(texelsPerRow); }
};
/// The most clusters a compressed path draws: shaders read a cluster id as a float, exact up
/// to 2^24.
inline constexpr int kMaxShaderClusters = 1 << 24;
/// Texels per row of a path for a transfer.
int shaderTexelsPerRow(const Transfer& t, ShaderPath path);
/// Packs the rows for `path` (checked against the transfer as shaderPath does).
ShaderRows packShaderRows(const Transfer& t, ShaderPath path);
/// Exit radiance relit on the CPU per lightmap texel (a per-texel Haar bake,
/// relight/relight_haar.hpp), packed for the per-pixel dense path: a one-band RGB transfer
///     T_c = R_c / L'_00,c
/// against the drawn light's first coefficient `lightDc` (LightPacker::rotated()[0]), which no
/// turn changes (band 0 is rotation-invariant), so the stage's T·L' is R itself, blended over
/// prt render's four bilinear taps and times the albedo per pixel, exactly as prt render fetches
/// its relit lightmap. A channel whose L_00 is zero carries no light (a non-negative
/// environment's mean is zero only where it is black), so R is zero there and so is T. Draw
/// it at one band with radianceLightmapShape.
ShaderRows packRadianceLightmap(std::span<const Rgb> radiance,
                                const TransferShape::LightmapSize& lightmap, const Rgb& lightDc);
/// The shape packRadianceLightmap's rows are drawn with: per texel, one band, RGB, every texel.
TransferShape radianceLightmapShape(const TransferShape::LightmapSize& lightmap);

/// What the per-pixel stage computes at lightmap UV `uv` before albedo, on the CPU: the four
/// taps of bilinearTaps, each relit from the packed rows — dense against the packed light
/// (LightPacker::data(), `bands` shown), compressed from the cluster table — and blended. The
/// reference the per-pixel shaders follow (tests/relight).
Rgb evalPerPixel(const ShaderRows& rows, std::span<const float> light, int bands,
                 const std::vector<float>& table, Vec2f uv);

/// Texels of the per-frame cluster table of a compressed transfer: K(N + 1)·Q.
std::size_t clusterTableTexels(const Transfer& t);
/// Lays the per-frame projections out as (r, g, b, 0) texels into `rgba`, resized to
/// 4·K(N + 1)·Q floats; no allocation once it has that size.
void packClusterTable(const ClusterLight& projected, std::vector<float>& rgba);
/// The shader's sum at row r from the two packings: for vectors out[0] = c_k + Σ_j w_rj d_kj
/// (albedo not applied); for matrices out[i] = L'_r,i for i < Q. `coeffs` = Q.
void evalPackedRow(const ShaderRows& rows, const std::vector<float>& table, int coeffs,
                   std::size_t r, Rgb* out);

/// Largest band count a packed light holds (core/band_limits.hpp).
inline constexpr int kMaxPackedBands = bands::kMaxPackedLight;
inline constexpr int kMaxPackedCoeffs = kMaxPackedBands * kMaxPackedBands;

/// b² rounded up to a multiple of 4: the coefficients the shader reads at b bands.
constexpr int paddedCoeffs(int bands) {
  return (bands * bands + 3) / 4 * 4;
}

/// The per-frame light of a GPU viewer: rotated and packed (see the top). Header-only.
class LightPacker {
 public:
  LightPacker() : rotation_(1) {}

  /// The light to draw with (its bands: the most the viewer can use with it).
  void setLight(const sh::RgbSh& light) {
    PRT_CHECK(light.bands >= 1 && light.bands <= kMaxPackedBands, "light bands out of range");
    light_ = light;
  }
  const sh::RgbSh& light() const { return light_; }

  /// Rotates the first `bands` bands (1..light bands) by `r` and packs them; O(bands³), no
  /// allocation once the rotation has been built for this band count.
  void pack(const Mat3d& r, int bands) {
    PRT_CHECK(bands >= 1 && bands <= light_.bands, "bands out of range for the light");
    if (rotation_.bands() != bands)
      rotation_ = sh::Rotation(bands, r);
    else
      rotation_.set(r);
    rotation_.apply(light_.c.data(), rotated_.data());
    const int n = bands * bands, padded = paddedCoeffs(bands);
    for (int i = 0; i < n; ++i) {
      float* dst = data_.data() + 4 * i;
      dst[0] = rotated_[i].x, dst[1] = rotated_[i].y, dst[2] = rotated_[i].z, dst[3] = 0.0f;
    }
    std::fill(data_.begin() + 4 * n, data_.begin() + 4 * padded, 0.0f);
    bands_ = bands;
  }

  int bands() const { return bands_; }
  /// The packed block: 4 · paddedCoeffs(bands) floats.
  const float* data() const { return data_.data(); }
  std::size_t bytes() const { return sizeof(float) * 4 * std::size_t(paddedCoeffs(bands_)); }
  /// The rotated coefficients after the last pack: bands² of them.
  std::span<const Rgb> rotated() const {
    return {rotated_.data(), static_cast<std::size_t>(bands_ * bands_)};
  }

 private:
  sh::RgbSh light_;
  sh::Rotation rotation_;
  int bands_ = 0;
  std::array<Rgb, kMaxPackedCoeffs> rotated_{};
  alignas(16) std::array<float, 4 * kMaxPackedCoeffs> data_{};
};

/// The glossy kernels as the shaders take them: shaders/prt_sh_basis.glsl evaluates the real SH
/// basis without its normalisation N_lm (the associated-Legendre recurrence times (x + iy)^m),
/// so the per-coefficient kernels of PreparedMaterial (A_l/π, Λ_l) are handed over multiplied by
/// it (sh::normalization): diffuse_i = (A_l/π)·N_lm, glossy_i = Λ_l·N_lm for the first 64
/// coefficients (zero past the kernel's size).
std::array<float, 64> shaderKernel(std::span<const float> perCoefficient);

}  // namespace prt::relight
