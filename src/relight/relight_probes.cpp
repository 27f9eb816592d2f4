#include "prt/relight/relight_probes.hpp"

#include <algorithm>
#include <cmath>

#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/sh/convolve.hpp"

namespace prt::relight {

ProbeLighting relightProbes(const Transfer& transfer, const sh::RgbSh& light) {
  if (transfer.domain() != TransferDomain::Probes)
    throw Error("relight probes: the transfer is over " + std::string(toString(transfer.domain())) +
                ", not probes");
  const ProbeGrid& grid = transfer.shape().probes;
  if (transfer.rows().first != 0 || transfer.rowCount() != grid.probes())
    throw Error("relight probes: the transfer covers probes " +
                std::to_string(transfer.rows().first) + ".." +
                std::to_string(transfer.rows().end()) + " of " + std::to_string(grid.probes()) +
                " (merge the pieces first)");
  ProbeLighting out;
  out.grid = grid;
  out.bands = std::min(light.bands, transfer.bands());
  const int channels = transfer.channels();
  out.coefficients.assign(grid.probes() * out.coeffs(), Rgb(0.0f));
  parallelFor(grid.probes(), 64, [&](std::size_t begin, std::size_t end) {
    std::vector<float> row(transfer.stride());
    for (std::size_t p = begin; p < end; ++p) {
      const float* m = row.data();
      if (transfer.compressed())
        transfer.reconstructRow(p, row.data());
      else
        m = transfer.row(p);
      relightProbe(m, transfer.bands(), channels, light, out.bands,
                   out.coefficients.data() + p * out.coeffs());
    }
  });
  return out;
}

void relightProbe(const float* matrix, int transferBands, int channels, const sh::RgbSh& light,
                  int bands, Rgb* out) {
  PRT_CHECK(bands <= transferBands && bands <= light.bands, "relightProbe: bands beyond the data");
  const std::size_t b2 = std::size_t(bands) * std::size_t(bands);
  const std::size_t n = std::size_t(transferBands) * std::size_t(transferBands);
  for (std::size_t i = 0; i < b2; ++i) {
    Rgb acc(0.0f);
    for (std::size_t j = 0; j < b2; ++j) {
      const float* e = matrix + (i * n + j) * std::size_t(channels);
      const Rgb& l = light.c[j];
      acc += channels == 1 ? l * e[0] : Rgb(e[0] * l.x, e[1] * l.y, e[2] * l.z);
    }
    out[i] = acc;
  }
}

void sampleProbes(const ProbeLighting& lighting, const Vec3f& point, Rgb* out) {
  const ProbeGrid& g = lighting.grid;
  const std::size_t b2 = lighting.coeffs();
  int lo[3];
  float t[3];
  for (int a = 0; a < 3; ++a) {
    const float u = std::clamp((point[a] - g.origin[a]) / g.spacing[a], 0.0f,
                               float(g.count[a] - 1));
    lo[a] = std::min(int(std::floor(u)), std::max(g.count[a] - 2, 0));
    t[a] = g.count[a] > 1 ? u - float(lo[a]) : 0.0f;
  }
  std::fill_n(out, b2, Rgb(0.0f));
  for (int corner = 0; corner < 8; ++corner) {
    float w = 1.0f;
    int c[3];
    for (int a = 0; a < 3; ++a) {
      const int up = (corner >> a) & 1;
      w *= up ? t[a] : 1.0f - t[a];
      c[a] = std::min(lo[a] + up, g.count[a] - 1);
    }
    if (w == 0.0f) continue;
    const Rgb* p = lighting.probe(g.row(c[0], c[1], c[2]));
    for (std::size_t i = 0; i < b2; ++i) out[i] += p[i] * w;
  }
}

Rgb shadeDiffuse(const Rgb* incident, int bands, const Vec3f& normal, const Rgb& albedo) {
  const std::vector<double> a = sh::clampedCosineKernel(bands);
  std::vector<float> y(std::size_t(bands) * std::size_t(bands));
  sh::eval(bands, normal, y.data());
  Rgb e(0.0f);
  for (int l = 0; l < bands; ++l)
    for (int m = -l; m <= l; ++m) {
      const int i = l * l + l + m;
      e += incident[i] * float(a[std::size_t(l)] * y[std::size_t(i)]);
    }
  return albedo * e * float(1.0 / kPi);
}

}  // namespace prt::relight
