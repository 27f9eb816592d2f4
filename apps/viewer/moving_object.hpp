#pragma once
// The object a probe bake lights in prt view (issue 32): a mesh the user moves through the grid
// while the light turns, shaded every frame through the relit probes around it — what an engine
// does for a character or a prop. It starts at the grid's centre at the size prt render gives it
// (render/probe_object.hpp) and stays inside the box the probes span (outside it the grid can
// only repeat its faces).

#include <memory>
#include <string>

#include "prt/geometry/mesh.hpp"
#include "prt/render/camera.hpp"
#include "prt/transfer/probe_grid.hpp"

namespace prt::viewer {

class MovingObject {
 public:
  /// `mesh` as loaded (any size and place), named `name` (a file or builtin:NAME).
  MovingObject(Mesh mesh, std::string name, const ProbeGrid& grid);

  const std::shared_ptr<const Mesh>& mesh() const { return mesh_; }
  const std::string& name() const { return name_; }
  Vec3f position() const { return at_; }
  float size() const { return size_; }
  /// The grid's default size (the size slider spans a tenth of it to four times it).
  float defaultSize() const { return defaultSize_; }

  /// Moves its centre to `p`, clamped to the box the probes span.
  void moveTo(const Vec3f& p);
  /// Moves it in the image plane of `camera` by (dx, dy) pixels of a view `height` pixels tall,
  /// at its own depth (the point under the cursor follows the cursor), then clamps.
  void drag(const render::Camera& camera, double dxPixels, double dyPixels, int height);
  /// Its largest side, clamped to [defaultSize / 10, 4 defaultSize].
  void setSize(float size);

  /// The mesh scaled and placed (render::placeObject).
  Mesh placed() const;

 private:
  std::shared_ptr<const Mesh> mesh_;
  std::string name_;
  Bounds box_;
  Vec3f at_;
  float size_ = 1, defaultSize_ = 1;
};

}  // namespace prt::viewer
