#include "prt/haar/project_light.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/envmap/layout.hpp"
#include "prt/envmap/project.hpp"
#include "prt/haar/cube_haar.hpp"
#include "prt/sh/rotate.hpp"
#include "prt/sh/sh.hpp"

namespace prt::haar {

namespace {

constexpr int kSupersample = 8;         // points per texel side through lookup()
constexpr std::size_t kSplatTexels = 16;  // environment texels per cube texel to splat instead
constexpr int kCapSide = 256;           // stratified points per disc side

/// Adds the mean of f(ω) over each texel, by kSupersample² points weighted by their exact solid
/// angles, to sum (weighted by the texel's solid angle, divided out by the caller).
template <typename F>
void supersample(int n, const F& radianceAt, std::vector<Rgbd>& power) {
  const int fine = n * kSupersample;
  const std::vector<double> omega = envmap::cubeTexelSolidAngles(fine);
  const std::size_t face = std::size_t(n) * n;
  parallelFor(6 * std::size_t(n), 1, [&](std::size_t b, std::size_t e) {
    for (std::size_t fy = b; fy < e; ++fy) {  // one row of texels of one face
      const int f = int(fy / std::size_t(n)), y = int(fy % std::size_t(n));
      for (int x = 0; x < n; ++x) {
        Rgbd sum(0.0);
        for (int j = 0; j < kSupersample; ++j)
          for (int i = 0; i < kSupersample; ++i) {
            const int px = x * kSupersample + i, py = y * kSupersample + j;
            const double s = 2.0 * (px + 0.5) / fine - 1.0, t = 2.0 * (py + 0.5) / fine - 1.0;
            const Vec3d d = normalize(envmap::cubeFaceDirection(f, s, t));
            const Rgb l = radianceAt(Vec3f(d));
            sum += Rgbd(l) * omega[std::size_t(py) * fine + px];
          }
        power[std::size_t(f) * face + std::size_t(y) * n + x] += sum;
      }
    }
  });
}

}  // namespace

const char* toString(Selection selection) {
  return selection == Selection::AreaWeighted ? "area" : "magnitude";
}

Selection parseSelection(const std::string& s) {
  if (s == "area") return Selection::AreaWeighted;
  if (s == "magnitude") return Selection::Magnitude;
  throw Error("unknown Haar term selection '" + s + "' (area|magnitude)");
}

std::vector<Rgb> cubeMeans(const envmap::Environment& env, int n, const Mat3d& rotation) {
  checkResolution(n, "Haar lighting");
  const std::size_t count = coefficientCount(n);
  std::vector<Rgbd> power(count, Rgbd(0.0));
  const Mat3d inverseRotation = rotation.transposed();
  const Mat3f turn = rotation.cast<float>();
  const auto turned = [&](const Vec3f& d) { return Vec3f(inverseRotation * Vec3d(d)); };
  if (env.kind() == envmap::Environment::Kind::Analytic) {
    const auto& smooth = env.smooth();
    if (smooth) supersample(n, [&](const Vec3f& d) { return smooth(turned(d)); }, power);
    for (const envmap::Cap& cap : env.caps()) {
      // Uniform in solid angle over the disc: cos θ = 1 − u (1 − cos α), φ = 2π v.
      const Vec3f c = normalize(turn * cap.direction);
      Vec3f t, b;
      orthonormalBasis(c, t, b);
      const double cosAlpha = std::cos(cap.halfAngle);
      const Rgbd each = Rgbd(cap.power()) / double(kCapSide * kCapSide);
      for (int j = 0; j < kCapSide; ++j)
        for (int i = 0; i < kCapSide; ++i) {
          const double cosTheta = 1.0 - (i + 0.5) / kCapSide * (1.0 - cosAlpha);
          const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
          const double phi = 2.0 * kPi * (j + 0.5) / kCapSide;
          const Vec3f d = t * float(sinTheta * std::cos(phi)) + b * float(sinTheta * std::sin(phi)) +
                          c * float(cosTheta);
          power[texelOf(d, n)] += each;
        }
    }
  } else if (env.texelCount() >= kSplatTexels * count) {
    for (std::size_t k = 0; k < env.texelCount(); ++k) {
      const envmap::Texel tx = env.texel(k);
      if (tx.solidAngle <= 0) continue;
      power[texelOf(turn * tx.direction, n)] += Rgbd(tx.radiance) * env.texelSolidAngle(k);
    }
  } else {
    supersample(n, [&](const Vec3f& d) { return env.lookup(turned(d)); }, power);
  }
  const std::vector<double> omega = envmap::cubeTexelSolidAngles(n);
  const std::size_t face = std::size_t(n) * n;
  std::vector<Rgb> means(count);
  for (std::size_t k = 0; k < count; ++k) means[k] = Rgb(power[k] / omega[k % face]);
  return means;
}

HaarLight approximate(const std::vector<Rgb>& means, int n, std::size_t terms,
                      Selection selection) {
  checkResolution(n, "Haar lighting");
  const std::size_t count = coefficientCount(n);
  if (means.size() != count)
    throw Error("Haar lighting: " + std::to_string(means.size()) + " texel means for a cube of " +
                std::to_string(count));
  if (terms < 1) throw Error("Haar lighting: at least one term must be kept");
  std::array<std::vector<double>, 3> c;
  for (int ch = 0; ch < 3; ++ch) {
    c[ch].resize(count);
    for (std::size_t k = 0; k < count; ++k) c[ch][k] = means[k][std::size_t(ch)];
    forward(c[ch].data(), n);
  }
  std::vector<double> norm2(count), score(count);
  double total = 0;
  for (std::size_t k = 0; k < count; ++k) {
    norm2[k] = c[0][k] * c[0][k] + c[1][k] * c[1][k] + c[2][k] * c[2][k];
    total += norm2[k];
    const double side = supportSide(std::uint32_t(k), n);
    score[k] = std::sqrt(norm2[k]) * (selection == Selection::AreaWeighted ? side * side : 1.0);
  }
  std::vector<std::uint32_t> order(count);
  std::iota(order.begin(), order.end(), 0u);
  const std::size_t keep = std::min(terms, count);
  std::partial_sort(order.begin(), order.begin() + std::ptrdiff_t(keep), order.end(),
                    [&](std::uint32_t a, std::uint32_t b) {
                      return score[a] != score[b] ? score[a] > score[b] : a < b;
                    });
  order.resize(keep);
  std::sort(order.begin(), order.end());
  HaarLight light;
  light.resolution = n;
  double kept = 0;
  for (std::uint32_t k : order) {
    light.index.push_back(k);
    light.value.push_back(Rgb(float(c[0][k]), float(c[1][k]), float(c[2][k])));
    kept += norm2[k];
  }
  light.energyKept = total > 0 ? std::min(1.0, kept / total) : 1.0;
  return light;
}

UnshadowedPart unshadowedPart(const envmap::Environment& env, const std::vector<Rgb>& means,
                              int n, const Mat3d& rotation) {
  return unshadowedPart(envmap::projectEnvironment(env, kUnshadowedBands), means, n, rotation);
}

UnshadowedPart unshadowedPart(const sh::RgbSh& environmentSh, const std::vector<Rgb>& means, int n,
                              const Mat3d& rotation) {
  checkResolution(n, "Haar lighting");
  PRT_CHECK(means.size() == coefficientCount(n), "texel means of the cube");
  if (environmentSh.bands != kUnshadowedBands)
    throw Error("Haar lighting: the environment's SH has " + std::to_string(environmentSh.bands) +
                " bands, the unshadowed part " + std::to_string(kUnshadowedBands));
  UnshadowedPart out;
  out.sh = sh::Rotation(kUnshadowedBands, rotation).apply(environmentSh);
  const std::vector<double> omega = envmap::cubeTexelSolidAngles(n);
  const auto power = [&](std::size_t k) {
    const Rgb& c = means[k];
    return (0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z) * omega[k % omega.size()];
  };
  std::vector<std::uint32_t> order(means.size());
  std::iota(order.begin(), order.end(), 0u);
  const std::size_t keep = std::min(kBrightTexels, order.size());
  std::partial_sort(order.begin(), order.begin() + std::ptrdiff_t(keep), order.end(),
                    [&](std::uint32_t a, std::uint32_t b) {
                      const double x = power(a), y = power(b);
                      return x != y ? x > y : a < b;
                    });
  constexpr int kCoeffs = kUnshadowedBands * kUnshadowedBands;
  for (std::size_t i = 0; i < keep; ++i) {
    const std::uint32_t j = order[i];
    if (!(power(j) > 0)) break;
    const Rgb l = means[j];
    out.bright.push_back({j, l});
    const std::vector<double> patch = texelPatchSh(j, n);
    for (int k = 0; k < kCoeffs; ++k)
      out.sh.c[std::size_t(k)] -= l * float(patch[std::size_t(k)]);
  }
  return out;
}

std::vector<double> texelPatchSh(std::uint32_t texel, int n) {
  // Σ over the texel's 16 × 16 midpoints of Y(d̂) dA/|d|³.
  constexpr int kSub = 16, kCoeffs = kUnshadowedBands * kUnshadowedBands;
  std::vector<double> y(kCoeffs), patch(kCoeffs, 0.0);
  const CubeTexel t = cubeTexel(texel, n);
  const double step = 2.0 / n / kSub;
  for (int b = 0; b < kSub; ++b)
    for (int a = 0; a < kSub; ++a) {
      const double s = -1.0 + 2.0 * t.x / n + (a + 0.5) * step;
      const double tt = -1.0 + 2.0 * t.y / n + (b + 0.5) * step;
      const Vec3d d = envmap::cubeFaceDirection(t.face, s, tt);
      const double len = length(d);
      sh::eval(kUnshadowedBands, d / len, y.data());
      const double w = step * step / (len * len * len);
      for (int k = 0; k < kCoeffs; ++k) patch[std::size_t(k)] += y[std::size_t(k)] * w;
    }
  return patch;
}

sh::RgbSh fullSh(const HaarLight& light) {
  PRT_CHECK(light.unshadowed.bands == kUnshadowedBands, "the light's SH");
  sh::RgbSh out = light.unshadowed;
  constexpr int kCoeffs = kUnshadowedBands * kUnshadowedBands;
  for (const BrightTexel& b : light.bright) {
    const std::vector<double> patch = texelPatchSh(b.texel, light.resolution);
    for (int k = 0; k < kCoeffs; ++k)
      out.c[std::size_t(k)] += b.radiance * float(patch[std::size_t(k)]);
  }
  return out;
}

HaarLight projectLight(const envmap::Environment& env, int n, std::size_t terms,
                       const Mat3d& rotation, Selection selection) {
  const std::vector<Rgb> means = cubeMeans(env, n, rotation);
  HaarLight light = approximate(means, n, terms, selection);
  UnshadowedPart part = unshadowedPart(env, means, n, rotation);
  light.unshadowed = std::move(part.sh);
  light.bright = std::move(part.bright);
  return light;
}

}  // namespace prt::haar
