#include "prt/transport/bake_texels.hpp"

// A per-texel bake is a bake of the texel domain (transport/passes.hpp runs its passes, with
// the lightmap's samples and dilation in texel_domain.cpp): this is the call that names the
// lightmap and returns its samples beside the transfer.

#include "prt/transport/passes.hpp"

namespace prt {

BakeSettings texelSettings(const BakeSettings& settings, int width, int height, int padding) {
  BakeSettings s = settings;
  s.domain = TransferDomain::Texels;
  s.lightmap = {width, height, padding, false};
  return s;
}

TexelBakeFootprint texelBakeFootprint(const Mesh& mesh, const BakeSettings& settings, int width,
                                      int height) {
  return bakeFootprint(mesh, texelSettings(settings, width, height, settings.lightmap.padding));
}

TexelBake bakeTexels(const Mesh& mesh, const Occluder& occluder, const BakeSettings& settings,
                     std::span<const Vec2f> uvs, int width, int height, int padding,
                     BakeStats* stats, const ProgressFn& progress) {
  /// The threads of this process, over the UV set given.
  struct Threads : ThreadExecutor {
    std::span<const Vec2f> uvs;
    BakePassOptions passOptions() const override {
      BakePassOptions o;
      o.lightmapUvs = uvs;
      return o;
    }
  } threads;
  threads.uvs = uvs;
  TexelBake out;
  TexelBakeInfo info;
  out.transfer = bake(mesh, occluder, texelSettings(settings, width, height, padding), threads,
                      stats, progress, &info);
  out.samples = std::move(info.samples);
  out.invalid = std::move(info.inside);
  out.filled = std::move(info.filled);
  return out;
}

}  // namespace prt
