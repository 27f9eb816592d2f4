#include "prt/render/validate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <sstream>

#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/core/sampling.hpp"
#include "prt/relight/relight.hpp"
#include "prt/render/metrics.hpp"
#include "prt/sh/convolve.hpp"
#include "prt/sh/rotate.hpp"

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

/// The environment minus its b-band SH reconstruction, texel by texel: L_k − Σ_i L_b,i Y_i(ω_k)
/// at each texel centre ω_k (signed), in the same layout, so the reference integrates it as it
/// integrates L.
envmap::Environment residualEnvironment(const envmap::Environment& env, const sh::RgbSh& lb) {
  std::vector<image::Image> imgs = env.images();
  const std::size_t n = env.texelCount();
  const std::size_t perImage = imgs.empty() ? 0 : imgs[0].size();
  parallelFor(n, 4096, [&](std::size_t b, std::size_t e) {
    std::vector<float> y(static_cast<std::size_t>(lb.bands) * lb.bands);
    for (std::size_t k = b; k < e; ++k) {
      const envmap::Texel t = env.texel(k);
      Vec3d r(t.radiance);
      if (t.solidAngle > 0) {
        sh::eval(lb.bands, t.direction, y.data());
        for (std::size_t i = 0; i < y.size(); ++i) r -= Vec3d(lb.c[i]) * double(y[i]);
      }
      const bool cube = env.kind() == envmap::Environment::Kind::Cube;
      imgs[cube ? k / perImage : 0].pixels[cube ? k % perImage : k] = Rgb(r);
    }
  });
  switch (env.kind()) {
    case envmap::Environment::Kind::Cube:
      return envmap::Environment::cube({imgs[0], imgs[1], imgs[2], imgs[3], imgs[4], imgs[5]});
    case envmap::Environment::Kind::Probe:
      return envmap::Environment::probe(imgs[0]);
    default:  // lat-long, and an analytic environment's texel lat-long
      return envmap::Environment::latLong(imgs[0]);
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
  // Diffuse (vector) transfer holds the diffuse part only, with diffuse bounces: the reference
  // renders the same, the lobe dropped (kd kept).
  if (!transfer.isMatrix()) {
    rs.material.lobe = {};
    rs.material.specular = Rgb(0.0f);
  }
  rs.vertices = vertexSubset(nv, settings.maxVertices, rs.seed);
  // Glossy (matrix) transfer is seen from an eye; its floor has no closed form even unshadowed.
  const bool glossy = transfer.isMatrix();
  if (glossy && !rs.eye)
    throw Error("validating glossy (matrix) transfer needs the eye the reference and PRT share");
  const bool residualFloor = bake.mode != TransferMode::Unshadowed || glossy;
  // Progress: the reference, then (shadowed, inter-reflected) one residual run per band count
  // over the floor subset, in proportion to their vertex counts.
  const std::size_t nMain = rs.vertices.size();
  const std::size_t nFloorRuns =
      residualFloor ? kept.size() * std::min(nMain, settings.floorVertices) : 0;
  const double mainShare = double(nMain) / double(nMain + nFloorRuns);
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

  double refStd = 0;
  for (std::size_t i = 0; i < n; ++i)
    refStd += std::sqrt(sumSq(rep.reference.stdError[i]) / (sumSq(ref[i]) + 3 * eps));
  refStd /= std::max<std::size_t>(n, 1);

  // The truncation floor: the error a perfect b-band transfer would still have. A perfect
  // transfer relights exactly the b-band light L_b (T·L_b is the transport of L_b), so its error
  // is R(L) − R(L_b) = R(L − L_b) by linearity. It is taken over an evenly strided subset of at
  // most settings.floorVertices of the validated vertices (an RMS over vertices; a thousand
  // estimate it to a few per cent of itself).
  //  * unshadowed: R is the clamped-cosine irradiance, R(L) by quadrature over the texels and
  //    R(L_b) = ρ Σ Λ_l L_lm Y_lm(n)/π in closed form (Ramamoorthi & Hanrahan 2001): exact;
  //  * shadowed, inter-reflected: the reference itself run with the residual environment L − L_b
  //    (same transport, visibility and bounces, same samples), whose squared estimate is
  //    debiased by its own squared standard error, so the floor covers visibility too.
  const std::size_t stride =
      (n + settings.floorVertices - 1) / std::max<std::size_t>(settings.floorVertices, 1);
  std::vector<std::uint32_t> floorVerts;
  std::vector<std::size_t> floorIdx;  // positions in `verts`
  for (std::size_t i = 0; i < n; i += std::max<std::size_t>(stride, 1)) {
    floorVerts.push_back(verts[i]);
    floorIdx.push_back(i);
  }
  const std::size_t nf = floorVerts.size();
  std::vector<Rgb> floorRef(nf);
  if (!residualFloor) {
    const EnvironmentSampler sampler(env);
    parallelFor(nf, 4, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) {
        const std::uint32_t v = floorVerts[i];
        const Rgb a = mesh.hasAlbedo() ? mesh.albedo[v] : Rgb(1.0f);
        floorRef[i] = a * sampler.irradianceQuadrature(mesh.normals[v], rs.rotation) *
                      static_cast<float>(1.0 / kPi);
      }
    });
  }
  rep.floorMethod = residualFloor ? "residual reference" : "irradiance quadrature";
  rep.floorVertices = nf;
  const sh::RgbSh rotatedLight = sh::Rotation(light.bands, rs.rotation).apply(light);
  const std::vector<double> lambda = sh::clampedCosineKernel(rep.bands);
  std::size_t floorRun = 0;

  std::vector<Rgb> albedo;
  if (mesh.hasAlbedo()) albedo = mesh.albedo;
  std::vector<Rgb> prt(n);
  std::vector<float> y(static_cast<std::size_t>(rep.bands) * rep.bands);
  for (int b : kept) {
    // PRT radiance at b bands (relight rotates the light itself).
    std::vector<Rgb> all(nv);
    relight::relight(transfer.cut(b), light.truncated(b), rs.material,
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
    double floorSq = 0;
    if (!residualFloor) {
      // Unshadowed band-limited irradiance E_b(n) = Σ_{l<b} Λ_l L_lm Y_lm(n), radiance ρ E_b / π.
      std::vector<Rgb> floorTest(nf);
      for (std::size_t i = 0; i < nf; ++i) {
        const std::uint32_t v = floorVerts[i];
        sh::eval(b, mesh.normals[v], y.data());
        Vec3d e(0.0);
        for (int l = 0; l < b; ++l)
          for (int m = -l; m <= l; ++m) {
            const int k = l * (l + 1) + m;
            e += Vec3d(rotatedLight.c[k]) * (lambda[l] * y[k]);
          }
        const Rgb a = mesh.hasAlbedo() ? mesh.albedo[v] : Rgb(1.0f);
        floorTest[i] = a * Rgb(e * (1.0 / kPi));
      }
      const double f = relativeRmse(row(floorTest), row(floorRef), eps);
      floorSq = f * f;
    } else {
      ReferenceSettings fr = rs;
      fr.vertices = floorVerts;
      const double lo = mainShare + (1 - mainShare) * double(floorRun) / double(kept.size());
      const double hi = mainShare + (1 - mainShare) * double(floorRun + 1) / double(kept.size());
      ++floorRun;
      const ReferenceResult res = renderReference(
          mesh, occluder, residualEnvironment(env, light.truncated(b)), fr, part(lo, hi));
      rep.floorRays += res.rays;
      rep.floorSeconds += res.seconds;
      // The same metric as rel RMSE, with R(L − L_b) for the difference: E[x̂²] = x² + se², so
      // x̂² − se² estimates x² without the reference noise inflating the floor.
      double sum = 0;
      for (std::size_t i = 0; i < nf; ++i) {
        const Rgb& r0 = ref[floorIdx[i]];
        for (int c = 0; c < 3; ++c) {
          const double x = res.radiance[i][c], se = res.stdError[i][c];
          sum += (x * x - se * se) / (double(r0[c]) * r0[c] + eps);
        }
      }
      floorSq = std::max(0.0, sum / (3.0 * double(std::max<std::size_t>(nf, 1))));
    }
    BandRow r;
    r.bands = b;
    r.relRmse = relativeRmse(row(prt), row(ref), eps);
    r.floor = std::sqrt(floorSq);
    r.refStdErr = refStd;
    // What the lobe itself loses at b bands: its zonal energy beyond b (0 for a diffuse surface).
    r.lobeEnergyBeyond = rs.material.glossy() ? rs.material.lobe.energyBeyond(b) : 0.0;
    std::vector<float> err(n);
    double sum = 0, mx = 0, diffEnergy = 0, refEnergy = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double d2 = sumSq(prt[i] - ref[i]), r2 = sumSq(ref[i]);
      const double e = std::sqrt(d2 / (r2 + 3 * eps));
      err[i] = static_cast<float>(e);
      sum += e;
      mx = std::max(mx, e);
      diffEnergy += d2;
      refEnergy += r2;
    }
    // Energy-weighted: ‖R_b − R_ref‖ / ‖R_ref‖ over all vertices and channels, i.e. e(p)² weighted
    // by each vertex's share of the reference energy (no ε): bright vertices count most.
    r.energyRel = refEnergy > 0 ? std::sqrt(diffEnergy / refEnergy) : 0.0;
    r.meanRel = sum / std::max<std::size_t>(n, 1);
    r.maxRel = mx;
    if (rep.referenceIsZero) {
      // Relative to nothing: undefined, not 0 % (and not the 1e32 % that ε alone would give).
      const double na = std::numeric_limits<double>::quiet_NaN();
      r.relRmse = r.energyRel = r.meanRel = r.maxRel = r.floor = r.refStdErr = na;
      std::fill(err.begin(), err.end(), 0.0f);
    }
    rep.rows.push_back(r);
    rep.vertexError = std::move(err);
  }
  return rep;
}

