// prt info's description of where a bake's rows lie, beyond the mesh: a lightmap (its coverage
// and the bilinear mismatch across its UV seams) or a probe grid (where its probes are).

#include "info_domain.hpp"

#include <fmt/format.h>

#include <vector>

#include "prt/geometry/texel_sampling.hpp"
#include "prt/render/lightmap_seams.hpp"

namespace prt::cli {

void describeBakeDomain(const BakeFile& b, std::ostream& out, Json& j) {
  const Mesh& m = b.mesh;
  if (b.domain() == TransferDomain::Texels) {
    const TransferShape::LightmapSize lm = b.lightmap();
    // Where the texels were sampled, counted again from the UVs the bake is over.
    const TexelSamples s = sampleTexels(m, m.lightmapUvs, lm.width, lm.height);
    std::size_t partial = 0;
    for (const TexelSample& t : s.samples) partial += !t.centreInside;
    const double share = double(s.samples.size()) / double(s.texelCount());
    j["lightmap"] = {{"width", lm.width},
                     {"height", lm.height},
                     {"padding", lm.padding},
                     {"seamsFixed", lm.seamsFixed},
                     {"denoised", lm.denoised},
                     {"coveredTexels", s.samples.size()},
                     {"partialTexels", partial},
                     {"coverage", share}};
    out << fmt::format(
        "lightmap    {}x{} over the lightmap UVs, padding {}: {:.1f}% of the texels covered ({}; "
        "{} partly)\n",
        lm.width, lm.height, lm.padding, 100.0 * share, s.samples.size(), partial);
    // The seams of the richest vector transfer (render/lightmap_seams.hpp), relit in SH: not of
    // Haar transfer.
    for (std::size_t i : transferPreference(b)) {
      const Transfer& x = b.transfers[i].transfer;
      if (x.isMatrix() || x.isHaar() || !b.complete()) continue;
      // Under a white sky (the transfer's mean) and under the builtin sky's sun (the shadow
      // edges, where seams show most).
      Json under = Json::array();
      std::vector<render::SeamStats> each;
      for (const render::SeamLight& l : render::seamLights(x.bands())) {
        each.push_back(render::measureSeams(m, x, l.light));
        under.push_back({{"light", l.name},
                         {"mismatch", each.back().mismatch},
                         {"maxMismatch", each.back().maxMismatch}});
      }
      const render::SeamStats& seams = each.front();
      j["lightmap"]["seams"] = {{"transfer", b.transfers[i].describe()},
                                {"edges", seams.edges},
                                {"length", seams.length},
                                {"mismatch", seams.mismatch},
                                {"maxMismatch", seams.maxMismatch},
                                {"under", std::move(under)}};
      if (seams.edges == 0)
        out << "seams       none (no smooth edge is cut between charts)\n";
      else
        out << fmt::format(
            "seams       {} edges ({:.4g} long): bilinear mismatch across them {:.2f}% of the "
            "white-sky radiance there (max {:.2f}%), {:.2f}% under the builtin sky's sun (max "
            "{:.2f}%), {}{}\n",
            seams.edges, seams.length, 100 * seams.mismatch, 100 * seams.maxMismatch,
            100 * each[1].mismatch, 100 * each[1].maxMismatch, b.transfers[i].describe(),
            lm.seamsFixed ? ", after the seam fix" : " (prt bake --seam-fix closes them)");
      break;
    }
  }
  if (b.domain() == TransferDomain::Probes) {
    const ProbeGrid g = b.probeGrid();
    const Vec3f far = g.position(g.probes() - 1);
    j["probeGrid"] = {{"count", {g.count[0], g.count[1], g.count[2]}},
                      {"origin", {g.origin.x, g.origin.y, g.origin.z}},
                      {"spacing", {g.spacing.x, g.spacing.y, g.spacing.z}},
                      {"probes", g.probes()}};
    out << fmt::format(
        "probes      {}, from ({:.4g}, {:.4g}, {:.4g}) to ({:.4g}, {:.4g}, {:.4g})\n", g.describe(),
        g.origin.x, g.origin.y, g.origin.z, far.x, far.y, far.z);
  }
}

}  // namespace prt::cli
