#include "prt/envmap/builtin.hpp"

#include <cmath>

#include "prt/core/error.hpp"
#include "prt/core/spec.hpp"
#include "prt/envmap/sky.hpp"

namespace prt::envmap {

namespace {

constexpr double kAny = 1e300;  // parameters whose range the model itself checks

}  // namespace

bool isBuiltin(const std::string& spec) {
  return spec.rfind("builtin:", 0) == 0;
}

std::vector<std::string> builtinNames() {
  return {"sky", "constant", "studio"};
}

Environment builtinEnvironment(const std::string& spec, int texelWidth) {
  if (!isBuiltin(spec)) throw Error(spec, "not a builtin environment");
  Spec s(spec, "builtin:");
  if (s.name() == "sky") {
    SkyParams p;
    p.turbidity = s.number("turbidity", p.turbidity, -kAny, kAny);
    p.elevationDeg = s.number("elevation", p.elevationDeg, -kAny, kAny);
    p.azimuthDeg = s.number("azimuth", p.azimuthDeg, -kAny, kAny);
    p.sunPower = s.number("sun", p.sunPower, -kAny, kAny);
    p.sunRadiusDeg = s.number("sunsize", p.sunRadiusDeg, -kAny, kAny);
    p.skyScale = s.number("sky", p.skyScale, -kAny, kAny);
    p.groundAlbedo = s.number("ground", p.groundAlbedo, -kAny, kAny);
    s.finish();
    try {
      auto sky = std::make_shared<PreethamSky>(p);
      std::vector<Cap> caps;
      const Cap sun = sky->sunCap();
      if (sun.radiance.x > 0 || sun.radiance.y > 0 || sun.radiance.z > 0) caps.push_back(sun);
      return Environment::analytic([sky](const Vec3f& d) { return sky->sky(d); }, std::move(caps),
                                   texelWidth);
    } catch (const Error& e) {
      throw Error(spec, e.what());
    }
  }
  if (s.name() == "constant") {
    const double v = s.number("value", 1.0, -kAny, kAny);
    const Rgb c(static_cast<float>(s.number("r", v, -kAny, kAny)),
                static_cast<float>(s.number("g", v, -kAny, kAny)),
                static_cast<float>(s.number("b", v, -kAny, kAny)));
    s.finish();
    if (c.x < 0 || c.y < 0 || c.z < 0) throw Error(spec, "radiance must be >= 0");
    return Environment::analytic([c](const Vec3f&) { return c; }, {}, texelWidth);
  }
  if (s.name() == "studio") {
    const float k = static_cast<float>(s.number("intensity", 1.0, -kAny, kAny));
    s.finish();
    if (k < 0) throw Error(spec, "intensity must be >= 0");
    auto deg = [](double d) { return d * kPi / 180; };
    std::vector<Cap> caps = {
        {normalize(Vec3f(1.0f, 1.0f, 1.0f)), deg(15), Rgb(8.0f, 7.6f, 7.0f) * k},    // key, warm
        {normalize(Vec3f(-1.0f, 0.3f, 0.8f)), deg(25), Rgb(1.2f, 1.3f, 1.5f) * k},   // fill, cool
        {normalize(Vec3f(0.0f, 0.6f, -1.0f)), deg(10), Rgb(6.0f, 6.0f, 6.0f) * k}};  // rim
    return Environment::analytic(
        [k](const Vec3f& d) { return Rgb(0.05f + 0.05f * std::max(d.y, 0.0f)) * k; },
        std::move(caps), texelWidth);
  }
  std::string list;
  for (const auto& n : builtinNames()) list += (list.empty() ? "" : ", ") + n;
  throw Error(spec, "unknown builtin environment '" + s.name() + "' (known: " + list + ")");
}

}  // namespace prt::envmap