std::string formatTable(const ValidationReport& rep) {
  std::ostringstream os;
  char line[200];
  const bool lobe = !rep.rows.empty() && rep.rows.front().lobeEnergyBeyond > 0;
  std::snprintf(line, sizeof line, "%5s | %9s | %15s | %12s | %11s | %16s | %11s%s\n", "bands",
                "rel RMSE", "energy-weighted", "mean rel err", "max rel err", "truncation floor",
                "ref std err", lobe ? " | lobe energy > B" : "");
  os << line;
  os << "------+-----------+-----------------+--------------+-------------+------------------+----"
        "--------"
     << (lobe ? "+------------------" : "") << "\n";
  // A percentage, or "n/a" where it is undefined (a zero reference): never "inf%" or "-nan%".
  const auto pct = [](double v, int width) {
    char cell[48];
    if (std::isfinite(v))
      std::snprintf(cell, sizeof cell, "%*.3f%%", width, 100 * v);
    else
      std::snprintf(cell, sizeof cell, "%*s", width + 1, "n/a");
    return std::string(cell);
  };
  for (const BandRow& r : rep.rows) {
    std::snprintf(line, sizeof line, "%5d | %s | %s | %s | %s | %s | %s", r.bands,
                  pct(r.relRmse, 8).c_str(), pct(r.energyRel, 14).c_str(),
                  pct(r.meanRel, 11).c_str(), pct(r.maxRel, 10).c_str(), pct(r.floor, 15).c_str(),
                  pct(r.refStdErr, 10).c_str());
    os << line;
    if (lobe) os << " | " << pct(r.lobeEnergyBeyond, 15);
    os << "\n";
  }
  if (rep.referenceIsZero)
    os << "n/a: the reference is zero at every validated vertex; relative errors are undefined\n";
  return os.str();
}

