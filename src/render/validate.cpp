#include "prt/render/validate.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <sstream>

#include "prt/core/error.hpp"
#include "prt/core/json.hpp"
#include "prt/core/parallel.hpp"
#include "prt/core/sampling.hpp"
#include "prt/geometry/texel_sampling.hpp"
#include "prt/relight/encoded_diffuse.hpp"
#include "prt/relight/relight.hpp"
#include "prt/sh/encode_irradiance.hpp"
#include "prt/relight/relight_probes.hpp"
#include "prt/render/camera.hpp"
#include "prt/render/metrics.hpp"
#include "prt/render/primary.hpp"
#include "prt/render/probe_points.hpp"
#include "prt/render/render.hpp"
#include "prt/render/texel_points.hpp"
#include "prt/sh/convolve.hpp"
#include "prt/sh/rotate.hpp"
#include "validation_errors.hpp"

namespace prt::render {

RandomOrder subsetOrder(std::size_t n, std::uint64_t seed) {
  return RandomOrder(n, deriveSeed(seed, 0x5eb5e7ull));
}

std::vector<std::uint32_t> vertexSubset(std::size_t n, std::size_t count, std::uint64_t seed) {
  std::vector<std::uint32_t> subset;
  if (count == 0 || count >= n) {
    subset.resize(n);
    std::iota(subset.begin(), subset.end(), 0u);
    return subset;
  }
  // The first `count` of a uniformly random order: a uniformly random subset.
  RandomOrder order = subsetOrder(n, seed);
  for (std::size_t i = 0; i < count; ++i) subset.push_back(order.next());
  std::sort(subset.begin(), subset.end());
  return subset;
}

namespace {

/// `count` valid texels of `lightmap` (0: every one) by chooseRows' rule, with their points:
/// candidates drawn in batches from the covered texels' order, each batch sampled and probed
/// at once (texelSamplePoints), its valid texels kept in the order drawn.
RowPoints drawTexels(const Mesh& mesh, const Occluder& occluder,
                     const TransferShape::LightmapSize& lightmap, std::size_t count,
                     std::uint64_t seed) {
  if (mesh.lightmapUvs.size() != mesh.vertexCount())
    throw Error(mesh.source, "per-texel transfer needs the mesh's lightmap UVs");
  const TexelCoverage covered =
      coverTexels(mesh, mesh.lightmapUvs, lightmap.width, lightmap.height);
  const std::size_t n = covered.count();
  // Every valid texel: the covered ones in texel order (the order does not matter then).
  const bool all = count == 0 || count >= n;
  RandomOrder order = subsetOrder(all ? 0 : n, seed);
  std::size_t next = 0;  // of the covered texels in texel order, when `all`
  struct Kept {
    std::uint32_t texel;
    Vec3f position, normal;
    Rgb albedo;
  };
  std::vector<Kept> kept;
  bool coloured = false;
  const std::size_t want = all ? n : count;
  while (kept.size() < want && (all ? next < n : !order.done())) {
    // Some more than are missing, since a few may lie inside geometry; extras are dropped, so
    // the texels kept do not depend on the batches.
    const std::size_t missing = want - kept.size();
    const std::size_t batch = all ? n : std::min(n - order.drawn(), missing + missing / 8 + 16);
    std::vector<std::uint32_t> drawn(batch);
    for (std::uint32_t& t : drawn) t = covered.select(all ? next++ : order.next());
    std::vector<std::uint32_t> sorted = drawn;
    std::sort(sorted.begin(), sorted.end());
    const RowPoints p = texelSamplePoints(mesh, occluder, lightmap, sorted);
    coloured = !p.albedo.empty();
    for (std::uint32_t t : drawn) {
      if (kept.size() == want) break;
      if (!std::binary_search(p.valid.begin(), p.valid.end(), t)) continue;  // inside geometry
      const std::size_t e = p.entry(t);
      kept.push_back({t, p.positions[e], p.normals[e], coloured ? p.albedo[e] : Rgb(1.0f)});
    }
  }
  std::sort(kept.begin(), kept.end(),
            [](const Kept& a, const Kept& b) { return a.texel < b.texel; });
  RowPoints out;
  for (const Kept& k : kept) {
    out.rows.push_back(k.texel);
    out.positions.push_back(k.position);
    out.normals.push_back(k.normal);
    if (coloured) out.albedo.push_back(k.albedo);
  }
  out.valid = out.rows;
  return out;
}

}  // namespace

RowChoice chooseRows(const Mesh& mesh, const Occluder& occluder, const Transfer& transfer,
                     std::size_t count, std::uint64_t seed) {
  RowChoice c;
  if (transfer.domain() == TransferDomain::Vertices) {
    c.rows = vertexSubset(transfer.shape().domainRows(mesh.vertexCount()), count, seed);
    return c;
  }
  auto points = std::make_shared<RowPoints>(
      transfer.domain() == TransferDomain::Probes
          ? drawProbePoints(mesh, occluder, transfer.shape().probes, count, seed)
          : drawTexels(mesh, occluder, transfer.shape().lightmap, count, seed));
  c.rows = points->rows;
  c.points = std::move(points);
  return c;
}

namespace {

/// The relighting kernels take rows in blocks of up to 8 (relight/*_kernels.cpp), and the last
/// few rows of each range a thread is given (parallelFor halves ranges) through a scalar form
/// that rounds differently in the last bit. The gathered rows are padded to a power of two
/// (at most twice as many), so that every range is whole blocks and each row is relit bit for
/// bit as in a whole transfer of 2^k rows (a lightmap of power-of-two sides).
constexpr std::size_t kRelightBlock = 8;

std::size_t paddedRows(std::size_t n) {
  return std::bit_ceil(std::max(n, kRelightBlock));
}

/// Rows `rows` of `t` (any order) as a transfer of their own — a dense copy of those rows, or
/// their cluster ids and weights beside the shared means and basis — padded with zero rows to
/// paddedRows, each checked finite, as a mapped bake's rows have not been (io/bake_file.hpp:
/// mapBake): what validation reads of a transfer of any size.
Transfer gatherRows(const Transfer& t, std::span<const std::uint32_t> rows,
                    const std::string& bakeName) {
  const std::size_t n = paddedRows(rows.size());
  TransferShape shape = t.shape();
  shape.rows = {0, n};
  const std::size_t S = t.stride();
  Transfer out;
  if (!t.compressed()) {
    std::vector<float> values(n * S, 0.0f);
    for (std::size_t i = 0; i < rows.size(); ++i)
      std::copy_n(t.row(rows[i]), S, values.data() + i * S);
    out = Transfer::dense(shape, FloatArray(std::move(values)));
  } else {
    const CpcaRows& c = t.cpca();
    const std::size_t N = static_cast<std::size_t>(c.basisCount);
    CpcaRows g;
    g.clusters = c.clusters;
    g.basisCount = c.basisCount;
    g.means = c.means;  // shared, not copied
    g.basis = c.basis;
    g.cluster.assign(n, 0);
    std::vector<float> weights(n * N, 0.0f);
    for (std::size_t i = 0; i < rows.size(); ++i) {
      g.cluster[i] = c.cluster[rows[i]];
      std::copy_n(c.weights.data() + std::size_t(rows[i]) * N, N, weights.data() + i * N);
    }
    g.weights = FloatArray(std::move(weights));
    out = Transfer::cpca(shape, std::move(g));
  }
  // Each row as relighting reads it: its values, or its reconstruction from the cluster's.
  std::vector<float> row(S);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    out.reconstructRow(i, row.data());
    if (!std::all_of(row.begin(), row.end(), [](float x) { return std::isfinite(x); }))
      throw Error(bakeName, std::string("the transfer of ") + rowName(t.domain()) + " " +
                                std::to_string(rows[i]) + " is not finite (a corrupt bake?)");
  }
  return out;
}

/// PRT's exit radiance at the validated rows `verts` of a probe grid (probeNormalRow, ascending):
/// `probes` holds their probes' rows, each once, in order (gatherRows); each probe's incident SH
/// under `light` rotated by `rotation` (relight_probes.hpp: relightProbe, at the light's bands),
/// shaded at the row's normal with albedo kd (shadeDiffuse) — what prt render gives an object
/// there.
void relightProbeRows(const Transfer& probes, const sh::RgbSh& light, const Mat3d& rotation,
                      const Rgb& kd, std::span<const std::uint32_t> verts, std::vector<Rgb>& out) {
  const sh::RgbSh rotated = sh::Rotation(light.bands, rotation).apply(light);
  const int b = light.bands;
  std::vector<float> row(probes.stride());
  std::vector<Rgb> incident(std::size_t(b) * std::size_t(b));
  std::size_t at = 0;
  for (std::size_t i = 0; i < verts.size(); ++i) {
    const std::size_t probe = verts[i] / kProbeNormals;
    if (i == 0 || probe != verts[i - 1] / kProbeNormals) {
      if (i > 0) ++at;
      probes.reconstructRow(at, row.data());
      relight::relightProbe(row.data(), probes.bands(), probes.channels(), rotated, b,
                            incident.data());
    }
    out[i] = relight::shadeDiffuse(incident.data(), b, probeNormal(int(verts[i] % kProbeNormals)),
                                   kd);
  }
}


/// The light PRT relights with at b bands: the first b² coefficients of `light`, windowed at b
/// bands as `prt light --bands b --window W` would; `factors` receives the window's per-band
/// factors (1 without one).
sh::RgbSh lightAt(const sh::RgbSh& light, int b, sh::Window window, std::vector<double>& factors) {
  sh::RgbSh lb = light.truncated(b);
  factors = sh::applyWindow(lb, window).window;
  return lb;
}

/// The band counts to validate: the list asked for (default 1..rep.bands), those beyond what
/// both the light and the transfer hold dropped with a warning, sorted, once each.
std::vector<int> bandsToValidate(const ValidateSettings& settings, ValidationReport& rep) {
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
  return kept;
}

/// The reference with the bake's transport. Diffuse (vector) transfer holds the diffuse part
/// only, with diffuse bounces: the reference renders the same, the lobe dropped (kd kept). Its
/// rows: chooseRows', or the precomputed reference's; per texel with their points alone.
ReferenceSettings referenceFor(const ValidateSettings& settings, const BakeRecipe& bake,
                               const Mesh& mesh, const Occluder& occluder, const Transfer& transfer,
                               std::size_t nv) {
  const bool probes = transfer.domain() == TransferDomain::Probes;
  ReferenceSettings rs = settings.reference;
  rs.mode = bake.mode;
  rs.bounces = bake.effectiveBounces();
  // A probe's matrix holds no lobe (its surfaces bounce diffusely, and the object it lights is
  // not there yet): its reference is diffuse, as a vector's.
  rs.material =
      referenceMaterial(bake.material, probes ? TransferLayout::Vector : transfer.layout());
  rs.bandLimit.reset();
  if (settings.precomputed && probes)
    throw Error(settings.bakeName,
                "a probe grid is validated against a reference computed here, not read from a "
                "reference file");
  if (settings.precomputed) {
    rs.vertices = settings.precomputed->vertices;
    for (std::uint32_t v : rs.vertices)
      if (v >= nv)
        throw Error("the reference has vertex " + std::to_string(v) + " of a mesh with " +
                    std::to_string(nv));
    if (transfer.domain() == TransferDomain::Texels) {
      std::vector<std::uint32_t> texels = rs.vertices;  // as a file lists them: any order
      std::sort(texels.begin(), texels.end());
      texels.erase(std::unique(texels.begin(), texels.end()), texels.end());
      rs.points = std::make_shared<const RowPoints>(
          texelRowPointsAt(mesh, occluder, transfer.shape().lightmap, texels));
    }
  } else {
    RowChoice c = chooseRows(mesh, occluder, transfer, settings.maxVertices, rs.seed);
    rs.vertices = std::move(c.rows);
    rs.points = std::move(c.points);
  }
  // Glossy (matrix) transfer over a surface is seen from an eye.
  if (transfer.isMatrix() && !probes && !rs.eye)
    throw Error("validating glossy (matrix) transfer needs the eye the reference and PRT share");
  return rs;
}

/// A non-finite reference (radiance beyond float range) leaves nothing to compare against:
/// refused rather than tabulated as inf % and NaN %. A zero one is said (relative errors n/a).
void checkReference(const envmap::Environment& env, ValidationReport& rep) {
  const ReferenceResult& r = rep.reference;
  double total = 0;
  for (std::size_t i = 0; i < r.radiance.size(); ++i) {
    if (!isFinite(r.radiance[i]) || !isFinite(r.stdError[i]))
      throw Error(env.source(), "the reference radiance at vertex " +
                                    std::to_string(r.vertices[i]) +
                                    " is not finite (the environment is too bright for 32-bit "
                                    "floats); nothing to validate against");
    total += sumSq(r.radiance[i]);
  }
  rep.referenceIsZero = !(total > 0);
  if (rep.referenceIsZero)
    rep.warnings.push_back(
        "the reference is zero at every validated vertex (a black environment?): relative "
        "errors are undefined (n/a)");
}

/// The floor's vertices: an even stride of at most `count` of the validated ones (an RMS over
/// vertices; a thousand estimate it to a few per cent of itself), as positions among them.
std::vector<std::size_t> floorEntries(std::size_t validated, std::size_t count) {
  const std::size_t stride = (validated + count - 1) / std::max<std::size_t>(count, 1);
  std::vector<std::size_t> idx;
  for (std::size_t i = 0; i < validated; i += std::max<std::size_t>(stride, 1)) idx.push_back(i);
  return idx;
}

/// The floor columns of row r (lane k of `lanes`) from the floor run's band-limited estimates:
/// floor² = mean over the floor's vertices of Σ_c (x̂² − se²)/(R_ref² + ε)/3 for x = e_b − e
/// (E[x̂²] = x² + se², so its noise does not inflate it), the light-only floor likewise, and
/// what the identity rel RMSE² = floor² + noise² leaves over, (R_b − R_ref)² − (x̂² − se²) −
/// se_ref² per vertex, with its standard error; `explained` = √(floor² + noise²) / rel RMSE on
/// the same vertices.
void fillFloor(BandRow& r, const Metric& metric, const ReferenceResult& floorRun,
               const std::vector<std::size_t>& floorIdx, const std::vector<Rgb>& prt, std::size_t k,
               std::size_t lanes) {
  const std::size_t nf = floorIdx.size();
  const double count = double(std::max<std::size_t>(nf, 1));
  const auto floorSq = [&](Estimate BandLimitedEstimate::*part, std::vector<double>* rest) {
    double sum = 0;
    for (std::size_t j = 0; j < nf; ++j) {
      const std::size_t i = floorIdx[j];
      const Estimate& e = floorRun.bandLimited[j * lanes + k].*part;
      double f = 0;
      for (int c = 0; c < 3; ++c) {
        const double x = e.mean[c], se = e.stdError[c];
        f += (x * x - se * se) * metric.weight(i, c) / 3.0;
      }
      sum += f;
      if (rest) (*rest)[j] = metric.errorSq(i, prt[i]) - f - metric.noiseSq(i);
    }
    return sum / count;
  };
  std::vector<double> rest(nf);
  const double fSq = floorSq(&BandLimitedEstimate::difference, &rest);
  const double lightSq = floorSq(&BandLimitedEstimate::light, nullptr);
  r.floor = std::sqrt(std::max(0.0, fSq));
  r.lightFloor = std::sqrt(std::max(0.0, lightSq));
  double restMean = 0, restVar = 0, errSq = 0, noise = 0;
  for (double x : rest) restMean += x / count;
  for (double x : rest) restVar += (x - restMean) * (x - restMean);
  r.unexplainedSq = restMean;
  r.unexplainedSqStdErr = nf > 1 ? std::sqrt(restVar / double(nf - 1) / double(nf)) : 0.0;
  // The same over the floor's vertices only, so that the three share their vertices.
  for (std::size_t i : floorIdx) {
    errSq += metric.errorSq(i, prt[i]);
    noise += metric.noiseSq(i);
  }
  r.explained = errSq > 0 ? std::sqrt(std::max(0.0, fSq + noise / count) / (errSq / count)) : 1.0;
}

/// The error columns of row r over every validated vertex, and the per-vertex error `err`
/// (errorColumns, validation_errors.hpp).
void fillErrors(BandRow& r, std::vector<float>& err, const Metric& metric,
                const std::vector<Rgb>& prt, const std::vector<char>& counted, double negativeBelow,
                std::size_t negativeVertices) {
  const ErrorColumns e = errorColumns(metric, prt, counted, negativeBelow, negativeVertices, &err);
  r.relRmse = e.relRmse;
  r.energyRel = e.energyRel;
  r.meanRel = e.meanRel;
  r.maxRel = e.maxRel;
  r.negativeShare = e.negativeShare;
}

}  // namespace

