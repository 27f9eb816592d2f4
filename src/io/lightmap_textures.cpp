#include "prt/io/lightmap_textures.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "bake_mesh.hpp"
#include "prt/core/error.hpp"
#include "prt/core/version.hpp"
#include "prt/image/data_texture.hpp"

namespace prt::io {

namespace {

constexpr const char* kChannelNames[4] = {"R", "G", "B", "A"};
constexpr const char* kColours[3] = {"r", "g", "b"};

}  // namespace

TextureEncoding parseTextureEncoding(const std::string& s) {
  if (s == "exr") return TextureEncoding::Float32Exr;
  if (s == "png") return TextureEncoding::Unorm16Png;
  throw Error("unknown texture format '" + s.substr(0, 40) + "' (expected exr or png)");
}

CoefficientTextures encodeCoefficientTextures(const BakedTransfer& baked, const Mesh& mesh,
                                              TextureEncoding encoding, const std::string& source) {
  const Transfer& t = baked.transfer;
  if (t.domain() != TransferDomain::Texels)
    throw Error(source,
                "holds per-vertex transfer: coefficient textures are of per-texel "
                "transfer (prt bake --domain texels)");
  if (t.isMatrix())
    throw Error(source, "per-texel matrices have no coefficient textures (bake vector transfer)");
  const TransferShape::LightmapSize lm = t.shape().lightmap;
  if (t.rows().first != 0 || t.rowCount() != lm.texels())
    throw Error(source, "is a partial bake (merge the pieces with prt merge first)");
  const Transfer dense = t.toDense();
  const std::size_t S = dense.stride(), texels = lm.texels();
  const int C = dense.channels();
  const std::size_t images = (S + 3) / 4;
  const bool png = encoding == TextureEncoding::Unorm16Png;

  CoefficientTextures out;
  nlohmann::json textures = nlohmann::json::array();
  for (std::size_t k = 0; k < images; ++k) {
    const int used = static_cast<int>(std::min<std::size_t>(4, S - 4 * k));
    // A 16-bit PNG has 1, 3 or 4 channels here (grey + alpha would read oddly in engines).
    const int stored = png ? (used == 2 ? 3 : used) : used;
    image::DataTexture tex;
    tex.width = lm.width;
    tex.height = lm.height;
    nlohmann::json channels = nlohmann::json::array();
    std::vector<std::uint16_t> quantised;
    if (png) quantised.assign(texels * std::size_t(stored), 0);
    for (int j = 0; j < used; ++j) {
      const std::size_t value = 4 * k + std::size_t(j);
      const int e = static_cast<int>(value) / C, c = static_cast<int>(value) % C;
      const int l = static_cast<int>(std::floor(std::sqrt(double(e)) + 1e-9));
      std::vector<float> plane(texels);
      for (std::size_t x = 0; x < texels; ++x) plane[x] = dense.row(x)[value];
      nlohmann::json ch = {{"channel", kChannelNames[j]},
                           {"value", value},
                           {"coefficient", e},
                           {"l", l},
                           {"m", e - l * (l + 1)},
                           {"colour", C == 1 ? "all" : kColours[c]}};
      if (png) {
        const auto [lo, hi] = std::minmax_element(plane.begin(), plane.end());
        const double offset = *lo, scale = *hi > *lo ? double(*hi) - double(*lo) : 1.0;
        for (std::size_t x = 0; x < texels; ++x) {
          const double q = std::round(65535.0 * (double(plane[x]) - offset) / scale);
          const auto v = static_cast<std::uint16_t>(std::clamp(q, 0.0, 65535.0));
          quantised[x * std::size_t(stored) + std::size_t(j)] = v;
          const double back = offset + scale * double(v) / 65535.0;
          out.maxQuantisationError =
              std::max(out.maxQuantisationError, std::abs(back - double(plane[x])));
        }
        ch["offset"] = offset;
        ch["scale"] = scale;
      } else {
        tex.channelNames.push_back(kChannelNames[j]);
        tex.planes.push_back(std::move(plane));
      }
      channels.push_back(std::move(ch));
    }
    const std::string file = "t" + std::to_string(k) + (png ? ".png" : ".exr");
    const std::string label = source + " (" + file + ")";
    out.files.emplace_back(file,
                           png ? image::encodePng16(lm.width, lm.height, stored, quantised, label)
                               : image::encodeExrData(tex, label));
    textures.push_back({{"file", file}, {"channels", std::move(channels)}});
  }
  const int set = lightmapTexCoord(mesh);
  out.manifest = {
      {"format", "prtkit-coefficient-textures"},
      {"version", 1},
      {"generator", kGenerator},
      {"source", source},
      {"mode", toString(baked.mode())},
      {"bands", dense.bands()},
      {"channels", C},
      {"lightmap",
       {{"width", lm.width},
        {"height", lm.height},
        {"padding", lm.padding},
        {"texCoord", set},
        {"rowZero", "v = 0 (the image's top row, as glTF reads textures)"}}},
      {"encoding", png ? "unorm16" : "float32"},
      {"decode", png ? "T = offset + scale * q / 65535 (q the 16-bit sample)" : "T = sample"},
      {"relight",
       "radiance_c = albedo_c * sum_e T_e,c * L_e,c; coefficient e = l(l+1)+m of the light's "
       "real SH (prtkit's convention, docs/conventions.md)"},
      {"textures", std::move(textures)}};
  out.files.emplace_back("transfer.json", out.manifest.dump(2) + "\n");
  return out;
}

}  // namespace prt::io
