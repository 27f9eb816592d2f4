#pragma once
// The renderer's OpenGL uploads: texture buffers of RGBA32F texels (and the driver's limit on
// their size), 3-float vertex attributes and lat-long environment textures. Each call needs a
// current OpenGL 3.3 core context.

#include <epoxy/gl.h>

#include <cstddef>
#include <span>

#include "prt/image/image.hpp"

namespace prt::viewer {

/// Throws one line when a texture buffer of `texels` RGBA32F texels exceeds this OpenGL's limit.
void requireTextureBufferTexels(double texels, const char* what, const char* advice);

/// (Re)fills texture buffer `texture` over `buffer` with RGBA32F texels.
void uploadTextureBuffer(GLuint& buffer, GLuint& texture, std::span<const float> rgba,
                         GLenum usage);

/// (Re)fills vertex buffer `buffer` with `count` 3-float values and points attribute `location`
/// of the bound vertex array at it.
void uploadVertexAttribute(GLuint& buffer, GLuint location, const void* data, std::size_t count,
                           GLenum usage);

/// An RGB32F lat-long texture: wraps in u (azimuth), clamps in v (poles), bilinear.
void uploadLatLong(GLuint& texture, const image::Image& img);

}  // namespace prt::viewer
