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
// How a transfer is drawn is the library's one dispatch (relight::shaderPath, shader_transfer.hpp):
// dense and compressed vectors and compressed matrices in the vertex shader from per-vertex
// texels uploaded once; dense matrices on the CPU (render::RelitView, the code prt render
// runs, with the orbit camera's eye) into a radiance buffer the shader only displays, or with
// --glossy-on gpu in the vertex shader. Why the CPU by default: docs/viewer.md, "Glossy
// transfer". Per-texel (lightmap) vectors, dense or compressed, are relit per pixel in the
// fragment shader from the same per-row texels (docs/viewer.md, "Per-texel transfer").
//
// What is drawn is one value, DrawState: the bake, the transfer, the band count, the material,
// the environment and the background. A SceneView keeps the state its GPU buffers were made
// from and, each frame, uploads what differs from the scene's; the light rotation, the camera,
// exposure and tone map are per-frame parameters.

#include <optional>
#include <string>
#include <vector>

#include <functional>
#include <memory>

#include "haar_view.hpp"
#include "moving_object.hpp"
#include "prt/envmap/environment.hpp"
#include "prt/image/color.hpp"
#include "prt/image/image.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/io/lighting.hpp"
#include "prt/relight/shader_transfer.hpp"
#include "prt/render/camera.hpp"
#include "prt/render/relit_view.hpp"
#include "prt/transfer/material.hpp"
#include "renderer.hpp"

namespace prt::viewer {

inline constexpr double kDragDegreesPerPixel = 0.25;

/// One light to choose from: an environment (image, face folder, builtin), or an SH light file
/// (.json, or the course's light.txt), whose "image" is its SH reconstruction — loaded by
/// io::loadLighting, the rules every verb shares.
struct EnvironmentEntry {
  std::string name;       ///< as given (path or builtin:NAME)
  io::Lighting lighting;  ///< the environment or the file's coefficients, at the bake's bands
  image::Image latLong;   ///< the background: the environment, or the SH file's reconstruction
  sh::RgbSh light;        ///< at the bake's bands (padded with zeros when the file has fewer)
};

/// What is drawn: everything a SceneView uploads when it changes. Shared pointers keep the bake
/// and the environment alive while a view holds the state, so identity comparisons are sound.
struct DrawState {
  std::shared_ptr<const BakeFile> bake;
  const BakedTransfer* transfer = nullptr;  ///< one of bake->transfers
  int bands = 0;                            ///< shown, ≤ the transfer's
  Material material;
  std::shared_ptr<const EnvironmentEntry> environment;
  BackgroundMode background = BackgroundMode::Env;
  /// A probe bake's moving object (its mesh, where it is and how large) and probe markers.
  std::shared_ptr<const Mesh> object;
  Vec3f objectAt{0.0f};
  float objectSize = 0;
  bool showProbes = false;
  bool operator==(const DrawState&) const = default;
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
  /// Reads and checks a bake: complete, holds a transfer, bands within the viewer's limit (or
  /// Haar transfer only). Throws prt::Error("FILE: problem").
  static BakeFile readCheckedBake(const std::string& path);
  /// Loads an environment (image, face folder, builtin:NAME) and projects it to `bands`, or
  /// reads an SH light file (.json, .txt) and cuts or pads it to `bands` (io::loadLighting's
  /// rules; its warnings in the entry). Throws prt::Error("FILE: ...") when unreadable.
  static EnvironmentEntry loadEnvironment(const std::string& spec, int bands);

  /// Replaces the bake (environments are re-projected when the band count changes), lists its
  /// transfers in prt::transferPreference's order and shows the first (what prt render picks by
  /// default) at its full band count with its material (unless one was set with
  /// overrideMaterial), resets the camera to the default framing of a width × height view.
  void setBake(BakeFile bake, const std::string& name, int width, int height);
  /// Adds and selects an environment; throws prt::Error naming it when it is an SH light file
  /// and the bake is Haar.
  void addEnvironment(EnvironmentEntry entry);

  /// Loads a file dropped on the window: a .glb replaces the bake, anything else is added as an
  /// environment and selected. Returns "" on success, else the error line; the scene is
  /// unchanged on failure.
  std::string loadDropped(const std::string& path, int width, int height);

