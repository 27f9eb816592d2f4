#include "seam_fix.hpp"

#include <fmt/format.h>

#include "cli.hpp"
#include "prt/core/error.hpp"
#include "prt/render/lightmap_seams.hpp"
#include "prt/transport/lightmap_seam_fix.hpp"

namespace prt::cli {

void fixBakeSeams(BakeFile& file, const std::string& name) {
  if (file.domain() != TransferDomain::Texels)
    throw Error(name, "--seam-fix is of per-texel transfer (bake with --domain texels)");
  file.requireComplete(name);
  file.requireSh(name,
                 "the seam fix solves for SH coefficients across seams, and a Haar row's "
                 "sparse terms differ from texel to texel");
  for (BakedTransfer& t : file.transfers) {
    if (t.transfer.compressed())
      throw Error(name, "holds compressed transfer (" + t.describe() +
                            "): fix the seams before compressing");
    const render::SeamStats before = render::measureSeams(file.mesh, t.transfer);
    SeamFixStats st;
    t.transfer = fixLightmapSeams(file.mesh, t.transfer, &st);
    const render::SeamStats after = render::measureSeams(file.mesh, t.transfer);
    info(fmt::format(
        "{}: seam fix over {} seam edges ({} samples, {} texels changed, {:.2f} s): mismatch "
        "{:.2f}% -> {:.2f}% (max {:.1f}% -> {:.1f}%)",
        t.describe(), st.edges, st.samples, st.texels, st.seconds, 100 * before.mismatch,
        100 * after.mismatch, 100 * before.maxMismatch, 100 * after.maxMismatch));
  }
}

}  // namespace prt::cli
