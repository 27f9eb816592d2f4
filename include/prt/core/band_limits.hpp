#pragma once
// Every limit on SH band counts, in one place (bands B = degrees 0..B−1, B² coefficients).
// Each exists for a stated reason; everything that checks a band count checks it against one of
// these and words its refusal with bandLimitMessage, so the CLI, the viewers and the page agree.
// The web page reads the same numbers from a module generated at build time (web/gen/constants.cpp).

#include <string>

namespace prt::bands {

/// The library: SH evaluation, rotation, projection, light files and bake files (2·32−1 = 63
/// is the widest rotation block the fixed-size tables hold).
inline constexpr int kMaxLibrary = 32;
/// Baking: a B-band bake costs B² (vectors) or B⁴ (matrices) per sample; 16 bands already hold a
/// Phong lobe of exponent ~100 and a 16-band matrix is 256 KB per vertex.
inline constexpr int kMaxBake = 16;
/// The viewers' light: a std140 block of B² vec4 = 16 KiB at 32 bands, the smallest
/// GL_MAX_UNIFORM_BLOCK_SIZE OpenGL 3.3 allows.
inline constexpr int kMaxPackedLight = 32;
/// The shaders' glossy responses (viewer --glossy-on gpu, the page's compressed matrices): their
/// SH arrays hold 64 coefficients.
inline constexpr int kMaxShaderGlossy = 8;

/// "WHAT has B bands; WHO takes 1..MAX" — the one wording of a band-count refusal.
inline std::string bandLimitMessage(const std::string& what, int bands, const std::string& who,
                                    int max) {
  return what + " has " + std::to_string(bands) + " bands; " + who + " takes 1.." +
         std::to_string(max);
}

}  // namespace prt::bands
