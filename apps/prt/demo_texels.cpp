#include "demo_texels.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>

#include "cli.hpp"
#include "demo_page.hpp"
#include "prt/envmap/project.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/image/image_io.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/relight/relighter.hpp"
#include "prt/render/camera.hpp"
#include "prt/render/exposure.hpp"
#include "prt/render/metrics.hpp"
#include "prt/render/reference.hpp"
#include "prt/render/render.hpp"
#include "prt/transport/bake.hpp"
#include "prt/transport/bake_texels.hpp"

namespace prt::cli {

namespace {

constexpr int kResolution = 128;
constexpr int kCoarseGrid = 2;
constexpr int kReferenceGrid = 48;
/// The reference takes this many times --reference-samples a vertex: its band-limited lane
/// (the negative lobes of a cut light) is noisier than the radiance itself.
constexpr int kReferenceSampleFactor = 4;

std::string box(int grid) {
  return fmt::format("builtin:cornell?grid={}", grid);
}

/// The grid whose box has the vertex count nearest `rows` (vertex count grows with the grid).
int gridWithRows(std::size_t rows) {
  int best = kCoarseGrid;
  double bestGap = 1e300;
  for (int g = kCoarseGrid; g <= 256; ++g) {
    const double gap = std::abs(double(builtinScene(box(g)).vertexCount()) - double(rows));
    if (gap > bestGap) break;
    bestGap = gap, best = g;
  }
  return best;
}

/// Relative RMSE over the pixels the reference shows the model in (the background is black in
/// both and would only dilute it).
double modelRelRmse(const image::Image& test, const image::Image& ref) {
  double sum = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < ref.pixels.size(); ++i) {
    const Rgb r = ref.pixels[i], t = test.pixels[i];
    if (r.x + r.y + r.z <= 0) continue;
    for (int c = 0; c < 3; ++c) {
      const double d = (&t.x)[c] - (&r.x)[c];
      sum += d * d / ((&r.x)[c] * (&r.x)[c] + 1e-2);
    }
    n += 3;
  }
  return n ? std::sqrt(sum / double(n)) : 0.0;
}

/// The fine box's vertices as the reference's points, those on the edge of their surface moved
/// 1 mm into it (along the surface, toward the mean of their triangles' centroids): the radiance
/// at a vertex is the limit of the surface's radiance as a point approaches it, and a vertex on
/// a corner — a wall's edge on the floor — lies on the other surface's edge, where half its rays
/// pass under it (docs/validation.md: the reference there was five times too dark, and drawn per
/// vertex the darkness spread over the vertex spacing). A vertex inside its surface, whose
/// triangles surround it, stays where it is.
std::shared_ptr<render::RowPoints> insetVertices(const Mesh& m) {
  auto pts = std::make_shared<render::RowPoints>();
  std::vector<Vec3f> centre(m.vertexCount(), Vec3f(0.0f));
  std::vector<float> reach(m.vertexCount(), 0.0f);  // the mean distance to its centroids
  std::vector<int> count(m.vertexCount(), 0);
  for (const auto& t : m.triangles) {
    const Vec3f c = (m.positions[t[0]] + m.positions[t[1]] + m.positions[t[2]]) * (1.0f / 3.0f);
    for (int k = 0; k < 3; ++k)
      centre[t[k]] += c, reach[t[k]] += length(c - m.positions[t[k]]), ++count[t[k]];
  }
  constexpr float kInset = 1e-3f;
  pts->positions = m.positions;
  for (std::size_t v = 0; v < m.vertexCount(); ++v) {
    if (!count[v]) continue;
    const float inv = 1.0f / float(count[v]);
    Vec3f d = centre[v] * inv - m.positions[v];
    d = d - m.normals[v] * dot(m.normals[v], d);  // along the surface
    // On the edge when its triangles lie to one side: their centroids' mean a good part of
    // their distance away (inside a surface it is the vertex itself, to rounding).
    if (length(d) > 0.2f * reach[v] * inv) pts->positions[v] += d * (kInset / length(d));
  }
  pts->normals = m.normals;
  pts->albedo = m.albedo;
  return pts;
}

}  // namespace

