// The bake file (.glb with _PRT attributes and extras.prtkit) through prt::decodeBake.
#include "fuzz_common.hpp"
#include "prt/io/bake_file.hpp"

PRT_FUZZ_TARGET(prt::decodeBake(prt::fuzz::bytes(data, size), "fuzz.glb"))
