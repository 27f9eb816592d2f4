#pragma once
// The viewer's OpenGL renderer: the relit mesh over the environment, one frame in three passes.
//
//  1. Into a 4× multisampled RGBA32F framebuffer (linear, scene-referred radiance):
//     a. the background, a full-screen triangle whose fragment shader turns its pixel into the
//        camera ray d (the same mapping as render::RayGenerator) and looks up the lat-long image
//        of the environment, or of its SH reconstruction, at Rᵀ d (the environment rotated by R:
//        L'(ω) = L(Rᵀ ω), as render::environmentBackground);
//     b. the mesh, whose vertex shader relights each vertex (vertex v = gl_VertexID)
//          R(v) = albedo(v) ⊙ Σ_{i < b²} T_i(v) L'_i
//        from the transfer in a texture buffer and the rotated light L' = D(R) L in a uniform
//        block (LightPacker); the rasteriser interpolates R perspective-correctly across each
//        triangle — the barycentric interpolation prt render does on ray hits.
//        Glossy (matrix) transfer instead arrives as per-vertex exit radiance computed on the
//        CPU (SceneView, relight::relightGlossy) in a vertex buffer the shader passes through.
//  2. The samples are resolved (box filter, like render's stratified spp average).
//  3. A full-screen pass applies exposure 2^stops, the tone map and the sRGB encode
//     (image::toneMap, image::linearToSrgb: the same formulas in GLSL) into the target.
//
// Transfer layout in the texture buffer (GL_RGBA32F texels):
//   scalar: vertex v's B² coefficients zero-padded to P = roundUp4(B²), texels v·P/4 .. ;
//           the shader dots four coefficients per fetch with four light vec4s;
//   RGB:    one texel (r, g, b, 0) per coefficient, texels v·B² + i.
// Truncating to b < B bands only shortens the shader's loop: nothing is re-uploaded.
//
// CPCA-compressed transfer (prt compress) is relit in the compressed space, as Sloan et al. 2003
// do on the GPU: per vertex, a texture buffer holds the cluster id and N weights (16·⌈(N+1)/4⌉
// bytes, uploaded once); per frame, the CPU projects the rotated light onto every cluster's mean
// and basis (relight::projectClusters, K(N+1) dot products, or K(N+1) matrix-vector products of
// B² for glossy matrices) and uploads the table to a second texture buffer; the vertex shader
// sums c_k + Σ_j w_j d_kj (shaders/viewer/compressed.vert) or forms L'_v = L'_k0 + Σ_j w_j L'_kj
// and shades it as glossy.vert (compressedGlossy.vert). Layouts: prt/relight/cluster_table.hpp.

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "prt/compress/cpca.hpp"
#include "prt/core/vec.hpp"
#include "prt/geometry/mesh.hpp"
#include "prt/image/color.hpp"
#include "prt/image/image.hpp"
#include "prt/relight/glossy_shader.hpp"
#include "prt/relight/light_packer.hpp"
#include "prt/render/camera.hpp"
#include "prt/transfer/field.hpp"

namespace prt::viewer {

// The light packing lives in the library (prt/relight/light_packer.hpp); the viewer's names.
using relight::LightPacker;
using relight::paddedCoeffs;
inline constexpr int kMaxViewerBands = relight::kMaxPackedBands;
inline constexpr int kMaxViewerCoeffs = relight::kMaxPackedCoeffs;

enum class BackgroundMode { Env, Sh, None };

/// Bands the vertex-shader glossy path evaluates (its SH arrays hold 64 coefficients).
inline constexpr int kMaxGpuGlossyBands = relight::kMaxShaderGlossyBands;

struct FrameParams {
  render::Camera camera;
  int width = 640, height = 480;
  Mat3d lightRotation = Mat3d::identity();  ///< R: the environment as drawn behind the mesh
  const LightPacker* light = nullptr;       ///< packed D(R) L at the bands to draw with
  /// Compressed transfer only: this frame's cluster projections of D(R) L as RGBA texels
  /// (relight::packClusterTable), uploaded by draw.
  std::span<const float> clusterTable;
  BackgroundMode background = BackgroundMode::Env;
  float exposureStops = 0.0f;
  image::ToneMap toneMap = image::ToneMap::Aces;
};

/// Bytes per vertex the dense paths upload for a transfer of this shape: scalar vectors
/// 16·⌈B²/4⌉, RGB vectors 16·B², matrices in the vertex shader (--glossy-on gpu)
/// 16·B²·⌈B²/4⌉, matrices relit on the CPU 12 (the exit radiance, again on every relit frame).
std::size_t denseBytesPerVertex(const TransferField& shape, bool glossyOnGpu);

/// An RGBA8 colour framebuffer object for offscreen display output (headless mode).
class OffscreenTarget {
 public:
  OffscreenTarget(int width, int height);
  ~OffscreenTarget();
  OffscreenTarget(const OffscreenTarget&) = delete;
  OffscreenTarget& operator=(const OffscreenTarget&) = delete;
  unsigned fbo() const { return fbo_; }
  /// The tone-mapped sRGB pixels as an image of codes / 255 (top row first).
  image::Image readEncoded() const;

