#include "prt/render/validate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <sstream>

#include "prt/core/error.hpp"
#include "prt/core/json.hpp"
#include "prt/core/parallel.hpp"
#include "prt/core/sampling.hpp"
#include "prt/relight/relight.hpp"
#include "prt/render/metrics.hpp"
#include "prt/sh/convolve.hpp"

namespace prt::render {

std::vector<std::uint32_t> vertexSubset(std::size_t n, std::size_t count, std::uint64_t seed) {
  std::vector<std::uint32_t> all(n);
  std::iota(all.begin(), all.end(), 0u);
  if (count == 0 || count >= n) return all;
  // Partial Fisher–Yates shuffle with a PCG32 stream of `seed`: the first `count` entries are a
  // uniformly random subset.
  Pcg32 rng(deriveSeed(seed, 0x5eb5e7ull));
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t j = i + static_cast<std::size_t>(rng.next() % (n - i));
    std::swap(all[i], all[j]);
  }
  all.resize(count);
  std::sort(all.begin(), all.end());
  return all;
}

namespace {

/// Per-vertex values as a one-row image, so render::metrics applies unchanged.
image::Image row(const std::vector<Rgb>& v) {
  image::Image img(static_cast<int>(v.size()), 1);
  std::copy(v.begin(), v.end(), img.pixels.begin());
  return img;
}

double sumSq(const Rgb& c) {
  return double(c.x) * c.x + double(c.y) * c.y + double(c.z) * c.z;
}

/// The light PRT relights with at b bands: the first b² coefficients of `light`, windowed at b
/// bands as `prt light --bands b --window W` would; `factors` receives the window's per-band
/// factors (1 without one).
sh::RgbSh lightAt(const sh::RgbSh& light, int b, sh::Window window, std::vector<double>& factors) {
  sh::RgbSh lb = light.truncated(b);
  switch (window) {
    case sh::Window::None:
      factors.assign(static_cast<std::size_t>(b), 1.0);
      break;
    case sh::Window::Hanning:
      factors = sh::hanningWindow(b);
      sh::convolveZonal(lb, factors);
      break;
    case sh::Window::Lanczos:
      factors = sh::lanczosWindow(b);
      sh::convolveZonal(lb, factors);
      break;
    case sh::Window::Dering:
      factors = sh::dering(lb).window;
      break;
  }
  return lb;
}

const char* windowName(sh::Window w) {
  switch (w) {
    case sh::Window::Hanning:
      return "hanning";
    case sh::Window::Lanczos:
      return "lanczos";
    case sh::Window::Dering:
      return "dering";
    default:
      return "none";
  }
}

}  // namespace

