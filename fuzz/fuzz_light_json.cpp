// Our light JSON through prt::io::parseLightJson.
#include "fuzz_common.hpp"
#include "prt/io/light_file.hpp"

PRT_FUZZ_TARGET(prt::io::parseLightJson(prt::fuzz::text(data, size), "fuzz.json"))