  const BakeFile& bake() const { return *bake_; }
  const std::string& bakeName() const { return bakeName_; }
  std::size_t environmentCount() const { return envs_.size(); }
  const EnvironmentEntry& environment(std::size_t k) const { return *envs_[k]; }
  /// The transfers in the order the panel lists them (prt::transferPreference).
  std::size_t transferCount() const { return order_.size(); }
  const BakedTransfer& transferAt(std::size_t k) const { return bake_->transfers[order_[k]]; }
  /// The shown transfer.
  const BakedTransfer& transfer() const { return transferAt(transfer_); }
  int transferIndex() const { return transfer_; }
  int environmentIndex() const { return env_; }
  int bakeBands() const { return bakeBands_; }
  int bands() const { return bands_; }
  /// The basis the transfer is relit in, for messages: "3 of 5 bands", or a Haar bake's
  /// "Haar 32² cube, 64 terms a row".
  std::string basisText() const;

  /// Selects transfer k of the panel's list; its material comes with it unless
  /// overrideMaterial was called.
  void selectTransfer(int k);
  /// Selects the first transfer of `mode` in the list (prt::Error naming the bake if none).
  void selectMode(TransferMode mode);
  void selectEnvironment(int k);

  /// The material relighting uses (glossy lobe and ks apply to matrix transfer only).
  const Material& material() const { return material_; }
  /// Sets the material live (the panel's sliders); it stays until the next transfer selection.
  void setMaterial(const Material& m) { material_ = m; }
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

  /// What is drawn now.
  DrawState drawState() const;

  /// A probe bake (prt probes) is drawn with an object the user moves through its grid
  /// (probe_view.hpp); probeBake() says whether the bake is one.
  bool probeBake() const { return bake_->domain() == TransferDomain::Probes; }
  /// A Haar bake (prt bake --basis haar) is relit on the CPU under the environment's largest
  /// wavelet terms (haar_view.hpp); its SH band count is 1 (the background and the exposure's
  /// light only). Its environments must be images (an SH light file holds no wavelets).
  bool haarBake() const {
    return !bake_->transfers.empty() && bake_->transfers.front().transfer.isHaar();
  }
  /// The moving object of a probe bake: set by setBake (a sphere, unless setObject gave another
  /// mesh), placed anew in the grid of every probe bake set.
  std::optional<MovingObject> object;
  /// The object's mesh for this and later probe bakes (prt view --object).
  void setObject(Mesh mesh, const std::string& name);
  /// Probe markers: an octahedron at every probe, lit as the object is.
  bool showProbes = false;

  OrbitCamera orbit;
  BackgroundMode background = BackgroundMode::Env;
  float exposureStops = 0.0f;
  image::ToneMap toneMap = image::ToneMap::Aces;
  bool autoRotate = false;
  double spinDegreesPerSecond = 30.0;

  /// Output for warnings the scene meets (a light with too few bands); none by default.
  std::function<void(const std::string&)> warn;

