#pragma once
// Data textures: images whose channels are numbers, not colours (per-texel transfer
// coefficients for engines, issue 18), written as they are — no exposure, tone map or sRGB
// encoding, which belong to pictures (image_io.hpp):
//
//   * float OpenEXR: named 32-bit float channels (1–4 for a texture, up to kMaxExrChannels for
//     a volume's layers), ZIP-compressed (tinyexr), with optional string attributes in its
//     header;
//   * 16-bit PNG: 1–4 channels (grey, grey + alpha, RGB, RGBA) of unsigned 16-bit values
//     (libpng), the caller's quantisation (a value v is stored as round(65535 (v − offset) /
//     scale); io/lightmap_textures.hpp keeps offset and scale beside the images).
//
// Row 0 is the image's top row, as glTF and OpenGL-on-upload read a texture whose texel (x, y)
// lies at UV ((x + ½)/W, (y + ½)/H). Both return the file's bytes (the caller writes them, e.g.
// into a FolderOutput); prt::Error("NAME: ...") on a size or channel count out of range.

#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace prt::image {

/// The most channels an EXR data texture holds (a probe grid's 3 B² layers at 16 bands).
inline constexpr int kMaxExrChannels = 768;

struct DataTexture {
  int width = 0, height = 0;
  std::vector<std::string> channelNames;   ///< the EXR channel names ("R", "sh0.R", ...)
  std::vector<std::vector<float>> planes;  ///< one per channel, width · height, row by row
  /// EXR only: string attributes of the header (name, value), e.g. a JSON description.
  std::vector<std::pair<std::string, std::string>> attributes;
};

/// The texture as a float OpenEXR file (channels stored in name order, as EXR requires; 1 to
/// kMaxExrChannels of them, names unique, at most 255 bytes).
std::string encodeExrData(const DataTexture& texture, const std::string& name);

/// Interleaved 16-bit values (width · height · channels, row by row) as a 16-bit PNG.
std::string encodePng16(int width, int height, int channels, std::span<const std::uint16_t> values,
                        const std::string& name);

/// Interleaved 8-bit values (width · height · channels, row by row) as an 8-bit PNG (1 to 4
/// channels: grey, grey + alpha, RGB, RGBA).
std::string encodePng8(int width, int height, int channels, std::span<const std::uint8_t> values,
                       const std::string& name);

}  // namespace prt::image