ValidationReport validate(const Mesh& mesh, const Occluder& occluder, const Transfer& transfer,
                          const BakeRecipe& bake, const envmap::Environment& env,
                          const sh::RgbSh& light, const ValidateSettings& settings,
                          const ProgressFn& progress) {
  const std::size_t nv = mesh.vertexCount();
  if (transfer.rowCount() != nv)
    throw Error(mesh.source, "transfer has " + std::to_string(transfer.rowCount()) +
                                 " vertices, mesh has " + std::to_string(nv) +
                                 " (validation needs a complete bake)");
  if (light.bands < 1 || transfer.bands() < 1) throw Error("light or transfer has no bands");

  ValidationReport rep;
  rep.mode = bake.mode;
  rep.bounces = bake.effectiveBounces();
  rep.transferBands = transfer.bands();
  rep.lightBands = light.bands;
  rep.bands = std::min(transfer.bands(), light.bands);
  if (light.bands != transfer.bands())
    rep.warnings.push_back("light has " + std::to_string(light.bands) + " bands, transfer " +
                           std::to_string(transfer.bands()) + ": validating up to " +
                           std::to_string(rep.bands) + " bands");

  std::vector<int> bands = settings.bandsList;
  if (bands.empty())
    for (int b = 1; b <= rep.bands; ++b) bands.push_back(b);
  std::vector<int> kept;
  for (int b : bands) {
    if (b < 1) throw Error("band count " + std::to_string(b) + " must be at least 1");
    if (b > rep.bands)
      rep.warnings.push_back("skipping " + std::to_string(b) + " bands (only " +
                             std::to_string(rep.bands) + " available)");
    else
      kept.push_back(b);
  }
  std::sort(kept.begin(), kept.end());
  kept.erase(std::unique(kept.begin(), kept.end()), kept.end());
  if (kept.empty())
    throw Error("no band count to validate: asked for more than the " + std::to_string(rep.bands) +
                " bands available");

  // The reference, with the bake's transport.
  ReferenceSettings rs = settings.reference;
  rs.mode = bake.mode;
  rs.bounces = rep.bounces;
  rs.material = bake.material;
  rs.bandLimit.reset();
  // Diffuse (vector) transfer holds the diffuse part only, with diffuse bounces: the reference
  // renders the same, the lobe dropped (kd kept).
  if (!transfer.isMatrix()) {
    rs.material.lobe = {};
    rs.material.specular = Rgb(0.0f);
  }
  rs.vertices = vertexSubset(nv, settings.maxVertices, rs.seed);
  // Glossy (matrix) transfer is seen from an eye.
  const bool glossy = transfer.isMatrix();
  if (glossy && !rs.eye)
    throw Error("validating glossy (matrix) transfer needs the eye the reference and PRT share");

  // The floor's vertices: an even stride of at most settings.floorVertices of the validated
  // ones (an RMS over vertices; a thousand estimate it to a few per cent of itself).
  const std::size_t nMain = rs.vertices.size();
  const std::size_t stride =
      (nMain + settings.floorVertices - 1) / std::max<std::size_t>(settings.floorVertices, 1);
  std::vector<std::uint32_t> floorVerts;
  std::vector<std::size_t> floorIdx;  // positions in the validated vertices
  for (std::size_t i = 0; i < nMain; i += std::max<std::size_t>(stride, 1)) {
    floorVerts.push_back(rs.vertices[i]);
    floorIdx.push_back(i);
  }
  const std::size_t nf = floorVerts.size();

  // Progress: the reference, then the band-limited run over the floor's vertices (about twice
  // the reference's work per vertex), in proportion.
  const double mainShare = double(nMain) / double(nMain + 2 * nf);
  const auto part = [&](double lo, double hi) -> ProgressFn {
    if (!progress) return {};
    return [&progress, lo, hi](double f) { return progress(lo + (hi - lo) * f); };
  };
  rep.reference = renderReference(mesh, occluder, env, rs, part(0.0, mainShare));
  const auto& verts = rep.reference.vertices;
  const std::size_t n = verts.size();
  const std::vector<Rgb>& ref = rep.reference.radiance;
  // A non-finite reference (radiance beyond float range) leaves nothing to compare against:
  // refuse it rather than tabulate inf % and NaN %.
  for (std::size_t i = 0; i < n; ++i)
    if (!isFinite(ref[i]) || !isFinite(rep.reference.stdError[i]))
      throw Error(env.source(), "the reference radiance at vertex " + std::to_string(verts[i]) +
                                    " is not finite (the environment is too bright for 32-bit "
                                    "floats); nothing to validate against");
  double refTotal = 0;
  for (const Rgb& c : ref) refTotal += sumSq(c);
  rep.referenceIsZero = !(refTotal > 0);
  if (rep.referenceIsZero)
    rep.warnings.push_back(
        "the reference is zero at every validated vertex (a black environment?): relative "
        "errors are undefined (n/a)");

  double meanRef = 0;
  for (const Rgb& c : ref) meanRef += (double(c.x) + c.y + c.z) / 3.0;
  meanRef /= std::max<std::size_t>(n, 1);
  const double eps = 1e-2 * meanRef * meanRef + 1e-30;
  // Per vertex and channel, the weight of relative RMSE: 1 / (R_ref² + ε).
  const auto weight = [&](std::size_t i, int c) {
    return 1.0 / (double(ref[i][c]) * ref[i][c] + eps);
  };
  // The reference's noise in the rel RMSE metric: what an exact transfer's rel RMSE would be.
  const auto noiseSq = [&](std::size_t i) {
    double s = 0;
    for (int c = 0; c < 3; ++c)
      s += double(rep.reference.stdError[i][c]) * rep.reference.stdError[i][c] * weight(i, c);
    return s / 3.0;
  };
  double refNoiseSq = 0;
  for (std::size_t i = 0; i < n; ++i) refNoiseSq += noiseSq(i);
  const double refStd = std::sqrt(refNoiseSq / double(std::max<std::size_t>(n, 1)));

  // The b-band lights PRT relights with, and the same as band limits for the floor.
  std::vector<sh::RgbSh> lights;
  BandLimitSettings bl;
  bl.light = light;
  bl.truncateKernel = glossy;
  for (int b : kept) {
    BandLimit lim;
    lim.bands = b;
    lights.push_back(lightAt(light, b, settings.window, lim.window));
    bl.limits.push_back(std::move(lim));
  }
  rep.window = windowName(settings.window);

  // The truncation floor: the error of exact band-limited relighting, e_b − e per floor vertex
  // and band count from the reference's own samples (reference.hpp), in one run for all band
  // counts. Its radiance is the reference's at those vertices, bit for bit.
  ReferenceSettings fr = rs;
  fr.vertices = floorVerts;
  fr.bandLimit = std::move(bl);
  const ReferenceResult floorRun = renderReference(mesh, occluder, env, fr, part(mainShare, 1.0));
  rep.floorMethod = kFloorMethod;
  rep.floorVertices = nf;
  rep.floorRays = floorRun.rays;
  rep.floorSeconds = floorRun.seconds;

  // Vertices whose negative radiance counts: for glossy transfer those facing the eye.
  std::vector<char> counted(n, 1);
  if (glossy)
    for (std::size_t i = 0; i < n; ++i)
      counted[i] = dot(mesh.normals[verts[i]], *rs.eye - mesh.positions[verts[i]]) > 0;
  rep.negativeVertices = static_cast<std::size_t>(std::count(counted.begin(), counted.end(), 1));
  const double negativeBelow = -1e-3 * meanRef;

  std::vector<Rgb> albedo;
  if (mesh.hasAlbedo()) albedo = mesh.albedo;
  std::vector<Rgb> prt(n);
  const std::size_t lanes = kept.size();
  for (std::size_t k = 0; k < lanes; ++k) {
    const int b = kept[k];
    // PRT radiance at b bands (relight rotates the light itself).
    std::vector<Rgb> all(nv);
    relight::relight(transfer.cut(b), lights[k], rs.material,
                     {mesh.positions, mesh.normals, albedo}, rs.eye ? *rs.eye : Vec3f(0.0f), all,
                     rs.rotation);
    for (std::size_t i = 0; i < n; ++i) {
      prt[i] = all[verts[i]];
      if (!isFinite(prt[i]))
        throw Error(settings.bakeName,
                    "the PRT radiance at vertex " + std::to_string(verts[i]) +
                        " is not finite at " + std::to_string(b) +
                        " bands (the transfer times the light overflows 32-bit floats)");
    }

    // floor² = mean over the floor's vertices of Σ_c (x̂² − se²)/(R_ref² + ε)/3 for x = e_b − e:
    // E[x̂²] = x² + se², so its noise does not inflate it. Alongside, per vertex, what the
    // identity rel RMSE² = floor² + noise² leaves over: (R_b − R_ref)² − (x̂² − se²) − se_ref².
    const auto floorSq = [&](Estimate BandLimitedEstimate::*part, std::vector<double>* rest) {
      double sum = 0;
      for (std::size_t j = 0; j < nf; ++j) {
        const std::size_t i = floorIdx[j];
        const Estimate& e = floorRun.bandLimited[j * lanes + k].*part;
        double f = 0, a = 0;
        for (int c = 0; c < 3; ++c) {
          const double x = e.mean[c], se = e.stdError[c], d = double(prt[i][c]) - ref[i][c];
          f += (x * x - se * se) * weight(i, c) / 3.0;
          a += d * d * weight(i, c) / 3.0;
        }
        sum += f;
        if (rest) (*rest)[j] = a - f - noiseSq(i);
      }
      return sum / double(std::max<std::size_t>(nf, 1));
    };
    std::vector<double> rest(nf);
    const double fSq = floorSq(&BandLimitedEstimate::difference, &rest);
    const double lightSq = floorSq(&BandLimitedEstimate::light, nullptr);

    BandRow r;
    r.bands = b;
    r.relRmse = relativeRmse(row(prt), row(ref), eps);
    r.floor = std::sqrt(std::max(0.0, fSq));
    r.lightFloor = std::sqrt(std::max(0.0, lightSq));
    r.refStdErr = refStd;
    double restMean = 0, restVar = 0, errSq = 0, noise = 0;
    for (double x : rest) restMean += x / double(std::max<std::size_t>(nf, 1));
    for (double x : rest) restVar += (x - restMean) * (x - restMean);
    r.unexplainedSq = restMean;
    r.unexplainedSqStdErr = nf > 1 ? std::sqrt(restVar / double(nf - 1) / double(nf)) : 0.0;
    // The same over the floor's vertices only, so that the three share their vertices.
    for (std::size_t j = 0; j < nf; ++j) {
      const std::size_t i = floorIdx[j];
      for (int c = 0; c < 3; ++c) {
        const double d = double(prt[i][c]) - ref[i][c];
        errSq += d * d * weight(i, c) / 3.0;
      }
      noise += noiseSq(i);
    }
    r.explained =
        errSq > 0 ? std::sqrt(std::max(0.0, fSq + noise / double(nf)) / (errSq / double(nf))) : 1.0;
    // What the lobe itself loses at b bands: its zonal energy beyond b (0 for a diffuse surface).
    r.lobeEnergyBeyond = rs.material.glossy() ? rs.material.lobe.energyBeyond(b) : 0.0;
    std::vector<float> err(n);
    double sum = 0, mx = 0, diffEnergy = 0, refEnergy = 0;
    std::size_t negative = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double d2 = sumSq(prt[i] - ref[i]), r2 = sumSq(ref[i]);
      const double e = std::sqrt(d2 / (r2 + 3 * eps));
      err[i] = static_cast<float>(e);
      sum += e;
      mx = std::max(mx, e);
      diffEnergy += d2;
      refEnergy += r2;
      if (counted[i] && std::min({prt[i].x, prt[i].y, prt[i].z}) < negativeBelow) ++negative;
    }
    // Energy-weighted: ‖R_b − R_ref‖ / ‖R_ref‖ over all vertices and channels, i.e. e(p)² weighted
    // by each vertex's share of the reference energy (no ε): bright vertices count most.
    r.energyRel = refEnergy > 0 ? std::sqrt(diffEnergy / refEnergy) : 0.0;
    r.meanRel = sum / std::max<std::size_t>(n, 1);
    r.maxRel = mx;
    r.negativeShare =
        rep.negativeVertices > 0 ? double(negative) / double(rep.negativeVertices) : 0.0;
    if (rep.referenceIsZero) {
      // Relative to nothing: undefined, not 0 % (and not the 1e32 % that ε alone would give).
      const double na = std::numeric_limits<double>::quiet_NaN();
      r.relRmse = r.energyRel = r.meanRel = r.maxRel = r.floor = r.refStdErr = r.explained = na;
      std::fill(err.begin(), err.end(), 0.0f);
    }
    rep.rows.push_back(r);
    rep.vertexError = std::move(err);
  }
  return rep;
}

