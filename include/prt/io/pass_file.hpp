#pragma once
// Pass files: one pass of a bake split for job arrays (`prt bake --pass K --shard I/N`, then
// `prt merge`), where no MPI joins the ranks (docs/distributed.md). Pass K of a bake
// (prt/transport/passes.hpp) reads the whole of pass K − 1 (or the sum of the passes before), so
// a job array bakes pass 0 in shards, merges them into one pass file, bakes pass 1 reading it,
// and so on; the last pass is written as ordinary bake pieces that `prt merge` joins into the
// bake, bit for bit what one process would have baked.
//
// A piece holds, for its rows of pass K: the pass's own rows (what pass K + 1 reads), the running
// sum of passes 0..K over those rows when the bake sums its passes (what the last pass adds to),
// the per-row estimator variance summed over passes 0..K (the bake's error estimate), and each
// pass's rays and seconds (pass K: this piece's; earlier passes: the whole pass's).
// Per texel the header names the domain and the lightmap (width, height, padding); without them
// a pass file is per vertex.
//
// Bytes: "PRTPASS2", a little-endian uint64 n, a uint64 checksum (FNV-1a of every byte after
// it), n bytes of JSON (identity, pass, passes, shape, rows, sumChannels, rays, seconds) padded
// with spaces to a multiple of 8, then the rows (floats), the sum (floats) and the variances
// (doubles). A file whose checksum does not match is refused by name, as are "PRTPASS1" files
// (no checksum); pieces of another bake (identity: settings, seed, mesh) are refused at merge.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "prt/core/float_array.hpp"
#include "prt/transfer/shape.hpp"

namespace prt {

struct PassPiece {
  std::string identity;  ///< the bake (transport's bakeIdentity): pieces of one bake only join
  int pass = 0;          ///< K
  int passes = 0;        ///< the bake's pass count
  std::string name;      ///< the pass's name ("bounce 1")
  TransferShape shape;   ///< of the pass's rows; shape.rows: the rows this piece holds
  FloatArray values;     ///< rows × shape.stride()
  int sumChannels = 0;   ///< 0: no running sum
  FloatArray sum;        ///< rows × B² × sumChannels: passes 0..K summed
  std::vector<double> variance;     ///< per row, over passes 0..K
  std::vector<std::uint64_t> rays;  ///< per pass 0..K
  std::vector<double> seconds;      ///< per pass 0..K
};

std::string encodePassPiece(const PassPiece& piece);
/// Throws prt::Error("NAME: ...") for anything malformed or inconsistent.
PassPiece decodePassPiece(std::span<const unsigned char> bytes, const std::string& name);
void writePassPiece(const std::string& path, const PassPiece& piece);
PassPiece readPassPiece(const std::string& path);

/// Joins pieces of one pass (in any order) into one piece of the union of their rows, bit for
/// bit; rays and seconds of the pass add. Throws prt::Error("merge: the piece starting at
/// vertex F ...") for pieces of another bake or pass, gaps and overlaps.
PassPiece mergePassPieces(std::vector<PassPiece> pieces);

}  // namespace prt
