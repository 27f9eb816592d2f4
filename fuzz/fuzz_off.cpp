// Object File Format (OFF, COFF, NOFF, CNOFF) through prt::loadMeshBytes; gzip input as .off.gz.
#include "fuzz_common.hpp"
#include "prt/geometry/load.hpp"

PRT_FUZZ_TARGET({
  const bool gz = size >= 2 && data[0] == 0x1f && data[1] == 0x8b;
  prt::loadMeshBytes(gz ? "fuzz.off.gz" : "fuzz.off", prt::fuzz::bytes(data, size));
})
