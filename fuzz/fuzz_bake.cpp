// The bake file (.glb with _PRT attributes and the PRTKIT_radiance_transfer extension) through prt::decodeBake.
#include "fuzz_common.hpp"
#include "prt/io/bake_file.hpp"

PRT_FUZZ_TARGET(prt::decodeBake(prt::fuzz::bytes(data, size), "fuzz.glb"))
