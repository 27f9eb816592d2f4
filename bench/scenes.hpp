#pragma once
// The scenes the bake benchmarks share, loaded once per program: "bunny" (Debian's glmark2-data;
// null when absent, the case then skips saying so), "bunny-atlas" (the bunny over prt unwrap's
// atlas at 512², padding 2: it has no lightmap UVs of its own), "cornell" (builtin:cornell, its
// packed lightmap UVs), anything else builtin:sphere-plane.

#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include "prt/geometry/builtin.hpp"
#include "prt/geometry/load.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/unwrap/unwrap.hpp"

namespace prt::bench {

inline constexpr const char* kBunny = "/usr/share/glmark2/models/bunny.obj";

struct Scene {
  Mesh mesh;
  std::unique_ptr<Occluder> occluder;
};

// Scenes are loaded once and shared by all cases.
inline Scene* scene(const std::string& name) {
  static std::map<std::string, std::unique_ptr<Scene>> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return it->second.get();
  auto s = std::make_unique<Scene>();
  if (name == "bunny" || name == "bunny-atlas") {
    if (!std::filesystem::exists(kBunny)) return nullptr;
    s->mesh = loadMesh(kBunny);
    // The per-texel case: the bunny has no lightmap UVs; prt unwrap's atlas at 512², padding 2.
    if (name == "bunny-atlas") s->mesh = unwrap(s->mesh).mesh;
  } else if (name == "cornell") {
    s->mesh = builtinScene("builtin:cornell");
  } else {
    s->mesh = builtinScene("builtin:sphere-plane");
  }
  s->occluder = makeEmbreeOccluder(s->mesh);
  return cache.emplace(name, std::move(s)).first->second.get();
}

}  // namespace prt::bench
