#include "renderer.hpp"

#include <epoxy/gl.h>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "gl_uploads.hpp"
#include "prt/core/error.hpp"

// One frame, in the passes renderer.hpp lists: (1) the background (a) and the relit mesh (b)
// into the multisampled HDR framebuffer, (2) its resolve, (3) the tone map into the target.

namespace prt::viewer {

namespace {

GLint loc(GLuint program, const char* name) {
  return glGetUniformLocation(program, name);
}

void uniform3(GLuint program, const char* name, const Vec3f& v) {
  glUniform3f(loc(program, name), v.x, v.y, v.z);
}

}  // namespace

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

}  // namespace prt::viewer
