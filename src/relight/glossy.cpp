#include "prt/relight/glossy.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/sh/convolve.hpp"
#include "prt/sh/sh.hpp"

namespace prt::relight {

PreparedMaterial prepareMaterial(const Material& material, int bands) {
  sh::checkBands(bands);
  PreparedMaterial p;
  p.bands = bands;
  p.specular = material.specular;
  p.kd = material.diffuse;
  const std::vector<double> a = sh::clampedCosineKernel(bands);
  const std::vector<double> g =
      material.glossy() ? material.lobe.zonal(bands) : std::vector<double>{};
  p.diffuse.resize(static_cast<std::size_t>(bands * bands));
  if (!g.empty()) p.glossy.resize(p.diffuse.size());
  for (int l = 0; l < bands; ++l)
    for (int i = l * l; i < (l + 1) * (l + 1); ++i) {
      p.diffuse[i] = static_cast<float>(a[l] / kPi);
      if (!g.empty()) p.glossy[i] = static_cast<float>(g[l]);
    }
  return p;
}

namespace {

// u += d_i · row, w += g_i · row over the matrix's rows: the whole per-vertex cost. Compiled for
// AVX2+FMA and for the baseline, picked at load time (GCC function multi-versioning).
// (GCC only: clang 14, used by the fuzz build, emits no symbol for multiversioned functions.)
#if defined(__GNUC__) && !defined(__clang__)
#define PRT_GLOSSY_CLONES [[gnu::target_clones("arch=haswell", "default")]]
#else
#define PRT_GLOSSY_CLONES
#endif
PRT_GLOSSY_CLONES void accumulateRows(const float* m, std::size_t rows, std::size_t rowStride,
                                      std::size_t width, const float* d, const float* g, float* u,
                                      float* w) {
  std::fill_n(u, width, 0.0f);
  if (g) std::fill_n(w, width, 0.0f);
  for (std::size_t i = 0; i < rows; ++i) {
    const float* row = m + i * rowStride;
    const float di = d[i];
    if (g) {
      const float gi = g[i];
      for (std::size_t j = 0; j < width; ++j) {
        u[j] += di * row[j];
        w[j] += gi * row[j];
      }
    } else {
      for (std::size_t j = 0; j < width; ++j) u[j] += di * row[j];
    }
  }
}

}  // namespace

void relightGlossy(const TransferField& transfer, const PreparedLight& light,
                   const PreparedMaterial& material, const GlossyView& view,
                   std::span<const Rgb> albedo, std::span<Rgb> out) {
  const std::size_t nv = transfer.vertexCount;
  if (!transfer.isMatrix()) throw Error("relight: glossy relighting needs matrix transfer");
  if (transfer.channels != 1 && transfer.channels != 3)
    throw Error("relight: transfer has " + std::to_string(transfer.channels) + " channels");
  if (transfer.data.size() != nv * transfer.stride())
    throw Error("relight: transfer holds " + std::to_string(transfer.data.size()) +
                " floats, expected " + std::to_string(nv * transfer.stride()));
  if (light.bands < 1 || light.bands > transfer.bands)
    throw Error("relight: prepared light has " + std::to_string(light.bands) +
                " bands, transfer has " + std::to_string(transfer.bands));
  if (material.bands != transfer.bands)
    throw Error("relight: material prepared for " + std::to_string(material.bands) +
                " bands, transfer has " + std::to_string(transfer.bands));
  if (view.positions.size() != nv || view.normals.size() != nv || out.size() != nv)
    throw Error("relight: positions, normals and output must hold one value per vertex (" +
                std::to_string(nv) + ")");
  if (!albedo.empty() && albedo.size() != 1 && albedo.size() != nv)
    throw Error("relight: " + std::to_string(albedo.size()) + " albedo values for " +
                std::to_string(nv) + " vertices (expected one per vertex, one, or none)");

  const int bands = transfer.bands;
  const std::size_t nB = static_cast<std::size_t>(bands * bands);
  const std::size_t nb = static_cast<std::size_t>(light.bands * light.bands);
  const std::size_t ch = static_cast<std::size_t>(transfer.channels);
  const std::size_t width = nb * ch, rowStride = nB * ch;
  const bool glossy = !material.glossy.empty();
  const float* L = light.interleaved.data();  // (r, g, b) per coefficient
  const float* M = transfer.data.data();
  const std::size_t grain = std::max<std::size_t>(16, 16384 / (nB * nB * ch));

  parallelFor(nv, grain, [&](std::size_t begin, std::size_t end) {
    std::vector<float> yn(nB), yr(nB), d(nB), g(glossy ? nB : 0), u(width), w(glossy ? width : 0);
    for (std::size_t v = begin; v < end; ++v) {
      const Vec3f n = view.normals[v];
      sh::eval(bands, n, yn.data());
      for (std::size_t i = 0; i < nB; ++i) d[i] = material.diffuse[i] * yn[i];
      if (glossy) {
        const Vec3f toEye = view.eye - view.positions[v];
        const float len = length(toEye);
        const Vec3f vdir = len > 0 ? toEye / len : n;
        sh::eval(bands, reflectView(n, vdir), yr.data());
        for (std::size_t i = 0; i < nB; ++i) g[i] = material.glossy[i] * yr[i];
      }
      accumulateRows(M + v * transfer.stride(), nB, rowStride, width, d.data(),
                     glossy ? g.data() : nullptr, u.data(), w.data());
      Rgb diff(0.0f), spec(0.0f);
      for (std::size_t j = 0; j < nb; ++j)
        for (std::size_t c = 0; c < 3; ++c) {
          const std::size_t k = j * ch + (ch == 1 ? 0 : c);
          diff[c] += u[k] * L[3 * j + c];
          if (glossy) spec[c] += w[k] * L[3 * j + c];
        }
      const Rgb kd = material.kd                      ? *material.kd
                     : albedo.size() == nv && nv != 1 ? albedo[v]
                     : albedo.size() == 1             ? albedo[0]
                                                      : Rgb(1.0f);
      out[v] = kd * diff + material.specular * spec;
    }
  });
}

RelightInfo relightGlossy(const TransferField& transfer, const sh::RgbSh& light,
                          const Material& material, const GlossyView& view,
                          std::span<const Rgb> albedo, std::span<Rgb> out, const Mat3d& rotation) {
  RelightInfo info;
  const int bands = std::min(light.bands, transfer.bands);
  const sh::Rotation rot(bands, rotation);
  const PreparedLight p = prepareLight(light, transfer.bands, &rot, &info);
  relightGlossy(transfer, p, prepareMaterial(material, transfer.bands), view, albedo, out);
  return info;
}

}  // namespace prt::relight
