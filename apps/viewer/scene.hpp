#pragma once
// What the viewer shows, without any OpenGL: the bake and its transfers, the environments (each
// with its lat-long background image and its SH projection at the bake's bands), the light's
// rotation, the orbit camera and the display settings. The window and the headless runner both
// drive a Scene; tests drive it directly.
//
// The light's rotation is R = Ry(spin) · R_user: the user's rotation (--rotate, or dragging),
// then the auto-rotation about +Y (as prt render --turntable turns it). Dragging horizontally by
// Δx pixels turns the environment about world +Y by Δx · kDragDegreesPerPixel; vertically, about
// the camera's right axis.
//
// Glossy (matrix) transfer is view-dependent, e(p, v) with v = normalize(eye − p) per vertex
// (prt/relight/glossy.hpp), so it cannot be a fixed per-vertex vector dotted with the light in
// the vertex shader. SceneView relights it on the CPU with the library's kernel,
// relight::relightGlossy — the very code prt render runs, with the orbit camera's eye — into a
// radiance buffer the shader only displays, and only on frames where the light rotation, the
// eye, the bands, the material or the environment changed. Why the CPU and not the vertex
// shader (a B⁴ matrix per vertex in a texture buffer): docs/viewer.md, "Glossy transfer".
//
// CPCA-compressed transfer (prt compress, bake file version 3) is drawn from its compressed form,
// never expanded: each frame SceneView projects the rotated light onto every cluster's mean and
// basis (relight::projectClusters, the step prt render runs too) and hands the table to the
// renderer, whose vertex shader sums N weighted cluster values per vertex (renderer.hpp).
// Compressed matrices follow --glossy-on: on the GPU that table holds B² values per cluster
// vector and compressedGlossy.vert shades them; on the CPU relight::relightCompressedGlossy
// relights into the radiance buffer, as for dense matrices.

#include <optional>
#include <string>
#include <vector>

#include "prt/envmap/environment.hpp"
#include "prt/image/color.hpp"
#include "prt/image/image.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/relight/cluster_table.hpp"
#include "prt/relight/glossy.hpp"
#include "prt/relight/light_packer.hpp"
#include "prt/render/camera.hpp"
#include "prt/transfer/material.hpp"
#include "renderer.hpp"

namespace prt::viewer {

inline constexpr double kDragDegreesPerPixel = 0.25;

/// One light to choose from: an environment (image, face folder, builtin), or an SH light file
/// (.json, or the course's light.txt), whose "image" is its SH reconstruction.
struct EnvironmentEntry {
  std::string name;         ///< as given (path or builtin:NAME)
  bool isShFile = false;    ///< an SH light file: no image, `source` holds its coefficients
  envmap::Environment env;  ///< (environments only)
  sh::RgbSh source;         ///< (SH files only) the coefficients as read
  image::Image latLong;     ///< the background: the environment, or the SH file's reconstruction
  sh::RgbSh light;          ///< at the bake's bands: projected, or the file's cut to them
};

/// Orbit camera: the library's camera (render::frameMesh's framing, or --camera) plus the mouse's
/// yaw, pitch, distance and pan as a render::Orbit; its view is render::viewMatrix of camera().
/// The zero orbit is the starting camera bit for bit, so prt view frames as prt render does by
/// construction (docs/conventions.md, "Camera").
class OrbitCamera {
 public:
  OrbitCamera() = default;
  explicit OrbitCamera(const render::Camera& start) : start_(start) {}
  render::Camera camera() const { return render::orbitCamera(start_, orbit_); }
  /// World → eye space of camera() (column-major, OpenGL).
  render::Mat4f view() const { return render::viewMatrix(camera()); }
  /// Yaw about the camera's up axis through the target, pitch about its right axis (clamped).
  void orbit(double dYawRad, double dPitchRad);
  /// Moves the target in the image plane by (dx, dy) × the view height at the target.
  void pan(double dx, double dy);
  /// Distance *= factor.
  void zoom(double factor);
  void reset() { orbit_ = {}; }

