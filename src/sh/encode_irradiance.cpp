// Irradiance encodings engines store: l2, deringed l2, l1 and its non-negative forms, ZH3
// (sh/irradiance_encoding.hpp names the papers).
#include "prt/sh/encode_irradiance.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "prt/core/error.hpp"
#include "prt/core/luminance.hpp"
#include "prt/sh/convolve.hpp"
#include "prt/sh/project.hpp"

namespace prt::sh {

namespace {

constexpr double kY1 = 0.48860251190291992;   // √(3/4π): |Y₁ₘ| along its axis
constexpr double kY00 = 0.28209479177387814;  // 1/√(4π)

/// Y₂₀ about an axis at cos θ = t: √(5/16π) (3t² − 1).
double zonalY20(double t) {
  return 0.31539156525252005 * (3 * t * t - 1);
}

struct Names {
  IrradianceEncoding e;
  const char* name;
};
constexpr Names kNames[] = {{IrradianceEncoding::L2, "l2"},
                            {IrradianceEncoding::L2Deringed, "l2-deringed"},
                            {IrradianceEncoding::L1, "l1"},
                            {IrradianceEncoding::L1Windowed, "l1-windowed"},
                            {IrradianceEncoding::L1Geomerics, "l1-geomerics"},
                            {IrradianceEncoding::ZH3, "zh3"},
                            {IrradianceEncoding::ZH3Shared, "zh3-shared"},
                            {IrradianceEncoding::ZH3Optimal, "zh3-optimal"},
                            {IrradianceEncoding::ZH3Hallucinated, "zh3-hallucinated"}};

Vec3d channelBandOne(const std::vector<Rgbd>& c, int ch) {
  return bandOneVector(c[1][ch], c[2][ch], c[3][ch]);
}

/// The zonal axis: the luminance's band-1 direction (+Z when it has none).
Vec3d luminanceAxis(const std::vector<Rgbd>& c) {
  const Vec3d v = bandOneVector(luminanceOf(c[1]), luminanceOf(c[2]), luminanceOf(c[3]));
  const double len = length(v);
  return len > 0 ? v / len : Vec3d(0, 0, 1);
}

/// z(a) = Σ_m L₂ₘ Y₂ₘ(a) per channel: band 2 of `l` projected on the zonal harmonic about `a`,
/// up to the constant √(4π/5) (the addition theorem: Y₂₀(a·ω) = √(4π/5) Σ_m Y₂ₘ(a) Y₂ₘ(ω)).
Rgbd zonalProjection(const std::vector<Rgbd>& l, const Vec3d& a) {
  double y[9];
  eval(3, a, y);
  Rgbd z(0.0);
  for (int m = 4; m < 9; ++m) z += l[m] * y[m];
  return z;
}

/// The maximum over the sphere of a score of the axis (zh3-optimal's and zh3-shared's quartics
/// in a), by a Fibonacci search of 2,000 directions (neighbours ~4.6° apart) refined by shrinking
/// steps towards the best neighbour. Axis and −axis are the same zonal harmonic.
template <class Score>
Vec3d bestAxis(Score score) {
  constexpr int kSearch = 2000;
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  Vec3d best(0, 0, 1);
  double bestE = -1;
  for (int i = 0; i < kSearch; ++i) {
    const double z = 1 - (i + 0.5) / kSearch, r = std::sqrt(1 - z * z), phi = golden * i;
    const Vec3d a(r * std::cos(phi), r * std::sin(phi), z);  // a hemisphere suffices
    const double e = score(a);
    if (e > bestE) bestE = e, best = a;
  }
  for (double step = 0.05; step > 1e-7; step *= 0.5) {
    Vec3d t, b;
    orthonormalBasis(best, t, b);
    bool moved = true;
    while (moved) {
      moved = false;
      for (const Vec3d& d : {t, -t, b, -b}) {
        const Vec3d a = normalize(best + d * step);
        const double e = score(a);
        if (e > bestE) bestE = e, best = a, moved = true;
      }
    }
  }
  return best;
}

/// zh3-optimal's axis: the one that holds the most of band 2 summed over the channels, the
/// maximum of Σ_c z_c(a)² (what the zonal harmonic about a holds, up to the constant 4π/5).
Vec3d bestZonalAxis(const std::vector<Rgbd>& l) {
  return bestAxis([&](const Vec3d& a) {
    const Rgbd z = zonalProjection(l, a);
    return dot(z, z);
  });
}

/// zh3-shared's axis for the chroma `w` (the channels' L₀₀): the maximum of (Σ_c w_c z_c(a))²,
/// which is what the least-squares zonal term s w Y₂₀(a·ω) removes of band 2, times |w|² 5/4π.
Vec3d bestSharedAxis(const std::vector<Rgbd>& l, const Rgbd& w) {
  return bestAxis([&](const Vec3d& a) {
    const double p = dot(zonalProjection(l, a), w);
    return p * p;
  });
}

/// Hazel's (Geomerics 2014) non-negative reconstruction of one channel from its mean E₀ and
/// band-1 vector d (E_l1(n) = E₀ + d·n): with s = min(|d| / 2E₀, 1), p = 1 + 2s,
/// a = (1 − s)/(1 + s) and q = (1 + d̂·n)/2, E = E₀ (a + (1 − a)(p + 1) q^p). Its mean is E₀
/// (∫ (p + 1) q^p = 4π); its band 1 is d's exactly at s → 0 and s = 1 (a directional light).
double geomerics(double e0, const Vec3d& d, const Vec3d& n) {
  const double len = length(d);
  if (e0 <= 0 || len == 0) return e0 + dot(d, n);
  const double s = std::min(len / (2 * e0), 1.0);
  const double p = 1 + 2 * s, a = (1 - s) / (1 + s);
  const double q = 0.5 * (1 + dot(d, n) / len);
  return e0 * (a + (1 - a) * (p + 1) * std::pow(std::max(q, 0.0), p));
}

}  // namespace

const char* toString(IrradianceEncoding e) {
  for (const Names& n : kNames)
    if (n.e == e) return n.name;
  return "?";
}

IrradianceEncoding parseIrradianceEncoding(const std::string& name) {
  for (const Names& n : kNames)
    if (name == n.name) return n.e;
  std::string all;
  for (std::size_t i = 0; i < std::size(kNames); ++i)
    all += std::string(i == 0 ? "" : i + 1 == std::size(kNames) ? " or " : ", ") + kNames[i].name;
  throw Error("encoding must be " + all + ", got '" + name + "'");
}

int storedNumbers(IrradianceEncoding e) {
  switch (e) {
    case IrradianceEncoding::L2:
    case IrradianceEncoding::L2Deringed:
      return 27;
    case IrradianceEncoding::ZH3:
    case IrradianceEncoding::ZH3Shared:
      return 15;
    case IrradianceEncoding::ZH3Optimal:
      return 17;
    default:
      return 12;
  }
}

Vec3d bandOneVector(double cm1, double c0, double cp1) {
  return Vec3d(-cp1, -cm1, c0);
}

EncodedIrradiance encodeIrradiance(const RgbSh& radiance, IrradianceEncoding encoding) {
  checkBands(radiance.bands);
  // The radiance's bands 0..2 (what the light lacks is zero), and their irradiance SH.
  std::vector<Rgbd> l(9, Rgbd(0.0));
  RgbSh e(3);
  for (int i = 0; i < std::min(9, radiance.bands * radiance.bands); ++i) {
    l[i] = Rgbd(radiance.c[i]);
    e.c[i] = radiance.c[i];
  }
  convolveZonal(e, clampedCosineKernel(3));
  EncodedIrradiance out;
  out.encoding = encoding;
  if (encoding == IrradianceEncoding::L2Deringed) dering(e);
  out.sh.resize(shRows(encoding));
  for (std::size_t i = 0; i < out.sh.size(); ++i) out.sh[i] = Rgbd(e.c[i]);
  if (encoding == IrradianceEncoding::L1Windowed) {
    // E(n) = E₀ + d·n has its minimum E₀ − |d| at n = −d̂: scaling band 1 by min(1, E₀/|d|)
    // is the mildest window that leaves it non-negative (zero where E₀ ≤ 0: no window can).
    for (int ch = 0; ch < 3; ++ch) {
      const double e0 = out.sh[0][ch] * kY00, d = kY1 * length(channelBandOne(out.sh, ch));
      const double w = d <= std::max(e0, 0.0) ? 1.0 : std::max(e0, 0.0) / d;
      for (int i = 1; i < 4; ++i) out.sh[i][ch] *= w;
    }
  }
  if (isZonal(encoding)) {
    // The zonal coefficient is made from the radiance's bands, then convolved.
    const double lambda2 = clampedCosineKernel(3)[2];
    if (encoding == IrradianceEncoding::ZH3Shared) {
      // One zonal number s shared in proportion to the channels' L₀₀, about the axis where
      // that colour holds the most of band 2: s = Σ_c L₀₀,c ẑ_c / Σ_c L₀₀,c² (least squares),
      // ẑ = √(4π/5) z(a). No L₀₀ (an unlit texel): nothing to share, the luminance axis kept.
      const Rgbd w = l[0];
      const double w2 = dot(w, w);
      out.axis = w2 > 0 ? bestSharedAxis(l, w) : luminanceAxis(l);
      const double s =
          w2 > 0 ? std::sqrt(4 * kPi / 5) * dot(zonalProjection(l, out.axis), w) / w2 : 0;
      out.zonal = w * (s * lambda2);
    } else if (encoding != IrradianceEncoding::ZH3Hallucinated) {
      // The projection of band 2 on the zonal harmonic about the axis, z = √(4π/5) Σ_m L₂ₘ
      // Y₂ₘ(a): the best one number along a fixed axis can hold of band 2 (least squares).
      out.axis = encoding == IrradianceEncoding::ZH3Optimal ? bestZonalAxis(l) : luminanceAxis(l);
      out.zonal = zonalProjection(l, out.axis) * (std::sqrt(4 * kPi / 5) * lambda2);
    } else {
      // Roughton et al. 2024's fit from band 1 alone: r = |L₁·a| / L₀ per channel,
      // z = L₀ (0.08 r + 0.6 r²) (their SHHallucinateZH3Irradiance, RGB form).
      out.axis = luminanceAxis(l);
      for (int ch = 0; ch < 3; ++ch) {
        const double l0 = l[0][ch];
        if (l0 <= 0) continue;
        const double r = std::fabs(dot(channelBandOne(l, ch), out.axis)) / l0;
        out.zonal[ch] = lambda2 * l0 * (0.08 * r + 0.6 * r * r);
      }
    }
  }
  return out;
}

Rgbd evaluate(const EncodedIrradiance& e, const Vec3d& n) {
  if (e.encoding == IrradianceEncoding::L1Geomerics) {
    Rgbd out;
    for (int ch = 0; ch < 3; ++ch)
      out[ch] = geomerics(e.sh[0][ch] * kY00, kY1 * channelBandOne(e.sh, ch), n);
    return out;
  }
  const int bands = shRows(e.encoding) == 9 ? 3 : 2;
  double y[9];
  eval(bands, n, y);
  Rgbd out(0.0);
  for (int i = 0; i < bands * bands; ++i) out += e.sh[i] * y[i];
  if (isZonal(e.encoding)) out += e.zonal * zonalY20(dot(e.axis, n));
  return out;
}

EncodingError encodingError(const RgbSh& radiance, const EncodedIrradiance& encoded) {
  RgbSh reference = radiance;
  convolveZonal(reference, clampedCosineKernel(radiance.bands));
  const int n = radiance.bands * radiance.bands;
  const SphereQuadrature grid = gaussLegendreSphere(std::max(48, 8 * radiance.bands));
  std::vector<double> y(n);
  double err2 = 0, ref2 = 0, negative = 0, minimum = INFINITY;
  for (std::size_t k = 0; k < grid.dirs.size(); ++k) {
    eval(radiance.bands, grid.dirs[k], y.data());
    Rgbd truth(0.0);
    for (int i = 0; i < n; ++i) truth += Rgbd(reference.c[i]) * y[i];
    const Rgbd got = evaluate(encoded, grid.dirs[k]);
    const double w = grid.weights[k];
    err2 += w * dot(got - truth, got - truth);
    ref2 += w * dot(truth, truth);
    const double lo = std::min({got.x, got.y, got.z});
    minimum = std::min(minimum, lo);
    if (lo < 0) negative += w;
  }
  EncodingError r;
  r.relativeRms = ref2 > 0 ? std::sqrt(err2 / ref2) : 0;
  r.negativeShare = negative / (4 * kPi);
  const double rms = std::sqrt(ref2 / (12 * kPi));
  r.relativeMinimum = rms > 0 ? minimum / rms : 0;
  return r;
}

}  // namespace prt::sh
