#include "bake_common.hpp"

#include <string>

#include <cstdio>
#include <limits>

#include "prt/core/band_limits.hpp"
#include "prt/core/error.hpp"
#include "prt/core/units.hpp"
#include "prt/geometry/texel_sampling.hpp"
#include "prt/haar/haar_light.hpp"
#include "prt/sh/sh.hpp"

namespace prt::bakedetail {

void validateBake(const Mesh& mesh, const BakeSettings& s) {
  const std::string name = mesh.source.empty() ? "mesh" : mesh.source;
  if (mesh.vertexCount() == 0 || mesh.triangleCount() == 0)
    throw Error(name, "cannot bake an empty mesh (" + std::to_string(mesh.vertexCount()) +
                          " vertices, " + std::to_string(mesh.triangleCount()) + " triangles)");
  if (mesh.normals.size() != mesh.vertexCount())
    throw Error(name, "has " + std::to_string(mesh.normals.size()) + " normals for " +
                          std::to_string(mesh.vertexCount()) + " vertices");
  if (mesh.hasAlbedo() && mesh.albedo.size() != mesh.vertexCount())
    throw Error(name, "has " + std::to_string(mesh.albedo.size()) + " albedo values for " +
                          std::to_string(mesh.vertexCount()) + " vertices");
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
    for (std::uint32_t i : mesh.triangles[t])
      if (i >= mesh.vertexCount())
        throw Error(name, "triangle " + std::to_string(t) + " references vertex " +
                              std::to_string(i) + " (mesh has " +
                              std::to_string(mesh.vertexCount()) + ")");
  if (s.basis == TransferBasis::Haar) {
    if (s.layout != TransferLayout::Vector || s.domain == TransferDomain::Probes)
      throw Error(name, "a Haar bake is diffuse transfer (vector), per vertex or per texel");
    const int bounceBands = s.effectiveBounces() > 0 ? s.haar.bounceBands : 0;
    if (s.haar.bounceBands != bounceBands ||
        (s.effectiveBounces() > 0 && (bounceBands < 1 || bounceBands > haar::kUnshadowedBands)))
      throw Error(name, "an inter-reflected Haar bake holds its bounce in 1 to " +
                            std::to_string(haar::kUnshadowedBands) +
                            " SH bands (and only it), got " + std::to_string(s.haar.bounceBands));
    if (s.samples > kMaxHaarRaysPerTexel)
      throw Error(name, "a Haar bake casts 1 to " + std::to_string(kMaxHaarRaysPerTexel) +
                            " rays per cube texel (its samples), got " +
                            std::to_string(s.samples));
    s.inBasis(TransferShape{}).check(name);
  } else if (s.bands < 1 || s.bands > bands::kMaxBake) {
    throw Error(bands::bandLimitMessage("the bake", s.bands, "baking", bands::kMaxBake));
  }
  checkRecipe(s);
  if (s.adaptive() &&
      (s.basis != TransferBasis::SphericalHarmonics || s.layout != TransferLayout::Vector ||
       s.domain == TransferDomain::Probes || s.sampling != Sampling::CosineSobol))
    throw Error(name,
                "adaptive sampling (a target error) is made for diffuse SH transfer "
                "(vector) per vertex or per texel, sampled by cosine-Sobol'");
  if (s.domain == TransferDomain::Texels) {
    const auto& lm = s.lightmap;
    if (lm.width < 1 || lm.width > kMaxLightmapSide || lm.height < 1 ||
        lm.height > kMaxLightmapSide)
      throw Error(name, "a " + std::to_string(lm.width) + " x " + std::to_string(lm.height) +
                            " lightmap: each side must be 1.." + std::to_string(kMaxLightmapSide));
    if (lm.padding < 0 || lm.padding > kMaxLightmapPadding)
      throw Error(name, "the dilation padding must be 0.." + std::to_string(kMaxLightmapPadding) +
                            " texels");
  }
  if (s.domain == TransferDomain::Probes) {
    if (s.layout != TransferLayout::Matrix)
      throw Error(name, "a probe bake holds matrices (the light arriving from every direction): "
                        "bake it with the matrix layout");
    checkProbeGrid(s.probes, name);
  }
  const std::size_t rows = domainRows(mesh, s);
  if (s.rows.first >= rows || s.rows.count > rows - s.rows.first) {
    if (s.domain == TransferDomain::Texels)
      throw Error(name, "texel range [" + std::to_string(s.rows.first) + ", " +
                            std::to_string(s.rows.end()) + ") is outside the " +
                            std::to_string(s.lightmap.width) + " x " +
                            std::to_string(s.lightmap.height) + " lightmap");
    if (s.domain == TransferDomain::Probes)
      throw Error(name, "probe range [" + std::to_string(s.rows.first) + ", " +
                            std::to_string(s.rows.end()) + ") is outside the grid (" +
                            std::to_string(s.probes.probes()) + " probes)");
    throw Error(name, "vertex range [" + std::to_string(s.rows.first) + ", " +
                          std::to_string(s.rows.first + s.rows.count) + ") is outside the mesh (" +
                          std::to_string(mesh.vertexCount()) + " vertices)");
  }
}

RowRange bakeRows(const Mesh& mesh, const BakeSettings& s) {
  const std::size_t n = domainRows(mesh, s);
  const std::size_t first = std::min(s.rows.first, n);
  return {first, s.rows.count ? std::min(s.rows.count, n - first) : n - first};
}

BounceAlbedo resolveAlbedo(const Mesh& mesh, const BakeSettings& s) {
  BounceAlbedo a;
  if (s.material.diffuse) {
    a.uniform = *s.material.diffuse;
    a.grey = a.uniform.x == a.uniform.y && a.uniform.y == a.uniform.z;
  } else if (mesh.hasAlbedo() || mesh.baseColour) {
    a.perVertex = true;
    if (mesh.baseColour) a.store = std::make_shared<const std::vector<Rgb>>(albedoAtVertices(mesh));
    a.values = a.store ? a.store.get() : &mesh.albedo;
    a.grey = std::all_of(a.values->begin(), a.values->end(),
                         [](const Rgb& c) { return c.x == c.y && c.y == c.z; });
  }
  return a;
}

BakeSettings diffuseBounceSource(const BakeSettings& matrixBake) {
  BakeSettings vs = matrixBake;
  vs.layout = TransferLayout::Vector;
  vs.rows = {};
  vs.bounces = matrixBake.effectiveBounces() - 1;
  vs.mode = vs.bounces > 0 ? TransferMode::Interreflected : TransferMode::Shadowed;
  // A probe gathers the light of the surfaces, which is the mesh's: its vertices' transfer,
  // interpolated across the hit triangle.
  if (vs.domain == TransferDomain::Probes) vs.domain = TransferDomain::Vertices;
  return vs;
}

std::vector<BakeSettings> glossyBounceOrders(const BakeSettings& matrixBake) {
  const int bounces = matrixBake.effectiveBounces();
  std::vector<BakeSettings> orders(static_cast<std::size_t>(bounces) + 1, matrixBake);
  for (int j = bounces - 1; j >= 0; --j) {
    BakeSettings& o = orders[static_cast<std::size_t>(j)];
    o.rows = {};
    o.bounces = j;
    o.mode = j > 0 ? TransferMode::Interreflected : TransferMode::Shadowed;
    o.seed = matrixBounceOrderSeed(orders[static_cast<std::size_t>(j) + 1].seed, j);
  }
  return orders;
}

BakeSettings haarBounceSource(const BakeSettings& haarBake) {
  BakeSettings vs = haarBake;
  vs.basis = TransferBasis::SphericalHarmonics;
  vs.haar = {};
  vs.layout = TransferLayout::Vector;
  vs.bands = haarBake.haar.bounceBands;
  vs.samples = haarBake.samples * kHaarBounceSamplesPerTexelRay;
  vs.rows = {};
  return vs;
}

BakePlan planBake(const Mesh& mesh, const BakeSettings& s, bool checkMemory) {
  validateBake(mesh, s);
  BakePlan plan;
  plan.footprint = bakeFootprint(mesh, s);
  if (checkMemory) checkFootprint(mesh, s, plan.footprint);
  plan.rows = bakeRows(mesh, s);
  plan.domainRows = domainRows(mesh, s);
  if (s.basis == TransferBasis::Haar && s.effectiveBounces() > 0)
    plan.haarBounce = haarBounceSource(s);
  if (s.layout == TransferLayout::Matrix && s.effectiveBounces() > 0) {
    // Probes gather the diffuse light of the surfaces (their lobe would need the direction a
    // probe's light leaves toward an object that is not there yet).
    if (!s.glossyBounces(TransferLayout::Matrix) || s.domain == TransferDomain::Probes) {
      plan.diffuseSource = diffuseBounceSource(s);
    } else {
      plan.glossyOrders = glossyBounceOrders(s);
      for (const BakeSettings& o : plan.glossyOrders)
        plan.glossyChannels.push_back(bakeFootprint(mesh, o).channels);
    }
  }
  return plan;
}

BakeStats matrixStats(MatrixPassKind kind, const std::vector<std::uint64_t>& rays,
                      const std::vector<double>& seconds, const std::vector<double>& variance,
                      double secondsTotal) {
  BakeStats st;
  const std::size_t last = seconds.size() - 1;
  for (std::uint64_t r : rays) st.rays += r;
  st.secondsDirect = seconds[last];
  if (kind == MatrixPassKind::DiffuseBounces) {
    double s = 0;
    std::uint64_t r = 0;
    for (std::size_t k = 0; k < last; ++k) s += seconds[k], r += rays[k];
    st.secondsBounce = {s};
    st.raysBounce = {r};
  } else if (kind == MatrixPassKind::GlossyBounces) {
    st.secondsDirect = seconds[0];
    for (std::size_t k = 1; k <= last; ++k) {
      st.secondsBounce.push_back(seconds[k]);
      st.raysBounce.push_back(rays[k]);
    }
  }
  st.raysPerSecond = raysPerSecondOf(st.rays, secondsTotal);
  // L00 = √(4π) gives L'_00 Y00 = M_00: the white-sky radiance's error is M_00's.
  const StandardErrors m00 = standardErrors(variance);
  st.stdErrT0Mean = st.stdErrConstMean = m00.mean;
  st.stdErrT0Max = st.stdErrConstMax = m00.max;
  st.secondsTotal = secondsTotal;
  return st;
}

void checkFootprint(const Mesh& mesh, const BakeSettings& s, const BakeFootprint& f) {
  const std::size_t need =
      f.transferBytes > std::numeric_limits<std::size_t>::max() - f.workingBytes
          ? std::numeric_limits<std::size_t>::max()
          : f.transferBytes + f.workingBytes;
  if (fitsInMemory(need)) return;
  const std::size_t have = physicalMemoryBytes();
  const std::string name = mesh.source.empty() ? "mesh" : mesh.source;
  if (s.domain == TransferDomain::Probes)
    throw Error(name, "the transfer of " + s.probes.describe() + " at " + std::to_string(s.bands) +
                          " bands needs " + bytesText(f.bytesPerRow) + " per probe, " +
                          bytesText(need) + " in all; this machine has " + bytesText(have) +
                          " (fewer bands or fewer probes)");
  if (s.domain == TransferDomain::Texels)
    throw Error(name, std::string(toString(s.layout)) + " transfer of a " +
                          std::to_string(s.lightmap.width) + " x " +
                          std::to_string(s.lightmap.height) + " lightmap at " +
                          std::to_string(s.bands) + " bands needs " + bytesText(f.bytesPerRow) +
                          " per texel, " + bytesText(need) + " in all; this machine has " +
                          bytesText(have) +
                          " (fewer bands, a smaller --resolution, or vector transfer)");
  throw Error(name, std::string(toString(s.layout)) + " transfer at " + std::to_string(s.bands) +
                        " bands needs " + bytesText(f.bytesPerRow) + " per vertex, " +
                        bytesText(need) + " in all; this machine has " + bytesText(have) +
                        " (fewer bands, a vertex range, or a smaller mesh)");
}

}  // namespace prt::bakedetail