 private:
  render::Camera start_;
  render::Orbit orbit_;
};

class Scene {
 public:
  /// Reads and checks a bake: complete, holds a transfer, bands within the viewer's limit.
  /// Throws prt::Error("FILE: problem").
  static BakeFile readCheckedBake(const std::string& path);
  /// Loads an environment (image, face folder, builtin:NAME) and projects it to `bands`, or
  /// reads an SH light file (.json, .txt) and cuts it to `bands`. Throws prt::Error("FILE: ...")
  /// when unreadable, or when an SH light has fewer bands than `bands` (the transfer's upper
  /// bands would see no light: project the environment at the bake's bands instead).
  static EnvironmentEntry loadEnvironment(const std::string& spec, int bands);

  /// Replaces the bake (environments are re-projected when the band count changes), picks the
  /// transfer as prt render does (pickTransfer: the richest mode, a matrix before a vector) and
  /// the full band count, takes that transfer's material (unless one was set with
  /// overrideMaterial), resets the camera to the default framing of a width × height view.
  void setBake(BakeFile bake, const std::string& name, int width, int height);
  void addEnvironment(EnvironmentEntry entry);

  /// Loads a file dropped on the window: a .glb replaces the bake, anything else is added as an
  /// environment and selected. Returns "" on success, else the error line; the scene is
  /// unchanged on failure.
  std::string loadDropped(const std::string& path, int width, int height);

  const BakeFile& bake() const { return bake_; }
  const std::string& bakeName() const { return bakeName_; }
  const std::vector<EnvironmentEntry>& environments() const { return envs_; }
  const BakedTransfer& transfer() const { return bake_.transfers[transfer_]; }
  /// The shown transfer's compressed form, or nullptr when it is dense.
  const CompressedTransfer* compressed() const {
    const auto& c = transfer().compressed;
    return c ? &*c : nullptr;
  }
  int transferIndex() const { return transfer_; }
  int environmentIndex() const { return env_; }
  int bakeBands() const { return bakeBands_; }
  int bands() const { return bands_; }

  /// Selects transfer k; its material comes with it unless overrideMaterial was called.
  void selectTransfer(int k);
  void selectEnvironment(int k);

  /// The material relighting uses (glossy lobe and ks apply to matrix transfer only).
  const Material& material() const { return material_; }
  /// Sets the material live (the panel's sliders); it stays until the next transfer selection.
  void setMaterial(const Material& m);
  /// As prt view --material: this material for every transfer from now on.
  void overrideMaterial(const Material& m) { materialOverride_ = m, setMaterial(m); }
  /// Clamps to 1..bake bands.
  void setBands(int b);

  // Light rotation.
  Mat3d lightRotation() const;
  void setUserRotation(const Mat3d& r) { userRotation_ = r; }
  void dragLight(double dxPixels, double dyPixels);
  void advanceSpin(double seconds);
  void resetLight() { userRotation_ = Mat3d::identity(), spinRad_ = 0; }

  /// The SH reconstruction of the current environment at the current bands (unrotated,
  /// clamped at 0) as a lat-long image: the background for BackgroundMode::Sh.
  image::Image shBackground() const;

  OrbitCamera orbit;
  BackgroundMode background = BackgroundMode::Env;
  float exposureStops = 0.0f;
  image::ToneMap toneMap = image::ToneMap::Aces;
  bool autoRotate = false;
  double spinDegreesPerSecond = 30.0;

  /// Bumped whenever the mesh/transfer, the environment image or the SH background change, so a
  /// renderer knows what to re-upload.
  int meshVersion = 0, transferVersion = 0, envVersion = 0, shVersion = 0, materialVersion = 0;

