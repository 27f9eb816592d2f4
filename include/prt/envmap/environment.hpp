#pragma once
// An environment: distant radiance L(ω) as a function of direction, either tabulated (a lat-long
// image, an angular probe or six cube faces) or analytic (a smooth function plus uniform discs
// such as the sun). Two views of it:
//  * lookup(dir): the radiance seen along `dir` (bilinear between texel centres), for renderers
//    and Monte Carlo references;
//  * texels: every texel's direction, exact solid angle and radiance, for projection and for
//    building importance-sampling distributions (Σ texel solid angles = 4π).
// Layout conventions (directions, faces, solid angles) are stated in layout.hpp.

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "prt/envmap/layout.hpp"
#include "prt/image/image.hpp"

namespace prt::envmap {

/// A uniform disc of radiance on the sphere (a spherical cap): the sun, a round area light.
struct Cap {
  Vec3f direction;       ///< unit centre direction
  double halfAngle = 0;  ///< angular radius α in radians (0 < α ≤ π)
  Rgb radiance;          ///< radiance inside the cap
  bool contains(const Vec3f& d) const;
  /// ∫ L dω over the cap = radiance · 2π (1 − cos α).
  Rgb power() const;
};

/// One texel: unit direction of its centre, exact solid angle (sr), radiance.
struct Texel {
  Vec3f direction;
  float solidAngle = 0;
  Rgb radiance;
};

class Environment {
 public:
  enum class Kind { LatLong, Probe, Cube, Analytic };

  Environment() = default;
  /// A lat-long (2:1) image.
  static Environment latLong(image::Image img);
  /// A square angular light probe (Debevec).
  static Environment probe(image::Image img);
  /// Six square faces of the same size in the order +X −X +Y −Y +Z −Z.
  static Environment cube(std::array<image::Image, 6> faces);
  /// Cuts a vertical (3:4) or horizontal (4:3) cross into faces.
  static Environment cross(const image::Image& img, Layout layout);
  /// A smooth function plus discs; texels are a lat-long sampling of width `texelWidth`
  /// (smooth part at texel centres, discs by their covered fraction, 8×8 supersampled).
  static Environment analytic(std::function<Rgb(const Vec3f&)> smooth, std::vector<Cap> caps,
                              int texelWidth = 512);

  Kind kind() const { return kind_; }
  bool empty() const { return kind_ != Kind::Analytic && texelCount() == 0; }

  /// Radiance along direction `dir` (unit).
  Rgb lookup(const Vec3f& dir) const;

  std::size_t texelCount() const { return count_; }
  Texel texel(std::size_t k) const;
  /// Exact solid angle of texel k in double precision.
  double texelSolidAngle(std::size_t k) const;

  /// The analytic parts (Kind::Analytic only).
  const std::function<Rgb(const Vec3f&)>& smooth() const { return smooth_; }
  const std::vector<Cap>& caps() const { return caps_; }
  /// For Kind::Analytic: the smooth part alone as a lat-long environment (for projection).
  Environment smoothPart() const;

  /// Faces (Kind::Cube) or the single image (other kinds; the texel lat-long for Analytic).
  const std::vector<image::Image>& images() const { return images_; }

  /// What the user named to load it (a file, a folder, builtin:NAME; "" when built in code), so
  /// messages about it name the input (envmap::loadEnvironment sets it).
  const std::string& source() const { return source_; }
  void setSource(std::string source) { source_ = std::move(source); }

 private:
  Kind kind_ = Kind::LatLong;
  std::vector<image::Image> images_;
  std::size_t count_ = 0;
  // Geometry tables: cube: N×N face solid angles; lat-long: per-row solid angle and per-column
  // (cos φ, sin φ), per-row (sin θ, cos θ); probe: per-texel solid angles.
  std::shared_ptr<const std::vector<double>> solid_;
  std::shared_ptr<const std::vector<float>> solidF_;
  std::shared_ptr<const std::vector<float>> colTrig_, rowTrig_;
  std::function<Rgb(const Vec3f&)> smooth_;
  std::vector<Cap> caps_;
  image::Image smoothImage_;
  std::string source_;

  void initTables();
};

}  // namespace prt::envmap
