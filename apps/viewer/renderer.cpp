#include "renderer.hpp"

#include <epoxy/gl.h>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <string>

#include "prt/core/error.hpp"
#include "prt/relight/shader_transfer.hpp"
#include "prt_viewer_shaders.hpp"

namespace prt::viewer {

namespace {

/// Throws one line when a texture buffer of `texels` RGBA32F texels exceeds this OpenGL's limit.
void requireTextureBufferTexels(double texels, const char* what, const char* advice) {
  GLint maxTexels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
  if (texels > double(maxTexels))
    throw Error(
        fmt::format("{} needs {:.0f} texels, more than this OpenGL's texture buffer "
                    "limit of {} ({})",
                    what, texels, maxTexels, advice));
}

}  // namespace

namespace {

// ---- shaders ---------------------------------------------------------------------------------
// The stages live in shaders/stages/ (shared with the web page), flattened with the desktop's
// host interface shaders/hosts/gl33.glsl and embedded at configure time (cmake/Shaders.cmake).
// Each source gets the desktop's #version here and the sizes its arrays take from the C++
// limits: the light block's kMaxPackedCoeffs vec4s, the glossy kernels' kMaxShaderGlossy².

std::string glsl330(const char* body, const char* defines = "") {
  return fmt::format(
      "#version 330 core\n#define PRT_LIGHT_VEC4S {}\n#define PRT_GLOSSY_COEFFS {}\n{}{}",
      kMaxViewerCoeffs, bands::kMaxShaderGlossy * bands::kMaxShaderGlossy, defines, body);
}

GLuint compile(GLenum type, const std::string& source, const char* name) {
  const GLuint s = glCreateShader(type);
  const char* src = source.c_str();
  glShaderSource(s, 1, &src, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    std::string line(log);
    std::replace(line.begin(), line.end(), '\n', ' ');
    glDeleteShader(s);
    throw Error(fmt::format("viewer shader '{}' does not compile: {}", name, line));
  }
  return s;
}

GLuint link(const std::string& vs, const std::string& fs, const char* name) {
  const GLuint v = compile(GL_VERTEX_SHADER, vs, name), f = compile(GL_FRAGMENT_SHADER, fs, name);
  const GLuint p = glCreateProgram();
  glAttachShader(p, v);
  glAttachShader(p, f);
  glLinkProgram(p);
  glDeleteShader(v);
  glDeleteShader(f);
  GLint ok = 0;
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetProgramInfoLog(p, sizeof log, nullptr, log);
    glDeleteProgram(p);
    throw Error(fmt::format("viewer shader '{}' does not link: {}", name, log));
  }
  return p;
}

GLint loc(GLuint program, const char* name) {
  return glGetUniformLocation(program, name);
}

void uniform3(GLuint program, const char* name, const Vec3f& v) {
  glUniform3f(loc(program, name), v.x, v.y, v.z);
}

/// An RGB32F lat-long texture: wraps in u (azimuth), clamps in v (poles), bilinear.
void uploadLatLong(GLuint& texture, const image::Image& img) {
  if (!texture) glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, img.width, img.height, 0, GL_RGB, GL_FLOAT,
               img.pixels.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

/// Reads the bound read framebuffer's colour attachment into a top-row-first image.
image::Image readPixels(int w, int h, GLenum type) {
  image::Image img;
  img.width = w, img.height = h;
  img.pixels.resize(std::size_t(w) * h);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  if (type == GL_FLOAT) {
    std::vector<float> rows(std::size_t(w) * h * 3);
    glReadPixels(0, 0, w, h, GL_RGB, GL_FLOAT, rows.data());
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const float* p = &rows[(std::size_t(h - 1 - y) * w + x) * 3];
        img.pixels[std::size_t(y) * w + x] = {p[0], p[1], p[2]};
      }
  } else {
    std::vector<unsigned char> rows(std::size_t(w) * h * 3);
    glReadPixels(0, 0, w, h, GL_RGB, GL_UNSIGNED_BYTE, rows.data());
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const unsigned char* p = &rows[(std::size_t(h - 1 - y) * w + x) * 3];
        img.pixels[std::size_t(y) * w + x] = {p[0] / 255.0f, p[1] / 255.0f, p[2] / 255.0f};
      }
  }
  return img;
}

}  // namespace

// ---- OffscreenTarget ------------------------------------------------------------------------

OffscreenTarget::OffscreenTarget(int width, int height) : width_(width), height_(height) {
  glGenTextures(1, &colour_);
  glBindTexture(GL_TEXTURE_2D, colour_);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  glGenFramebuffers(1, &fbo_);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colour_, 0);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw Error(fmt::format("cannot create a {}x{} offscreen framebuffer", width, height));
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

