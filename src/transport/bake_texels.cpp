#include "prt/transport/bake_texels.hpp"

#include <algorithm>
#include <string>

#include "bake_common.hpp"
#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/geometry/texel_sampling.hpp"

namespace prt {

using namespace bakedetail;

TexelBake bakeTexels(const Mesh& mesh, const Occluder& occluder, const BakeSettings& settings,
                     std::span<const Vec2f> uvs, int width, int height, int padding,
                     BakeStats* stats, const ProgressFn& progressFn) {
  const auto t0 = Clock::now();
  validateBake(mesh, settings);
  const std::string name = mesh.source.empty() ? "mesh" : mesh.source;
  if (settings.layout != TransferLayout::Vector)
    throw Error(name, "per-texel glossy matrices are not baked yet (bake vector transfer)");
  if (settings.rows.first != 0 || settings.rows.count != 0)
    throw Error(name, "a per-texel bake covers the whole lightmap (no vertex range)");
  if (padding < 0) throw Error(name, "the dilation padding must be 0 or more texels");
  checkLightmapUvs(mesh, uvs, width, height, "the lightmap UV set");

  TexelBake out;
  out.samples = sampleTexels(mesh, uvs, width, height);
  const std::vector<TexelSample>& s = out.samples.samples;
  std::vector<RowPoint> points(s.size());
  parallelFor(s.size(), 256, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i)
      points[i] = {samplePosition(mesh, s[i]), sampleNormal(mesh, s[i]), s[i].texel};
  });

  const auto setup = makeVectorSetup(mesh, settings);
  const int bounces = settings.effectiveBounces();
  const int channels = bounces > 0 && !vectorAlbedoGrey(*setup) ? 3 : 1;
  const std::size_t nc = std::size_t(settings.bands) * settings.bands;
  const std::size_t texels = out.samples.texelCount();
  Progress progress(progressFn, s.size() * std::size_t(bounces + 1));

  // The passes at the samples, each also laid out and dilated as a lightmap for the next to read.
  const auto asImage = [&](const std::vector<float>& rows, std::size_t stride,
                           std::vector<float>& image, std::vector<std::uint8_t>& filled) {
    image.assign(texels * stride, 0.0f);
    filled.assign(texels, 0);
    for (std::size_t i = 0; i < s.size(); ++i) {
      std::copy_n(rows.begin() + std::ptrdiff_t(i * stride), stride,
                  image.begin() + std::ptrdiff_t(s[i].texel * stride));
      filled[s[i].texel] = 1;
    }
    dilateTexels(image, int(stride), filled, width, height, std::max(padding, 1));
  };
  std::vector<std::uint64_t> rays;
  std::vector<double> passSeconds, variance(s.size(), 0.0), passVariance(s.size());
  std::vector<float> pass(s.size() * nc), sum;
  auto tp = Clock::now();
  rays.push_back(computeTexelRows(mesh, occluder, *setup, 0, points, nullptr, 1, pass.data(),
                                  passVariance.data(), &progress));
  passSeconds.push_back(seconds(tp));
  for (std::size_t i = 0; i < s.size(); ++i) variance[i] += passVariance[i];
  // The sum in `channels` per coefficient (a scalar direct pass spread over RGB when needed).
  sum.assign(s.size() * nc * channels, 0.0f);
  const auto add = [&](const std::vector<float>& p, int pc) {
    for (std::size_t i = 0; i < s.size(); ++i)
      for (std::size_t k = 0; k < nc; ++k)
        for (int c = 0; c < channels; ++c)
          sum[(i * nc + k) * channels + c] += p[(i * nc + k) * pc + (pc == 1 ? 0 : c)];
  };
  add(pass, 1);
  int prevChannels = 1;
  std::vector<float> image;
  std::vector<std::uint8_t> filled;
  for (int k = 1; k <= bounces; ++k) {
    asImage(pass, nc * prevChannels, image, filled);
    const TexelImage prev{image.data(), width, height, nc * prevChannels, uvs};
    std::vector<float> next(s.size() * nc * channels);
    tp = Clock::now();
    rays.push_back(computeTexelRows(mesh, occluder, *setup, k, points, &prev, channels, next.data(),
                                    passVariance.data(), &progress));
    passSeconds.push_back(seconds(tp));
    for (std::size_t i = 0; i < s.size(); ++i) variance[i] += passVariance[i];
    add(next, channels);
    pass = std::move(next);
    prevChannels = channels;
  }

  std::vector<float> result;
  asImage(sum, nc * channels, result, out.filled);
  if (padding == 0)  // dilation above fed the bounces; without padding the gutter stays empty
    for (std::size_t t = 0; t < texels; ++t)
      if (out.samples.sampleOfTexel[t] < 0) {
        out.filled[t] = 0;
        std::fill_n(result.begin() + std::ptrdiff_t(t * nc * channels), nc * channels, 0.0f);
      }
  TransferShape shape{TransferDomain::Texels, TransferLayout::Vector, settings.bands, channels,
                      RowRange{0, texels}};
  shape.lightmap = {width, height};
  out.transfer = Transfer::dense(shape, FloatArray(std::move(result)));
  if (stats) {
    *stats = vectorStats(rays, passSeconds, variance);
    stats->secondsTotal = seconds(t0);
    stats->threads = maxThreads();
    stats->vertices = s.size();
  }
  return out;
}

}  // namespace prt