namespace {

std::string jsonString(const std::string& s) {
  std::string o = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') {
      o += '\\';
      o += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      o += buf;
    } else {
      o += c;
    }
  }
  return o + "\"";
}

std::string num(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

}  // namespace

std::string reportJson(const ValidationReport& rep, int indent) {
  const std::string i1(indent, ' '), i2(2 * indent, ' '), i3(3 * indent, ' ');
  const char* nl = indent > 0 ? "\n" : "";
  std::ostringstream os;
  os << "{" << nl;
  os << i1 << "\"mode\": " << jsonString(toString(rep.mode)) << "," << nl;
  os << i1 << "\"bounces\": " << rep.bounces << "," << nl;
  os << i1 << "\"transferBands\": " << rep.transferBands << "," << nl;
  os << i1 << "\"lightBands\": " << rep.lightBands << "," << nl;
  os << i1 << "\"vertices\": " << rep.reference.vertices.size() << "," << nl;
  os << i1 << "\"referenceRays\": " << rep.reference.rays << "," << nl;
  os << i1 << "\"referenceSeconds\": " << num(rep.reference.seconds) << "," << nl;
  os << i1 << "\"floorMethod\": " << jsonString(rep.floorMethod) << "," << nl;
  os << i1 << "\"floorVertices\": " << rep.floorVertices << "," << nl;
  os << i1 << "\"floorRays\": " << rep.floorRays << "," << nl;
  os << i1 << "\"floorSeconds\": " << num(rep.floorSeconds) << "," << nl;
  os << i1 << "\"referenceIsZero\": " << (rep.referenceIsZero ? "true" : "false") << "," << nl;
  os << i1 << "\"warnings\": [";
  for (std::size_t k = 0; k < rep.warnings.size(); ++k)
    os << (k ? ", " : "") << jsonString(rep.warnings[k]);
  os << "]," << nl;
  os << i1 << "\"rows\": [" << nl;
  for (std::size_t k = 0; k < rep.rows.size(); ++k) {
    const BandRow& r = rep.rows[k];
    os << i2 << "{" << nl;
    os << i3 << "\"bands\": " << r.bands << "," << nl;
    os << i3 << "\"relRmse\": " << num(r.relRmse) << "," << nl;
    os << i3 << "\"energyWeightedRelErr\": " << num(r.energyRel) << "," << nl;
    os << i3 << "\"meanRelErr\": " << num(r.meanRel) << "," << nl;
    os << i3 << "\"maxRelErr\": " << num(r.maxRel) << "," << nl;
    os << i3 << "\"truncationFloor\": " << num(r.floor) << "," << nl;
    os << i3 << "\"refStdErr\": " << num(r.refStdErr) << "," << nl;
    os << i3 << "\"lobeEnergyBeyond\": " << num(r.lobeEnergyBeyond) << nl;
    os << i2 << "}" << (k + 1 < rep.rows.size() ? "," : "") << nl;
  }
  os << i1 << "]" << nl << "}" << nl;
  return os.str();
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