 private:
  BakeFile bake_;
  std::string bakeName_;
  std::vector<EnvironmentEntry> envs_;
  int transfer_ = 0, env_ = 0, bakeBands_ = 0, bands_ = 0;
  Mat3d userRotation_ = Mat3d::identity();
  double spinRad_ = 0;
  Material material_;
  std::optional<Material> materialOverride_;
};

/// Keeps a Renderer and a LightPacker in step with a Scene: uploads what changed (by the
/// scene's version counters), then packs the light for this frame. Needs a current context.
class SceneView {
 public:
  SceneView() = default;
  /// Relight glossy (matrix) transfer in the vertex shader instead of on the CPU (prt view
  /// --glossy-on gpu); set before the first prepare.
  bool glossyOnGpu = false;
  /// Uploads what changed since the last call and returns this frame's parameters (the light
  /// rotated and packed: the per-frame CPU work).
  FrameParams prepare(const Scene& scene, int width, int height);
  Renderer& renderer() { return renderer_; }
  const LightPacker& packer() const { return packer_; }
  /// Seconds the last prepare spent on the per-frame light work (rotation + packing, plus the
  /// glossy relighting when it ran).
  double lastLightSeconds() const { return lightSeconds_; }
  /// Seconds the last glossy relighting took (relightGlossy + radiance upload); 0 when the last
  /// prepare did not relight (vector transfer, or nothing changed).
  double lastGlossySeconds() const { return glossySeconds_; }
  /// Glossy relightings so far (frames where something view- or light-dependent changed).
  int glossyRelights() const { return glossyRelights_; }
  /// Of those, the ones served from the view-collapsed transfer (only the light had changed).
  int glossyLightOnlyRelights() const { return glossyLightOnly_; }
  /// The last glossy relighting's per-vertex exit radiance (what the shader shows).
  const std::vector<Rgb>& glossyRadiance() const { return radiance_; }
  /// One line on what the shown transfer costs the GPU, after a prepare: for compressed
  /// transfer "relit compressed (CPCA K x N): B bytes per vertex uploaded once (dense: D), T
  /// bytes of cluster table per frame" (or, for matrices relit on the CPU, that it is), else
  /// the dense bytes per vertex.
  std::string uploadSummary(const Scene& scene) const;
  /// Bytes the renderer uploads per frame for the light: the packed block, or for compressed
  /// transfer on the GPU the cluster table.
  std::size_t lightUploadBytes() const {
    return renderer_.compressed() ? renderer_.clusterTableBytes() : packer_.bytes();
  }
  /// Compressed transfer drawn on the GPU: this frame's cluster table (relight/cluster_table.hpp).
  const std::vector<float>& clusterTable() const { return clusterTable_; }

 private:
  /// Matrix transfer: relights on the CPU into the renderer's radiance buffer when the light,
  /// eye, bands, material or transfer differ from the last time. When only the light changed
  /// (it turns under a still camera), from the matrices collapsed for this eye
  /// (relight::viewTransfer, built on the first such frame): a vector relighting, 23× less work
  /// at 5 bands (docs/performance.md).
  void relightGlossy(const Scene& scene, const render::Camera& camera, const Mat3d& rotation);
  /// The packer's rotated light at `bands` in relight's (r, g, b) per coefficient layout.
  const relight::PreparedLight& packedLight(int bands);
  /// Compressed transfer on the GPU: projects the packed light onto the clusters into
  /// clusterTable_ (and, for matrices, uploads the glossy kernels when the material changed).
  void projectCompressed(const Scene& scene);

  Renderer renderer_;
  LightPacker packer_;
  int mesh_ = -1, transfer_ = -1, env_ = -1, light_ = -1, sh_ = -1;
  double lightSeconds_ = 0, glossySeconds_ = 0;
  int glossyRelights_ = 0, gpuMaterial_ = -1;
  // Glossy state: the transfer cut to the shown bands, the prepared material, the radiance, and
  // what they were computed for.
  TransferField glossyField_;
  TransferField glossyView_;  ///< viewTransfer for the current eye and material, if valid
  bool glossyViewValid_ = false;
  int glossyLightOnly_ = 0;
  relight::PreparedMaterial glossyMaterial_;
  relight::PreparedLight glossyLight_;
  std::vector<Rgb> radiance_;
  std::vector<float> clusterTable_;
  bool compressedOnGpu_ = false;
  int glossyTransfer_ = -1, glossyMaterialVersion_ = -1, glossyBands_ = -1,
      glossyLightVersion_ = -1;
  Mat3d glossyRotation_;
  Vec3f glossyEye_{0.0f};
};

}  // namespace prt::viewer
