#include "prt/io/bake_merge.hpp"

#include <algorithm>
#include <cstring>

#include "prt/core/error.hpp"

namespace prt {

BakeFile mergeBakes(std::vector<BakeFile> pieces) {
  if (pieces.empty()) throw Error("merge: no bake files");
  const auto rowName = [](const BakeFile& b, bool plural = false) {
    return std::string(plural ? toString(b.domain()) : prt::rowName(b.domain()));
  };
  std::sort(pieces.begin(), pieces.end(),
            [](const BakeFile& a, const BakeFile& b) { return a.rows().first < b.rows().first; });
  for (const BakeFile& p : pieces)
    for (const BakedTransfer& t : p.transfers)
      if (t.transfer.compressed())
        throw Error("merge: the piece starting at " + rowName(p) + " " +
                    std::to_string(p.rows().first) + " holds compressed transfer (" + t.describe() +
                    "), which cannot be merged: merge the bakes, then compress");
  BakeFile out = std::move(pieces.front());
  const Mesh& m0 = out.mesh;
  // The rows of every transfer, gathered piece by piece.
  std::vector<std::vector<float>> values;
  for (const BakedTransfer& t : out.transfers)
    values.emplace_back(t.transfer.values().data(),
                        t.transfer.values().data() + t.transfer.values().size());
  RowRange rows = out.rows();
  for (std::size_t i = 1; i < pieces.size(); ++i) {
    const BakeFile& p = pieces[i];
    const std::string who =
        "merge: the piece starting at " + rowName(p) + " " + std::to_string(p.rows().first);
    const Mesh& m = p.mesh;
    if (m.positions != m0.positions || m.normals != m0.normals || m.triangles != m0.triangles ||
        m.albedo != m0.albedo || m.lightmapUvs != m0.lightmapUvs || m.uvs != m0.uvs ||
        m.baseColour != m0.baseColour)
      throw Error(who + " was baked from a different mesh");
    if (p.domain() != out.domain() || !(p.lightmap() == out.lightmap()) ||
        !(p.probeGrid() == out.probeGrid()))
      throw Error(who + " is over another domain (" + toString(p.domain()) + ", not " +
                  toString(out.domain()) + ", or another lightmap or probe grid)");
    if (p.rows().first < rows.end())
      throw Error(who + " overlaps the previous range (which ends at " +
                  std::to_string(rows.end()) + ")");
    if (p.rows().first > rows.end())
      throw Error(who + " leaves a gap: " + rowName(p, true) + " " + std::to_string(rows.end()) +
                  ".." + std::to_string(p.rows().first - 1) + " are missing");
    if (p.transfers.size() != out.transfers.size()) throw Error(who + " holds different modes");
    for (std::size_t t = 0; t < out.transfers.size(); ++t) {
      BakedTransfer& a = out.transfers[t];
      const BakedTransfer* b = p.find(a.mode(), a.transfer.layout());
      if (!b) throw Error(who + std::string(" lacks the ") + a.describe() + " transfer");
      const TransferShape& sa = a.transfer.shape();
      const TransferShape& sb = b->transfer.shape();
      if (!(a.recipe == b->recipe) || sa.bands != sb.bands || sa.channels != sb.channels ||
          sa.domain != sb.domain)
        throw Error(who + " was baked with different settings (" + a.describe() + ")");
      values[t].insert(values[t].end(), b->transfer.values().data(),
                       b->transfer.values().data() + b->transfer.values().size());
      // Weighted by the rows each piece's error estimate is over (its sampled rows: every
      // vertex, the covered texels), so that the merged means are one bake's.
      a.stats = combineBakeStats(a.stats, a.stats.vertices, b->stats, b->stats.vertices);
    }
    rows.count += p.rows().count;
  }
  for (std::size_t t = 0; t < out.transfers.size(); ++t) {
    TransferShape shape = out.transfers[t].transfer.shape();
    shape.rows = rows;
    out.transfers[t].transfer = Transfer::dense(shape, FloatArray(std::move(values[t])));
  }
  return out;
}

}  // namespace prt
