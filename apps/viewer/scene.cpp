#include "scene.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/envmap/load.hpp"
#include "prt/envmap/preview.hpp"
#include "prt/envmap/project.hpp"
#include "prt/io/light_file.hpp"
#include "prt/relight/relight.hpp"

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

/// The modes from the richest to the plainest, as prt render picks its default.
int richness(TransferMode m) {
  switch (m) {
    case TransferMode::Interreflected:
      return 0;
    case TransferMode::Shadowed:
      return 1;
    case TransferMode::Unshadowed:
      return 2;
  }
  return 3;
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
  // space (SceneView); `field` keeps its shape (layout, bands, channels) for the checks below.
  BakeFile bake = readBake(path);
  if (bake.transfers.empty())
    throw Error(path, "the bake holds no transfer (bake it with prt bake --mode ...)");
  bake.requireComplete(path);
  for (const BakedTransfer& t : bake.transfers) {
    if (t.field.bands < 1 || t.field.bands > kMaxViewerBands)
      throw Error(path, fmt::format("the {} transfer has {} bands; the viewer draws 1..{}",
                                    toString(t.settings.mode), t.field.bands, kMaxViewerBands));
    if (t.field.bands != bake.transfers.front().field.bands)
      throw Error(path, fmt::format("its transfers have different band counts ({} {}, {} {})",
                                    toString(bake.transfers.front().settings.mode),
                                    bake.transfers.front().field.bands, toString(t.settings.mode),
                                    t.field.bands));
  }
  return bake;
}

namespace {

/// An SH light file's coefficients at the bake's bands: cut when it has more (exact: bands are
/// orthogonal), refused when it has fewer.
sh::RgbSh fitShLight(const std::string& name, const sh::RgbSh& source, int bands) {
  if (source.bands < bands)
    throw Error(name, fmt::format("the light has {} bands but the bake {}; the transfer's upper "
                                  "bands would see no light (write it with prt light --bands {})",
                                  source.bands, bands, bands));
  return source.truncated(bands);
}

}  // namespace

EnvironmentEntry Scene::loadEnvironment(const std::string& spec, int bands) {
  EnvironmentEntry e;
  e.name = spec;
  if (io::isLightFile(spec)) {
    e.isShFile = true;
    e.source = io::readLight(spec).coefficients;
    e.light = fitShLight(spec, e.source, bands);
    e.latLong = envmap::renderSh(e.source, 512);
    return e;
  }
  envmap::LoadedEnvironment loaded = envmap::loadEnvironment(spec);
  e.env = std::move(loaded.env);
  if (e.env.kind() == envmap::Environment::Kind::LatLong)
    e.latLong = e.env.images().front();
  else
    e.latLong = envmap::renderEnvironment(e.env, latLongWidth(e.env));
  e.light = envmap::projectEnvironment(e.env, bands);
  return e;
}

void Scene::setBake(BakeFile bake, const std::string& name, int width, int height) {
  PRT_CHECK(!bake.transfers.empty(), "setBake needs a transfer");
  const int bands = bake.transfers.front().field.bands;
  if (bands != bakeBands_) {
    // All or nothing: an SH light file with too few bands for the new bake refuses the bake.
    std::vector<sh::RgbSh> lights;
    for (const EnvironmentEntry& e : envs_)
      lights.push_back(e.isShFile ? fitShLight(e.name, e.source, bands)
                                  : envmap::projectEnvironment(e.env, bands));
    for (std::size_t k = 0; k < envs_.size(); ++k) envs_[k].light = std::move(lights[k]);
  }
  // pickTransfer's order: the richest mode first, a matrix before a vector of the same mode.
  std::stable_sort(bake.transfers.begin(), bake.transfers.end(),
                   [](const BakedTransfer& a, const BakedTransfer& b) {
                     const int ra = richness(a.settings.mode), rb = richness(b.settings.mode);
                     if (ra != rb) return ra < rb;
                     return a.field.isMatrix() && !b.field.isMatrix();
                   });
  bake_ = std::move(bake);
  bakeName_ = name;
  bakeBands_ = bands_ = bands;
  transfer_ = 0;
  setMaterial(materialOverride_ ? *materialOverride_ : bake_.transfers.front().settings.material);
  orbit = OrbitCamera(render::frameMesh(bake_.mesh, width, height));
  ++meshVersion, ++transferVersion, ++shVersion;
}

void Scene::setMaterial(const Material& m) {
  material_ = m;
  ++materialVersion;
}

void Scene::addEnvironment(EnvironmentEntry entry) {
  envs_.push_back(std::move(entry));
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
  k = std::clamp(k, 0, int(bake_.transfers.size()) - 1);
  if (k == transfer_) return;
  transfer_ = k, ++transferVersion;
  setMaterial(materialOverride_ ? *materialOverride_ : bake_.transfers[k].settings.material);
}

