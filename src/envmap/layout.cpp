#include "prt/envmap/layout.hpp"

#include <algorithm>
#include <cmath>

#include "prt/core/error.hpp"
#include "prt/core/quadrature.hpp"

namespace prt::envmap {

Layout parseLayout(const std::string& name) {
  if (name == "latlong" || name == "equirect") return Layout::LatLong;
  if (name == "probe" || name == "angular") return Layout::Probe;
  if (name == "vcross") return Layout::VCross;
  if (name == "hcross") return Layout::HCross;
  if (name == "faces" || name == "cube") return Layout::Faces;
  throw Error("unknown layout '" + name + "' (expected latlong, probe, vcross, hcross or faces)");
}

const char* layoutName(Layout layout) {
  switch (layout) {
    case Layout::LatLong:
      return "latlong";
    case Layout::Probe:
      return "probe";
    case Layout::VCross:
      return "vcross";
    case Layout::HCross:
      return "hcross";
    case Layout::Faces:
      return "faces";
  }
  return "?";
}

Layout detectLayout(int width, int height, const std::string& file) {
  if (width == 2 * height) return Layout::LatLong;
  if (width == height) return Layout::Probe;
  if (4 * width == 3 * height) return Layout::VCross;
  if (3 * width == 4 * height) return Layout::HCross;
  throw Error(
      file,
      std::to_string(width) + "x" + std::to_string(height) +
          " fits no layout (lat-long 2:1, probe 1:1, vertical cross 3:4, horizontal cross 4:3)");
}

Vec3d cubeFaceDirection(int face, double s, double t) {
  switch (face) {
    case PosX:
      return {1, -t, -s};
    case NegX:
      return {-1, -t, s};
    case PosY:
      return {s, 1, t};
    case NegY:
      return {s, -1, -t};
    case PosZ:
      return {s, -t, 1};
    default:
      return {-s, -t, -1};
  }
}

int cubeFaceCoords(const Vec3f& d, float& s, float& t) {
  const float ax = std::abs(d.x), ay = std::abs(d.y), az = std::abs(d.z);
  if (ax >= ay && ax >= az) {
    const float inv = 1.0f / ax;
    t = -d.y * inv;
    s = (d.x > 0 ? -d.z : d.z) * inv;
    return d.x > 0 ? PosX : NegX;
  }
  if (ay >= az) {
    const float inv = 1.0f / ay;
    s = d.x * inv;
    t = (d.y > 0 ? d.z : -d.z) * inv;
    return d.y > 0 ? PosY : NegY;
  }
  const float inv = 1.0f / az;
  t = -d.y * inv;
  s = (d.z > 0 ? d.x : -d.x) * inv;
  return d.z > 0 ? PosZ : NegZ;
}

std::vector<double> cubeTexelSolidAngles(int n) {
  // A(a, b): solid angle of [0, a] × [0, b] on the plane at unit distance (signed, odd in a, b).
  auto area = [](double a, double b) { return std::atan2(a * b, std::sqrt(a * a + b * b + 1.0)); };
  std::vector<double> edge(n + 1);
  for (int i = 0; i <= n; ++i) edge[i] = 2.0 * i / n - 1.0;
  std::vector<double> out(static_cast<std::size_t>(n) * n);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      out[static_cast<std::size_t>(y) * n + x] =
          area(edge[x + 1], edge[y + 1]) - area(edge[x], edge[y + 1]) - area(edge[x + 1], edge[y]) +
          area(edge[x], edge[y]);
  return out;
}

Vec3d latLongDirection(int width, int height, double x, double y) {
  const double theta = kPi * y / height;
  const double phi = 2.0 * kPi * (x / width - 0.5);
  const double st = std::sin(theta);
  return {st * std::cos(phi), std::cos(theta), st * std::sin(phi)};
}

void latLongPixel(const Vec3f& d, int width, int height, float& px, float& py) {
  const float len = length(d);
  const float phi = std::atan2(d.z, d.x);
  const float theta = std::acos(std::clamp(d.y / len, -1.0f, 1.0f));
  px = (phi / (2.0f * kPif) + 0.5f) * width;
  py = theta / kPif * height;
}

Vec3d probeDirection(double a, double b, bool* inside) {
  const double r = std::sqrt(a * a + b * b);
  if (inside) *inside = r <= 1.0;
  if (r == 0) return {0, 0, -1};
  const double ang = kPi * std::min(r, 1.0);
  const double k = std::sin(ang) / r;
  return {k * a, k * b, -std::cos(ang)};
}

namespace {

// ∫ along the straight edge p0 → p1 of G(r)/r² (x dy − y dx), G(r) = 1 − cos(π min(r, 1)).
// G(r)/r² → π²/2 at r = 0, so the integrand is bounded; it has a kink where r crosses 1, so the
// edge is split there and each smooth piece integrated by 8-point Gauss–Legendre.
double edgeFlux(double x0, double y0, double x1, double y1) {
  static const QuadratureRule rule = gaussLegendre(8);
  const std::vector<double>& gx = rule.nodes;
  const std::vector<double>& gw = rule.weights;
  const double dx = x1 - x0, dy = y1 - y0;
  const double cr = x0 * dy - y0 * dx;  // x dy − y dx = cr dτ along p(τ) = p0 + τ (p1 − p0)
  if (cr == 0) return 0;
  // Crossings of |p(τ)| = 1: a τ² + 2 b τ + c = 0.
  const double a = dx * dx + dy * dy, b = x0 * dx + y0 * dy, c = x0 * x0 + y0 * y0 - 1;
  double cuts[4] = {0, 1, 1, 1};
  int nc = 1;
  const double disc = b * b - a * c;
  if (disc > 0) {
    const double sq = std::sqrt(disc);
    for (double tau : {(-b - sq) / a, (-b + sq) / a})
      if (tau > 0 && tau < 1) cuts[nc++] = tau;
  }
  cuts[nc++] = 1;
  std::sort(cuts, cuts + nc);
  auto g = [](double r2) {
    if (r2 >= 1) return 2.0 / r2;
    if (r2 < 1e-12) return kPi * kPi / 2;
    const double r = std::sqrt(r2);
    return (1 - std::cos(kPi * r)) / r2;
  };
  double sum = 0;
  for (int i = 0; i + 1 < nc; ++i) {
    const double lo = cuts[i], hi = cuts[i + 1], half = 0.5 * (hi - lo), mid = 0.5 * (hi + lo);
    if (half <= 0) continue;
    const double mx = x0 + mid * dx, my = y0 + mid * dy;
    if (mx * mx + my * my >= 1) {
      // Outside the disc G = 2 and (x dy − y dx)/r² = dθ: the piece is exactly 2 Δθ (a
      // quadrature of 1/r² would leave ~1e-6 on long edges).
      const double ax = x0 + lo * dx, ay = y0 + lo * dy, bx = x0 + hi * dx, by = y0 + hi * dy;
      sum += 2 * std::atan2(ax * by - ay * bx, ax * bx + ay * by);
      continue;
    }
    double piece = 0;
    for (int k = 0; k < 8; ++k) {
      const double tau = mid + half * gx[k];
      const double px = x0 + tau * dx, py = y0 + tau * dy;
      piece += gw[k] * g(px * px + py * py);
    }
    sum += piece * half * cr;
  }
  return sum;
}

}  // namespace

std::vector<double> probeTexelSolidAngles(int width, int height) {
  // Image coordinates: a = 2 x/W − 1 (right), b = 1 − 2 y/H (up). Fluxes of the horizontal edges
  // (W × (H+1)) and vertical edges ((W+1) × H), each computed once in a fixed direction, so
  // neighbouring texels use the identical value with opposite signs and the sum telescopes.
  auto ax = [&](int x) { return 2.0 * x / width - 1.0; };
  auto by = [&](int y) { return 1.0 - 2.0 * y / height; };
  std::vector<double> horiz(static_cast<std::size_t>(width) * (height + 1));
  std::vector<double> vert(static_cast<std::size_t>(width + 1) * height);
  for (int y = 0; y <= height; ++y)
    for (int x = 0; x < width; ++x)
      horiz[static_cast<std::size_t>(y) * width + x] =
          edgeFlux(ax(x), by(y), ax(x + 1), by(y));  // left → right
  for (int y = 0; y < height; ++y)
    for (int x = 0; x <= width; ++x)
      vert[static_cast<std::size_t>(y) * (width + 1) + x] =
          edgeFlux(ax(x), by(y + 1), ax(x), by(y));  // bottom → top
  std::vector<double> out(static_cast<std::size_t>(width) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      // Counter-clockwise in (a, b): bottom edge left→right, right edge up, top edge right→left,
      // left edge down.
      const double bottom = horiz[static_cast<std::size_t>(y + 1) * width + x];
      const double top = horiz[static_cast<std::size_t>(y) * width + x];
      const double right = vert[static_cast<std::size_t>(y) * (width + 1) + x + 1];
      const double left = vert[static_cast<std::size_t>(y) * (width + 1) + x];
      // A texel wholly outside the disc sees nothing: exactly 0, not the rounding residue of
      // its four fluxes.
      const double nx = std::clamp(0.0, ax(x), ax(x + 1)), ny = std::clamp(0.0, by(y + 1), by(y));
      out[static_cast<std::size_t>(y) * width + x] =
          nx * nx + ny * ny >= 1 ? 0.0 : bottom + right - top - left;
    }
  return out;
}

}  // namespace prt::envmap
