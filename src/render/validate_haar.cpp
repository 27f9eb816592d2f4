#include "prt/render/validate_haar.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "prt/core/error.hpp"
#include "prt/haar/project_light.hpp"
#include "prt/relight/relight_haar.hpp"
#include "prt/render/texel_points.hpp"
#include "prt/render/validate.hpp"
#include "prt/transfer/row_dilation.hpp"
#include "validation_errors.hpp"

namespace prt::render {

HaarValidationReport validateHaar(const Mesh& mesh, const Occluder& occluder,
                                  const Transfer& transfer, const BakeRecipe& bake,
                                  const envmap::Environment& env,
                                  const HaarValidateSettings& settings,
                                  const ProgressFn& progress) {
  const bool perTexel = transfer.domain() == TransferDomain::Texels;
  if (!transfer.isHaar() || (!perTexel && transfer.domain() != TransferDomain::Vertices))
    throw Error(settings.bakeName, "validateHaar validates Haar transfer per vertex or per texel");
  requireWholeDomain(mesh, transfer, "validation");
  const int n = transfer.shape().haar.resolution;
  HaarValidationReport rep;
  rep.mode = bake.mode;
  rep.domain = transfer.domain();
  rep.resolution = n;
  rep.transferTerms = transfer.shape().haar.terms;

  // The rows: the SH validation's (chooseRows; per texel valid texels with their points), or the
  // precomputed reference's.
  ReferenceSettings rs = settings.reference;
  rs.mode = bake.mode;
  rs.bounces = bake.effectiveBounces();
  rs.material = referenceMaterial(bake.material, TransferLayout::Vector);
  rs.bandLimit.reset();
  const std::size_t domainRows = transfer.rowCount();
  if (settings.precomputed) {
    rep.reference = *settings.precomputed;
    for (std::uint32_t v : rep.reference.vertices)
      if (v >= domainRows)
        throw Error(std::string("the reference has ") + rowName(transfer.domain()) + " " +
                    std::to_string(v) + " of " + std::to_string(domainRows));
    if (perTexel) {
      std::vector<std::uint32_t> texels = rep.reference.vertices;
      std::sort(texels.begin(), texels.end());
      texels.erase(std::unique(texels.begin(), texels.end()), texels.end());
      rs.points = std::make_shared<const RowPoints>(texelRowPointsAt(
          mesh, occluder, transfer.shape().lightmap, texels, rowDilation(TransferBasis::Haar)));
    }
  } else {
    RowChoice c = chooseRows(mesh, occluder, transfer, settings.maxVertices, rs.seed);
    rs.vertices = std::move(c.rows);
    rs.points = std::move(c.points);
    rep.reference = settings.runReference ? settings.runReference(rs, progress)
                                          : renderReference(mesh, occluder, env, rs, progress);
  }
  const auto& verts = rep.reference.vertices;
  const std::size_t count = verts.size();
  // The SH table's metric (validation_errors.hpp), over the same vertices.
  const Metric metric(rep.reference.radiance, rep.reference.stdError);
  double noise = 0;
  for (std::size_t i = 0; i < count; ++i) noise += metric.noiseSq(i);
  rep.refStdErr = std::sqrt(noise / double(std::max<std::size_t>(count, 1)));
  const std::vector<char> counted(count, 1);
  if (!(metric.meanRef > 0))
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
  // The validated rows alone, gathered with their normals and albedo (the mesh's vertices, or
  // the texels' points), so that nothing here is of the lightmap's size.
  const std::size_t stride = transfer.stride();
  std::vector<float> values(count * stride);
  std::vector<Vec3f> normals(count);
  std::vector<Rgb> albedo;
  const std::vector<Rgb> vertexAlbedo = perTexel ? std::vector<Rgb>() : albedoAtVertices(mesh);
  const RowPoints* points = rs.points.get();
  if (points ? !points->albedo.empty() : !vertexAlbedo.empty()) albedo.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint32_t r = verts[i];
    std::copy_n(transfer.values().data() + (r - transfer.rows().first) * stride, stride,
                values.data() + i * stride);
    const std::size_t at = points ? points->entry(r) : r;
    normals[i] = points ? points->normals[at] : mesh.normals[at];
    if (!albedo.empty()) albedo[i] = points ? points->albedo[at] : vertexAlbedo[at];
  }
  TransferShape gatheredShape = transfer.shape();
  gatheredShape.rows = {0, count};
  const Transfer gathered = Transfer::dense(gatheredShape, FloatArray(std::move(values)));
  const std::span<const Rgb> kd = rs.material.diffuseOr(albedo);
  for (std::size_t k : budgets) {
    haar::HaarLight light = haar::approximate(means, n, k);
    light.unshadowed = unshadowed.sh;
    light.bright = unshadowed.bright;
    const std::vector<Rgb> atVertices = relight::relightHaar(gathered, light, normals, kd);
    HaarRow row;
    row.lightTerms = k;
    row.energyKept = light.energyKept;
    for (std::size_t i = 0; i < count; ++i)
      if (!isFinite(atVertices[i]))
        throw Error(settings.bakeName, std::string("the radiance of ") +
                                           rowName(transfer.domain()) + " " +
                                           std::to_string(verts[i]) + " is not finite");
    const ErrorColumns e =
        errorColumns(metric, atVertices, counted, -1e-3 * metric.meanRef, count);
    row.relRmse = e.relRmse;
    row.energyRel = e.energyRel;
    row.meanRel = e.meanRel;
    row.maxRel = e.maxRel;
    row.negativeShare = e.negativeShare;
    rep.rows.push_back(row);
  }
  return rep;
}

std::string formatHaarTable(const HaarValidationReport& r) {
  std::string out;
  char line[256];
  std::snprintf(line, sizeof line, "Haar %d² cube, %d terms per %s; reference std err %.2f%%\n",
                r.resolution, r.transferTerms, rowName(r.domain), 100 * r.refStdErr);
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