OffscreenTarget::~OffscreenTarget() {
  glDeleteFramebuffers(1, &fbo_);
  glDeleteTextures(1, &colour_);
}

image::Image OffscreenTarget::readEncoded() const {
  return readFramebufferEncoded(fbo_, width_, height_);
}

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

namespace {

/// (Re)fills texture buffer `texture` over `buffer` with RGBA32F texels.
void uploadTextureBuffer(GLuint& buffer, GLuint& texture, std::span<const float> rgba,
                         GLenum usage) {
  if (!buffer) glGenBuffers(1, &buffer);
  glBindBuffer(GL_TEXTURE_BUFFER, buffer);
  // Orphan and refill: a previous frame may still be reading the old contents.
  glBufferData(GL_TEXTURE_BUFFER, GLsizeiptr(sizeof(float) * rgba.size()), rgba.data(), usage);
  if (!texture) glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_BUFFER, texture);
  glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, buffer);
  glBindBuffer(GL_TEXTURE_BUFFER, 0);
}

static_assert(sizeof(Vec3f) == 3 * sizeof(float) && sizeof(Rgb) == 3 * sizeof(float));

/// (Re)fills vertex buffer `buffer` with `count` 3-float values and points attribute `location`
/// of the bound vertex array at it.
void uploadVertexAttribute(GLuint& buffer, GLuint location, const void* data, std::size_t count,
                           GLenum usage) {
  if (!buffer) glGenBuffers(1, &buffer);
  glBindBuffer(GL_ARRAY_BUFFER, buffer);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(sizeof(float) * 3 * count), data, usage);
  glVertexAttribPointer(location, 3, GL_FLOAT, GL_FALSE, sizeof(float) * 3, nullptr);
  glEnableVertexAttribArray(location);
}

static_assert(sizeof(Vec2f) == 2 * sizeof(float));

}  // namespace

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

void Renderer::resize(int w, int h) {
  if (w == fbWidth_ && h == fbHeight_) return;
  if (!msFbo_) {
    glGenFramebuffers(1, &msFbo_);
    glGenFramebuffers(1, &resolveFbo_);
    glGenTextures(1, &msColour_);
    glGenTextures(1, &resolveColour_);
    glGenRenderbuffers(1, &msDepth_);
  }
  GLint maxSamples = 1;
  glGetIntegerv(GL_MAX_SAMPLES, &maxSamples);
  const int samples = std::min(4, int(maxSamples));
  glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, msColour_);
  glTexImage2DMultisample(GL_TEXTURE_2D_MULTISAMPLE, samples, GL_RGBA32F, w, h, GL_TRUE);
  glBindRenderbuffer(GL_RENDERBUFFER, msDepth_);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH_COMPONENT24, w, h);
  glBindFramebuffer(GL_FRAMEBUFFER, msFbo_);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D_MULTISAMPLE, msColour_,
                         0);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, msDepth_);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw Error(fmt::format("cannot create a {}x{} multisampled float framebuffer", w, h));
  glBindTexture(GL_TEXTURE_2D, resolveColour_);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, w, h, 0, GL_RGBA, GL_FLOAT, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, resolveFbo_);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, resolveColour_, 0);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw Error(fmt::format("cannot create a {}x{} float framebuffer", w, h));
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  fbWidth_ = w, fbHeight_ = h;
}

void Renderer::setGlossyUniforms(unsigned p, const Vec3f& eye) const {
  glUniform1fv(loc(p, "uDiffuse"), GLsizei(glossyDiffuse_.size()), glossyDiffuse_.data());
  glUniform1fv(loc(p, "uGlossy"), GLsizei(glossyLobe_.size()), glossyLobe_.data());
  const Rgb kd = glossyKd_.value_or(Rgb(1.0f));
  glUniform3f(loc(p, "uKd"), kd.x, kd.y, kd.z);
  glUniform1i(loc(p, "uHasKd"), glossyKd_.has_value());
  glUniform3f(loc(p, "uKs"), glossyKs_.x, glossyKs_.y, glossyKs_.z);
  uniform3(p, "uEye", eye);
}

void Renderer::draw(const FrameParams& f, unsigned target) {
  PRT_CHECK(f.light != nullptr, "FrameParams.light is null");
  const int w = f.width, h = f.height;
  resize(w, h);

  // The library's camera frame and matrices (render/camera.hpp), as RayGenerator uses them.
  const render::Camera& c = f.camera;
  const render::CameraBasis basis = render::cameraBasis(c, w, h);
  // Clip planes around the bounding sphere: depth d of its centre, everything within d ± r.
  const float d = dot(centre_ - c.eye, basis.forward);
  const float farZ = std::max(d + 1.01f * radius_, 1e-3f * radius_);
  const float nearZ = std::max(d - 1.01f * radius_, 1e-4f * farZ);
  const render::Mat4f viewProj =
      render::multiply(render::projectionMatrix(c, w, h, nearZ, farZ), render::viewMatrix(c));

  glBindFramebuffer(GL_FRAMEBUFFER, msFbo_);
  glViewport(0, 0, w, h);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  if (f.background != BackgroundMode::None) drawBackground(f, basis);  // (a)
  drawMesh(f, viewProj.data());                                        // (b)
  toneMap(f, target);                                                  // (2), (3)
}

