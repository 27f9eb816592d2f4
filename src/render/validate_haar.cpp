#include "prt/render/validate_haar.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "prt/core/error.hpp"
#include "prt/haar/project_light.hpp"
#include "prt/relight/relight_haar.hpp"
#include "prt/render/validate.hpp"

namespace prt::render {

HaarValidationReport validateHaar(const Mesh& mesh, const Occluder& occluder,
                                  const Transfer& transfer, const BakeRecipe& bake,
                                  const envmap::Environment& env,
                                  const HaarValidateSettings& settings,
                                  const ProgressFn& progress) {
  if (!transfer.isHaar() || transfer.domain() != TransferDomain::Vertices)
    throw Error(settings.bakeName, "validateHaar validates per-vertex Haar transfer");
  if (transfer.rowCount() != mesh.vertexCount() || transfer.rows().first != 0)
    throw Error(settings.bakeName, "transfer has " + std::to_string(transfer.rowCount()) +
                                       " rows, the mesh " + std::to_string(mesh.vertexCount()) +
                                       " (validation needs a complete bake)");
  const int n = transfer.shape().haar.resolution;
  HaarValidationReport rep;
  rep.mode = bake.mode;
  rep.resolution = n;
  rep.transferTerms = transfer.shape().haar.terms;

  ReferenceSettings rs = settings.reference;
  rs.mode = bake.mode;
  rs.bounces = 0;
  rs.material = referenceMaterial(bake.material, TransferLayout::Vector);
  rs.bandLimit.reset();
  if (settings.precomputed) {
    rep.reference = *settings.precomputed;
    for (std::uint32_t v : rep.reference.vertices)
      if (v >= mesh.vertexCount())
        throw Error("the reference has vertex " + std::to_string(v) + " of a mesh with " +
                    std::to_string(mesh.vertexCount()));
  } else {
    rs.vertices = vertexSubset(mesh.vertexCount(), settings.maxVertices, rs.seed);
    rep.reference = settings.runReference ? settings.runReference(rs, progress)
                                          : renderReference(mesh, occluder, env, rs, progress);
  }
  const auto& verts = rep.reference.vertices;
  const auto& ref = rep.reference.radiance;
  const std::size_t count = verts.size();
  double mean = 0;
  for (const Rgb& c : ref) mean += (double(c.x) + c.y + c.z) / 3.0;
  mean /= double(std::max<std::size_t>(count, 1));
  const double eps = 1e-2 * mean * mean + 1e-30;
  double noise = 0;
  for (std::size_t i = 0; i < count; ++i)
    for (int c = 0; c < 3; ++c)
      noise += double(rep.reference.stdError[i][c]) * rep.reference.stdError[i][c] /
               (double(ref[i][c]) * ref[i][c] + eps);
  rep.refStdErr = std::sqrt(noise / double(3 * std::max<std::size_t>(count, 1)));
  if (!(mean > 0))
    rep.warnings.push_back("the reference is zero at every validated vertex: relative errors "
                           "are undefined");

  // The cube's texel means once, then each budget's terms of their transform.
  const std::vector<Rgb> means = haar::cubeMeans(env, n, rs.rotation);
  std::vector<std::size_t> budgets;
  for (std::size_t k : settings.lightTerms)
    budgets.push_back(std::min(k, haar::coefficientCount(n)));
  budgets.push_back(haar::coefficientCount(n));
  std::sort(budgets.begin(), budgets.end());
  budgets.erase(std::unique(budgets.begin(), budgets.end()), budgets.end());
  const haar::UnshadowedPart unshadowed = haar::unshadowedPart(env, means, n, rs.rotation);
  const std::vector<Rgb> albedo = albedoAtVertices(mesh);
  const std::span<const Rgb> kd = rs.material.diffuseOr(albedo);
  for (std::size_t k : budgets) {
    haar::HaarLight light = haar::approximate(means, n, k);
    light.unshadowed = unshadowed.sh;
    light.bright = unshadowed.bright;
    const std::vector<Rgb> relit = relight::relightHaar(transfer, light, mesh.normals, kd);
    HaarRow row;
    row.lightTerms = k;
    row.energyKept = light.energyKept;
    double sq = 0, diff = 0, energy = 0, sum = 0, mx = 0;
    std::size_t negative = 0;
    for (std::size_t i = 0; i < count; ++i) {
      const Rgb& p = relit[verts[i]];
      if (!isFinite(p))
        throw Error(settings.bakeName, "the radiance of vertex " + std::to_string(verts[i]) +
                                           " is not finite");
      double d2 = 0, r2 = 0;
      for (int c = 0; c < 3; ++c) {
        const double d = double(p[c]) - ref[i][c];
        sq += d * d / (double(ref[i][c]) * ref[i][c] + eps);
        d2 += d * d;
        r2 += double(ref[i][c]) * ref[i][c];
      }
      diff += d2;
      energy += r2;
      const double e = std::sqrt(d2 / (r2 + 3 * eps));
      sum += e;
      mx = std::max(mx, e);
      if (std::min({p.x, p.y, p.z}) < -1e-3 * mean) ++negative;
    }
    const double nn = double(std::max<std::size_t>(count, 1));
    row.relRmse = std::sqrt(sq / (3 * nn));
    row.energyRel = energy > 0 ? std::sqrt(diff / energy) : 0.0;
    row.meanRel = sum / nn;
    row.maxRel = mx;
    row.negativeShare = double(negative) / nn;
    rep.rows.push_back(row);
  }
  return rep;
}

std::string formatHaarTable(const HaarValidationReport& r) {
  std::string out;
  char line[256];
  std::snprintf(line, sizeof line,
                "Haar %d² cube, %d terms per vertex; reference std err %.2f%%\n", r.resolution,
                r.transferTerms, 100 * r.refStdErr);
  out += line;
  out += "light terms   energy kept   rel RMSE   energy-weighted   mean rel   max rel   negative\n";
  for (const HaarRow& row : r.rows) {
    std::snprintf(line, sizeof line, "%11zu   %10.4f%%   %7.2f%%   %14.2f%%   %7.2f%%   %6.1f%%   %7.1f%%\n",
                  row.lightTerms, 100 * row.energyKept, 100 * row.relRmse, 100 * row.energyRel,
                  100 * row.meanRel, 100 * row.maxRel, 100 * row.negativeShare);
    out += line;
  }
  return out;
}

}  // namespace prt::render
