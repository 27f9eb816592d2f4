#include "scene.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "haar_view.hpp"
#include "probe_view.hpp"
#include "prt/core/band_limits.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/core/units.hpp"
#include "prt/envmap/load.hpp"
#include "prt/envmap/preview.hpp"
#include "prt/envmap/project.hpp"
#include "prt/geometry/load.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/relight/relight.hpp"
#include "prt/render/base_colour.hpp"
#include "prt/render/haar_shader.hpp"
#include "prt/render/texel_points.hpp"

namespace prt::viewer {

namespace {

/// Lat-long width for the background of a tabulated or analytic environment: an image already
/// lat-long is used as it is; others are resampled at about their own resolution.
int latLongWidth(const envmap::Environment& env) {
  const auto& imgs = env.images();
  const int n = imgs.empty() ? 512 : imgs.front().width;
  switch (env.kind()) {
    case envmap::Environment::Kind::Cube:
      return std::clamp(4 * n, 512, 4096);
    case envmap::Environment::Kind::Probe:
      return std::clamp(2 * n, 512, 4096);
    default:  // analytic: sharp sun discs deserve more texels than the projection's
      return 2048;
  }
}

}  // namespace

// ---- OrbitCamera ------------------------------------------------------------------------------

void OrbitCamera::orbit(double dYaw, double dPitch) {
  orbit_.yaw += dYaw;
  orbit_.pitch = render::clampPitch(start_, orbit_.pitch + dPitch);
}

void OrbitCamera::pan(double dx, double dy) {
  const render::Camera c = camera();
  const render::CameraBasis b = render::cameraBasis(c, 1, 1);
  // The view is 2 d tan(fovY/2) tall at the target.
  const double height = 2.0 * length(Vec3d(c.eye) - Vec3d(c.target)) * double(b.tanY);
  orbit_.pan += (Vec3d(b.right) * -dx + Vec3d(b.up) * dy) * height;
}

void OrbitCamera::zoom(double factor) {
  const double d0 = length(Vec3d(start_.eye) - Vec3d(start_.target));
  orbit_.scale = std::max(orbit_.scale * factor, 1e-6 / std::max(d0, 1e-12));
}

// ---- Scene --------------------------------------------------------------------------------------

BakeFile Scene::readCheckedBake(const std::string& path) {
  // CPCA-compressed transfer (prt compress) stays compressed: it is relit in the compressed
  // space (SceneView).
  // A base-colour texture stays with the mesh: the fragment stage multiplies it per pixel, as
  // prt render does (render/base_colour.hpp; SceneView::prepare).
  BakeFile bake = readBake(path);
  if (bake.transfers.empty())
    throw Error(path, "the bake holds no transfer (bake it with prt bake --mode ...)");
  bake.requireComplete(path);
  if (bake.transfers.front().transfer.isHaar()) {
    // Relit on the CPU, per vertex or per texel (haar_view.hpp); a file holds one basis.
    return bake;
  }
  for (const BakedTransfer& t : bake.transfers) {
    // Some path draws it (per-texel matrices only compressed; probes on the CPU, probe_view),
    // else refused naming the file.
    try {
      if (t.transfer.domain() != TransferDomain::Probes) relight::shaderPath(t.transfer, false);
    } catch (const Error& e) {
      throw Error(path, std::string(e.what()) + " (" + t.describe() + ")");
    }
    if (t.transfer.bands() > kMaxViewerBands)
      throw Error(path, bands::bandLimitMessage("the " + t.describe() + " transfer",
                                                t.transfer.bands(), "the viewer", kMaxViewerBands));
    if (t.transfer.bands() != bake.transfers.front().transfer.bands())
      throw Error(path, fmt::format("its transfers have different band counts ({} {}, {} {})",
                                    bake.transfers.front().describe(),
                                    bake.transfers.front().transfer.bands(), t.describe(),
                                    t.transfer.bands()));
  }
  return bake;
}

EnvironmentEntry Scene::loadEnvironment(const std::string& spec, int bands) {
  EnvironmentEntry e;
  e.name = spec;
  e.lighting = io::loadLighting(spec, bands);
  e.light = io::padded(e.lighting.coefficients, bands);
  if (e.lighting.isShFile()) {
    e.latLong = envmap::renderSh(e.lighting.coefficients, 512);
  } else {
    const envmap::Environment& env = *e.lighting.image;
    e.latLong = env.kind() == envmap::Environment::Kind::LatLong
                    ? env.images().front()
                    : envmap::renderEnvironment(env, latLongWidth(env));
  }
  return e;
}

void Scene::setBake(BakeFile bake, const std::string& name, int width, int height) {
  PRT_CHECK(!bake.transfers.empty(), "setBake needs a transfer");
  // A Haar bake has no SH bands: its environments' 1-band SH serve the background alone, and it
  // is relit from their images (an SH light file holds none).
  const int bands = std::max(1, bake.transfers.front().transfer.bands());
  if (bake.transfers.front().transfer.isHaar())
    for (const auto& e : envs_)
      if (e->lighting.isShFile())
        throw Error(name, "holds Haar transfer, and the light " + e->name +
                              " is an SH light file: load an environment first");
  if (bands != bakeBands_) {
    // The environments at the new band count, all or nothing.
    std::vector<std::shared_ptr<const EnvironmentEntry>> envs;
    for (const auto& e : envs_)
      envs.push_back(std::make_shared<const EnvironmentEntry>(loadEnvironment(e->name, bands)));
    envs_ = std::move(envs);
  }
  auto shared = std::make_shared<const BakeFile>(std::move(bake));
  order_ = transferPreference(*shared);
  bake_ = std::move(shared);
  bakeName_ = name;
  bakeBands_ = bands_ = bands;
  transfer_ = 0;
  material_ = materialOverride_ ? *materialOverride_ : transfer().recipe.material;
  orbit = OrbitCamera(render::frameMesh(bake_->mesh, width, height));
  object.reset();
  if (probeBake()) {
    if (!objectMesh_) {
      objectName_ = "builtin:sphere?subdiv=3";
      objectMesh_ = std::make_shared<const Mesh>(prt::loadScene({objectName_}));
    }
    object.emplace(*objectMesh_, objectName_, bake_->probeGrid());
  }
}

void Scene::setObject(Mesh mesh, const std::string& name) {
  objectMesh_ = std::make_shared<const Mesh>(std::move(mesh));
  objectName_ = name;
  if (probeBake()) object.emplace(*objectMesh_, objectName_, bake_->probeGrid());
}

void Scene::addEnvironment(EnvironmentEntry entry) {
  if (haarBake() && entry.lighting.isShFile())
    throw Error(entry.name, "is an SH light file, and " + bakeName_ +
                                " holds Haar transfer: give the environment (an image, a face "
                                "folder or builtin:NAME)");
  if (warn)
    for (const std::string& w : entry.lighting.warnings) warn(w);
  envs_.push_back(std::make_shared<const EnvironmentEntry>(std::move(entry)));
  selectEnvironment(int(envs_.size()) - 1);
}

std::string Scene::loadDropped(const std::string& path, int width, int height) {
  try {
    if (fileExtension(path) == "glb") {
      BakeFile b = readCheckedBake(path);
      setBake(std::move(b), path, width, height);
    } else {
      addEnvironment(loadEnvironment(path, bakeBands_));
    }
    return "";
  } catch (const std::exception& e) {
    return e.what();
  }
}

void Scene::selectTransfer(int k) {
  k = std::clamp(k, 0, int(order_.size()) - 1);
  if (k == transfer_) return;
  transfer_ = k;
  material_ = materialOverride_ ? *materialOverride_ : transfer().recipe.material;
}

void Scene::selectMode(TransferMode mode) {
  for (std::size_t k = 0; k < order_.size(); ++k)
    if (transferAt(k).mode() == mode) {
      selectTransfer(int(k));
      return;
    }
  prt::pickTransfer(*bake_, mode, {}, bakeName_);  // throws, naming what the bake holds
}

void Scene::selectEnvironment(int k) {
  if (envs_.empty()) return;
  env_ = std::clamp(k, 0, int(envs_.size()) - 1);
}

void Scene::setBands(int b) {
  bands_ = std::clamp(b, 1, std::max(bakeBands_, 1));
}

Mat3d Scene::lightRotation() const {
  return rotationAxisAngle({0, 1, 0}, spinRad_) * userRotation_;
}

void Scene::dragLight(double dx, double dy) {
  const double k = kDragDegreesPerPixel * kPi / 180.0;
  const Vec3d right = Vec3d(render::cameraBasis(orbit.camera(), 1, 1).right);
  userRotation_ =
      rotationAxisAngle({0, 1, 0}, dx * k) * rotationAxisAngle(right, dy * k) * userRotation_;
}

void Scene::advanceSpin(double seconds) {
  if (autoRotate)
    spinRad_ = std::fmod(spinRad_ + seconds * spinDegreesPerSecond * kPi / 180.0, 2.0 * kPi);
}

image::Image Scene::shBackground() const {
  if (envs_.empty()) return image::Image(1, 1);
  return envmap::renderSh(envs_[env_]->light.truncated(bands_), 512);
}

DrawState Scene::drawState() const {
  DrawState d;
  d.bake = bake_;
  d.transfer = order_.empty() ? nullptr : &transfer();
  d.bands = bands_;
  d.material = material_;
  d.environment = envs_.empty() ? nullptr : envs_[env_];
  d.background = background;
  if (object) {
    d.object = object->mesh();
    d.objectAt = object->position();
    d.objectSize = object->size();
    d.showProbes = showProbes;
  }
  return d;
}

// ---- SceneView ----------------------------------------------------------------------------------

void SceneView::setTransfer(const DrawState& now) {
  const Transfer& t = now.transfer->transfer;
  path_ = relight::shaderPath(t, glossyOnGpu);
  const CpcaRows* c = t.compressed() ? &t.cpca() : nullptr;
  renderer_.setTransfer(relight::packShaderRows(t, path_), t.shape(), c ? c->clusters : 0,
                        c ? c->basisCount : 0);
  const Mesh& mesh = now.bake->mesh;
  // Glossy per pixel: each texel shaded at its own sample point (render::shadingPoints).
  if (const std::vector<float> points = render::shadingPoints(mesh, t, now.material);
      !points.empty())
    renderer_.setTexelPoints(points);
  // (The transfer's rows are shared, not copied.)
  cpuView_.reset();
  if (path_ == relight::ShaderPath::CpuRadiance) cpuView_.emplace(mesh, t, now.material);
}

void SceneView::uploadEnvironment(const Scene& scene, const DrawState& now) {
  if (now.environment != drawn_.environment && now.environment) {
    renderer_.setEnvironmentImage(now.environment->latLong);
    packer_.setLight(now.environment->light);
  }
  // The SH background image is made only while it is shown.
  const bool shChanged = now.environment != drawn_.environment || now.bands != drawn_.bands;
  if (shChanged) shImageValid_ = false;
  if (now.background == BackgroundMode::Sh && !shImageValid_) {
    renderer_.setShImage(scene.shBackground());
    shImageValid_ = true;
  }
}

FrameParams SceneView::beginFrame(const Scene& scene, const DrawState& now, int width,
                                  int height) {
  FrameParams f;
  f.width = width, f.height = height;
  f.camera = scene.orbit.camera();
  f.bands = now.bands;
  f.lightRotation = scene.lightRotation();
  packer_.pack(f.lightRotation, now.bands);
  relightSeconds_ = 0;
  f.light = &packer_;
  f.background = now.background;
  f.exposureStops = scene.exposureStops;
  f.toneMap = scene.toneMap;
  return f;
}

FrameParams SceneView::prepareProbes(const Scene& scene, const DrawState& now, int width,
                                     int height) {
  const bool newMesh = now.bake != drawn_.bake || now.object != drawn_.object ||
                       !(now.objectAt == drawn_.objectAt) || now.objectSize != drawn_.objectSize ||
                       now.showProbes != drawn_.showProbes || path_ != relight::ShaderPath::CpuRadiance;
  if (newMesh) {
    probeMesh_ = probeSceneMesh(*now.bake, scene.object ? &*scene.object : nullptr,
                                now.showProbes);
    renderer_.setMesh(probeMesh_);
    useCpuRadiance(probeMesh_.vertexCount());
    probeLight_.clear();
  }
  uploadEnvironment(scene, now);
  const bool newTransfer = now.transfer != drawn_.transfer;
  drawn_ = now;

  const auto t0 = std::chrono::steady_clock::now();
  FrameParams f = beginFrame(scene, now, width, height);
  const std::span<const Rgb> light = packer_.rotated();
  if (newMesh || newTransfer || !std::equal(light.begin(), light.end(), probeLight_.begin(),
                                            probeLight_.end())) {
    probeLight_.assign(light.begin(), light.end());
    shadedRadiance_ = shadeProbeScene(now.transfer->transfer, now.bands, light, probeMesh_);
    renderer_.setRadiance(shadedRadiance_);
    ++shadedRelights_;
    relightSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  lightSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return f;
}

void SceneView::useCpuRadiance(std::size_t vertices) {
  relight::ShaderRows rows;
  rows.path = relight::ShaderPath::CpuRadiance;
  TransferShape shape;
  shape.rows = {0, vertices};
  renderer_.setTransfer(rows, shape);
  path_ = rows.path;
  cpuView_.reset();
}

FrameParams SceneView::prepareHaar(const Scene& scene, const DrawState& now, int width,
                                   int height) {
  const Mesh& mesh = now.bake->mesh;
  const Transfer& t = now.transfer->transfer;
  const bool perTexel = relight::drawnPerPixel(t);
  // Per texel the albedo multiplies per pixel unless the material's kd replaces it (then kd is
  // in the relit radiance, and the mesh is drawn white: render::texelAlbedo's rule).
  const bool white = perTexel && now.material.diffuse && !mesh.albedo.empty();
  const bool newMesh = now.bake != drawn_.bake || white != haarWhiteMesh_;
  const bool newTransfer = newMesh || now.transfer != drawn_.transfer;
  const bool newLight = now.environment != drawn_.environment || !(now.material == drawn_.material);
  if (newMesh) {
    if (white) {
      Mesh shown = mesh;
      shown.albedo.clear();
      renderer_.setMesh(shown);
    } else {
      renderer_.setMesh(mesh);
    }
    haarWhiteMesh_ = white;
  }
  if (newTransfer) {
    if (perTexel) {
      haarTexelNormals_ = haarTexelNormals(mesh, t);
      path_ = relight::ShaderPath::DenseVector;  // each relight uploads its radiance lightmap
      cpuView_.reset();
    } else {
      haarTexelNormals_.clear();
      useCpuRadiance(mesh.vertexCount());
    }
  }
  uploadEnvironment(scene, now);
  drawn_ = now;

  const auto t0 = std::chrono::steady_clock::now();
  FrameParams f = beginFrame(scene, now, width, height);
  if (newTransfer || newLight || !(f.lightRotation == haarRotation_)) {
    PRT_CHECK(now.environment && now.environment->lighting.image,
              "a Haar bake is relit from an environment image (Scene::addEnvironment)");
    const envmap::Environment& env = *now.environment->lighting.image;
    const int n = t.shape().haar.resolution;
    if (!haarLight_ || haarLightFor_ != now.environment || haarLight_->resolution() != n) {
      haarLight_.emplace(env, n);
      haarLightFor_ = now.environment;  // held: the light keeps a pointer into it
    }
    const haar::HaarLight light = haarLight_->at(f.lightRotation);
    if (perTexel) {
      const TransferShape::LightmapSize& lm = t.shape().lightmap;
      shadedRadiance_ = render::haarRadiance(mesh, t, now.material, light, haarTexelNormals_);
      renderer_.setTransfer(
          relight::packRadianceLightmap(shadedRadiance_, lm, packer_.rotated()[0]),
          relight::radianceLightmapShape(lm));
    } else {
      shadedRadiance_ = render::haarRadiance(mesh, t, now.material, light);
      renderer_.setRadiance(shadedRadiance_);
    }
    haarRotation_ = f.lightRotation;
    haarLightTerms_ = light.terms();
    ++shadedRelights_;
    relightSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  lightSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // Per vertex the base-colour texture is folded into the vertices' albedo, as prt render draws
  // a Haar bake; per texel it multiplies per pixel.
  f.baseColour = perTexel && render::pixelTexture(mesh, now.material) != nullptr;
  return f;
}

FrameParams SceneView::prepare(const Scene& scene, int width, int height) {
  const DrawState now = scene.drawState();
  if (now.bake->domain() == TransferDomain::Probes) return prepareProbes(scene, now, width, height);
  if (now.transfer && now.transfer->transfer.isHaar())
    return prepareHaar(scene, now, width, height);
  using relight::ShaderPath;
  const bool newMesh = now.bake != drawn_.bake;
  const bool newTransfer = newMesh || now.transfer != drawn_.transfer;
  if (newMesh) renderer_.setMesh(now.bake->mesh);
  if (newTransfer) setTransfer(now);
  const Transfer& t = now.transfer->transfer;
  if (newTransfer || now.bands != drawn_.bands)
    shown_ = path_ == ShaderPath::CpcaVector || path_ == ShaderPath::CpcaMatrix ? t.cut(now.bands)
                                                                                : Transfer();
  // The base-colour texture multiplies per pixel unless the material's kd replaces it.
  const BaseColourTexture* texture = render::pixelTexture(now.bake->mesh, now.material);
  if (cpuView_) {
    cpuView_->setBands(now.bands);
    cpuView_->setMaterial(now.material);
  }
  const bool glossyKernels = path_ == ShaderPath::DenseMatrix || path_ == ShaderPath::CpcaMatrix;
  if (glossyKernels && (newTransfer || !(now.material == drawn_.material))) {
    // The kernels depend on l only, so the transfer's band count serves every b ≤ B.
    const PreparedMaterial pm = prepareMaterial(now.material, t.bands());
    renderer_.setGlossyMaterial(pm.diffuse, pm.glossy, pm.kd, pm.specular);
  }
  uploadEnvironment(scene, now);
  drawn_ = now;

  const auto t0 = std::chrono::steady_clock::now();
  FrameParams f = beginFrame(scene, now, width, height);
  if (path_ == ShaderPath::CpcaVector || path_ == ShaderPath::CpcaMatrix) {
    // K(N+1) projections of D(R) L onto the transfer cut to the shown bands.
    relight::packClusterTable(
        relight::projectClusters(shown_, relight::prepareLight(packer_.rotated(), now.bands)),
        clusterTable_);
    f.clusterTable = clusterTable_;
  } else if (path_ == ShaderPath::CpuRadiance) {
    const auto tr = std::chrono::steady_clock::now();
    if (cpuView_->relightRotated(packer_.rotated(), now.bands, f.camera.eye)) {
      renderer_.setRadiance(cpuView_->radiance(), cpuView_->highlight());
      relightSeconds_ =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - tr).count();
    }
  }
  lightSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  f.baseColour = texture != nullptr;
  return f;
}

std::size_t SceneView::lightUploadBytes() const {
  switch (path_) {
    case relight::ShaderPath::CpcaVector:
    case relight::ShaderPath::CpcaMatrix:
      return renderer_.clusterTableBytes();
    case relight::ShaderPath::CpuRadiance:
      return sizeof(Rgb) * (cpuView_ ? cpuView_->radiance().size() : shadedRadiance_.size());
    default:
      // A per-texel Haar bake's relit lightmap, one (r, g, b, 0) texel each.
      if (!haarTexelNormals_.empty()) return 16 * haarTexelNormals_.size() + packer_.bytes();
      return packer_.bytes();
  }
}

std::string SceneView::uploadSummary(const Scene& scene) const {
  const Transfer& t = scene.transfer().transfer;
  const char* row = rowName(t.domain());
  const std::string where =
      relight::drawnPerPixel(t)
          ? fmt::format(" per pixel from a {} x {} lightmap", t.shape().lightmap.width,
                        t.shape().lightmap.height)
          : std::string(" per vertex");
  // A dense row's bytes: a vector's on the dense path, a matrix's B⁴ floats a channel.
  const std::size_t dense =
      t.isMatrix()
          ? sizeof(float) * std::size_t(t.coeffs()) * std::size_t(t.coeffs()) * t.channels()
          : 16 * std::size_t(relight::shaderTexelsPerRow(t, relight::ShaderPath::DenseVector));
  const std::string upload = bytesText(t.rowCount() * renderer_.bytesPerVertex());
  if (t.isHaar())
    return fmt::format(
        "Haar transfer ({}² cube, {} terms a {}, {} B stored) relit on the CPU under the "
        "light's {} largest terms: {} bytes of radiance per {} per relit frame{}",
        t.shape().haar.resolution, t.shape().haar.terms, row,
        t.rowCount() ? t.bytes() / t.rowCount() : 0, haarLightTerms_,
        relight::drawnPerPixel(t) ? 16 : sizeof(Rgb), row,
        relight::drawnPerPixel(t) ? ", drawn" + where : std::string());
  if (t.domain() == TransferDomain::Probes)
    return fmt::format(
        "{} relit on the CPU, then the scene, the object and the markers shaded through them: "
        "{} bytes of radiance per vertex per relit frame ({} vertices)",
        t.shape().probes.describe(), sizeof(Rgb), probeMesh_.vertexCount());
  switch (path_) {
    case relight::ShaderPath::CpuRadiance:
      return fmt::format(
          "{} relit on the CPU (relight::Relighter): {} bytes of radiance per {} per relit frame",
          t.compressed() ? fmt::format("compressed (CPCA {} x {}) matrices", t.cpca().clusters,
                                       t.cpca().basisCount)
                         : std::string("dense matrices"),
          sizeof(Rgb), row);
    case relight::ShaderPath::CpcaVector:
    case relight::ShaderPath::CpcaMatrix:
      return fmt::format(
          "relit compressed {}(CPCA {} x {}){}: {} bytes per {} uploaded once ({}; dense: {}), {} "
          "bytes of cluster table per frame",
          t.isMatrix() ? "glossy matrices " : "", t.cpca().clusters, t.cpca().basisCount, where,
          renderer_.bytesPerVertex(), row, upload, dense, renderer_.clusterTableBytes());
    default:
      return fmt::format("dense transfer relit{}: {} bytes per {} uploaded ({})", where,
                         renderer_.bytesPerVertex(), row, upload);
  }
}

std::string Scene::basisText() const {
  const Transfer& t = transfer().transfer;
  if (t.isHaar())
    return fmt::format("Haar {}² cube, {} terms a row", t.shape().haar.resolution,
                       t.shape().haar.terms);
  return fmt::format("{} of {} bands", bands_, bakeBands_);
}

}  // namespace prt::viewer
