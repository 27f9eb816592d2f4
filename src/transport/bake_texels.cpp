#include "prt/transport/bake_texels.hpp"

#include <algorithm>
#include <string>

#include "bake_common.hpp"
#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/core/units.hpp"
#include "prt/geometry/texel_sampling.hpp"
#include "prt/transport/texel_validity.hpp"

namespace prt {

using namespace bakedetail;

TexelBakeFootprint texelBakeFootprint(const Mesh& mesh, const BakeSettings& settings, int width,
                                      int height) {
  BakeSettings whole = settings;
  whole.rows = {};  // the channels rule only (the rows here are texels)
  TexelBakeFootprint f;
  f.channels = bakeFootprint(mesh, whole).channels;
  const std::size_t texels = std::size_t(std::max(width, 0)) * std::size_t(std::max(height, 0));
  const std::size_t nc = std::size_t(settings.bands) * std::size_t(settings.bands);
  const bool matrix = settings.layout == TransferLayout::Matrix;
  f.bytesPerTexel = (matrix ? nc * nc : nc) * std::size_t(f.channels) * sizeof(float);
  const std::size_t count = settings.rows.count ? std::min(settings.rows.count, texels) : texels;
  f.transferBytes = f.bytesPerTexel * count;
  // Per sample (at most one per texel) the pass being baked and the sum or the order it reads,
  // each laid out once more as a dilated lightmap, and the samples themselves (~40 bytes).
  const int bounces = settings.effectiveBounces();
  const std::size_t vec = nc * std::size_t(f.channels) * sizeof(float) * texels;
  const std::size_t all = f.bytesPerTexel * texels;
  if (!matrix)
    f.workingBytes = all * (bounces > 0 ? 3 : 1);
  else if (bounces == 0)
    f.workingBytes = all;
  else if (settings.glossyBounces(TransferLayout::Matrix))
    f.workingBytes = 3 * all;  // the order read (rows and lightmap) and the one being baked
  else
    f.workingBytes = all + 4 * vec;
  f.workingBytes += texels * 40;
  return f;
}

TexelBake bakeTexels(const Mesh& mesh, const Occluder& occluder, const BakeSettings& settings,
                     std::span<const Vec2f> uvs, int width, int height, int padding,
                     BakeStats* stats, const ProgressFn& progressFn) {
  const auto t0 = Clock::now();
  BakeSettings whole = settings;
  whole.rows = {};  // the rows are texels, checked below
  validateBake(mesh, whole);
  const std::string name = mesh.source.empty() ? "mesh" : mesh.source;
  if (padding < 0 || padding > kMaxLightmapPadding)
    throw Error(
        name, "the dilation padding must be 0.." + std::to_string(kMaxLightmapPadding) + " texels");
  {
    const TexelBakeFootprint f = texelBakeFootprint(mesh, settings, width, height);
    const std::size_t need = f.transferBytes + f.workingBytes, have = physicalMemoryBytes();
    if (need > have / 10 * 9)
      throw Error(name, std::string(toString(settings.layout)) + " transfer of a " +
                            std::to_string(width) + " x " + std::to_string(height) +
                            " lightmap at " + std::to_string(settings.bands) + " bands needs " +
                            bytesText(f.bytesPerTexel) + " per texel, " + bytesText(need) +
                            " in all; this machine has " + bytesText(have) +
                            " (fewer bands, a smaller --resolution, or vector transfer)");
  }

  checkLightmapUvs(mesh, uvs, width, height, "the lightmap UV set");
  const std::size_t texels = std::size_t(width) * std::size_t(height);
  RowRange range = settings.rows;
  if (range.count == 0 && range.first < texels) range.count = texels - range.first;
  if (range.first >= texels || range.count > texels - range.first)
    throw Error(name, "texel range [" + std::to_string(range.first) + ", " +
                          std::to_string(range.end()) + ") is outside the " +
                          std::to_string(width) + " x " + std::to_string(height) + " lightmap");

  TexelBake out;
  out.samples = sampleTexels(mesh, uvs, width, height);
  // A range of one pass needs the texels it holds and those its dilation reads (within
  // `padding` rings: the rows of texels `padding` above and below it); the bounces read the
  // whole previous pass. Each texel's value depends on its own seed alone, so the range's rows
  // equal the whole bake's exactly.
  if (settings.effectiveBounces() == 0 && range.count < texels) {
    const int ring = std::max(padding, 1);
    const std::size_t y0 = range.first / std::size_t(width), y1 = (range.end() - 1) / width;
    const std::size_t lo = (y0 > std::size_t(ring) ? y0 - ring : 0) * width,
                      hi = std::min<std::size_t>(height, y1 + ring + 1) * width;
    std::vector<TexelSample> kept;
    for (const TexelSample& t : out.samples.samples)
      if (t.texel >= lo && t.texel < hi) kept.push_back(t);
    std::fill(out.samples.sampleOfTexel.begin(), out.samples.sampleOfTexel.end(), -1);
    for (std::size_t i = 0; i < kept.size(); ++i)
      out.samples.sampleOfTexel[kept[i].texel] = static_cast<std::int32_t>(i);
    out.samples.samples = std::move(kept);
  }
  const std::vector<TexelSample>& s = out.samples.samples;
  std::vector<RowPoint> points(s.size());
  parallelFor(s.size(), 256, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i)
      points[i] = {samplePosition(mesh, s[i]), sampleNormal(mesh, s[i]), s[i].texel};
  });

  // Points inside geometry (texel_validity.hpp) are baked like the rest but do not count as
  // covered: their texels are refilled from valid neighbours wherever one lies within the
  // dilation's reach, and keep their own (dark, hidden) value where none does.
  std::vector<Vec3f> positions(s.size()), normals(s.size());
  for (std::size_t i = 0; i < s.size(); ++i)
    positions[i] = points[i].position, normals[i] = points[i].normal;
  const std::vector<std::uint8_t> inside = insideGeometry(mesh, occluder, positions, normals);
  out.invalid.clear();
  for (std::size_t i = 0; i < s.size(); ++i)
    if (inside[i]) out.invalid.push_back(s[i].texel);

  // Every kind of bake runs K + 1 passes over the samples (vector: T⁰..Tᴷ; matrix: the diffuse
  // bounce's K vector passes then the matrices, or the glossy orders 0..K).
  const int bounces = settings.effectiveBounces();
  Progress progress(progressFn, s.size() * std::size_t(bounces + 1));
  // A pass at the samples laid out as the lightmap and dilated, for the next pass to read.
  const auto asImage = [&](const std::vector<float>& rows, std::size_t stride,
                           std::vector<float>& image, std::vector<std::uint8_t>& filled) {
    image.assign(texels * stride, 0.0f);
    filled.assign(texels, 0);
    for (std::size_t i = 0; i < s.size(); ++i) {
      if (inside[i]) continue;
      std::copy_n(rows.begin() + std::ptrdiff_t(i * stride), stride,
                  image.begin() + std::ptrdiff_t(s[i].texel * stride));
      filled[s[i].texel] = 1;
    }
    dilateTexels(image, int(stride), filled, width, height, std::max(padding, 1));
    for (std::size_t i = 0; i < s.size(); ++i)
      if (inside[i] && !filled[s[i].texel]) {
        std::copy_n(rows.begin() + std::ptrdiff_t(i * stride), stride,
                    image.begin() + std::ptrdiff_t(s[i].texel * stride));
        filled[s[i].texel] = 1;
      }
  };
  std::vector<std::uint64_t> rays;
  std::vector<double> passSeconds, variance(s.size(), 0.0);
  const std::size_t nc = std::size_t(settings.bands) * settings.bands;

  // The vector passes of `vs` at the samples (each laid out and dilated as a lightmap for the
  // next to read): their sum, per sample, in `channels` per coefficient (a scalar direct pass
  // spread over RGB when needed). `countVariance`: their per-texel variances are the bake's
  // error estimate (a vector bake), not a matrix bake's diffuse bounce source.
  const auto vectorPasses = [&](const BakeSettings& vs, bool countVariance, int& channels) {
    const auto setup = makeVectorSetup(mesh, vs);
    const int bounces = vs.effectiveBounces();
    channels = bounces > 0 && !vectorAlbedoGrey(*setup) ? 3 : 1;
    std::vector<double> passVariance(s.size());
    std::vector<float> pass(s.size() * nc), sum;
    auto tp = Clock::now();
    rays.push_back(computeTexelRows(mesh, occluder, *setup, 0, points, nullptr, 1, pass.data(),
                                    passVariance.data(), &progress));
    passSeconds.push_back(seconds(tp));
    if (countVariance)
      for (std::size_t i = 0; i < s.size(); ++i) variance[i] += passVariance[i];
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
      rays.push_back(computeTexelRows(mesh, occluder, *setup, k, points, &prev, channels,
                                      next.data(), passVariance.data(), &progress));
      passSeconds.push_back(seconds(tp));
      if (countVariance)
        for (std::size_t i = 0; i < s.size(); ++i) variance[i] += passVariance[i];
      add(next, channels);
      pass = std::move(next);
      prevChannels = channels;
    }
    return sum;
  };
  // One matrix pass at the samples, reading `bounced` (a dilated lightmap) when it bounces.
  const auto matrixPass = [&](const BakeSettings& ms, bool bounce, bool glossy, int channels,
                              const TexelImage* bounced, bool countVariance) {
    const auto setup = makeMatrixSetup(mesh, ms, bounce, glossy, channels);
    std::vector<float> rows(s.size() * nc * nc * std::size_t(channels));
    std::vector<double> passVariance(s.size());
    const auto tp = Clock::now();
    rays.push_back(computeMatrixTexelRows(mesh, occluder, *setup, points, bounced, rows.data(),
                                          passVariance.data(), &progress));
    passSeconds.push_back(seconds(tp));
    if (countVariance) variance = passVariance;
    return rows;
  };

  int channels = 1;
  std::vector<float> sum;  // the transfer per sample, channels interleaved per coefficient
  MatrixPassKind matrixKind = MatrixPassKind::Direct;  // how its passes are reported
  if (settings.layout == TransferLayout::Vector) {
    sum = vectorPasses(settings, true, channels);
  } else {
    channels = texelBakeFootprint(mesh, settings, width, height).channels;
    if (bounces == 0) {
      // Unshadowed or shadowed matrices: one pass.
      sum = matrixPass(settings, false, false, channels, nullptr, true);
    } else if (!settings.glossyBounces(TransferLayout::Matrix)) {
      // Diffuse bounce surfaces: the vector transfer with K − 1 bounces (its passes summed),
      // dilated, then the matrices that gather it through the hits' lightmap UVs.
      int vc = 1;
      const std::vector<float> vsum = vectorPasses(diffuseBounceSource(settings), false, vc);
      std::vector<float> image;
      std::vector<std::uint8_t> filled;
      asImage(vsum, nc * vc, image, filled);
      const TexelImage bounced{image.data(), width, height, nc * std::size_t(vc), uvs};
      sum = matrixPass(settings, true, false, channels, &bounced, true);
      matrixKind = MatrixPassKind::DiffuseBounces;
    } else {
      // Glossy bounce surfaces: the matrices of orders 0..K, each from the one before read
      // through its dilated lightmap.
      const std::vector<BakeSettings> orders = glossyBounceOrders(settings);
      std::vector<float> image;
      std::vector<std::uint8_t> filled;
      int prevChannels = 1;
      for (int j = 0; j <= bounces; ++j) {
        const BakeSettings& o = orders[std::size_t(j)];
        const int c = texelBakeFootprint(mesh, o, width, height).channels;
        const TexelImage prev{image.data(), width, height, nc * nc * std::size_t(prevChannels),
                              uvs};
        sum = matrixPass(o, j > 0, j > 0, c, j > 0 ? &prev : nullptr, j == bounces);
        if (j < bounces) asImage(sum, nc * nc * std::size_t(c), image, filled);
        prevChannels = c;
      }
      matrixKind = MatrixPassKind::GlossyBounces;
    }
  }
  const std::size_t perChannel = settings.layout == TransferLayout::Matrix ? nc * nc : nc;

  std::vector<float> result;
  asImage(sum, perChannel * channels, result, out.filled);
  if (padding == 0)  // dilation above fed the bounces; without padding the gutter stays empty
    for (std::size_t t = 0; t < texels; ++t)
      if (out.samples.sampleOfTexel[t] < 0) {
        out.filled[t] = 0;
        std::fill_n(result.begin() + std::ptrdiff_t(t * perChannel * channels),
                    perChannel * channels, 0.0f);
      }
  TransferShape shape{TransferDomain::Texels, settings.layout, settings.bands, channels, range};
  shape.lightmap = {width, height, padding};
  const std::size_t stride = perChannel * std::size_t(channels);
  if (range.count < texels)
    result = std::vector<float>(result.begin() + std::ptrdiff_t(range.first * stride),
                                result.begin() + std::ptrdiff_t(range.end() * stride));
  out.transfer = Transfer::dense(shape, FloatArray(std::move(result)));
  if (stats) {
    // The error estimates over the range's covered texels (all of them for a whole bake).
    std::vector<double> inRange;
    for (std::size_t i = 0; i < s.size(); ++i)
      if (s[i].texel >= range.first && s[i].texel < range.end()) inRange.push_back(variance[i]);
    *stats = settings.layout == TransferLayout::Vector
                 ? vectorStats(rays, passSeconds, inRange)
                 : matrixStats(matrixKind, rays, passSeconds, inRange, seconds(t0));
    stats->secondsTotal = seconds(t0);
    stats->threads = maxThreads();
    stats->vertices = inRange.size();
  }
  return out;
}

}  // namespace prt