std::string formatTable(const ValidationReport& rep) {
  std::ostringstream os;
  char line[300];
  const bool lobe = !rep.rows.empty() && rep.rows.front().lobeEnergyBeyond > 0;
  std::snprintf(line, sizeof line, "%5s | %9s | %15s | %12s | %11s | %16s | %11s | %9s | %8s%s\n",
                "bands", "rel RMSE", "energy-weighted", "mean rel err", "max rel err",
                "truncation floor", "ref std err", "explained", "negative",
                lobe ? " | lobe energy > B" : "");
  os << line;
  os << "------+-----------+-----------------+--------------+-------------+------------------+----"
        "---------+-----------+----------"
     << (lobe ? "+------------------" : "") << "\n";
  // A percentage, or "n/a" where it is undefined (a zero reference): never "inf%" or "-nan%".
  const auto cell = [](double v, int width, int digits) {
    char text[48];
    if (std::isfinite(v))
      std::snprintf(text, sizeof text, "%*.*f%%", width, digits, 100 * v);
    else
      std::snprintf(text, sizeof text, "%*s", width + 1, "n/a");
    return std::string(text);
  };
  const auto pct = [&](double v, int width) { return cell(v, width, 3); };
  for (const BandRow& r : rep.rows) {
    std::snprintf(line, sizeof line, "%5d | %s | %s | %s | %s | %s | %s | %s | %7.2f%%", r.bands,
                  pct(r.relRmse, 8).c_str(), pct(r.energyRel, 14).c_str(),
                  pct(r.meanRel, 11).c_str(), pct(r.maxRel, 10).c_str(), pct(r.floor, 15).c_str(),
                  pct(r.refStdErr, 10).c_str(), cell(r.explained, 8, 1).c_str(),
                  100 * r.negativeShare);
    os << line;
    if (lobe) os << " | " << pct(r.lobeEnergyBeyond, 15);
    os << "\n";
  }
  if (rep.referenceIsZero)
    os << "n/a: the reference is zero at every validated vertex; relative errors are undefined\n";
  return os.str();
}