/// (a) What rays that miss show: the environment (or its SH reconstruction), turned as the light.
void Renderer::drawBackground(const FrameParams& f, const render::CameraBasis& basis) {
  const int w = f.width, h = f.height;
  const Vec3f &forward = basis.forward, &right = basis.right, &up = basis.up;
  const float tanX = basis.tanX, tanY = basis.tanY;
  glUseProgram(backgroundProgram_);
  glUniform2f(loc(backgroundProgram_, "uViewport"), float(w), float(h));
  uniform3(backgroundProgram_, "uForward", forward);
  uniform3(backgroundProgram_, "uRightTan", right * tanX);
  uniform3(backgroundProgram_, "uUpTan", up * tanY);
  // GLSL mat3 is column-major: uploading R's rows as columns gives Rᵀ.
  float rt[9];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) rt[3 * i + j] = float(f.lightRotation.m[i][j]);
  glUniformMatrix3fv(loc(backgroundProgram_, "uRotationT"), 1, GL_FALSE, rt);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, f.background == BackgroundMode::Env ? envTexture_ : shTexture_);
  glUniform1i(loc(backgroundProgram_, "uLatLong"), 0);
  glBindVertexArray(emptyVao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

/// (b) The relit mesh, by the transfer's shader path; viewProj column-major, for GL.
void Renderer::drawMesh(const FrameParams& f, const float* viewProj) {
  const render::Camera& c = f.camera;
  // The light block, timed (the per-frame upload the stats report), and a mesh program's state.
  const auto uploadLight = [&] {
    const auto t0 = std::chrono::steady_clock::now();
    glBindBuffer(GL_UNIFORM_BUFFER, lightUbo_);
    glBufferSubData(GL_UNIFORM_BUFFER, 0, GLsizeiptr(f.light->bytes()), f.light->data());
    glBindBufferBase(GL_UNIFORM_BUFFER, 0, lightUbo_);
    uploadSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  const auto beginMesh = [&](GLuint program) {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glUseProgram(program);
    glUniformMatrix4fv(loc(program, "uViewProj"), 1, GL_FALSE, viewProj);
    glActiveTexture(GL_TEXTURE4);
    glBindTexture(GL_TEXTURE_2D, baseColourTexture_);
    glUniform1i(loc(program, "uBaseColour"), 4);
    glUniform1i(loc(program, "uBaseColourOn"), f.baseColour);
  };
  using relight::ShaderPath;
  const int b = std::min(f.bands, transferBands_);
  const bool drawable =
      triangles_ > 0 && hasTransfer_ && (path_ != ShaderPath::CpuRadiance || hasRadiance_);
  if (drawable) {
    // The program of the path and its per-vertex texels; then what the path needs per frame.
    const GLuint p = perPixel_ ? (path_ == ShaderPath::CpcaVector   ? lightmapCompressedProgram_
                                  : path_ == ShaderPath::CpcaMatrix ? lightmapGlossyProgram_
                                                                    : lightmapProgram_)
                     : path_ == ShaderPath::DenseMatrix ? glossyProgram_
                     : path_ == ShaderPath::CpcaVector  ? compressedProgram_
                     : path_ == ShaderPath::CpcaMatrix  ? compressedGlossyProgram_
                     : path_ == ShaderPath::CpuRadiance ? radianceProgram_
                                                        : meshProgram_;
    const bool compressed = path_ == ShaderPath::CpcaVector || path_ == ShaderPath::CpcaMatrix;
    if (compressed) {
      PRT_CHECK(!f.clusterTable.empty(), "compressed transfer needs FrameParams.clusterTable");
      const auto t0 = std::chrono::steady_clock::now();
      uploadTextureBuffer(clusterBuffer_, clusterTexture_, f.clusterTable, GL_STREAM_DRAW);
      clusterTableBytes_ = sizeof(float) * f.clusterTable.size();
      uploadSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    } else {
      uploadLight();
    }
    beginMesh(p);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_BUFFER, transferTexture_);
    if (perPixel_) {
      // Per-texel rows, relit per pixel at the lightmap UV (prt_lightmap.glsl).
      glUniform1i(loc(p, "uRows"), 1);
      glUniform2i(loc(p, "uLightmapSize"), lightmap_.width, lightmap_.height);
      glUniform1i(loc(p, "uTexelsPerRow"), texelsPerRow_);
      if (path_ == ShaderPath::CpcaVector || path_ == ShaderPath::CpcaMatrix) {
        glActiveTexture(GL_TEXTURE2);
        glBindTexture(GL_TEXTURE_BUFFER, clusterTexture_);
        glUniform1i(loc(p, "uClusters"), 2);
        glUniform1i(loc(p, "uBasisCount"), basisCount_);
        if (path_ == ShaderPath::CpcaMatrix) {
          // Glossy per pixel: the texels' points, and the table of b² values per vector.
          PRT_CHECK(hasTexelPoints_, "per-texel matrices need setTexelPoints");
          glActiveTexture(GL_TEXTURE3);
          glBindTexture(GL_TEXTURE_BUFFER, pointsTexture_);
          glUniform1i(loc(p, "uPoints"), 3);
          glUniform1i(loc(p, "uBands"), std::min(b, bands::kMaxShaderGlossy));
          glUniform1i(loc(p, "uCoeffs"), b * b);
          setGlossyUniforms(p, c.eye);
        }
      } else {
        glUniform1i(loc(p, "uRgb"), transferChannels_ == 3);
        glUniform1i(loc(p, "uCount"), transferChannels_ == 3 ? b * b : paddedCoeffs(b) / 4);
      }
    } else
      switch (path_) {
        case ShaderPath::DenseVector:
          glUniform1i(loc(p, "uTransfer"), 1);
          glUniform1i(loc(p, "uTexelsPerVertex"), texelsPerRow_);
          glUniform1i(loc(p, "uRgb"), transferChannels_ == 3);
          glUniform1i(loc(p, "uCount"), transferChannels_ == 3 ? b * b : paddedCoeffs(b) / 4);
          break;
        case ShaderPath::CpuRadiance:  // the radiance attribute, made on the CPU
          break;
        case ShaderPath::DenseMatrix:
          glUniform1i(loc(p, "uTransfer"), 1);
          glUniform1i(loc(p, "uBands"), std::min(b, bands::kMaxShaderGlossy));
          glUniform1i(loc(p, "uRowTexels"), texelsPerRow_ / (transferBands_ * transferBands_));
          glUniform1i(loc(p, "uVertexTexels"), texelsPerRow_);
          setGlossyUniforms(p, c.eye);
          break;
        case ShaderPath::CpcaVector:
        case ShaderPath::CpcaMatrix:
          glUniform1i(loc(p, "uWeights"), 1);
          glActiveTexture(GL_TEXTURE2);
          glBindTexture(GL_TEXTURE_BUFFER, clusterTexture_);
          glUniform1i(loc(p, "uClusters"), 2);
          glUniform1i(loc(p, "uTexelsPerVertex"), texelsPerRow_);
          glUniform1i(loc(p, "uBasisCount"), basisCount_);
          if (path_ == ShaderPath::CpcaMatrix) {
            // The table was projected from the transfer cut to the shown bands: b² values per
            // cluster vector.
            glUniform1i(loc(p, "uBands"), std::min(b, bands::kMaxShaderGlossy));
            glUniform1i(loc(p, "uCoeffs"), b * b);
            setGlossyUniforms(p, c.eye);
          }
          break;
      }
    glBindVertexArray(vao_);
    glDrawElements(GL_TRIANGLES, GLsizei(3 * triangles_), GL_UNSIGNED_INT, nullptr);
    glDisable(GL_DEPTH_TEST);
    glActiveTexture(GL_TEXTURE0);
  }
}

/// (2) Resolves the multisampled HDR frame, (3) tone maps it into `target`.
void Renderer::toneMap(const FrameParams& f, unsigned target) {
  const int w = f.width, h = f.height;
  glBindFramebuffer(GL_READ_FRAMEBUFFER, msFbo_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolveFbo_);
  glBlitFramebuffer(0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, target);
  glViewport(0, 0, w, h);
  glUseProgram(toneProgram_);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, resolveColour_);
  glUniform1i(loc(toneProgram_, "uHdr"), 0);
  glUniform1f(loc(toneProgram_, "uScale"), std::exp2(f.exposureStops));
  // The shader's op is the enum's value (prt_display.glsl; the page's from web constants).
  glUniform1i(loc(toneProgram_, "uToneMap"), static_cast<int>(f.toneMap));
  glBindVertexArray(emptyVao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glUseProgram(0);
}

image::Image readFramebufferEncoded(unsigned fbo, int width, int height) {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
  if (fbo == 0) glReadBuffer(GL_BACK);
  image::Image img = readPixels(width, height, GL_UNSIGNED_BYTE);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  return img;
}

image::Image Renderer::readLinear() const {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, resolveFbo_);
  image::Image img = readPixels(fbWidth_, fbHeight_, GL_FLOAT);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  return img;
}

}  // namespace prt::viewer