namespace prt {

std::size_t domainRows(const Mesh& mesh, const BakeSettings& s) {
  return s.domain == TransferDomain::Texels   ? s.lightmap.texels()
         : s.domain == TransferDomain::Probes ? s.probes.probes()
                                              : mesh.vertexCount();
}

BakeFootprint bakeFootprint(const Mesh& mesh, const BakeSettings& s) {
  using namespace bakedetail;
  BakeFootprint f;
  const std::size_t n = domainRows(mesh, s);
  const std::size_t count = bakeRows(mesh, s).count;
  const bool inter = s.effectiveBounces() > 0;
  const BounceAlbedo a = resolveAlbedo(mesh, s);
  const bool glossy = s.glossyBounces(s.layout) && s.domain != TransferDomain::Probes;
  const Rgb ks = s.material.specular;
  const bool colouredLobe = glossy && !(ks.x == ks.y && ks.y == ks.z);
  f.channels = inter && (!a.grey || colouredLobe) ? 3 : 1;
  const auto bytes = [&](TransferLayout layout, std::size_t rows) {
    TransferShape shape = s.inBasis(TransferShape{});
    shape.layout = layout, shape.channels = f.channels;
    shape.rows.count = rows;
    return shape.denseBytes();
  };
  f.bytesPerRow = bytes(s.layout, 1);
  f.transferBytes = bytes(s.layout, count);
  if (s.basis == TransferBasis::Haar) {
    // The bounce's SH passes over the whole domain (the sum, the pass read, the pass baked);
    // per texel the result laid out as the lightmap and the sample points.
    if (inter) {
      TransferShape sh{TransferDomain::Vertices, TransferLayout::Vector, s.haar.bounceBands,
                       f.channels, RowRange{0, n}};
      f.workingBytes = 3 * sh.denseBytes();
    }
    if (s.domain == TransferDomain::Texels) f.workingBytes += bytes(s.layout, n) + n * 40;
    return f;
  }
  if (s.domain == TransferDomain::Probes) {
    // The diffuse transfer of one bounce less over the whole mesh, as a matrix bake's (the sum
    // and the pass being baked), and each probe's position and inside flag.
    if (inter) f.workingBytes = 3 * bytes(TransferLayout::Vector, mesh.vertexCount());
    f.workingBytes += n * 16;
    return f;
  }
  if (s.domain == TransferDomain::Texels) {
    // Per texel of the whole lightmap: the pass being baked and the pass (or sum, or order) it
    // reads, that one laid out once more as a dilated lightmap, and the sample points (~40 B).
    const std::size_t all = bytes(s.layout, n), vec = bytes(TransferLayout::Vector, n);
    if (s.layout == TransferLayout::Vector)
      f.workingBytes = all * (inter ? 3 : 1);
    else if (!inter)
      f.workingBytes = all;
    else if (glossy)
      f.workingBytes = 3 * all;
    else
      f.workingBytes = all + 4 * vec;
    f.workingBytes += n * 40;
    return f;
  }
  if (glossy) {
    // The matrices with K − 1 bounces over the whole mesh, and while they are baked those with
    // K − 2 (each order is baked from the one before and then dropped).
    const std::size_t mat = bytes(TransferLayout::Matrix, n);
    f.workingBytes = s.bounces > 1 ? 2 * mat : mat;
  } else if (inter) {
    // Vector: two full-mesh buffers of the previous and current order. Matrix: the diffuse
    // vector transfer with K − 1 bounces over the whole mesh, plus its own working buffers.
    const std::size_t vec = bytes(TransferLayout::Vector, n);
    f.workingBytes = s.layout == TransferLayout::Matrix ? 3 * vec : 2 * vec;
  }
  return f;
}

}  // namespace prt