std::string reportJson(const ValidationReport& rep, int indent) {
  Json j;
  j["mode"] = toString(rep.mode);
  j["bounces"] = rep.bounces;
  j["transferBands"] = rep.transferBands;
  j["lightBands"] = rep.lightBands;
  j["vertices"] = rep.reference.vertices.size();
  j["referenceRays"] = rep.reference.rays;
  j["referenceSeconds"] = rep.reference.seconds;
  j["floorMethod"] = rep.floorMethod;
  j["floorVertices"] = rep.floorVertices;
  j["floorRays"] = rep.floorRays;
  j["floorSeconds"] = rep.floorSeconds;
  j["window"] = rep.window;
  j["negativeVertices"] = rep.negativeVertices;
  j["referenceIsZero"] = rep.referenceIsZero;
  j["warnings"] = rep.warnings;
  Json rows = Json::array();
  for (const BandRow& r : rep.rows)
    rows.push_back({{"bands", r.bands},
                    {"relRmse", r.relRmse},
                    {"energyWeightedRelErr", r.energyRel},
                    {"meanRelErr", r.meanRel},
                    {"maxRelErr", r.maxRel},
                    {"truncationFloor", r.floor},
                    {"refStdErr", r.refStdErr},
                    {"lightTruncationFloor", r.lightFloor},
                    {"explained", r.explained},
                    {"unexplainedSq", r.unexplainedSq},
                    {"unexplainedSqStdErr", r.unexplainedSqStdErr},
                    {"negativeShare", r.negativeShare},
                    {"lobeEnergyBeyond", r.lobeEnergyBeyond}});
  j["rows"] = std::move(rows);
  return formatJson(j, indent);
}

