#include "prt/transport/bake_request.hpp"

#include <algorithm>
#include <cmath>

#include "prt/core/band_limits.hpp"
#include "prt/core/error.hpp"
#include "prt/geometry/texel_sampling.hpp"
#include "prt/haar/haar_light.hpp"
#include "prt/haar/resolution.hpp"
#include "prt/transport/bake.hpp"
#include "prt/transport/passes.hpp"

namespace prt {

long long defaultSamples(TransferBasis basis) {
  return basis == TransferBasis::Haar ? kDefaultHaarRaysPerTexel : 1024;
}

void checkBakeRequest(const BakeRequest& r, OptionSpelling spelling) {
  if (r.modes.empty()) throw Error("no " + optionName(spelling, "mode") + " given");
  for (std::size_t i = 0; i < r.modes.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (r.modes[i] == r.modes[j])
        throw Error(optionName(spelling, "mode") + (spelling == OptionSpelling::Cli ? " " : "") +
                    toString(r.modes[i]) + " given twice");
  if (r.basis == TransferBasis::Haar) {
    const bool cli = spelling == OptionSpelling::Cli;
    // Inter-reflected: the bounce each row holds is SH of `bands` bands, relit against the
    // light's SH (haar_light.hpp holds kUnshadowedBands).
    for (TransferMode m : r.modes)
      if (effectiveBounces(m, r.bounces) > 0)
        checkOptionRange(spelling, "bands", r.bands, 1, haar::kUnshadowedBands);
    if (r.layout != TransferLayout::Vector)
      throw Error(std::string(cli ? "--basis haar" : "basis='haar'") +
                  " bakes diffuse transfer (vector): the glossy matrices are SH only");
    if (r.domain == TransferDomain::Probes)
      throw Error(std::string(cli ? "--basis haar" : "basis='haar'") +
                  " bakes surfaces (per vertex or per texel): a probe holds SH matrices");
    if (r.domain == TransferDomain::Texels && r.lightmap.denoise)
      throw Error(optionName(spelling, "denoise") +
                  " filters SH lightmaps: a Haar row's terms are the sparse largest of its own "
                  "transfer, and no two texels keep the same ones");
    if (r.domain == TransferDomain::Texels && r.lightmap.seamFix)
      throw Error(optionName(spelling, "seam-fix") +
                  " solves for SH coefficients across seams: a Haar row's sparse terms differ "
                  "from texel to texel");
    // The cube's side: --resolution per vertex (--cube-resolution too), --cube-resolution per
    // texel, where --resolution is the lightmap's; cube_resolution in Python.
    const std::string cube =
        cli && r.domain == TransferDomain::Vertices ? "resolution" : "cube-resolution";
    if (!haar::validResolution(r.haar.resolution))
      throw Error(optionLabel(spelling, cube) + ": the Haar cube's side must be a power " +
                  "of two from " + std::to_string(haar::kMinResolution) + " to " +
                  std::to_string(haar::kMaxResolution) + ", got " +
                  std::to_string(r.haar.resolution));
    checkOptionRange(spelling, "terms", r.haar.terms, 1,
                     static_cast<long long>(haar::coefficientCount(r.haar.resolution)));
    checkOptionRange(spelling, "samples", r.samples, 1, kMaxHaarRaysPerTexel);
  } else {
    checkOptionRange(spelling, "bands", r.bands, 1, bands::kMaxBake);
    checkOptionRange(spelling, "samples", r.samples, 1, kMaxBakeSamples);
  }
  checkOptionRange(spelling, "bounces", r.bounces, 0, kMaxBounces);
  if (!(r.targetError >= 0 && r.targetError <= kMaxTargetError))
    throw Error(
        optionLabel(spelling, "target-error") +
        ": must be in [0, 1] (the standard error of a row's radiance under the unit sky; 0: off)");
  if (r.targetError > 0) {
    const std::string option = optionLabel(spelling, "target-error");
    if (r.basis != TransferBasis::SphericalHarmonics)
      throw Error(option +
                  " samples SH rows adaptively: a Haar bake casts its rays per cube texel");
    if (r.layout != TransferLayout::Vector)
      throw Error(option +
                  " samples diffuse transfer (vector) adaptively, not the glossy "
                  "matrices");
    if (r.domain == TransferDomain::Probes)
      throw Error(option +
                  " samples surfaces' rows adaptively (per vertex or per texel), not "
                  "probes");
    if (r.sampling != Sampling::CosineSobol)
      throw Error(option +
                  " needs cosine-Sobol' sampling (its pilot is the first 64 points of "
                  "each row's Sobol' sequence)");
  }
  if (r.albedo)
    for (float x : {r.albedo->x, r.albedo->y, r.albedo->z})
      if (!(x >= 0.0f && x <= 1.0f))
        throw Error(optionLabel(spelling, "albedo") + ": components must lie in [0, 1]");
  if (r.material) checkMaterial(*r.material);
  if (r.domain == TransferDomain::Texels) {
    checkOptionRange(spelling, "resolution", r.lightmap.resolution, 1, kMaxLightmapSide);
    checkOptionRange(spelling, "padding", r.lightmap.padding, 0, kMaxLightmapPadding);
    const std::size_t texels = std::size_t(r.lightmap.resolution) * r.lightmap.resolution;
    if (r.lightmap.seamFix && (r.rows.first > 0 || (r.rows.count && r.rows.count < texels)))
      throw Error(optionName(spelling, "seam-fix") +
                  " needs the whole lightmap (a seam joins texels of other ranges): bake the "
                  "pieces without it, then fix the seams of the merged bake (prt merge "
                  "--seam-fix)");
    if (r.lightmap.denoise && (r.rows.first > 0 || (r.rows.count && r.rows.count < texels)))
      throw Error(optionName(spelling, "denoise") +
                  " needs the whole lightmap (its filter reads texels of other ranges): bake the "
                  "pieces without it, merge them, then prt denoise the merged bake");
  } else if (r.domain == TransferDomain::Probes) {
    if (r.layout != TransferLayout::Matrix)
      throw Error("a probe holds the matrix of the light arriving from every direction: " +
                  std::string(spelling == OptionSpelling::Cli ? "--transfer matrix"
                                                              : "layout='matrix'") +
                  " (prt probes sets it)");
    for (int n : r.probes.count) checkOptionRange(spelling, "grid", n, 0, kMaxProbeSide);
    if (r.lightmap.seamFix)
      throw Error(optionName(spelling, "seam-fix") + " fixes the seams of a lightmap, not probes");
    if (r.lightmap.denoise)
      throw Error(optionName(spelling, "denoise") + " filters a lightmap, not probes");
  } else if (r.lightmap.seamFix) {
    throw Error(optionName(spelling, "seam-fix") + " fixes the seams of a lightmap: add " +
                (spelling == OptionSpelling::Cli ? "--domain texels" : "domain='texels'"));
  } else if (r.lightmap.denoise) {
    throw Error(optionName(spelling, "denoise") + " filters a lightmap: add " +
                (spelling == OptionSpelling::Cli ? "--domain texels" : "domain='texels'"));
  }
}

Material bakeMaterial(const BakeRequest& r, const Mesh& mesh) {
  Material m;
  if (r.material)
    m = *r.material;
  else if (mesh.gloss)
    m = materialFromGloss(*mesh.gloss);
  if (r.albedo) m.diffuse = r.albedo;
  return m;
}

BakeMeshPreparation prepareBakeMesh(Mesh& mesh, const BakeRequest& r) {
  BakeMeshPreparation out;
  if (!r.material && mesh.gloss)
    out.notes.push_back("material from " + mesh.source + " ('" + mesh.gloss->material +
                        "'): " + bakeMaterial(r, mesh).spec());
  // A given albedo (or kd) replaces the mesh's own in the mesh the bake keeps, so that every
  // consumer of the result relights with the albedo its bounces were baked with; it replaces
  // the whole diffuse colour, the base-colour texture with it.
  if (const std::optional<Rgb> kd = bakeMaterial(r, mesh).diffuse) {
    mesh.albedo.assign(mesh.vertexCount(), *kd);
    mesh.baseColour.reset();
  }
  if (r.domain != TransferDomain::Texels) return out;
  const int n = r.lightmap.resolution;
  LightmapUvChoice c = r.lightmap.uv == UvSetOption::Auto
                           ? findLightmapUvs(mesh, r.lightmap.uv, n, n)
                           : chooseLightmapUvs(mesh, r.lightmap.uv, n, n);
  out.uvSetsRefused = c.refused;
  if (c.uvs.empty()) {
    out.lightmapUvsFound = false;
    return out;
  }
  for (const std::string& why : c.refused)
    out.notes.push_back(mesh.source + ": passed over " + why);
  out.uvSetName = c.name;
  out.notes.push_back(mesh.source + ": a " + std::to_string(n) + " x " + std::to_string(n) +
                      " lightmap over its " + c.name + " (padding " +
                      std::to_string(r.lightmap.padding) + ")");
  if (c.uvs.data() != mesh.lightmapUvs.data()) mesh.lightmapUvs.assign(c.uvs.begin(), c.uvs.end());
  return out;
}

BakeSettings bakeSettings(const BakeRequest& r, const Mesh& mesh, TransferMode mode) {
  BakeSettings s;
  s.mode = mode;
  s.samples = static_cast<int>(r.samples);
  s.bounces = effectiveBounces(mode, r.bounces);  // what a bake file records
  s.seed = r.seed;
  s.sampling = r.sampling;
  s.targetError = r.targetError;
  s.material = bakeMaterial(r, mesh);
  s.layout = r.layout;
  s.bands = r.bands;
  s.basis = r.basis;
  if (r.basis == TransferBasis::Haar) {
    s.haar = r.haar;
    s.haar.bounceBands = s.effectiveBounces() > 0 ? r.bands : 0;
  }
  s.domain = r.domain;
  if (r.domain == TransferDomain::Texels)
    s.lightmap = {r.lightmap.resolution, r.lightmap.resolution, r.lightmap.padding, false};
  if (r.domain == TransferDomain::Probes) s.probes = probeGridOf(r, mesh);
  s.rows = r.rows;
  return s;
}

ProbeGrid probeGridOf(const BakeRequest& r, const Mesh& mesh) {
  if (r.probes.bounds)
    return makeProbeGrid(r.probes.bounds->first, r.probes.bounds->second, r.probes.count,
                         mesh.source.empty() ? "probes" : mesh.source);
  const Bounds b = computeBounds(mesh);
  return makeProbeGrid(b.lo, b.hi, r.probes.count, mesh.source.empty() ? "probes" : mesh.source);
}

void refuseNonFinite(const Mesh& mesh, TransferMode mode, const Transfer& t) {
  if (t.empty()) return;
  const std::size_t stride = t.stride();
  const FloatArray& values = t.values();
  for (std::size_t k = 0; k < values.size(); ++k)
    if (!std::isfinite(values[k]))
      throw Error(mesh.source, std::string(toString(mode)) + " transfer of " + rowName(t.domain()) +
                                   " " + std::to_string(t.rows().first + k / stride) +
                                   " is not finite (check the material albedos and "
                                   "coordinates); nothing written");
}

std::vector<BakeResult> bake(const BakeRequest& request, const Mesh& mesh, const Occluder& occluder,
                             PassExecutor& executor, const BakeObserver& observer) {
  std::vector<BakeResult> results;
  for (TransferMode mode : request.modes) {
    BakeResult r;
    r.settings = bakeSettings(request, mesh, mode);
    if (observer.starting) observer.starting(r.settings);
    TexelBakeInfo texels;
    r.transfer = bake(mesh, occluder, r.settings, executor, &r.stats,
                      observer.progress ? observer.progress(r.settings) : ProgressFn{},
                      request.domain == TransferDomain::Texels ? &texels : nullptr);
    r.texelsSampled = texels.samples.samples.size();
    r.texelsInside = texels.inside.size();
    refuseNonFinite(mesh, mode, r.transfer);
    if (observer.finished) observer.finished(r);
    results.push_back(std::move(r));
  }
  return results;
}

}  // namespace prt
