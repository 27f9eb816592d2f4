#include "prt/relight/relighter.hpp"

#include <algorithm>

#include "prt/core/error.hpp"
#include "prt/relight/view_transfer.hpp"

namespace prt::relight {

namespace {

/// The material as relight() prepares it: the kernels for matrices, kd alone for vectors.
PreparedMaterial prepareFor(const Transfer& t, const Material& m) {
  if (t.isMatrix()) return prepareMaterial(m, t.bands());
  PreparedMaterial p;
  p.kd = m.diffuse;
  return p;
}

}  // namespace

Relighter::Relighter(Transfer transfer, Surface surface)
    : full_(std::move(transfer)), cut_(full_), surface_(surface) {
  requireShTransfer(full_);
  prepared_ = prepareFor(cut_, material_);
  radiance_.assign(full_.rowCount(), Rgb(0.0f));
}

void Relighter::setMaterial(const Material& material) {
  if (material == material_) return;
  material_ = material;
  prepared_ = prepareFor(cut_, material_);
  viewChanged_ = true;
}

void Relighter::setBands(int b) {
  if (b < 1 || b > full_.bands())
    throw Error("relight: " + std::to_string(b) + " bands asked of a transfer of " +
                std::to_string(full_.bands()));
  if (b == cut_.bands()) return;
  cut_ = full_.cut(b);
  prepared_ = prepareFor(cut_, material_);
  viewChanged_ = true;
}

std::span<const Rgb> Relighter::relight(const sh::RgbSh& light, const Mat3d& rotation,
                                        const Vec3f& eye, RelightInfo* info) {
  const int b = std::min(light.bands, bands());
  std::vector<Rgb> rotated(light.c.begin(), light.c.begin() + b * b);
  if (rotation != Mat3d::identity())
    sh::Rotation(b, rotation).apply(light.c.data(), rotated.data());
  RelightInfo i;
  relightRotated(rotated, b, eye, &i);
  i.lightBands = light.bands;
  i.lightTruncated = light.bands > bands();
  if (info) *info = i;
  return radiance_;
}

std::span<const Rgb> Relighter::relightRotated(std::span<const Rgb> rotated, int lightBands,
                                               const Vec3f& eye, RelightInfo* info) {
  PRT_CHECK(rotated.size() >= static_cast<std::size_t>(lightBands * lightBands),
            "fewer rotated coefficients than the light's bands");
  const int b = std::min(lightBands, bands());
  RelightInfo i;
  i.bands = b;
  i.lightBands = lightBands;
  i.transferBands = bands();
  i.lightTruncated = lightBands > bands();
  i.transferTruncated = lightBands < bands();
  if (info) *info = i;

  const std::span<const Rgb> used = rotated.first(static_cast<std::size_t>(b * b));
  const bool sameLight = lastLightBands_ == b &&
                         std::equal(used.begin(), used.end(), lastLight_.begin(), lastLight_.end());
  const bool sameView = haveLast_ && !viewChanged_ && lastEye_ == eye;
  const bool viewDependent = cut_.isMatrix();
  if (haveLast_ && sameLight && !viewChanged_ && (sameView || !viewDependent)) return radiance_;

  const PreparedLight light = prepareLight(used, b);
  const bool dense = !cut_.compressed();
  if (viewDependent && dense && sameView) {
    // Only the light changed: collapse the matrices for this eye once, then relight vectors.
    if (!collapsedValid_) {
      collapsed_ = viewTransfer(cut_, prepared_, surface_, eye);
      collapsedValid_ = true;
    }
    relightPrepared(collapsed_, light, PreparedMaterial{}, Surface{}, eye, radiance_);
    ++lightOnlyFrames_;
  } else {
    if (!sameView) collapsedValid_ = false;
    relightPrepared(cut_, light, prepared_, surface_, eye, radiance_);
  }
  if (viewChanged_) collapsedValid_ = false;
  haveLast_ = true;
  viewChanged_ = false;
  lastEye_ = eye;
  lastLight_.assign(used.begin(), used.end());
  lastLightBands_ = b;
  ++frames_;
  return radiance_;
}

}  // namespace prt::relight
