#include "prt/envmap/project.hpp"

#include <array>
#include <cmath>
#include <utility>

#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/envmap/analytic.hpp"
#include "prt/sh/sh_fixed.hpp"

namespace prt::envmap {

namespace {

constexpr std::size_t kChunk = 1024;

/// A valid but extremely bright environment (RGBE reaches 1.7e38) overflows the float sums to
/// inf; say so instead of handing on coefficients that no later stage can use.
void checkFiniteProjection(const sh::RgbSh& c, const std::string& source) {
  for (std::size_t i = 0; i < c.c.size(); ++i)
    if (!isFinite(c.c[i]))
      throw Error(source, "projecting the environment onto SH overflowed: coefficient " +
                              std::to_string(i) +
                              " is not finite (radiance too bright for 32-bit floats; scale the "
                              "image down)");
}

// Accumulates texels [lo, hi) into out (3·B² doubles, RGB interleaved per coefficient).
template <int B, typename TexelFn>
void accumulate(const TexelFn& texelAt, std::size_t lo, std::size_t hi, double* out) {
  constexpr int n = B * B;
  float ar[n] = {}, ag[n] = {}, ab[n] = {};
  float y[n];
  for (std::size_t k = lo; k < hi; ++k) {
    const Texel t = texelAt(k);
    if (t.solidAngle == 0.0f) continue;
    sh::evalFixed<B>(t.direction.x, t.direction.y, t.direction.z, y);
    const float r = t.radiance.x * t.solidAngle, g = t.radiance.y * t.solidAngle,
                b = t.radiance.z * t.solidAngle;
    for (int i = 0; i < n; ++i) {
      ar[i] += y[i] * r;
      ag[i] += y[i] * g;
      ab[i] += y[i] * b;
    }
  }
  for (int i = 0; i < n; ++i) {
    out[3 * i] += ar[i];
    out[3 * i + 1] += ag[i];
    out[3 * i + 2] += ab[i];
  }
}

template <typename TexelFn>
using AccumulateFn = void (*)(const TexelFn&, std::size_t, std::size_t, double*);

template <typename TexelFn, int... I>
constexpr auto makeTable(std::integer_sequence<int, I...>) {
  return std::array<AccumulateFn<TexelFn>, sizeof...(I)>{&accumulate<I + 1, TexelFn>...};
}

template <typename TexelFn>
sh::RgbSh projectTexels(int bands, std::size_t count, const TexelFn& texelAt,
                        const ProgressFn& progress, const std::string& source = "") {
  sh::checkBands(bands);
  static constexpr auto table =
      makeTable<TexelFn>(std::make_integer_sequence<int, sh::kMaxBands>{});
  const auto fn = table[bands - 1];
  const std::size_t n = static_cast<std::size_t>(bands) * bands;
  Progress prog(progress, count);
  std::vector<double> total = parallelReduce(
      count, kChunk, std::vector<double>(3 * n, 0.0),
      [&](std::size_t lo, std::size_t hi, std::vector<double>& partial) {
        if (prog.cancelled()) return;
        fn(texelAt, lo, hi, partial.data());
        prog.advance(hi - lo);
      },
      [](std::vector<double>& acc, const std::vector<double>& p) {
        for (std::size_t i = 0; i < acc.size(); ++i) acc[i] += p[i];
      });
  prog.check();
  sh::RgbSh out(bands);
  for (std::size_t i = 0; i < n; ++i)
    out.c[i] = {static_cast<float>(total[3 * i]), static_cast<float>(total[3 * i + 1]),
                static_cast<float>(total[3 * i + 2])};
  checkFiniteProjection(out, source);
  return out;
}

}  // namespace

sh::RgbSh projectEnvironment(const Environment& env, int bands, const ProgressFn& progress) {
  sh::checkBands(bands);
  if (env.kind() == Environment::Kind::Analytic) {
    const Environment smooth = env.smoothPart();
    sh::RgbSh out = projectEnvironment(smooth, bands, progress);
    for (const Cap& cap : env.caps()) {
      const sh::RgbSh c = capSh(bands, cap);
      for (std::size_t i = 0; i < out.c.size(); ++i) out.c[i] += c.c[i];
    }
    checkFiniteProjection(out, env.source());
    return out;
  }
  auto texelAt = [&env](std::size_t k) { return env.texel(k); };
  return projectTexels(bands, env.texelCount(), texelAt, progress, env.source());
}

sh::RgbSh projectGames202Faces(const std::array<image::Image, 6>& faces, int bands,
                               const ProgressFn& progress) {
  static constexpr float frames[6][3][3] = {
      {{0, 0, 1}, {0, -1, 0}, {-1, 0, 0}},  {{0, 0, 1}, {0, -1, 0}, {1, 0, 0}},
      {{1, 0, 0}, {0, 0, -1}, {0, -1, 0}},  {{1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
      {{-1, 0, 0}, {0, -1, 0}, {0, 0, -1}}, {{1, 0, 0}, {0, -1, 0}, {0, 0, 1}}};
  const int w = faces[0].width, h = faces[0].height;
  for (const auto& f : faces)
    PRT_CHECK(f.width == w && f.height == h && w == h && w > 0, "faces differ");
  const std::vector<double> solid = cubeTexelSolidAngles(w);
  const std::size_t n2 = faces[0].size();
  auto texelAt = [&](std::size_t k) {
    const std::size_t face = k / n2, r = k % n2;
    const int y = static_cast<int>(r / w), x = static_cast<int>(r % w);
    const float u = 2.0f * ((x + 0.5f) / w) - 1.0f, v = 2.0f * ((y + 0.5f) / h) - 1.0f;
    const auto& F = frames[face];
    const Vec3f d =
        normalize(Vec3f(u * F[0][0] + v * F[1][0] + F[2][0], u * F[0][1] + v * F[1][1] + F[2][1],
                        u * F[0][2] + v * F[1][2] + F[2][2]));
    return Texel{d, static_cast<float>(solid[r]), faces[face].pixels[r]};
  };
  return projectTexels(bands, 6 * n2, texelAt, progress);
}

}  // namespace prt::envmap
