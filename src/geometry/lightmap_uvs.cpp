#include "prt/geometry/lightmap_uvs.hpp"

#include "prt/core/error.hpp"
#include "prt/geometry/texel_sampling.hpp"

namespace prt {

UvSetOption parseUvSetOption(const std::string& s) {
  if (s == "auto") return UvSetOption::Auto;
  if (s == "1") return UvSetOption::Lightmap;
  if (s == "0") return UvSetOption::Texture;
  throw Error("unknown UV set '" + s.substr(0, 40) + "' (auto, 0 or 1)");
}

LightmapUvChoice findLightmapUvs(const Mesh& mesh, UvSetOption option, int width, int height) {
  struct Candidate {
    const std::vector<Vec2f>* uvs;
    const char* name;
  };
  std::vector<Candidate> candidates;
  if (option != UvSetOption::Texture) candidates.push_back({&mesh.lightmapUvs, "lightmap UVs"});
  if (option != UvSetOption::Lightmap) candidates.push_back({&mesh.uvs, "texture UVs"});
  LightmapUvChoice choice;
  for (const Candidate& c : candidates) {
    if (c.uvs->empty()) {
      choice.refused.push_back(std::string(c.name) + ": the mesh has none");
      continue;
    }
    try {
      checkLightmapUvs(mesh, *c.uvs, width, height, c.name);
    } catch (const Error& e) {
      // "SOURCE: NAME…: why" → "NAME…: why" (the mesh is named once, by the caller's line).
      std::string why = e.what();
      if (!mesh.source.empty() && why.rfind(mesh.source + ": ", 0) == 0)
        why = why.substr(mesh.source.size() + 2);
      choice.refused.push_back(why);
      continue;
    }
    choice.uvs = *c.uvs;
    choice.name = c.name;
    return choice;
  }
  return choice;
}

LightmapUvChoice chooseLightmapUvs(const Mesh& mesh, UvSetOption option, int width, int height) {
  LightmapUvChoice choice = findLightmapUvs(mesh, option, width, height);
  if (!choice.uvs.empty()) return choice;
  std::string reasons;
  for (const std::string& r : choice.refused) reasons += (reasons.empty() ? "" : "; ") + r;
  throw Error(mesh.source,
              "no UV set can hold a " + std::to_string(width) + " x " + std::to_string(height) +
                  " lightmap (" + reasons +
                  "); give the mesh a lightmap UV set (glTF TEXCOORD_1, or prt unwrap)");
}

}  // namespace prt
