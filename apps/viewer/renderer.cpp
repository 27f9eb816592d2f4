#include "renderer.hpp"

#include <epoxy/gl.h>

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <iterator>

#include "gl_uploads.hpp"
#include "prt/core/error.hpp"
#include "prt/relight/shader_transfer.hpp"
#include "prt_viewer_shaders.hpp"
#include "shader_programs.hpp"

// The renderer's programs and what it uploads (mesh, transfer, radiance, material, images);
// the frame it draws with them is in renderer_draw.cpp.

namespace prt::viewer {

// ---- Renderer -------------------------------------------------------------------------------

Renderer::Renderer() {
  using namespace prt::shaders;
  meshProgram_ = link(glsl330(kShaderMeshVert), glsl330(kShaderMeshFrag), "mesh");
  backgroundProgram_ =
      link(glsl330(kShaderFullscreenVert), glsl330(kShaderBackgroundFrag), "background");
  toneProgram_ = link(glsl330(kShaderFullscreenVert), glsl330(kShaderToneFrag), "tone map");
  glossyProgram_ = link(glsl330(kShaderGlossyVert), glsl330(kShaderMeshFrag), "glossy mesh");
  compressedProgram_ =
      link(glsl330(kShaderCompressedVert), glsl330(kShaderMeshFrag), "compressed mesh");
  compressedGlossyProgram_ = link(glsl330(kShaderCompressedGlossyVert), glsl330(kShaderMeshFrag),
                                  "compressed glossy mesh");
  radianceProgram_ = link(glsl330(kShaderRadianceVert), glsl330(kShaderMeshFrag), "radiance mesh");
  // Per-texel transfer: the lightmap UV through, relit per pixel (dense, or CPCA).
  lightmapProgram_ = link(glsl330(kShaderLightmapVert),
                          glsl330(kShaderMeshFrag, "#define PRT_LIGHTMAP 1\n"), "lightmap mesh");
  lightmapCompressedProgram_ =
      link(glsl330(kShaderLightmapVert),
           glsl330(kShaderMeshFrag, "#define PRT_LIGHTMAP 1\n#define PRT_LIGHTMAP_CPCA 1\n"),
           "compressed lightmap mesh");
  lightmapGlossyProgram_ = link(glsl330(kShaderLightmapVert),
                                glsl330(kShaderMeshFrag,
                                        "#define PRT_LIGHTMAP 1\n#define PRT_LIGHTMAP_CPCA 1\n"
                                        "#define PRT_LIGHTMAP_GLOSSY 1\n"),
                                "compressed glossy lightmap mesh");
  glUniformBlockBinding(meshProgram_, glGetUniformBlockIndex(meshProgram_, "Light"), 0);
  glUniformBlockBinding(lightmapProgram_, glGetUniformBlockIndex(lightmapProgram_, "Light"), 0);
  glUniformBlockBinding(glossyProgram_, glGetUniformBlockIndex(glossyProgram_, "Light"), 0);
  glGenVertexArrays(1, &vao_);
  glGenVertexArrays(1, &emptyVao_);
  glGenBuffers(1, &lightUbo_);
  glBindBuffer(GL_UNIFORM_BUFFER, lightUbo_);
  glBufferData(GL_UNIFORM_BUFFER, sizeof(float) * 4 * kMaxViewerCoeffs, nullptr, GL_DYNAMIC_DRAW);
  glBindBuffer(GL_UNIFORM_BUFFER, 0);
  // A black 1×1 image until the caller sets real ones.
  image::Image black;
  black.width = black.height = 1;
  black.pixels = {Rgb(0.0f)};
  setEnvironmentImage(black);
  setShImage(black);
}

Renderer::~Renderer() {
  const GLuint programs[] = {meshProgram_,          backgroundProgram_, toneProgram_,
                             glossyProgram_,        compressedProgram_, compressedGlossyProgram_,
                             radianceProgram_,      lightmapProgram_,   lightmapCompressedProgram_,
                             lightmapGlossyProgram_};
  for (GLuint p : programs) glDeleteProgram(p);
  const GLuint buffers[] = {positions_,   albedo_,       indices_, transferBuffer_,
                            lightUbo_,    radiance_,     normals_, clusterBuffer_,
                            lightmapUvs_, pointsBuffer_, baseUvs_, lobe_};
  glDeleteBuffers(GLsizei(std::size(buffers)), buffers);
  const GLuint textures[] = {transferTexture_, envTexture_,     shTexture_,     msColour_,
                             resolveColour_,   clusterTexture_, pointsTexture_, baseColourTexture_};
  glDeleteTextures(GLsizei(std::size(textures)), textures);
  glDeleteRenderbuffers(1, &msDepth_);
  const GLuint fbos[] = {msFbo_, resolveFbo_};
  glDeleteFramebuffers(2, fbos);
  const GLuint vaos[] = {vao_, emptyVao_};
  glDeleteVertexArrays(2, vaos);
}

static_assert(sizeof(Vec2f) == 2 * sizeof(float));

void Renderer::setMesh(const Mesh& mesh) {
  glBindVertexArray(vao_);
  uploadVertexAttribute(positions_, 0, mesh.positions.data(), mesh.positions.size(),
                        GL_STATIC_DRAW);
  hasAlbedo_ = mesh.albedo.size() == mesh.positions.size() && !mesh.albedo.empty();
  if (hasAlbedo_) {
    uploadVertexAttribute(albedo_, 1, mesh.albedo.data(), mesh.albedo.size(), GL_STATIC_DRAW);
  } else {
    // relight's rule: a single albedo applies to all vertices, none means white.
    const Rgb a = mesh.albedo.size() == 1 ? mesh.albedo[0] : Rgb(1.0f);
    glDisableVertexAttribArray(1);
    glVertexAttrib3f(1, a.x, a.y, a.z);
  }
  if (mesh.normals.size() == mesh.positions.size()) {
    uploadVertexAttribute(normals_, 3, mesh.normals.data(), mesh.normals.size(), GL_STATIC_DRAW);
  } else {
    glDisableVertexAttribArray(3);
    glVertexAttrib3f(3, 0.0f, 1.0f, 0.0f);
  }
  // The lightmap UVs per-texel transfer is fetched at (location 4, two floats).
  hasLightmapUvs_ = !mesh.lightmapUvs.empty() && mesh.lightmapUvs.size() == mesh.positions.size();
  if (hasLightmapUvs_) {
    if (!lightmapUvs_) glGenBuffers(1, &lightmapUvs_);
    glBindBuffer(GL_ARRAY_BUFFER, lightmapUvs_);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(sizeof(Vec2f) * mesh.lightmapUvs.size()),
                 mesh.lightmapUvs.data(), GL_STATIC_DRAW);
    glVertexAttribPointer(4, 2, GL_FLOAT, GL_FALSE, sizeof(Vec2f), nullptr);
    glEnableVertexAttribArray(4);
  } else {
    glDisableVertexAttribArray(4);
    glVertexAttrib2f(4, 0.0f, 0.0f);
  }
  // The base-colour texture (geometry/base_colour.hpp: sRGB codes decoded before bilinear
  // filtering, repeat wrapping, no mipmaps, row 0 at v = 0 — GL's t = 0) at the texture UVs
  // (location 5); without one a white texel, which uBaseColourOn leaves unread anyway.
  const bool textured = mesh.baseColour && !mesh.baseColour->image.empty() &&
                        mesh.uvs.size() == mesh.positions.size();
  if (!baseColourTexture_) glGenTextures(1, &baseColourTexture_);
  glBindTexture(GL_TEXTURE_2D, baseColourTexture_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  static const std::uint8_t kWhite[3] = {255, 255, 255};
  const image::Srgb8Image* tex = textured ? &mesh.baseColour->image : nullptr;
  glTexImage2D(GL_TEXTURE_2D, 0, GL_SRGB8, tex ? tex->width : 1, tex ? tex->height : 1, 0, GL_RGB,
               GL_UNSIGNED_BYTE, tex ? tex->rgb.data() : kWhite);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
  glBindTexture(GL_TEXTURE_2D, 0);
  if (textured) {
    if (!baseUvs_) glGenBuffers(1, &baseUvs_);
    glBindBuffer(GL_ARRAY_BUFFER, baseUvs_);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(sizeof(Vec2f) * mesh.uvs.size()), mesh.uvs.data(),
                 GL_STATIC_DRAW);
    glVertexAttribPointer(5, 2, GL_FLOAT, GL_FALSE, sizeof(Vec2f), nullptr);
    glEnableVertexAttribArray(5);
  } else {
    glDisableVertexAttribArray(5);
    glVertexAttrib2f(5, 0.0f, 0.0f);
  }
  glDisableVertexAttribArray(6);  // the CPU's lobe, until setRadiance gives one
  glVertexAttrib3f(6, 0.0f, 0.0f, 0.0f);
  if (!indices_) glGenBuffers(1, &indices_);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices_);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, sizeof(mesh.triangles[0]) * mesh.triangles.size(),
               mesh.triangles.data(), GL_STATIC_DRAW);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  triangles_ = mesh.triangleCount();
  vertices_ = mesh.vertexCount();
  hasRadiance_ = hasTransfer_ = false;  // the radiance and transfer were for another mesh
  const Bounds b = computeBounds(mesh);
  centre_ = b.centre();
  radius_ = std::max(b.radius(), 1e-6f);
}

