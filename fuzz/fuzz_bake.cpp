// The bake file (.glb with _PRT attributes and the PRTKIT_radiance_transfer extension) through
// prt::decodeBake, and then past decoding, as every verb uses what it decoded: each transfer of a
// small complete bake relit (render::RelitView: per vertex or per texel, whose rows are sampled
// over the lightmap UVs; a Haar transfer relit under a Haar light) and drawn into a tiny image. A reader that decodes what its users then
// crash on (a lightmap UV of 1e9 once did) is a finding here too.
#include "fuzz_common.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/relight/relight_haar.hpp"
#include "prt/render/camera.hpp"
#include "prt/render/primary.hpp"
#include "prt/render/relit_view.hpp"
#include "prt/render/render.hpp"

namespace {

void decodeAndDraw(std::span<const unsigned char> bytes) {
  const prt::BakeFile f = prt::decodeBake(bytes, "fuzz.glb");
  // Small complete bakes only: the fuzzer explores the readers, not long relights.
  if (!f.complete() || f.mesh.vertexCount() > 4096 || f.domainRows() > (1u << 16)) return;
  const auto occluder = prt::makeEmbreeOccluder(f.mesh);
  prt::render::FrameSettings frame;
  frame.width = 16, frame.height = 12, frame.spp = 1;
  const prt::render::Camera camera = prt::render::frameMesh(f.mesh, frame.width, frame.height);
  for (const prt::BakedTransfer& t : f.transfers) {
    if (t.transfer.isHaar()) {
      // A Haar bake as prt render draws it: relit under a Haar light of its cube (a few
      // terms and the unshadowed part's SH, no environment to project), drawn per vertex.
      prt::haar::HaarLight light;
      light.resolution = t.transfer.shape().haar.resolution;
      light.index = {0, 1};
      light.value = {prt::Rgb(1.0f), prt::Rgb(0.25f)};
      light.unshadowed = prt::sh::RgbSh(prt::haar::kUnshadowedBands);
      light.unshadowed.c[0] = prt::Rgb(3.5449077f);
      const std::vector<prt::Rgb> radiance =
          prt::relight::relightHaar(t.transfer, light, f.mesh.normals, {});
      (void)prt::render::tracePrimary(camera, frame, *occluder,
                                      prt::render::vertexRadianceShader(f.mesh, radiance), {}, {});
      continue;
    }
    prt::render::RelitView view(f.mesh, *occluder, t.transfer, t.recipe.material);
    prt::sh::RgbSh light(view.bands());
    light.c[0] = prt::Rgb(3.5449077f);  // a white sky: L00 = √(4π)
    view.relight(light, prt::Mat3d::identity(), camera.eye, "fuzz.glb");
    (void)prt::render::tracePrimary(camera, frame, *occluder, view.shader(), {}, {});
  }
}

}  // namespace

PRT_FUZZ_TARGET(decodeAndDraw(prt::fuzz::bytes(data, size)))
