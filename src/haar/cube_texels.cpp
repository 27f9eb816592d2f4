#include "prt/haar/cube_texels.hpp"

#include <cmath>

#include "prt/envmap/layout.hpp"
#include "prt/haar/cube_haar.hpp"

namespace prt::haar {

namespace {

/// ½ Σ Θ_i u_i over the closed polygon (the vector ∫_P ω dω up to the orientation's sign).
Vec3d polygonMoment(const Vec3d* v, int count) {
  Vec3d sum(0.0);
  for (int i = 0; i < count; ++i) {
    const Vec3d& a = v[i];
    const Vec3d& b = v[(i + 1) % count];
    const Vec3d c = cross(a, b);
    const double s = length(c);
    if (s <= 0) continue;
    sum += c * (std::atan2(s, dot(a, b)) / s);
  }
  return sum * 0.5;
}

/// ∫_P max(n·ω, 0) dω over the convex spherical polygon with unit vertices `v` (its edges great
/// arcs), clipped to n's hemisphere: Lambert's formula (the header).
double polygonClampedCosine(const Vec3d* v, int count, const Vec3d& n) {
  // Sutherland–Hodgman against the plane n·ω = 0; a crossing edge meets it at
  // ((n·a) b − (n·b) a) / (n·a − n·b) (normalised): both weights positive, so the point of the
  // arc between a and b on the horizon, not its antipode.
  std::array<Vec3d, 16> clipped;
  int m = 0;
  for (int i = 0; i < count && m < 15; ++i) {
    const Vec3d& a = v[i];
    const Vec3d& b = v[(i + 1) % count];
    const double da = dot(n, a), db = dot(n, b);
    if (da >= 0) clipped[std::size_t(m++)] = a;
    if ((da >= 0) != (db >= 0)) {
      const Vec3d x = (b * da - a * db) / (da - db);
      const double len = length(x);
      if (len > 0) clipped[std::size_t(m++)] = x / len;
    }
  }
  if (m < 3) return 0.0;
  return std::abs(dot(n, polygonMoment(clipped.data(), m)));
}

}  // namespace

TexelGeometry texelGeometry(std::uint32_t j, int n) {
  const CubeTexel t = cubeTexel(j, n);
  const double s0 = 2.0 * t.x / n - 1.0, s1 = 2.0 * (t.x + 1) / n - 1.0;
  const double t0 = 2.0 * t.y / n - 1.0, t1 = 2.0 * (t.y + 1) / n - 1.0;
  TexelGeometry g;
  g.corners[0] = normalize(envmap::cubeFaceDirection(t.face, s0, t0));
  g.corners[1] = normalize(envmap::cubeFaceDirection(t.face, s1, t0));
  g.corners[2] = normalize(envmap::cubeFaceDirection(t.face, s1, t1));
  g.corners[3] = normalize(envmap::cubeFaceDirection(t.face, s0, t1));
  g.moment = polygonMoment(g.corners.data(), 4);
  const Vec3d centre = normalize(g.corners[0] + g.corners[1] + g.corners[2] + g.corners[3]);
  if (dot(g.moment, centre) < 0) g.moment = -g.moment;  // orient toward the texel
  return g;
}

double clampedCosine(const TexelGeometry& g, const Vec3d& normal) {
  int above = 0;
  for (const Vec3d& v : g.corners) above += dot(v, normal) >= 0 ? 1 : 0;
  if (above == 0) return 0.0;
  if (above == 4) return std::max(0.0, dot(normal, g.moment)) / kPi;
  return polygonClampedCosine(g.corners.data(), 4, normal) / kPi;
}

CubeTexels::CubeTexels(int n) : n_(n) {
  checkResolution(n, "Haar cube");
  const std::size_t total = coefficientCount(n);
  texels_.resize(total);
  for (std::size_t j = 0; j < total; ++j) texels_[j] = texelGeometry(std::uint32_t(j), n);
  const std::vector<double> omega = envmap::cubeTexelSolidAngles(n);
  omega_.resize(total);
  for (std::size_t j = 0; j < total; ++j) omega_[j] = omega[j % omega.size()];
  for (int f = 0; f < 6; ++f) {
    const Vec3d c = envmap::cubeFaceDirection(f, 0, 0);
    faces_[std::size_t(f)].centre = Vec3f(c);
    faces_[std::size_t(f)].s = Vec3f(envmap::cubeFaceDirection(f, 1, 0) - c);
    faces_[std::size_t(f)].t = Vec3f(envmap::cubeFaceDirection(f, 0, 1) - c);
    int k = 0;
    for (double b : {-1.0, 1.0})
      for (double a : {-1.0, 1.0})
        faces_[std::size_t(f)].corners[std::size_t(k++)] =
            Vec3f(normalize(envmap::cubeFaceDirection(f, a, b)));
  }
}

CubeTexels::FaceSide CubeTexels::faceSide(int face, const Vec3f& normal) const {
  int above = 0, below = 0;
  for (const Vec3f& c : faces_[std::size_t(face)].corners) {
    const float d = dot(c, normal);
    above += d > 0;
    below += d <= 0;
  }
  return above == 0 ? FaceSide::Below : below == 0 ? FaceSide::Above : FaceSide::Across;
}

bool CubeTexels::aboveHorizon(std::uint32_t j, const Vec3d& normal) const {
  for (const Vec3d& c : texels_[j].corners)
    if (dot(c, normal) > 0) return true;
  return false;
}

Vec3f CubeTexels::sample(std::uint32_t j, float u, float v, float& weight) const {
  const CubeTexel t = cubeTexel(j, n_);
  return sample(t.face, t.x, t.y, u, v, weight);
}

}  // namespace prt::haar