void Renderer::setTransfer(const relight::ShaderRows& rows, const TransferShape& shape,
                           int clusters, int basisCount) {
  using relight::ShaderPath;
  const double texels = double(rows.texelsPerRow) * double(shape.rowCount());
  const bool compressed =
      rows.path == ShaderPath::CpcaVector || rows.path == ShaderPath::CpcaMatrix;
  if (rows.perPixel) {
    if (shape.rows.first != 0 || shape.rowCount() != rows.lightmap.texels())
      throw Error(fmt::format("the transfer has {} rows for a {} x {} lightmap", shape.rowCount(),
                              rows.lightmap.width, rows.lightmap.height));
    if (!hasLightmapUvs_) throw Error("per-texel transfer needs the mesh's lightmap UVs");
  } else if (shape.rowCount() != vertices_) {
    throw Error(
        fmt::format("the transfer has {} rows for {} vertices", shape.rowCount(), vertices_));
  }
  if (rows.path != ShaderPath::CpuRadiance) {
    requireTextureBufferTexels(texels,
                               compressed ? "the compressed transfer's weights" : "the transfer",
                               compressed ? "use fewer PCA vectors" : "use fewer bands");
    uploadTextureBuffer(transferBuffer_, transferTexture_, rows.rgba, GL_STATIC_DRAW);
  }
  if (compressed) {
    const double tableTexels = double(clusters) * (basisCount + 1) *
                               (rows.path == ShaderPath::CpcaMatrix ? double(shape.coeffs()) : 1.0);
    requireTextureBufferTexels(tableTexels, "the per-frame cluster table", "use fewer clusters");
  }
  path_ = rows.path;
  perPixel_ = rows.perPixel;
  lightmap_ = rows.lightmap;
  texelsPerRow_ = rows.texelsPerRow;
  basisCount_ = basisCount;
  transferBands_ = shape.bands;
  transferChannels_ = shape.channels;
  hasTransfer_ = true;
}