 private:
  std::shared_ptr<const BakeFile> bake_ = std::make_shared<const BakeFile>();
  std::string bakeName_;
  std::vector<std::size_t> order_;
  std::vector<std::shared_ptr<const EnvironmentEntry>> envs_;
  int transfer_ = 0, env_ = 0, bakeBands_ = 0, bands_ = 0;
  Mat3d userRotation_ = Mat3d::identity();
  double spinRad_ = 0;
  Material material_;
  std::optional<Material> materialOverride_;
  std::shared_ptr<const Mesh> objectMesh_;  ///< setObject's (none: a sphere)
  std::string objectName_;
};

/// Keeps a Renderer in step with a Scene: uploads what differs between the scene's DrawState and
/// the one its buffers hold, then makes this frame's light (rotated and packed, the cluster
/// table of compressed transfer, or the CPU relighting of matrices). Needs a current context.
class SceneView {
 public:
  SceneView() = default;
  /// Relight dense glossy (matrix) transfer in the vertex shader instead of on the CPU (prt view
  /// --glossy-on gpu); set before the first prepare.
  bool glossyOnGpu = false;
  /// Uploads what changed since the last call and returns this frame's parameters.
  FrameParams prepare(const Scene& scene, int width, int height);
  Renderer& renderer() { return renderer_; }
  const LightPacker& packer() const { return packer_; }
  /// How the shown transfer is drawn (after a prepare).
  relight::ShaderPath path() const { return path_; }
  /// Seconds the last prepare spent on the per-frame light work (rotation + packing, plus the
  /// cluster projections or the CPU relighting when they ran).
  double lastLightSeconds() const { return lightSeconds_; }
  /// Seconds the last CPU relighting took (relighting + radiance upload); 0 when the last
  /// prepare did not relight on the CPU.
  double lastRelightSeconds() const { return relightSeconds_; }
  /// CPU relightings so far (frames where something view- or light-dependent changed; probe
  /// and Haar bakes: where the light or the mesh changed).
  int cpuRelights() const { return cpuView_ ? cpuView_->frames() : shadedRelights_; }
  /// Of those, the ones served from the view-collapsed transfer (only the light had changed).
  int cpuLightOnlyRelights() const { return cpuView_ ? cpuView_->lightOnlyFrames() : 0; }
  /// The last CPU relighting's per-vertex exit radiance (what the shader shows).
  std::span<const Rgb> cpuRadiance() const {
    return cpuView_ ? cpuView_->radiance() : std::span<const Rgb>(shadedRadiance_);
  }
  /// One line on what the shown transfer costs the GPU, after a prepare: what is uploaded once
  /// per vertex (against the dense rows) and per frame.
  std::string uploadSummary(const Scene& scene) const;
  /// Bytes the renderer uploads per frame for the light: the packed block, the cluster table, or
  /// the CPU-relit radiance.
  std::size_t lightUploadBytes() const;
  /// Compressed transfer: this frame's cluster table (relight/shader_transfer.hpp).
  const std::vector<float>& clusterTable() const { return clusterTable_; }

 private:
  /// The transfer-dependent part of an upload: the path, the per-vertex texels, the relighter.
  void setTransfer(const DrawState& now);
  /// Draws `vertices` vertices from radiance the CPU relights (setRadiance each relit frame):
  /// a probe scene's, a Haar bake's.
  void useCpuRadiance(std::size_t vertices);
  /// The environment's image and light when they changed, and the SH background while shown.
  void uploadEnvironment(const Scene& scene, const DrawState& now);
  /// This frame's parameters, the light turned and packed (the light work's start).
  FrameParams beginFrame(const Scene& scene, const DrawState& now, int width, int height);
  /// prepare for a probe bake (probe_view.hpp): the scene, the object and the markers as one
  /// mesh, shaded on the CPU when the light, the bands or the mesh change.
  FrameParams prepareProbes(const Scene& scene, const DrawState& now, int width, int height);
  /// prepare for a Haar bake (haar_view.hpp): relit on the CPU when the light (environment or
  /// rotation), the transfer or the material change.
  FrameParams prepareHaar(const Scene& scene, const DrawState& now, int width, int height);

  Renderer renderer_;
  LightPacker packer_;
  DrawState drawn_;  ///< what the GPU buffers hold
  bool shImageValid_ = false;
  relight::ShaderPath path_ = relight::ShaderPath::DenseVector;
  Transfer shown_;  ///< the transfer cut to the shown bands (compressed projections)
  /// CpuRadiance: the rows relit on the CPU as prt render relights them (under a texture the
  /// glossy lobe apart, render/base_colour.hpp).
  std::optional<render::RelitView> cpuView_;
  std::vector<float> clusterTable_;
  double lightSeconds_ = 0, relightSeconds_ = 0;
  Mesh probeMesh_;                 ///< a probe bake's drawn mesh (probeSceneMesh)
  std::vector<Rgb> probeLight_;    ///< the rotated light its radiance was shaded under
  /// The radiance the CPU shaded last (a probe scene's or a Haar bake's), and how often.
  std::vector<Rgb> shadedRadiance_;
  int shadedRelights_ = 0;
  /// A Haar bake's light, kept per environment and cube (its fine cube made once), and the
  /// environment it was made of.
  std::optional<HaarViewLight> haarLight_;
  std::shared_ptr<const EnvironmentEntry> haarLightFor_;
  Mat3d haarRotation_;  ///< the light rotation the Haar radiance (shadedRadiance_) was relit at
  std::size_t haarLightTerms_ = 0;
  /// A per-texel Haar bake: the normals its rows are relit at (haarTexelNormals), and whether
  /// the mesh was uploaded white (a kd replaces its albedo per pixel).
  std::vector<Vec3f> haarTexelNormals_;
  bool haarWhiteMesh_ = false;
};

}  // namespace prt::viewer
