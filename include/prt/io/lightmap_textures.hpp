#pragma once
// Per-texel transfer as coefficient textures, for engines (prt export --format exr|png; issue
// 18): the W × H lightmap's rows, value e·C + c of a row (coefficient e = l(l+1) + m, colour
// channel c of C) in texture ⌊(e·C + c)/4⌋, channel (e·C + c) mod 4 — the order the bake file's
// vertex columns use — with a JSON manifest (transfer.json) saying which coefficient and colour
// each channel holds, the lightmap UV set, and how to relight:
//
//   radiance_c(uv) = albedo_c(uv) · Σ_e T_e,c(uv) · L_e,c    (scalar transfer: T_e,c = T_e)
//
// with L the light's SH in prtkit's convention (docs/conventions.md). Float EXR stores the
// values; 16-bit PNG stores q = round(65535 (T − offset) / scale) per channel, decoded as
// T = offset + scale · q / 65535 (offset and scale per channel in the manifest, the channel's
// range, so the error is at most scale / 131070). Texel (x, y) is image row y, column x: row 0
// is v = 0, the image's top row as glTF reads textures.

#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "prt/io/bake_file.hpp"

namespace prt::io {

enum class TextureEncoding { Float32Exr, Unorm16Png };
/// "exr" | "png"; throws prt::Error otherwise.
TextureEncoding parseTextureEncoding(const std::string& s);

struct CoefficientTextures {
  /// (file name, bytes): t0.exr, t1.exr, ... then transfer.json.
  std::vector<std::pair<std::string, std::string>> files;
  nlohmann::json manifest;
  /// The largest error the encoding makes in any value (0 for float).
  double maxQuantisationError = 0;
};

/// The textures of `transfer` (per texel, complete; compressed rows are reconstructed) of a
/// bake of `mesh`. `source` names the bake in the manifest and in errors. Throws prt::Error for
/// a per-vertex transfer, a partial one, or a matrix (per-texel matrices are not baked).
CoefficientTextures encodeCoefficientTextures(const BakedTransfer& transfer, const Mesh& mesh,
                                              TextureEncoding encoding, const std::string& source);

}  // namespace prt::io