 private:
  int width_, height_;
  unsigned fbo_ = 0, colour_ = 0;
};

/// Reads an 8-bit framebuffer (0: the window's back buffer) as codes / 255, top row first.
image::Image readFramebufferEncoded(unsigned fbo, int width, int height);

class Renderer {
 public:
  /// Compiles the shaders; needs a current OpenGL 3.3 core context. Throws prt::Error.
  Renderer();
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Uploads positions, albedo (white when the mesh has none) and triangles.
  void setMesh(const Mesh& mesh);
  /// Uploads a transfer with one row per mesh vertex. Throws prt::Error when it does not fit
  /// the driver's texture-buffer limit or its bands exceed kMaxViewerBands.
  void setTransfer(const TransferField& transfer);
  /// Draws per-vertex radiance from setRadiance instead of relighting a transfer in the shader
  /// (glossy transfer, relit on the CPU); until the next setTransfer.
  void setDirectRadiance();
  /// Uploads exit radiance, one value per mesh vertex (albedo already applied).
  void setRadiance(std::span<const Rgb> radiance);
  /// The other glossy path (prt view --glossy-on gpu): uploads scalar transfer matrices (rows
  /// padded to a multiple of four) and relights them in the vertex shader (shaders/viewer/
  /// glossy.vert). Throws prt::Error for RGB matrices, more than kMaxGpuGlossyBands bands or a
  /// transfer over the texture-buffer limit.
  void setGlossyTransfer(const TransferField& transfer);
  /// The material for setGlossyTransfer's shader: per-coefficient kernels (A_l/π and Λ_l, as
  /// relight::PreparedMaterial, at least b² of them), kd (unset: the mesh's albedo) and ks.
  void setGlossyMaterial(std::span<const float> diffuse, std::span<const float> glossy,
                         std::optional<Rgb> kd, Rgb ks);
  /// Uploads CPCA-compressed transfer (one row per mesh vertex): the per-vertex cluster ids and
  /// weights (relight::packCompressedVertices). Vectors are relit by compressed.vert; matrices
  /// by compressedGlossy.vert with setGlossyMaterial's kernels. Each frame then needs
  /// FrameParams::clusterTable. Throws prt::Error for matrices of more than kMaxGpuGlossyBands
  /// bands or data over the texture-buffer limit.
  void setCompressedTransfer(const CompressedTransfer& transfer);
  /// True while the transfer drawn is compressed (setCompressedTransfer).
  bool compressed() const { return compressed_; }
  /// Bytes per vertex the compressed transfer uploaded (16·⌈(N+1)/4⌉), 0 when not compressed.
  std::size_t compressedBytesPerVertex() const { return compressed_ ? 16 * compressedTexels_ : 0; }
  /// Bytes of the last cluster table uploaded (the per-frame upload of compressed transfer).
  std::size_t clusterTableBytes() const { return clusterTableBytes_; }
  /// The lat-long images behind BackgroundMode::Env and ::Sh (linear RGB).
  void setEnvironmentImage(const image::Image& latLong);
  void setShImage(const image::Image& latLong);

  /// Draws one frame into framebuffer `target` (0: the window), viewport width × height.
  void draw(const FrameParams& frame, unsigned target);
  /// The last frame's resolved linear radiance (top row first).
  image::Image readLinear() const;

  /// Seconds the last draw spent uploading the light block, and for compressed transfer the
  /// cluster table (CPU side of the copies).
  double lastUploadSeconds() const { return uploadSeconds_; }
  std::size_t triangleCount() const { return triangles_; }

 private:
  void resize(int width, int height);

  /// Sets the glossy kernels, kd, ks and eye uniforms of a glossy program.
  void setGlossyUniforms(unsigned program, const Vec3f& eye) const;

  unsigned meshProgram_ = 0, backgroundProgram_ = 0, toneProgram_ = 0, glossyProgram_ = 0;
  unsigned compressedProgram_ = 0, compressedGlossyProgram_ = 0;
  unsigned weightsBuffer_ = 0, weightsTexture_ = 0, clusterBuffer_ = 0, clusterTexture_ = 0;
  bool compressed_ = false;
  int compressedBasis_ = 0, compressedCoeffs_ = 1;
  std::size_t compressedTexels_ = 0, clusterTableBytes_ = 0;
  unsigned vao_ = 0, emptyVao_ = 0, positions_ = 0, albedo_ = 0, indices_ = 0, normals_ = 0;
  unsigned transferBuffer_ = 0, transferTexture_ = 0, lightUbo_ = 0, radiance_ = 0;
  unsigned envTexture_ = 0, shTexture_ = 0;
  unsigned msFbo_ = 0, msColour_ = 0, msDepth_ = 0, resolveFbo_ = 0, resolveColour_ = 0;
  int fbWidth_ = 0, fbHeight_ = 0;
  bool hasAlbedo_ = false, direct_ = false, hasRadiance_ = false, glossyGpu_ = false;
  // Kernels × the SH normalisation, 64 each.
  std::vector<float> glossyDiffuse_ = std::vector<float>(64), glossyLobe_ = std::vector<float>(64);
  std::optional<Rgb> glossyKd_;
  Rgb glossyKs_{0.0f};
  int transferBands_ = 0, transferChannels_ = 1, transferStride_ = 0;
  std::size_t triangles_ = 0, vertices_ = 0;
  Vec3f centre_{0.0f};
  float radius_ = 1.0f;
  double uploadSeconds_ = 0.0;
};

}  // namespace prt::viewer
