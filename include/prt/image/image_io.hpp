#pragma once
// Reading and writing images.
//
// Formats, chosen by the (case-insensitive) extension:
//  * .hdr  Radiance RGBE (our bounds-checked decoder), linear.
//  * .exr  OpenEXR, linear, read by the OpenEXR library (every compression, DWAA/DWAB of
//          Blender's bundled Poly Haven maps included; written by tinyexr). RGB(A) or
//          single-channel Y; other channels are ignored.
//  * .png, .jpg/.jpeg: 8-bit (or 16-bit PNG) decoded from sRGB to linear by default, or by the
//          course's (v/255)^2.2 with LdrDecode::Gamma22. Alpha is ignored; grey expands to RGB.
// Writing: .png (exposure, tone map, sRGB encode, 8-bit), .exr (32-bit float, ZIP), .hdr (RGBE).
//
// Pixel policy (never propagate NaN): a non-finite channel (NaN or ±Inf) becomes 0 and a negative
// channel is clamped to 0. The reader counts the pixels touched by each rule in ReadStats, so
// callers can warn; the pixels themselves are always finite and non-negative afterwards.
// Errors: prt::Error("FILE: what is wrong") for unreadable, truncated or unknown files.

#include <cstddef>
#include <span>
#include <string>

#include "prt/image/color.hpp"
#include "prt/image/image.hpp"

namespace prt::image {

enum class LdrDecode { Srgb, Gamma22 };

struct ReadOptions {
  LdrDecode ldrDecode = LdrDecode::Srgb;
};

/// What the reader had to repair (pixel counts; a pixel counts once per rule).
struct ReadStats {
  std::size_t nonFinitePixels = 0;  ///< had a NaN or ±Inf channel (set to 0)
  std::size_t negativePixels = 0;   ///< had a negative finite channel (clamped to 0)
  std::size_t pixels = 0;           ///< all the pixels read
  double negativeSum = 0;           ///< Σ |v| over the negative channels clamped
  double positiveSum = 0;           ///< Σ v over the finite positive channels
  bool ldr = false;                 ///< decoded from an 8/16-bit format
};

/// True for the extensions readImage understands (hdr, exr, png, jpg, jpeg).
bool isReadableImageExtension(const std::string& ext);
/// Reads an image; throws prt::Error("PATH: ...") on failure.
Image readImage(const std::string& path, const ReadOptions& options = {},
                ReadStats* stats = nullptr);

/// Decodes an image held in memory; `ext` (lower case, no dot) chooses the format as for
/// readImage and `label` names it in messages. Declared sizes are checked against the bytes
/// present and prt::limits() before anything is allocated.
Image readImageBytes(const std::string& label, const std::string& ext,
                     std::span<const unsigned char> bytes, const ReadOptions& options = {},
                     ReadStats* stats = nullptr);
/// Checks an encoded PNG or JPEG before anything decodes it: the signature, PNG chunk lengths
/// against the bytes present, and the width and height in its header against prt::limits()
/// (throws Error(label, ...) otherwise).
void checkEncodedImageSize(const std::string& label, std::span<const unsigned char> bytes);

/// Decodes a PNG or JPEG held in memory (by content) to its 8-bit sRGB codes, exactly: grey
/// expands to RGB, alpha is dropped, a 16-bit PNG is rounded to 8 bits (round(v / 257)). The
/// checks of readImageBytes come first (signature, PNG chunk lengths, a JPEG's end marker, the
/// declared size against prt::limits()), so a small file cannot ask for a large allocation.
/// Throws prt::Error(label, ...).
Srgb8Image readSrgb8Bytes(const std::string& label, std::span<const unsigned char> bytes);
/// Reads a colour texture file as 8-bit sRGB codes: PNG and JPEG as readSrgb8Bytes, HDR and EXR
/// (linear) encoded to sRGB, each channel clamped to [0, 1] and rounded. Throws
/// prt::Error("PATH: ...").
Srgb8Image readSrgb8Image(const std::string& path);
/// The PNG bytes of `img` (8-bit RGB, stb_image_write: the same bytes for the same codes).
/// Throws prt::Error(name, ...) for an empty or inconsistent image.
std::string encodePng(const Srgb8Image& img, const std::string& name);

/// Applies the pixel policy in place and returns the counts (used by the readers; exposed for
/// images built in memory).
ReadStats sanitize(Image& img);

struct WriteOptions {
  ToneMap toneMap = ToneMap::Aces;  ///< PNG only
  float exposureStops = 0.0f;       ///< PNG only: multiply by 2^exposure before tone mapping
};
/// Writes by extension (png, exr, hdr; "-", standard output, gets PNG) by the output policy of
/// prt/core/file.hpp; throws prt::Error("PATH: ...") on failure.
void writeImage(const std::string& path, const Image& img, const WriteOptions& options = {});

}  // namespace prt::image