void Scene::selectEnvironment(int k) {
  if (envs_.empty()) return;
  env_ = std::clamp(k, 0, int(envs_.size()) - 1);
  ++envVersion, ++shVersion;
}

void Scene::setBands(int b) {
  b = std::clamp(b, 1, std::max(bakeBands_, 1));
  if (b != bands_) bands_ = b, ++shVersion;
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
  return envmap::renderSh(envs_[env_].light.truncated(bands_), 512);
}

FrameParams SceneView::prepare(const Scene& scene, int width, int height) {
  if (mesh_ != scene.meshVersion) renderer_.setMesh(scene.bake().mesh), mesh_ = scene.meshVersion;
  const bool matrix = scene.transfer().field.isMatrix();
  if (transfer_ != scene.transferVersion) {
    // Compressed transfer: its ids and weights (vectors, and matrices relit on the GPU).
    compressedOnGpu_ = scene.compressed() && (!matrix || glossyOnGpu);
    if (compressedOnGpu_) renderer_.setCompressedTransfer(*scene.compressed()), gpuMaterial_ = -1;
    // Matrix transfer is relit on the CPU (relightGlossy below): nothing to upload for it.
    else if (scene.transfer().field.isMatrix() && glossyOnGpu)
      renderer_.setGlossyTransfer(scene.transfer().field), gpuMaterial_ = -1;
    else if (scene.transfer().field.isMatrix())
      renderer_.setDirectRadiance();
    else
      renderer_.setTransfer(scene.transfer().field);
    transfer_ = scene.transferVersion;
  }
  const auto& envs = scene.environments();
  if (env_ != scene.envVersion && !envs.empty()) {
    const EnvironmentEntry& e = envs[scene.environmentIndex()];
    renderer_.setEnvironmentImage(e.latLong);
    packer_.setLight(e.light);
    env_ = scene.envVersion;
  }
  if (light_ != scene.shVersion && !envs.empty()) {
    packer_.setLight(envs[scene.environmentIndex()].light);
    light_ = scene.shVersion;
  }
  // The SH background image is made only while it is shown.
  if (sh_ != scene.shVersion && scene.background == BackgroundMode::Sh) {
    renderer_.setShImage(scene.shBackground());
    sh_ = scene.shVersion;
  }
  FrameParams f;
  f.width = width, f.height = height;
  f.camera = scene.orbit.camera();
  const auto t0 = std::chrono::steady_clock::now();
  f.lightRotation = scene.lightRotation();
  packer_.pack(f.lightRotation, scene.bands());
  glossySeconds_ = 0;
  if (compressedOnGpu_) {
    projectCompressed(scene);
    f.clusterTable = clusterTable_;
  } else if (matrix && glossyOnGpu) {
    if (gpuMaterial_ != scene.materialVersion) {
      // The kernels depend on l only, so the transfer's band count serves every b ≤ B.
      const relight::PreparedMaterial pm =
          relight::prepareMaterial(scene.material(), scene.transfer().field.bands);
      renderer_.setGlossyMaterial(pm.diffuse, pm.glossy, pm.kd, pm.specular);
      gpuMaterial_ = scene.materialVersion;
    }
  } else if (matrix) {
    relightGlossy(scene, f.camera, f.lightRotation);
  }
  lightSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  f.light = &packer_;
  f.background = scene.background;
  f.exposureStops = scene.exposureStops;
  f.toneMap = scene.toneMap;
  return f;
}

std::string SceneView::uploadSummary(const Scene& scene) const {
  const TransferField& shape = scene.transfer().field;
  const std::size_t dense = denseBytesPerVertex(shape, glossyOnGpu);
  const CompressedTransfer* c = scene.compressed();
  if (!c && shape.isMatrix() && !glossyOnGpu)
    return fmt::format(
        "dense matrices relit on the CPU (relightGlossy): {} bytes of radiance per "
        "vertex per relit frame",
        dense);
  if (!c) return fmt::format("dense transfer: {} bytes per vertex uploaded", dense);
  if (!renderer_.compressed())
    return fmt::format(
        "compressed (CPCA {} x {}), relit on the CPU (relightCompressedGlossy): "
        "{} bytes of radiance per vertex per relit frame",
        c->clusters, c->basisCount, sizeof(Rgb));
  return fmt::format(
      "relit compressed (CPCA {} x {}): {} bytes per vertex uploaded once "
      "(dense: {}), {} bytes of cluster table per frame",
      c->clusters, c->basisCount, renderer_.compressedBytesPerVertex(), dense,
      renderer_.clusterTableBytes());
}

