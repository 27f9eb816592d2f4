#include "prt/envmap/builtin.hpp"

#include <cmath>
#include <map>
#include <set>

#include "prt/core/error.hpp"
#include "prt/envmap/sky.hpp"

namespace prt::envmap {

namespace {

struct Spec {
  std::string name;
  std::map<std::string, double> params;
};

Spec parse(const std::string& spec) {
  Spec s;
  const std::string rest = spec.substr(8);  // after "builtin:"
  const auto q = rest.find('?');
  s.name = rest.substr(0, q);
  if (q == std::string::npos) return s;
  std::string query = rest.substr(q + 1);
  std::size_t pos = 0;
  while (pos <= query.size()) {
    const std::size_t amp = query.find('&', pos);
    const std::string item =
        query.substr(pos, amp == std::string::npos ? std::string::npos : amp - pos);
    if (!item.empty()) {
      const auto eq = item.find('=');
      if (eq == std::string::npos)
        throw Error(spec, "parameter '" + item + "' has no value (use NAME=VALUE)");
      const std::string key = item.substr(0, eq), value = item.substr(eq + 1);
      std::size_t used = 0;
      double v = 0;
      try {
        v = std::stod(value, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != value.size() || value.empty() || !std::isfinite(v))
        throw Error(spec, "parameter '" + key + "' needs a finite number, got '" + value + "'");
      s.params[key] = v;
    }
    if (amp == std::string::npos) break;
    pos = amp + 1;
  }
  return s;
}

void checkKeys(const std::string& spec, const Spec& s, const std::set<std::string>& allowed) {
  for (const auto& [k, v] : s.params)
    if (!allowed.count(k)) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      throw Error(spec, "unknown parameter '" + k + "' (known: " + list + ")");
    }
}

double get(const Spec& s, const std::string& key, double def) {
  const auto it = s.params.find(key);
  return it == s.params.end() ? def : it->second;
}

}  // namespace

bool isBuiltin(const std::string& spec) {
  return spec.rfind("builtin:", 0) == 0;
}

std::vector<std::string> builtinNames() {
  return {"sky", "constant", "studio"};
}

Environment builtinEnvironment(const std::string& spec, int texelWidth) {
  if (!isBuiltin(spec)) throw Error(spec, "not a builtin environment");
  const Spec s = parse(spec);
  if (s.name == "sky") {
    checkKeys(spec, s, {"turbidity", "elevation", "azimuth", "sun", "sunsize", "sky", "ground"});
    SkyParams p;
    p.turbidity = get(s, "turbidity", p.turbidity);
    p.elevationDeg = get(s, "elevation", p.elevationDeg);
    p.azimuthDeg = get(s, "azimuth", p.azimuthDeg);
    p.sunPower = get(s, "sun", p.sunPower);
    p.sunRadiusDeg = get(s, "sunsize", p.sunRadiusDeg);
    p.skyScale = get(s, "sky", p.skyScale);
    p.groundAlbedo = get(s, "ground", p.groundAlbedo);
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
  if (s.name == "constant") {
    checkKeys(spec, s, {"value", "r", "g", "b"});
    const double v = get(s, "value", 1.0);
    const Rgb c(static_cast<float>(get(s, "r", v)), static_cast<float>(get(s, "g", v)),
                static_cast<float>(get(s, "b", v)));
    if (c.x < 0 || c.y < 0 || c.z < 0) throw Error(spec, "radiance must be >= 0");
    return Environment::analytic([c](const Vec3f&) { return c; }, {}, texelWidth);
  }
  if (s.name == "studio") {
    checkKeys(spec, s, {"intensity"});
    const float k = static_cast<float>(get(s, "intensity", 1.0));
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
  throw Error(spec, "unknown builtin environment '" + s.name + "' (known: " + list + ")");
}

}  // namespace prt::envmap