TexelRow demoTexelRow(const envmap::Environment& env, const std::string& envName, const DemoArgs& a,
                      const render::FrameSettings& frame, const std::string& folder) {
  const auto t0 = std::chrono::steady_clock::now();
  TexelRow row;
  row.environment = envName;
  row.resolution = kResolution;
  row.bands = a.bands;
  const sh::RgbSh light = envmap::projectEnvironment(env, a.bands);
  BakeSettings s;
  s.mode = TransferMode::Interreflected;
  s.bounces = a.bounces;
  s.bands = a.bands;
  s.samples = a.samples;

  const Mesh coarse = builtinScene(box(kCoarseGrid));
  const auto coarseOcc = makeEmbreeOccluder(coarse);
  const render::Camera camera = render::frameMesh(coarse, frame.width, frame.height);
  const auto draw = [&](const Occluder& occ, const render::ShadeFn& shade) {
    return render::tracePrimary(camera, frame, occ, shade, {});
  };

  // The reference: brute force at the fine box's vertices (each just inside its faces:
  // insetVertices), drawn as per-vertex radiance.
  const Mesh fine = builtinScene(box(kReferenceGrid));
  const auto fineOcc = makeEmbreeOccluder(fine);
  render::ReferenceSettings rs;
  rs.points = insetVertices(fine);
  rs.samples = a.referenceSamples * kReferenceSampleFactor;
  rs.mode = s.mode;
  rs.bounces = s.bounces;
  // Beside it, the exact relighting under the light cut to the bands PRT has (e_b): what a
  // noise-free bake at infinite resolution gives, so the errors below are the storage's alone.
  rs.bandLimit = render::BandLimitSettings{light, {render::BandLimit{a.bands, {}}}, false};
  const render::ReferenceResult ref =
      render::renderReference(fine, *fineOcc, env, rs, progressBar("reference texels row"));
  std::vector<Rgb> refRadiance(fine.vertexCount()), limited(fine.vertexCount());
  for (std::size_t i = 0; i < ref.vertices.size(); ++i) {
    refRadiance[ref.vertices[i]] = ref.radiance[i];
    limited[ref.vertices[i]] = ref.bandLimited[i].radiance.mean;
  }
  const image::Image fullImage = draw(*fineOcc, render::vertexRadianceShader(fine, refRadiance));
  const image::Image refImage = draw(*fineOcc, render::vertexRadianceShader(fine, limited));
  // The reference's own noise, as the errors below measure it (relative, RMS over vertices).
  double noise = 0;
  for (const render::BandLimitedEstimate& e : ref.bandLimited)
    for (int c = 0; c < 3; ++c) {
      const double m = (&e.radiance.mean.x)[c], se = (&e.radiance.stdError.x)[c];
      noise += se * se / (m * m + 1e-2);
    }
  row.referenceNoise = std::sqrt(noise / std::max<std::size_t>(1, 3 * ref.bandLimited.size()));
  row.referenceVertices = int(fine.vertexCount());
  row.referenceSamples = rs.samples;
  const float exposure =
      render::autoExposure(*fineOcc, render::vertexRadianceShader(fine, refRadiance), camera,
                           frame.width, frame.height, image::ToneMap::Aces);
  const image::WriteOptions wo{image::ToneMap::Aces, exposure};
  const auto save = [&](const std::string& name, const image::Image& img) {
    image::writeImage((std::filesystem::path(folder) / name).string(), img, wo);
    return name;
  };
  row.referenceImage = save("img/texels_reference.png", refImage);
  row.fullReferenceImage = save("img/texels_reference_full.png", fullImage);

  const auto vertexEntry = [&](const Mesh& m, const std::string& label, const std::string& name) {
    const auto occ = makeEmbreeOccluder(m);
    const Transfer t = bake(m, *occ, s, nullptr, progressBar("bake " + name));
    relight::Relighter r(t, {m.positions, m.normals, m.albedo});
    const std::span<const Rgb> lit = r.relight(light, Mat3d::identity(), camera.eye);
    const std::vector<Rgb> radiance(lit.begin(), lit.end());
    const image::Image img = draw(*occ, render::vertexRadianceShader(m, radiance));
    TexelRowEntry e{label,
                    save("img/texels_" + name + ".png", img),
                    t.rowCount(),
                    t.shape().denseBytes(),
                    modelRelRmse(img, refImage),
                    modelRelRmse(img, fullImage)};
    return e;
  };
  row.coarse = vertexEntry(
      coarse, fmt::format("per vertex, the coarse box ({} vertices)", coarse.vertexCount()),
      "coarse");

  // Per texel on the same coarse box.
  const TexelBake tb = bakeTexels(coarse, *coarseOcc, s, coarse.lightmapUvs, kResolution,
                                  kResolution, 2, nullptr, progressBar("bake texels"));
  relight::Relighter rt(tb.transfer, relight::Surface{});
  const std::span<const Rgb> lit = rt.relight(light, Mat3d::identity(), camera.eye);
  const std::vector<Rgb> lightmap(lit.begin(), lit.end());
  const image::Image texImg =
      draw(*coarseOcc,
           render::texelRadianceShader(coarse, lightmap, kResolution, kResolution, coarse.albedo));
  row.texels = {fmt::format("per texel, the same coarse box ({}² lightmap)", kResolution),
                save("img/texels_texels.png", texImg),
                tb.transfer.rowCount(),
                tb.transfer.shape().denseBytes(),
                modelRelRmse(texImg, refImage),
                modelRelRmse(texImg, fullImage)};

  // Per vertex at the lightmap's bytes: the box tessellated to as many vertices as texels.
  const Mesh dense = builtinScene(box(gridWithRows(tb.transfer.rowCount())));
  row.dense = vertexEntry(dense,
                          fmt::format("per vertex, the box tessellated to the same bytes ({} "
                                      "vertices)",
                                      dense.vertexCount()),
                          "dense");
  row.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  info(
      fmt::format("demo: per-texel row: rel. RMSE against the reference: per vertex (coarse) "
                  "{:.1f}%, per texel {:.1f}%, per vertex at the same bytes {:.1f}% (the "
                  "reference's noise {:.1f}%; {:.1f} s)",
                  100 * row.coarse.relRmse, 100 * row.texels.relRmse, 100 * row.dense.relRmse,
                  100 * row.referenceNoise, row.seconds));
  return row;
}

}  // namespace prt::cli