const relight::PreparedLight& SceneView::packedLight(int b) {
  glossyLight_.bands = b;
  glossyLight_.interleaved.resize(std::size_t(3 * b * b));
  for (int i = 0; i < b * b; ++i) {
    const Rgb c = packer_.coefficient(i);
    for (int k = 0; k < 3; ++k) glossyLight_.interleaved[std::size_t(3 * i + k)] = c[k];
  }
  return glossyLight_;
}

void SceneView::projectCompressed(const Scene& scene) {
  const CompressedTransfer& t = *scene.compressed();
  if (t.layout == TransferLayout::Matrix && gpuMaterial_ != scene.materialVersion) {
    const relight::PreparedMaterial pm = relight::prepareMaterial(scene.material(), t.bands);
    renderer_.setGlossyMaterial(pm.diffuse, pm.glossy, pm.kd, pm.specular);
    gpuMaterial_ = scene.materialVersion;
  }
  // K(N+1) projections of D(R) L cut to the shown bands (projectClusters uses the leading b²
  // coefficients: vectors T·L over them, matrices the leading b² columns).
  relight::packClusterTable(relight::projectClusters(t, packedLight(scene.bands())), clusterTable_);
}

void SceneView::relightGlossy(const Scene& scene, const render::Camera& camera,
                              const Mat3d& rotation) {
  const int b = scene.bands();
  const bool sameRotation =
      std::equal(&rotation.m[0][0], &rotation.m[0][0] + 9, &glossyRotation_.m[0][0]);
  const bool sameView = glossyTransfer_ == scene.transferVersion && glossyBands_ == b &&
                        glossyMaterialVersion_ == scene.materialVersion && glossyEye_ == camera.eye;
  if (sameView && glossyLightVersion_ == light_ && sameRotation) return;
  if (!sameView) glossyViewValid_ = false;
  const auto t0 = std::chrono::steady_clock::now();
  const TransferField& full = scene.transfer().field;
  const CompressedTransfer* compressed = scene.compressed();
  if (glossyTransfer_ != scene.transferVersion || glossyBands_ != b) {
    // Fewer bands than baked: the leading b² × b² block of every matrix (exact, as prt render
    // --bands); kept so later frames only relight.
    glossyField_ = b < full.bands && !compressed ? full.truncated(b) : TransferField{};
    glossyMaterialVersion_ = -1;
  }
  const TransferField& field = b < full.bands ? glossyField_ : full;
  if (glossyMaterialVersion_ != scene.materialVersion) {
    if (compressed) {
      // Compressed rows cannot be cut per band: the kernels of rows i ≥ b² are zeroed instead
      // (and the light is cut to b bands), which sums exactly the leading b² × b² block.
      glossyMaterial_ = relight::prepareMaterial(scene.material(), full.bands);
      for (std::size_t i = std::size_t(b * b); i < glossyMaterial_.diffuse.size(); ++i) {
        glossyMaterial_.diffuse[i] = 0.0f;
        if (!glossyMaterial_.glossy.empty()) glossyMaterial_.glossy[i] = 0.0f;
      }
    } else {
      glossyMaterial_ = relight::prepareMaterial(scene.material(), b);
    }
  }
  // The light D(R) L the packer just rotated.
  packedLight(b);
  const Mesh& mesh = scene.bake().mesh;
  radiance_.resize(mesh.vertexCount());
  // Exactly prt render's call: each vertex seen from the camera's eye, the mesh's albedo as kd
  // unless the material sets one.
  const relight::GlossyView view{mesh.positions, mesh.normals, camera.eye};
  if (compressed) {
    relight::relightCompressedGlossy(*compressed, glossyLight_, glossyMaterial_, view, mesh.albedo,
                                     radiance_);
  } else if (sameView) {
    // Only the light changed: collapse the matrices for this eye once (a frame's work), then
    // every further light-only frame is a vector relighting.
    if (!glossyViewValid_) {
      glossyView_ = relight::viewTransfer(field, glossyMaterial_, view, mesh.albedo);
      glossyViewValid_ = true;
    }
    relight::relight(glossyView_, glossyLight_, {}, radiance_);
    ++glossyLightOnly_;
  } else {
    relight::relightGlossy(field, glossyLight_, glossyMaterial_, view, mesh.albedo, radiance_);
  }
  renderer_.setRadiance(radiance_);
  glossyTransfer_ = scene.transferVersion, glossyBands_ = b;
  glossyMaterialVersion_ = scene.materialVersion, glossyLightVersion_ = light_;
  glossyRotation_ = rotation, glossyEye_ = camera.eye;
  ++glossyRelights_;
  glossySeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace prt::viewer