std::vector<Rgb> vertexErrorColours(const Mesh& mesh, const ValidationReport& report,
                                    float* scaleOut) {
  const auto& verts = report.reference.vertices;
  if (report.vertexError.size() != verts.size())
    throw Error("vertexErrorColours: the report's errors and vertices differ in number");
  std::vector<float> sorted = report.vertexError;
  std::sort(sorted.begin(), sorted.end());
  const float scale =
      sorted.empty() ? 1.0f : std::max(1e-6f, sorted[(sorted.size() - 1) * 99 / 100]);
  if (scaleOut) *scaleOut = scale;
  std::vector<float> error(mesh.vertexCount(), 0.0f);
  std::vector<char> known(mesh.vertexCount(), 0);
  for (std::size_t i = 0; i < verts.size(); ++i) {
    if (verts[i] >= mesh.vertexCount())
      throw Error("vertexErrorColours: the report names a vertex past the mesh");
    error[verts[i]] = report.vertexError[i];
    known[verts[i]] = 1;
  }
  if (!verts.empty() && verts.size() < mesh.vertexCount()) {
    parallelFor(mesh.vertexCount(), 64, [&](std::size_t b, std::size_t e) {
      for (std::size_t v = b; v < e; ++v) {
        if (known[v]) continue;
        float best = std::numeric_limits<float>::infinity();
        for (std::size_t i = 0; i < verts.size(); ++i) {
          const Vec3f d = mesh.positions[verts[i]] - mesh.positions[v];
          float dist = dot(d, d);
          if (dot(mesh.normals[verts[i]], mesh.normals[v]) < 0.5f) dist += 1e6f;
          if (dist < best) {
            best = dist;
            error[v] = report.vertexError[i];
          }
        }
      }
    });
  }
  std::vector<Rgb> colour(mesh.vertexCount());
  for (std::size_t v = 0; v < colour.size(); ++v)
    colour[v] = falseColour(std::min(1.0f, error[v] / scale));
  return colour;
}

}  // namespace prt::render
