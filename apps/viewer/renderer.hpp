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
//        CPU (SceneView, relight::Relighter) in a vertex buffer the shader passes through.
//  2. The samples are resolved (box filter, like render's stratified spp average).
//  3. A full-screen pass applies exposure 2^stops, the tone map and the sRGB encode
//     (image::toneMap, image::linearToSrgb: the same formulas in GLSL) into the target.
//
// The transfer arrives through one upload path, setTransfer(relight::ShaderRows): the library
// packs it for the path that draws it (relight/shader_transfer.hpp has every layout) and the
// renderer puts the texels in a texture buffer and picks the program:
//   DenseVector  mesh.vert              per-vertex coefficients against the light block
//   DenseMatrix  glossy.vert            per-vertex matrices (--glossy-on gpu)
//   CpcaVector   compressed.vert        ids + weights, the per-frame cluster table
//   CpcaMatrix   compressedGlossy.vert  ids + weights, the cluster table of B² values
//   CpuRadiance  mesh.vert (uDirect)    exit radiance relit on the CPU (setRadiance)
// Per-texel transfer (rows.perPixel; dense or CPCA vectors) draws lightmap.vert, which passes
// the lightmap UV (location 4) and albedo, and mesh.frag compiled with PRT_LIGHTMAP (and
// PRT_LIGHTMAP_CPCA), which relights the four texels of prt render's bilinear fetch per pixel
// (shaders/prt_lightmap.glsl).
// Truncating to b < B bands only shortens the shaders' loops: nothing is re-uploaded.
//
// Sources: renderer.cpp (programs and uploads), renderer_draw.cpp (the frame),
// framebuffer_readback.cpp (readLinear), over gl_uploads and shader_programs.

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

// OffscreenTarget and readFramebufferEncoded, which the renderer's users read frames back with.
#include "framebuffer_readback.hpp"
#include "prt/core/band_limits.hpp"
#include "prt/core/vec.hpp"
#include "prt/geometry/mesh.hpp"
#include "prt/image/color.hpp"
#include "prt/image/image.hpp"
#include "prt/relight/shader_transfer.hpp"
#include "prt/render/camera.hpp"
#include "prt/transfer/transfer.hpp"

namespace prt::viewer {

// The light packing lives in the library (prt/relight/shader_transfer.hpp); the viewer's names.
using relight::LightPacker;
using relight::paddedCoeffs;
inline constexpr int kMaxViewerBands = bands::kMaxPackedLight;
inline constexpr int kMaxViewerCoeffs = relight::kMaxPackedCoeffs;

enum class BackgroundMode { Env, Sh, None };

struct FrameParams {
  render::Camera camera;
  int width = 640, height = 480;
  Mat3d lightRotation = Mat3d::identity();  ///< R: the environment as drawn behind the mesh
  const LightPacker* light = nullptr;       ///< packed D(R) L at the bands to draw with
  int bands = 0;                            ///< the bands shown (≤ the light's and transfer's)
  /// Compressed transfer only: this frame's cluster projections of D(R) L as RGBA texels
  /// (relight::packClusterTable) at the shown bands, uploaded by draw.
  std::span<const float> clusterTable;
  BackgroundMode background = BackgroundMode::Env;
  /// The mesh's base-colour texture multiplies the diffuse part per pixel
  /// (render::pixelTexture: the mesh has one and the material sets no kd).
  bool baseColour = false;
  float exposureStops = 0.0f;
  image::ToneMap toneMap = image::ToneMap::Aces;
};

class Renderer {
 public:
  /// Compiles the shaders; needs a current OpenGL 3.3 core context. Throws prt::Error.
  Renderer();
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Uploads positions, albedo (white when the mesh has none), triangles, and the base-colour
  /// texture with its UVs (white and constant without one).
  void setMesh(const Mesh& mesh);
  /// The one upload path: the per-vertex texels of a transfer packed for `rows.path`
  /// (relight::packShaderRows) over `shape` (bands, channels); `clusters` and `basisCount` for
  /// the compressed paths. CpuRadiance uploads nothing: each relit frame comes by setRadiance.
  /// Throws prt::Error when the texels exceed the driver's texture-buffer limit.
  void setTransfer(const relight::ShaderRows& rows, const TransferShape& shape, int clusters = 0,
                   int basisCount = 0);
  /// Uploads exit radiance, one value per mesh vertex (albedo already applied): what the
  /// CpuRadiance path draws. Under a base-colour texture `radiance` is the part it multiplies
  /// and `lobe` the glossy part added after (render::splitForTexture; empty: none).
  void setRadiance(std::span<const Rgb> radiance, std::span<const Rgb> lobe = {});
  /// Per-texel glossy matrices (CpcaMatrix per pixel): the texels' sample points, normals and
  /// albedo (render::packTexelPoints, three RGBA texels per lightmap texel), uploaded once.
  void setTexelPoints(std::span<const float> texels);
  /// The material for the glossy programs: per-coefficient kernels (A_l/π and Λ_l, as
  /// PreparedMaterial, at least b² of them), kd (unset: the mesh's albedo) and ks.
  void setGlossyMaterial(std::span<const float> diffuse, std::span<const float> glossy,
                         std::optional<Rgb> kd, Rgb ks);
  /// How the transfer uploaded is drawn.
  relight::ShaderPath path() const { return path_; }
  /// Bytes per vertex the transfer uploaded once (16 per texel).
  std::size_t bytesPerVertex() const { return 16 * std::size_t(texelsPerRow_); }
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
  void drawBackground(const FrameParams& f, const render::CameraBasis& basis);
  void drawMesh(const FrameParams& f, const float* viewProj);
  void toneMap(const FrameParams& f, unsigned target);