void Renderer::setTexelPoints(std::span<const float> texels) {
  requireTextureBufferTexels(double(texels.size() / 4), "the texels' points",
                             "use a smaller lightmap");
  uploadTextureBuffer(pointsBuffer_, pointsTexture_, texels, GL_STATIC_DRAW);
  hasTexelPoints_ = true;
}

void Renderer::setGlossyMaterial(std::span<const float> diffuse, std::span<const float> glossy,
                                 std::optional<Rgb> kd, Rgb ks) {
  // The SH normalisation N_lm the shader's basis leaves out (relight::shaderKernel).
  const auto d = relight::shaderKernel(diffuse), g = relight::shaderKernel(glossy);
  static_assert(d.size() == bands::kMaxShaderGlossy * bands::kMaxShaderGlossy);
  glossyDiffuse_.assign(d.begin(), d.end());
  glossyLobe_.assign(g.begin(), g.end());
  glossyKd_ = kd;
  glossyKs_ = ks;
}

void Renderer::setRadiance(std::span<const Rgb> radiance, std::span<const Rgb> lobe) {
  PRT_CHECK(radiance.size() == vertices_, "setRadiance needs one value per vertex");
  PRT_CHECK(lobe.empty() || lobe.size() == vertices_, "setRadiance: one lobe value per vertex");
  glBindVertexArray(vao_);
  // Orphan and refill: the previous frame may still be reading the old contents.
  uploadVertexAttribute(radiance_, 2, radiance.data(), radiance.size(), GL_STREAM_DRAW);
  if (!lobe.empty()) {
    uploadVertexAttribute(lobe_, 6, lobe.data(), lobe.size(), GL_STREAM_DRAW);
  } else {
    glDisableVertexAttribArray(6);
    glVertexAttrib3f(6, 0.0f, 0.0f, 0.0f);
  }
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  hasRadiance_ = true;
}

void Renderer::setEnvironmentImage(const image::Image& img) {
  uploadLatLong(envTexture_, img);
}
void Renderer::setShImage(const image::Image& img) {
  uploadLatLong(shTexture_, img);
}

}  // namespace prt::viewer