ValidationReport validate(const Mesh& mesh, const Occluder& occluder, const Transfer& transfer,
                          const BakeRecipe& bake, const envmap::Environment& env,
                          const sh::RgbSh& light, const ValidateSettings& settings,
                          const ProgressFn& progress) {
  PRT_CHECK(!settings.reference.points, "validate() places the rows' points itself");
  const bool texels = transfer.domain() == TransferDomain::Texels;
  const std::size_t nv = transfer.shape().domainRows(mesh.vertexCount());
  if (transfer.rowCount() != nv || transfer.rows().first != 0)
    throw Error(mesh.source, "transfer has " + std::to_string(transfer.rowCount()) + " rows, " +
                                 (texels ? "the lightmap " : "the mesh ") + std::to_string(nv) +
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
  if (!settings.encodings.empty()) {
    // Checked before the reference runs: an encoding holds the light arriving at a row.
    const char* label = "--encoding";
    if (!transfer.isMatrix() || transfer.domain() == TransferDomain::Probes)
      throw Error(settings.bakeName,
                  std::string(label) + " measures an irradiance encoding of the light arriving at "
                                       "each row, which a surface's matrix bake holds (prt bake "
                                       "--transfer matrix); this is " +
                      (transfer.domain() == TransferDomain::Probes ? "a probe grid"
                                                                   : "vector transfer"));
  }
  const std::vector<int> kept = bandsToValidate(settings, rep);
  const ReferenceSettings rs = referenceFor(settings, bake, mesh, occluder, transfer, nv);
  if (!settings.encodings.empty() && rs.material.glossy())
    throw Error(settings.bakeName, "--encoding: the bake's material " + rs.material.spec() +
                                       " has a glossy lobe; an irradiance encoding shades the "
                                       "diffuse part only");
  const RowPoints* points = rs.points.get();
  const bool probes = transfer.domain() == TransferDomain::Probes;
  // Glossy: a surface's matrix transfer, seen from the eye (a probe's matrix has no eye).
  const bool glossy = transfer.isMatrix() && !probes;
  const std::vector<std::size_t> floorIdx =
      floorEntries(rs.vertices.size(), settings.floorVertices);
  const std::size_t nf = floorIdx.size();

  // Progress: the reference, then the band-limited run over the floor's vertices (about twice
  // the reference's work per vertex), in proportion.
  const double mainShare = double(rs.vertices.size()) / double(rs.vertices.size() + 2 * nf);
  const auto part = [&](double lo, double hi) -> ProgressFn {
    if (!progress) return {};
    return [&progress, lo, hi](double f) { return progress(lo + (hi - lo) * f); };
  };
  const auto runReference = [&](const ReferenceSettings& r, const ProgressFn& p) {
    return settings.runReference ? settings.runReference(r, p)
                                 : renderReference(mesh, occluder, env, r, p);
  };
  if (settings.precomputed) {
    PRT_CHECK(settings.precomputed->radiance.size() == rs.vertices.size() &&
                  settings.precomputed->stdError.size() == rs.vertices.size(),
              "a precomputed reference holds one estimate per vertex");
    rep.reference = *settings.precomputed;
    rep.reference.bandLimited.clear();
    if (progress && !progress(mainShare)) throw Cancelled();
  } else {
    rep.reference = runReference(rs, part(0.0, mainShare));
  }
  checkReference(env, rep);
  const auto& verts = rep.reference.vertices;
  const std::size_t n = verts.size();
  const Metric metric(rep.reference.radiance, rep.reference.stdError);
  double refNoiseSq = 0;
  for (std::size_t i = 0; i < n; ++i) refNoiseSq += metric.noiseSq(i);
  const double refStd = std::sqrt(refNoiseSq / double(std::max<std::size_t>(n, 1)));

  // The b-band lights PRT relights with, and the same as band limits for the floor.
  std::vector<sh::RgbSh> lights;
  BandLimitSettings bl;
  bl.light = light;
  // A probe's relit SH is shaded with the b-band cosine kernel over the whole sphere.
  bl.truncateKernel = glossy || probes;
  bl.wholeSphere = probes;
  for (int b : kept) {
    BandLimit lim;
    lim.bands = b;
    lights.push_back(lightAt(light, b, settings.window, lim.window));
    bl.limits.push_back(std::move(lim));
  }
  rep.window = sh::toString(settings.window);

  // The truncation floor: the error of exact band-limited relighting, e_b − e per floor vertex
  // and band count from the reference's own samples (reference.hpp), in one run for all band
  // counts. Its radiance is the reference's at those vertices, bit for bit.
  ReferenceSettings fr = rs;
  fr.vertices.clear();
  for (std::size_t i : floorIdx) fr.vertices.push_back(rs.vertices[i]);
  fr.bandLimit = std::move(bl);
  const ReferenceResult floorRun = runReference(fr, part(mainShare, 1.0));
  rep.floorMethod = kFloorMethod;
  rep.floorVertices = nf;
  rep.floorRays = floorRun.rays;
  rep.floorSeconds = floorRun.seconds;

  // The validated rows alone, gathered: where they are (the mesh's vertices, or the points of
  // the texels drawn), their albedo and their transfer, so that nothing here is of the size of
  // the domain (relighting is per row: relighting these is relighting the whole at them).
  const std::size_t padded = paddedRows(n);
  std::vector<Vec3f> positions(padded, Vec3f(0.0f)), normals(padded, Vec3f(0, 0, 1));
  std::vector<Rgb> albedo;
  const std::vector<Rgb> vertexAlbedo =
      !points && (mesh.hasAlbedo() || mesh.baseColour)
          ? albedoAtVertices(mesh)  // the texture folded in at the vertices, as the reference
          : std::vector<Rgb>();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t at = points ? points->entry(verts[i]) : verts[i];
    positions[i] = points ? points->positions[at] : mesh.positions[at];
    normals[i] = points ? points->normals[at] : mesh.normals[at];
    if (points && !points->albedo.empty()) albedo.push_back(points->albedo[at]);
    if (!vertexAlbedo.empty()) albedo.push_back(vertexAlbedo[at]);
  }
  if (!albedo.empty()) albedo.resize(padded, Rgb(1.0f));
  // Of a probe grid, the probes of the validated rows, each once.
  std::vector<std::uint32_t> probeRows;
  if (probes) {
    for (std::uint32_t r : verts) probeRows.push_back(r / kProbeNormals);
    probeRows.erase(std::unique(probeRows.begin(), probeRows.end()), probeRows.end());
  }
  const Transfer validated = gatherRows(transfer, probes ? probeRows : verts, settings.bakeName);

  // Vertices whose negative radiance counts: for glossy transfer those facing the eye.
  std::vector<char> counted(n, 1);
  if (glossy)
    for (std::size_t i = 0; i < n; ++i) counted[i] = dot(normals[i], *rs.eye - positions[i]) > 0;
  rep.negativeVertices = static_cast<std::size_t>(std::count(counted.begin(), counted.end(), 1));

  std::vector<Rgb> padPrt(padded);
  for (std::size_t k = 0; k < kept.size(); ++k) {
    const int b = kept[k];
    // PRT radiance at b bands (relight rotates the light itself).
    if (probes)
      relightProbeRows(validated, lights[k], rs.rotation,
                       rs.material.diffuse ? *rs.material.diffuse : Rgb(1.0f), verts, padPrt);
    else
      relight::relight(validated.cut(b), lights[k], rs.material, {positions, normals, albedo},
                       rs.eye ? *rs.eye : Vec3f(0.0f), padPrt, rs.rotation);
    const std::vector<Rgb> prt(padPrt.begin(), padPrt.begin() + std::ptrdiff_t(n));
    for (std::size_t i = 0; i < n; ++i)
      if (!isFinite(prt[i]))
        throw Error(settings.bakeName,
                    std::string("the PRT radiance at ") + rowName(transfer.domain()) + " " +
                        std::to_string(probes ? verts[i] / kProbeNormals : verts[i]) +
                        " is not finite at " + std::to_string(b) +
                        " bands (the transfer times the light overflows 32-bit floats)");
    BandRow r;
    r.bands = b;
    r.refStdErr = refStd;
    std::vector<float> err;
    fillErrors(r, err, metric, prt, counted, -1e-3 * metric.meanRef, rep.negativeVertices);
    fillFloor(r, metric, floorRun, floorIdx, prt, k, kept.size());
    // What the lobe itself loses at b bands: its zonal energy beyond b (0 for a diffuse surface).
    r.lobeEnergyBeyond = rs.material.glossy() ? rs.material.lobe.energyBeyond(b) : 0.0;
    if (rep.referenceIsZero) {
      // Relative to nothing: undefined, not 0 % (and not the 1e32 % that ε alone would give).
      const double na = std::numeric_limits<double>::quiet_NaN();
      r.relRmse = r.energyRel = r.meanRel = r.maxRel = r.floor = r.refStdErr = r.explained = na;
      std::fill(err.begin(), err.end(), 0.0f);
    }
    rep.rows.push_back(r);
    rep.vertexError = std::move(err);
  }
  // Each encoding at the full band count (padPrt holds the bake's own relighting there).
  const std::vector<Rgb> own(padPrt.begin(), padPrt.begin() + std::ptrdiff_t(n));
  for (const sh::IrradianceEncoding e : settings.encodings) {
    std::vector<Rgb> shaded = relight::encodedDiffuse(validated, lights.back(), e, rs.material,
                                                      {positions, normals, albedo}, rs.rotation);
    shaded.resize(n);
    BandRow r;
    std::vector<float> err;
    fillErrors(r, err, metric, shaded, counted, -1e-3 * metric.meanRef, rep.negativeVertices);
    double d2 = 0, o2 = 0;
    for (std::size_t i = 0; i < n; ++i) d2 += sumSq(shaded[i] - own[i]), o2 += sumSq(own[i]);
    EncodingRow row;
    row.encoding = e;
    row.numbers = sh::storedNumbers(e);
    row.relRmse = r.relRmse;
    row.energyRel = r.energyRel;
    row.vsBake = o2 > 0 ? std::sqrt(d2 / o2) : 0.0;
    row.negativeShare = r.negativeShare;
    rep.encodings.push_back(row);
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
  if (!rep.encodings.empty()) {
    std::snprintf(line, sizeof line, "\n%-16s | %7s | %9s | %15s | %15s | %8s\n",
                  "encoding", "numbers", "rel RMSE", "energy-weighted", "vs the bake's", "negative");
    os << line;
    os << "-----------------+---------+-----------+-----------------+-----------------+---------\n";
    for (const EncodingRow& e : rep.encodings) {
      std::snprintf(line, sizeof line, "%-16s | %7d | %s | %s | %s | %7.2f%%\n",
                    sh::toString(e.encoding), e.numbers, pct(e.relRmse, 8).c_str(),
                    pct(e.energyRel, 14).c_str(), pct(e.vsBake, 14).c_str(),
                    100 * e.negativeShare);
      os << line;
    }
  }
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
  if (!rep.encodings.empty()) {
    Json enc = Json::array();
    for (const EncodingRow& e : rep.encodings)
      enc.push_back({{"encoding", sh::toString(e.encoding)},
                     {"numbers", e.numbers},
                     {"relRmse", e.relRmse},
                     {"energyWeightedRelErr", e.energyRel},
                     {"vsBake", e.vsBake},
                     {"negativeShare", e.negativeShare}});
    j["encodings"] = std::move(enc);
  }
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

image::Image errorImage(const Mesh& mesh, const Occluder& occluder, const Transfer& transfer,
                        const ValidationReport& report, int width, int height, float* scale,
                        const ProgressFn& progress) {
  if (transfer.domain() == TransferDomain::Texels) {
    // The lightmap itself: each validated texel's relative error at the largest band count
    // through the false-colour ramp (scaled to its 99th percentile), black elsewhere.
    const TransferShape::LightmapSize lm = transfer.shape().lightmap;
    std::vector<float> sorted(report.vertexError.begin(), report.vertexError.end());
    std::sort(sorted.begin(), sorted.end());
    const float s = sorted.empty()
                        ? 1.0f
                        : std::max(sorted[std::size_t(0.99 * double(sorted.size() - 1))], 1e-6f);
    image::Image img(lm.width, lm.height, Rgb(0.0f));
    for (std::size_t i = 0; i < report.reference.vertices.size(); ++i) {
      const std::uint32_t t = report.reference.vertices[i];
      img.at(int(t % std::uint32_t(lm.width)), int(t / std::uint32_t(lm.width))) =
          falseColour(std::min(report.vertexError[i] / s, 1.0f));
    }
    if (scale) *scale = s;
    return img;
  }
  // The mesh, each vertex's error (a Voronoi fill between the vertices of a subset).
  const std::vector<Rgb> colour = vertexErrorColours(mesh, report, scale);
  FrameSettings fs;
  fs.width = width;
  fs.height = height;
  return renderRelit(mesh, occluder, colour, frameMesh(mesh, width, height), fs,
                     colourBackground(Rgb(0.0f)), progress);
}

}  // namespace prt::render