  unsigned meshProgram_ = 0, backgroundProgram_ = 0, toneProgram_ = 0, glossyProgram_ = 0;
  unsigned compressedProgram_ = 0, compressedGlossyProgram_ = 0, radianceProgram_ = 0;
  unsigned lightmapProgram_ = 0, lightmapCompressedProgram_ = 0, lightmapUvs_ = 0;
  unsigned clusterBuffer_ = 0, clusterTexture_ = 0;
  unsigned lightmapGlossyProgram_ = 0, pointsBuffer_ = 0, pointsTexture_ = 0;
  std::size_t clusterTableBytes_ = 0;
  unsigned vao_ = 0, emptyVao_ = 0, positions_ = 0, albedo_ = 0, indices_ = 0, normals_ = 0;
  unsigned transferBuffer_ = 0, transferTexture_ = 0, lightUbo_ = 0, radiance_ = 0;
  unsigned envTexture_ = 0, shTexture_ = 0;
  unsigned baseColourTexture_ = 0, baseUvs_ = 0, lobe_ = 0;
  unsigned msFbo_ = 0, msColour_ = 0, msDepth_ = 0, resolveFbo_ = 0, resolveColour_ = 0;
  int fbWidth_ = 0, fbHeight_ = 0;
  bool hasAlbedo_ = false, hasTransfer_ = false, hasRadiance_ = false, hasLightmapUvs_ = false;
  bool perPixel_ = false;  ///< per-texel rows, relit per pixel
  bool hasTexelPoints_ = false;
  TransferShape::LightmapSize lightmap_{};
  relight::ShaderPath path_ = relight::ShaderPath::DenseVector;
  int texelsPerRow_ = 0, basisCount_ = 0;
  // Kernels × the SH normalisation, kMaxShaderGlossy² each (relight::shaderKernel).
  std::vector<float> glossyDiffuse_ =
                         std::vector<float>(bands::kMaxShaderGlossy * bands::kMaxShaderGlossy),
                     glossyLobe_ = glossyDiffuse_;
  std::optional<Rgb> glossyKd_;
  Rgb glossyKs_{0.0f};
  int transferBands_ = 0, transferChannels_ = 1;
  std::size_t triangles_ = 0, vertices_ = 0;
  Vec3f centre_{0.0f};
  float radius_ = 1.0f;
  double uploadSeconds_ = 0.0;
};

}  // namespace prt::viewer
