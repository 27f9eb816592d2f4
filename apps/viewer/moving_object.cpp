#include "moving_object.hpp"

#include <algorithm>
#include <cmath>

#include "prt/render/probe_object.hpp"

namespace prt::viewer {

MovingObject::MovingObject(Mesh mesh, std::string name, const ProbeGrid& grid)
    : mesh_(std::make_shared<const Mesh>(std::move(mesh))),
      name_(std::move(name)),
      box_(render::probeGridBounds(grid)),
      at_(render::defaultObjectPosition(grid)),
      size_(render::defaultObjectSize(grid)),
      defaultSize_(size_) {}

void MovingObject::moveTo(const Vec3f& p) {
  for (int a = 0; a < 3; ++a) at_[a] = std::clamp(p[a], box_.lo[a], box_.hi[a]);
}

void MovingObject::drag(const render::Camera& camera, double dx, double dy, int height) {
  const render::CameraBasis b = render::cameraBasis(camera, 1, 1);
  // The view is 2 d tan(fovY/2) tall at depth d along the view axis.
  const double depth = std::max(dot(Vec3d(at_) - Vec3d(b.eye), Vec3d(b.forward)), 1e-6);
  const double perPixel = 2.0 * depth * double(b.tanY) / std::max(height, 1);
  moveTo(Vec3f(Vec3d(at_) + (Vec3d(b.right) * dx - Vec3d(b.up) * dy) * perPixel));
}

void MovingObject::setSize(float size) {
  if (std::isfinite(size)) size_ = std::clamp(size, 0.1f * defaultSize_, 4.0f * defaultSize_);
}

Mesh MovingObject::placed() const {
  return render::placeObject(*mesh_, at_, size_);
}

}  // namespace prt::viewer
