// Stanford PLY, ASCII and binary, through prt::loadMeshBytes; gzip input (1f 8b) is read as
// .ply.gz, so the capped inflater is fuzzed too.
#include "fuzz_common.hpp"
#include "prt/geometry/load.hpp"

PRT_FUZZ_TARGET({
  const bool gz = size >= 2 && data[0] == 0x1f && data[1] == 0x8b;
  prt::loadMeshBytes(gz ? "fuzz.ply.gz" : "fuzz.ply", prt::fuzz::bytes(data, size));
})
