#include "prt/relight/relight_haar.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/haar/cube_texels.hpp"
#include "prt/haar/project_light.hpp"
#include "prt/sh/convolve.hpp"
#include "prt/transfer/albedo.hpp"
#include "prt/transfer/haar_rows.hpp"

namespace prt::relight {

namespace {

constexpr std::size_t kRowGrain = 256;

/// A bright texel as each row meets it: (1/π) ∫_texel max(n·ω, 0) dω is n·Φ/π for a texel wholly
/// above n's horizon (cube_texels.hpp), nothing for one wholly below, and the clipped polygon only
/// where the horizon crosses it. A cone about the texel's centre c decides which with one dot
/// product: every corner lies within the angle α of c, so n·c ≥ sin α puts them all above the
/// horizon and n·c ≤ −sin α all below (the margin covers float rounding; the rows between take
/// the exact, clipped integral, as every row once did).
struct BrightCone {
  Vec3f centre;
  float sinHalfAngle = 1;
  Vec3f momentOverPi;
  Rgb radiance;
  haar::TexelGeometry texel;
};

BrightCone brightCone(const haar::TexelGeometry& g, const Rgb& radiance) {
  const Vec3d c = normalize(g.corners[0] + g.corners[1] + g.corners[2] + g.corners[3]);
  double cosAlpha = 1;
  for (const Vec3d& v : g.corners) cosAlpha = std::min(cosAlpha, dot(c, v));
  const double sinAlpha = std::sqrt(std::max(0.0, 1 - cosAlpha * cosAlpha));
  constexpr double kMargin = 1e-5;
  return {Vec3f(c), float(sinAlpha + kMargin), Vec3f(g.moment / kPi), radiance, g};
}

}  // namespace

void relightHaar(const Transfer& transfer, const haar::HaarLight& light,
                 std::span<const Vec3f> normals, std::span<const Rgb> albedo, std::span<Rgb> out) {
  if (!transfer.isHaar())
    throw Error("relight: a Haar light relights Haar transfer, and this transfer is " +
                transfer.shape().describe());
  const TransferShape& shape = transfer.shape();
  if (light.resolution != shape.haar.resolution)
    throw Error("relight: the light's cube is " + std::to_string(light.resolution) +
                "² per face and the transfer's " + std::to_string(shape.haar.resolution) +
                "² (project the light at the transfer's resolution)");
  if (light.unshadowed.bands != haar::kUnshadowedBands)
    throw Error("relight: the Haar light holds no SH for the unshadowed part");
  const std::size_t rows = transfer.rowCount();
  if (out.size() != rows || normals.size() != rows)
    throw Error("relight: " + std::to_string(out.size()) + " outputs and " +
                std::to_string(normals.size()) + " normals for " + std::to_string(rows) + " rows");
  const Albedo kd(albedo, rows);
  const std::vector<Rgb> dense = light.dense();
  const Rgb* l = dense.data();
  // The unshadowed part: the light's SH convolved with the clamped cosine over π.
  constexpr int kBands = haar::kUnshadowedBands, kCoeffs = kBands * kBands;
  std::vector<Rgb> lobe(kCoeffs);
  const std::vector<double> a = sh::clampedCosineKernel(kBands);
  for (int lb = 0; lb < kBands; ++lb)
    for (int i = lb * lb; i < (lb + 1) * (lb + 1); ++i)
      lobe[std::size_t(i)] = light.unshadowed.c[std::size_t(i)] * float(a[std::size_t(lb)] / kPi);
  // The bright texels, for their exact share of the unshadowed part.
  std::vector<BrightCone> bright;
  for (const haar::BrightTexel& b : light.bright)
    bright.push_back(brightCone(haar::texelGeometry(b.texel, light.resolution), b.radiance));
  const std::size_t terms = static_cast<std::size_t>(shape.haar.terms);
  const float* values = transfer.values().data();
  // The indices are checked as they are read (a mapped bake's rows are not checked on loading:
  // io/bake_file.hpp's mapBake), one compare per term.
  const float count = static_cast<float>(dense.size());
  std::atomic<bool> bad{false};
  const std::size_t stride = shape.stride();
  // An inter-reflected row's bounce: its SH against the whole light's (haar::fullSh).
  const auto bounceCoeffs =
      static_cast<std::size_t>(shape.haar.bounceBands * shape.haar.bounceBands);
  const std::size_t bounceAt = shape.haarBounceOffset();
  const bool rgbBounce = shape.channels == 3;
  std::vector<Rgb> bounceLight;
  if (bounceCoeffs > 0) {
    const sh::RgbSh full = haar::fullSh(light);
    bounceLight.assign(full.c.begin(), full.c.begin() + std::ptrdiff_t(bounceCoeffs));
  }
  parallelFor(rows, kRowGrain, [&](std::size_t b, std::size_t e) {
    std::vector<float> y((e - b) * kCoeffs);
    sh::evalBatch(kBands, normals.subspan(b, e - b), y.data());
    for (std::size_t r = b; r < e; ++r) {
      const float* p = values + r * stride;
      // An occluded-part row starts from the unshadowed light (SH of the rest, the bright
      // texels exactly) and takes its terms away; a visible-part row is its terms alone.
      const bool occluded = p[0] == 0.0f;
      float x = 0, g = 0, z = 0;
      if (occluded) {
        const float* yr = y.data() + (r - b) * kCoeffs;
        for (int i = 0; i < kCoeffs; ++i) {
          x += yr[i] * lobe[std::size_t(i)].x;
          g += yr[i] * lobe[std::size_t(i)].y;
          z += yr[i] * lobe[std::size_t(i)].z;
        }
        const Vec3f& nrm = normals[r];
        for (const BrightCone& c : bright) {
          const float side = dot(nrm, c.centre);
          if (side <= -c.sinHalfAngle) continue;  // wholly below the horizon: nothing
          const float u = side >= c.sinHalfAngle ? std::max(0.0f, dot(nrm, c.momentOverPi))
                                                 : float(haar::clampedCosine(c.texel, Vec3d(nrm)));
          x += u * c.radiance.x;
          g += u * c.radiance.y;
          z += u * c.radiance.z;
        }
      }
      const float sign = occluded ? -1.0f : 1.0f;
      for (std::size_t t = 0; t < terms; ++t) {
        const float k = p[1 + 2 * t];
        if (!(k >= 0.0f && k < count)) {
          bad = true;
          break;
        }
        const Rgb& c = l[static_cast<std::uint32_t>(k)];
        const float v = sign * p[2 + 2 * t];
        x += v * c.x;
        g += v * c.y;
        z += v * c.z;
      }
      const float* q = p + bounceAt;
      for (std::size_t i = 0; i < bounceCoeffs; ++i) {
        const Rgb& c = bounceLight[i];
        const float* bi = q + (rgbBounce ? 3 * i : i);
        x += bi[0] * c.x;
        g += bi[rgbBounce ? 1 : 0] * c.y;
        z += bi[rgbBounce ? 2 : 0] * c.z;
      }
      out[r] = kd.at(r) * Rgb(x, g, z);
    }
  });
  if (bad) throw Error("relight: a Haar row names a coefficient outside its cube");
}

std::vector<Rgb> relightHaar(const Transfer& transfer, const haar::HaarLight& light,
                             std::span<const Vec3f> normals, std::span<const Rgb> albedo) {
  std::vector<Rgb> out(transfer.rowCount());
  relightHaar(transfer, light, normals, albedo, out);
  return out;
}

}  // namespace prt::relight
