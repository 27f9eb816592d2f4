#include "demo_haar.hpp"

#include <fmt/format.h>

#include <chrono>
#include <filesystem>

#include "cli.hpp"
#include "demo_page.hpp"
#include "prt/envmap/project.hpp"
#include "prt/haar/project_light.hpp"
#include "prt/image/image_io.hpp"
#include "prt/relight/relight_haar.hpp"
#include "prt/render/exposure.hpp"
#include "prt/render/relit_view.hpp"
#include "prt/render/render.hpp"
#include "prt/render/validate.hpp"
#include "prt/render/validate_haar.hpp"
#include "prt/transfer/haar_rows.hpp"
#include "prt/transport/bake.hpp"

namespace prt::cli {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

constexpr int kResolution = 32;
constexpr int kLightTerms = 200;
constexpr std::size_t kVertices = 2000;

}  // namespace

HaarRow demoHaarRow(const Mesh& mesh, const Occluder& occluder, const BakedTransfer& shadowed,
                    const std::vector<const envmap::Environment*>& envs,
                    const std::vector<std::string>& envNames, const DemoArgs& a,
                    const render::FrameSettings& frame, const render::Camera& camera,
                    const std::string& folder) {
  const auto t0 = Clock::now();
  HaarRow row;
  row.bands = shadowed.transfer.bands();
  row.resolution = kResolution;
  // The same bytes per vertex at most: 4 B² of SH; a Haar row's as stored (haar_rows.hpp).
  const std::size_t shBytes = shadowed.transfer.stride() * sizeof(float);
  row.terms = 1;
  while (haar::storedHaarRowBytes(kResolution, row.terms + 1) <= shBytes) ++row.terms;
  row.lightTerms = kLightTerms;
  row.referenceSamples = a.referenceSamples;
  BakeSettings hs;
  hs.mode = TransferMode::Shadowed;
  hs.basis = TransferBasis::Haar;
  hs.haar = {kResolution, row.terms};
  hs.samples = 1;
  const std::size_t haarBytes = haar::storedHaarRowBytes(kResolution, row.terms);
  info(fmt::format("demo: Haar row: {}² cube, {} terms per vertex ({} B, as {} SH bands)",
                   kResolution, row.terms, haarBytes, row.bands));
  const auto tb = Clock::now();
  const Transfer haarT = bake(mesh, occluder, hs);
  row.bakeSeconds = since(tb);
  const std::vector<Rgb> albedo = albedoAtVertices(mesh);

  for (std::size_t e = 0; e < envs.size() && e < 2; ++e) {
    const envmap::Environment& env = *envs[e];
    HaarRowLight L;
    L.environment = envNames[e];
    // Both against the same reference vertices (the same seed's subset).
    render::ValidateSettings sv;
    sv.reference.samples = a.referenceSamples;
    sv.bandsList = {row.bands};
    sv.maxVertices = kVertices;
    sv.floorVertices = 64;
    const sh::RgbSh light = envmap::projectEnvironment(env, row.bands);
    const render::ValidationReport sr =
        render::validate(mesh, occluder, shadowed.transfer, shadowed.recipe, env, light, sv);
    render::HaarValidateSettings hv;
    hv.reference.samples = a.referenceSamples;
    hv.lightTerms = {std::size_t(kLightTerms)};
    hv.precomputed = &sr.reference;  // the reference SH was measured against
    const render::HaarValidationReport hr =
        render::validateHaar(mesh, occluder, haarT, hs, env, hv);
    row.vertices = int(sr.reference.vertices.size());
    L.refStdErr = hr.refStdErr;
    const std::string name = std::to_string(e);
    L.sh = {fmt::format("SH, {} bands", row.bands), "img/haar_" + name + "_sh.png", shBytes,
            sr.rows.back().relRmse, sr.rows.back().energyRel};
    L.haar = {fmt::format("Haar, {}² cube, {} terms", kResolution, row.terms),
              "img/haar_" + name + "_haar.png", haarBytes,
              hr.rows.front().relRmse, hr.rows.front().energyRel};

    // The pictures, at the SH frame's exposure, so they compare.
    render::RelitView view(mesh, occluder, shadowed.transfer, Material{});
    view.relight(light, Mat3d::identity(), camera.eye, "demo");
    const render::ShadeFn shShade = view.shader();
    const haar::HaarLight hl = haar::projectLight(env, kResolution, kLightTerms);
    const std::vector<Rgb> radiance = relight::relightHaar(haarT, hl, mesh.normals, albedo);
    const render::ShadeFn haarShade = render::vertexRadianceShader(mesh, radiance);
    image::WriteOptions wo;
    wo.toneMap = image::ToneMap::Aces;
    wo.exposureStops = render::surveyFrame(occluder, shShade, camera, frame.width, frame.height,
                                           wo.toneMap)
                           .exposureStops;
    const render::BackgroundFn bg = render::environmentBackground(env, Mat3d::identity());
    for (const auto& [shade, image] :
         {std::pair{&shShade, L.sh.image}, std::pair{&haarShade, L.haar.image}})
      image::writeImage((std::filesystem::path(folder) / image).string(),
                        render::tracePrimary(camera, frame, occluder, *shade, bg), wo);
    info(fmt::format("demo: Haar row under {}: SH {:.1f}% ({} B) vs Haar {:.1f}% ({} B) rel. RMSE",
                     L.environment, 100 * L.sh.relRmse, shBytes, 100 * L.haar.relRmse, haarBytes));
    row.lights.push_back(std::move(L));
  }
  row.seconds = since(t0);
  return row;
}

}  // namespace prt::cli
