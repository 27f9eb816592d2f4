// Projection onto SH: exact product quadrature for callables, fixed-order double accumulation
// for weighted samples.
#include "prt/sh/project.hpp"

#include <cmath>
#include <string>

#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/core/quadrature.hpp"

namespace prt::sh {

SphereQuadrature gaussLegendreSphere(int n) {
  const QuadratureRule rule = gaussLegendre(n);
  const std::vector<double>& z = rule.nodes;
  const std::vector<double>& w = rule.weights;
  // φ: 2n equally spaced nodes, offset half a step, each 2π / (2n).
  const int nphi = 2 * n;
  SphereQuadrature q;
  q.dirs.reserve(static_cast<std::size_t>(n) * nphi);
  q.weights.reserve(static_cast<std::size_t>(n) * nphi);
  for (int i = 0; i < n; ++i) {
    const double s = std::sqrt(std::fmax(0.0, 1 - z[i] * z[i]));
    for (int j = 0; j < nphi; ++j) {
      const double phi = 2 * kPi * (j + 0.5) / nphi;
      q.dirs.push_back({s * std::cos(phi), s * std::sin(phi), z[i]});
      q.weights.push_back(w[i] * 2 * kPi / nphi);
    }
  }
  return q;
}

namespace {
int defaultN(int bands, int quadratureN) {
  if (quadratureN < 0)
    throw Error("quadrature order must be >= 0, got " + std::to_string(quadratureN));
  return quadratureN > 0 ? quadratureN : bands + 8;
}
}  // namespace

ShCoeffs projectFunction(int bands, const std::function<double(const Vec3d&)>& f, int quadratureN) {
  checkBands(bands);
  const SphereQuadrature q = gaussLegendreSphere(defaultN(bands, quadratureN));
  const int n = bands * bands;
  std::vector<double> acc(n, 0.0), y(n);
  for (std::size_t k = 0; k < q.dirs.size(); ++k) {
    eval(bands, q.dirs[k], y.data());
    const double v = f(q.dirs[k]) * q.weights[k];
    for (int i = 0; i < n; ++i) acc[i] += v * y[i];
  }
  ShCoeffs out(bands);
  for (int i = 0; i < n; ++i) out.c[i] = float(acc[i]);
  return out;
}

RgbSh projectFunctionRgb(int bands, const std::function<Rgbd(const Vec3d&)>& f, int quadratureN) {
  checkBands(bands);
  const SphereQuadrature q = gaussLegendreSphere(defaultN(bands, quadratureN));
  const int n = bands * bands;
  std::vector<Rgbd> acc(n, Rgbd(0.0));
  std::vector<double> y(n);
  for (std::size_t k = 0; k < q.dirs.size(); ++k) {
    eval(bands, q.dirs[k], y.data());
    const Rgbd v = f(q.dirs[k]) * q.weights[k];
    for (int i = 0; i < n; ++i) acc[i] += v * y[i];
  }
  RgbSh out(bands);
  for (int i = 0; i < n; ++i) out.c[i] = Rgb(acc[i]);
  return out;
}

RgbSh projectSamples(int bands, std::span<const Vec3f> dirs, std::span<const Rgb> values,
                     std::span<const float> weights) {
  checkBands(bands);
  if (dirs.size() != values.size() || dirs.size() != weights.size())
    throw Error("projectSamples: " + std::to_string(dirs.size()) + " directions, " +
                std::to_string(values.size()) + " values and " + std::to_string(weights.size()) +
                " weights (must match)");
  const std::size_t n = static_cast<std::size_t>(bands) * bands;
  // Fixed chunks of samples, each summed in order, partials combined in chunk order: the result
  // is bit-identical for any thread count.
  constexpr std::size_t kChunk = 4096;
  std::vector<Rgbd> total = parallelReduce(
      dirs.size(), kChunk, std::vector<Rgbd>(n, Rgbd(0.0)),
      [&](std::size_t b, std::size_t e, std::vector<Rgbd>& acc) {
        float y[kMaxBands * kMaxBands];
        for (std::size_t k = b; k < e; ++k) {
          eval(bands, dirs[k], y);
          const Rgbd v = Rgbd(values[k]) * double(weights[k]);
          for (std::size_t i = 0; i < n; ++i) acc[i] += v * double(y[i]);
        }
      },
      [](std::vector<Rgbd>& t, const std::vector<Rgbd>& p) {
        for (std::size_t i = 0; i < t.size(); ++i) t[i] += p[i];
      });
  RgbSh out(bands);
  for (std::size_t i = 0; i < n; ++i) out.c[i] = Rgb(total[i]);
  return out;
}

}  // namespace prt::sh
